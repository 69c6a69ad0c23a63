//! `fix ID group bond/break Nevery bondtype Rmax [prob fraction seed]` (LAMMPS MC package) and
//! the dmhs extension `fix ID group dmhs/bond/break Nevery bondtype Rmax [temp Tmax] [prob ...]`.
//!
//! Every Nevery steps, after the first half of the velocity update (post_integrate):
//! * each atom of the group picks, among its bonds of `bondtype` to other group atoms that are
//!   longer than Rmax, the longest one (the first of equal lengths in bond order);
//! * a bond breaks when both its atoms picked it (so at most one bond per atom per step) and,
//!   with `prob`, when a uniform random number is below the fraction;
//! * angles that contain a broken bond as one of their two bonds, and dihedrals that contain it
//!   as one of their three, are deleted (if the system had angles/dihedrals at run start);
//! * the special lists and the neighbour lists are rebuilt on the same step.
//!
//! `f_ID[1]` is the number of bonds broken at the last check, `f_ID[2]` the running total.
//!
//! `dmhs/bond/break ... temp Tmax` adds the temperature criterion of the DMHS paper
//! (Alexiadis 2015, "Linking the three models"): on a check step, every bond of `bondtype`
//! between group atoms breaks when the temperature T = esph/cv of either of its atoms exceeds
//! Tmax (all such bonds at once: a melting particle loses all its bonds); the distance rule above
//! applies to the remaining bonds. Needs an atom style with sph.
//! dmhs/bond/break also reports `f_ID[3]`, the longest checked bond (bondtype, group atoms,
//! before breaking) at the last check, and `f_ID[4]`, the longest since the fix was defined.
//!
//! With `prob` below 1 the random numbers are dmhs' own (Park-Miller, one per atom with a
//! partner, in atom-ID order), so runs are reproducible but not bit-identical to LAMMPS, whose
//! draws follow its per-processor atom order.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::random_park::RanPark;
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};
use std::collections::HashMap;

/// The owned atoms i, j (tag i < tag j) that chose each other (`partner[i]` is the tag of i's
/// choice, 0 for none), as LAMMPS' bond/break and bond/create pair them. Below `fraction` 1,
/// each pair is kept when the random number of its lower-tag atom is below `fraction`; one
/// number is drawn per atom with a partner, in atom-ID order (see the module doc).
pub fn mutual_partners(a: &crate::engine::atoms::Atoms, partner: &[i64], fraction: f64, random: &mut RanPark) -> Vec<(usize, usize)> {
    let choice: std::collections::BTreeMap<i64, (i64, f64)> = (0..partner.len()).filter(|&i| partner[i] != 0).map(|i| (a.tag[i], (partner[i], 0.0))).collect();
    let map = a.tag_map();
    let local = |t: i64| map.get(t).expect("partner is an owned atom");
    // in the local order of the lower-ID atom, as the atoms were scanned
    let mut pairs: Vec<(usize, usize)> = mutual_choices(&choice, fraction, random).into_iter().map(|(t, p)| (local(t), local(p))).collect();
    pairs.sort_unstable();
    pairs
}

/// The pairs of atoms (lower ID first, in ID order) whose choices (`choice[t]` = (partner,
/// r^2)) name each other (the rule of [`mutual_partners`], by ID); below `fraction` 1 each is
/// kept when the random number of its lower-ID atom is below `fraction`, one number drawn per
/// atom with a choice, in ID order.
pub fn mutual_choices(choice: &std::collections::BTreeMap<i64, (i64, f64)>, fraction: f64, random: &mut RanPark) -> Vec<(i64, i64)> {
    let probability: HashMap<i64, f64> = if fraction < 1.0 { choice.keys().map(|&t| (t, random.uniform())).collect() } else { HashMap::new() };
    choice
        .iter()
        .filter(|&(&t, &(p, _))| t < p && choice.get(&p).is_some_and(|c| c.0 == t))
        .filter(|&(t, _)| fraction >= 1.0 || probability[t] < fraction)
        .map(|(&t, &(p, _))| (t, p))
        .collect()
}

pub const SYNTAX: &str = "fix ID group bond/break Nevery bondtype Rmax [prob fraction seed]";
pub const DMHS_SYNTAX: &str = "fix ID group dmhs/bond/break Nevery bondtype Rmax [temp Tmax] [prob fraction seed]";

pub struct FixBondBreak {
    id: String,
    groupbit: u32,
    dmhs: bool,
    nevery: i64,
    btype: usize,
    cutsq: f64,
    tmax: Option<f64>,
    fraction: f64,
    random: RanPark,
    /// Angles / dihedrals are removed with their bonds (LAMMPS: if any existed at run start).
    angleflag: bool,
    dihedralflag: bool,
    breakcount: usize,
    breakcounttotal: usize,
    /// dmhs/bond/break only: the longest checked bond at the last check and since the fix was
    /// defined (before breaking; bonds broken by temperature excluded).
    longest: f64,
    longest_ever: f64,
}

impl FixBondBreak {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let dmhs = style.text.starts_with("dmhs/");
        let mut a = Args::from_words(args, cmd.span, if dmhs { DMHS_SYNTAX } else { SYNTAX });
        if !state.atoms.features.bonds {
            return Err(Diagnostic::at(style.span, format!("fix {} needs an atom style with bonds", style.text), "atom style has no bonds"));
        }
        let nevery = a.i64_in("Nevery", 1, i64::MAX)?;
        let btype = a.i64_in("bond type", 1, state.topo.nbondtypes.max(1) as i64)? as usize;
        if btype > state.topo.nbondtypes {
            return Err(a.error_at(a.last().unwrap(), "Invalid bond type in fix bond/break command", "no bond types defined"));
        }
        let rmax = a.non_negative_f64("Rmax")?;
        let (mut fraction, mut seed, mut tmax) = (1.0, 12345, None);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "prob" => {
                    fraction = a.f64_where("prob fraction", "in [0, 1]", |x| (0.0..=1.0).contains(&x))?;
                    seed = a.i64_in("prob seed", 1, i32::MAX as i64)? as i32;
                }
                "temp" if dmhs => {
                    tmax = Some(a.f64("temp Tmax")?);
                    if !state.atoms.features.sph {
                        return Err(a.error_at(w, "the temp criterion needs per-atom esph and cv (an atom style with sph)", "atom style has no esph/cv"));
                    }
                }
                _ => return Err(a.unknown_keyword(w, if dmhs { &["temp", "prob"] } else { &["prob"] })),
            }
        }
        Ok(FixBondBreak {
            id,
            groupbit,
            dmhs,
            nevery,
            btype,
            cutsq: rmax * rmax,
            tmax,
            fraction,
            random: RanPark::new(seed),
            angleflag: false,
            dihedralflag: false,
            breakcount: 0,
            breakcounttotal: 0,
            longest: 0.0,
            longest_ever: 0.0,
        })
    }
}

/// Refuse `special_bonds angle/dihedral yes`: LAMMPS rebuilds the special lists of the atoms a
/// changed bond touches without the angle/dihedral trim, which dmhs' global rebuild does not copy.
pub fn check_special(state: &State, style: &str) -> Result<(), String> {
    if state.special_bonds.angle || state.special_bonds.dihedral {
        return Err(format!("fix {style} with special_bonds angle/dihedral yes is not supported (LAMMPS rebuilds the lists of changed atoms without that trim)"));
    }
    Ok(())
}

/// Delete bond (a, b) (either order, first match) and, if asked, the angles and dihedrals that
/// contain it as one of their consecutive pairs.
pub fn remove_bond(state: &mut State, a: i64, b: i64, angles: bool, dihedrals: bool) {
    let same = |p: i64, q: i64| (p == a && q == b) || (p == b && q == a);
    let t = &mut state.topo;
    if let Some(k) = t.bonds.iter().position(|bd| same(bd.atoms[0], bd.atoms[1])) {
        t.bonds.remove(k);
    }
    if angles {
        t.angles.retain(|an| !(same(an.atoms[0], an.atoms[1]) || same(an.atoms[1], an.atoms[2])));
    }
    if dihedrals {
        t.dihedrals.retain(|d| !(same(d.atoms[0], d.atoms[1]) || same(d.atoms[1], d.atoms[2]) || same(d.atoms[2], d.atoms[3])));
    }
}

impl Fix for FixBondBreak {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        if self.dmhs { "dmhs/bond/break" } else { "bond/break" }
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_integrate: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        check_special(state, self.style())?;
        if ctx.bond_style.is_none() {
            return Err("no bond_style is defined".into());
        }
        self.angleflag = !state.topo.angles.is_empty();
        self.dihedralflag = !state.topo.dihedrals.is_empty();
        Ok(())
    }
    fn post_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        // the ghosts of a distributed run at this step's positions (LAMMPS forwards them here)
        state.forward_positions_ranks();
        let periods = state.domain.as_ref().unwrap().periods();
        let a = &state.atoms;
        let mut hot_bonds: Vec<(i64, i64)> = vec![];
        let temp = |i: usize| a.esph[i] / a.cv[i];
        let lists = &state.bonded_lists.bonds;
        let mut longest_sq: f64 = 0.0;
        // the bonds longer than Rmax, as (tag, tag, r^2), in list order: chunk entries, then
        // the wide ones, then the ones across periodic faces; a distributed run's ranks each list the bonds they
        // compute, and every rank then reads all of them in rank order
        let mut candidates: Vec<f64> = vec![];
        for e in lists.all() {
            if e.typ != self.btype {
                continue;
            }
            let (i1, i2) = (e.atoms[0] as usize, e.atoms[1] as usize);
            if a.mask[i1] & self.groupbit == 0 || a.mask[i2] & self.groupbit == 0 {
                continue;
            }
            if let Some(tmax) = self.tmax {
                if temp(i1) > tmax || temp(i2) > tmax {
                    hot_bonds.push((a.tag[i1], a.tag[i2]));
                    continue;
                }
            }
            let p1 = periods.shifted(a.x[i1], e.shift[0]);
            let p2 = periods.shifted(a.x[i2], e.shift[1]);
            let del = [p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]];
            let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
            longest_sq = longest_sq.max(rsq);
            if rsq > self.cutsq {
                candidates.extend([a.tag[i1] as f64, a.tag[i2] as f64, rsq]);
            }
        }
        let candidates = state.allgather_ranks(candidates);
        // each atom's longest candidate (the first of equal lengths), by atom ID
        let mut choice: std::collections::BTreeMap<i64, (i64, f64)> = Default::default();
        for c in candidates.chunks_exact(3) {
            let (t1, t2, rsq) = (c[0] as i64, c[1] as i64, c[2]);
            for (t, other) in [(t1, t2), (t2, t1)] {
                let e = choice.entry(t).or_insert((0, 0.0));
                if rsq > e.1 {
                    *e = (other, rsq);
                }
            }
        }
        let mut broken = mutual_choices(&choice, self.fraction, &mut self.random);
        // the bonds broken by temperature, every rank's (each bond is listed on one rank)
        let hot: Vec<f64> = hot_bonds.iter().flat_map(|&(p, q)| [p as f64, q as f64]).collect();
        broken.extend(state.allgather_ranks(hot).chunks_exact(2).map(|c| (c[0] as i64, c[1] as i64)));
        self.breakcount = broken.len();
        let mut longest = [longest_sq];
        state.max_ranks(&mut longest);
        self.longest = longest[0].sqrt();
        self.longest_ever = self.longest_ever.max(self.longest);
        self.breakcounttotal += broken.len();
        for &(p, q) in &broken {
            remove_bond(state, p, q, self.angleflag, self.dihedralflag);
        }
        if !broken.is_empty() {
            state.topology_changed();
        }
        Ok(())
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        match i {
            1 => Some(self.breakcount as f64),
            2 => Some(self.breakcounttotal as f64),
            3 if self.dmhs => Some(self.longest),
            4 if self.dmhs => Some(self.longest_ever),
            _ => None,
        }
    }
    fn describe(&self) -> String {
        format!("fix {} {} (bond type {}, Rmax {}, every {})", self.id, self.style(), self.btype, self.cutsq.sqrt(), self.nevery)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::topology::{Angle, Bond, Dihedral};

    #[test]
    fn a_broken_bond_takes_its_angles_and_dihedrals_along() {
        let mut state = State::new();
        let t = &mut state.topo;
        t.bonds = (1..5).map(|k| Bond::new(1, [k, k + 1])).collect();
        t.angles = (1..4).map(|k| Angle::new(1, [k, k + 1, k + 2])).collect();
        t.dihedrals = (1..3).map(|k| Dihedral::new(1, [k, k + 1, k + 2, k + 3])).collect();
        // bond 4-3 given in the other order: 3-4 goes, with angles 2-3-4 and 3-4-5 and both dihedrals
        remove_bond(&mut state, 4, 3, true, true);
        let bonds: Vec<[i64; 2]> = state.topo.bonds.iter().map(|b| b.atoms).collect();
        assert_eq!(bonds, vec![[1, 2], [2, 3], [4, 5]]);
        let angles: Vec<[i64; 3]> = state.topo.angles.iter().map(|a| a.atoms).collect();
        assert_eq!(angles, vec![[1, 2, 3]]);
        assert!(state.topo.dihedrals.is_empty());
        // without angles/dihedrals at run start (LAMMPS' angleflag), only the bond goes
        remove_bond(&mut state, 1, 2, false, false);
        assert_eq!(state.topo.angles.len(), 1);
    }
}
