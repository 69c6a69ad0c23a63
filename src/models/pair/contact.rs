//! The engine's loop for granular contact styles (gran/hooke, gran/hooke/history, granular):
//! every listed pair that overlaps (r < R_i + R_j) gets a force and torques from the style's
//! [`ContactModel`], with its contact history (see [`crate::engine::contact_history`]) read and written
//! next to the list entry. Forces and torques go to both atoms when both are owned; a pair with
//! a periodic image is computed from both sides and applied to the owned atom only. The slab
//! schedule of [`super::for_each_chunk`] keeps results identical for every thread count.
//!
//! Overlapping pairs are collected in batches of [`LANES`] and handed to the model together, so a
//! model can evaluate them lane by lane in vector registers (the same IEEE operations per lane as
//! one pair at a time, so the same bits); the results are applied in list order.

use super::{sum_tallies, PairInput, PairOutput, Tally};
use crate::engine::par::lanes::{lanes, L, LANES};
use crate::engine::par::bounded::scope;
use crate::engine::par::{slab_phase, AtomsMut, ChunksMut};
use crate::engine::contact_history::{ContactHistory, HistoryChunk};
use crate::engine::neighbor::special_level;
use crate::engine::tally::PairShare;

/// What a contact model sees of one overlapping pair (i is the atom that lists the pair), or of
/// a batch of pairs with `T` = [`L`].
pub struct Contact<'a, T = f64> {
    /// x_i - x_j
    pub del: [T; 3],
    pub rsq: T,
    pub radi: T,
    pub radj: T,
    pub vi: &'a [T; 3],
    pub vj: &'a [T; 3],
    pub omegai: &'a [T; 3],
    pub omegaj: &'a [T; 3],
    /// the effective mass ([`effective_mass`]; against a wall the sphere's mass)
    pub meff: T,
}

/// m_eff of a pair contact as LAMMPS' granular pair styles take it: m_i m_j / (m_i + m_j), or
/// the other sphere's mass when one is in fix freeze's group (j's rule last).
#[inline(always)]
pub fn effective_mass(mi: f64, mj: f64, frozen_i: bool, frozen_j: bool) -> f64 {
    let mut meff = mi * mj / (mi + mj);
    if frozen_i {
        meff = mj;
    }
    if frozen_j {
        meff = mi;
    }
    meff
}

/// The [`Contact`] of listed pair i-j as the pair loop makes it, for a style's `single`
/// (compute pair/local): the state of the atoms now.
pub fn contact_of<'a>(input: &'a PairInput, i: usize, j: usize, rsq: f64) -> Contact<'a> {
    let a = input.atoms;
    let rmass = input.rigid_mass.unwrap_or(&a.rmass[..]);
    Contact {
        del: [a.x[i][0] - a.x[j][0], a.x[i][1] - a.x[j][1], a.x[i][2] - a.x[j][2]],
        rsq,
        radi: a.radius[i],
        radj: a.radius[j],
        vi: &a.v[i],
        vj: &a.v[j],
        omegai: &a.omega[i],
        omegaj: &a.omega[j],
        meff: effective_mass(rmass[i], rmass[j], input.frozen(i), input.frozen(j)),
    }
}

/// A contact's result: the force on i (j gets its negative) and the torques on i and j.
#[derive(Clone, Copy, Debug, Default)]
pub struct ContactForce<T = f64> {
    pub f: [T; 3],
    pub ti: [T; 3],
    pub tj: [T; 3],
}

/// The most history values per contact a model keeps (LAMMPS' size_history of pair granular:
/// a mindlin_rescale spring and its contact radius, a rolling spring and a twisting spring).
pub const MAX_HISTORY: usize = 10;

/// A granular contact law.
pub trait ContactModel: Sync {
    type Params: Sync;
    /// The most history values per contact (0: the model keeps none; at most [`MAX_HISTORY`]).
    const HISTORY: usize;
    /// History values per contact of this instance (those of its models, up to `HISTORY`).
    fn history_size(&self) -> usize {
        Self::HISTORY
    }
    fn params(&self, ti: usize, tj: usize) -> &Self::Params;
    /// Some pair interacts beyond touching (LAMMPS beyond_contact: a cohesive contact that
    /// holds until the pull-off distance); then [`ContactModel::touch`] decides, and touch flags
    /// are kept even without history values.
    fn beyond_contact(&self) -> bool {
        false
    }
    /// Whether a listed pair is in contact, given whether it was (only for `beyond_contact`).
    fn touch(_p: &Self::Params, rsq: f64, radi: f64, radj: f64, _was: bool) -> bool {
        let radsum = radi + radj;
        rsq < radsum * radsum
    }
    /// The contact of an overlapping pair; `hist` holds its history (empty without one), and
    /// `update` is false during run setup (LAMMPS' `shearupdate`).
    fn contact(p: &Self::Params, c: &Contact, hist: &mut [f64], update: bool, dt: f64) -> ContactForce;
    /// A batch of overlapping pairs (lanes `0..b.n`; the others repeat lane 0 and are
    /// ignored). The default evaluates them one at a time with [`ContactModel::contact`].
    fn contact_lanes(&self, b: &LaneSrc, update: bool, dt: f64) -> LanesOut {
        let mut o = LanesOut::default();
        // each lane read straight from the arrays (gathering all four lanes first and picking
        // one back out cost a single contact, the common case of a sparse bed, twice as much);
        // del and rsq are the operations of `LaneSrc::contact`, per lane the same bits
        let hsize = b.hsize;
        for l in 0..b.n {
            let (i, j) = (b.ij[0][l], b.ij[1][l]);
            let (xi, xj) = (&b.x[i], &b.x[j]);
            let del = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
            let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
            let meff = effective_mass(b.rmass[i], b.rmass[j], b.frozen(i), b.frozen(j));
            let one = Contact { del, rsq, radi: b.radius[i], radj: b.radius[j], vi: &b.v[i], vj: &b.v[j], omegai: &b.omega[i], omegaj: &b.omega[j], meff };
            let mut h = [0.0; MAX_HISTORY];
            let e = b.e[l];
            h[..hsize].copy_from_slice(&b.values[e * hsize..(e + 1) * hsize]);
            let (ti, tj) = b.types(l);
            let r = Self::contact(self.params(ti, tj), &one, &mut h[..b.hsize], update, dt);
            for (d, hd) in h[..b.hsize].iter().enumerate() {
                o.hist[d][l] = *hd;
            }
            for d in 0..3 {
                o.force.f[d][l] = r.f[d];
                o.force.ti[d][l] = r.ti[d];
                o.force.tj[d][l] = r.tj[d];
            }
        }
        o
    }
}

/// The loop's record of a batch: atoms, history entry and special weight of each lane.
#[derive(Clone, Default)]
struct Batch {
    n: usize,
    i: [usize; LANES],
    j: [usize; LANES],
    e: [usize; LANES],
    factor: L,
}

/// Where a batch's inputs come from: the atoms of each lane and the atom arrays. A model reads
/// them lane-wise with the accessors, which load straight into vector registers (gathering
/// lane by lane through memory first would stall the vector loads).
pub struct LaneSrc<'a> {
    pub n: usize,
    /// atoms i (index 0) and j (index 1) of each lane
    pub ij: [[usize; LANES]; 2],
    pub e: [usize; LANES],
    pub x: &'a [[f64; 3]],
    pub v: &'a [[f64; 3]],
    pub omega: &'a [[f64; 3]],
    pub radius: &'a [f64],
    pub rmass: &'a [f64],
    /// group masks and fix freeze's bit (0: no fix freeze)
    pub mask: &'a [u32],
    pub freeze_bit: u32,
    pub typ: &'a [usize],
    pub values: &'a [f64],
    pub hsize: usize,
}

impl LaneSrc<'_> {
    /// x_i - x_j, computed again exactly as the loop computed it.
    #[inline(always)]
    pub fn del(&self) -> [L; 3] {
        let [i, j] = &self.ij;
        std::array::from_fn(|d| lanes(|l| self.x[i[l]][d] - self.x[j[l]][d]))
    }
    /// A 3-vector per-atom array of atom i (`which` 0) or j (1).
    #[inline(always)]
    pub fn v3(&self, a: &[[f64; 3]], which: usize) -> [L; 3] {
        let idx = &self.ij[which];
        std::array::from_fn(|d| lanes(|l| a[idx[l]][d]))
    }
    /// A scalar per-atom array of atom i (`which` 0) or j (1).
    #[inline(always)]
    pub fn scalar(&self, a: &[f64], which: usize) -> L {
        let idx = &self.ij[which];
        lanes(|l| a[idx[l]])
    }
    /// Whether atom `i` is in fix freeze's group.
    #[inline(always)]
    pub fn frozen(&self, i: usize) -> bool {
        self.freeze_bit != 0 && self.mask[i] & self.freeze_bit != 0
    }
    /// The effective masses of the lanes ([`effective_mass`]).
    #[inline(always)]
    pub fn meff(&self) -> L {
        if self.freeze_bit == 0 {
            let (mi, mj) = (self.scalar(self.rmass, 0), self.scalar(self.rmass, 1));
            return mi * mj / (mi + mj);
        }
        let [i, j] = &self.ij;
        lanes(|l| effective_mass(self.rmass[i[l]], self.rmass[j[l]], self.frozen(i[l]), self.frozen(j[l])))
    }
    /// The first `N` history values (zeros beyond `hsize`).
    #[inline(always)]
    pub fn hist<const N: usize>(&self) -> [L; N] {
        let (e, h) = (&self.e, self.hsize);
        std::array::from_fn(|d| lanes(|l| if d < h { self.values[e[l] * h + d] } else { 0.0 }))
    }
    /// The batch as a [`Contact`] of lanes, with the velocities of i and j (`v3(v, 0|1)`) and
    /// angular velocities (`v3(omega, 0|1)`) the caller gathered.
    #[inline(always)]
    pub fn contact<'v>(&self, vi: &'v [L; 3], vj: &'v [L; 3], omegai: &'v [L; 3], omegaj: &'v [L; 3]) -> Contact<'v, L> {
        let del = self.del();
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        Contact {
            del,
            rsq,
            radi: self.scalar(self.radius, 0),
            radj: self.scalar(self.radius, 1),
            vi,
            vj,
            omegai,
            omegaj,
            meff: self.meff(),
        }
    }
    /// Atom types of lane `l`.
    pub fn types(&self, l: usize) -> (usize, usize) {
        (self.typ[self.ij[0][l]], self.typ[self.ij[1][l]])
    }
}

/// Results of a batch: force on i, torques on i and j, per lane.
#[derive(Clone, Default)]
pub struct LanesOut {
    pub force: ContactForce<L>,
    /// the history values after the evaluation (the first `hsize` are used)
    pub hist: [L; MAX_HISTORY],
}

impl LanesOut {
    /// The results of a model with `N` history values.
    #[inline(always)]
    pub fn new<const N: usize>(force: ContactForce<L>, h: [L; N]) -> LanesOut {
        LanesOut { force, hist: std::array::from_fn(|d| if d < N { h[d] } else { L::default() }) }
    }
}

/// A chunk's energy-step sums: its tallies and, for compute pe/atom and stress/atom (`shares`
/// is `Some`), its pairs' virials.
#[derive(Clone, Default)]
struct Sums {
    t: Tally,
    shares: Option<Vec<PairShare>>,
}

/// One pair's tallies on an energy step. Out of line and cold: written inline in the batch
/// code, the `Vec`'s push and what it referenced cost the loop over the entries registers and
/// instructions on every step (docs/performance.md, "The contact loop's per-atom tallies").
#[cold]
#[inline(never)]
fn tally_pair(sums: &mut Sums, i: usize, j: usize, w: f64, del: [f64; 3], f: [f64; 3]) {
    sums.t.xyz(w, del, f);
    if let Some(shares) = &mut sums.shares {
        shares.push(PairShare::xyz(i, j, 0.0, del, f));
    }
}

/// A contact that is over forgets its history. Rare, so out of line: inlined, the loop over the
/// entries kept running offsets into `values` for it on every entry.
#[cold]
#[inline(never)]
fn forget(values: &mut [f64], e: usize, hsize: usize) {
    values[e * hsize..(e + 1) * hsize].iter_mut().for_each(|s| *s = 0.0);
}

/// Compute all contacts of the list. `history` must be given when `M::HISTORY > 0` (and
/// aligned with the list by [`ContactHistory::rebuilt`]).
pub fn compute_contacts<M: ContactModel>(model: &M, input: &PairInput, out: &mut PairOutput, history: Option<&mut ContactHistory>) -> Tally {
    let special = input.list.has_special;
    match (input.eflag, special || input.type_filter.is_some() || model.beyond_contact()) {
        (false, false) => contact_loop::<M, false, false>(model, input, out, history),
        (true, false) => contact_loop::<M, true, false>(model, input, out, history),
        (false, true) => contact_loop::<M, false, true>(model, input, out, history),
        (true, true) => contact_loop::<M, true, true>(model, input, out, history),
    }
}

/// `EXTRA`: special weights, a type filter (hybrid) or a beyond-contact model apply.
fn contact_loop<M: ContactModel, const EFLAG: bool, const EXTRA: bool>(
    model: &M,
    input: &PairInput,
    out: &mut PairOutput,
    history: Option<&mut ContactHistory>,
) -> Tally {
    let a = input.atoms;
    let nlocal = a.nlocal;
    let nall = a.nall();
    assert!(a.radius.len() == nall && a.rmass.len() == nall && a.omega.len() == nall && a.v.len() == nall && a.typ.len() == nall);
    assert!(out.f.len() >= nlocal && out.torque.len() >= nlocal);
    let beyond = model.beyond_contact();
    let hsize = model.history_size();
    assert!(hsize <= M::HISTORY && M::HISTORY <= MAX_HISTORY);
    let mut no_history: Vec<HistoryChunk> = vec![];
    let hist: &mut Vec<HistoryChunk> = match history {
        Some(h) if hsize > 0 || beyond => {
            assert!(h.size() == hsize && h.chunks.len() == input.list.chunks.len(), "contact history not aligned with the neighbour list");
            &mut h.chunks
        }
        _ => {
            assert!(hsize == 0 && !beyond, "a contact model with history needs its history store");
            &mut no_history
        }
    };
    let stride = input.ntypes + 1;
    // with rigid bodies the effective mass takes the bodies' masses (LAMMPS' mass_rigid)
    let rmass = input.rigid_mass.unwrap_or(&a.rmass[..]);
    assert!(rmass.len() >= nall);
    let (x, v, omega, radius, typ) = (&a.x[..], &a.v[..], &a.omega[..], &a.radius[..], &a.typ[..]);
    let update = input.advance;
    let dt = input.dt;
    let list = input.list;
    let bounds = list.bounds();
    // each chunk's tallies and, for compute pe/atom and stress/atom, its pairs' virials
    let record = EFLAG && out.peratom.is_some();
    let mut parts = vec![Sums::default(); list.chunks.len()];
    // neighbour entries read positions, radii and types unchecked (all hold every atom)
    scope(nall, |s| {
    let (x_of, radius_of, typ_of) = (s.reader(x), s.reader(radius), s.reader(typ));
    for parity in 0..2 {
        let windows = (AtomsMut::new(&mut *out.f), AtomsMut::new(&mut *out.torque), ChunksMut::new(&mut *hist));
        slab_phase(&bounds, parity, windows, &mut parts, |c, (mut fo, mut to, mut hist)| {
        let chunk = &list.chunks[c];
        let mut sums = Sums { t: Tally::default(), shares: record.then(Vec::new) };
        let mut empty = HistoryChunk::default();
        if !(hsize > 0 || beyond) {
            // flags nobody reads, so that every atom's flags below are one slice of its entries
            empty.touch.resize(chunk.len(), 0);
        }
        let h = if hsize > 0 || beyond { &mut hist[c] } else { &mut empty };
        let (touch, values): (&mut [u8], &mut [f64]) = (&mut h.touch[..], &mut h.values[..]);
        let mut b = Batch::default();
        // evaluate the batch and apply its results in list order
        let mut flush = |b: &mut Batch, n: usize, values: &mut [f64], sums: &mut Sums| {
            if n == 0 {
                return;
            }
            b.n = n;
            // unused lanes repeat lane 0 (valid numbers; their results are ignored)
            for l in b.n..LANES {
                b.i[l] = b.i[0];
                b.j[l] = b.j[0];
                b.e[l] = b.e[0];
            }
            let src = LaneSrc { n: b.n, ij: [b.i, b.j], e: b.e, x, v, omega, radius, rmass, mask: &a.mask, freeze_bit: input.freeze_bit, typ, values, hsize };
            let mut r = model.contact_lanes(&src, update, dt);
            let apply = |l: usize| {
                let e = b.e[l];
                for d in 0..hsize {
                    values[e * hsize + d] = r.hist[d][l];
                }
                let r = &mut r.force;
                if EXTRA && b.factor[l] != 1.0 {
                    let fac = b.factor[l];
                    for d in 0..3 {
                        r.f[d][l] *= fac;
                        r.ti[d][l] *= fac;
                        r.tj[d][l] *= fac;
                    }
                }
                let (i, j) = (b.i[l], b.j[l]);
                for d in 0..3 {
                    fo[i][d] += r.f[d][l];
                    to[i][d] += r.ti[d][l];
                }
                let w = if j < nlocal {
                    for d in 0..3 {
                        fo[j][d] -= r.f[d][l];
                        to[j][d] += r.tj[d][l];
                    }
                    1.0
                } else {
                    0.5
                };
                if EFLAG {
                    let del = [x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]];
                    tally_pair(sums, i, j, w, del, [r.f[0][l], r.f[1][l], r.f[2][l]]);
                }
            };
            crate::engine::par::lanes::for_each_lane(b.n, apply);
        };
        // lanes filled so far (a local, so it stays in a register)
        let mut n = 0usize;
        // the chunk's entries checked against the scope once (not once per atom)
        let entries = chunk.view(&s);
        for i in chunk.start..chunk.end {
            let xi = x[i];
            let radi = radius[i];
            let ti = typ[i];
            let k0 = chunk.first_entry(i);
            let neigh = entries.of(i);
            // the atom's touch flags, checked once here instead of at every entry
            let touch = &mut touch[k0..k0 + neigh.len()];
            for (k, &je) in neigh.iter().enumerate() {
                let (j, jraw) = (je.index(), je.raw());
                let (xj, radj) = (*x_of.get(je), *radius_of.get(je));
                let del = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
                let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                let radsum = radi + radj;
                let e = k0 + k;
                let touching = if beyond { M::touch(model.params(ti, *typ_of.get(je)), rsq, radi, radj, touch[k] != 0) } else { rsq < radsum * radsum };
                if !EXTRA {
                    // the common case without branches on the (unpredictable) overlap test:
                    // every entry is written to the next lane, which is kept only if touching
                    b.i[n] = i;
                    b.j[n] = j;
                    b.e[n] = e;
                    n += touching as usize;
                    if hsize > 0 {
                        let was = touch[k];
                        touch[k] = touching as u8;
                        if was > touching as u8 {
                            // the contact is over
                            forget(values, e, hsize);
                        }
                    }
                    if n == LANES {
                        flush(&mut b, n, values, &mut sums);
                        n = 0;
                    }
                    continue;
                }
                if !touching {
                    if (hsize > 0 || beyond) && touch[k] != 0 {
                        touch[k] = 0;
                        forget(values, e, hsize);
                    }
                    continue;
                }
                let tj = *typ_of.get(je);
                if let Some(filter) = input.type_filter {
                    if !filter[ti * stride + tj] {
                        continue;
                    }
                }
                let factor = input.special_lj[special_level(jraw)];
                if factor == 0.0 {
                    continue;
                }
                if hsize > 0 || beyond {
                    touch[k] = 1;
                }
                b.i[n] = i;
                b.j[n] = j;
                b.e[n] = e;
                b.factor[n] = factor;
                n += 1;
                if n == LANES {
                    flush(&mut b, n, values, &mut sums);
                    n = 0;
                }
            }
        }
        flush(&mut b, n, values, &mut sums);
        sums
        });
    }
    });
    if let Some(pa) = out.peratom.as_deref_mut() {
        parts.iter().filter_map(|p| p.shares.as_deref()).for_each(|s| pa.add_pairs(s));
    }
    sum_tallies(parts.iter().map(|p| &p.t))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// fix freeze's rule, per lane as for one pair (LAMMPS: j's rule applied last).
    #[test]
    fn frozen_spheres_give_the_other_mass() {
        assert_eq!(effective_mass(2.0, 6.0, false, false), 1.5);
        assert_eq!(effective_mass(2.0, 6.0, true, false), 6.0);
        assert_eq!(effective_mass(2.0, 6.0, false, true), 2.0);
        assert_eq!(effective_mass(2.0, 6.0, true, true), 2.0);
        let x = vec![[0.0; 3]; 8];
        let rmass: Vec<f64> = (0..8).map(|i| 1.0 + i as f64 * 0.37).collect();
        let mask = vec![1, 3, 1, 1, 3, 3, 1, 1];
        let typ = vec![1; 8];
        for freeze_bit in [0, 2] {
            let src = LaneSrc {
                n: LANES,
                ij: [std::array::from_fn(|l| 2 * l), std::array::from_fn(|l| 2 * l + 1)],
                e: [0; LANES],
                x: &x,
                v: &x,
                omega: &x,
                radius: &rmass,
                rmass: &rmass,
                mask: &mask,
                freeze_bit,
                typ: &typ,
                values: &[],
                hsize: 0,
            };
            let m = src.meff();
            for l in 0..LANES {
                let (i, j) = (2 * l, 2 * l + 1);
                let frozen = |k: usize| mask[k] & freeze_bit != 0;
                assert_eq!(m[l].to_bits(), effective_mass(rmass[i], rmass[j], frozen(i), frozen(j)).to_bits());
            }
        }
    }
}
