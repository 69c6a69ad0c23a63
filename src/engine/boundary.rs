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
