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
