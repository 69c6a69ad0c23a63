//! Special neighbours: the 1-2, 1-3 and 1-4 partners of each atom through bonds, and the
//! weights (`special_bonds`) the pair styles apply to them — LAMMPS' src/special.cpp,
//! `Force::set_special` (src/force.cpp), `Input::special_bonds` and the neighbour-list side
//! (`Neighbor::init` special_flag, `find_special`, src/npair*.cpp).
//!
//! # The rule LAMMPS 2025 applies, and this module reproduces
//!
//! **Lists** (built per atom ID from the bond topology, [`build_special`]):
//! * 1-2: the bond partners. 1-3: partners of 1-2 partners. 1-4: 1-2 partners of 1-3 partners.
//! * Only as far as needed: if `lj[2] = coul[2] = lj[3] = coul[3] = 1` only 1-2 is built;
//!   else if `lj[3] = coul[3] = 1` only 1-2 and 1-3.
//! * Each level is de-duplicated (the atom itself removed); `angle yes` then keeps a 1-3 entry
//!   of atom A only if (A, B) are the end atoms 1,3 of a defined angle, or atoms 1,3 / 3,1 of a
//!   defined dihedral, or A is atom 4 and B atom 2 of a defined dihedral (LAMMPS flags only
//!   that direction, so B = atom 2 does *not* keep atom 4 unless another rule does: a quirk
//!   that makes the lists asymmetric, reproduced here); without any angle or dihedral all 1-3
//!   entries go. `dihedral yes` keeps a 1-4 entry only for the end atoms of a defined
//!   dihedral (both directions); without dihedrals all 1-4 entries go.
//! * The levels are concatenated; an atom already at a lower level is dropped from a higher
//!   one (a ring's 1-3 partner that is also 1-2 stays 1-2).
//!
//! **Action in the neighbour list** for a level L with weights (lj[L], coul[L]) ([`SpecialBonds::flags`]):
//! * both 0 → [`SpecialFlag::Exclude`]: the pair is left out of the list;
//! * both 1 → [`SpecialFlag::Normal`]: the pair is a plain pair (weight 1);
//! * otherwise → [`SpecialFlag::Weighted`]: kept and tagged with L; the pair style multiplies
//!   its LJ part by lj[L] and its Coulomb part by coul[L] (even a 0 weight is then applied
//!   by multiplication, e.g. lj 0 0.5 1 with coul 0 0 0 keeps 1-4 pairs weighted 1 / 0).
//! * with a KSpace solver, or pair styles coul/wolf, coul/dsf, thole, amoeba, hippo or
//!   coul/exclude (also inside hybrid), every level is Weighted (`force_weighted`).
//! * A pair is looked up in atom i's list only ([`pair_action`]); and if its separation
//!   exceeds half the box length in a periodic dimension (`Domain::minimum_image_check`) the
//!   pair is kept as a plain pair whatever the level: it is a periodic image, not the bonded
//!   partner itself.

use crate::engine::domain::Domain;
use dmhs_parser::{Args, DResult, Diagnostic, Span};
use std::collections::HashMap;

// ---------------------------------------------------------------------------------------
// special_bonds settings

/// The `special_bonds` settings. Index 0 of `lj`/`coul` is 1 (plain pairs), 1..=3 the levels.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecialBonds {
    pub lj: [f64; 4],
    pub coul: [f64; 4],
    /// `angle yes`: trim the 1-3 list to atoms of defined angles/dihedrals.
    pub angle: bool,
    /// `dihedral yes`: trim the 1-4 list to the end atoms of defined dihedrals.
    pub dihedral: bool,
}

impl Default for SpecialBonds {
    /// LAMMPS' defaults: `lj/coul 0 0 0`, `angle no`, `dihedral no`.
    fn default() -> SpecialBonds {
        SpecialBonds { lj: [1.0, 0.0, 0.0, 0.0], coul: [1.0, 0.0, 0.0, 0.0], angle: false, dihedral: false }
    }
}

/// What the neighbour list does with the pairs of one special level (LAMMPS `special_flag`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecialFlag {
    /// 0: both weights 0, the pair is removed from the list.
    Exclude,
    /// 1: both weights 1, the pair is an ordinary pair.
    Normal,
    /// 2: kept and tagged with its level; the pair style applies the weights.
    Weighted,
}

/// What the neighbour list does with one candidate pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairAction {
    /// Not special (or special with both weights 1, or a far periodic image): a plain pair.
    Keep,
    /// Special with both weights 0: not in the list.
    Exclude,
    /// Special at this level (1, 2 or 3): in the list with `special_lj/coul[level]`.
    Weighted(u8),
}

pub const SPECIAL_BONDS_SYNTAX: &str = "special_bonds keyword values ...   keywords: lj/coul w1 w2 w3, lj w1 w2 w3, \
coul w1 w2 w3, amber, charmm, dreiding, fene, angle yes/no, dihedral yes/no, one/five no";

const KEYWORDS: &[&str] =
    &["lj/coul", "lj", "coul", "amber", "charmm", "dreiding", "fene", "angle", "dihedral", "one/five"];

impl SpecialBonds {
    /// Parse the arguments of `special_bonds`. Like LAMMPS, every command starts again from
    /// the defaults (`special_bonds angle yes` alone also resets the weights to 0 0 0), and the
    /// weights are checked to lie in [0, 1] after all keywords (a later keyword may override).
    pub fn parse(args: &mut Args) -> DResult<SpecialBonds> {
        args.syntax = SPECIAL_BONDS_SYNTAX;
        if args.is_empty() {
            return Err(args.missing("a special_bonds keyword"));
        }
        let mut sb = SpecialBonds::default();
        // the word that last set each weight, for the range check
        let mut lj_at: [Option<Span>; 4] = [None; 4];
        let mut coul_at: [Option<Span>; 4] = [None; 4];
        while let Some(w) = args.peek() {
            args.skip(1);
            let preset = |lj: [f64; 3], coul: [f64; 3]| ([1.0, lj[0], lj[1], lj[2]], [1.0, coul[0], coul[1], coul[2]]);
            match w.text.as_str() {
                "amber" => (sb.lj, sb.coul) = preset([0.0, 0.0, 0.5], [0.0, 0.0, 5.0 / 6.0]),
                "charmm" => (sb.lj, sb.coul) = preset([0.0; 3], [0.0; 3]),
                "dreiding" => (sb.lj, sb.coul) = preset([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]),
                "fene" => (sb.lj, sb.coul) = preset([0.0, 1.0, 1.0], [0.0, 1.0, 1.0]),
                kw @ ("lj/coul" | "lj" | "coul") => {
                    for level in 1..=3 {
                        let x = args.f64(&format!("{kw} weight {level}"))?;
                        let at = args.last().map(|w| w.span);
                        if kw != "coul" {
                            sb.lj[level] = x;
                            lj_at[level] = at;
                        }
                        if kw != "lj" {
                            sb.coul[level] = x;
                            coul_at[level] = at;
                        }
                    }
                }
                "angle" => sb.angle = lammps_logical(args, "angle")?,
                "dihedral" => sb.dihedral = lammps_logical(args, "dihedral")?,
                "one/five" => {
                    if lammps_logical_strict(args, "one/five")? {
                        let v = args.last().expect("just parsed");
                        return Err(args.error_at(
                            v,
                            "Cannot set special_bonds one/five if atom style does not support it",
                            "no supported atom style keeps 1-5 lists",
                        ));
                    }
                }
                _ => return Err(args.unknown_keyword(w, KEYWORDS)),
            }
        }
        for level in 1..=3 {
            for (x, at, what) in [(sb.lj[level], lj_at[level], "lj"), (sb.coul[level], coul_at[level], "coul")] {
                if !(0.0..=1.0).contains(&x) {
                    let span = at.unwrap_or_default();
                    return Err(Diagnostic::at(
                        span,
                        format!("special_bonds {what} weight {level} must be in [0, 1], found {x}"),
                        "out of range",
                    )
                    .with_help(format!("syntax: {SPECIAL_BONDS_SYNTAX}")));
                }
            }
        }
        Ok(sb)
    }

    /// Whether changing from `old` to `self` makes LAMMPS rebuild the special lists (once a box
    /// exists): only a change of the 1-3/1-4 weights or of the angle/dihedral trims does.
    pub fn needs_rebuild(&self, old: &SpecialBonds) -> bool {
        self.lj[2] != old.lj[2]
            || self.lj[3] != old.lj[3]
            || self.coul[2] != old.coul[2]
            || self.coul[3] != old.coul[3]
            || self.angle != old.angle
            || self.dihedral != old.dihedral
    }

    /// The neighbour-list action per level (index 1..=3; index 0 is `Normal`).
    /// `force_weighted`: a KSpace solver or a pair style that needs every special pair
    /// (coul/wolf, coul/dsf, thole, amoeba, hippo, coul/exclude) is in use.
    pub fn flags(&self, force_weighted: bool) -> [SpecialFlag; 4] {
        let mut f = [SpecialFlag::Normal; 4];
        for (level, flag) in f.iter_mut().enumerate().skip(1) {
            *flag = if force_weighted {
                SpecialFlag::Weighted
            } else if self.lj[level] == 0.0 && self.coul[level] == 0.0 {
                SpecialFlag::Exclude
            } else if self.lj[level] == 1.0 && self.coul[level] == 1.0 {
                SpecialFlag::Normal
            } else {
                SpecialFlag::Weighted
            };
        }
        f
    }

    /// How many levels the list build needs: 1 (1-2 only), 2 or 3.
    fn levels_needed(&self) -> usize {
        if self.lj[2] == 1.0 && self.coul[2] == 1.0 && self.lj[3] == 1.0 && self.coul[3] == 1.0 {
            1
        } else if self.lj[3] == 1.0 && self.coul[3] == 1.0 {
            2
        } else {
            3
        }
    }
}

/// LAMMPS `utils::logical`: yes/no, on/off, true/false, 1/0 (lower case only).
fn lammps_logical(args: &mut Args, what: &str) -> DResult<bool> {
    let k = args.choice(what, &["no", "yes", "off", "on", "false", "true", "0", "1"])?;
    Ok(k % 2 == 1)
}

/// `one/five` takes only yes/no in LAMMPS.
fn lammps_logical_strict(args: &mut Args, what: &str) -> DResult<bool> {
    Ok(args.choice(what, &["no", "yes"])? == 1)
}

// ---------------------------------------------------------------------------------------
// Lists

/// The special partners of one atom, as LAMMPS stores them: 1-2 partners first, then 1-3,
/// then 1-4, with cumulative counts (`nspecial`). Within a level the order is unspecified.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SpecialList {
    pub ids: Vec<i64>,
    /// Cumulative counts: `ids[..n[0]]` are 1-2, `ids[n[0]..n[1]]` 1-3, `ids[n[1]..n[2]]` 1-4.
    pub n: [usize; 3],
}

impl SpecialList {
    /// The level (1, 2, 3) of atom `tag` in this list, or None.
    pub fn level(&self, tag: i64) -> Option<u8> {
        let k = self.ids.iter().position(|&t| t == tag)?;
        Some(if k < self.n[0] {
            1
        } else if k < self.n[1] {
            2
        } else {
            3
        })
    }
    pub fn one_two(&self) -> &[i64] {
        &self.ids[..self.n[0]]
    }
    pub fn one_three(&self) -> &[i64] {
        &self.ids[self.n[0]..self.n[1]]
    }
    pub fn one_four(&self) -> &[i64] {
        &self.ids[self.n[1]..self.n[2]]
    }
}

/// What LAMMPS reports while building the lists (for the log, see [`SpecialStats::log`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SpecialStats {
    /// Largest raw (before de-duplication) count per level; None for levels not built.
    pub max12: usize,
    pub max13: Option<usize>,
    pub max14: Option<usize>,
    /// Total 1-3 entries before/after the angle trim (if `angle yes` and 1-3 was built).
    pub angle_trim: Option<(usize, usize)>,
    /// Total 1-4 entries before/after the dihedral trim (if `dihedral yes` and 1-4 was built).
    pub dihedral_trim: Option<(usize, usize)>,
    /// Largest combined list, at least 1. LAMMPS prints the larger of this and the value of
    /// a previous build, plus `extra/special/per/atom`.
    pub max_special: usize,
}

impl SpecialStats {
    /// LAMMPS' log lines from "Finding 1-2 1-3 1-4 neighbors ..." up to, not including,
    /// the "special bonds CPU" line. `max_special` is the value to print (see the field).
    pub fn log(&self, sb: &SpecialBonds, max_special: usize) -> String {
        let mut s = String::from("Finding 1-2 1-3 1-4 neighbors ...\n");
        s += &format!("  special bond factors lj:    {:<8} {:<8} {:<8}\n", sb.lj[1], sb.lj[2], sb.lj[3]);
        s += &format!("  special bond factors coul:  {:<8} {:<8} {:<8}\n", sb.coul[1], sb.coul[2], sb.coul[3]);
        s += &format!("{:>6} = max # of 1-2 neighbors\n", self.max12);
        if let Some(m) = self.max13 {
            s += &format!("{m:>6} = max # of 1-3 neighbors\n");
        }
        if let Some(m) = self.max14 {
            s += &format!("{m:>6} = max # of 1-4 neighbors\n");
        }
        if let Some((a, b)) = self.angle_trim {
            s +=
                &format!("  {a} = # of 1-3 neighbors before angle trim\n  {b} = # of 1-3 neighbors after angle trim\n");
        }
        if let Some((a, b)) = self.dihedral_trim {
            s += &format!(
                "  {a} = # of 1-4 neighbors before dihedral trim\n  {b} = # of 1-4 neighbors after dihedral trim\n"
            );
        }
        s += &format!("{max_special:>6} = max # of special neighbors\n");
        s
    }
}

/// The bond topology by atom ID.
#[derive(Clone, Copy, Debug, Default)]
pub struct Topology<'a> {
    pub bonds: &'a [[i64; 2]],
    pub angles: &'a [[i64; 3]],
    pub dihedrals: &'a [[i64; 4]],
}

/// Build every atom's special list (LAMMPS `Special::build`). `ids` are the atom IDs; the
/// result is parallel to it. Errors: a duplicate atom ID, or a bond/angle/dihedral naming an
/// atom that does not exist.
pub fn build_special(
    sb: &SpecialBonds,
    ids: &[i64],
    topo: Topology,
) -> Result<(Vec<SpecialList>, SpecialStats), String> {
    let mut index: HashMap<i64, usize> = HashMap::with_capacity(ids.len());
    for (i, &id) in ids.iter().enumerate() {
        if index.insert(id, i).is_some() {
            return Err(format!("duplicate atom ID {id}"));
        }
    }
    let idx = |id: i64, what: &str| index.get(&id).copied().ok_or_else(|| format!("{what} atom {id} is missing"));
    for b in topo.bonds {
        for &a in b {
            idx(a, "bond")?;
        }
    }
    for a in topo.angles {
        for &t in a {
            idx(t, "angle")?;
        }
    }
    for d in topo.dihedrals {
        for &t in d {
            idx(t, "dihedral")?;
        }
    }
    let n = ids.len();
    let mut stats = SpecialStats::default();
    let levels = sb.levels_needed();

    // 1-2: both directions of every bond, duplicates kept for now (as LAMMPS counts them)
    let mut l12: Vec<Vec<i64>> = vec![vec![]; n];
    for &[a, b] in topo.bonds {
        l12[index[&a]].push(b);
        l12[index[&b]].push(a);
    }
    stats.max12 = l12.iter().map(Vec::len).max().unwrap_or(0);

    // 1-3: for every atom, each ordered pair of distinct slots of its 1-2 list. LAMMPS lists
    // the repeats and removes them after; dmhs counts them (the log's maxima are LAMMPS') but
    // keeps only first appearances, so a densely bonded deck (every atom bonded to every
    // other) costs its unique entries, not deg^3 (the order of first appearances, and so the
    // lists, are the same)
    let unique = |n: usize| -> (Vec<Vec<i64>>, Vec<std::collections::HashSet<i64>>) {
        (vec![vec![]; n], (0..n).map(|i| std::collections::HashSet::from([ids[i]])).collect())
    };
    let (mut l13, mut seen13) = unique(n);
    let mut count13 = vec![0usize; n];
    // an atom bonded twice to one partner is in its own raw 1-3 list (its 1-4 list then gets
    // its 1-2 partners, which LAMMPS' "before dihedral trim" count includes)
    let mut self13 = vec![false; n];
    if levels >= 2 {
        for list in &l12 {
            for (j, &a) in list.iter().enumerate() {
                let ia = index[&a];
                count13[ia] += list.len() - 1;
                for (k, &b) in list.iter().enumerate() {
                    if j != k {
                        if b == a {
                            self13[ia] = true;
                        } else if seen13[ia].insert(b) {
                            l13[ia].push(b);
                        }
                    }
                }
            }
        }
        stats.max13 = Some(count13.iter().copied().max().unwrap_or(0));
    }
    drop(seen13);

    // 1-4: atom a in i's 1-3 list gets i's 1-2 partners (with LAMMPS' repeats, a gets them
    // once for each time it is in i's 1-3 list: counted, not stored)
    let (mut l14, mut seen14) = unique(n);
    if levels >= 3 {
        let mut count14 = vec![0usize; n];
        for list in &l12 {
            for (j, &a) in list.iter().enumerate() {
                let deg = l12[index[&a]].len();
                for (k, &b) in list.iter().enumerate() {
                    if j != k {
                        count14[index[&b]] += deg;
                    }
                }
            }
        }
        for i in 0..n {
            let me = self13[i].then_some(ids[i]);
            for &a in l13[i].iter().chain(me.iter()) {
                let ia = index[&a];
                for &b in &l12[i] {
                    if seen14[ia].insert(b) {
                        l14[ia].push(b);
                    }
                }
            }
        }
        stats.max14 = Some(count14.iter().copied().max().unwrap_or(0));
    }
    drop(seen14);

    // de-duplicate the 1-2 level, dropping the atom itself (the others are already)
    for (i, list) in l12.iter_mut().enumerate() {
        dedup_keep_first(list, ids[i]);
    }

    if levels >= 2 && sb.angle {
        let before = l13.iter().map(Vec::len).sum();
        if topo.angles.is_empty() && topo.dihedrals.is_empty() {
            l13.iter_mut().for_each(Vec::clear);
        } else {
            let mut keep: std::collections::HashSet<(i64, i64)> = std::collections::HashSet::new();
            for &[a1, _, a3] in topo.angles {
                keep.insert((a1, a3));
                keep.insert((a3, a1));
            }
            for &[d1, d2, d3, d4] in topo.dihedrals {
                keep.insert((d1, d3));
                keep.insert((d3, d1));
                keep.insert((d4, d2)); // LAMMPS flags 4 -> 2 only (see the module doc)
            }
            for (i, list) in l13.iter_mut().enumerate() {
                list.retain(|&b| keep.contains(&(ids[i], b)));
            }
        }
        stats.angle_trim = Some((before, l13.iter().map(Vec::len).sum()));
    }

    if levels >= 3 && sb.dihedral {
        let before = l14.iter().map(Vec::len).sum();
        let mut keep: std::collections::HashSet<(i64, i64)> = std::collections::HashSet::new();
        for &[d1, _, _, d4] in topo.dihedrals {
            keep.insert((d1, d4));
            keep.insert((d4, d1));
        }
        for (i, list) in l14.iter_mut().enumerate() {
            list.retain(|&b| keep.contains(&(ids[i], b)));
        }
        stats.dihedral_trim = Some((before, l14.iter().map(Vec::len).sum()));
    }

    // combine: an atom stays at the lowest level it appears in
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut list = SpecialList::default();
        for (level, src) in [&l12[i], &l13[i], &l14[i]].into_iter().enumerate() {
            for &b in src {
                if !list.ids.contains(&b) {
                    list.ids.push(b);
                }
            }
            list.n[level] = list.ids.len();
        }
        out.push(list);
    }
    stats.max_special = out.iter().map(|l| l.ids.len()).max().unwrap_or(0).max(1);
    Ok((out, stats))
}

/// Remove repeats (keeping the first) and `me` from a list.
fn dedup_keep_first(list: &mut Vec<i64>, me: i64) {
    let mut seen = std::collections::HashSet::new();
    seen.insert(me);
    list.retain(|&t| seen.insert(t));
}

// ---------------------------------------------------------------------------------------
// Neighbour-list decision

/// LAMMPS `Domain::minimum_image_check`: the separation exceeds half the box in a periodic
/// dimension (so the pair is a periodic image, not the bonded partner).
pub fn minimum_image_check(domain: &Domain, del: [f64; 3]) -> bool {
    let prd = domain.prd();
    (0..3).any(|d| domain.periodic(d) && del[d].abs() > 0.5 * prd[d])
}

/// What the neighbour list does with the pair (i, j): `list_i` is atom i's special list,
/// `tag_j` atom j's ID, `far_image` the result of [`minimum_image_check`] for `x_i - x_j`.
/// Only atom i's list is searched (LAMMPS `find_special`), which matters for the asymmetric
/// lists `angle yes` can produce.
pub fn pair_action(flags: &[SpecialFlag; 4], list_i: &SpecialList, tag_j: i64, far_image: bool) -> PairAction {
    let Some(level) = list_i.level(tag_j) else { return PairAction::Keep };
    match flags[level as usize] {
        SpecialFlag::Normal => PairAction::Keep,
        _ if far_image => PairAction::Keep,
        SpecialFlag::Exclude => PairAction::Exclude,
        SpecialFlag::Weighted => PairAction::Weighted(level),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::domain::BoundaryKind;
    use dmhs_parser::{Span, Word};

    fn words(s: &str) -> Vec<Word> {
        let mut out = vec![];
        let mut pos = 0;
        for t in s.split_whitespace() {
            let lo = s[pos..].find(t).unwrap() + pos;
            out.push(Word::new(t, Span::new(Default::default(), lo, lo + t.len())));
            pos = lo + t.len();
        }
        out
    }

    fn parse(s: &str) -> DResult<SpecialBonds> {
        let w = words(s);
        SpecialBonds::parse(&mut Args::from_words(&w, Span::default(), ""))
    }

    #[test]
    fn parsing_follows_lammps() {
        // values observed from real LAMMPS (extract_global special_lj / special_coul)
        let sb = parse("lj 0 0.5 1").unwrap();
        assert_eq!((sb.lj, sb.coul), ([1.0, 0.0, 0.5, 1.0], [1.0, 0.0, 0.0, 0.0]));
        let sb = parse("angle yes").unwrap(); // resets the weights
        assert_eq!((sb.lj, sb.coul, sb.angle), ([1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], true));
        for v in ["on", "true", "1"] {
            assert!(parse(&format!("angle {v}")).unwrap().angle);
        }
        let sb = parse("amber").unwrap();
        assert_eq!((sb.lj, sb.coul), ([1.0, 0.0, 0.0, 0.5], [1.0, 0.0, 0.0, 0.8333333333333334]));
        let sb = parse("lj 0 0 0.5 coul 0.1 0.2 0.3 charmm").unwrap();
        assert_eq!((sb.lj, sb.coul), ([1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]));
        assert_eq!(parse("lj 0 0 1.5 lj 0 0 1").unwrap().lj, [1.0, 0.0, 0.0, 1.0]);
        assert_eq!(parse("lj 0 0 1e-1").unwrap().lj[3], 0.1);
        assert_eq!(parse("fene dihedral no one/five no").unwrap().lj, [1.0, 0.0, 1.0, 1.0]);
        // errors LAMMPS also raises
        for bad in ["", "angle YES", "extra 2", "lj/coul 0 0 1.5", "lj 0 0", "lj 0 0 .5x", "one/five yes"] {
            assert!(parse(bad).is_err(), "{bad}");
        }
        let e = parse("lj/coul 0 0 1.5").unwrap_err();
        assert_eq!(e.primary_span().unwrap().lo, 12);
        assert!(parse("dihedrl yes").unwrap_err().help.iter().any(|h| h.contains("dihedral")));
    }

    #[test]
    fn flags_per_level() {
        use SpecialFlag::*;
        let sb = parse("lj 0 0.5 1").unwrap();
        assert_eq!(sb.flags(false), [Normal, Exclude, Weighted, Weighted]);
        assert_eq!(parse("lj/coul 0 1 1").unwrap().flags(false), [Normal, Exclude, Normal, Normal]);
        assert_eq!(sb.flags(true), [Normal, Weighted, Weighted, Weighted]);
        assert!(parse("lj 1 0 0").unwrap().needs_rebuild(&parse("lj 0 0 0.5").unwrap()));
        assert!(!parse("lj 1 0 0").unwrap().needs_rebuild(&SpecialBonds::default()));
    }

    /// (atom ID, sorted 1-2, sorted 1-3, sorted 1-4)
    type AtomLists = (i64, &'static [i64], &'static [i64], &'static [i64]);

    /// Special lists from real LAMMPS 22 Jul 2025 (`extract_atom` nspecial/special after
    /// read_data) for 24 atoms: chain 1-6 (angles 1-2-3, 2-3-4; dihedrals 1-2-3-4, 3-4-5-6),
    /// 4-ring 7-10, triangle 11-13, branch 14(15,16,17)-18 with bond 14-15 listed twice
    /// (angles 15-14-16, 14-17-18; dihedral 16-14-17-18), 5-ring 19-23, lone atom 24.
    /// Regenerate with src/models/bonded/testdata/gen_special.py.
    struct Scenario {
        settings: &'static str,
        lists: &'static [AtomLists],
        log: &'static str,
    }

    const BONDS: &[[i64; 2]] = &[
        [1, 2],
        [2, 3],
        [3, 4],
        [4, 5],
        [5, 6],
        [7, 8],
        [8, 9],
        [9, 10],
        [10, 7],
        [11, 12],
        [12, 13],
        [13, 11],
        [14, 15],
        [14, 16],
        [14, 17],
        [17, 18],
        [15, 14],
        [19, 20],
        [20, 21],
        [21, 22],
        [22, 23],
        [23, 19],
    ];
    const ANGLES: &[[i64; 3]] = &[[1, 2, 3], [2, 3, 4], [15, 14, 16], [14, 17, 18]];
    const DIHEDRALS: &[[i64; 4]] = &[[1, 2, 3, 4], [3, 4, 5, 6], [16, 14, 17, 18]];

    #[test]
    fn lists_match_lammps() {
        // a shuffled ID order, as in the LAMMPS data file
        let ids: Vec<i64> = vec![13, 20, 2, 7, 24, 11, 5, 18, 9, 1, 22, 15, 4, 17, 10, 3, 23, 8, 14, 19, 6, 21, 12, 16];
        let topo = Topology { bonds: BONDS, angles: ANGLES, dihedrals: DIHEDRALS };
        for sc in SCENARIOS {
            let sb = if sc.settings.is_empty() { SpecialBonds::default() } else { parse(sc.settings).unwrap() };
            let (lists, stats) = build_special(&sb, &ids, topo).unwrap();
            for &(id, l12, l13, l14) in sc.lists {
                let l = &lists[ids.iter().position(|&t| t == id).unwrap()];
                let sorted = |s: &[i64]| {
                    let mut v = s.to_vec();
                    v.sort();
                    v
                };
                let got = (sorted(l.one_two()), sorted(l.one_three()), sorted(l.one_four()));
                assert_eq!(got, (l12.to_vec(), l13.to_vec(), l14.to_vec()), "`{}` atom {id}", sc.settings);
            }
            assert_eq!(stats.log(&sb, stats.max_special), sc.log, "`{}`", sc.settings);
        }
    }

    /// Every atom bonded to every other (a fuzzed deck made one: 2.3 GB for 256 atoms when the
    /// repeats were stored): the lists hold each partner once, at level 1, and the maxima are
    /// LAMMPS' counts with repeats, (n-1)(n-2) and (n-1)^2 (n-2).
    #[test]
    fn a_complete_graph_costs_its_unique_entries() {
        let n = 200i64;
        let ids: Vec<i64> = (1..=n).collect();
        let bonds: Vec<[i64; 2]> = (1..=n).flat_map(|a| (a + 1..=n).map(move |b| [a, b])).collect();
        let (lists, stats) = build_special(&SpecialBonds::default(), &ids, Topology { bonds: &bonds, ..Default::default() }).unwrap();
        assert!(lists.iter().all(|l| l.one_two().len() == n as usize - 1 && l.one_three().is_empty() && l.one_four().is_empty()));
        let m = (n - 1) as usize;
        assert_eq!((stats.max12, stats.max13, stats.max14), (m, Some(m * (m - 1)), Some(m * m * (m - 1))));
    }

    #[test]
    fn missing_atoms_are_errors() {
        let topo = Topology { bonds: &[[1, 3]], ..Default::default() };
        assert_eq!(build_special(&SpecialBonds::default(), &[1, 2], topo).unwrap_err(), "bond atom 3 is missing");
        assert!(build_special(&SpecialBonds::default(), &[1, 1], Topology::default()).is_err());
    }

    /// LJ (epsilon = sigma = 1, pair_style lj/cut) forces from real LAMMPS with special
    /// weights, to check the exclusions and weights per level end to end
    /// (regenerate: src/models/bonded/testdata/gen_pair.py). The sum order differs from LAMMPS'
    /// neighbour-list order, hence a 1e-13 tolerance here.
    struct PairCase {
        special: &'static str,
        boundary: &'static str,
        cut: f64,
        box_: [[f64; 2]; 3],
        bonds: &'static [[i64; 2]],
        x: &'static [[f64; 3]],
        f: &'static [[f64; 3]],
        evdwl: f64,
    }

    #[test]
    fn weighted_lj_matches_lammps() {
        for case in PAIR_CASES {
            let sb = parse(case.special).unwrap();
            let flags = sb.flags(false);
            let n = case.x.len();
            let ids: Vec<i64> = (1..=n as i64).collect();
            let (lists, _) = build_special(&sb, &ids, Topology { bonds: case.bonds, ..Default::default() }).unwrap();
            let periodic: Vec<bool> = case.boundary.split(' ').map(|b| b == "p").collect();
            let kind = |p: bool| if p { BoundaryKind::Periodic } else { BoundaryKind::Fixed };
            let domain = Domain::new(3, case.box_.map(|b| b[0]), case.box_.map(|b| b[1]), [0, 1, 2].map(|d| [kind(periodic[d]); 2]));
            let prd = domain.prd();
            let mut f = vec![[0.0f64; 3]; n];
            let mut e = 0.0;
            // every pair (and, in periodic dimensions, its nearest images) within the cutoff
            for i in 0..n {
                for j in 0..n {
                    for shift in -1i32..=1 {
                        if i == j && shift == 0 || (shift != 0 && !periodic[0]) || j < i {
                            continue;
                        }
                        let del = [
                            case.x[i][0] - case.x[j][0] - shift as f64 * prd[0],
                            case.x[i][1] - case.x[j][1],
                            case.x[i][2] - case.x[j][2],
                        ];
                        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                        if rsq >= case.cut * case.cut {
                            continue;
                        }
                        let w = match pair_action(&flags, &lists[i], ids[j], minimum_image_check(&domain, del)) {
                            PairAction::Exclude => continue,
                            PairAction::Keep => 1.0,
                            PairAction::Weighted(l) => sb.lj[l as usize],
                        };
                        let r2inv = 1.0 / rsq;
                        let r6inv = r2inv * r2inv * r2inv;
                        let fpair = w * r6inv * (48.0 * r6inv - 24.0) * r2inv;
                        // shifted energy is off in LAMMPS by default: plain 4 (r^-12 - r^-6)
                        e += w * r6inv * (4.0 * r6inv - 4.0);
                        let half = if i == j { 0.5 } else { 1.0 };
                        for d in 0..3 {
                            f[i][d] += half * del[d] * fpair;
                            f[j][d] -= half * del[d] * fpair;
                        }
                    }
                }
            }
            for (i, (got, want)) in f.iter().zip(case.f).enumerate() {
                for (d, (&a, &b)) in got.iter().zip(want).enumerate() {
                    assert!(
                        (a - b).abs() <= 1e-13 * b.abs().max(1e-3),
                        "`{}` atom {} dim {d}: {a} vs {b}",
                        case.special,
                        i + 1
                    );
                }
            }
            assert!((e - case.evdwl).abs() <= 1e-13 * case.evdwl.abs(), "`{}`: {e} vs {}", case.special, case.evdwl);
        }
    }

    #[rustfmt::skip]
    const SCENARIOS: &[Scenario] = &[
        Scenario {
            settings: "",
            lists: &[
                (1, &[2], &[3], &[4]),
                (2, &[1, 3], &[4], &[5]),
                (3, &[2, 4], &[1, 5], &[6]),
                (4, &[3, 5], &[2, 6], &[1]),
                (5, &[4, 6], &[3], &[2]),
                (6, &[5], &[4], &[3]),
                (7, &[8, 10], &[9], &[]),
                (8, &[7, 9], &[10], &[]),
                (9, &[8, 10], &[7], &[]),
                (10, &[7, 9], &[8], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[18], &[]),
                (15, &[14], &[16, 17], &[18]),
                (16, &[14], &[15, 17], &[18]),
                (17, &[14, 18], &[15, 16], &[]),
                (18, &[17], &[14], &[15, 16]),
                (19, &[20, 23], &[21, 22], &[]),
                (20, &[19, 21], &[22, 23], &[]),
                (21, &[20, 22], &[19, 23], &[]),
                (22, &[21, 23], &[19, 20], &[]),
                (23, &[19, 22], &[20, 21], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        0        0       \n  special bond factors coul:  0        0        0       \n     4 = max # of 1-2 neighbors\n     6 = max # of 1-3 neighbors\n    10 = max # of 1-4 neighbors\n     5 = max # of special neighbors\n",
        },
        Scenario {
            settings: "lj/coul 0 1 1",
            lists: &[
                (1, &[2], &[], &[]),
                (2, &[1, 3], &[], &[]),
                (3, &[2, 4], &[], &[]),
                (4, &[3, 5], &[], &[]),
                (5, &[4, 6], &[], &[]),
                (6, &[5], &[], &[]),
                (7, &[8, 10], &[], &[]),
                (8, &[7, 9], &[], &[]),
                (9, &[8, 10], &[], &[]),
                (10, &[7, 9], &[], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[], &[]),
                (15, &[14], &[], &[]),
                (16, &[14], &[], &[]),
                (17, &[14, 18], &[], &[]),
                (18, &[17], &[], &[]),
                (19, &[20, 23], &[], &[]),
                (20, &[19, 21], &[], &[]),
                (21, &[20, 22], &[], &[]),
                (22, &[21, 23], &[], &[]),
                (23, &[19, 22], &[], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        1        1       \n  special bond factors coul:  0        1        1       \n     4 = max # of 1-2 neighbors\n     3 = max # of special neighbors\n",
        },
        Scenario {
            settings: "lj/coul 0 0.5 1",
            lists: &[
                (1, &[2], &[3], &[]),
                (2, &[1, 3], &[4], &[]),
                (3, &[2, 4], &[1, 5], &[]),
                (4, &[3, 5], &[2, 6], &[]),
                (5, &[4, 6], &[3], &[]),
                (6, &[5], &[4], &[]),
                (7, &[8, 10], &[9], &[]),
                (8, &[7, 9], &[10], &[]),
                (9, &[8, 10], &[7], &[]),
                (10, &[7, 9], &[8], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[18], &[]),
                (15, &[14], &[16, 17], &[]),
                (16, &[14], &[15, 17], &[]),
                (17, &[14, 18], &[15, 16], &[]),
                (18, &[17], &[14], &[]),
                (19, &[20, 23], &[21, 22], &[]),
                (20, &[19, 21], &[22, 23], &[]),
                (21, &[20, 22], &[19, 23], &[]),
                (22, &[21, 23], &[19, 20], &[]),
                (23, &[19, 22], &[20, 21], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        0.5      1       \n  special bond factors coul:  0        0.5      1       \n     4 = max # of 1-2 neighbors\n     6 = max # of 1-3 neighbors\n     4 = max # of special neighbors\n",
        },
        Scenario {
            settings: "lj 0 0.5 1",
            lists: &[
                (1, &[2], &[3], &[4]),
                (2, &[1, 3], &[4], &[5]),
                (3, &[2, 4], &[1, 5], &[6]),
                (4, &[3, 5], &[2, 6], &[1]),
                (5, &[4, 6], &[3], &[2]),
                (6, &[5], &[4], &[3]),
                (7, &[8, 10], &[9], &[]),
                (8, &[7, 9], &[10], &[]),
                (9, &[8, 10], &[7], &[]),
                (10, &[7, 9], &[8], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[18], &[]),
                (15, &[14], &[16, 17], &[18]),
                (16, &[14], &[15, 17], &[18]),
                (17, &[14, 18], &[15, 16], &[]),
                (18, &[17], &[14], &[15, 16]),
                (19, &[20, 23], &[21, 22], &[]),
                (20, &[19, 21], &[22, 23], &[]),
                (21, &[20, 22], &[19, 23], &[]),
                (22, &[21, 23], &[19, 20], &[]),
                (23, &[19, 22], &[20, 21], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        0.5      1       \n  special bond factors coul:  0        0        0       \n     4 = max # of 1-2 neighbors\n     6 = max # of 1-3 neighbors\n    10 = max # of 1-4 neighbors\n     5 = max # of special neighbors\n",
        },
        Scenario {
            settings: "lj/coul 0 0 0 angle yes",
            lists: &[
                (1, &[2], &[3], &[4]),
                (2, &[1, 3], &[4], &[5]),
                (3, &[2, 4], &[1, 5], &[6]),
                (4, &[3, 5], &[2], &[1]),
                (5, &[4, 6], &[3], &[2]),
                (6, &[5], &[4], &[3]),
                (7, &[8, 10], &[], &[]),
                (8, &[7, 9], &[], &[]),
                (9, &[8, 10], &[], &[]),
                (10, &[7, 9], &[], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[18], &[]),
                (15, &[14], &[16], &[18]),
                (16, &[14], &[15, 17], &[18]),
                (17, &[14, 18], &[16], &[]),
                (18, &[17], &[14], &[15, 16]),
                (19, &[20, 23], &[], &[21, 22]),
                (20, &[19, 21], &[], &[22, 23]),
                (21, &[20, 22], &[], &[19, 23]),
                (22, &[21, 23], &[], &[19, 20]),
                (23, &[19, 22], &[], &[20, 21]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        0        0       \n  special bond factors coul:  0        0        0       \n     4 = max # of 1-2 neighbors\n     6 = max # of 1-3 neighbors\n    10 = max # of 1-4 neighbors\n  36 = # of 1-3 neighbors before angle trim\n  13 = # of 1-3 neighbors after angle trim\n     5 = max # of special neighbors\n",
        },
        Scenario {
            settings: "lj/coul 0 0 0 dihedral yes",
            lists: &[
                (1, &[2], &[3], &[4]),
                (2, &[1, 3], &[4], &[]),
                (3, &[2, 4], &[1, 5], &[6]),
                (4, &[3, 5], &[2, 6], &[1]),
                (5, &[4, 6], &[3], &[]),
                (6, &[5], &[4], &[3]),
                (7, &[8, 10], &[9], &[]),
                (8, &[7, 9], &[10], &[]),
                (9, &[8, 10], &[7], &[]),
                (10, &[7, 9], &[8], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[18], &[]),
                (15, &[14], &[16, 17], &[]),
                (16, &[14], &[15, 17], &[18]),
                (17, &[14, 18], &[15, 16], &[]),
                (18, &[17], &[14], &[16]),
                (19, &[20, 23], &[21, 22], &[]),
                (20, &[19, 21], &[22, 23], &[]),
                (21, &[20, 22], &[19, 23], &[]),
                (22, &[21, 23], &[19, 20], &[]),
                (23, &[19, 22], &[20, 21], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        0        0       \n  special bond factors coul:  0        0        0       \n     4 = max # of 1-2 neighbors\n     6 = max # of 1-3 neighbors\n    10 = max # of 1-4 neighbors\n  59 = # of 1-4 neighbors before dihedral trim\n  6 = # of 1-4 neighbors after dihedral trim\n     5 = max # of special neighbors\n",
        },
        Scenario {
            settings: "lj/coul 0 0 0 angle yes dihedral yes",
            lists: &[
                (1, &[2], &[3], &[4]),
                (2, &[1, 3], &[4], &[]),
                (3, &[2, 4], &[1, 5], &[6]),
                (4, &[3, 5], &[2], &[1]),
                (5, &[4, 6], &[3], &[]),
                (6, &[5], &[4], &[3]),
                (7, &[8, 10], &[], &[]),
                (8, &[7, 9], &[], &[]),
                (9, &[8, 10], &[], &[]),
                (10, &[7, 9], &[], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[18], &[]),
                (15, &[14], &[16], &[]),
                (16, &[14], &[15, 17], &[18]),
                (17, &[14, 18], &[16], &[]),
                (18, &[17], &[14], &[16]),
                (19, &[20, 23], &[], &[]),
                (20, &[19, 21], &[], &[]),
                (21, &[20, 22], &[], &[]),
                (22, &[21, 23], &[], &[]),
                (23, &[19, 22], &[], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        0        0       \n  special bond factors coul:  0        0        0       \n     4 = max # of 1-2 neighbors\n     6 = max # of 1-3 neighbors\n    10 = max # of 1-4 neighbors\n  36 = # of 1-3 neighbors before angle trim\n  13 = # of 1-3 neighbors after angle trim\n  59 = # of 1-4 neighbors before dihedral trim\n  6 = # of 1-4 neighbors after dihedral trim\n     5 = max # of special neighbors\n",
        },
        Scenario {
            settings: "lj/coul 0 0.5 1 angle yes",
            lists: &[
                (1, &[2], &[3], &[]),
                (2, &[1, 3], &[4], &[]),
                (3, &[2, 4], &[1, 5], &[]),
                (4, &[3, 5], &[2], &[]),
                (5, &[4, 6], &[3], &[]),
                (6, &[5], &[4], &[]),
                (7, &[8, 10], &[], &[]),
                (8, &[7, 9], &[], &[]),
                (9, &[8, 10], &[], &[]),
                (10, &[7, 9], &[], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[18], &[]),
                (15, &[14], &[16], &[]),
                (16, &[14], &[15, 17], &[]),
                (17, &[14, 18], &[16], &[]),
                (18, &[17], &[14], &[]),
                (19, &[20, 23], &[], &[]),
                (20, &[19, 21], &[], &[]),
                (21, &[20, 22], &[], &[]),
                (22, &[21, 23], &[], &[]),
                (23, &[19, 22], &[], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        0.5      1       \n  special bond factors coul:  0        0.5      1       \n     4 = max # of 1-2 neighbors\n     6 = max # of 1-3 neighbors\n  36 = # of 1-3 neighbors before angle trim\n  13 = # of 1-3 neighbors after angle trim\n     4 = max # of special neighbors\n",
        },
        Scenario {
            settings: "amber",
            lists: &[
                (1, &[2], &[3], &[4]),
                (2, &[1, 3], &[4], &[5]),
                (3, &[2, 4], &[1, 5], &[6]),
                (4, &[3, 5], &[2, 6], &[1]),
                (5, &[4, 6], &[3], &[2]),
                (6, &[5], &[4], &[3]),
                (7, &[8, 10], &[9], &[]),
                (8, &[7, 9], &[10], &[]),
                (9, &[8, 10], &[7], &[]),
                (10, &[7, 9], &[8], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[18], &[]),
                (15, &[14], &[16, 17], &[18]),
                (16, &[14], &[15, 17], &[18]),
                (17, &[14, 18], &[15, 16], &[]),
                (18, &[17], &[14], &[15, 16]),
                (19, &[20, 23], &[21, 22], &[]),
                (20, &[19, 21], &[22, 23], &[]),
                (21, &[20, 22], &[19, 23], &[]),
                (22, &[21, 23], &[19, 20], &[]),
                (23, &[19, 22], &[20, 21], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        0        0.5     \n  special bond factors coul:  0        0        0.8333333333333334\n     4 = max # of 1-2 neighbors\n     6 = max # of 1-3 neighbors\n    10 = max # of 1-4 neighbors\n     5 = max # of special neighbors\n",
        },
        Scenario {
            settings: "fene",
            lists: &[
                (1, &[2], &[], &[]),
                (2, &[1, 3], &[], &[]),
                (3, &[2, 4], &[], &[]),
                (4, &[3, 5], &[], &[]),
                (5, &[4, 6], &[], &[]),
                (6, &[5], &[], &[]),
                (7, &[8, 10], &[], &[]),
                (8, &[7, 9], &[], &[]),
                (9, &[8, 10], &[], &[]),
                (10, &[7, 9], &[], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[], &[]),
                (15, &[14], &[], &[]),
                (16, &[14], &[], &[]),
                (17, &[14, 18], &[], &[]),
                (18, &[17], &[], &[]),
                (19, &[20, 23], &[], &[]),
                (20, &[19, 21], &[], &[]),
                (21, &[20, 22], &[], &[]),
                (22, &[21, 23], &[], &[]),
                (23, &[19, 22], &[], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    0        1        1       \n  special bond factors coul:  0        1        1       \n     4 = max # of 1-2 neighbors\n     3 = max # of special neighbors\n",
        },
        Scenario {
            settings: "lj/coul 1 1 1",
            lists: &[
                (1, &[2], &[], &[]),
                (2, &[1, 3], &[], &[]),
                (3, &[2, 4], &[], &[]),
                (4, &[3, 5], &[], &[]),
                (5, &[4, 6], &[], &[]),
                (6, &[5], &[], &[]),
                (7, &[8, 10], &[], &[]),
                (8, &[7, 9], &[], &[]),
                (9, &[8, 10], &[], &[]),
                (10, &[7, 9], &[], &[]),
                (11, &[12, 13], &[], &[]),
                (12, &[11, 13], &[], &[]),
                (13, &[11, 12], &[], &[]),
                (14, &[15, 16, 17], &[], &[]),
                (15, &[14], &[], &[]),
                (16, &[14], &[], &[]),
                (17, &[14, 18], &[], &[]),
                (18, &[17], &[], &[]),
                (19, &[20, 23], &[], &[]),
                (20, &[19, 21], &[], &[]),
                (21, &[20, 22], &[], &[]),
                (22, &[21, 23], &[], &[]),
                (23, &[19, 22], &[], &[]),
                (24, &[], &[], &[]),
            ],
            log: "Finding 1-2 1-3 1-4 neighbors ...\n  special bond factors lj:    1        1        1       \n  special bond factors coul:  1        1        1       \n     4 = max # of 1-2 neighbors\n     3 = max # of special neighbors\n",
        },
    ];

    #[rustfmt::skip]
    const PAIR_CASES: &[PairCase] = &[
    // chain, lj 0 0.5 1
    PairCase {
        special: "lj 0 0.5 1", boundary: "f f f", cut: 3.5,
        box_: [[0.0, 8.0], [0.0, 8.0], [0.0, 8.0]],
        bonds: &[[1, 2], [2, 3], [3, 4], [4, 5], [5, 6]],
        x: &[[1.0, 1.0, 1.0], [1.95, 1.3, 1.1], [2.7, 2.0, 1.2], [3.6, 1.7, 1.6], [4.5, 2.2, 1.3], [5.1, 3.0, 1.7]],
        f: &[[0.10122192755198446, 0.05363394365429697, 0.01400362755089671], [0.21309306397443883, 0.053961687959207985, 0.059893846342130797], [0.11502161565556909, -0.019432083790508273, 0.004878193044061399], [-0.13923674790954638, 0.010408251130369174, -0.05776434579569683], [-0.19484366048723029, -0.026688138014278398, -0.011301295059334013], [-0.09525619878521574, -0.07188366093908745, -0.009710026082058062]],
        evdwl: -0.21253884308906093,
    },
    // chain, lj/coul 0 1 1 (1-3, 1-4 plain)
    PairCase {
        special: "lj/coul 0 1 1", boundary: "f f f", cut: 3.5,
        box_: [[0.0, 8.0], [0.0, 8.0], [0.0, 8.0]],
        bonds: &[[1, 2], [2, 3], [3, 4], [4, 5], [5, 6]],
        x: &[[1.0, 1.0, 1.0], [1.95, 1.3, 1.1], [2.7, 2.0, 1.2], [3.6, 1.7, 1.6], [4.5, 2.2, 1.3], [5.1, 3.0, 1.7]],
        f: &[[0.1839225922081058, 0.10228139345201541, 0.023733117510440396], [0.4053498336812648, 0.10056938970631729, 0.11815347352601745], [0.20632831721906514, -0.04874538178604698, 0.004815778985607577], [-0.25995223292322966, 0.025802996117316873, -0.11125455400004064], [-0.3688510267068477, -0.04602228981645813, -0.02096837096042388], [-0.1667974834783584, -0.13388610767314446, -0.014479445061600902]],
        evdwl: -0.39440546212336564,
    },
    // chain, lj/coul 0.25 0 0.75 (1-3 excluded)
    PairCase {
        special: "lj/coul 0.25 0 0.75", boundary: "f f f", cut: 3.5,
        box_: [[0.0, 8.0], [0.0, 8.0], [0.0, 8.0]],
        bonds: &[[1, 2], [2, 3], [3, 4], [4, 5], [5, 6]],
        x: &[[1.0, 1.0, 1.0], [1.95, 1.3, 1.1], [2.7, 2.0, 1.2], [3.6, 1.7, 1.6], [4.5, 2.2, 1.3], [5.1, 3.0, 1.7]],
        f: &[[-5.5452347068200405, -1.7517734940260732, -0.5819655182793213], [3.218122823398414, -0.43849252713036935, 0.2721794456689553], [-0.5308948087726294, 3.175369307073696, -0.9733265581165135], [1.9187675934970037, -1.5125393883638605, 1.6122612520781212], [0.3977006214589467, -0.21091920397610064, -0.6983262745625956], [0.5415384772383054, 0.7383553064227076, 0.3691776532113538]],
        evdwl: -0.7591139070090233,
    },
    // periodic: the far image of a bonded partner is a plain pair
    PairCase {
        special: "lj 0 0 0", boundary: "p f f", cut: 2.5,
        box_: [[0.0, 3.0], [0.0, 6.0], [0.0, 6.0]],
        bonds: &[[1, 2]],
        x: &[[0.5, 3.0, 3.0], [1.5, 3.0, 3.0]],
        f: &[[-0.181640625, 0.0, 0.0], [0.181640625, 0.0, 0.0]],
        evdwl: -0.0615234375,
    },
    ];
}
