//! `replicate nx ny nz [bbox]`: the system copied nx*ny*nz times, as LAMMPS'
//! Replicate on one process.
//!
//! Atoms are first unwrapped with their image flags; copy (ix, iy, iz) is shifted by
//! (ix, iy, iz) old box lengths (a triclinic box's by its edge vectors, the tilts included) and
//! remapped into the new box, whose upper bounds are lo + n * prd and whose tilts are xy ny,
//! xz nz, yz nz. Copies are made replica by replica (z fastest, then y, then x), each in the
//! old local order, and copy k = ix + nx (iy + ny iz) adds k * maxtag to atom IDs and
//! k * maxmol to positive molecule IDs; bonds, angles and dihedrals are copied with their atom
//! IDs shifted the same way. Every other per-atom value is copied unchanged. Shrink-wrapped
//! faces of the new box are padded as create_box pads them.

use super::need_box;
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap};

pub const SYNTAX: &str = "replicate nx ny nz [bbox]";

pub fn replicate(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let mut a = Args::new(cmd, SYNTAX);
    let mut n = [0usize; 3];
    for (d, what) in ["nx", "ny", "nz"].iter().enumerate() {
        n[d] = a.i64_in(what, 1, i32::MAX as i64)? as usize;
    }
    if let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            // a bounding box speeds up the assignment to processes; one process has nothing to gain
            "bbox" => {}
            // LAMMPS 22 Jul 2025 refuses it too ("Illegal replicate command"); later versions add it
            "bondlist" => return Err(a.error_at(w, "replicate bondlist is not in LAMMPS 22 Jul 2025 (the version dmhs follows) and is not supported", "supported: bbox")),
            _ => return Err(a.unknown_keyword(w, &["bbox"])),
        }
    }
    a.finish()?;
    let nrep = n[0] * n[1] * n[2];
    if nrep > i32::MAX as usize {
        return Err(Diagnostic::at(cmd.span, format!("replicate {}x{}x{} = {nrep} copies: more than 2^31 - 1 (replicate in several steps)", n[0], n[1], n[2]), "too many copies"));
    }
    if sim.state.dimension == 2 && n[2] != 1 {
        return Err(Diagnostic::at(cmd.args[2].span, "a 2d simulation cannot be replicated in z", "must be 1 in 2d"));
    }
    refuse_stored_values(sim, cmd)?;
    let domain = sim.state.domain.clone().expect("need_box");
    if (0..3).any(|d| n[d] > 1 && !domain.periodic(d)) {
        sim.out.print("WARNING: Replicating in a non-periodic dimension");
    }
    let st = &mut sim.state;
    st.atoms.clear_ghosts();
    let nold = st.atoms.nlocal;
    let maxtag = st.atoms.max_tag();
    let maxmol = if st.atoms.features.molecule { st.atoms.max_molecule() } else { 0 };
    // LAMMPS' atom IDs are 32-bit integers
    if maxtag as i128 + (nrep as i128 - 1) * nold as i128 >= i32::MAX as i128 {
        return Err(Diagnostic::at(cmd.span, format!("replicate would give atom IDs beyond 2^31 - 1 (LAMMPS' limit): {nrep} copies of {nold} atoms, largest ID {maxtag}"), "replicated IDs too big"));
    }
    crate::sim::memory::check_atoms((nold * nrep) as f64, st.atoms.features, 0, 0).map_err(|e| Diagnostic::at(cmd.span, format!("replicate: {} atoms: {e}", nold * nrep), "too many atoms for this machine"))?;
    sim.out.print(&format!("Replication is creating a {}x{}x{} = {nrep} times larger system...", n[0], n[1], n[2]));

    let st = &mut sim.state;
    let old_order = lammps_local_order(st);
    let prd = domain.prd();
    let mut big = domain.clone();
    for d in 0..3 {
        big.hi[d] = domain.lo[d] + n[d] as f64 * prd[d];
    }
    let tilt = domain.tilt;
    big.tilt = tilt.map(|[xy, xz, yz]| [xy * n[1] as f64, xz * n[2] as f64, yz * n[2] as f64]);
    // copies (ix, iy, iz) with z fastest; copy k of atom old_order[j] becomes atom k * nold + j
    let reps: Vec<[usize; 3]> = (0..n[0]).flat_map(|ix| (0..n[1]).flat_map(move |iy| (0..n[2]).map(move |iz| [ix, iy, iz]))).collect();
    let periods = domain.periods();
    let unwrapped: Vec<[f64; 3]> = old_order.iter().map(|&i| periods.unmap_summed(st.atoms.x[i], st.atoms.image[i])).collect();
    let mut placed = Vec::with_capacity(nold * nrep);
    for rep in &reps {
        // copy (ix, iy, iz) is the image (ix, iy, iz) of the old box (LAMMPS' arithmetic)
        let shift = rep.map(|k| k as i32);
        for u in &unwrapped {
            let mut x = periods.unmap(*u, shift);
            let mut image = [0; 3];
            big.remap(&mut x, &mut image);
            placed.push((x, image));
        }
    }
    // inside the new box along each non-periodic dimension (a triclinic box's in box fractions)
    let inside = |x: &[f64; 3]| {
        let (c, lo, hi) = if big.triclinic() { (big.x2lamda(*x), [0.0; 3], [1.0; 3]) } else { (*x, big.lo, big.hi) };
        (0..3).all(|d| big.periodic(d) || (c[d] >= lo[d] && c[d] < hi[d]))
    };
    let lost = placed.iter().filter(|(x, _)| !inside(x)).count();
    if lost > 0 {
        return Err(Diagnostic::at(cmd.span, format!("replicate: {lost} copied atoms would lie outside the new box in a non-periodic dimension (LAMMPS: \"Replicate did not assign all atoms correctly\")"), "atoms outside the box"));
    }
    let order: Vec<usize> = reps.iter().flat_map(|_| old_order.iter().copied()).collect();
    st.atoms.permute(&order);
    let atoms = &mut st.atoms;
    for (i, (x, image)) in placed.into_iter().enumerate() {
        let copy = copy_index(reps[i / nold.max(1)], n);
        atoms.x[i] = x;
        atoms.image[i] = image;
        atoms.tag[i] += copy * maxtag;
        if atoms.features.molecule && atoms.molecule[i] > 0 {
            atoms.molecule[i] += copy * maxmol;
        }
    }
    replicate_topology(&mut st.topo, &reps, n, maxtag);
    // LAMMPS' set_initial_box(1): the margins of shrink-wrapped faces come from the new box and
    // pad it until the next run wraps it (seen by $(ylo) and EDGE regions between commands)
    st.box_initial = Some(big.clone());
    st.domain = Some(crate::engine::boundary::pad_shrink_faces(&big));
    st.grid_areas = st.domain.as_ref().map(crate::engine::domain::Domain::face_areas);
    sim.out.print(&format!("  {}", crate::deck::box_text(&big)));
    sim.out.print(&format!("  {} atoms", sim.state.atoms.nlocal));
    let t = &sim.state.topo;
    for (count, what) in [(t.bonds.len(), "bonds"), (t.angles.len(), "angles"), (t.dihedrals.len(), "dihedrals")] {
        if count > 0 {
            sim.out.print(&format!("  {count} {what}"));
        }
    }
    if sim.state.atoms.features.molecular() {
        sim.state.rebuild_special().map_err(|e| Diagnostic::at(cmd.span, e, "special lists"))?;
    }
    sim.state.lists_valid = false;
    Ok(())
}

/// LAMMPS' number of copy (ix, iy, iz): its IDs are offset by that many times the old largest.
fn copy_index(rep: [usize; 3], n: [usize; 3]) -> i64 {
    (rep[2] * n[1] * n[0] + rep[1] * n[0] + rep[0]) as i64
}

/// LAMMPS refuses to replicate while a fix stores per-atom values it could not copy (fix
/// move's original positions, a granular pair's contact history, the BPM bonds' reference
/// lengths); so does dmhs. The DMHS fields (temperature, water, phase, ...) are properties of
/// the particles and are copied.
fn refuse_stored_values(sim: &mut Simulation, cmd: &Command) -> DResult<()> {
    let refuse = |what: String| Err(Diagnostic::at(cmd.span, format!("cannot replicate with fixes that store per-atom values ({what}); unfix them before replicate and define them again after it"), "stored per-atom values"));
    if let Some(e) = sim.state.atoms.extra.iter().find(|e| !e.name.starts_with("dmhs/")) {
        return refuse(format!("per-atom array `{}`", e.name));
    }
    if sim.state.topo.bonds.iter().any(|b| b.history[0] != 0.0) {
        return refuse("the reference lengths of the BPM bonds".into());
    }
    if let Some(p) = sim.pair.as_deref_mut() {
        if p.histories().iter().any(|h| !h.records().is_empty()) {
            return refuse("the pair style's contact history".into());
        }
    }
    Ok(())
}

/// Owned atoms in LAMMPS' local order: the order LAMMPS knew at the last rebuild, less the
/// atoms gone since, then atoms made since in dmhs' order (their creation order).
fn lammps_local_order(st: &crate::engine::state::State) -> Vec<usize> {
    let mut order = st.lammps_order.clone();
    order.before_rebuild(&st.atoms);
    let map = st.atoms.tag_map();
    order.ids().iter().map(|&t| map.get(t).expect("every ordered atom is owned")).collect()
}

/// Bonds, angles and dihedrals of every copy, copy by copy in the atoms' order of copies.
fn replicate_topology(t: &mut crate::engine::topology::Topology, reps: &[[usize; 3]], n: [usize; 3], maxtag: i64) {
    let (bonds, angles, dihedrals) = (std::mem::take(&mut t.bonds), std::mem::take(&mut t.angles), std::mem::take(&mut t.dihedrals));
    for rep in reps {
        let off = copy_index(*rep, n) * maxtag;
        t.bonds.extend(bonds.iter().map(|b| crate::engine::topology::Bond { atoms: b.atoms.map(|a| a + off), ..*b }));
        t.angles.extend(angles.iter().map(|a| crate::engine::topology::Angle { atoms: a.atoms.map(|x| x + off), ..*a }));
        t.dihedrals.extend(dihedrals.iter().map(|d| crate::engine::topology::Dihedral { atoms: d.atoms.map(|x| x + off), ..*d }));
    }
}
