//! What LAMMPS' BPM bond styles share (src/BPM/bond_bpm.cpp and fix bond/history): the
//! `bond_style` keywords `store/local`, `overlay/pair` and `break`, the checks before a run, the
//! per-bond reference state stored at the first force evaluation, the pass over the bonds
//! (forces, torques for the styles that have them, breaking) and what happens to a broken bond.
//! A style (bpm/spring, bpm/rotational) brings only its kernel ([`BpmStyle`]).
//!
//! Each bond's reference state lives in its topology record (`Bond::history`, LAMMPS'
//! bondstore): stored for every bond at the first evaluation after `bond_style`, and for a bond
//! found unset later (created since) when it is first computed. A broken bond is removed from
//! the topology, and the pair between its atoms turns on from the next step: LAMMPS' fix
//! update/special/bonds removes the 1-2 entry from both special lists and clears the special
//! bits of the pair's neighbour entries; dmhs does the same to its special table and neighbour
//! list, so no list is rebuilt. `store/local FIXID N values...` records every broken bond
//! (`id1 id2 time x y z x/ref y/ref z/ref`) in fix FIXID (see
//! `crate::models::fix::store_local`), created by the `bond_style` command.

use super::{Vec3, Virial};
use crate::engine::bonded_lists::{chunk, Entry};
use crate::engine::fields::Field;
use crate::engine::par::{slab_phase, AtomsMut};
use crate::engine::state::{RunError, State};
use crate::engine::topology::BOND_HISTORY;
use crate::models::bonded::pass::BondedTally;
use dmhs_parser::{Args, DResult, Span, Word};

use std::sync::atomic::{AtomicBool, Ordering};

/// LAMMPS' EPSILON below which a stored reference length counts as unset.
const EPSILON: f64 = 1e-10;

/// Reference positions for `x/ref y/ref z/ref` (LAMMPS' property/atom d_BPM_X_REF ...), the
/// positions when `bond_style` was given. Bonds read them on their owned atoms (a LAMMPS ghost
/// has its owner's value), so ghosts need none.
pub const X_REF: [Field; 3] =
    [Field { name: "BPM_X_REF", ghosts: false }, Field { name: "BPM_Y_REF", ghosts: false }, Field { name: "BPM_Z_REF", ghosts: false }];

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

/// The settings every BPM bond style has (LAMMPS BondBPM), and its stored flag.
#[derive(Debug)]
pub struct Bpm {
    pub overlay: bool,
    pub break_bonds: bool,
    pub store_local: Option<StoreLocal>,
    /// LAMMPS' `stored_flag` of the style's bond history: every bond's reference state is
    /// (re)stored at the first force evaluation after the style was defined.
    stored: AtomicBool,
}

impl Default for Bpm {
    fn default() -> Self {
        Bpm { overlay: false, break_bonds: true, store_local: None, stored: AtomicBool::new(false) }
    }
}

/// LAMMPS `utils::logical`.
pub fn logical(a: &mut Args, what: &str) -> DResult<bool> {
    Ok(a.choice(what, &["no", "yes", "off", "on", "false", "true", "0", "1"])? % 2 == 1)
}

/// The keywords of [`Bpm::keyword`], for "did you mean" lists.
pub const KEYWORDS: [&str; 3] = ["store/local", "overlay/pair", "break"];

impl Bpm {
    /// A keyword of LAMMPS' BondBPM::settings, `w` already taken from `a`: `Ok(false)` when `w`
    /// is not one (the style's own keywords).
    pub fn keyword(&mut self, w: &Word, a: &mut Args) -> DResult<bool> {
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
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// LAMMPS' BondBPM::init_style checks.
    pub fn check(&self, state: &State, many_body: bool) -> Result<(), String> {
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
        Ok(())
    }
}

/// The per-atom arrays a BPM kernel reads (owned atoms; empty where the atom style has none).
pub struct BpmAtoms<'a> {
    pub v: &'a [Vec3],
    pub omega: &'a [Vec3],
    pub quat: &'a [[f64; 4]],
}

/// What one intact bond adds: `f1` to atom 1 (the lower ID), `-f1` to atom 2 (subtracted, as
/// LAMMPS does, which gives the same bits), torques `t1`, `t2` (styles with
/// [`BpmStyle::TORQUES`]), its energy and virial.
#[derive(Clone, Copy, Debug, Default)]
pub struct BondOut {
    pub f1: Vec3,
    pub t1: Vec3,
    pub t2: Vec3,
    pub energy: f64,
    pub virial: Virial,
}

/// A BPM bond style: the shared settings and its kernel.
pub trait BpmStyle: Sync {
    /// The style adds torques (the atoms have a torque array).
    const TORQUES: bool;
    fn bpm(&self) -> &Bpm;
    /// The reference state of a bond from `del = x1 - x2` (atom 1 the lower ID); element 0 is
    /// the reference length.
    fn reference(&self, del: Vec3) -> [f64; BOND_HISTORY];
    /// One bond of type `btype` with reference state `hist`, atoms `i1` (the lower ID) and
    /// `i2`, `del = x1 - x2`. `None`: the bond breaks.
    fn bond(&self, btype: usize, hist: &[f64; BOND_HISTORY], i1: usize, i2: usize, del: Vec3, atoms: &BpmAtoms) -> Option<BondOut>;
}

/// The side of [`BpmStyle`] the engine calls through a `dyn BondStyle`
/// (`BondStyle::as_bpm`): one monomorphised pass per style.
pub trait BpmPass: Sync {
    fn shared(&self) -> &Bpm;
    fn compute(&self, state: &mut State, eflag: bool) -> Result<(BondedTally, Vec<Broken>), RunError>;
}

impl<S: BpmStyle> BpmPass for S {
    fn shared(&self) -> &Bpm {
        BpmStyle::bpm(self)
    }
    fn compute(&self, state: &mut State, eflag: bool) -> Result<(BondedTally, Vec<Broken>), RunError> {
        compute(state, self, eflag)
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
    atoms: BpmAtoms<'a>,
    tag: &'a [i64],
    bonds: &'a [crate::engine::topology::Bond],
    prd: Vec3,
    eflag: bool,
}

/// What a pass over some bonds found besides forces: bonds that broke, and reference states
/// stored now (LAMMPS' store_bond for bonds created since the first evaluation).
#[derive(Clone, Debug, Default)]
struct Found {
    broken: Vec<Broken>,
    stored: Vec<(u32, [f64; BOND_HISTORY])>,
}

fn run_bonds<S: BpmStyle>(style: &S, inp: &Inputs, entries: &[Entry<2>], shifts: bool, (f, t): &mut (AtomsMut<Vec3>, AtomsMut<Vec3>), tally: &mut BondedTally, found: &mut Found) {
    for e in entries {
        let [(i1, s1), (i2, s2)] = ordered(e, inp.tag);
        let (p1, p2) = (image(inp.x, i1, s1, inp.prd, shifts), image(inp.x, i2, s2, inp.prd, shifts));
        let del = [p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]];
        let mut hist = inp.bonds[e.rec as usize].history;
        if hist[0] < EPSILON || hist[0].is_nan() {
            hist = style.reference(del);
            found.stored.push((e.rec, hist));
        }
        let Some(out) = style.bond(e.typ, &hist, i1 as usize, i2 as usize, del, &inp.atoms) else {
            found.broken.push(Broken { rec: e.rec, atoms: [i1, i2], x: [p1, p2] });
            continue;
        };
        let fa = &mut f[i1 as usize];
        for d in 0..3 {
            fa[d] += out.f1[d];
        }
        let fb = &mut f[i2 as usize];
        for d in 0..3 {
            fb[d] -= out.f1[d];
        }
        if S::TORQUES {
            let ta = &mut t[i1 as usize];
            for d in 0..3 {
                ta[d] += out.t1[d];
            }
            let tb = &mut t[i2 as usize];
            for d in 0..3 {
                tb[d] += out.t2[d];
            }
        }
        if inp.eflag {
            tally.ebond += out.energy;
            for k in 0..6 {
                tally.virial[k] += out.virial[k];
            }
        }
    }
}

/// The bond pass of a BPM style: stores unset reference states, adds the forces (and torques)
/// of the intact bonds (chunks on the slab schedule, then the leftovers) and returns the bonds
/// that broke, in list order. The caller removes them ([`remove_broken`]).
pub fn compute<S: BpmStyle>(state: &mut State, style: &S, eflag: bool) -> Result<(BondedTally, Vec<Broken>), RunError> {
    let lists = &state.bonded_lists.bonds;
    if lists.is_empty() {
        return Ok((BondedTally::default(), vec![]));
    }
    let prd = state.domain.as_ref().unwrap().prd();
    let (x, tag) = (&state.atoms.x, &state.atoms.tag);
    // LAMMPS' store_data: every bond's reference at the first evaluation of the style; later,
    // bonds whose reference is unset store it when computed (run_bonds)
    if !style.bpm().stored.swap(true, Ordering::Relaxed) {
        for (e, shifts) in lists.entries.iter().map(|e| (e, false)).chain(lists.leftover.iter().map(|e| (e, true))) {
            let [(i1, s1), (i2, s2)] = ordered(e, tag);
            let (p1, p2) = (image(x, i1, s1, prd, shifts), image(x, i2, s2, prd, shifts));
            let del = [p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]];
            state.topo.bonds[e.rec as usize].history = style.reference(del);
        }
    }
    let mut f = std::mem::take(&mut state.atoms.f);
    let mut torque = std::mem::take(&mut state.atoms.torque);
    let a = &state.atoms;
    let inp = Inputs { x, atoms: BpmAtoms { v: &a.v, omega: &a.omega, quat: &a.quat }, tag, bonds: &state.topo.bonds, prd, eflag };
    let bounds = state.neighbor.list.bounds();
    assert!(lists.nchunks() + 1 <= bounds.len(), "bonded lists built on another neighbour list");
    let mut parts: Vec<(BondedTally, Found)> = vec![Default::default(); bounds.len() - 1];
    for parity in 0..2 {
        slab_phase(&bounds, parity, (AtomsMut::new(&mut f), AtomsMut::new(&mut torque)), &mut parts, |c, mut w| {
            let mut out = (BondedTally::default(), Found::default());
            run_bonds(style, &inp, chunk(lists, c), false, &mut w, &mut out.0, &mut out.1);
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
    run_bonds(style, &inp, &lists.leftover, true, &mut (AtomsMut::new(&mut f), AtomsMut::new(&mut torque)), &mut tally, &mut found);
    for (rec, hist) in found.stored {
        state.topo.bonds[rec as usize].history = hist;
    }
    state.atoms.f = f;
    state.atoms.torque = torque;
    if !found.broken.is_empty() && !style.bpm().break_bonds {
        return Err(RunError::new(state.step, "BPM bond broke with break no option"));
    }
    Ok((tally, found.broken))
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
