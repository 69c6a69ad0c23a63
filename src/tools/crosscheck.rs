//! Per-atom comparison with LAMMPS: tables of per-atom values keyed by atom ID (the format of
//! lammps-refs/), dmhs' own captures, and the max absolute/relative differences per quantity.

pub use crate::output::atom_table::AtomTable;
use crate::output::atom_table::{forces_table, state_table};
use crate::sim::Simulation;

/// Forces (and SPH rates, torques) of the simulation now, as lammps_driver.py writes forces0.txt.
pub fn capture_forces(sim: &Simulation) -> AtomTable {
    forces_table(&sim.state)
}

/// Unwrapped positions and velocities (and SPH/sphere state) now, as final.txt.
pub fn capture_state(sim: &Simulation) -> AtomTable {
    state_table(&sim.state)
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
    for (q, cols) in [("drho", &["drho"][..]), ("desph", &["desph"][..]), ("torque", &["tqx", "tqy", "tqz"][..]), ("heatflow", &["heatflow"][..])] {
        if ref0.column(cols[0]).is_some() {
            out.push(compare(ours0, ref0, q, cols, Scale::MaxMagnitude)?);
        }
    }
    out.push(compare(ours, reference, "position", &["xu", "yu", "zu"], Scale::Fixed(box_len))?);
    out.push(compare(ours, reference, "velocity", &["vx", "vy", "vz"], Scale::MaxMagnitude)?);
    for (q, cols) in [("rho", &["rho"][..]), ("esph", &["esph"][..]), ("omega", &["omegax", "omegay", "omegaz"][..]), ("temperature", &["temperature"][..])] {
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

/// One engine's run as crosscheck compares it: forces after the setup of the first run (step
/// 0), state and forces at the checkpoints, the state at the end of the deck.
#[derive(Clone, Debug, Default)]
pub struct Capture {
    pub forces0: AtomTable,
    pub checkpoints: Vec<(i64, AtomTable)>,
    pub fin: AtomTable,
}

/// The quantities compared, their columns, and which strict tolerance applies (0 force-like,
/// 1 position, 2 velocity-like: `cli_crosscheck::within`'s grouping).
pub const QUANTITIES: [(&str, &[&str], usize); 11] = [
    ("force", &["fx", "fy", "fz"], 0),
    ("drho", &["drho"], 0),
    ("desph", &["desph"], 0),
    ("torque", &["tqx", "tqy", "tqz"], 0),
    ("position", &["xu", "yu", "zu"], 1),
    ("velocity", &["vx", "vy", "vz"], 2),
    ("rho", &["rho"], 2),
    ("esph", &["esph"], 2),
    ("omega", &["omegax", "omegay", "omegaz"], 2),
    ("heatflow", &["heatflow"], 0),
    ("temperature", &["temperature"], 2),
];

/// dmhs may be at most this many times further from LAMMPS than LAMMPS is from itself.
pub const CHAOS_MARGIN: f64 = 100.0;

/// One quantity along the run: per point (step 0, checkpoints, end) the largest difference of
/// dmhs from LAMMPS and of LAMMPS (one-ulp nudge) from LAMMPS, both divided by `scale`.
#[derive(Clone, Debug)]
pub struct Curve {
    pub quantity: &'static str,
    pub tol: f64,
    pub scale: f64,
    /// Why this scale (printed).
    pub scale_why: String,
    /// (point label, dmhs-vs-LAMMPS, LAMMPS-vs-LAMMPS, atom with the largest dmhs difference).
    pub rows: Vec<(String, f64, f64, i64)>,
}

impl Curve {
    /// The largest difference allowed at a point: the strict tolerance, or `CHAOS_MARGIN` times
    /// LAMMPS' own divergence there when that is larger.
    pub fn allowed(&self, selfdiff: f64) -> f64 {
        self.tol.max(CHAOS_MARGIN * selfdiff)
    }
    /// Points where dmhs differs by more than allowed.
    pub fn failures(&self) -> Vec<String> {
        self.rows
            .iter()
            .filter(|(_, d, e, _)| !(*d <= self.allowed(*e)))
            .map(|(label, d, e, id)| {
                let why = if self.allowed(*e) > self.tol { format!("{CHAOS_MARGIN} x LAMMPS' own divergence {e:.1e}") } else { format!("tolerance {:.0e}; LAMMPS' own divergence {e:.1e}", self.tol) };
                format!("{} at {label}: dmhs differs from LAMMPS by {d:.3e} > {:.1e} ({why}; atom {id})", self.quantity, self.allowed(*e))
            })
            .collect()
    }
    /// The last point up to which dmhs agrees within the strict tolerance (None: not even the first).
    pub fn agrees_up_to(&self) -> Option<&str> {
        let n = self.rows.iter().take_while(|r| r.1 <= self.tol).count();
        n.checked_sub(1).map(|k| self.rows[k].0.as_str())
    }
}

fn checkpoint_at<'a>(cap: &'a Capture, step: i64, which: &str) -> Result<&'a AtomTable, String> {
    cap.checkpoints.iter().find(|x| x.0 == step).map(|x| &x.1).ok_or_else(|| format!("LAMMPS{which} wrote no checkpoint at step {step}"))
}

fn max_magnitude(t: &AtomTable, cols: &[&str]) -> Option<f64> {
    let ci: Vec<usize> = cols.iter().map(|c| t.column(c)).collect::<Option<_>>()?;
    Some(t.rows.values().flat_map(|(_, v)| ci.iter().map(move |&k| v[k].abs())).fold(0.0, f64::max))
}

/// The divergence curves of every quantity the reference has: dmhs (`ours`) and LAMMPS
/// perturbed by round-off (`other`) against LAMMPS (`base`), at step 0 (forces), at each
/// checkpoint both engines wrote, and at the end. Each quantity is divided by one scale for the
/// whole run, its largest magnitude in `base` at any point (positions: the box length), so a
/// quantity that happens to vanish at one point (the forces of a perfect lattice at step 0) is
/// measured against the size it has in the run.
pub fn curves(ours: &Capture, base: &Capture, other: &Capture, box_len: f64, tols: [f64; 3]) -> Result<Vec<Curve>, String> {
    let mut points: Vec<(String, &AtomTable, &AtomTable, &AtomTable)> = vec![("step 0".to_string(), &ours.forces0, &base.forces0, &other.forces0)];
    for (step, t) in &ours.checkpoints {
        points.push((format!("step {step}"), t, checkpoint_at(base, *step, "")?, checkpoint_at(other, *step, " (nudged run)")?));
    }
    points.push(("end".to_string(), &ours.fin, &base.fin, &other.fin));
    let mut out = vec![];
    for (q, cols, tk) in QUANTITIES {
        let present: Vec<_> = points.iter().filter(|p| p.2.column(cols[0]).is_some()).collect();
        if present.is_empty() {
            continue;
        }
        let (scale, scale_why) = if q == "position" {
            (box_len, "box length".to_string())
        } else {
            let (mut m, mut at) = (0.0, "");
            for p in &present {
                let v = max_magnitude(p.2, cols).unwrap_or(0.0);
                if v > m {
                    (m, at) = (v, p.0.as_str());
                }
            }
            let mut why = format!("largest |{q}| in LAMMPS over step 0, the checkpoints and the end ({at})");
            if let Some(s0) = (q != "position").then(|| max_magnitude(&base.forces0, cols)).flatten().filter(|s0| *s0 < 1e-6 * m) {
                why += &format!("; at step 0 it is only {s0:.1e}");
            }
            (m, why)
        };
        let s = if scale > 0.0 { scale } else { 1.0 };
        let mut rows = vec![];
        for (label, o, b, x) in &present {
            let d = compare(o, b, q, cols, Scale::Fixed(1.0))?;
            let e = compare(x, b, q, cols, Scale::Fixed(1.0))?;
            rows.push((label.clone(), d.max_abs / s, e.max_abs / s, d.worst_id));
        }
        out.push(Curve { quantity: q, tol: tols[tk], scale, scale_why, rows });
    }
    Ok(out)
}

/// The divergence table: one row per point, per quantity dmhs-vs-LAMMPS and LAMMPS-vs-LAMMPS.
pub fn curve_table(curves: &[Curve]) -> String {
    let mut s = format!("{:<12}", "point");
    for c in curves {
        s += &format!(" {:>10} {:>10}", short(c.quantity), "(LAMMPS)");
    }
    s.push('\n');
    // every curve's points are a subsequence of step 0, the checkpoints, the end; force (first)
    // has step 0 and the checkpoints, the state quantities add the end
    let mut labels: Vec<&str> = vec![];
    for r in curves.iter().flat_map(|c| &c.rows) {
        if !labels.contains(&r.0.as_str()) {
            labels.push(&r.0);
        }
    }
    for label in labels {
        s += &format!("{label:<12}");
        for c in curves {
            match c.rows.iter().find(|r| r.0 == label) {
                Some(r) => s += &format!(" {:>10.2e} {:>10.2e}", r.1, r.2),
                None => s += &format!(" {:>10} {:>10}", "-", "-"),
            }
        }
        s.push('\n');
    }
    s
}

fn short(q: &str) -> &str {
    match q {
        "position" => "pos",
        "velocity" => "vel",
        _ => q,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(rows: &[(f64, f64)]) -> Curve {
        let rows = rows.iter().enumerate().map(|(k, &(d, e))| (format!("step {}", 1 << k), d, e, 7)).collect();
        Curve { quantity: "velocity", tol: 1e-8, scale: 1.0, scale_why: String::new(), rows }
    }

    #[test]
    fn round_off_then_no_faster_than_lammps_passes() {
        let c = curve(&[(0.0, 0.0), (1e-12, 3e-12), (2e-6, 1e-6), (0.5, 0.4)]);
        assert!(c.failures().is_empty());
        assert_eq!(c.agrees_up_to(), Some("step 2"));
    }

    #[test]
    fn an_early_difference_fails_even_where_lammps_diverges_later() {
        // 1e-6 at step 2 while LAMMPS reproduces itself to 1e-15 there
        let c = curve(&[(0.0, 0.0), (1e-6, 1e-15), (0.5, 0.4)]);
        let f = c.failures();
        assert_eq!(f.len(), 1, "{f:?}");
        assert!(f[0].contains("at step 2"), "{f:?}");
    }

    #[test]
    fn growing_faster_than_the_margin_fails() {
        let c = curve(&[(1e-9, 1e-12), (1e-3, 1e-6)]);
        assert_eq!(c.failures().len(), 1);
        // a deck that stays at round-off keeps the strict tolerance
        assert!(!curve(&[(2e-8, 1e-16)]).failures().is_empty());
    }
}
