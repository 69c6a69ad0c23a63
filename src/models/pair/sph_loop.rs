//! The engine-owned SPH pair loop: per-particle records, batches of [`LANES`] pairs, and the
//! accumulation of forces and rates. The physics of a pair is the style's ([`SphKernel`]).
//!
//! Layout. A particle is one cache line, two rows of four f64, so that four partners become
//! lane vectors by two 4x4 transposes:
//! - 3D: `[x, y, z, vx] [vy, vz, a, b]` (the memory of [`Packed`]);
//! - 2D: `[x, y, vx, vy] [a, b, m, 0]`, m the particle's mass.
//!
//! The 2D layout is used when every particle has the same z and no z velocity (what a 2D run
//! is); the z terms LAMMPS computes are then zeros, and leaving them out gives the same sums,
//! because every accumulator starts at +0 (a zero of either sign added to it changes nothing).
//! Rates and forces of a particle are kept as one row of four (2D: fx fy drho desph; 3D: fx fy
//! fz drho, with desph beside), added with one vector operation per pair and partner.

use super::sph::{Packed, SphKernel};
use super::{sum_tallies, PairInput, PairOutput, Tally};
use crate::engine::tally::PairShare;
use crate::engine::par::bounded::{scope_writing, Entry, Reader};
use crate::engine::par::lanes::{for_each_lane, lanes, transpose4, L, LANES};
use crate::engine::par::{completed_after, ranges, slab_phase, AtomsMut};

/// Up to [`LANES`] neighbours j of one particle i, field by field (unused lanes repeat lane 0;
/// their results are ignored). `D` is the dimension of the vectors.
#[derive(Clone, Copy, Debug)]
pub struct Batch<const D: usize> {
    /// The particle i and the j (indices into the atoms, owned then ghosts), for styles that
    /// keep per-particle values beside the records (sph/lj: the sound speed).
    pub i: usize,
    pub j: [usize; LANES],
    /// Types of the j.
    pub tj: [usize; LANES],
    /// x_i - x_j
    pub del: [L; D],
    pub rsq: L,
    /// sqrt(rsq), taken as soon as rsq is known: its latency is the batch's longest, and taken
    /// inside the style's arithmetic it stalled the loop (dambreak2d: 15% of the loop's samples)
    pub r: L,
    /// The j's velocity (estimate) and style scalars, as in [`Packed`].
    pub v: [L; D],
    pub a: L,
    pub b: L,
    /// The j's masses (per type, as LAMMPS' SPH styles use them).
    pub m: L,
}

/// What a batch of SPH pairs contributes, per lane: force on i (j gets the opposite), density
/// and energy rates of i and j, and the scalar LAMMPS tallies in the virial (`fpair`).
#[derive(Clone, Copy, Debug)]
pub struct SphContribution<const D: usize> {
    pub f: [L; D],
    pub fpair: L,
    pub drho_i: L,
    pub drho_j: L,
    pub de_i: L,
    pub de_j: L,
}

impl<const D: usize> Default for SphContribution<D> {
    fn default() -> Self {
        let z = L::default();
        SphContribution { f: [z; D], fpair: z, drho_i: z, drho_j: z, de_i: z, de_j: z }
    }
}

/// `sum_k a[k][l] * b[k][l]` lane by lane, k in order (LAMMPS' `delx*velx + dely*vely + ...`).
#[inline(always)]
pub fn dot_lanes<const D: usize>(a: &[L; D], b: &[L; D]) -> L {
    let mut s = a[0] * b[0];
    for k in 1..D {
        s += a[k] * b[k];
    }
    s
}

/// One particle as the loop reads it (see the module text).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(64))]
struct Record([[f64; 4]; 2]);

impl Record {
    fn new<const D: usize>(p: &Packed, m: f64) -> Record {
        if D == 2 {
            Record([[p.x[0], p.x[1], p.v[0], p.v[1]], [p.a, p.b, m, 0.0]])
        } else {
            Record([[p.x[0], p.x[1], p.x[2], p.v[0]], [p.v[1], p.v[2], p.a, p.b]])
        }
    }
    /// The style's record back (2D: z of position and velocity 0; the loop passes positions
    /// only as differences).
    #[inline(always)]
    fn packed<const D: usize>(&self) -> Packed {
        let [r, s] = self.0;
        if D == 2 {
            Packed { x: [r[0], r[1], 0.0], v: [r[2], r[3], 0.0], a: s[0], b: s[1] }
        } else {
            Packed { x: [r[0], r[1], r[2]], v: [r[3], s[0], s[1]], a: s[2], b: s[3] }
        }
    }
}

/// Write the neighbours j with `keep(j, rsq)` to `out` without branches; returns their count.
/// `out` must have room for all of `neigh`.
#[inline(always)]
fn gather_inside<'id, const D: usize>(neigh: &[Entry<'id>], recs: Reader<'id, '_, Record>, xi: [f64; 3], out: &mut [Entry<'id>], keep: impl Fn(Entry<'id>, f64) -> bool) -> usize {
    let out = &mut out[..neigh.len()];
    let mut n_in = 0usize;
    for (&j, slot) in neigh.iter().zip(0..) {
        let xj = recs.get(j).0[0];
        let (dx, dy) = (xi[0] - xj[0], xi[1] - xj[1]);
        let rsq = if D == 2 {
            dx * dx + dy * dy
        } else {
            let dz = xi[2] - xj[2];
            dx * dx + dy * dy + dz * dz
        };
        let ok = keep(j, rsq);
        // n_in <= slot: every write lands inside `out`
        out[n_in.min(slot)] = j;
        n_in += ok as usize;
    }
    n_in
}

/// [`gather_inside`] in 2D for one cutoff `cutsq` for all partners, four neighbours at a time
/// (one transpose of their first rows gives the position differences as lane vectors); the same
/// rsq, so the same neighbours in the same order. (In 3D this measured slower than the scalar
/// gather, although it ran 10% fewer instructions.)
#[inline(always)]
fn gather_inside_uniform_2d<'id>(neigh: &[Entry<'id>], recs: Reader<'id, '_, Record>, xi: [f64; 3], out: &mut [Entry<'id>], cutsq: f64) -> usize {
    let quads = neigh.chunks_exact(LANES);
    let rest = quads.remainder();
    let out = &mut out[..neigh.len()];
    let c = L::splat(cutsq);
    let mut n_in = 0usize;
    for (q, slot) in quads.zip((0..).step_by(LANES)) {
        let j: [Entry; LANES] = std::array::from_fn(|l| q[l]);
        let r: [&Record; LANES] = j.map(|j| recs.get(j));
        let t = transpose4([&r[0].0[0], &r[1].0[0], &r[2].0[0], &r[3].0[0]]);
        let (dx, dy) = (xi[0] - t[0], xi[1] - t[1]);
        let inside = (dx * dx + dy * dy).lt_bits(&c);
        for (l, &jl) in j.iter().enumerate() {
            // n_in <= slot + l: every write lands inside `out`
            out[n_in.min(slot + l)] = jl;
            n_in += ((inside >> l) & 1) as usize;
        }
    }
    let done = neigh.len() - rest.len();
    n_in + gather_inside::<2>(rest, recs, xi, &mut out[n_in.min(done)..], |_, rsq| rsq < cutsq)
}

/// The SPH pair loop on the slab schedule (see [`super::for_each_chunk`]): Newton's third law
/// for owned partners, rates for both atoms, virial from `fpair` as LAMMPS' `ev_tally`.
///
/// For each atom the neighbours inside the cutoff are first gathered without branches (about
/// 40% of listed pairs lie in the skin, and a branch on that is badly predicted); only those go
/// through the kernel, [`LANES`] at a time. Contributions are gathered per atom and added to
/// the outputs at the end, in the order of a one-pair-at-a-time loop.
pub fn compute_sph<K: SphKernel>(kernel: &K, input: &PairInput, out: &mut PairOutput) -> Tally {
    let a = input.atoms;
    let nall = a.nall();
    // per-atom preparation in parallel (each record depends on its own atom only)
    if input.dimension == 2 {
        // a 2D record needs every particle in the plane of the first, at rest across it
        let z0 = a.x.first().map(|x| x[2]).unwrap_or(0.0);
        let rec = |p: &Packed, i: usize| (Record::new::<2>(p, input.type_mass[a.typ[i]]), p.x[2] != z0 || p.v[2] != 0.0);
        let (recs, off_plane) = records(nall, kernel, input, rec);
        if !off_plane {
            let t = sph_loop::<K, 2>(kernel, input, out, &recs);
            keep_records(recs);
            return t;
        }
        keep_records(recs);
    }
    let (recs, _) = records(nall, kernel, input, |p, _| (Record::new::<3>(p, 0.0), false));
    let t = sph_loop::<K, 3>(kernel, input, out, &recs);
    keep_records(recs);
    t
}

thread_local! {
    /// The records' storage, kept from one pass to the next: every record is rewritten each
    /// pass, so the buffer needs no clearing (a fresh zeroed one cost a memset of 64 bytes per
    /// particle per pass).
    static RECORDS: std::cell::RefCell<Vec<Record>> = const { std::cell::RefCell::new(Vec::new()) };
}

fn keep_records(v: Vec<Record>) {
    RECORDS.with(|r| *r.borrow_mut() = v);
}

/// The records of atoms `0..n`, `rec(packed, i)` of the kernel's records (in parallel ranges),
/// and whether `rec` flagged any atom. The kernel packs [`LANES`] atoms at a time. Written in
/// place: returned one by one and collected, a record went through the stack in scalar pieces
/// and was read back whole, a store-forwarding stall.
fn records<K: SphKernel>(n: usize, kernel: &K, input: &PairInput, rec: impl Fn(&Packed, usize) -> (Record, bool) + Sync) -> (Vec<Record>, bool) {
    const CHUNK: usize = 1024; // a multiple of LANES
    let mut v = RECORDS.with(|r| std::mem::take(&mut *r.borrow_mut()));
    // only new slots are initialised; the rest are overwritten below
    v.resize(n, Record::default());
    let flagged = std::sync::atomic::AtomicBool::new(false);
    ranges(n, CHUNK, AtomsMut::new(&mut v), |r, mut slots| {
        let slots = slots.slice(r.clone());
        let mut any = false;
        let mut quads = slots.chunks_exact_mut(LANES);
        let mut i = r.start;
        for quad in &mut quads {
            kernel.pack_lanes(input, i, |l, p| {
                let (rc, f) = rec(p, i + l);
                quad[l] = rc;
                any |= f;
            });
            i += LANES;
        }
        for slot in quads.into_remainder() {
            let (rc, f) = rec(&kernel.pack(input, i), i);
            *slot = rc;
            any |= f;
            i += 1;
        }
        if any {
            flagged.store(true, std::sync::atomic::Ordering::Relaxed);
        }
    });
    (v, flagged.into_inner())
}

/// The pairs of one batch that the energy-step tallies read: the first `n` lanes.
struct Pairs<const D: usize> {
    i: usize,
    n: usize,
    js: [usize; LANES],
    del: [L; D],
    fpair: L,
    f: [L; D],
}

/// The virial of a batch's pairs (LAMMPS' `ev_tally`, or `ev_tally_xyz` for a force not along
/// the pair, `central` false) and, for compute pe/atom and stress/atom, each pair's share.
/// Only energy steps come here, out of line: inlined, its `Vec` growth and its copies of the
/// batch shaped the every-step loop (dambreak2d: 9% more instructions).
#[cold]
#[inline(never)]
fn tally_batch<const D: usize>(t: &mut Tally, mut shares: Option<&mut Vec<PairShare>>, central: bool, nlocal: usize, p: &Pairs<D>) {
    for (l, &j) in p.js[..p.n].iter().enumerate() {
        let w = if j < nlocal { 1.0 } else { 0.5 };
        let d: [f64; 3] = std::array::from_fn(|k| if k < D { p.del[k][l] } else { 0.0 });
        if central {
            t.central(w, 0.0, d, p.fpair[l]);
        } else {
            t.xyz(w, d, std::array::from_fn(|k| if k < D { p.f[k][l] } else { 0.0 }));
        }
        if let Some(s) = shares.as_deref_mut() {
            s.push(PairShare::central(p.i, j, 0.0, d, p.fpair[l]));
        }
    }
}

fn sph_loop<K: SphKernel, const D: usize>(kernel: &K, input: &PairInput, out: &mut PairOutput, recs: &[Record]) -> Tally {
    let a = input.atoms;
    let nlocal = a.nlocal;
    let stride = input.ntypes + 1;
    let typ: Vec<u32> = a.typ.iter().map(|&t| t as u32).collect();
    // per owned atom: 2D [fx fy drho desph]; 3D [fx fy fz drho] and desph
    let mut acc = vec![L::default(); nlocal];
    let mut acc_e = vec![0.0f64; if D == 3 { nlocal } else { 0 }];
    let eflag = input.eflag;
    let record = eflag && out.peratom.is_some();
    // types i whose cutoff is the same for every partner type, with no type filter (the common
    // case): their cutoff test needs no partner types
    let uniform_cut: Vec<Option<f64>> = (0..stride)
        .map(|ti| {
            let row = &kernel.cutsq_row(ti)[1..];
            let same = input.type_filter.is_none() && !row.is_empty() && row.iter().all(|&c| c == row[0]);
            if same { Some(row[0]) } else { None }
        })
        .collect();
    // the sums go to the outputs chunk by chunk as chunks complete, added to what other styles
    // (hybrid/overlay) put there already
    let [first, second] = kernel.rates();
    let (forces, first, second) = out.forces_and_rates(first, second);
    let (has_first, has_second) = (!first.is_empty(), !second.is_empty());
    let list = input.list;
    let nchunks = list.chunks.len();
    let bounds = list.bounds();
    // each chunk's tallies and, for compute pe/atom and stress/atom, its pairs' virials
    let mut parts = vec![(Tally::default(), Vec::new()); nchunks];
    let nall = a.nall();
    for parity in 0..2 {
        let windows = (AtomsMut::new(&mut acc), AtomsMut::new(&mut acc_e), AtomsMut::new(forces), AtomsMut::new(&mut *first), AtomsMut::new(&mut *second));
        slab_phase(&bounds, parity, windows, &mut parts, |c, (acc, acc_e, mut f, mut first, mut second)| {
        // neighbour entries read the records and types unchecked (both hold every atom), and
        // write the sums of owned partners unchecked (the list's owned entries lie in the window)
        scope_writing(nall, nlocal, acc.range(), |s| {
        let (recs_of, typ_of) = (s.reader(recs), s.reader(&typ));
        let mut acc = s.writer(acc);
        let mut acc_e = (D == 3).then(|| s.writer(acc_e));
        let chunk = &list.chunks[c];
        let view = chunk.view(&s);
        let mut t = Tally::default();
        let mut shares: Vec<PairShare> = Vec::new();
        let mut inside: Vec<Entry> = Vec::new();
        for i in chunk.start..chunk.end {
            let pi = recs[i].packed::<D>();
            let xi = pi.x;
            let ti = typ[i] as usize;
            let cutsq = kernel.cutsq_row(ti);
            let filter = input.type_filter.map(|fl| &fl[ti * stride..(ti + 1) * stride]);
            // gather the neighbours inside the cutoff (and the type filter), branch-free; room
            // for every neighbour and the padding of the last batch
            let neigh = view.of(i);
            if let Some(&first) = neigh.first() {
                if inside.len() < neigh.len() + LANES {
                    inside.resize(neigh.len() + LANES, first);
                }
            }
            let n_in = match uniform_cut[ti] {
                Some(c) if D == 2 => gather_inside_uniform_2d(neigh, recs_of, xi, &mut inside, c),
                Some(c) => gather_inside::<D>(neigh, recs_of, xi, &mut inside, |_, rsq| rsq < c),
                None => gather_inside::<D>(neigh, recs_of, xi, &mut inside, |j, rsq| {
                    let tj = *typ_of.get(j) as usize;
                    rsq < cutsq[tj] && filter.map(|fl| fl[tj]).unwrap_or(true)
                }),
            };
            let mut own = L::default();
            let mut own_e = 0.0;
            // pad to whole batches with copies of the first neighbour (their results are ignored)
            let padded = n_in.next_multiple_of(LANES);
            for k in n_in..padded {
                inside[k] = inside[0];
            }
            for (start, batch) in (0..n_in).step_by(LANES).zip(inside[..padded].chunks_exact(LANES)) {
                let n = (n_in - start).min(LANES);
                let es: [Entry; LANES] = std::array::from_fn(|l| batch[l]);
                let js = es.map(Entry::index);
                let rj: [&Record; LANES] = es.map(|e| recs_of.get(e));
                let c0 = transpose4([&rj[0].0[0], &rj[1].0[0], &rj[2].0[0], &rj[3].0[0]]);
                let c1 = transpose4([&rj[0].0[1], &rj[1].0[1], &rj[2].0[1], &rj[3].0[1]]);
                let tj = es.map(|e| *typ_of.get(e) as usize);
                let (xj, vj, aj, bj, mj): ([L; D], [L; D], L, L, L) = if D == 2 {
                    (std::array::from_fn(|k| c0[k]), std::array::from_fn(|k| c0[2 + k]), c1[0], c1[1], c1[2])
                } else {
                    let v3 = [c0[3], c1[0], c1[1]];
                    (std::array::from_fn(|k| c0[k]), std::array::from_fn(|k| v3[k]), c1[2], c1[3], lanes(|l| input.type_mass[tj[l]]))
                };
                let del: [L; D] = std::array::from_fn(|k| xi[k] - xj[k]);
                let rsq = dot_lanes(&del, &del);
                let b = Batch { i, j: js, tj, del, rsq, r: rsq.sqrt(), v: vj, a: aj, b: bj, m: mj };
                let c = kernel.pair_lanes::<D>(input, &pi, ti, &b);
                // rows per lane: what i gets and what j gets (minus the force)
                let nf: [L; D] = c.f.map(|f| -f);
                let (ri, rj) = if D == 2 {
                    (transpose4([&c.f[0].0, &c.f[1].0, &c.drho_i.0, &c.de_i.0]), transpose4([&nf[0].0, &nf[1].0, &c.drho_j.0, &c.de_j.0]))
                } else {
                    (transpose4([&c.f[0].0, &c.f[1].0, &c.f[D - 1].0, &c.drho_i.0]), transpose4([&nf[0].0, &nf[1].0, &nf[D - 1].0, &c.drho_j.0]))
                };
                // apply in list order (the sums of a one-pair-at-a-time loop)
                let apply = |l: usize| {
                    own += ri[l];
                    if D == 3 {
                        own_e += c.de_i[l];
                    }
                    if let Some(j) = s.owned(es[l]) {
                        *acc.at(j) += rj[l];
                        if let Some(acc_e) = &mut acc_e {
                            *acc_e.at(j) += c.de_j[l];
                        }
                    }
                };
                for_each_lane(n, apply);
                if eflag {
                    // copied here, on energy steps only: a reference to `b` or `c` would keep
                    // them in memory on every step
                    let pairs = Pairs { i, n, js, del: b.del, fpair: c.fpair, f: c.f };
                    tally_batch(&mut t, record.then_some(&mut shares), K::CENTRAL || !input.newton_pair, nlocal, &pairs);
                }
            }
            acc[i] += own;
            if let Some(acc_e) = &mut acc_e {
                acc_e[i] += own_e;
            }
        }
        // chunks no task adds to any more: their sums to the outputs, while in this core's cache
        for done in completed_after(c, nchunks) {
            for i in list.chunks[done].start..list.chunks[done].end {
                let r = acc[i];
                // 2D: fx fy drho desph; 3D: fx fy fz drho, desph beside
                let (fz, rho_rate, e_rate) = match &acc_e {
                    None => (0.0, r[2], r[3]),
                    Some(e) => (r[2], r[3], e[i]),
                };
                let fi = &mut f[i];
                fi[0] += r[0];
                fi[1] += r[1];
                fi[2] += fz;
                if has_first {
                    first[i] += rho_rate;
                }
                if has_second {
                    second[i] += e_rate;
                }
            }
        }
        (t, shares)
        })
        });
    }
    if let Some(pa) = out.peratom.as_deref_mut() {
        parts.iter().for_each(|(_, s)| pa.add_pairs(s));
    }
    sum_tallies(parts.iter().map(|p| &p.0))
}
