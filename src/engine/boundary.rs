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

/// The dimensions with a shrink-wrapped face.
fn shrink_dims(domain: &Domain) -> Vec<usize> {
    let shrink = |b: BoundaryKind| matches!(b, BoundaryKind::Shrink | BoundaryKind::ShrinkMin);
    (0..3).filter(|&d| domain.boundary[d][0] != BoundaryKind::Periodic && (shrink(domain.boundary[d][0]) || shrink(domain.boundary[d][1]))).collect()
}

/// Resize shrink-wrapped faces to the atom extent (LAMMPS `Domain::reset_box`), the atoms'
/// positions in box fractions on a triclinic box (as LAMMPS' callers convert them).
/// `initial` is the box as first created (its length sets the margin; `m` keeps it as a bound).
pub fn reset_shrink_wrap(domain: &mut Domain, initial: &Domain, atoms: &mut Atoms) {
    reset_shrink_wrap_over(domain, initial, atoms, |_| {});
}

/// [`reset_shrink_wrap`] of atoms whose positions are in box coordinates: on a triclinic box
/// with a shrink-wrapped face they go to box fractions and back around it (LAMMPS' read_data
/// and change_box).
pub fn reset_shrink_wrap_box_coords(domain: &mut Domain, initial: &Domain, atoms: &mut Atoms) {
    if domain.triclinic() && !shrink_dims(domain).is_empty() {
        to_fractions(domain, atoms);
        reset_shrink_wrap(domain, initial, atoms);
        to_box(domain, atoms);
    } else {
        reset_shrink_wrap(domain, initial, atoms);
    }
}

/// Every owned atom remapped into the box (LAMMPS' Domain::remap), then LAMMPS' migration:
/// in box fractions on a triclinic box (one more round trip through them), the
/// shrink-wrapped faces reset around the atoms (change_box, displace_atoms, read_dump).
pub fn remap_and_migrate(domain: &mut Domain, initial: Option<&Domain>, atoms: &mut Atoms) {
    for i in 0..atoms.nlocal {
        domain.remap(&mut atoms.x[i], &mut atoms.image[i]);
    }
    let tilted = domain.triclinic();
    if tilted {
        to_fractions(domain, atoms);
    }
    if let Some(initial) = initial {
        reset_shrink_wrap(domain, initial, atoms);
    }
    if tilted {
        to_box(domain, atoms);
    }
}

/// LAMMPS' Domain::pbc over the owned atoms (their positions in box fractions on a triclinic
/// box): an atom of fix deform's `remap v` group that crosses a periodic face also gets the
/// box's velocity change.
pub fn pbc_owned(domain: &Domain, atoms: &mut Atoms) {
    let vremap = domain.rate.vremap;
    for i in 0..atoms.nlocal {
        let v = vremap.filter(|&g| atoms.mask[i] & g != 0).map(|_| &mut atoms.v[i]);
        domain.pbc(&mut atoms.x[i], &mut atoms.image[i], v);
    }
}

/// The owned atoms' positions to box fractions (LAMMPS' x2lamda(nlocal)).
pub fn to_fractions(domain: &Domain, atoms: &mut Atoms) {
    for x in atoms.x[..atoms.nlocal].iter_mut() {
        *x = domain.x2lamda(*x);
    }
}

/// The owned atoms' positions from box fractions (LAMMPS' lamda2x(nlocal)).
pub fn to_box(domain: &Domain, atoms: &mut Atoms) {
    for x in atoms.x[..atoms.nlocal].iter_mut() {
        *x = domain.lamda2x(*x);
    }
}

/// [`reset_shrink_wrap`] over the atoms of every rank: `max_over_ranks` takes each element's
/// largest value over the ranks (a rank alone: nothing to do), so every rank gets the same box.
/// On a triclinic box the extent is in box fractions; the atoms go back to box coordinates in
/// the old box, each face is placed at its extreme fraction's point in the old box, and the
/// atoms go to fractions of the new box and are wrapped once more (LAMMPS: x2lamda can leave
/// [0, 1) by round-off).
pub fn reset_shrink_wrap_over(domain: &mut Domain, initial: &Domain, atoms: &mut Atoms, max_over_ranks: impl FnOnce(&mut [f64])) {
    let dims = shrink_dims(domain);
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
    let tilted = domain.triclinic();
    let old = domain.clone();
    if tilted {
        to_box(&old, atoms);
    }
    for d in dims {
        let [blo, bhi] = domain.boundary[d];
        let (mut lo, mut hi) = (-extent[2 * d], extent[2 * d + 1]);
        if tilted {
            // the box point at that fraction along d (the other fractions 0)
            let point = |f: f64| {
                let mut l = [0.0; 3];
                l[d] = f;
                old.lamda2x(l)[d]
            };
            (lo, hi) = (point(lo), point(hi));
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
    if tilted {
        to_fractions(domain, atoms);
        pbc_owned(domain, atoms);
    }
}
