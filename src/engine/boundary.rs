//! Non-periodic boundaries: shrink-wrapping (`s`, `m`) and atoms lost through fixed faces.

use crate::engine::atoms::Atoms;
use crate::engine::domain::{BoundaryKind, Domain};

/// LAMMPS' margin for shrink-wrapped faces, as a fraction of the initial box length.
const SMALL: f64 = 1.0e-4;

/// The box LAMMPS' `Domain::set_initial_box(1)` leaves: shrink-wrapped (`s`) faces pushed out
/// by `SMALL` of the box length (create_box, read_data and replicate do this; `m` faces stay).
pub fn pad_shrink_faces(domain: &Domain) -> Domain {
    let mut padded = domain.clone();
    for d in 0..3 {
        let small = SMALL * (domain.hi[d] - domain.lo[d]);
        if domain.boundary[d][0] == BoundaryKind::Shrink {
            padded.lo[d] -= small;
        }
        if domain.boundary[d][1] == BoundaryKind::Shrink {
            padded.hi[d] += small;
        }
    }
    padded
}

/// Resize shrink-wrapped faces to the atom extent (LAMMPS `Domain::reset_box`).
/// `initial` is the box as first created (its length sets the margin; `m` keeps it as a bound).
pub fn reset_shrink_wrap(domain: &mut Domain, initial: &Domain, atoms: &Atoms) {
    reset_shrink_wrap_over(domain, initial, atoms, |_| {});
}

/// [`reset_shrink_wrap`] over the atoms of every rank: `max_over_ranks` takes each element's
/// largest value over the ranks (a rank alone: nothing to do), so every rank gets the same box.
pub fn reset_shrink_wrap_over(domain: &mut Domain, initial: &Domain, atoms: &Atoms, max_over_ranks: impl FnOnce(&mut [f64])) {
    let shrink = |b: BoundaryKind| matches!(b, BoundaryKind::Shrink | BoundaryKind::ShrinkMin);
    let dims: Vec<usize> = (0..3).filter(|&d| domain.boundary[d][0] != BoundaryKind::Periodic && (shrink(domain.boundary[d][0]) || shrink(domain.boundary[d][1]))).collect();
    if dims.is_empty() {
        return;
    }
    // per dimension -lo and hi (a maximum of -x is minus the least x, exactly), then whether
    // any atom exists
    let mut extent = [f64::NEG_INFINITY; 7];
    for x in &atoms.x[..atoms.nlocal] {
        for &d in &dims {
            extent[2 * d] = extent[2 * d].max(-x[d]);
            extent[2 * d + 1] = extent[2 * d + 1].max(x[d]);
        }
    }
    extent[6] = if atoms.nlocal > 0 { 1.0 } else { 0.0 };
    max_over_ranks(&mut extent);
    if extent[6] <= 0.0 {
        return;
    }
    for d in dims {
        let [blo, bhi] = domain.boundary[d];
        let (lo, hi) = (-extent[2 * d], extent[2 * d + 1]);
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
