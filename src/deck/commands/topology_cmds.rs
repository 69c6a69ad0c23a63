//! Topology commands: create_bonds, delete_bonds.

use super::need_box;
use crate::engine::topology::{Angle, Bond, Dihedral};
use crate::sim::Simulation;
use dmhs_parser::args::Args;
use dmhs_parser::{Command, DResult, Diagnostic, SourceMap};

/// `create_bonds many group1 group2 btype rmin rmax`, `single/bond btype a1 a2`,
/// `single/angle atype a1 a2 a3`, `single/dihedral dtype a1 a2 a3 a4`, each with `special yes|no`.
/// As LAMMPS: `many` bonds every pair of atoms, one in each group, whose distance lies in
/// [rmin, rmax] and that LAMMPS' neighbour list holds (the pair's type has a cutoff, no
/// `neigh_modify exclude` rule removes it, the atoms are not bonded already); the special lists
/// are rebuilt (with `special yes`, the default).
pub fn create_bonds(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let syntax = "create_bonds many group1 group2 btype rmin rmax | single/bond btype a1 a2 | single/angle atype a1 a2 a3 | single/dihedral dtype a1 a2 a3 a4 [special yes|no]";
    let mut a = Args::new(cmd, syntax);
    if !sim.state.atoms.features.molecular() {
        return Err(a.error_at(&cmd.name, "create_bonds needs an atom style with bonds (bond, angle, molecular, full, or a hybrid of them)", "atoms have no bonds"));
    }
    let style_w = a.word("style")?;
    let styles = ["many", "single/bond", "single/angle", "single/dihedral", "single/improper"];
    let Some(style) = styles.iter().position(|s| *s == style_w.text) else {
        return Err(a.unknown_keyword(style_w, &styles));
    };
    if style == 4 {
        return Err(a.error_at(style_w, "create_bonds single/improper is not supported: dmhs has no improper styles", "not supported"));
    }
    let topo = &sim.state.topo;
    let (ntypes_of, what) = match style {
        0 | 1 => (topo.nbondtypes, "bond type"),
        2 => (topo.nangletypes, "angle type"),
        _ => (topo.ndihedraltypes, "dihedral type"),
    };
    let mut groups = [0u32; 2];
    let mut range = [0.0f64; 2];
    if style == 0 {
        for g in &mut groups {
            let w = a.word("group ID")?;
            *g = sim.state.groups.bit(&w.text).ok_or_else(|| a.error_at(w, format!("group `{}` does not exist", w.text), "unknown group"))?;
        }
    }
    if ntypes_of == 0 {
        let w = a.peek().unwrap_or(style_w);
        return Err(a.error_at(w, format!("no {what}s are defined (create_box ... {}/types N, or a data file header)", what.split(' ').next().unwrap()), format!("no {what}s")));
    }
    let typ = a.i64_in(what, 1, ntypes_of as i64)? as usize;
    let mut ids = vec![];
    if style == 0 {
        range = [a.f64("rmin")?, a.f64("rmax")?];
        if range[0] > range[1] {
            let w = a.last().unwrap();
            return Err(a.error_at(w, format!("rmin {} is larger than rmax {}", range[0], range[1]), "rmax must be >= rmin"));
        }
    } else {
        let n = style + 1;
        let map = sim.state.atoms.tag_map();
        for _ in 0..n {
            let id = a.i64("atom ID")?;
            let w = a.last().unwrap();
            if map.get(id).is_none_or(|i| i >= sim.state.atoms.nlocal) {
                return Err(a.error_at(w, format!("atom {id} does not exist"), "no such atom"));
            }
            if ids.contains(&id) {
                return Err(a.error_at(w, format!("atom {id} appears twice"), "the atoms must differ"));
            }
            ids.push(id);
        }
    }
    let mut special = true;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "special" => special = a.yes_no("special")?,
            _ => return Err(a.unknown_keyword(w, &["special"])),
        }
    }
    if style == 0 && !special {
        return Err(a.error_at(a.last().unwrap(), "create_bonds many cannot use `special no` (LAMMPS refuses it too: the next many would bond bonded pairs again)", "needs special yes"));
    }
    match style {
        0 => {
            let added = many(sim, cmd, groups, typ, range)?;
            let total = sim.state.topo.bonds.len();
            sim.out.print(&format!("Added {added} bonds, new total = {total}"));
        }
        1 => sim.state.topo.bonds.push(Bond::new(typ, [ids[0], ids[1]])),
        2 => sim.state.topo.angles.push(Angle::new(typ, [ids[0], ids[1], ids[2]])),
        _ => sim.state.topo.dihedrals.push(Dihedral::new(typ, [ids[0], ids[1], ids[2], ids[3]])),
    }
    if special {
        sim.state.rebuild_special().map_err(|e| Diagnostic::at(cmd.span, e, "special lists"))?;
    } else {
        // LAMMPS leaves the special lists as they were until the next rebuild asks for them
        sim.state.special_dirty = true;
    }
    sim.state.lists_valid = false;
    Ok(())
}

/// The bonds of `create_bonds many`; returns how many it added.
fn many(sim: &mut Simulation, cmd: &Command, groups: [u32; 2], typ: usize, range: [f64; 2]) -> DResult<usize> {
    // LAMMPS initialises the whole system and builds a neighbour list for the command
    sim.init_run().map_err(|e| Diagnostic::at(e.at.unwrap_or(cmd.span), e.message, "while initialising for create_bonds"))?;
    let Some(pair) = sim.pair.as_deref() else {
        return Err(Diagnostic::at(cmd.span, "create_bonds many needs a pair style (its neighbour list finds the pairs)", "no pair style"));
    };
    if sim.state.special_bonds.lj[1] != 0.0 || sim.state.special_bonds.coul[1] != 0.0 {
        return Err(Diagnostic::at(cmd.span, "create_bonds many needs special_bonds 1-2 weights of 0.0 (so that bonded pairs are not in the neighbour list)", "special_bonds 1-2 weight is not 0"));
    }
    let state = &sim.state;
    let ntypes = state.ntypes;
    let skin = state.neigh_settings.skin;
    // the list cutoff of each type pair (0: the pair is not in LAMMPS' list)
    let stride = ntypes + 1;
    let mut cutneigh = vec![0.0; stride * stride];
    let mut cutmax: f64 = 0.0;
    for i in 1..=ntypes {
        for j in 1..=ntypes {
            let c = pair.cutoff(i, j);
            if c > 0.0 {
                cutneigh[i * stride + j] = c + skin;
                cutmax = cutmax.max(c + skin);
            }
        }
    }
    if range[1] > cutmax {
        return Err(Diagnostic::at(cmd.span, format!("create_bonds max distance {} is larger than the neighbour cutoff {} (largest pair cutoff + skin)", range[1], cutmax), "rmax beyond the neighbour list"));
    }
    let domain = state.domain.as_ref().unwrap();
    let at = &state.atoms;
    let n = at.nlocal;
    let bonded: std::collections::HashSet<(i64, i64)> = state.topo.bonds.iter().map(|b| (b.atoms[0].min(b.atoms[1]), b.atoms[0].max(b.atoms[1]))).collect();
    let (rminsq, rmaxsq) = (range[0] * range[0], range[1] * range[1]);
    // candidates: atoms in either group, binned at rmax (a bin of at least 1e-12 of the box)
    let cand: Vec<usize> = (0..n).filter(|&i| at.mask[i] & (groups[0] | groups[1]) != 0).collect();
    // (a triclinic box is binned in box fractions, by its widths across each dimension)
    let prd = if domain.triclinic() { domain.lamda_reach(1.0).map(|r| 1.0 / r) } else { domain.prd() };
    let dim = domain.dimension;
    let nbin: Vec<usize> = (0..3).map(|d| if d < dim { ((prd[d] / range[1].max(1e-12 * prd[d])).floor() as usize).clamp(1, 1 << 10) } else { 1 }).collect();
    let bin_of = |x: [f64; 3]| -> [usize; 3] {
        let mut b = [0usize; 3];
        let (x, lo, len) = if domain.triclinic() { (domain.x2lamda(x), [0.0; 3], [1.0; 3]) } else { (x, domain.lo, prd) };
        for d in 0..dim {
            let f = ((x[d] - lo[d]) / len[d] * nbin[d] as f64).floor();
            b[d] = (f.max(0.0) as usize).min(nbin[d] - 1);
        }
        b
    };
    let mut bins: std::collections::HashMap<[usize; 3], Vec<usize>> = std::collections::HashMap::new();
    for &i in &cand {
        bins.entry(bin_of(at.x[i])).or_default().push(i);
    }
    let mut new_bonds: Vec<(i64, i64)> = vec![];
    for &i in &cand {
        let b = bin_of(at.x[i]);
        let mut seen_bins: Vec<[usize; 3]> = vec![];
        let offs: Vec<i64> = vec![-1, 0, 1];
        for dx in &offs {
            for dy in &offs {
                for dz in if dim == 3 { offs.as_slice() } else { &[0i64][..] } {
                    let mut nb = [0usize; 3];
                    let mut ok = true;
                    for (d, o) in [*dx, *dy, *dz].iter().enumerate() {
                        let m = nbin[d] as i64;
                        let k = b[d] as i64 + o;
                        nb[d] = if (0..m).contains(&k) {
                            k as usize
                        } else if domain.periodic(d) {
                            k.rem_euclid(m) as usize
                        } else {
                            ok = false;
                            0
                        };
                    }
                    if !ok || seen_bins.contains(&nb) {
                        continue;
                    }
                    seen_bins.push(nb);
                    for &j in bins.get(&nb).map(|v| v.as_slice()).unwrap_or(&[]) {
                        let (ti, tj) = (at.tag[i], at.tag[j]);
                        if ti >= tj {
                            continue;
                        }
                        let ok_groups = (at.mask[i] & groups[0] != 0 && at.mask[j] & groups[1] != 0) || (at.mask[i] & groups[1] != 0 && at.mask[j] & groups[0] != 0);
                        if !ok_groups || bonded.contains(&(ti, tj)) {
                            continue;
                        }
                        let cut = cutneigh[at.typ[i] * stride + at.typ[j]];
                        if cut == 0.0 || state.neigh_settings.exclusions.excluded(at, i, j) {
                            continue;
                        }
                        let mut del = [at.x[i][0] - at.x[j][0], at.x[i][1] - at.x[j][1], at.x[i][2] - at.x[j][2]];
                        domain.minimum_image(&mut del);
                        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                        if rsq < rminsq || rsq > rmaxsq || rsq > cut * cut {
                            continue;
                        }
                        new_bonds.push((ti, tj));
                    }
                }
            }
        }
    }
    new_bonds.sort_unstable();
    new_bonds.dedup();
    let added = new_bonds.len();
    // the bonds already there keep their places; the new ones follow them in each atom's list
    sim.state.topo.assign_bond_slots();
    let slots = many_slots(&sim.state, &new_bonds, cutmax);
    sim.state.topo.bonds.extend(new_bonds.into_iter().zip(slots).map(|((i, j), slots)| Bond { slots, ..Bond::new(typ, [i, j]) }));
    Ok(added)
}

/// Each new bond's place in its two atoms' bond lists, as LAMMPS' create_bonds many appends
/// them: every owned atom walks its full neighbour list (built for the command, cutoff
/// `cutneighmax`) and appends a bond per partner in range. A full binned list runs over the
/// stencil bins in increasing bin index (z, then y, then x of LAMMPS' neighbour bins) and
/// inside a bin over increasing local index (owned atoms in LAMMPS' local order, then ghosts).
/// Ghosts of different atoms in one bin are ordered by their owner's local index here
/// (LAMMPS orders them by Comm::borders' swaps; only periodic decks can see the difference).
fn many_slots(state: &crate::engine::state::State, bonds: &[(i64, i64)], cutneighmax: f64) -> Vec<[u32; 2]> {
    let at = &state.atoms;
    let domain = state.domain.as_ref().unwrap();
    let map = at.tag_map();
    // LAMMPS' local order now: create_bonds does not sort, new atoms come last
    let mut order = state.lammps_order.clone();
    order.before_rebuild(at);
    let lpos: std::collections::HashMap<i64, usize> = order.ids().iter().enumerate().map(|(k, &t)| (t, k)).collect();
    // Neighbor's bins (NBinStandard::setup_bins, one process: the box is the bin box)
    let binsize = if state.neigh_settings.binsize > 0.0 { state.neigh_settings.binsize } else { 0.5 * cutneighmax };
    let mut nbin = [1i64; 3];
    let mut inv = [0.0; 3];
    for d in 0..3 {
        let len = domain.hi[d] - domain.lo[d];
        let n = if d == 2 && domain.dimension == 2 { 1 } else { (len * (1.0 / binsize)) as i64 };
        nbin[d] = n.max(1);
        inv[d] = 1.0 / (len / nbin[d] as f64);
    }
    // NBin::coord2bin, per axis (C's truncating casts)
    let coord = |x: f64, d: usize| -> i64 {
        let (lo, hi) = (domain.lo[d], domain.hi[d]);
        if x >= hi {
            ((x - hi) * inv[d]) as i64 + nbin[d]
        } else if x >= lo {
            (((x - lo) * inv[d]) as i64).min(nbin[d] - 1)
        } else {
            ((x - lo) * inv[d]) as i64 - 1
        }
    };
    let prd = domain.prd();
    // per atom: (list key of the partner, bond, side)
    type Key = ([i64; 3], bool, usize);
    let mut lists: std::collections::HashMap<i64, Vec<(Key, usize, usize)>> = std::collections::HashMap::new();
    for (k, &(ti, tj)) in bonds.iter().enumerate() {
        for (side, (a, b)) in [(ti, tj), (tj, ti)].into_iter().enumerate() {
            let (Some(i), Some(j)) = (map.get(a), map.get(b)) else { continue };
            // the partner as atom a sees it: itself, or the ghost image closest to a
            let raw = [at.x[i][0] - at.x[j][0], at.x[i][1] - at.x[j][1], at.x[i][2] - at.x[j][2]];
            let mut del = raw;
            domain.minimum_image(&mut del);
            let mut xj = at.x[j];
            let mut ghost = false;
            for d in 0..3 {
                if del[d] != raw[d] {
                    ghost = true;
                    xj[d] += if raw[d] > del[d] { prd[d] } else { -prd[d] };
                }
            }
            let key = ([coord(xj[2], 2), coord(xj[1], 1), coord(xj[0], 0)], ghost, lpos.get(&b).copied().unwrap_or(usize::MAX));
            lists.entry(a).or_default().push((key, k, side));
        }
    }
    // the places the atoms' existing bonds hold
    let mut next: std::collections::HashMap<i64, u32> = std::collections::HashMap::new();
    for b in &state.topo.bonds {
        for k in 0..2 {
            let n = next.entry(b.atoms[k]).or_insert(0);
            *n = (*n).max(b.slots[k].wrapping_add(1));
        }
    }
    let mut slots = vec![[u32::MAX; 2]; bonds.len()];
    for (tag, mut list) in lists {
        list.sort_unstable_by_key(|e| e.0);
        let mut n = next.get(&tag).copied().unwrap_or(0);
        for (_, k, side) in list {
            slots[k][side] = n;
            n += 1;
        }
    }
    slots
}

/// What `delete_bonds` selects besides the group.
#[derive(Clone, Copy, PartialEq)]
enum Select {
    /// Every interaction (`multi`), or none (`stats`).
    All,
    None,
    /// An atom of the interaction has a type in the range.
    AtomType(usize, usize),
    Bond(usize, usize),
    Angle(usize, usize),
    Dihedral(usize, usize),
}

/// A type range as `delete_bonds` takes it: `n`, `*`, `*n`, `n*`, `m*n`, within `lo..=hi`.
fn type_range(a: &mut Args, what: &str, lo: usize, hi: usize) -> DResult<(usize, usize)> {
    let w = a.word(what)?;
    let bad = || a.error_at(w, format!("expected a {what} or a range of them (n, *, *n, n*, m*n) within {lo}..={hi}, found `{}`", w.text), "bad type range");
    let num = |s: &str, default: usize| if s.is_empty() { Some(default) } else { s.parse::<usize>().ok() };
    let (l, h) = match w.text.split_once('*') {
        None => {
            let n = num(&w.text, usize::MAX).filter(|_| !w.text.is_empty()).ok_or_else(bad)?;
            (n, n)
        }
        Some((l, h)) => (num(l, lo).ok_or_else(bad)?, num(h, hi).ok_or_else(bad)?),
    };
    if l < lo || h > hi || l > h {
        return Err(bad());
    }
    Ok((l, h))
}

/// `delete_bonds group-ID multi|atom T|bond T|angle T|dihedral T|improper T|stats [any] [undo]
/// [remove] [special]`, as LAMMPS: the interactions whose atoms are all in the group (any of
/// them with `any`) and that the style selects are turned off (on with `undo`); `remove` then
/// drops every turned-off interaction of the group (all kinds); `special` rebuilds the 1-2,
/// 1-3, 1-4 lists, which otherwise stay as they were (turned-off and removed interactions keep
/// their special weights). The counts LAMMPS prints follow.
pub fn delete_bonds(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let syntax = "delete_bonds group-ID multi|atom T|bond T|angle T|dihedral T|improper T|stats [any] [undo] [remove] [special]";
    let mut a = Args::new(cmd, syntax);
    if !sim.state.atoms.features.molecular() {
        return Err(a.error_at(&cmd.name, "delete_bonds needs an atom style with bonds (bond, angle, molecular, full, or a hybrid of them)", "atoms have no bonds"));
    }
    let gw = a.word("group ID")?;
    let bit = sim.state.groups.bit(&gw.text).ok_or_else(|| a.error_at(gw, format!("group `{}` does not exist", gw.text), "unknown group"))?;
    let t = &sim.state.topo;
    let select = match a.choice("style", &["multi", "atom", "bond", "angle", "dihedral", "improper", "stats"])? {
        0 => Select::All,
        1 => {
            let (l, h) = type_range(&mut a, "atom type", 1, sim.state.ntypes)?;
            Select::AtomType(l, h)
        }
        2 => {
            // type 0: bonds broken by a bond-breaking style (dmhs removes those when they break)
            let (l, h) = type_range(&mut a, "bond type", 0, t.nbondtypes)?;
            Select::Bond(l, h)
        }
        3 => {
            let (l, h) = type_range(&mut a, "angle type", 0, t.nangletypes)?;
            Select::Angle(l, h)
        }
        4 => {
            let (l, h) = type_range(&mut a, "dihedral type", 0, t.ndihedraltypes)?;
            Select::Dihedral(l, h)
        }
        5 => {
            // dmhs keeps no impropers: nothing to select
            type_range(&mut a, "improper type", 0, t.nimpropertypes)?;
            Select::None
        }
        _ => Select::None,
    };
    let (mut any, mut undo, mut remove, mut special) = (false, false, false, false);
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "any" => any = true,
            "undo" => undo = true,
            "remove" => remove = true,
            "special" => special = true,
            _ => return Err(a.unknown_keyword(w, &["any", "undo", "remove", "special"])),
        }
    }
    let st = &mut sim.state;
    if remove && !special && !st.special_frozen {
        // the lists LAMMPS holds now are those of the current topology; they stay after removal
        st.rebuild_special().map_err(|e| Diagnostic::at(cmd.span, e, "special lists"))?;
    }
    let map = st.atoms.tag_map();
    let (mask, typ) = (&st.atoms.mask, &st.atoms.typ);
    let mut missing = None;
    let mut atom_of = |id: i64| -> Option<usize> {
        let i = map.get(id);
        if i.is_none() {
            missing = Some(id);
        }
        i
    };
    // the atoms' indices if the interaction is in the group; None otherwise
    let mut in_group = |ids: &[i64]| -> Option<Vec<usize>> {
        let idx: Option<Vec<usize>> = ids.iter().map(|&id| atom_of(id)).collect();
        let idx = idx?;
        let inside = |i: &usize| mask[*i] & bit != 0;
        (if any { idx.iter().any(inside) } else { idx.iter().all(inside) }).then_some(idx)
    };
    let of_atom_type = |idx: &[usize]| matches!(select, Select::AtomType(l, h) if idx.iter().any(|&i| (l..=h).contains(&typ[i])));
    let t = &mut st.topo;
    for b in t.bonds.iter_mut() {
        if let Some(idx) = in_group(&b.atoms) {
            if select == Select::All || of_atom_type(&idx) || matches!(select, Select::Bond(l, h) if (l..=h).contains(&b.typ)) {
                b.off = !undo;
            }
        }
    }
    for g in t.angles.iter_mut() {
        if let Some(idx) = in_group(&g.atoms) {
            if select == Select::All || of_atom_type(&idx) || matches!(select, Select::Angle(l, h) if (l..=h).contains(&g.typ)) {
                g.off = !undo;
            }
        }
    }
    for d in t.dihedrals.iter_mut() {
        if let Some(idx) = in_group(&d.atoms) {
            if select == Select::All || of_atom_type(&idx) || matches!(select, Select::Dihedral(l, h) if (l..=h).contains(&d.typ)) {
                d.off = !undo;
            }
        }
    }
    if remove {
        let nbefore = t.bonds.len() + t.angles.len() + t.dihedrals.len();
        t.bonds.retain(|b| !(b.off && in_group(&b.atoms).is_some()));
        t.angles.retain(|g| !(g.off && in_group(&g.atoms).is_some()));
        t.dihedrals.retain(|d| !(d.off && in_group(&d.atoms).is_some()));
        // the special lists stay as they were (LAMMPS), unless `special` rebuilds them below
        st.special_frozen |= nbefore != t.bonds.len() + t.angles.len() + t.dihedrals.len();
    }
    if let Some(id) = missing {
        return Err(Diagnostic::at(cmd.span, format!("an interaction names atom {id}, which does not exist"), "bond atom missing"));
    }
    sim.out.print("Deleting bonds ...");
    let t = &sim.state.topo;
    let count = |offs: &mut dyn Iterator<Item = bool>| offs.fold((0, 0), |(on, off), o| if o { (on, off + 1) } else { (on + 1, off) });
    let ft = sim.state.atoms.features;
    for (allowed, (on, off), what) in [
        (ft.bonds, count(&mut t.bonds.iter().map(|b| b.off)), "bonds"),
        (ft.angles, count(&mut t.angles.iter().map(|g| g.off)), "angles"),
        (ft.dihedrals, count(&mut t.dihedrals.iter().map(|d| d.off)), "dihedrals"),
        (ft.dihedrals, (0, 0), "impropers"),
    ] {
        if allowed {
            sim.out.print(&format!("  {} total {what}, {on} turned on, {off} turned off", on + off));
        }
    }
    if special {
        sim.state.rebuild_special().map_err(|e| Diagnostic::at(cmd.span, e, "special lists"))?;
    }
    sim.state.lists_valid = false;
    Ok(())
}
