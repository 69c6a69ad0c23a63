//! Per-atom comparison with LAMMPS: tables of per-atom values keyed by atom ID (the format of
//! lammps-refs/), dmhs' own captures, and the max absolute/relative differences per quantity.

use crate::sim::Simulation;
use std::collections::BTreeMap;
use std::path::Path;

/// Per-atom values by atom ID; `columns` names the values (after `id type`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AtomTable {
    pub columns: Vec<String>,
    pub rows: BTreeMap<i64, (usize, Vec<f64>)>,
}

impl AtomTable {
    /// Read the `# id type c1 c2 ...` text format of lammps-refs.
    pub fn read(path: &Path) -> Result<AtomTable, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        Self::parse(&text).map_err(|e| format!("{}: {e}", path.display()))
    }
    pub fn parse(text: &str) -> Result<AtomTable, String> {
        let mut lines = text.lines();
        let header = lines.next().ok_or("empty table")?;
        let names: Vec<&str> = header.trim_start_matches('#').split_whitespace().collect();
        if names.len() < 2 || names[0] != "id" || names[1] != "type" {
            return Err(format!("header must start with `# id type`, found `{header}`"));
        }
        let mut t = AtomTable { columns: names[2..].iter().map(|s| s.to_string()).collect(), rows: BTreeMap::new() };
        for (k, line) in lines.enumerate() {
            let w: Vec<&str> = line.split_whitespace().collect();
            if w.is_empty() {
                continue;
            }
            if w.len() != names.len() {
                return Err(format!("line {}: {} values, expected {}", k + 2, w.len(), names.len()));
            }
            let id: i64 = w[0].parse().map_err(|_| format!("line {}: bad id", k + 2))?;
            let typ: usize = w[1].parse().map_err(|_| format!("line {}: bad type", k + 2))?;
            let vals: Result<Vec<f64>, _> = w[2..].iter().map(|s| s.parse::<f64>()).collect();
            t.rows.insert(id, (typ, vals.map_err(|_| format!("line {}: bad number", k + 2))?));
        }
        Ok(t)
    }
    /// The text format (`%.17g`-exact numbers).
    pub fn to_text(&self) -> String {
        let mut s = format!("# id type {}\n", self.columns.join(" "));
        for (id, (typ, vals)) in &self.rows {
            s += &format!("{id} {typ}");
            for v in vals {
                s += &format!(" {v:?}");
            }
            s.push('\n');
        }
        s
    }
    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }
}

fn table(sim: &Simulation, columns: &[&str], value: impl Fn(usize, &str) -> f64) -> AtomTable {
    let a = &sim.state.atoms;
    let mut t = AtomTable { columns: columns.iter().map(|s| s.to_string()).collect(), rows: BTreeMap::new() };
    for i in 0..a.nlocal {
        t.rows.insert(a.tag[i], (a.typ[i], columns.iter().map(|c| value(i, c)).collect()));
    }
    t
}

/// Forces (and SPH rates, torques) of the current state, as lammps_driver.py writes forces0.txt.
pub fn capture_forces(sim: &Simulation) -> AtomTable {
    let ft = sim.state.atoms.features;
    let mut cols = vec!["fx", "fy", "fz"];
    if ft.sph {
        cols.extend(["drho", "desph"]);
    }
    if ft.sphere {
        cols.extend(["tqx", "tqy", "tqz"]);
    }
    let a = &sim.state.atoms;
    table(sim, &cols, |i, c| match c {
        "fx" => a.f[i][0],
        "fy" => a.f[i][1],
        "fz" => a.f[i][2],
        "drho" => a.drho[i],
        "desph" => a.desph[i],
        "tqx" => a.torque[i][0],
        "tqy" => a.torque[i][1],
        _ => a.torque[i][2],
    })
}

/// Unwrapped positions and velocities (and SPH/sphere state), as final.txt.
pub fn capture_state(sim: &Simulation) -> AtomTable {
    let ft = sim.state.atoms.features;
    let mut cols = vec!["xu", "yu", "zu", "vx", "vy", "vz"];
    if ft.sph {
        cols.extend(["rho", "esph"]);
    }
    if ft.sphere {
        cols.extend(["omegax", "omegay", "omegaz"]);
    }
    let a = &sim.state.atoms;
    let prd = sim.state.domain.as_ref().map(|d| d.prd()).unwrap_or([0.0; 3]);
    table(sim, &cols, |i, c| match c {
        "xu" => a.x[i][0] + a.image[i][0] as f64 * prd[0],
        "yu" => a.x[i][1] + a.image[i][1] as f64 * prd[1],
        "zu" => a.x[i][2] + a.image[i][2] as f64 * prd[2],
        "vx" => a.v[i][0],
        "vy" => a.v[i][1],
        "vz" => a.v[i][2],
        "rho" => a.rho[i],
        "esph" => a.esph[i],
        "omegax" => a.omega[i][0],
        "omegay" => a.omega[i][1],
        _ => a.omega[i][2],
    })
}

/// The difference of one quantity (a group of columns) between two tables.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    pub quantity: String,
    pub max_abs: f64,
    /// `max_abs / scale`.
    pub max_rel: f64,
    /// The scale the relative difference is measured against.
    pub scale: f64,
    pub scale_name: String,
    /// Atom with the largest difference.
    pub worst_id: i64,
}

/// How a quantity's relative difference is scaled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// Largest magnitude of the quantity in the reference (e.g. the force scale).
    MaxMagnitude,
    /// A fixed length (e.g. the box size for positions).
    Fixed(f64),
}

/// Compare the columns `cols` of two tables (same atom IDs required).
pub fn compare(ours: &AtomTable, reference: &AtomTable, quantity: &str, cols: &[&str], scale: Scale) -> Result<Difference, String> {
    if ours.rows.len() != reference.rows.len() {
        return Err(format!("{quantity}: dmhs has {} atoms, the reference {}", ours.rows.len(), reference.rows.len()));
    }
    let ci: Vec<(usize, usize)> = cols
        .iter()
        .map(|c| match (ours.column(c), reference.column(c)) {
            (Some(a), Some(b)) => Ok((a, b)),
            _ => Err(format!("{quantity}: column `{c}` missing")),
        })
        .collect::<Result<_, _>>()?;
    let mut max_abs: f64 = 0.0;
    let mut worst = 0;
    let mut mag: f64 = 0.0;
    for (id, (typ, rv)) in &reference.rows {
        let (otyp, ov) = ours.rows.get(id).ok_or_else(|| format!("{quantity}: atom {id} missing in dmhs"))?;
        if otyp != typ {
            return Err(format!("{quantity}: atom {id} has type {otyp} in dmhs, {typ} in the reference"));
        }
        for &(a, b) in &ci {
            let d = (ov[a] - rv[b]).abs();
            if !(d <= max_abs) {
                max_abs = d;
                worst = *id;
            }
            mag = mag.max(rv[b].abs());
        }
    }
    let (s, name) = match scale {
        Scale::MaxMagnitude => (mag, format!("max |{quantity}|")),
        Scale::Fixed(x) => (x, "box length".to_string()),
    };
    let max_rel = if s > 0.0 { max_abs / s } else { max_abs };
    Ok(Difference { quantity: quantity.to_string(), max_abs, max_rel, scale: s, scale_name: name, worst_id: worst })
}

/// The comparison of a whole run: forces at step 0 and the final state.
pub fn compare_runs(ours0: &AtomTable, ref0: &AtomTable, ours: &AtomTable, reference: &AtomTable, box_len: f64) -> Result<Vec<Difference>, String> {
    let mut out = vec![compare(ours0, ref0, "force", &["fx", "fy", "fz"], Scale::MaxMagnitude)?];
    for (q, cols) in [("drho", &["drho"][..]), ("desph", &["desph"][..]), ("torque", &["tqx", "tqy", "tqz"][..])] {
        if ref0.column(cols[0]).is_some() {
            out.push(compare(ours0, ref0, q, cols, Scale::MaxMagnitude)?);
        }
    }
    out.push(compare(ours, reference, "position", &["xu", "yu", "zu"], Scale::Fixed(box_len))?);
    out.push(compare(ours, reference, "velocity", &["vx", "vy", "vz"], Scale::MaxMagnitude)?);
    for (q, cols) in [("rho", &["rho"][..]), ("esph", &["esph"][..]), ("omega", &["omegax", "omegay", "omegaz"][..])] {
        if reference.column(cols[0]).is_some() {
            out.push(compare(ours, reference, q, cols, Scale::MaxMagnitude)?);
        }
    }
    Ok(out)
}

/// A table of differences for printing.
pub fn report(diffs: &[Difference]) -> String {
    let mut s = format!("{:<10} {:>12} {:>12} {:>14}  {}\n", "quantity", "max abs", "max rel", "scale", "worst atom");
    for d in diffs {
        s += &format!("{:<10} {:>12.3e} {:>12.3e} {:>14.6e}  {} ({})\n", d.quantity, d.max_abs, d.max_rel, d.scale, d.worst_id, d.scale_name);
    }
    s
}
