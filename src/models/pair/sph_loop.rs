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

use crate::engine::par::lanes::{for_each_lane, lanes, transpose4, L, LANES};
use super::sph::{Packed, SphKernel};
use super::{at, for_each_chunk_then, sum_tallies, PairInput, PairOutput, SharedMut, Tally};
use crate::engine::neighbor::NEIGH_MASK;

/// Up to [`LANES`] neighbours j of one particle i, field by field (unused lanes repeat lane 0;
/// their results are ignored). `D` is the dimension of the vectors.
#[derive(Clone, Copy, Debug)]
pub struct Batch<const D: usize> {
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
fn gather_inside<const D: usize>(neigh: &[u32], recs: &[Record], xi: [f64; 3], out: *mut u32, keep: impl Fn(usize, f64) -> bool) -> usize {
    let mut n_in = 0usize;
    for &jraw in neigh {
        let j = (jraw & NEIGH_MASK) as usize;
        let xj = at(recs, j).0[0];
        let (dx, dy) = (xi[0] - xj[0], xi[1] - xj[1]);
        let rsq = if D == 2 {
            dx * dx + dy * dy
        } else {
            let dz = xi[2] - xj[2];
            dx * dx + dy * dy + dz * dz
        };
        let ok = keep(j, rsq);
        // SAFETY: the caller reserved room for every neighbour
        unsafe { *out.add(n_in) = j as u32 };
        n_in += ok as usize;
    }
    n_in
}

/// [`gather_inside`] in 2D for one cutoff `cutsq` for all partners, four neighbours at a time
/// (one transpose of their first rows gives the position differences as lane vectors); the same
/// rsq, so the same neighbours in the same order. (In 3D this measured slower than the scalar
/// gather, although it ran 10% fewer instructions.)
#[inline(always)]
fn gather_inside_uniform_2d(neigh: &[u32], recs: &[Record], xi: [f64; 3], out: *mut u32, cutsq: f64) -> usize {
    let quads = neigh.chunks_exact(LANES);
    let rest = quads.remainder();
    let c = L::splat(cutsq);
    let mut n_in = 0usize;
    for q in quads {
        let j: [u32; LANES] = std::array::from_fn(|l| q[l] & NEIGH_MASK);
        // SAFETY: neighbour indices are below nall = recs.len()
        let r: [&Record; LANES] = j.map(|j| unsafe { recs.get_unchecked(j as usize) });
        let t = transpose4([&r[0].0[0], &r[1].0[0], &r[2].0[0], &r[3].0[0]]);
        let (dx, dy) = (xi[0] - t[0], xi[1] - t[1]);
        let inside = (dx * dx + dy * dy).lt_bits(&c);
        for (l, &jl) in j.iter().enumerate() {
            // SAFETY: the caller reserved room for every neighbour
            unsafe { *out.add(n_in) = jl };
            n_in += ((inside >> l) & 1) as usize;
        }
    }
    // SAFETY: room for the rest follows the n_in written
    n_in + gather_inside::<2>(rest, recs, xi, unsafe { out.add(n_in) }, |_, rsq| rsq < cutsq)
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
    let parallel = rayon::current_num_threads() > 1 && nall >= super::PARALLEL_MIN_ATOMS;
    // per-atom preparation in parallel (each record depends on its own atom only)
    if input.dimension == 2 {
        // a 2D record needs every particle in the plane of the first, at rest across it
        let z0 = a.x.first().map(|x| x[2]).unwrap_or(0.0);
        let rec = |p: &Packed, i: usize| (Record::new::<2>(p, at(input.type_mass, a.typ[i])), p.x[2] != z0 || p.v[2] != 0.0);
        let (recs, off_plane) = records(nall, parallel, kernel, input, rec);
        if !off_plane {
            return sph_loop::<K, 2>(kernel, input, out, &recs);
        }
    }
    let (recs, _) = records(nall, parallel, kernel, input, |p, _| (Record::new::<3>(p, 0.0), false));
    sph_loop::<K, 3>(kernel, input, out, &recs)
}

/// The records of atoms `0..n`, `rec(packed, i)` of the kernel's records (in parallel when
/// `parallel`), and whether `rec` flagged any atom. The kernel packs [`LANES`] atoms at a time.
/// Written in place: returned one by one and collected, a record went through the stack in
/// scalar pieces and was read back whole, a store-forwarding stall.
fn records<K: SphKernel>(n: usize, parallel: bool, kernel: &K, input: &PairInput, rec: impl Fn(&Packed, usize) -> (Record, bool) + Sync) -> (Vec<Record>, bool) {
    const CHUNK: usize = 1024; // a multiple of LANES
    let mut v: Vec<Record> = Vec::with_capacity(n);
    let fill = |c: usize, slots: &mut [std::mem::MaybeUninit<Record>]| {
        let mut flagged = false;
        let mut quads = slots.chunks_exact_mut(LANES);
        let mut i = c * CHUNK;
        for quad in &mut quads {
            kernel.pack_lanes(input, i, |l, p| {
                let (r, f) = rec(p, i + l);
                quad[l].write(r);
                flagged |= f;
            });
            i += LANES;
        }
        for slot in quads.into_remainder() {
            let (r, f) = rec(&kernel.pack(input, i), i);
            slot.write(r);
            flagged |= f;
            i += 1;
        }
        flagged
    };
    let spare = &mut v.spare_capacity_mut()[..n];
    let flagged = if parallel {
        use rayon::prelude::*;
        spare.par_chunks_mut(CHUNK).enumerate().map(|(c, s)| fill(c, s)).reduce(|| false, |x, y| x | y)
    } else {
        spare.chunks_mut(CHUNK).enumerate().fold(false, |acc, (c, s)| acc | fill(c, s))
    };
    // SAFETY: every one of the n slots was written above
    unsafe { v.set_len(n) };
    (v, flagged)
}

fn sph_loop<K: SphKernel, const D: usize>(kernel: &K, input: &PairInput, out: &mut PairOutput, recs: &[Record]) -> Tally {
    let a = input.atoms;
    let nlocal = a.nlocal;
    let stride = input.ntypes + 1;
    let typ: Vec<u32> = a.typ.iter().map(|&t| t as u32).collect();
    // per owned atom: 2D [fx fy drho desph]; 3D [fx fy fz drho] and desph
    let mut acc = vec![L::default(); nlocal];
    let mut acc_e = vec![0.0f64; if D == 3 { nlocal } else { 0 }];
    let (shared, shared_e) = (SharedMut::new(&mut acc), SharedMut::new(&mut acc_e));
    let eflag = input.eflag;
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
    let has_rates = !out.drho.is_empty();
    let water = kernel.rate_is_water() && !out.dwater.is_empty();
    let (f, drho, desph, dwater) = (SharedMut::new(out.f), SharedMut::new(out.drho), SharedMut::new(out.desph), SharedMut::new(out.dwater));
    let flush = |chunk: &crate::engine::neighbor::ChunkList| {
        for i in chunk.start..chunk.end {
            // SAFETY: a complete chunk's atoms are touched by this task only (for_each_chunk_then);
            // the rate arrays are used only when they exist (has_rates, water)
            unsafe {
                let r = *shared.get(i);
                // 2D: fx fy drho desph; 3D: fx fy fz drho, desph beside
                let (fz, rho_rate, e_rate) = if D == 2 { (0.0, r[2], r[3]) } else { (r[2], r[3], *shared_e.get(i)) };
                let fi = f.get(i);
                fi[0] += r[0];
                fi[1] += r[1];
                fi[2] += fz;
                if water {
                    *dwater.get(i) += e_rate;
                } else if has_rates {
                    *drho.get(i) += rho_rate;
                    *desph.get(i) += e_rate;
                }
            }
        }
    };
    let parts = for_each_chunk_then(
        input.list,
        |chunk| {
            // the task's own copies: values read through the closure's captures were loaded
            // again after every store to the accumulators
            let (shared, shared_e, nlocal) = (shared, shared_e, nlocal);
            let mut t = Tally::default();
            let mut inside: Vec<u32> = Vec::with_capacity(128);
            for i in chunk.start..chunk.end {
                let pi = recs[i].packed::<D>();
                let xi = pi.x;
                let ti = typ[i] as usize;
                let cutsq = kernel.cutsq_row(ti);
                let filter = input.type_filter.map(|fl| &fl[ti * stride..(ti + 1) * stride]);
                // gather the neighbours inside the cutoff (and the type filter), branch-free
                let neigh = chunk.neighbors(i);
                inside.clear();
                inside.reserve(neigh.len() + LANES);
                let n_in = match uniform_cut[ti] {
                    Some(c) if D == 2 => gather_inside_uniform_2d(neigh, recs, xi, inside.as_mut_ptr(), c),
                    Some(c) => gather_inside::<D>(neigh, recs, xi, inside.as_mut_ptr(), |_, rsq| rsq < c),
                    None => gather_inside::<D>(neigh, recs, xi, inside.as_mut_ptr(), |j, rsq| {
                        let tj = at(&typ, j) as usize;
                        rsq < at(cutsq, tj) && filter.map(|fl| at(fl, tj)).unwrap_or(true)
                    }),
                };
                // SAFETY: the first n_in entries were written
                unsafe { inside.set_len(n_in) };
                let mut own = L::default();
                let mut own_e = 0.0;
                // pad to whole batches with copies of the first neighbour (their results are ignored)
                if n_in > 0 {
                    while inside.len() % LANES != 0 {
                        inside.push(inside[0]);
                    }
                }
                for (start, batch) in (0..n_in).step_by(LANES).zip(inside.chunks_exact(LANES)) {
                    let n = (n_in - start).min(LANES);
                    let js: [usize; LANES] = std::array::from_fn(|l| batch[l] as usize);
                    // SAFETY: neighbour indices are below nall = recs.len()
                    let rj: [&Record; LANES] = js.map(|j| unsafe { recs.get_unchecked(j) });
                    let c0 = transpose4([&rj[0].0[0], &rj[1].0[0], &rj[2].0[0], &rj[3].0[0]]);
                    let c1 = transpose4([&rj[0].0[1], &rj[1].0[1], &rj[2].0[1], &rj[3].0[1]]);
                    let tj = js.map(|j| at(&typ, j) as usize);
                    let (xj, vj, aj, bj, mj): ([L; D], [L; D], L, L, L) = if D == 2 {
                        (std::array::from_fn(|k| c0[k]), std::array::from_fn(|k| c0[2 + k]), c1[0], c1[1], c1[2])
                    } else {
                        let v3 = [c0[3], c1[0], c1[1]];
                        (std::array::from_fn(|k| c0[k]), std::array::from_fn(|k| v3[k]), c1[2], c1[3], lanes(|l| at(input.type_mass, tj[l])))
                    };
                    let del: [L; D] = std::array::from_fn(|k| xi[k] - xj[k]);
                    let rsq = dot_lanes(&del, &del);
                    let b = Batch { tj, del, rsq, r: rsq.sqrt(), v: vj, a: aj, b: bj, m: mj };
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
                        let j = js[l];
                        own += ri[l];
                        if D == 3 {
                            own_e += c.de_i[l];
                        }
                        if j < nlocal {
                            // SAFETY: an owned j is in this chunk or the next (slab schedule)
                            unsafe {
                                *shared.get(j) += rj[l];
                                if D == 3 {
                                    *shared_e.get(j) += c.de_j[l];
                                }
                            }
                        }
                    };
                    for_each_lane(n, apply);
                    if eflag {
                        for l in 0..n {
                            let w = if js[l] < nlocal { 1.0 } else { 0.5 };
                            let fp = c.fpair[l];
                            let d: [f64; D] = std::array::from_fn(|k| b.del[k][l]);
                            t.virial[0] += w * d[0] * d[0] * fp;
                            t.virial[1] += w * d[1] * d[1] * fp;
                            t.virial[3] += w * d[0] * d[1] * fp;
                            if D == 3 {
                                t.virial[2] += w * d[D - 1] * d[D - 1] * fp;
                                t.virial[4] += w * d[0] * d[D - 1] * fp;
                                t.virial[5] += w * d[1] * d[D - 1] * fp;
                            }
                        }
                    }
                }
                // SAFETY: i belongs to this chunk
                unsafe {
                    *shared.get(i) += own;
                    if D == 3 {
                        *shared_e.get(i) += own_e;
                    }
                }
            }
            t
        },
        flush,
    );
    sum_tallies(&parts)
}
