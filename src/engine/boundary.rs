//! Non-periodic boundaries: shrink-wrapping (`s`, `m`) and atoms lost through fixed faces.

use crate::engine::atoms::Atoms;
use crate::engine::domain::{BoundaryKind, Domain};
use crate::sim::{RunError, Simulation};

/// LAMMPS' margin for shrink-wrapped faces, as a fraction of the initial box length.
const SMALL: f64 = 1.0e-4;

/// Resize shrink-wrapped faces to the atom extent (LAMMPS `Domain::reset_box`).
/// `initial` is the box as first created (its length sets the margin; `m` keeps it as a bound).
pub fn reset_shrink_wrap(domain: &mut Domain, initial: &Domain, atoms: &Atoms) {
    let n = atoms.nlocal;
    if n == 0 {
        return;
    }
    for d in 0..3 {
        let [blo, bhi] = domain.boundary[d];
        if blo == BoundaryKind::Periodic {
            continue;
        }
        let shrink = |b: BoundaryKind| matches!(b, BoundaryKind::Shrink | BoundaryKind::ShrinkMin);
        if !shrink(blo) && !shrink(bhi) {
            continue;
        }
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for x in &atoms.x[..n] {
            lo = lo.min(x[d]);
            hi = hi.max(x[d]);
        }
        let small = SMALL * (initial.hi[d] - initial.lo[d]);
        match blo {
            BoundaryKind::Shrink => domain.lo[d] = lo - small,
            BoundaryKind::ShrinkMin => domain.lo[d] = (lo - small).min(initial.lo[d]),
            _ => {}
        }
        match bhi {
            BoundaryKind::Shrink => domain.hi[d] = hi + small,
            BoundaryKind::ShrinkMin => domain.hi[d] = (hi + small).max(initial.hi[d]),
            _ => {}
        }
    }
}

/// Atoms outside a fixed face are lost, as in LAMMPS: an error naming the first one
/// (or, with `thermo_modify lost ignore`, they are removed).
pub fn check_lost(sim: &mut Simulation) -> Result<(), RunError> {
    let Some(domain) = sim.state.domain.as_ref() else { return Ok(()) };
    let a = &sim.state.atoms;
    let mut gone = vec![false; a.nlocal];
    let mut first: Option<(usize, usize)> = None;
    for i in 0..a.nlocal {
        for d in 0..3 {
            let [blo, bhi] = domain.boundary[d];
            let x = a.x[i][d];
            let out = (blo == BoundaryKind::Fixed && x < domain.lo[d]) || (bhi == BoundaryKind::Fixed && x >= domain.hi[d]) || !x.is_finite();
            if out {
                gone[i] = true;
                first.get_or_insert((i, d));
            }
        }
    }
    let Some((i, d)) = first else { return Ok(()) };
    if sim.thermo.lost_ignore {
        let tags: std::collections::HashSet<i64> = (0..a.nlocal).filter(|&k| gone[k]).map(|k| a.tag[k]).collect();
        sim.state.atoms.retain(&gone);
        sim.state.topo.remove_atoms(&tags);
        return Ok(());
    }
    let n_lost = gone.iter().filter(|&&g| g).count();
    Err(RunError::new(
        sim.state.step,
        format!(
            "lost atoms: {n_lost} of {} left the box through a fixed boundary (first: atom {} at {} = {}, box {}..{}){}",
            a.nlocal,
            a.tag[i],
            ["x", "y", "z"][d],
            a.x[i][d],
            domain.lo[d],
            domain.hi[d],
            crate::sim::stability::dt_hint(sim)
        ),
    ))
}
