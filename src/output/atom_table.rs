//! Tables of per-atom values keyed by atom ID, in the text format of lammps-refs/ (`# id type
//! c1 c2 ...`, numbers that round-trip exactly): what `dmhs capture` writes and `crosscheck`
//! compares, and dmhs' own captures of forces and state.

use crate::engine::state::State;
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

fn table(state: &State, columns: &[&str], value: impl Fn(usize, &str) -> f64) -> AtomTable {
    let a = &state.atoms;
    let mut t = AtomTable { columns: columns.iter().map(|s| s.to_string()).collect(), rows: BTreeMap::new() };
    for i in 0..a.nlocal {
        t.rows.insert(a.tag[i], (a.typ[i], columns.iter().map(|c| value(i, c)).collect()));
    }
    t
}

/// Forces (and SPH rates, torques) of the current state, as lammps_driver.py writes forces0.txt.
pub fn forces_table(state: &State) -> AtomTable {
    let ft = state.atoms.features;
    let mut cols = vec!["fx", "fy", "fz"];
    if ft.sph {
        cols.extend(["drho", "desph"]);
    }
    if ft.sphere {
        cols.extend(["tqx", "tqy", "tqz"]);
    }
    let a = &state.atoms;
    // LAMMPS' heatflow (fix property/atom heatflow)
    let heatflow = a.field_values(crate::engine::fields::HEATFLOW);
    if heatflow.is_some() {
        cols.push("heatflow");
    }
    table(state, &cols, |i, c| match c {
        "fx" => a.f[i][0],
        "fy" => a.f[i][1],
        "fz" => a.f[i][2],
        "drho" => a.drho[i],
        "desph" => a.desph[i],
        "tqx" => a.torque[i][0],
        "tqy" => a.torque[i][1],
        "heatflow" => heatflow.map_or(0.0, |q| q[i]),
        _ => a.torque[i][2],
    })
}

/// Unwrapped positions and velocities (and SPH/sphere state), as final.txt.
pub fn state_table(state: &State) -> AtomTable {
    let ft = state.atoms.features;
    let mut cols = vec!["xu", "yu", "zu", "vx", "vy", "vz"];
    if ft.sph {
        cols.extend(["rho", "esph"]);
    }
    if ft.sphere {
        cols.extend(["omegax", "omegay", "omegaz"]);
    }
    let a = &state.atoms;
    // per-atom temperature (LAMMPS' fix property/atom temperature; DMHS' fix dmhs/phase)
    let temperature = a.field_values(crate::engine::fields::TEMPERATURE);
    if temperature.is_some() {
        cols.push("temperature");
    }
    let periods = state.domain.as_ref().map(|d| d.periods()).unwrap_or_default();
    table(state, &cols, |i, c| match c {
        "xu" => periods.unmap(a.x[i], a.image[i])[0],
        "yu" => periods.unmap(a.x[i], a.image[i])[1],
        "zu" => periods.unmap(a.x[i], a.image[i])[2],
        "vx" => a.v[i][0],
        "vy" => a.v[i][1],
        "vz" => a.v[i][2],
        "rho" => a.rho[i],
        "esph" => a.esph[i],
        "omegax" => a.omega[i][0],
        "omegay" => a.omega[i][1],
        "temperature" => temperature.map_or(0.0, |t| t[i]),
        _ => a.omega[i][2],
    })
}


/// State and forces in one table (the columns of final.txt, then those of forces0.txt), as
/// lammps_driver.py writes checkpoint.STEP.txt.
pub fn checkpoint_table(state: &State) -> AtomTable {
    let (s, f) = (state_table(state), forces_table(state));
    let mut t = AtomTable { columns: s.columns, rows: s.rows };
    t.columns.extend(f.columns);
    for (id, (_, vals)) in f.rows {
        if let Some(row) = t.rows.get_mut(&id) {
            row.1.extend(vals);
        }
    }
    t
}
