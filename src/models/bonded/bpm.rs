//! What LAMMPS' BPM bond styles share (src/BPM/bond_bpm.cpp and fix bond/history): the
//! `bond_style` keywords `store/local`, `overlay/pair` and `break`, the checks before a run, the
//! per-bond reference state stored at the first force evaluation, the pass over the bonds
//! (forces, torques for the styles that have them, breaking) and what happens to a broken bond.
//! A style (bpm/spring, bpm/rotational) brings only its kernel ([`BpmStyle`]).
//!
//! Each bond's reference state lives in its topology record (`Bond::history`, LAMMPS'
//! bondstore): stored for every bond at the first evaluation after `bond_style`, and for a bond
//! found unset later (created since) when it is first computed. The LAMMPS-order list keeps a
//! copy next to each listed bond (`Listed::history`), which the pass reads in list order and
//! refreshes when it rewrites a record. A broken bond is removed from
//! the topology, and the pair between its atoms turns on from the next step: LAMMPS' fix
//! update/special/bonds removes the 1-2 entry from both special lists and clears the special
//! bits of the pair's neighbour entries; dmhs does the same to its special table and neighbour
//! list, so no list is rebuilt. `store/local FIXID N values...` records every broken bond
//! (`id1 id2 time x y z x/ref y/ref z/ref`) in fix FIXID (see
//! `crate::models::fix::store_local`), created by the `bond_style` command.

use crate::engine::domain::Periods;
use super::{Vec3, Virial};
use crate::engine::bonded_lists::{Entry, Listed};
use crate::engine::fields::Field;
use crate::engine::par::lanes::LANES;
use crate::engine::par::{ranges, AtomsMut};
use crate::engine::state::{RunError, State};
use crate::engine::topology::BOND_HISTORY;
use crate::models::bonded::pass::BondedTally;
use crate::engine::tally::PerAtomTally;
use dmhs_parser::{Args, DResult, Span, Word};

use std::sync::atomic::{AtomicBool, Ordering};

/// LAMMPS' EPSILON below which a stored reference length counts as unset.
const EPSILON: f64 = 1e-10;

/// Reference positions for `x/ref y/ref z/ref` (LAMMPS' property/atom d_BPM_X_REF ...), the
/// positions when `bond_style` was given. A LAMMPS ghost has its owner's value: ghosts carry
/// them (a distributed run's broken bond may have its second atom on another rank).
pub const X_REF: [Field; 3] =
    [Field { name: "BPM_X_REF", ghosts: true }, Field { name: "BPM_Y_REF", ghosts: true }, Field { name: "BPM_Z_REF", ghosts: true }];

/// The per-atom volumes of bpm/spring's `volume/factor yes` (LAMMPS' property/atom d_vol and
/// d_vol0): the sum over an atom's bonds of the current (VOL) and reference (VOL0) lengths cubed
/// (squared in 2D). A periodic image reads its atom's values (measured against LAMMPS: its ghosts
/// see vol0 as soon as a broken bond left it).
pub const VOL: Field = Field { name: "BPM_VOL", ghosts: false };
pub const VOL0: Field = Field { name: "BPM_VOL0", ghosts: false };
pub const VOLUMES: [Field; 2] = [VOL, VOL0];

/// The volume sums of one bond's two atoms, `V_1 + V_2` and `V0_1 + V0_2`, and 1 / dimension.
#[derive(Clone, Copy, Debug)]
pub struct VolSums {
    pub vol: f64,
    pub vol0: f64,
    pub invdim: f64,
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

/// The settings every BPM bond style has (LAMMPS BondBPM), and its stored flag.
#[derive(Debug)]
pub struct Bpm {
    pub overlay: bool,
    pub break_bonds: bool,
    /// `smooth` and `normalize` (each style reads them its own way).
    pub smooth: bool,
    pub normalize: bool,
    /// bpm/spring's `volume/factor yes` (the per-atom volumes [`VOL`], [`VOL0`]).
    pub volume: bool,
    pub store_local: Option<StoreLocal>,
    /// LAMMPS' `stored_flag` of the style's bond history: every bond's reference state is
    /// (re)stored at the first force evaluation after the style was defined.
    stored: AtomicBool,
}

impl Default for Bpm {
    fn default() -> Self {
        Bpm { overlay: false, break_bonds: true, smooth: true, normalize: false, volume: false, store_local: None, stored: AtomicBool::new(false) }
    }
}

/// LAMMPS `utils::logical`.
pub fn logical(a: &mut Args, what: &str) -> DResult<bool> {
    Ok(a.choice(what, &["no", "yes", "off", "on", "false", "true", "0", "1"])? % 2 == 1)
}

/// The keywords of [`Bpm::keyword`], for "did you mean" lists.
const KEYWORDS: [&str; 5] = ["store/local", "overlay/pair", "break", "smooth", "normalize"];

impl Bpm {
    /// Every bond's reference state has been stored (LAMMPS' `stored_flag`).
    pub fn is_stored(&self) -> bool {
        self.stored.load(Ordering::Relaxed)
    }

    /// The reference states came from a restart file (LAMMPS' FixBondHistory::restart).
    pub fn set_stored(&self) {
        self.stored.store(true, Ordering::Relaxed);
    }

    /// The arguments of `bond_style`: LAMMPS' BondBPM::settings, `smooth` and `normalize`, and
    /// the style's own keywords `own` (`own(w, a)`, `w` taken from `a`: `Ok(false)` when `w` is
    /// not one of `own_names`). Smoothing without breaking is refused, as both styles do.
    pub fn settings(&mut self, a: &mut Args, own_names: &[&str], mut own: impl FnMut(&Word, &mut Args) -> DResult<bool>) -> DResult<()> {
        let words = a.remaining();
        while let Some(w) = a.peek() {
            a.skip(1);
            if !self.keyword(w, a)? && !own(w, a)? {
                let known: Vec<&str> = KEYWORDS.iter().chain(own_names).copied().collect();
                return Err(a.unknown_keyword(w, &known));
            }
        }
        if self.smooth && !self.break_bonds {
            let w = words.iter().rev().find(|w| w.text == "break").expect("break no was given");
            return Err(a.error_at(w, "Illegal bond bpm command, must turn off smoothing with break no option", "add smooth no"));
        }
        Ok(())
    }

    /// One keyword of [`Bpm::settings`], `w` already taken from `a`: `Ok(false)` when `w` is
    /// not one.
    fn keyword(&mut self, w: &Word, a: &mut Args) -> DResult<bool> {
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
    /// A new reference state the bond keeps (bpm/spring/plastic's plastic strain), written
    /// after the pass.
    pub history: Option<[f64; BOND_HISTORY]>,
}

/// The `BondStyle` methods every BPM style spells the same way (in its `impl BondStyle`): the
/// coefficient table is `self.types`, the checks before a run `self.check`; the forces come
/// from the BPM pass, not from `compute`.
#[macro_export]
macro_rules! bpm_bond_style_common {
    () => {
        fn set_types(&mut self, n: usize) {
            self.types.resize(n);
        }
        fn check_all_set(&self) -> Result<(), String> {
            self.types.check_all_set("Bond")
        }
        fn compute(&self, _btype: usize, _del: $crate::models::bonded::Vec3, _rsq: f64) -> (f64, f64) {
            unreachable!("a BPM style runs the BPM pass (bpm::compute)")
        }
        fn equilibrium_distance(&self, _btype: usize) -> f64 {
            // LAMMPS estimates the longest stored r0 times the largest stretch; dmhs bonds take
            // the closest image, so the estimate would only feed the stability checks
            0.0
        }
        fn init(&self, state: &$crate::engine::state::State, many_body: bool) -> Result<(), String> {
            self.check(state, many_body)
        }
        fn as_bpm(&self) -> Option<&dyn $crate::models::bonded::bpm::BpmPass> {
            Some(self)
        }
    };
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
    /// `i2`, `del = x1 - x2`. `None`: the bond breaks (never with `break no`).
    fn bond(&self, btype: usize, hist: &[f64; BOND_HISTORY], i1: usize, i2: usize, del: Vec3, atoms: &BpmAtoms) -> Option<BondOut>;
    /// The style evaluates [`LANES`] bonds at once ([`BpmStyle::bonds`]).
    const LANE_KERNEL: bool = false;
    /// Bonds `b[..n]` (n <= [`LANES`]) at once, each as [`BpmStyle::bond`] gives it, handed to
    /// `emit(l, out)` in order. Called only for a style with [`BpmStyle::LANE_KERNEL`].
    fn bonds(&self, b: &[BondIn; LANES], n: usize, atoms: &BpmAtoms, mut emit: impl FnMut(usize, Option<BondOut>)) {
        for (l, b) in b.iter().enumerate().take(n) {
            emit(l, self.bond(b.typ, &b.hist, b.i1, b.i2, b.del, atoms));
        }
    }
    /// [`BpmStyle::bond`] with the volume sums of its atoms (styles with `volume/factor yes`).
    #[allow(clippy::too_many_arguments)]
    fn bond_volume(&self, btype: usize, hist: &[f64; BOND_HISTORY], i1: usize, i2: usize, del: Vec3, atoms: &BpmAtoms, _vol: VolSums) -> Option<BondOut> {
        self.bond(btype, hist, i1, i2, del, atoms)
    }
}

/// One bond as [`BpmStyle::bond`] takes it: type, reference state, atoms (`i1` the lower ID),
/// `del = x1 - x2`.
#[derive(Clone, Copy, Debug, Default)]
pub struct BondIn {
    pub typ: usize,
    pub hist: [f64; BOND_HISTORY],
    pub i1: usize,
    pub i2: usize,
    pub del: Vec3,
}

/// The side of [`BpmStyle`] the engine calls through a `dyn BondStyle`
/// (`BondStyle::as_bpm`): one monomorphised pass per style.
pub trait BpmPass: Sync {
    fn shared(&self) -> &Bpm;
    /// `peratom`: the per-atom tallies to add each bond's halves to (compute pe/atom, stress/atom).
    fn compute(&self, state: &mut State, eflag: bool, peratom: Option<&mut PerAtomTally>) -> Result<(BondedTally, Vec<Broken>), RunError>;
}

impl<S: BpmStyle> BpmPass for S {
    fn shared(&self) -> &Bpm {
        BpmStyle::bpm(self)
    }
    fn compute(&self, state: &mut State, eflag: bool, peratom: Option<&mut PerAtomTally>) -> Result<(BondedTally, Vec<Broken>), RunError> {
        compute(state, self, eflag, peratom)
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

/// Serial LAMMPS' bond list (Neighbor::bond_all): the owned atoms in LAMMPS' local order, each
/// atom's bonds in its own list's order ([`Bond::slots`]); with `newton_bond off` a bond is
/// listed by its atom of lower local index (a bond to a periodic image by both atoms), with
/// `newton_bond on` by its first atom, the only one that stores it. The
/// forces of the BPM styles are summed in this order: their shear angle is an `acos` near 1,
/// which turns a last-bit difference of a sum into a difference of 1e-8 at the next step.
///
/// [`Bond::slots`]: crate::engine::topology::Bond::slots
pub fn lammps_bond_list(state: &State, bonds: &[Entry<2>]) -> Vec<Listed> {
    let nlocal = state.atoms.nlocal;
    let mut lidx = vec![0u32; nlocal];
    for (k, &i) in state.lammps_order.indices(nlocal).iter().enumerate() {
        lidx[i] = k as u32;
    }
    let mut keyed: Vec<((u32, u32), Listed)> = Vec::with_capacity(bonds.len());
    for e in bonds {
        let rec = &state.topo.bonds[e.rec as usize];
        let (slots, history) = (rec.slots, rec.history);
        let [a, b] = e.atoms.map(|i| i as usize);
        if state.newton_bond {
            // each bond lives on its first atom only, which lists it
            keyed.push(((lidx[a], slots[0]), Listed { entry: *e, apply: [true, true], history }));
        } else if e.shifted() {
            keyed.push(((lidx[a], slots[0]), Listed { entry: *e, apply: [true, false], history }));
            let back = e.shift[1].map(|c| -c);
            keyed.push(((lidx[b], slots[1]), Listed { entry: Entry { shift: [back, [0; 3]], ..*e }, apply: [false, true], history }));
        } else {
            let key = if lidx[a] < lidx[b] { (lidx[a], slots[0]) } else { (lidx[b], slots[1]) };
            keyed.push((key, Listed { entry: *e, apply: [true, true], history }));
        }
    }
    keyed.sort_unstable_by_key(|k| k.0);
    keyed.into_iter().map(|k| k.1).collect()
}

/// A distributed run's BPM bond list: each rank lists, as LAMMPS does with `newton_bond off`,
/// every bond with an owned atom, its partner at the local copy (owned or ghost) closest to that
/// atom. A bond whose atoms are both owned here is listed once and both take its forces; a bond
/// to a ghost (an atom of another rank, or a periodic image) is listed by its owned atom, which
/// alone takes them. The rank that owns the other atom lists the same bond with the same
/// positions (a ghost is its owner's copy), so both compute the same bits, and see it break at
/// the same step. Order as [`lammps_bond_list`], in this rank's LAMMPS order.
pub fn rank_bond_list(state: &State, copies: &crate::models::bonded::pass::Copies) -> Result<Vec<Listed>, RunError> {
    let (a, nlocal) = (&state.atoms, state.atoms.nlocal);
    let map = a.tag_map();
    let mut lidx = vec![0u32; nlocal];
    for (k, &i) in state.lammps_order.indices(nlocal).iter().enumerate() {
        lidx[i] = k as u32;
    }
    let mut keyed: Vec<((u32, u32), Listed)> = vec![];
    for (rec, b) in state.topo.bonds.iter().enumerate().filter(|(_, b)| !b.off) {
        let own = b.atoms.map(|t| map.get(t));
        for k in 0..2 {
            let Some(o) = own[k] else { continue };
            let other = copies.closest(b.atoms[1 - k], a.x[o]).ok_or_else(|| crate::models::bonded::pass::missing_partner(state.step, "bond", b.atoms[1 - k], &b.atoms))? as usize;
            let mut atoms = [0u32; 2];
            (atoms[k], atoms[1 - k]) = (o as u32, other as u32);
            let entry = Entry { atoms, shift: [[0; 3]; 2], typ: b.typ, rec: rec as u32 };
            if other < nlocal {
                // both owned: listed once, from the first atom's side
                if k == 0 {
                    let key = if lidx[o] < lidx[other] { (lidx[o], b.slots[0]) } else { (lidx[other], b.slots[1]) };
                    keyed.push((key, Listed { entry, apply: [true, true], history: b.history }));
                }
            } else {
                let mut apply = [false; 2];
                apply[k] = true;
                keyed.push(((lidx[o], b.slots[k]), Listed { entry, apply, history: b.history }));
            }
        }
    }
    keyed.sort_unstable_by_key(|k| k.0);
    Ok(keyed.into_iter().map(|k| k.1).collect())
}

/// Position of atom `i` at periodic shift `s` (LAMMPS' ghost copy `x + s L`).
#[inline(always)]
fn image(x: &[Vec3], i: u32, s: [i8; 3], periods: Periods) -> Vec3 {
    periods.shifted(x[i as usize], s)
}

/// A listed bond's atoms as LAMMPS computes it, the lower ID first, their positions and
/// `del = x1 - x2`; `swapped`: atom 1 is the entry's second atom.
#[inline(always)]
fn ordered(e: &Entry<2>, x: &[Vec3], tag: &[i64], periods: Periods) -> ([u32; 2], [Vec3; 2], Vec3, bool) {
    let swapped = tag[e.atoms[1] as usize] < tag[e.atoms[0] as usize];
    let (a, b) = if swapped { (1, 0) } else { (0, 1) };
    let (p1, p2) = (image(x, e.atoms[a], e.shift[a], periods), image(x, e.atoms[b], e.shift[b], periods));
    ([e.atoms[a], e.atoms[b]], [p1, p2], [p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]], swapped)
}

/// One listed bond evaluated: its atoms (lower ID first) and their positions, the reference
/// state stored now if it was unset (LAMMPS' store_bond for bonds created since the first
/// evaluation), and what it adds (`None`: it breaks).
#[derive(Clone, Copy, Default)]
struct Done {
    atoms: [u32; 2],
    x: [Vec3; 2],
    swapped: bool,
    /// The reference length the bond was computed with.
    r0: f64,
    stored: Option<[f64; BOND_HISTORY]>,
    out: Option<BondOut>,
}

/// Bonds evaluated per thread in a block (in four parallel tasks: `ranges` shares a loop of
/// four or more).
const CHUNK: usize = 1024;
/// Bonds evaluated in a block on one thread.
const ALONE: usize = 64;

/// The bond pass of a BPM style: stores unset reference states, evaluates the bonds (in
/// parallel) and adds their forces, torques, energies and virials in serial LAMMPS' order
/// ([`lammps_bond_list`]), so the sums have LAMMPS' bits. Returns the bonds that broke, in that
/// order; the caller removes them ([`remove_broken`]).
pub fn compute<S: BpmStyle>(state: &mut State, style: &S, eflag: bool, mut peratom: Option<&mut PerAtomTally>) -> Result<(BondedTally, Vec<Broken>), RunError> {
    let distributed = state.distributed.is_some();
    // (every rank of a distributed run takes part in the exchange after the pass)
    if state.bonded_lists.lammps_bonds.is_empty() && !distributed {
        return Ok((BondedTally::default(), vec![]));
    }
    let periods = state.domain.as_ref().unwrap().periods();
    // the records whose reference state the pass rewrote (their list copies follow after it)
    let mut rewritten: Option<Vec<bool>> = None;
    // LAMMPS' store_data: every bond's reference at the first evaluation of the style
    let first = !style.bpm().stored.swap(true, Ordering::Relaxed);
    if first {
        for l in &state.bonded_lists.lammps_bonds {
            let (_, _, del, _) = ordered(&l.entry, &state.atoms.x, &state.atoms.tag, periods);
            state.topo.bonds[l.entry.rec as usize].history = style.reference(del);
        }
        // a bond to a periodic image is listed twice: the record keeps the last one's
        sync_history(state, None);
        if distributed {
            let mut all = vec![false; state.topo.bonds.len()];
            state.bonded_lists.lammps_bonds.iter().for_each(|l| all[l.entry.rec as usize] = true);
            rewritten = Some(all);
        }
    }
    let list = &state.bonded_lists.lammps_bonds;
    let (x, tag) = (&state.atoms.x, &state.atoms.tag);
    let mut vols = style.bpm().volume.then(|| volumes(state, list, periods, first));
    let atoms = BpmAtoms { v: &state.atoms.v, omega: &state.atoms.omega, quat: &state.atoms.quat };
    let mut f = std::mem::take(&mut state.atoms.f);
    let mut torque = std::mem::take(&mut state.atoms.torque);
    let mut tally = BondedTally::default();
    let mut broken: Vec<Broken> = vec![];
    // LAMMPS' ev_tally: with newton_bond off, half to each owned atom (a distributed run lists
    // its bonds as with newton_bond off whatever the setting)
    let newton = state.newton_bond && !distributed;
    let part = if newton { 1.0 } else { 0.5 };
    // LAMMPS' dvol0: a broken bond's reference volume leaves its atoms' vol0 after the pass
    let mut dvol0 = SideSums::new(if vols.is_some() { state.atoms.nlocal } else { 0 });
    // the bonds are evaluated (in parallel) and added (in order) a block at a time, so the
    // evaluated bonds are read back from cache, not from memory
    // (one thread: a block small enough that the evaluated bonds stay in the first-level cache)
    let block = match crate::engine::par::threads() {
        1 => ALONE,
        t => CHUNK * t,
    };
    let mut buf = vec![Done::default(); block.min(list.len())];
    for part_list in list.chunks(block) {
        let done = &mut buf[..part_list.len()];
        // a listed bond's atoms (lower ID first), their positions, `del`, whether swapped, its
        // reference state (stored now if it was unset)
        let prep = |l: &Listed| {
            let (i, p, del, swapped) = ordered(&l.entry, x, tag, periods);
            let mut hist = l.history;
            let mut stored = None;
            if hist[0] < EPSILON || hist[0].is_nan() {
                hist = style.reference(del);
                stored = Some(hist);
            }
            (i, p, del, swapped, hist, stored)
        };
        ranges(part_list.len(), CHUNK / 4, AtomsMut::new(done), |r, mut w| {
            if !S::LANE_KERNEL || vols.is_some() {
                for k in r {
                    let (i, p, del, swapped, hist, stored) = prep(&part_list[k]);
                    let typ = part_list[k].entry.typ;
                    let out = match &vols {
                        None => style.bond(typ, &hist, i[0] as usize, i[1] as usize, del, &atoms),
                        Some(v) => {
                            let [i1, i2] = i.map(|k| k as usize);
                            let sums = VolSums { vol: v.vol[i1] + v.vol[i2], vol0: v.vol0[i1] + v.vol0[i2], invdim: v.invdim };
                            style.bond_volume(typ, &hist, i1, i2, del, &atoms, sums)
                        }
                    };
                    w[k] = Done { atoms: i, x: p, swapped, r0: hist[0], stored, out };
                }
                return;
            }
            // LANES bonds at a time through the style's lane kernel
            let mut k = r.start;
            while k < r.end {
                let n = (r.end - k).min(LANES);
                let mut ins = [BondIn::default(); LANES];
                let mut seen = [([0u32; 2], [[0.0; 3]; 2], false, None); LANES];
                for j in 0..n {
                    let (i, p, del, swapped, hist, stored) = prep(&part_list[k + j]);
                    ins[j] = BondIn { typ: part_list[k + j].entry.typ, hist, i1: i[0] as usize, i2: i[1] as usize, del };
                    seen[j] = (i, p, swapped, stored);
                }
                style.bonds(&ins, n, &atoms, |j, out| {
                    let (atoms, x, swapped, stored) = seen[j];
                    w[k + j] = Done { atoms, x, swapped, r0: ins[j].hist[0], stored, out };
                });
                k += n;
            }
        });
        for (l, d) in part_list.iter().zip(done.iter()) {
            let rec = l.entry.rec;
            for h in [d.stored, d.out.and_then(|o| o.history)].into_iter().flatten() {
                state.topo.bonds[rec as usize].history = h;
                rewritten.get_or_insert_with(|| vec![false; state.topo.bonds.len()])[rec as usize] = true;
            }
            let Some(out) = d.out else {
                if vols.is_some() {
                    // LAMMPS subtracts (x - v is x + (-v), bit for bit)
                    dvol0.add(l, -bond_volume(d.r0 * d.r0, state.dimension, d.r0));
                }
                if !broken.iter().any(|b| b.rec == rec) {
                    broken.push(Broken { rec, atoms: d.atoms, x: d.x });
                }
                continue;
            };
            let apply = if d.swapped { [l.apply[1], l.apply[0]] } else { l.apply };
            let [i1, i2] = d.atoms.map(|i| i as usize);
            if apply[0] {
                f[i1].iter_mut().zip(out.f1).for_each(|(a, b)| *a += b);
                if S::TORQUES {
                    torque[i1].iter_mut().zip(out.t1).for_each(|(a, b)| *a += b);
                }
            }
            if apply[1] {
                f[i2].iter_mut().zip(out.f1).for_each(|(a, b)| *a -= b);
                if S::TORQUES {
                    torque[i2].iter_mut().zip(out.t2).for_each(|(a, b)| *a += b);
                }
            }
            if eflag {
                let sides = if newton { 1 } else { apply.iter().filter(|&&a| a).count() };
                for _ in 0..sides {
                    tally.ebond += part * out.energy;
                    for k in 0..6 {
                        tally.virial[k] += part * out.virial[k];
                    }
                }
                // LAMMPS' eatom and vatom: half to each atom of the bond (owned here)
                if let Some(pa) = peratom.as_deref_mut() {
                    let nlocal = pa.energy[PerAtomTally::BOND].len();
                    for (i, _) in [i1, i2].into_iter().zip(apply).filter(|&(i, a)| a && i < nlocal) {
                        pa.add(PerAtomTally::BOND, i, 0.5, out.energy, &out.virial);
                    }
                }
            }
        }
    }
    state.atoms.f = f;
    state.atoms.torque = torque;
    if distributed {
        share_histories(state, rewritten.as_deref())?;
    } else if let Some(changed) = rewritten {
        sync_history(state, Some(&changed));
    }
    if let Some(v) = vols.as_mut() {
        if !broken.is_empty() {
            v.vol0.iter_mut().zip(dvol0.finish()).for_each(|(a, d)| *a += d);
        }
        v.store(&mut state.atoms);
    }
    Ok((tally, broken))
}

/// Copy the records' reference states into the list's copies ([`Listed::history`]): all of
/// them, or those of the records marked in `changed`.
fn sync_history(state: &mut State, changed: Option<&[bool]>) {
    let bonds = &state.topo.bonds;
    for l in &mut state.bonded_lists.lammps_bonds {
        let rec = l.entry.rec as usize;
        if changed.is_none_or(|c| c[rec]) {
            l.history = bonds[rec].history;
        }
    }
}

/// The reference states the ranks of a distributed run stored or changed in this evaluation
/// (`changed`, by record), in every rank's topology: a bond's state then moves with no atom (a
/// rank that comes to own one of its atoms finds it there), and the end of the run leaves every
/// rank with all of them. Every rank holds the same topology, so records are named by index
/// (their atom IDs checked). A bond listed by two ranks is computed by both with the same bits;
/// if not (a bond across a periodic face, each side at its own image), the last rank's state
/// is kept everywhere.
fn share_histories(state: &mut State, changed: Option<&[bool]>) -> Result<(), RunError> {
    const W: usize = 3 + BOND_HISTORY;
    let mut mine: Vec<f64> = vec![];
    if let Some(c) = changed {
        for (rec, b) in state.topo.bonds.iter().enumerate().filter(|&(k, _)| c[k]) {
            mine.extend([rec as f64, b.atoms[0] as f64, b.atoms[1] as f64]);
            mine.extend_from_slice(&b.history);
        }
    }
    let all = state.allgather_ranks(mine);
    if all.is_empty() {
        return Ok(());
    }
    let mut changed = vec![false; state.topo.bonds.len()];
    for r in all.chunks_exact(W) {
        let rec = r[0] as usize;
        let b = state.topo.bonds.get_mut(rec).filter(|b| b.atoms == [r[1] as i64, r[2] as i64]);
        let Some(b) = b else {
            return Err(RunError::new(state.step, format!("the ranks' bond records differ at record {rec} (bond {} {})", r[1], r[2])));
        };
        b.history.copy_from_slice(&r[3..]);
        changed[rec] = true;
    }
    sync_history(state, Some(&changed));
    Ok(())
}

/// The per-atom volumes of one evaluation, owned atoms ([`VOL`], [`VOL0`]).
struct Volumes {
    vol: Vec<f64>,
    vol0: Vec<f64>,
    invdim: f64,
}

impl Volumes {
    fn store(&self, atoms: &mut crate::engine::atoms::Atoms) {
        let n = atoms.nlocal;
        for (field, values) in VOLUMES.into_iter().zip([&self.vol, &self.vol0]) {
            let k = atoms.add_field(field);
            atoms.extra[k].data[..n].copy_from_slice(&values[..n]);
        }
    }
}

/// A bond's share of an atom's volume from its squared length `rsq` and length `r` (LAMMPS:
/// rsq, times the length in 3D).
#[inline(always)]
fn bond_volume(rsq: f64, dim: usize, r: f64) -> f64 {
    if dim == 3 {
        rsq * r
    } else {
        rsq
    }
}

/// Sums over listed bonds onto their applied sides, in list order: owned sides directly,
/// periodic images (listed with `newton_bond on` only) each into its own sum, added to its owner
/// after all bonds (LAMMPS' reverse communication, images in the order first met).
struct SideSums {
    own: Vec<f64>,
    images: Vec<(u32, f64)>,
    index: std::collections::HashMap<(u32, [i8; 3]), usize>,
}

impl SideSums {
    fn new(n: usize) -> Self {
        SideSums { own: vec![0.0; n], images: vec![], index: Default::default() }
    }
    #[inline(always)]
    fn add(&mut self, l: &Listed, v: f64) {
        for k in 0..2 {
            let (a, s) = (l.entry.atoms[k], l.entry.shift[k]);
            if !l.apply[k] {
                continue;
            }
            if s == [0; 3] {
                self.own[a as usize] += v;
            } else {
                self.add_image(a, s, v);
            }
        }
    }
    #[inline(never)]
    fn add_image(&mut self, a: u32, s: [i8; 3], v: f64) {
        let n = self.images.len();
        let slot = *self.index.entry((a, s)).or_insert(n);
        if slot == n {
            self.images.push((a, 0.0));
        }
        self.images[slot].1 += v;
    }
    fn finish(mut self) -> Vec<f64> {
        for (a, v) in self.images {
            self.own[a as usize] += v;
        }
        self.own
    }
}

/// LAMMPS' calculate_vol over the listed bonds at the current positions: each atom's volume,
/// and the volumes of bonds whose reference is unset (created since), for vol0.
fn bond_volumes(state: &State, list: &[Listed], periods: Periods) -> (Vec<f64>, Option<Vec<f64>>) {
    let n = state.atoms.nlocal;
    let (mut vol, mut dvol0, mut created) = (SideSums::new(n), SideSums::new(n), false);
    for l in list {
        // the entry's own order: the squares of x1 - x2 and x2 - x1 have the same bits
        let (e, x) = (&l.entry, &state.atoms.x);
        let (p1, p2) = (image(x, e.atoms[0], e.shift[0], periods), image(x, e.atoms[1], e.shift[1], periods));
        let del = [p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]];
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        let v = bond_volume(rsq, state.dimension, rsq.sqrt());
        vol.add(l, v);
        let r0 = l.history[0];
        if r0 < EPSILON || r0.is_nan() {
            created = true;
            dvol0.add(l, v);
        }
    }
    (vol.finish(), created.then(|| dvol0.finish()))
}

/// The volumes of this evaluation: vol0 made at the first one, grown by bonds created since,
/// and vol now.
fn volumes(state: &State, list: &[Listed], periods: Periods, first: bool) -> Volumes {
    let a = &state.atoms;
    let saved = |f: Field| a.field_values(f).map(|v| v[..a.nlocal].to_vec()).unwrap_or_else(|| vec![0.0; a.nlocal]);
    let mut vol0 = if first { bond_volumes(state, list, periods).0 } else { saved(VOL0) };
    let (vol, dvol0) = bond_volumes(state, list, periods);
    if let Some(d) = dvol0 {
        vol0.iter_mut().zip(d).for_each(|(a, d)| *a += d);
    }
    Volumes { vol, vol0, invdim: 1.0 / state.dimension as f64 }
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
    remove_broken_records(state, broken.iter().map(|b| b.rec as usize).collect());
}

/// [`remove_broken`] of topology records `recs` (each once).
pub fn remove_broken_records(state: &mut State, recs: Vec<usize>) {
    if recs.is_empty() {
        return;
    }
    let pairs: Vec<[i64; 2]> = recs.iter().map(|&k| state.topo.bonds[k].atoms).collect();
    // new index of each record: its old one less the removed records before it
    let mut index: Vec<Option<u32>> = vec![Some(0); state.topo.bonds.len()];
    for &k in &recs {
        index[k] = None;
    }
    for (next, slot) in index.iter_mut().flatten().enumerate() {
        *slot = next as u32;
    }
    state.bonded_lists.bonds.retain_records(|rec| index[rec as usize]);
    state.bonded_lists.lammps_bonds.retain_mut(|l| match index[l.entry.rec as usize] {
        Some(rec) => {
            l.entry.rec = rec;
            true
        }
        None => false,
    });
    state.topo.release_bond_slots(&recs);
    state.topo.remove_bond_records(&recs);
    for &[p, q] in &pairs {
        state.special_table.remove_one_two(p, q);
    }
    // a distributed run's index of the records by atom moved with them
    state.stored_on = None;
    let map = state.atoms.tag_map();
    for &[p, q] in &pairs {
        for (t, other) in [(p, q), (q, p)] {
            if let Some(i) = map.get(t) {
                state.neighbor.list.clear_special(i, |j| state.atoms.tag[j] == other);
            }
        }
    }
}
