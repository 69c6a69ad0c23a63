//! Per-atom energies and virials of the central loop (compute pe/atom and stress/atom):
//! a separate pass over the list, run only on steps that need them, so the force loop pays
//! nothing. Each listed pair gives half its energy and virial to each owned atom, as LAMMPS'
//! `ev_tally` (a pair with a ghost is listed by both owners, each taking its half).

use super::{CentralKernel, PairInput};
use crate::engine::neighbor::{special_level, NEIGH_MASK};
use crate::engine::tally::PerAtomTally;

/// Add every listed pair of `kernel` to the pair tallies of `out`.
pub fn central_peratom<K: CentralKernel>(kernel: &K, input: &PairInput, out: &mut PerAtomTally) {
    let a = input.atoms;
    let (nlocal, stride) = (a.nlocal, input.ntypes + 1);
    let sites = kernel.sites(input);
    let special = input.list.has_special;
    for chunk in &input.list.chunks {
        for i in chunk.start..chunk.end {
            let (xi, ti) = (a.x[i], a.typ[i]);
            let row = kernel.row(ti);
            for &jraw in chunk.neighbors(i) {
                let j = (jraw & NEIGH_MASK) as usize;
                let (xj, tj) = (a.x[j], a.typ[j]);
                if input.type_filter.is_some_and(|fl| !fl[ti * stride + tj]) {
                    continue;
                }
                let del = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
                let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                let p = &row[tj];
                // as the force loop: only pairs inside the cutoff (never a NaN distance)
                let inside = rsq < K::cutsq(p, &sites[i], &sites[j]);
                if !inside {
                    continue;
                }
                let factor = if special { input.special_lj[special_level(jraw)] } else { 1.0 };
                let (fpair, e) = K::eval::<true>(p, rsq, factor, &sites[i], &sites[j]);
                let v = [del[0] * del[0] * fpair, del[1] * del[1] * fpair, del[2] * del[2] * fpair, del[0] * del[1] * fpair, del[0] * del[2] * fpair, del[1] * del[2] * fpair];
                out.add(PerAtomTally::PAIR, i, 0.5, e, &v);
                if j < nlocal {
                    out.add(PerAtomTally::PAIR, j, 0.5, e, &v);
                }
            }
        }
    }
}
