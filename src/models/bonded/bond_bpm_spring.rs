//! `bond_style bpm/spring` (LAMMPS BPM package, src/BPM/bond_bpm.cpp and bond_bpm_spring.cpp):
//! a breakable central spring whose rest length r0 is each bond's own, stored at the first
//! force evaluation (LAMMPS' fix bond/history; here `Bond::r0` of the topology record).
//!
//! With e = (r - r0) / r0, a bond breaks when |e| > ecrit (with `break yes`); otherwise
//!
//!   F = [k (r0 - r) - gamma (del . dv) / r] / r * del * s,   s = 1 - (e / ecrit)^8 with `smooth yes`
//!
//! (`normalize yes` uses -k e for the spring term) and the energy is 1/2 k (r - r0)^2 (divided by
//! r0 with `normalize yes`; the damping and the smoothing carry none).
//!
//! A broken bond is removed from the topology, and the pair between its atoms turns on from the
//! next step: LAMMPS' fix update/special/bonds removes the 1-2 entry from both special lists and
//! clears the special bits of the pair's neighbour entries; dmhs does the same to its special
//! table and neighbour list, so no list is rebuilt. `store/local FIXID N values...` records
//! every broken bond (`id1 id2 time x y z x/ref y/ref z/ref`) in fix FIXID (see
//! `crate::models::fix::store_local`), created by the `bond_style` command.

use super::{fmt_g, BondStyle, TypeTable, Vec3};
use crate::engine::bonded_lists::{chunk, Entry};
use crate::engine::fields::Field;
use crate::engine::par::{slab_phase, AtomsMut};
use crate::engine::state::{RunError, State};
use crate::models::bonded::bond_virial;
use crate::models::bonded::pass::BondedTally;
use dmhs_parser::{Args, DResult, Span};

use std::sync::atomic::{AtomicBool, Ordering};

const SYNTAX: &str = "bond_coeff N k ecrit gamma";
pub const SETTINGS_SYNTAX: &str =
    "bond_style bpm/spring [store/local fixID N id1|id2|time|x|y|z|x/ref|y/ref|z/ref ...] [overlay/pair yes/no] [break yes/no] [smooth yes/no] [normalize yes/no] [volume/factor no]";
/// LAMMPS' EPSILON below which a stored reference length counts as unset.
const EPSILON: f64 = 1e-10;

/// Reference positions for `x/ref y/ref z/ref` (LAMMPS' property/atom d_BPM_X_REF ...), the
/// positions when `bond_style` was given. Bonds read them on their owned atoms (a LAMMPS ghost
/// has its owner's value), so ghosts need none.
pub const X_REF: [Field; 3] =
    [Field { name: "BPM_X_REF", ghosts: false }, Field { name: "BPM_Y_REF", ghosts: false }, Field { name: "BPM_Z_REF", ghosts: false }];

#[derive(Clone, Copy, Debug, PartialEq)]
struct Params {
    k: f64,
    ecrit: f64,
    gamma: f64,
}

/// One value of a broken-bond record.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LocalValue {
    Id1,
    Id2,
    Time,
    X(usize),
    XRef(usize),
}

/// `store/local FIXID N values...`
#[derive(Clone, Debug)]
pub struct StoreLocal {
    pub fix_id: String,
    pub every: i64,
    pub values: Vec<LocalValue>,
    pub span: Span,
}

#[derive(Debug)]
pub struct BondBpmSpring {
    types: TypeTable<Params>,
    pub overlay: bool,
    pub break_bonds: bool,
    pub smooth: bool,
    pub normalize: bool,
    pub store_local: Option<StoreLocal>,
    /// LAMMPS' `stored_flag` of the style's bond history: every bond's r0 is (re)stored at the
    /// first force evaluation after the style was defined.
    stored: AtomicBool,
}

impl Default for BondBpmSpring {
    fn default() -> Self {
        BondBpmSpring { types: TypeTable::default(), overlay: false, break_bonds: true, smooth: true, normalize: false, store_local: None, stored: AtomicBool::new(false) }
    }
}

/// LAMMPS `utils::logical`.
fn logical(a: &mut Args, what: &str) -> DResult<bool> {
    Ok(a.choice(what, &["no", "yes", "off", "on", "false", "true", "0", "1"])? % 2 == 1)
}

impl BondBpmSpring {
    /// The kernel of one intact bond of type `btype` with reference length `r0`:
    /// `del = x1 - x2`, `dv = v1 - v2` (atom 1 has the lower ID). `None`: the bond breaks.
    /// Otherwise `(fbond, energy)`: the force on atom 1 is `del * fbond`.
    #[inline(always)]
    pub fn kernel(&self, btype: usize, r0: f64, del: Vec3, dv: Vec3) -> Option<(f64, f64)> {
        let p = self.types.get(btype);
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        let r = rsq.sqrt();
        let e = (r - r0) / r0;
        if e.abs() > p.ecrit && self.break_bonds {
            return None;
        }
        let rinv = 1.0 / r;
        let mut fbond = if self.normalize { -p.k * e } else { p.k * (r0 - r) };
        let energy = if self.normalize { 0.5 * p.k * e * (r - r0) } else { 0.5 * p.k * (r - r0) * (r - r0) };
        let dot = del[0] * dv[0] + del[1] * dv[1] + del[2] * dv[2];
        fbond -= p.gamma * dot * rinv;
        fbond *= rinv;
        if self.smooth {
            let mut s = (r - r0) / (r0 * p.ecrit);
            s *= s;
            s *= s;
            s *= s;
            fbond *= 1.0 - s;
        }
        Some((fbond, energy))
    }

    /// LAMMPS' BondBPM::init_style and BondBPMSpring::init_style checks.
    fn check(&self, state: &State, many_body: bool) -> Result<(), String> {
        let (lj, coul) = (state.special_bonds.lj, state.special_bonds.coul);
        if self.overlay {
            if lj[1..].iter().chain(&coul[1..]).any(|&w| w != 1.0) {
                return Err("With overlay/pair yes, BPM bond styles require a value of 1.0 for all special_bonds weights".into());
            }
        } else {
            if state.newton_bond && self.break_bonds {
                return Err("With overlay/pair no, or break yes, BPM bond styles require Newton bond off".into());
            }
            if lj[1] != 0.0 || lj[2] != 1.0 || lj[3] != 1.0 {
                return Err("With overlay/pair no, BPM bond styles require special LJ weights = 0,1,1".into());
            }
            if self.break_bonds && coul[1..].iter().any(|&w| w != 1.0) {
                return Err("With overlay/pair no, and break yes, BPM bond styles requires special Coulomb weights = 1,1,1".into());
            }
        }
        if many_body {
            return Err("Bond style bpm cannot be used with 3,4-body interactions".into());
        }
        if lj[2] != 1.0 || lj[3] != 1.0 || coul[2] != 1.0 || coul[3] != 1.0 {
            return Err("Bond style bpm requires 1-3 and 1-4 special weights of 1.0".into());
        }
        if !state.comm_vel {
            return Err("Bond bpm/spring requires ghost atoms store velocity (comm_modify vel yes)".into());
        }
        Ok(())
    }
}

impl BondStyle for BondBpmSpring {
    fn name(&self) -> &'static str {
        "bpm/spring"
    }
    fn settings(&mut self, a: &mut Args) -> DResult<()> {
        a.syntax = SETTINGS_SYNTAX;
        let words = a.remaining();
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "store/local" => {
                    let id = a.word("store/local fix ID")?.text.clone();
                    let every = a.i64_in("store/local N", 1, i32::MAX as i64)?;
                    let mut values = vec![];
                    while let Some(v) = a.peek() {
                        let value = match v.text.as_str() {
                            "id1" => LocalValue::Id1,
                            "id2" => LocalValue::Id2,
                            "time" => LocalValue::Time,
                            "x" => LocalValue::X(0),
                            "y" => LocalValue::X(1),
                            "z" => LocalValue::X(2),
                            "x/ref" => LocalValue::XRef(0),
                            "y/ref" => LocalValue::XRef(1),
                            "z/ref" => LocalValue::XRef(2),
                            _ => break,
                        };
                        values.push(value);
                        a.skip(1);
                    }
                    if values.is_empty() {
                        return Err(a.error_at(w, "Storing local data must include at least one value to output", "no values after store/local fixID N"));
                    }
                    self.store_local = Some(StoreLocal { fix_id: id, every, values, span: w.span });
                }
                "overlay/pair" => self.overlay = logical(a, "overlay/pair")?,
                "break" => self.break_bonds = logical(a, "break")?,
                "smooth" => self.smooth = logical(a, "smooth")?,
                "normalize" => self.normalize = logical(a, "normalize")?,
                "volume/factor" => {
                    if logical(a, "volume/factor")? {
                        let last = a.last().unwrap_or(w);
                        return Err(a.error_at(last, "bond_style bpm/spring volume/factor yes is not supported yet", "only volume/factor no"));
                    }
                }
                _ => return Err(a.unknown_keyword(w, &["store/local", "overlay/pair", "break", "smooth", "normalize", "volume/factor"])),
            }
        }
        if self.smooth && !self.break_bonds {
            let w = words.iter().rev().find(|w| w.text == "break").expect("break no was given");
            return Err(a.error_at(w, "Illegal bond bpm command, must turn off smoothing with break no option", "add smooth no"));
        }
        Ok(())
    }
    fn set_types(&mut self, n: usize) {
        self.types.resize(n);
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = SYNTAX;
        let k = args.f64("k")?;
        let ecrit = args.f64("ecrit")?;
        let gamma = args.f64("gamma")?;
        args.finish()?;
        self.types.set(lo, hi, Params { k, ecrit, gamma });
        Ok(())
    }
    fn check_all_set(&self) -> Result<(), String> {
        self.types.check_all_set("Bond")
    }
    fn compute(&self, _btype: usize, _del: Vec3, _rsq: f64) -> (f64, f64) {
        unreachable!("bpm/spring runs its own pass (bond_bpm_spring::compute)")
    }
    fn equilibrium_distance(&self, _btype: usize) -> f64 {
        // LAMMPS estimates the longest stored r0 times the largest 1 + ecrit; dmhs bonds take
        // the closest image, so the estimate only matters for the stability checks
        0.0
    }
    fn stiffness(&self, btype: usize) -> f64 {
        self.types.try_get(btype).map(|p| 0.5 * p.k).unwrap_or(0.0)
    }
    fn coeff_words(&self, btype: usize) -> String {
        let p = self.types.get(btype);
        format!("{} {} {}", fmt_g(p.k), fmt_g(p.ecrit), fmt_g(p.gamma))
    }
    fn init(&self, state: &State, many_body: bool) -> Result<(), String> {
        self.check(state, many_body)
    }
    fn as_bpm_spring(&self) -> Option<&BondBpmSpring> {
        Some(self)
    }
}

/// A bond that broke during a force evaluation.
#[derive(Clone, Copy, Debug)]
pub struct Broken {
    /// The topology record (valid until the records are removed).
    pub rec: u32,
    /// Local indices, atom 1 the lower ID, and their positions as the bond saw them.
    pub atoms: [u32; 2],
    pub x: [Vec3; 2],
}

/// Position of atom `i` at periodic shift `s` (LAMMPS' ghost copy `x + s L`); chunk entries
/// have no shifts.
#[inline(always)]
fn image(x: &[Vec3], i: u32, s: [i8; 3], prd: Vec3, shifts: bool) -> Vec3 {
    if shifts { crate::models::fix::bond_break::image(x[i as usize], s, prd) } else { x[i as usize] }
}

/// Atom order of a bond as LAMMPS computes it: the lower ID first.
#[inline(always)]
fn ordered(e: &Entry<2>, tag: &[i64]) -> [(u32, [i8; 3]); 2] {
    let (a, b) = ((e.atoms[0], e.shift[0]), (e.atoms[1], e.shift[1]));
    if tag[b.0 as usize] < tag[a.0 as usize] {
        [b, a]
    } else {
        [a, b]
    }
}

struct Inputs<'a> {
    x: &'a [Vec3],
    v: &'a [Vec3],
    tag: &'a [i64],
    bonds: &'a [crate::engine::topology::Bond],
    prd: Vec3,
    eflag: bool,
}

/// What a pass over some bonds found besides forces: bonds that broke, and reference lengths
/// stored now (LAMMPS' store_bond for bonds created since the first evaluation).
#[derive(Clone, Debug, Default)]
struct Found {
    broken: Vec<Broken>,
    stored: Vec<(u32, f64)>,
}

fn run_bonds(style: &BondBpmSpring, inp: &Inputs, entries: &[Entry<2>], shifts: bool, f: &mut AtomsMut<Vec3>, tally: &mut BondedTally, found: &mut Found) {
    for e in entries {
        let [(i1, s1), (i2, s2)] = ordered(e, inp.tag);
        let (p1, p2) = (image(inp.x, i1, s1, inp.prd, shifts), image(inp.x, i2, s2, inp.prd, shifts));
        let del = [p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]];
        let (v1, v2) = (inp.v[i1 as usize], inp.v[i2 as usize]);
        let dv = [v1[0] - v2[0], v1[1] - v2[1], v1[2] - v2[2]];
        let mut r0 = inp.bonds[e.rec as usize].r0;
        if r0 < EPSILON || r0.is_nan() {
            r0 = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
            found.stored.push((e.rec, r0));
        }
        let Some((fbond, energy)) = style.kernel(e.typ, r0, del, dv) else {
            found.broken.push(Broken { rec: e.rec, atoms: [i1, i2], x: [p1, p2] });
            continue;
        };
        let fa = &mut f[i1 as usize];
        for d in 0..3 {
            fa[d] += del[d] * fbond;
        }
        let fb = &mut f[i2 as usize];
        for d in 0..3 {
            fb[d] -= del[d] * fbond;
        }
        if inp.eflag {
            tally.ebond += energy;
            let v = bond_virial(del, fbond);
            for k in 0..6 {
                tally.virial[k] += v[k];
            }
        }
    }
}

/// The bond pass with bpm/spring: stores unset reference lengths, adds the forces of the intact
/// bonds (chunks on the slab schedule, then the leftovers) and returns the bonds that broke, in
/// list order. The caller removes them ([`remove_broken`]).
pub fn compute(state: &mut State, style: &BondBpmSpring, eflag: bool) -> Result<(BondedTally, Vec<Broken>), RunError> {
    let lists = &state.bonded_lists.bonds;
    if lists.is_empty() {
        return Ok((BondedTally::default(), vec![]));
    }
    let prd = state.domain.as_ref().unwrap().prd();
    let (x, tag) = (&state.atoms.x, &state.atoms.tag);
    // LAMMPS' store_data: every bond's r0 at the first evaluation of the style; later, bonds
    // whose r0 is unset store it when computed (run_bonds)
    if !style.stored.swap(true, Ordering::Relaxed) {
        for (e, shifts) in lists.entries.iter().map(|e| (e, false)).chain(lists.leftover.iter().map(|e| (e, true))) {
            let [(i1, s1), (i2, s2)] = ordered(e, tag);
            let (p1, p2) = (image(x, i1, s1, prd, shifts), image(x, i2, s2, prd, shifts));
            let del = [p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]];
            state.topo.bonds[e.rec as usize].r0 = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
        }
    }
    let mut f = std::mem::take(&mut state.atoms.f);
    let inp = Inputs { x, v: &state.atoms.v, tag, bonds: &state.topo.bonds, prd, eflag };
    let bounds = state.neighbor.list.bounds();
    assert!(lists.nchunks() + 1 <= bounds.len(), "bonded lists built on another neighbour list");
    let mut parts: Vec<(BondedTally, Found)> = vec![Default::default(); bounds.len() - 1];
    for parity in 0..2 {
        slab_phase(&bounds, parity, AtomsMut::new(&mut f), &mut parts, |c, mut f| {
            let mut out = (BondedTally::default(), Found::default());
            run_bonds(style, &inp, chunk(lists, c), false, &mut f, &mut out.0, &mut out.1);
            out
        });
    }
    let mut tally = BondedTally::default();
    let mut found = Found::default();
    for (t, p) in parts {
        tally.add(&t);
        found.broken.extend(p.broken);
        found.stored.extend(p.stored);
    }
    run_bonds(style, &inp, &lists.leftover, true, &mut AtomsMut::new(&mut f), &mut tally, &mut found);
    for (rec, r0) in found.stored {
        state.topo.bonds[rec as usize].r0 = r0;
    }
    let broken = found.broken;
    state.atoms.f = f;
    Ok((tally, broken))
}

/// The values of a broken-bond record (LAMMPS BondBPM::pack_*), at step `step`.
pub fn record(values: &[LocalValue], state: &State, b: &Broken) -> Vec<f64> {
    let [i, j] = b.atoms.map(|k| k as usize);
    let a = &state.atoms;
    values
        .iter()
        .map(|v| match *v {
            LocalValue::Id1 => a.tag[i] as f64,
            LocalValue::Id2 => a.tag[j] as f64,
            LocalValue::Time => state.step as f64,
            LocalValue::X(d) => (b.x[0][d] + b.x[1][d]) * 0.5,
            LocalValue::XRef(d) => {
                let r = a.field_values(X_REF[d]).expect("x/ref fields registered by bond_style");
                (r[i] + r[j]) * 0.5
            }
        })
        .collect()
}

/// Remove the broken bonds: their topology records, the 1-2 entries of their atoms' special
/// lists and the special bits of their neighbour-list entries (LAMMPS' fix
/// update/special/bonds), so the pair acts from the next force evaluation; the bonded lists
/// lose their entries and follow the records' new indices.
pub fn remove_broken(state: &mut State, broken: &[Broken]) {
    if broken.is_empty() {
        return;
    }
    let recs: Vec<usize> = broken.iter().map(|b| b.rec as usize).collect();
    let pairs: Vec<[i64; 2]> = recs.iter().map(|&k| state.topo.bonds[k].atoms).collect();
    // new index of each record: its old one less the removed records before it
    let mut index: Vec<Option<u32>> = vec![Some(0); state.topo.bonds.len()];
    for &k in &recs {
        index[k] = None;
    }
    let mut next = 0;
    for slot in index.iter_mut().flatten() {
        *slot = next;
        next += 1;
    }
    state.bonded_lists.bonds.retain_records(|rec| index[rec as usize]);
    state.topo.remove_bond_records(&recs);
    for &[p, q] in &pairs {
        state.special_table.remove_one_two(p, q);
    }
    let map = state.atoms.tag_map();
    for &[p, q] in &pairs {
        for (t, other) in [(p, q), (q, p)] {
            if let Some(i) = map.get(t) {
                state.neighbor.list.clear_special(i, |j| state.atoms.tag[j] == other);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::bonded::test_util::words;

    fn style(settings: &str, coeff: &str) -> BondBpmSpring {
        let mut s = BondBpmSpring::default();
        let w = words(settings);
        s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap();
        s.set_types(1);
        let w = words(coeff);
        s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).unwrap();
        s
    }

    /// One bond in real LAMMPS 22 Jul 2025 (`newton on off`, pair_style zero): atoms at (0,0,0)
    /// and (1, 0.1, 0) for the first `run 0` (which stores r0), then atom 2 moved to `x2`,
    /// v1 = (0.1, 0.2, -0.1), v2 = (0.3, -0.1, 0.05) and `run 0` again: the force on atom 1 and
    /// ebond (normalised by the 2 atoms, lj units), printed with %.17g. bond_coeff 1 2.0 0.3 0.5.
    #[test]
    fn matches_lammps_bit_for_bit() {
        #[rustfmt::skip]
        let cases: [(&str, Vec3, Vec3, f64); 6] = [
            ("smooth yes", [1.1, 0.15, 0.02], [0.28812122379427496, 0.039289257790128394, 0.0052385677053504529], 0.0055517071435228858),
            ("smooth yes", [0.85, -0.05, 0.1], [-0.17657731312415673, 0.01038690077200922, -0.020773801544018439], 0.010902646243618046),
            ("smooth no", [1.1, 0.15, 0.02], [0.28818538057892013, 0.039298006442580018, 0.0052397341923440021], 0.0055517071435228858),
            ("smooth no", [0.85, -0.05, 0.1], [-0.17716394746374067, 0.010421408674337688, -0.020842817348675376], 0.010902646243618046),
            ("normalize yes", [1.1, 0.15, 0.02], [0.28708532348637011, 0.039147998657232279, 0.0052197331542976379], 0.0055241550769597374),
            ("normalize yes", [0.85, -0.05, 0.1], [-0.17512896354970317, 0.010301703738217835, -0.020603407476435669], 0.010848538484103195),
        ];
        let r0 = {
            let d: Vec3 = [0.0 - 1.0, 0.0 - 0.1, 0.0 - 0.0];
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        };
        for (settings, x2, f1, e) in cases {
            let s = style(settings, "2.0 0.3 0.5");
            let del = [0.0 - x2[0], 0.0 - x2[1], 0.0 - x2[2]];
            let dv = [0.1 - 0.3, 0.2 - -0.1, -0.1 - 0.05];
            let (fbond, energy) = s.kernel(1, r0, del, dv).unwrap();
            let f = del.map(|d| 0.0 + d * fbond);
            assert_eq!(f.map(f64::to_bits), f1.map(f64::to_bits), "{settings} {x2:?}: {f:?} vs {f1:?}");
            assert_eq!((energy / 2.0).to_bits(), e.to_bits(), "{settings} {x2:?}: energy {energy} vs 2 x {e}");
        }
    }

    #[test]
    fn breaks_beyond_the_critical_strain_only() {
        let s = style("", "2.0 0.3 0.5");
        assert!(s.kernel(1, 1.0, [1.29, 0.0, 0.0], [0.0; 3]).is_some());
        assert!(s.kernel(1, 1.0, [1.31, 0.0, 0.0], [0.0; 3]).is_none());
        assert!(s.kernel(1, 1.0, [0.69, 0.0, 0.0], [0.0; 3]).is_none());
        let s = style("break no smooth no", "2.0 0.3 0.5");
        assert!(s.kernel(1, 1.0, [1.5, 0.0, 0.0], [0.0; 3]).is_some());
    }

    #[test]
    fn settings_errors_are_located() {
        let mut s = BondBpmSpring::default();
        let w = words("break no");
        let e = s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert!(e.message.contains("must turn off smoothing"), "{e}");
        let mut s = BondBpmSpring::default();
        let w = words("store/local brk 100 bogus");
        let e = s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert!(e.message.contains("at least one value"), "{e}");
        let mut s = BondBpmSpring::default();
        let w = words("smooth maybe");
        let e = s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert_eq!(e.primary_span().unwrap().lo, 7);
        let mut s = BondBpmSpring::default();
        let w = words("store/local brk 100 time id1 id2 overlay/pair yes");
        s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap();
        let sl = s.store_local.as_ref().unwrap();
        assert_eq!((sl.fix_id.as_str(), sl.every), ("brk", 100));
        assert_eq!(sl.values, vec![LocalValue::Time, LocalValue::Id1, LocalValue::Id2]);
        assert!(s.overlay);
    }
}
