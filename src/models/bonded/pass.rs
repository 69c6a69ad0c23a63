//! The bonded pass: bonds, angles and dihedrals between owned atoms, each partner taken at
//! its periodic image closest to the atom LAMMPS stores the interaction on (atom 1 of a bond,
//! atom 2 of an angle or dihedral), with the image's coordinate computed as LAMMPS' ghost
//! copy is (`x + shift * L`), so displacements match LAMMPS bit for bit.

use crate::engine::domain::Periods;
use crate::models::bonded::{angle_virial, bond_virial, dihedral_virial, AngleStyle, BondStyle, DihedralStyle};
use crate::engine::par::lanes::{transpose4, L, LANES};
use crate::engine::par::{alone, slab_phase, window_phase, AtomsMut, PARALLEL_MIN_WORK};
use crate::engine::state::{RunError, State};
use crate::engine::bonded_lists::{chunk, slab, wide_chunk, BondedLists, Entry, Slabbed, WIDE};
use crate::engine::topology::StoredOn;

/// Energies and virial of the bonded pass.
#[derive(Clone, Copy, Debug, Default)]
pub struct BondedTally {
    pub ebond: f64,
    pub eangle: f64,
    pub edihed: f64,
    pub virial: [f64; 6],
}

/// The bonded styles of a simulation, as the pass reads them.
#[derive(Clone, Copy)]
pub struct BondedStyles<'a> {
    pub bond: Option<&'a dyn BondStyle>,
    pub angle: Option<&'a dyn AngleStyle>,
    pub dihedral: Option<&'a dyn DihedralStyle>,
}

impl<'a> BondedStyles<'a> {
    pub fn of(bond: &'a Option<Box<dyn BondStyle>>, angle: &'a Option<Box<dyn AngleStyle>>, dihedral: &'a Option<Box<dyn DihedralStyle>>) -> Self {
        BondedStyles { bond: bond.as_deref(), angle: angle.as_deref(), dihedral: dihedral.as_deref() }
    }
}

/// Checks before a run: every used type has coefficients; the special lists. Returns warnings
/// (interactions without a style).
pub fn init_bonded(state: &mut State, bond: Option<&mut Box<dyn BondStyle>>, angle: Option<&mut Box<dyn AngleStyle>>, dihedral: Option<&mut Box<dyn DihedralStyle>>) -> Result<Vec<String>, String> {
        let t = &state.topo;
        let (has_bond, has_angle, has_dihedral) = (bond.is_some(), angle.is_some(), dihedral.is_some());
        if let Some(s) = bond {
            s.set_types(t.nbondtypes);
            if t.nbondtypes > 0 {
                s.check_all_set()?;
            }
            s.init(state, angle.is_some() || dihedral.is_some())?;
        }
        if let Some(s) = angle {
            s.set_types(t.nangletypes);
            if t.nangletypes > 0 {
                s.check_all_set()?;
            }
        }
        if let Some(s) = dihedral {
            s.set_types(t.ndihedraltypes);
            if t.ndihedraltypes > 0 {
                s.check_all_set()?;
            }
        }
        let missing = |n: usize, style: bool, what: &str| -> Option<String> {
            (n > 0 && !style).then(|| format!("{n} {what}s are defined but no {what}_style is set"))
        };
        let warnings = [
            missing(t.bonds.len(), has_bond, "bond"),
            missing(t.angles.len(), has_angle, "angle"),
            missing(t.dihedrals.len(), has_dihedral, "dihedral"),
        ]
        .into_iter()
        .flatten()
        .collect();
        if !state.special_frozen {
            state.rebuild_special()?;
        }
        Ok(warnings)
}

/// Map every interaction to local indices and closest-image shifts (after a rebuild); only
/// the kinds that have a style.
pub fn build_bonded_lists(state: &mut State, styles: BondedStyles) -> Result<(), RunError> {
        let bpm = styles.bond.is_some_and(|s| s.as_bpm().is_some());
        if bpm {
            state.topo.assign_bond_slots();
        }
        let t = &state.topo;
        if t.is_empty() {
            state.bonded_lists = BondedLists::default();
            return Ok(());
        }
        if state.distributed.is_some() {
            return build_distributed(state, styles);
        }
        let map = state.atoms.tag_map();
        let domain = state.domain.as_ref().unwrap();
        let prd = domain.prd();
        let x = &state.atoms.x;
        let step = state.step;
        let find = |tag: i64| map.get(tag).map(|i| i as u32);
        // the error of a record whose atoms are not all here (the first missing one named)
        let missing = |tags: &[i64], what: &str| {
            let tag = tags.iter().find(|&&t| map.get(t).is_none()).copied().unwrap_or(0);
            RunError::new(step, format!("{what} atom {tag} is missing"))
        };
        // shift of atom `o` that brings it closest to atom `r`, per periodic dimension
        let closest = |r: usize, o: usize| -> [i8; 3] {
            if domain.triclinic() {
                return closest_tilted(domain, x[r], x[o]);
            }
            let mut s = [0i8; 3];
            for d in 0..3 {
                if domain.periodic(d) {
                    let dx = x[r][d] - x[o][d];
                    if dx > 0.5 * prd[d] {
                        s[d] = 1;
                    } else if dx < -0.5 * prd[d] {
                        s[d] = -1;
                    }
                }
            }
            s
        };
        let (mut bonds, mut angles, mut dihedrals) = (vec![], vec![], vec![]);
        if styles.bond.is_some() {
            bonds = in_blocks(&t.bonds, |rec, b| {
                let i = [find(b.atoms[0])?, find(b.atoms[1])?];
                Some(Entry { atoms: i, shift: [[0; 3], closest(i[0] as usize, i[1] as usize)], typ: b.typ, rec: rec as u32 })
            }, |b| b.off)
            .map_err(|rec| missing(&t.bonds[rec].atoms, "bond"))?;
        }
        if styles.angle.is_some() {
            angles = in_blocks(&t.angles, |rec, a| {
                let i = [find(a.atoms[0])?, find(a.atoms[1])?, find(a.atoms[2])?];
                let r = i[1] as usize;
                Some(Entry { atoms: i, shift: [closest(r, i[0] as usize), [0; 3], closest(r, i[2] as usize)], typ: a.typ, rec: rec as u32 })
            }, |a| a.off)
            .map_err(|rec| missing(&t.angles[rec].atoms, "angle"))?;
        }
        if styles.dihedral.is_some() {
            dihedrals = in_blocks(&t.dihedrals, |rec, d| {
                let i = [find(d.atoms[0])?, find(d.atoms[1])?, find(d.atoms[2])?, find(d.atoms[3])?];
                let r = i[1] as usize;
                let shift = [closest(r, i[0] as usize), [0; 3], closest(r, i[2] as usize), closest(r, i[3] as usize)];
                Some(Entry { atoms: i, shift, typ: d.typ, rec: rec as u32 })
            }, |d| d.off)
            .map_err(|rec| missing(&t.dihedrals[rec].atoms, "dihedral"))?;
        }
        let lammps_bonds = if bpm { crate::models::bonded::bpm::lammps_bond_list(state, &bonds.concat()) } else { vec![] };
        let old = std::mem::take(&mut state.bonded_lists);
        state.bonded_lists = slabbed(state, &bonds, &angles, &dihedrals, lammps_bonds, old);
        Ok(())
    }

/// `entry(rec, record)` of every record not `off`, in record order, made in blocks of records on
/// the team (the blocks' entries one after the other); `Err(rec)`: the first record without one.
fn in_blocks<R: Sync, E: Send>(records: &[R], entry: impl Fn(usize, &R) -> Option<E> + Sync, off: impl Fn(&R) -> bool + Sync) -> Result<Vec<Vec<E>>, usize> {
    const BLOCK: usize = 4096;
    let blocks: Vec<usize> = (0..records.len().div_ceil(BLOCK)).collect();
    crate::engine::par::team::map(blocks, |b| {
        let lo = b * BLOCK;
        let block = &records[lo..(lo + BLOCK).min(records.len())];
        let mut out = Vec::with_capacity(block.len());
        for (k, r) in block.iter().enumerate() {
            if !off(r) {
                out.push(entry(lo + k, r).ok_or(lo + k)?);
            }
        }
        Ok(out)
    })
    .into_iter()
    .collect()
}

/// The entries grouped by the chunks of the neighbour list (see [`slab`]).
/// `old`: the lists they replace (their memory is reused).
fn slabbed(state: &State, bonds: &[Vec<Entry<2>>], angles: &[Vec<Entry<3>>], dihedrals: &[Vec<Entry<4>>], lammps_bonds: Vec<crate::engine::bonded_lists::Listed>, old: BondedLists) -> BondedLists {
    let chunks = &state.neighbor.list.chunks;
    let mut chunk_of = vec![0u32; state.atoms.nlocal];
    for (c, ch) in chunks.iter().enumerate() {
        chunk_of[ch.start..ch.end].iter_mut().for_each(|x| *x = c as u32);
    }
    let n = chunks.len();
    // the three kinds on the team, each into its slot
    use std::sync::Mutex;
    let BondedLists { bonds: old_bonds, angles: old_angles, dihedrals: old_dihedrals, .. } = old;
    let slots = (Mutex::new(Some(old_bonds)), Mutex::new(Some(old_angles)), Mutex::new(Some(old_dihedrals)));
    fn redo<E: Copy, const N: usize>(slot: &Mutex<Option<Slabbed<E>>>, parts: &[Vec<E>], atoms: impl Fn(&E) -> [u32; N], shifted: impl Fn(&E) -> bool, chunk_of: &[u32], n: usize) {
        let mut slot = slot.lock().unwrap_or_else(|e| e.into_inner());
        let old = slot.take().unwrap_or_default();
        *slot = Some(slab(parts, atoms, shifted, chunk_of, n, old));
    }
    crate::engine::par::team::run(3, &|kind| match kind {
        0 => redo(&slots.0, bonds, |e: &Entry<2>| e.atoms, Entry::shifted, &chunk_of, n),
        1 => redo(&slots.1, angles, |e: &Entry<3>| e.atoms, Entry::shifted, &chunk_of, n),
        _ => redo(&slots.2, dihedrals, |e: &Entry<4>| e.atoms, Entry::shifted, &chunk_of, n),
    });
    fn done<E>(s: Mutex<Option<Slabbed<E>>>) -> Slabbed<E> {
        s.into_inner().unwrap_or_else(|e| e.into_inner()).unwrap_or_default()
    }
    BondedLists { bonds: done(slots.0), angles: done(slots.1), dihedrals: done(slots.2), lammps_bonds }
}

/// A distributed run's bonded lists, as LAMMPS lists them with `newton_bond on`: each
/// interaction once, on the rank that owns the atom it is stored on (atom 1 of a bond, atom 2 of
/// an angle or dihedral), its other atoms at their local copies (owned or ghost) closest to
/// that atom. Forces on ghosts go back to their owners after the pass.
fn build_distributed(state: &mut State, styles: BondedStyles) -> Result<(), RunError> {
    if state.stored_on.is_none() {
        state.stored_on = Some(StoredOn::new(&state.topo));
    }
    let copies = Copies::new(&state.atoms);
    if styles.bond.is_some_and(|s| s.as_bpm().is_some()) {
        // a BPM style has neither angles nor dihedrals (its init refuses them)
        let lammps_bonds = crate::models::bonded::bpm::rank_bond_list(state, &copies)?;
        state.bonded_lists = BondedLists { lammps_bonds, ..BondedLists::default() };
        return Ok(());
    }
    let (t, a, on) = (&state.topo, &state.atoms, state.stored_on.as_ref().unwrap());
    let step = state.step;
    let closest = |tag: i64, x: [f64; 3]| copies.closest(tag, x);
    // the interactions stored on owned atoms, in record order: (record, reference atom)
    let owned_records = |list: &[(i64, u32)]| -> Vec<(u32, usize)> {
        let mut recs: Vec<(u32, usize)> = (0..a.nlocal).flat_map(|i| StoredOn::on(list, a.tag[i]).map(move |rec| (rec, i))).collect();
        recs.sort_unstable();
        recs
    };
    // the interaction's local atoms, each the copy closest to the reference atom `r`
    let local = |tags: &[i64], r: usize, atoms: &mut [u32], what: &str| -> Result<(), RunError> {
        for (m, &tag) in tags.iter().enumerate() {
            atoms[m] = closest(tag, a.x[r]).ok_or_else(|| missing_partner(step, what, tag, tags))?;
        }
        Ok(())
    };
    let (mut bonds, mut angles, mut dihedrals) = (vec![], vec![], vec![]);
    if styles.bond.is_some() {
        for (rec, r) in owned_records(&on.bonds) {
            let b = &t.bonds[rec as usize];
            let mut e = Entry { atoms: [0; 2], shift: [[0; 3]; 2], typ: b.typ, rec };
            local(&b.atoms, r, &mut e.atoms, "bond")?;
            bonds.push(e);
        }
    }
    if styles.angle.is_some() {
        for (rec, r) in owned_records(&on.angles) {
            let b = &t.angles[rec as usize];
            let mut e = Entry { atoms: [0; 3], shift: [[0; 3]; 3], typ: b.typ, rec };
            local(&b.atoms, r, &mut e.atoms, "angle")?;
            angles.push(e);
        }
    }
    if styles.dihedral.is_some() {
        for (rec, r) in owned_records(&on.dihedrals) {
            let b = &t.dihedrals[rec as usize];
            let mut e = Entry { atoms: [0; 4], shift: [[0; 3]; 4], typ: b.typ, rec };
            local(&b.atoms, r, &mut e.atoms, "dihedral")?;
            dihedrals.push(e);
        }
    }
    let old = std::mem::take(&mut state.bonded_lists);
    state.bonded_lists = slabbed(state, &[bonds], &[angles], &[dihedrals], vec![], old);
    Ok(())
}

/// Every local copy (owned atom or ghost) of each atom ID of a distributed run's rank, to find a
/// bonded partner's copy closest to an atom.
pub struct Copies<'a> {
    x: &'a [[f64; 3]],
    list: Vec<(i64, u32)>,
}

impl<'a> Copies<'a> {
    pub fn new(a: &'a crate::engine::atoms::Atoms) -> Self {
        let mut list: Vec<(i64, u32)> = (0..a.nall()).map(|j| (a.tag[j], j as u32)).collect();
        list.sort_unstable();
        Copies { x: &a.x, list }
    }
    /// The copy of atom `tag` closest to `x`, owned before ghosts on a tie (None: this rank has
    /// no copy).
    pub fn closest(&self, tag: i64, x: [f64; 3]) -> Option<u32> {
        let d2 = |j: u32| {
            let y = self.x[j as usize];
            (0..3).map(|d| (y[d] - x[d]) * (y[d] - x[d])).sum::<f64>()
        };
        StoredOn::on(&self.list, tag).min_by(|&p, &q| d2(p).total_cmp(&d2(q)))
    }
}

/// The error of an interaction whose atom `tag` has no copy on this rank.
pub fn missing_partner(step: i64, what: &str, tag: i64, tags: &[i64]) -> RunError {
    RunError::new(step, format!("{what} atom {tag} is missing on this rank: the {what} of atoms {tags:?} reaches beyond the ghost cutoff (pair cutoff + skin; comm_modify cutoff)"))
}

/// Bond, angle and dihedral forces on owned atoms: chunks in the pair loop's even/odd
/// schedule, the wide ones on windows of four chunks, then the leftovers, so results do not
/// depend on the thread count.
pub fn compute_bonded(state: &mut State, styles: BondedStyles, eflag: bool) -> Result<BondedTally, RunError> {
        let lists = &state.bonded_lists;
        let distributed = state.distributed.is_some();
        // the ranks of a distributed run all take part in the reverse communication, unless no
        // rank has anything to compute (the topology and styles are the same on every rank)
        let nothing = state.topo.is_empty() || (styles.bond.is_none() && styles.angle.is_none() && styles.dihedral.is_none());
        if nothing || (!distributed && lists.bonds.is_empty() && lists.angles.is_empty() && lists.dihedrals.is_empty()) {
            return Ok(BondedTally::default());
        }
        let periods = state.domain.as_ref().unwrap().periods();
        let mut f = std::mem::take(&mut state.atoms.f);
        if distributed {
            // ghost forces of this pass alone go back to their owners
            f[state.atoms.nlocal..].iter_mut().for_each(|g| *g = [0.0; 3]);
        }
        let ctx = Kernels { x: &state.atoms.x, periods, shifts: false, eflag, bond: styles.bond, angle: styles.angle, dihedral: styles.dihedral };
        // the bonded lists are grouped by the chunks of the neighbour list (each chunk's
        // interactions touch only atoms of that chunk and the next)
        let bounds = state.neighbor.list.bounds();
        let nchunks = lists.bonds.nchunks().max(lists.angles.nchunks()).max(lists.dihedrals.nchunks());
        assert!(nchunks + 1 <= bounds.len(), "bonded lists built on another neighbour list");
        // a few interactions among many atoms (capsules in a fluid) are not worth sharing; the
        // tallies of the tasks are kept on energy steps only
        let few = lists.bonds.len() + lists.angles.len() + lists.dihedrals.len() < PARALLEL_MIN_WORK;
        let phases = |f: &mut Vec<[f64; 3]>| {
            if eflag {
                run_phases(&bounds, lists, &ctx, f, |t| t)
            } else {
                run_phases(&bounds, lists, &ctx, f, |_| ());
                vec![]
            }
        };
        let parts = if few { alone(|| phases(&mut f)) } else { phases(&mut f) };
        let mut tally = BondedTally::default();
        for p in &parts {
            tally.add(p);
        }
        let ctx = Kernels { shifts: true, ..ctx };
        ctx.run(&lists.bonds.leftover, &lists.angles.leftover, &lists.dihedrals.leftover, &mut AtomsMut::new(&mut f), &mut tally);
        state.atoms.f = f;
        if let (Some(d), true) = (&state.decomp, distributed) {
            d.reverse_forces(&mut state.atoms);
        }
        Ok(tally)
}

/// The interactions of every chunk on the slab schedule, then the wide ones on the window
/// schedule (see [`Slabbed`](crate::engine::bonded_lists::Slabbed)); each task's tally through
/// `keep`, by chunk, the wide ones after.
fn run_phases<R: Clone + Default + Send>(bounds: &[usize], lists: &BondedLists, ctx: &Kernels, f: &mut [[f64; 3]], keep: impl Fn(BondedTally) -> R + Sync) -> Vec<R> {
    let mut parts = vec![R::default(); bounds.len() - 1];
    let task = |(b, a, d): (&[Entry<2>], &[Entry<3>], &[Entry<4>]), f: &mut AtomsMut<[f64; 3]>| {
        let mut t = BondedTally::default();
        // a chunk of the wide schedule usually has none
        if !(b.is_empty() && a.is_empty() && d.is_empty()) {
            ctx.run(b, a, d, f, &mut t);
        }
        keep(t)
    };
    for parity in 0..2 {
        slab_phase(bounds, parity, AtomsMut::new(&mut *f), &mut parts, |c, mut f| task((chunk(&lists.bonds, c), chunk(&lists.angles, c), chunk(&lists.dihedrals, c)), &mut f));
    }
    // the interactions reaching further along the slab axis, on windows of WIDE chunks
    if [lists.bonds.wide.len(), lists.angles.wide.len(), lists.dihedrals.wide.len()].iter().any(|&n| n > 0) {
        let mut wide_parts = vec![R::default(); bounds.len() - 1];
        for phase in 0..WIDE {
            window_phase(bounds, WIDE, phase, AtomsMut::new(&mut *f), &mut wide_parts, |c, mut f| task((wide_chunk(&lists.bonds, c), wide_chunk(&lists.angles, c), wide_chunk(&lists.dihedrals, c)), &mut f));
        }
        parts.extend(wide_parts);
    }
    parts
}

impl BondedTally {
    pub fn add(&mut self, o: &BondedTally) {
        self.ebond += o.ebond;
        self.eangle += o.eangle;
        self.edihed += o.edihed;
        for k in 0..6 {
            self.virial[k] += o.virial[k];
        }
    }
}

/// The shift of atom `o`'s image nearest to atom `r` in a triclinic box: LAMMPS' minimum
/// image (z, then y, then x, each period carrying its tilts), counted in periods.
fn closest_tilted(domain: &crate::engine::domain::Domain, xr: [f64; 3], xo: [f64; 3]) -> [i8; 3] {
    let p = domain.prd();
    let [xy, xz, yz] = domain.tilts();
    let step = [[p[0], 0.0, 0.0], [xy, p[1], 0.0], [xz, yz, p[2]]];
    let mut dx = [xr[0] - xo[0], xr[1] - xo[1], xr[2] - xo[2]];
    let mut s = [0i8; 3];
    for d in [2, 1, 0] {
        if !domain.periodic(d) {
            continue;
        }
        // a bonded partner lies within a period or two: the loops are short
        for _ in 0..4 {
            let sign = if dx[d] > 0.5 * p[d] { 1.0 } else if dx[d] < -0.5 * p[d] { -1.0 } else { break };
            for k in 0..3 {
                dx[k] -= sign * step[d][k];
            }
            s[d] += sign as i8;
        }
    }
    s
}

/// What the bonded kernels read.
pub struct Kernels<'a> {
    x: &'a [[f64; 3]],
    periods: Periods,
    /// Entries may carry periodic shifts (the leftovers).
    shifts: bool,
    eflag: bool,
    bond: Option<&'a dyn BondStyle>,
    angle: Option<&'a dyn AngleStyle>,
    dihedral: Option<&'a dyn DihedralStyle>,
}

fn sub(p: [f64; 3], q: [f64; 3]) -> [f64; 3] {
    [p[0] - q[0], p[1] - q[1], p[2] - q[2]]
}

fn add_virial(t: &mut [f64; 6], v: [f64; 6]) {
    for k in 0..6 {
        t[k] += v[k];
    }
}

impl Kernels<'_> {
    /// Position of an atom at a periodic shift, computed as LAMMPS' ghost copy (`x + s*L`).
    /// Chunk entries have no shifts (see `slab`), so their positions are read directly.
    #[inline(always)]
    fn pos(&self, i: u32, s: [i8; 3]) -> [f64; 3] {
        let p = self.x[i as usize];
        if self.shifts {
            return self.periods.shifted(p, s);
        }
        p
    }

    fn run(&self, bonds: &[Entry<2>], angles: &[Entry<3>], dihedrals: &[Entry<4>], f: &mut AtomsMut<[f64; 3]>, tally: &mut BondedTally) {
        if let Some(style) = self.bond {
            style.apply(bonds, self, f, tally);
        }
        if let Some(style) = self.angle {
            style.apply(angles, self, f, tally);
        }
        if let Some(style) = self.dihedral {
            style.apply(dihedrals, self, f, tally);
        }
    }
}

/// Add `fk` to atom `i`.
#[inline(always)]
fn add_force(f: &mut AtomsMut<[f64; 3]>, i: u32, fk: [f64; 3]) {
    let fa = &mut f[i as usize];
    for d in 0..3 {
        fa[d] += fk[d];
    }
}

pub fn apply_bonds<S: BondStyle + ?Sized>(style: &S, entries: &[Entry<2>], k: &Kernels, f: &mut AtomsMut<[f64; 3]>, tally: &mut BondedTally) {
    for e in entries {
        let del = sub(k.pos(e.atoms[0], e.shift[0]), k.pos(e.atoms[1], e.shift[1]));
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        let (fbond, energy) = style.compute(e.typ, del, rsq);
        add_force(f, e.atoms[0], [del[0] * fbond, del[1] * fbond, del[2] * fbond]);
        // LAMMPS subtracts del*fbond (not adds its negative): identical bits
        let fa = &mut f[e.atoms[1] as usize];
        for d in 0..3 {
            fa[d] -= del[d] * fbond;
        }
        if k.eflag {
            tally.ebond += energy;
            add_virial(&mut tally.virial, bond_virial(del, fbond));
        }
    }
}

pub fn apply_angles<S: AngleStyle + ?Sized>(style: &S, entries: &[Entry<3>], k: &Kernels, f: &mut AtomsMut<[f64; 3]>, tally: &mut BondedTally) {
    for e in entries {
        let x2 = k.pos(e.atoms[1], e.shift[1]);
        let del1 = sub(k.pos(e.atoms[0], e.shift[0]), x2);
        let del2 = sub(k.pos(e.atoms[2], e.shift[2]), x2);
        let r = style.compute(e.typ, del1, del2);
        add_force(f, e.atoms[0], r.f1);
        add_force(f, e.atoms[1], r.f2());
        add_force(f, e.atoms[2], r.f3);
        if k.eflag {
            tally.eangle += r.energy;
            add_virial(&mut tally.virial, angle_virial(del1, del2, r.f1, r.f3));
        }
    }
}

/// [`apply_angles`] four angles at a time: `kernel(types, del1, del2)` gives each lane's force
/// on atoms 1 and 3 and its energy, from the same operations as the style's `compute`; forces
/// and tallies are added in entry order, so the sums are those of [`apply_angles`]. A last
/// partial batch repeats its first angle in the unused lanes, whose results are dropped.
pub fn apply_angles_in_lanes(
    entries: &[Entry<3>],
    k: &Kernels,
    f: &mut AtomsMut<[f64; 3]>,
    tally: &mut BondedTally,
    kernel: impl Fn([usize; LANES], [L; 3], [L; 3]) -> ([L; 3], [L; 3], L),
) {
    for batch in entries.chunks(LANES) {
        let e = |l: usize| batch.get(l).unwrap_or(&batch[0]);
        // each lane's displacements as a row, turned into lanes in registers (lanes written one
        // value at a time were read back whole: a store-forwarding stall)
        let mut rows1 = [[0.0; 4]; LANES];
        let mut rows2 = [[0.0; 4]; LANES];
        for l in 0..LANES {
            let e = e(l);
            let x2 = k.pos(e.atoms[1], e.shift[1]);
            let (d1, d2) = (sub(k.pos(e.atoms[0], e.shift[0]), x2), sub(k.pos(e.atoms[2], e.shift[2]), x2));
            rows1[l] = [d1[0], d1[1], d1[2], 0.0];
            rows2[l] = [d2[0], d2[1], d2[2], 0.0];
        }
        let [d1x, d1y, d1z, _] = transpose4([&rows1[0], &rows1[1], &rows1[2], &rows1[3]]);
        let [d2x, d2y, d2z, _] = transpose4([&rows2[0], &rows2[1], &rows2[2], &rows2[3]]);
        let (f1, f3, energy) = kernel(std::array::from_fn(|l| e(l).typ), [d1x, d1y, d1z], [d2x, d2y, d2z]);
        // the middle atom's force as AngleForces::f2 makes it
        let f2 = [-(f1[0] + f3[0]), -(f1[1] + f3[1]), -(f1[2] + f3[2])];
        let f1 = transpose4([&f1[0].0, &f1[1].0, &f1[2].0, &energy.0]);
        let f2 = transpose4([&f2[0].0, &f2[1].0, &f2[2].0, &energy.0]);
        let f3 = transpose4([&f3[0].0, &f3[1].0, &f3[2].0, &energy.0]);
        for (l, e) in batch.iter().enumerate() {
            let row = |v: &L| [v[0], v[1], v[2]];
            add_force(f, e.atoms[0], row(&f1[l]));
            add_force(f, e.atoms[1], row(&f2[l]));
            add_force(f, e.atoms[2], row(&f3[l]));
            if k.eflag {
                tally.eangle += f1[l][3];
                let (d1, d2) = (&rows1[l], &rows2[l]);
                add_virial(&mut tally.virial, angle_virial([d1[0], d1[1], d1[2]], [d2[0], d2[1], d2[2]], row(&f1[l]), row(&f3[l])));
            }
        }
    }
}

pub fn apply_dihedrals<S: DihedralStyle + ?Sized>(style: &S, entries: &[Entry<4>], k: &Kernels, f: &mut AtomsMut<[f64; 3]>, tally: &mut BondedTally) {
    for e in entries {
        let p: [[f64; 3]; 4] = std::array::from_fn(|m| k.pos(e.atoms[m], e.shift[m]));
        let (vb1, vb2, vb3) = (sub(p[0], p[1]), sub(p[2], p[1]), sub(p[3], p[2]));
        let r = style.compute(e.typ, vb1, vb2, vb3);
        for (m, fm) in [r.f1, r.f2, r.f3, r.f4].into_iter().enumerate() {
            add_force(f, e.atoms[m], fm);
        }
        if k.eflag {
            tally.edihed += r.energy;
            add_virial(&mut tally.virial, dihedral_virial(vb1, vb2, vb3, r.f1, r.f3, r.f4));
        }
    }
}

/// Per-atom energies and virials of the bonded interactions into `out` (compute pe/atom and
/// stress/atom): a separate pass, run only on steps that need them. As LAMMPS' `ev_tally` of
/// bonds, angles and dihedrals: each atom of an interaction takes 1/2, 1/3 or 1/4 of it.
pub fn bonded_peratom(state: &State, styles: BondedStyles, result: &mut crate::engine::tally::PerAtomTally) {
    use crate::engine::tally::PerAtomTally;
    let lists = &state.bonded_lists;
    let Some(dom) = state.domain.as_ref() else { return };
    // a distributed run computes each interaction once, on one rank, with ghosts: their shares
    // go back to the owners (LAMMPS' reverse communication of eatom and vatom)
    let decomp = state.decomp.as_ref().filter(|_| state.distributed.is_some());
    let nlocal = state.atoms.nlocal;
    let mut all = decomp.map(|_| PerAtomTally::new(state.atoms.nall(), result.step));
    let out = match all.as_mut() {
        Some(all) => all,
        None => &mut *result,
    };
    // every entry at its shifts (chunk entries have none)
    let k = Kernels { x: &state.atoms.x, periods: dom.periods(), shifts: true, eflag: true, bond: styles.bond, angle: styles.angle, dihedral: styles.dihedral };
    if let Some(style) = styles.bond {
        for e in lists.bonds.all() {
            let del = sub(k.pos(e.atoms[0], e.shift[0]), k.pos(e.atoms[1], e.shift[1]));
            let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
            let (fbond, energy) = style.compute(e.typ, del, rsq);
            let v = bond_virial(del, fbond);
            e.atoms.iter().for_each(|&i| out.add(PerAtomTally::BOND, i as usize, 0.5, energy, &v));
        }
    }
    if let Some(style) = styles.angle {
        for e in lists.angles.all() {
            let x2 = k.pos(e.atoms[1], e.shift[1]);
            let del1 = sub(k.pos(e.atoms[0], e.shift[0]), x2);
            let del2 = sub(k.pos(e.atoms[2], e.shift[2]), x2);
            let r = style.compute(e.typ, del1, del2);
            let v = angle_virial(del1, del2, r.f1, r.f3);
            e.atoms.iter().for_each(|&i| out.add(PerAtomTally::ANGLE, i as usize, 1.0 / 3.0, r.energy, &v));
        }
    }
    if let Some(style) = styles.dihedral {
        for e in lists.dihedrals.all() {
            let p: [[f64; 3]; 4] = std::array::from_fn(|m| k.pos(e.atoms[m], e.shift[m]));
            let (vb1, vb2, vb3) = (sub(p[0], p[1]), sub(p[2], p[1]), sub(p[3], p[2]));
            let r = style.compute(e.typ, vb1, vb2, vb3);
            let v = dihedral_virial(vb1, vb2, vb3, r.f1, r.f3, r.f4);
            e.atoms.iter().for_each(|&i| out.add(PerAtomTally::DIHEDRAL, i as usize, 0.25, r.energy, &v));
        }
    }
    if let (Some(d), Some(all)) = (decomp, all) {
        let mut flat = all.flat();
        d.reverse_add(nlocal, &mut flat, PerAtomTally::WIDTH);
        let mine = PerAtomTally::from_flat(result.step, &flat[..nlocal * PerAtomTally::WIDTH]);
        for k in [PerAtomTally::BOND, PerAtomTally::ANGLE, PerAtomTally::DIHEDRAL] {
            for i in 0..nlocal {
                result.add(k, i, 1.0, mine.energy[k][i], &mine.virial[k][i]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::bonded::test_util::words;
    use crate::models::bonded::new_angle_style;
    use dmhs_parser::{Args, Span};

    /// A small generator of reproducible numbers in [0, 1).
    fn uniform(seed: &mut u64) -> f64 {
        *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn angles_in_lanes_give_the_bits_of_one_at_a_time() {
        let mut style = new_angle_style("harmonic").unwrap();
        style.set_types(2);
        for (t, coeff) in [(1, "2.0 180.0"), (2, "35.5 109.47")] {
            let w = words(coeff);
            style.coeff(t, t, &mut Args::from_words(&w, Span::default(), "")).unwrap();
        }
        let mut seed = 7;
        let mut x: Vec<[f64; 3]> = (0..40).map(|_| [0.0; 3].map(|_| 3.0 * uniform(&mut seed))).collect();
        // a straight angle (the clamp of the cosine and the bound on the sine) and a folded one
        x.extend([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]]);
        let n = x.len() as u32;
        let mut entries: Vec<Entry<3>> = (0..61)
            .map(|k| {
                // three distinct atoms (an arm of length zero has no direction: NaN, whose
                // sign bit is the compiler's choice of operand order)
                let a = (uniform(&mut seed) * 40.0) as u32;
                let atoms = [a, (a + 1 + (uniform(&mut seed) * 19.0) as u32) % 40, (a + 20 + (uniform(&mut seed) * 19.0) as u32) % 40];
                let shift = if k % 5 == 0 { [[1, 0, -1], [0; 3], [0, 1, 0]] } else { [[0; 3]; 3] };
                Entry { atoms, shift, typ: 1 + k % 2, rec: k as u32 }
            })
            .collect();
        entries.push(Entry { atoms: [n - 4, n - 3, n - 2], shift: [[0; 3]; 3], typ: 1, rec: 61 });
        entries.push(Entry { atoms: [n - 4, n - 3, n - 4], shift: [[0; 3]; 3], typ: 2, rec: 62 });
        entries.push(Entry { atoms: [n - 1, n - 3, n - 2], shift: [[0; 3]; 3], typ: 2, rec: 63 });
        let k = Kernels { x: &x, periods: Periods { prd: [3.0, 3.5, 4.0], tilt: None }, shifts: true, eflag: true, bond: None, angle: None, dihedral: None };
        // every length of a last partial batch
        for len in [entries.len(), entries.len() - 1, entries.len() - 2, entries.len() - 3, 1] {
            let (mut f_one, mut f_lanes) = (vec![[0.0; 3]; x.len()], vec![[0.0; 3]; x.len()]);
            let (mut t_one, mut t_lanes) = (BondedTally::default(), BondedTally::default());
            apply_angles(style.as_ref(), &entries[..len], &k, &mut AtomsMut::new(&mut f_one), &mut t_one);
            style.apply(&entries[..len], &k, &mut AtomsMut::new(&mut f_lanes), &mut t_lanes);
            let bits = |f: &[[f64; 3]]| f.iter().flat_map(|v| v.map(f64::to_bits)).collect::<Vec<_>>();
            assert_eq!(bits(&f_lanes), bits(&f_one), "forces, {len} angles");
            assert_eq!(t_lanes.eangle.to_bits(), t_one.eangle.to_bits());
            assert_eq!(t_lanes.virial.map(f64::to_bits), t_one.virial.map(f64::to_bits));
        }
    }
}
