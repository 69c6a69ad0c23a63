//! `fix ID group bond/create Nevery itype jtype Rmin bondtype [iparam maxbond newtype]
//! [jparam maxbond newtype] [prob fraction seed] [atype angletype]` (LAMMPS MC package).
//!
//! Every Nevery steps (post_integrate), each group atom of type itype (jtype) picks the closest
//! group atom of type jtype (itype) nearer than Rmin that is not already a 1-2 neighbour and
//! where neither atom has reached its maximum number of bonds of `bondtype` (maxbond 0: no
//! limit); a bond of `bondtype` is created when both atoms picked each other (and, with `prob`,
//! a random number is below the fraction). An atom whose count of `bondtype` bonds reaches
//! maxbond changes to newtype. With `atype`, every angle centred on an atom of a new bond whose
//! two bonds include a new bond is created with that angle type. Special and neighbour lists are
//! rebuilt on the same step. Counts start from the bonds of `bondtype` at the first run; bonds
//! that other fixes break are not subtracted (as in LAMMPS). Candidate pairs come from the pair
//! neighbour list, so Rmin must not exceed the pair cutoff of itype, jtype (LAMMPS checks the
//! same). `f_ID[1]`: bonds created at the last check, `f_ID[2]`: running total.
//!
//! With `prob` below 1 the random numbers are dmhs' own (one per atom with a partner, in
//! atom-ID order): reproducible, not bit-identical to LAMMPS.
//!
//! On several ranks, a pair with another rank's atom is checked by both owners (each for its
//! own atom's bond count) and every rank reads every rank's candidates, so all make the same
//! choices; the new bonds go into every rank's topology in ID order.

use super::bond_break::{check_special, mutual_choices, mutual_partners};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::neighbor::NEIGH_MASK;
use crate::engine::random_park::RanPark;
use crate::engine::state::{RunError, State};
use crate::engine::topology::{Angle, Bond};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};
use std::collections::{HashMap, HashSet};

pub const SYNTAX: &str = "fix ID group bond/create Nevery itype jtype Rmin bondtype [iparam maxbond newtype] [jparam maxbond newtype] [prob fraction seed] [atype angletype]";

pub struct FixBondCreate {
    id: String,
    groupbit: u32,
    nevery: i64,
    itype: usize,
    jtype: usize,
    cutsq: f64,
    btype: usize,
    imaxbond: usize,
    inewtype: usize,
    jmaxbond: usize,
    jnewtype: usize,
    fraction: f64,
    random: RanPark,
    atype: usize,
    /// Per-atom count of `btype` bonds (an extra per-atom array, so it follows sorting).
    counted: bool,
    createcount: usize,
    createcounttotal: usize,
}

impl FixBondCreate {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if !state.atoms.features.bonds {
            return Err(Diagnostic::at(style.span, "fix bond/create needs an atom style with bonds", "atom style has no bonds"));
        }
        let nt = state.ntypes as i64;
        let nevery = a.i64_in("Nevery", 1, i64::MAX)?;
        let itype = a.i64_in("itype", 1, nt)? as usize;
        let jtype = a.i64_in("jtype", 1, nt)? as usize;
        let rmin = a.non_negative_f64("Rmin")?;
        let btype = a.i64_in("bond type", 1, state.topo.nbondtypes.max(1) as i64)? as usize;
        if btype > state.topo.nbondtypes {
            return Err(a.error_at(a.last().unwrap(), "Invalid bond type in fix bond/create command", "no bond types defined"));
        }
        let mut f = FixBondCreate {
            id,
            groupbit,
            nevery,
            itype,
            jtype,
            cutsq: rmin * rmin,
            btype,
            imaxbond: 0,
            inewtype: itype,
            jmaxbond: 0,
            jnewtype: jtype,
            fraction: 1.0,
            random: RanPark::new(12345),
            atype: 0,
            counted: false,
            createcount: 0,
            createcounttotal: 0,
        };
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "iparam" => {
                    f.imaxbond = a.i64_in("iparam maxbond", 0, i64::MAX)? as usize;
                    f.inewtype = a.i64_in("iparam newtype", 1, nt)? as usize;
                }
                "jparam" => {
                    f.jmaxbond = a.i64_in("jparam maxbond", 0, i64::MAX)? as usize;
                    f.jnewtype = a.i64_in("jparam newtype", 1, nt)? as usize;
                }
                "prob" => {
                    f.fraction = a.f64_where("prob fraction", "in [0, 1]", |x| (0.0..=1.0).contains(&x))?;
                    f.random = RanPark::new(a.i64_in("prob seed", 1, i32::MAX as i64)? as i32);
                }
                "atype" => f.atype = a.i64_in("atype", 0, i64::MAX)? as usize,
                _ => return Err(a.unknown_keyword(w, &["iparam", "jparam", "prob", "atype"])),
            }
        }
        if itype == jtype && (f.imaxbond != f.jmaxbond || f.inewtype != f.jnewtype) {
            return Err(Diagnostic::at(cmd.span, "Inconsistent iparam/jparam values in fix bond/create command", "itype = jtype needs equal iparam and jparam"));
        }
        Ok(f)
    }

    fn count_name(&self) -> String {
        format!("bond/create:{}", self.id)
    }

    /// Whether (ti, ci) may bond to (tj, cj) by types and bond counts.
    fn possible(&self, ti: usize, ci: usize, tj: usize, cj: usize) -> bool {
        let ok = |max: usize, c: usize| max == 0 || c < max;
        if ti == self.itype && tj == self.jtype {
            ok(self.imaxbond, ci) && ok(self.jmaxbond, cj)
        } else if ti == self.jtype && tj == self.itype {
            ok(self.jmaxbond, ci) && ok(self.imaxbond, cj)
        } else {
            false
        }
    }

    /// The bonds to create (atom IDs), each atom's closest eligible partner where the two
    /// chose each other, in the local order of the lower-ID atom (one rank holding every atom).
    fn choose(&mut self, state: &State) -> Vec<(i64, i64)> {
        let periods = state.domain.as_ref().unwrap().periods();
        let a = &state.atoms;
        let n = a.nlocal;
        let k = a.find_extra(&self.count_name()).expect("bond count array");
        let count = |i: usize| a.extra[k].data[i] as usize;
        let owner = |j: usize| if j < n { j } else { a.ghost_owner[j - n] as usize };
        let bonded = bonded_pairs(state);
        let mut partner = vec![0i64; n];
        let mut distsq = vec![f64::INFINITY; n];
        for chunk in &state.neighbor.list.chunks {
            for i in chunk.start..chunk.end {
                if a.mask[i] & self.groupbit == 0 {
                    continue;
                }
                let xi = a.x[i];
                for &jraw in chunk.neighbors(i) {
                    let j = (jraw & NEIGH_MASK) as usize;
                    let jo = owner(j);
                    if jo == i {
                        continue;
                    }
                    if a.mask[jo] & self.groupbit == 0 || !self.possible(a.typ[i], count(i), a.typ[jo], count(jo)) {
                        continue;
                    }
                    let (ti, tj) = (a.tag[i], a.tag[jo]);
                    if bonded.contains(&(ti.min(tj), ti.max(tj))) {
                        continue;
                    }
                    // current position of j (ghosts are refreshed only after this hook)
                    let xj = if j < n { a.x[j] } else { periods.shifted(a.x[jo], a.ghost_shift[j - n]) };
                    let rsq = dist_sq(xi, xj);
                    if rsq >= self.cutsq {
                        continue;
                    }
                    if rsq < distsq[i] {
                        partner[i] = tj;
                        distsq[i] = rsq;
                    }
                    if rsq < distsq[jo] {
                        partner[jo] = ti;
                        distsq[jo] = rsq;
                    }
                }
            }
        }
        mutual_partners(a, &partner, self.fraction, &mut self.random).into_iter().map(|(i, j)| (a.tag[i], a.tag[j])).collect()
    }

    /// [`Self::choose`] on the ranks of a distributed run, in ID order. Each rank lists its
    /// candidate pairs (ID, ID, r^2) with what it can check: a pair of two atoms it owns
    /// whole, a pair with another rank's ghost for its own atom only (types, group, its own
    /// bond count); that rank lists the same pair for the other atom, and the pair is a
    /// candidate when both did. Every rank reads every list in rank order and makes the same
    /// choices (the first of equally close partners in that order).
    fn choose_on_ranks(&mut self, state: &mut State) -> Vec<(i64, i64)> {
        // the ghosts at this step's positions (LAMMPS forwards them here)
        state.forward_positions_ranks();
        let a = &state.atoms;
        let n = a.nlocal;
        let k = a.find_extra(&self.count_name()).expect("bond count array");
        let count = |i: usize| a.extra[k].data[i] as usize;
        let map = a.tag_map();
        let bonded = bonded_pairs(state);
        // (ID, ID, r^2, 1 whole / 0 one side)
        let mut mine: Vec<f64> = vec![];
        for chunk in &state.neighbor.list.chunks {
            for i in chunk.start..chunk.end {
                if a.mask[i] & self.groupbit == 0 {
                    continue;
                }
                for &jraw in chunk.neighbors(i) {
                    let j = (jraw & NEIGH_MASK) as usize;
                    let (ti, tj) = (a.tag[i], a.tag[j]);
                    if ti == tj || a.mask[j] & self.groupbit == 0 || bonded.contains(&(ti.min(tj), ti.max(tj))) {
                        continue;
                    }
                    // a ghost may be a periodic image of an atom this rank owns
                    let jo = if j < n { Some(j) } else { map.get(tj) };
                    let whole = match jo {
                        Some(jo) => self.possible(a.typ[i], count(i), a.typ[jo], count(jo)),
                        // the other atom's count is checked by its owner (0 passes any limit)
                        None => self.possible(a.typ[i], count(i), a.typ[j], 0),
                    };
                    if !whole {
                        continue;
                    }
                    let rsq = dist_sq(a.x[i], a.x[j]);
                    if rsq < self.cutsq {
                        mine.extend([ti as f64, tj as f64, rsq, jo.is_some() as u8 as f64]);
                    }
                }
            }
        }
        let all = state.allgather_ranks(mine);
        // (the atom checked, the other) of the one-sided pairs
        let checked: HashSet<(i64, i64)> = all.chunks_exact(4).filter(|c| c[3] == 0.0).map(|c| (c[0] as i64, c[1] as i64)).collect();
        let mut choice: std::collections::BTreeMap<i64, (i64, f64)> = Default::default();
        for c in all.chunks_exact(4) {
            let (p, q, rsq) = (c[0] as i64, c[1] as i64, c[2]);
            if c[3] == 0.0 && !checked.contains(&(q, p)) {
                continue;
            }
            for (t, other) in [(p, q), (q, p)] {
                let e = choice.entry(t).or_insert((0, f64::INFINITY));
                if rsq < e.1 {
                    *e = (other, rsq);
                }
            }
        }
        mutual_choices(&choice, self.fraction, &mut self.random)
    }

    /// Create the bonds `created` (atom IDs): count them on the atoms this rank owns, change
    /// the types of atoms that reach their limit, add the angles of `atype`.
    fn create(&mut self, state: &mut State, ctx: &FixCtx, created: &[(i64, i64)]) {
        self.createcount = created.len();
        self.createcounttotal += created.len();
        if created.is_empty() {
            return;
        }
        let k = state.atoms.find_extra(&self.count_name()).expect("bond count array");
        let map = state.atoms.tag_map();
        for &(ti, tj) in created {
            state.topo.bonds.push(Bond::new(self.btype, [ti, tj]));
            for m in [ti, tj].into_iter().filter_map(|t| map.get(t)) {
                let c = &mut state.atoms.extra[k].data[m];
                *c += 1.0;
                let c = *c as usize;
                let t = &mut state.atoms.typ[m];
                // LAMMPS: an itype atom converts at imaxbond, any other at jmaxbond
                if *t == self.itype {
                    if c == self.imaxbond {
                        *t = self.inewtype;
                    }
                } else if c == self.jmaxbond {
                    *t = self.jnewtype;
                }
            }
        }
        if self.atype > 0 && ctx.angle_style.is_some() {
            // angles centred on an atom of a new bond, made of two of its bonds of which at
            // least one is new (each once, whatever the order of the outer atoms)
            let new_bonds: HashSet<(i64, i64)> = created.iter().copied().collect();
            let mut nbrs: HashMap<i64, Vec<i64>> = HashMap::new();
            for b in &state.topo.bonds {
                nbrs.entry(b.atoms[0]).or_default().push(b.atoms[1]);
                nbrs.entry(b.atoms[1]).or_default().push(b.atoms[0]);
            }
            let is_new = |p: i64, q: i64| new_bonds.contains(&(p, q)) || new_bonds.contains(&(q, p));
            let mut centres: Vec<i64> = created.iter().flat_map(|&(p, q)| [p, q]).collect();
            centres.sort_unstable();
            centres.dedup();
            for c in centres {
                let list = nbrs.get(&c).cloned().unwrap_or_default();
                for x in 0..list.len() {
                    for y in x + 1..list.len() {
                        if is_new(list[x], c) || is_new(c, list[y]) {
                            state.topo.angles.push(Angle::new(self.atype, [list[x], c, list[y]]));
                        }
                    }
                }
            }
        }
        state.topology_changed();
    }
}

/// Every bonded pair of the topology, (lower ID, higher ID).
fn bonded_pairs(state: &State) -> HashSet<(i64, i64)> {
    state.topo.bonds.iter().map(|b| (b.atoms[0].min(b.atoms[1]), b.atoms[0].max(b.atoms[1]))).collect()
}

fn dist_sq(a: [f64; 3], b: [f64; 3]) -> f64 {
    let del = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    del[0] * del[0] + del[1] * del[1] + del[2] * del[2]
}

impl Fix for FixBondCreate {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "bond/create"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_integrate: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        check_special(state, "bond/create")?;
        let cut = ctx.pair.map(|p| p.cutoff(self.itype, self.jtype)).unwrap_or(0.0);
        if self.cutsq > cut * cut {
            return Err("Fix bond/create cutoff is longer than pairwise cutoff".into());
        }
        if self.atype > 0 && ctx.angle_style.is_some() && self.atype > state.topo.nangletypes {
            return Err("Fix bond/create angle type is invalid".into());
        }
        Ok(())
    }
    fn setup(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if self.counted {
            return Ok(());
        }
        // first run: count the bonds of btype per atom (LAMMPS FixBondCreate::setup)
        self.counted = true;
        let name = self.count_name();
        let a = &mut state.atoms;
        let n = a.nlocal;
        // an owned-atoms-only extra array (ghosts never read it); pushed directly since ghosts
        // exist during setup
        let k = a.find_extra(&name).unwrap_or_else(|| {
            a.extra.push(crate::engine::atoms::ExtraArray { name: name.clone(), stride: 1, data: vec![], ghosts: false });
            a.extra.len() - 1
        });
        let map = a.tag_map();
        let mut count = vec![0.0; n];
        for b in &state.topo.bonds {
            if b.typ == self.btype {
                for t in b.atoms {
                    if let Some(i) = map.get(t) {
                        count[i] += 1.0;
                    }
                }
            }
        }
        a.extra[k].data = count;
        Ok(())
    }
    fn post_integrate(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        let created = if state.distributed.is_some() { self.choose_on_ranks(state) } else { self.choose(state) };
        self.create(state, ctx, &created);
        Ok(())
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        match i {
            1 => Some(self.createcount as f64),
            2 => Some(self.createcounttotal as f64),
            _ => None,
        }
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.remove_extra(&self.count_name());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eligibility_follows_types_and_bond_counts() {
        let mut f = FixBondCreate {
            id: "c".into(),
            groupbit: 1,
            nevery: 1,
            itype: 1,
            jtype: 2,
            cutsq: 1.0,
            btype: 1,
            imaxbond: 2,
            inewtype: 3,
            jmaxbond: 1,
            jnewtype: 4,
            fraction: 1.0,
            random: RanPark::new(1),
            atype: 0,
            counted: false,
            createcount: 0,
            createcounttotal: 0,
        };
        assert!(f.possible(1, 1, 2, 0));
        assert!(f.possible(2, 0, 1, 1), "either order of the pair");
        assert!(!f.possible(1, 2, 2, 0), "itype atom at maxbond");
        assert!(!f.possible(1, 0, 2, 1), "jtype atom at maxbond");
        assert!(!f.possible(1, 0, 1, 0), "wrong types");
        f.imaxbond = 0;
        assert!(f.possible(1, 100, 2, 0), "maxbond 0: no limit");
    }
}
