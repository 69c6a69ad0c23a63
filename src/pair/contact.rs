//! The engine's loop for granular contact styles (gran/hooke, gran/hooke/history, granular):
//! every listed pair that overlaps (r < R_i + R_j) gets a force and torques from the style's
//! [`ContactModel`], with its contact history (see [`crate::contact_history`]) read and written
//! next to the list entry. Forces and torques go to both atoms when both are owned; a pair with
//! a periodic image is computed from both sides and applied to the owned atom only. The slab
//! schedule of [`super::for_each_chunk`] keeps results identical for every thread count.

use super::{for_each_slab, sum_tallies, PairInput, PairOutput, SharedMut, Tally};
use crate::contact_history::{ContactHistory, HistoryChunk};
use crate::neighbor::{special_level, NEIGH_MASK};

/// What a contact model sees of one overlapping pair (i is the atom that lists the pair).
pub struct Contact<'a> {
    /// x_i - x_j
    pub del: [f64; 3],
    pub rsq: f64,
    pub radi: f64,
    pub radj: f64,
    pub vi: &'a [f64; 3],
    pub vj: &'a [f64; 3],
    pub omegai: &'a [f64; 3],
    pub omegaj: &'a [f64; 3],
    pub mi: f64,
    pub mj: f64,
}

/// A contact's result: the force on i (j gets its negative) and the torques on i and j.
pub struct ContactForce {
    pub f: [f64; 3],
    pub ti: [f64; 3],
    pub tj: [f64; 3],
}

/// A granular contact law.
pub trait ContactModel: Sync {
    type Params: Sync;
    /// History values per contact (0: the model keeps none).
    const HISTORY: usize;
    fn params(&self, ti: usize, tj: usize) -> &Self::Params;
    /// The contact of an overlapping pair; `hist` holds its history (empty without one), and
    /// `update` is false during run setup (LAMMPS' `shearupdate`).
    fn contact(p: &Self::Params, c: &Contact, hist: &mut [f64], update: bool, dt: f64) -> ContactForce;
}

/// Compute all contacts of the list. `history` must be given when `M::HISTORY > 0` (and
/// aligned with the list by [`ContactHistory::rebuilt`]).
pub fn compute_contacts<M: ContactModel>(model: &M, input: &PairInput, out: &mut PairOutput, history: Option<&mut ContactHistory>) -> Tally {
    let special = input.list.has_special;
    match (input.eflag, special || input.type_filter.is_some()) {
        (false, false) => contact_loop::<M, false, false>(model, input, out, history),
        (true, false) => contact_loop::<M, true, false>(model, input, out, history),
        (false, true) => contact_loop::<M, false, true>(model, input, out, history),
        (true, true) => contact_loop::<M, true, true>(model, input, out, history),
    }
}

/// `EXTRA`: special weights or a type filter (hybrid) apply.
fn contact_loop<M: ContactModel, const EFLAG: bool, const EXTRA: bool>(
    model: &M,
    input: &PairInput,
    out: &mut PairOutput,
    history: Option<&mut ContactHistory>,
) -> Tally {
    let a = input.atoms;
    let nlocal = a.nlocal;
    let nall = a.nall();
    assert!(a.radius.len() == nall && a.rmass.len() == nall && a.omega.len() == nall && a.v.len() == nall);
    assert!(out.f.len() >= nlocal && out.torque.len() >= nlocal);
    let hsize = M::HISTORY;
    let hist_shared: Option<SharedMut<HistoryChunk>> = match history {
        Some(h) if hsize > 0 => {
            assert!(h.size() == hsize && h.chunks.len() == input.list.chunks.len(), "contact history not aligned with the neighbour list");
            Some(h.shared())
        }
        _ => {
            assert!(hsize == 0, "a contact model with history needs its history store");
            None
        }
    };
    let stride = input.ntypes + 1;
    let fsh = SharedMut::new(out.f);
    let tsh = SharedMut::new(out.torque);
    let (x, v, omega, radius, rmass, typ) = (&a.x[..], &a.v[..], &a.omega[..], &a.radius[..], &a.rmass[..], &a.typ[..]);
    let update = input.advance;
    let dt = input.dt;
    let parts = for_each_slab(input.list.chunks.len(), |c| {
        let chunk = &input.list.chunks[c];
        let mut t = Tally::default();
        // SAFETY: chunk c of the store is used only by the work item of list chunk c
        let hist: Option<&mut HistoryChunk> = hist_shared.as_ref().map(|h| unsafe { h.get(c) });
        let (touch, values): (&mut [u8], &mut [f64]) = match hist {
            Some(h) => (&mut h.touch[..], &mut h.values[..]),
            None => (&mut [], &mut []),
        };
        for i in chunk.start..chunk.end {
            let xi = x[i];
            let radi = radius[i];
            let ti = typ[i];
            let k0 = chunk.offsets[i - chunk.start] as usize;
            let mut fi = [0.0f64; 3];
            let mut tqi = [0.0f64; 3];
            for (k, &jraw) in chunk.neighbors(i).iter().enumerate() {
                let j = (jraw & NEIGH_MASK) as usize;
                // SAFETY: the list builder stores only indices < nall, the length of every
                // per-atom array checked above
                let (xj, radj) = unsafe { (*x.get_unchecked(j), *radius.get_unchecked(j)) };
                let del = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
                let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                let radsum = radi + radj;
                let e = k0 + k;
                if rsq >= radsum * radsum {
                    // not touching: the contact (if any) is over
                    if hsize > 0 && touch[e] != 0 {
                        touch[e] = 0;
                        values[e * hsize..(e + 1) * hsize].iter_mut().for_each(|s| *s = 0.0);
                    }
                    continue;
                }
                let tj = unsafe { *typ.get_unchecked(j) };
                if EXTRA {
                    if let Some(filter) = input.type_filter {
                        if !filter[ti * stride + tj] {
                            continue;
                        }
                    }
                }
                let factor = if EXTRA { input.special_lj[special_level(jraw)] } else { 1.0 };
                if EXTRA && factor == 0.0 {
                    continue;
                }
                let mut empty: [f64; 0] = [];
                let h: &mut [f64] = if hsize > 0 {
                    touch[e] = 1;
                    &mut values[e * hsize..(e + 1) * hsize]
                } else {
                    &mut empty
                };
                // SAFETY: as above
                let c = unsafe {
                    Contact {
                        del,
                        rsq,
                        radi,
                        radj,
                        vi: v.get_unchecked(i),
                        vj: v.get_unchecked(j),
                        omegai: omega.get_unchecked(i),
                        omegaj: omega.get_unchecked(j),
                        mi: *rmass.get_unchecked(i),
                        mj: *rmass.get_unchecked(j),
                    }
                };
                let mut r = M::contact(model.params(ti, tj), &c, h, update, dt);
                if EXTRA && factor != 1.0 {
                    for d in 0..3 {
                        r.f[d] *= factor;
                        r.ti[d] *= factor;
                        r.tj[d] *= factor;
                    }
                }
                for d in 0..3 {
                    fi[d] += r.f[d];
                    tqi[d] += r.ti[d];
                }
                let w = if j < nlocal {
                    // SAFETY: j is an owned atom of this chunk or the next (see for_each_chunk)
                    let (fj, tqj) = unsafe { (fsh.get(j), tsh.get(j)) };
                    for d in 0..3 {
                        fj[d] -= r.f[d];
                        tqj[d] += r.tj[d];
                    }
                    1.0
                } else {
                    0.5
                };
                if EFLAG {
                    let f = r.f;
                    t.virial[0] += w * del[0] * f[0];
                    t.virial[1] += w * del[1] * f[1];
                    t.virial[2] += w * del[2] * f[2];
                    t.virial[3] += w * del[0] * f[1];
                    t.virial[4] += w * del[0] * f[2];
                    t.virial[5] += w * del[1] * f[2];
                }
            }
            // SAFETY: i belongs to this chunk
            let (fo, to) = unsafe { (fsh.get(i), tsh.get(i)) };
            for d in 0..3 {
                fo[d] += fi[d];
                to[d] += tqi[d];
            }
        }
        t
    });
    sum_tallies(&parts)
}
