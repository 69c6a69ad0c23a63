//! The box and its atoms: lattice, region, create_box, create_atoms, delete_atoms,
//! read_data, write_data.

use super::{before_box, need_box};
use crate::engine::atoms::NewAtom;
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap};

pub fn lattice(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let l = crate::engine::lattice::Lattice::from_lammps(cmd, &sim.state.units, sim.state.dimension)?;
    if !l.is_none() {
        sim.out.print(&format!("Lattice spacing in x,y,z = {} {} {}", crate::output::format::g8(l.xlattice), crate::output::format::g8(l.ylattice), crate::output::format::g8(l.zlattice)));
    }
    sim.state.lattice = Some(l);
    Ok(())
}

pub fn region(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    // `region ID delete`: users (fixes, unions) look the ID up again before each run
    if cmd.args.get(1).is_some_and(|w| w.text == "delete") {
        let mut a = Args::new(cmd, "region ID delete");
        let w = a.word("region ID")?;
        a.skip(1);
        a.finish()?;
        let Some(k) = sim.state.regions.iter().position(|r| r.id == w.text) else {
            return Err(a.error_at(w, format!("region `{}` to delete does not exist", w.text), "unknown region"));
        };
        sim.state.regions.remove(k);
        return Ok(());
    }
    let existing = std::mem::take(&mut sim.state.regions);
    let (domain, lattice) = (sim.state.domain.clone(), sim.state.lattice.clone());
    let r = crate::engine::region::Region::from_lammps(cmd, domain.as_ref(), lattice.as_ref(), &existing, &mut |name| dmhs_parser::variables::compute_equal(sim, name));
    sim.state.regions = existing;
    sim.state.regions.push(r?);
    Ok(())
}

/// The region a command names after `keyword`, where it is now if it moves or changes its
/// shape (LAMMPS' `prematch` in the commands that use a region); errors at the command.
pub fn region_now(sim: &mut Simulation, cmd: &Command, keyword: &str) -> DResult<()> {
    let Some(k) = cmd.args.iter().position(|w| w.text == keyword) else { return Ok(()) };
    let Some(id) = cmd.args.get(k + 1) else { return Ok(()) };
    sim.prematch_regions(Some(&id.text)).map_err(|e| Diagnostic::at(id.span, e, "while placing this region"))
}

pub fn create_box(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    before_box(sim, cmd)?;
    let b = crate::deck::create_atoms::create_box(cmd, &sim.state.regions, sim.state.dimension, sim.state.boundary)?;
    sim.state.ntypes = b.ntypes;
    sim.state.type_mass = vec![0.0; b.ntypes + 1];
    sim.state.mass_set = vec![false; b.ntypes + 1];
    let t = &mut sim.state.topo;
    t.nbondtypes = b.bond_types;
    t.nangletypes = b.angle_types;
    t.ndihedraltypes = b.dihedral_types;
    t.nimpropertypes = b.improper_types;
    let d = &b.domain;
    sim.out.print(&format!("Created {}", crate::deck::box_text(d)));
    if let Ok(Some(w)) = crate::deck::tilt_check(d) {
        sim.out.print(&w);
    }
    sim.state.box_initial = Some(b.unpadded);
    sim.state.grid_areas = Some(b.domain.face_areas());
    sim.state.domain = Some(b.domain);
    Ok(())
}

pub fn create_atoms(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    region_now(sim, cmd, "region")?;
    sim.state.atoms.clear_ghosts();
    let existing: Vec<[f64; 3]> = sim.state.atoms.x[..sim.state.atoms.nlocal].to_vec();
    let domain = sim.state.domain.clone().unwrap();
    let st = &sim.state;
    let spec = crate::deck::create_atoms::CreateAtoms::from_lammps(cmd, st.ntypes, domain.dimension, st.lattice.as_ref(), &st.regions, &st.molecules)?;
    let made = spec.generate(&domain, st.lattice.as_ref(), &st.regions, &st.molecules, &existing)?;
    for w in made.warnings {
        sim.out.print(&format!("WARNING: {}", w.message));
    }
    let mut tag = sim.state.atoms.max_tag();
    let mol = spec.mol.as_ref().map(|(id, seed)| (sim.state.molecules.iter().find(|m| &m.id == id).cloned().expect("checked by the parser"), *seed));
    let per_point = mol.as_ref().map(|(m, _)| m.natoms()).unwrap_or(1);
    let n = made.atoms.len() as i64 * per_point as i64;
    if n > crate::engine::atoms::MAX_ATOM_ID - tag {
        return Err(Diagnostic::at(
            cmd.span,
            format!("new atom IDs exceed the largest atom ID {}: {n} atoms after ID {tag}", crate::engine::atoms::MAX_ATOM_ID),
            "too many atoms",
        ));
    }
    match mol {
        None => {
            for (x, typ) in &made.atoms {
                tag += 1;
                sim.state.atoms.push(&NewAtom::at(tag, *typ, *x));
            }
        }
        Some((m, seed)) => {
            let centers: Vec<[f64; 3]> = made.atoms.iter().map(|(x, _)| *x).collect();
            crate::deck::create_atoms::add_molecules(&mut sim.state, &m, seed, spec.rotate, spec.atom_type, &centers, &made.rotations).map_err(|e| Diagnostic::at(cmd.span, e, "create_atoms mol"))?;
        }
    }
    sim.state.lists_valid = false;
    sim.out.print(&format!("Created {n} atoms"));
    Ok(())
}

pub fn delete_atoms(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    region_now(sim, cmd, "region")?;
    let syntax = "delete_atoms group ID | region ID | overlap cutoff group1 group2 | random fraction F yes|no group-ID region-ID|NULL seed | random count N yes|no group-ID region-ID|NULL seed | variable name  [compress yes|no] [bond yes|no] [mol yes|no]";
    let mut a = Args::new(cmd, syntax);
    sim.state.atoms.clear_ghosts();
    let n = sim.state.atoms.nlocal;
    let mut gone = vec![false; n];
    match a.choice("delete style", &["group", "region", "overlap", "porosity", "random", "variable"])? {
        0 => {
            let w = a.word("group ID")?;
            let bit = sim.state.groups.bit(&w.text).ok_or_else(|| a.error_at(w, format!("group `{}` does not exist", w.text), "unknown group"))?;
            for i in 0..n {
                gone[i] = sim.state.atoms.mask[i] & bit != 0;
            }
        }
        1 => {
            let w = a.word("region ID")?;
            let r = sim.state.regions.iter().find(|r| r.id == w.text).ok_or_else(|| a.error_at(w, format!("region `{}` does not exist", w.text), "unknown region"))?;
            for i in 0..n {
                gone[i] = r.matches(sim.state.atoms.x[i]);
            }
        }
        2 => {
            let cut = a.positive_f64("cutoff")?;
            let g1w = a.word("group1")?;
            let g1 = sim.state.groups.bit(&g1w.text).ok_or_else(|| a.error_at(g1w, format!("group `{}` does not exist", g1w.text), "unknown group"))?;
            let g2w = a.word("group2")?;
            let g2 = sim.state.groups.bit(&g2w.text).ok_or_else(|| a.error_at(g2w, format!("group `{}` does not exist", g2w.text), "unknown group"))?;
            let cutneigh = overlap_cutoffs(sim, cmd, cut)?;
            gone = overlap_deletions(sim, cut, &cutneigh, g1, g2).map_err(|e| Diagnostic::at(cmd.span, e, "special bonds"))?;
        }
        4 => gone = random_deletions(sim, &mut a)?,
        5 => {
            let w = a.word("atom-style variable name")?;
            gone = super::atoms_cmds::atom_variable_values(sim, w, &w.text, "delete_atoms")?.iter().map(|&v| v != 0.0).collect();
        }
        _ => {
            let w = a.last().unwrap();
            return Err(a.error_at(w, "delete_atoms porosity is not a style of LAMMPS 22 Jul 2025: use delete_atoms random fraction F no group-ID region-ID seed", "not supported"));
        }
    }
    let molecular = sim.state.atoms.features.molecular();
    let mut compress = true;
    // LAMMPS reports the interactions deleted with `bond yes` or `mol yes`
    let mut report_topology = false;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "compress" => compress = a.yes_no("compress")?,
            // dmhs removes every bond, angle and dihedral of a deleted atom anyway (a dangling
            // one would only stop the next run with LAMMPS' "missing atoms" error)
            "bond" => {
                if a.yes_no("bond")? {
                    if !molecular {
                        return Err(a.error_at(w, "Cannot use delete_atoms bond yes for non-molecular systems", "no bonds in this atom style"));
                    }
                    report_topology = true;
                }
            }
            "mol" => {
                if a.yes_no("mol")? {
                    report_topology = true;
                    if !sim.state.atoms.features.molecule {
                        return Err(a.error_at(w, "Delete_atoms mol yes requires atom attribute molecule", "no molecule IDs"));
                    }
                    // every atom of a molecule (ID > 0) that lost an atom goes too
                    let at = &sim.state.atoms;
                    let mols: std::collections::HashSet<i64> = (0..n).filter(|&i| gone[i] && at.molecule[i] != 0).map(|i| at.molecule[i]).collect();
                    for i in 0..n {
                        gone[i] |= mols.contains(&at.molecule[i]);
                    }
                }
            }
            _ => return Err(a.unknown_keyword(w, &["compress", "bond", "mol"])),
        }
    }
    let t = &sim.state.topo;
    let before = [t.bonds.len(), t.angles.len(), t.dihedrals.len()];
    let ndel = sim.state.delete_owned(&gone);
    // LAMMPS renumbers IDs 1..N only for atomic systems, in its local order
    if compress && !sim.state.atoms.features.molecular() {
        sim.state.lammps_order.renumber(&mut sim.state.atoms);
    } else if compress {
        sim.out.print("WARNING: Ignoring 'compress yes' for molecular system");
    }
    sim.state.lists_valid = false;
    sim.out.print(&format!("Deleted {ndel} atoms, new total = {}", sim.state.atoms.nlocal));
    if report_topology {
        let t = &sim.state.topo;
        let after = [t.bonds.len(), t.angles.len(), t.dihedrals.len()];
        for (k, what) in ["bonds", "angles", "dihedrals"].iter().enumerate().filter(|(k, _)| before[*k] > 0) {
            sim.out.print(&format!("Deleted {} {what}, new total = {}", before[k] - after[k], after[k]));
        }
    }
    Ok(())
}

/// `delete_atoms random fraction F exact | count N error, group-ID region-ID|NULL seed`: the
/// atoms to delete among those in the group and region, as LAMMPS picks them (Marsaglia's
/// generator seeded by `seed` on one process, over the atoms in LAMMPS' local order: each with
/// probability F, or exactly floor(F * eligible) or N of them by select_subset).
fn random_deletions(sim: &mut Simulation, a: &mut Args) -> DResult<Vec<bool>> {
    let order = sim.state.lammps_order.current(&sim.state.atoms);
    let style = a.choice("random style", &["fraction", "count"])?;
    let (fraction, count, exact, strict) = if style == 0 {
        let f = a.f64_where("fraction", "between 0 and 1", |f| (0.0..=1.0).contains(&f))?;
        (f, 0, a.yes_no("exact (yes for the exact fraction)")?, false)
    } else {
        let c = a.i64_in("count", 0, i64::MAX)? as usize;
        (0.0, c, true, a.yes_no("error (yes: an error when too few atoms are eligible)")?)
    };
    let gw = a.word("group ID")?;
    let bit = sim.state.groups.bit(&gw.text).ok_or_else(|| a.error_at(gw, format!("group `{}` does not exist", gw.text), "unknown group"))?;
    let rw = a.word("region ID or NULL")?;
    let region = match rw.text.as_str() {
        "NULL" => None,
        id => Some(sim.state.regions.iter().find(|r| r.id == id).ok_or_else(|| a.error_at(rw, format!("Could not find delete_atoms random region ID {id}"), "unknown region"))?),
    };
    let seed = a.i64_in("random number seed", 1, *crate::engine::random_mars::SEED_RANGE.end())? as i32;
    let at = &sim.state.atoms;
    let eligible: Vec<usize> = order.into_iter().filter(|&i| at.mask[i] & bit != 0 && region.is_none_or(|r| r.matches(at.x[i]))).collect();
    let mut r = crate::engine::random_mars::RanMars::new(seed);
    let mut gone = vec![false; at.nlocal];
    if !exact {
        for &i in &eligible {
            gone[i] = r.uniform() <= fraction;
        }
        return Ok(gone);
    }
    let mut target = if style == 0 { (fraction * eligible.len() as f64) as usize } else { count };
    if target > eligible.len() {
        let msg = format!("Delete_atoms count of {target} exceeds number of eligible atoms {}", eligible.len());
        if strict {
            return Err(a.error_command(msg, "too few eligible atoms"));
        }
        sim.out.print(&format!("WARNING: {msg}"));
        target = eligible.len();
    }
    for (&i, pick) in eligible.iter().zip(r.select_subset(target, eligible.len())) {
        gone[i] = pick;
    }
    Ok(gone)
}

/// The neighbour cutoff of each type pair (row-major over `0..=ntypes`; pair cutoff plus skin,
/// 0 without interaction): LAMMPS finds overlaps in the pair style's neighbour list, so it
/// needs a pair style whose list reaches `cut`, and misses pairs of types whose list is shorter.
fn overlap_cutoffs(sim: &mut Simulation, cmd: &Command, cut: f64) -> DResult<Vec<f64>> {
    let n = sim.state.ntypes;
    if sim.pair.is_none() {
        return Err(Diagnostic::at(cmd.span, "Delete_atoms requires a pair style be defined (overlaps are found in its neighbor list)", "no pair_style yet"));
    }
    // the checks of the atoms' data (set later in many decks) wait for the run, as in LAMMPS
    sim.init_pair(false).map_err(|e| Diagnostic::at(cmd.span, e, "the pair style is not ready"))?;
    let pair = sim.pair.as_ref().expect("a pair style");
    let skin = sim.state.neigh_settings.skin;
    let mut cutneigh = vec![0.0; (n + 1) * (n + 1)];
    for i in 1..=n {
        for j in 1..=n {
            let c = pair.cutoff(i.min(j), i.max(j));
            cutneigh[i * (n + 1) + j] = if c > 0.0 { c + skin } else { 0.0 };
        }
    }
    let typed = || (1..=n).flat_map(|i| (1..=n).map(move |j| (i, j))).map(|(i, j)| cutneigh[i * (n + 1) + j]);
    let (max, min) = (typed().fold(0.0, f64::max), typed().fold(f64::INFINITY, f64::min));
    if cut > max {
        return Err(Diagnostic::at(cmd.span, format!("Delete_atoms cutoff > max neighbor cutoff ({cut} > {max})"), "only pairs in the neighbor list can be found"));
    }
    if cut > min {
        sim.out.print("WARNING: Delete_atoms cutoff > minimum neighbor cutoff");
    }
    Ok(cutneigh)
}

/// Atoms of group1 within `cut` of an atom of group2 (LAMMPS `delete_atoms overlap`), among
/// the pairs its full neighbour list holds: closer than `cutneigh` of their types, and not a
/// special pair its list excludes. LAMMPS visits the atoms in its local order and deletes one
/// at its first such partner that is still there; a partner that is a periodic image (a ghost)
/// does not tell whether its atom was deleted, so a pair across a periodic face where both
/// atoms are in both groups deletes the atom with the smaller ID.
fn overlap_deletions(sim: &mut Simulation, cut: f64, cutneigh: &[f64], g1: u32, g2: u32) -> Result<Vec<bool>, String> {
    let excluded = if sim.state.topo.bonds.is_empty() {
        None
    } else {
        sim.state.rebuild_special()?;
        Some(sim.state.special_bonds.flags(false))
    };
    sim.state.lammps_order.before_rebuild(&sim.state.atoms);
    let a = &sim.state.atoms;
    let d = sim.state.domain.as_ref().unwrap();
    let table = &sim.state.special_table;
    let stride = sim.state.ntypes + 1;
    let n = a.nlocal;
    let mut gone = vec![false; n];
    let cutsq = cut * cut;
    // cell list over the box
    let prd = d.prd();
    let nc: Vec<usize> = (0..3).map(|k| ((prd[k] / cut).floor() as usize).clamp(1, 1024)).collect();
    let cell = |x: &[f64; 3]| -> [usize; 3] {
        let mut c = [0usize; 3];
        for k in 0..3 {
            let f = ((x[k] - d.lo[k]) / prd[k] * nc[k] as f64).floor();
            c[k] = (f.max(0.0) as usize).min(nc[k] - 1);
        }
        c
    };
    let mut cells: std::collections::HashMap<[usize; 3], Vec<usize>> = Default::default();
    for j in 0..n {
        if a.mask[j] & g2 != 0 {
            cells.entry(cell(&a.x[j])).or_default().push(j);
        }
    }
    let tags = a.tag_map();
    let order: Vec<usize> = sim.state.lammps_order.ids().iter().filter_map(|&t| tags.get(t)).collect();
    for i in order {
        if a.mask[i] & g1 == 0 {
            continue;
        }
        let c = cell(&a.x[i]);
        let mut seen = std::collections::HashSet::new();
        'search: for dz in -1i64..=1 {
            for dy in -1i64..=1 {
                'cell: for dx in -1i64..=1 {
                    let mut cc = [0usize; 3];
                    for (k, off) in [dx, dy, dz].into_iter().enumerate() {
                        let v = c[k] as i64 + off;
                        let m = nc[k] as i64;
                        cc[k] = if d.periodic(k) {
                            v.rem_euclid(m) as usize
                        } else if v < 0 || v >= m {
                            continue 'cell;
                        } else {
                            v as usize
                        };
                    }
                    // a small box wraps several offsets onto one cell
                    if !seen.insert(cc) {
                        continue;
                    }
                    let Some(list) = cells.get(&cc) else { continue };
                    for &j in list {
                        if j == i {
                            continue;
                        }
                        let direct = [a.x[i][0] - a.x[j][0], a.x[i][1] - a.x[j][1], a.x[i][2] - a.x[j][2]];
                        let mut del = direct;
                        d.minimum_image(&mut del);
                        let image = del != direct;
                        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                        let listed = cutneigh[a.typ[i] * stride + a.typ[j]];
                        if rsq >= cutsq || rsq >= listed * listed {
                            continue;
                        }
                        if excluded.is_some_and(|f| f[table.level(a.tag[i], a.tag[j]) as usize] == crate::engine::special::SpecialFlag::Exclude) {
                            continue;
                        }
                        if !image {
                            if gone[j] {
                                continue;
                            }
                        } else if a.mask[i] & g2 != 0 && a.mask[j] & g1 != 0 && a.tag[i] > a.tag[j] {
                            continue;
                        }
                        gone[i] = true;
                        break 'search;
                    }
                }
            }
        }
    }
    Ok(gone)
}

pub fn read_data(sim: &mut Simulation, cmd: &Command, sources: &mut SourceMap) -> DResult<()> {
    crate::deck::data::read_data(sim, cmd, sources)
}

pub fn write_data(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    // LAMMPS' write_data runs init first: every type of a bonded style needs its coefficients
    let t = &sim.state.topo;
    let (nb, na, nd) = (t.nbondtypes, t.nangletypes, t.ndihedraltypes);
    let unset = |r: Result<(), String>| r.map_err(|e| Diagnostic::at(cmd.span, e, "write_data needs every coefficient"));
    if let Some(s) = sim.bond_style.as_mut() {
        s.set_types(nb);
        unset(s.check_all_set())?;
    }
    if let Some(s) = sim.angle_style.as_mut() {
        s.set_types(na);
        unset(s.check_all_set())?;
    }
    if let Some(s) = sim.dihedral_style.as_mut() {
        s.set_types(nd);
        unset(s.check_all_set())?;
    }
    // `dmhs check` writes no file
    if sim.state.check_only {
        return Ok(());
    }
    // `noinit`: the atoms as they are, unwrapped, the box not shrink-wrapped (LAMMPS skips its
    // init, pbc and reset_box)
    if !cmd.args.iter().skip(1).any(|w| w.text == "noinit") {
        sim.state.settle_into_box();
    }
    crate::deck::data::write_data(sim, cmd).map_err(|e| Diagnostic::at(cmd.span, e, "write_data failed"))
}
