//! Spatial decomposition of the box over ranks (LAMMPS' `comm_style brick`): a grid of Px x Py
//! x Pz sub-domains of equal size, each rank owning the atoms inside its own; ghosts are the
//! images of other ranks' atoms (and of its own across periodic faces) within the ghost cutoff
//! of the sub-domain. A pair with a ghost is listed by both owners, each taking its half (as in
//! a serial run), so forces never travel back: only positions and per-atom state go forward.
//!
//! Ranks sit in the grid as `processors` places them (by default as MPI's Cartesian topology
//! numbers them, z fastest; src/engine/procmap.rs).
//!
//! A triclinic box is cut in box fractions, as LAMMPS cuts it in lamda coordinates: from the
//! wrap of a rebuild to the list build its atoms are fractions, and migration, balancing and
//! the ghosts' selection work in [`frame`], the box of fractions, with the ghost cutoff's
//! [`reach`] across it; ghosts are placed back in the box with lamda2x.

use crate::engine::atoms::Atoms;
use crate::engine::comm::Comm;
use crate::engine::contact_history::{ContactHistory, ContactRecord};
use crate::engine::domain::Domain;
use crate::engine::procmap::Layout;
use std::sync::Arc;

/// The grid and this rank's place in it, the sub-domains, and the ghost exchange plan made at
/// the last rebuild.
pub struct Decomp {
    pub comm: Arc<dyn Comm>,
    pub procs: [usize; 3],
    /// Where each rank sits in the grid (`processors ... map`, `grid`).
    layout: Layout,
    /// Where the sub-domains are cut along each dimension, as fractions of the box (LAMMPS'
    /// xsplit, ysplit, zsplit): `procs[d] + 1` values from 0 to 1; uniform until balanced.
    splits: [Vec<f64>; 3],
    /// Ghosts: for each rank that receives some of this rank's atoms (itself included, for
    /// periodic images), the owned atoms sent and their periodic shifts, in the order sent.
    sends: Vec<(usize, Vec<(u32, [i8; 3])>)>,
    /// The number of ghosts received from each rank of `sends`, in ghost order.
    recv_counts: Vec<usize>,
    /// How many sub-domains away along each dimension the last [`Decomp::borders`] looked for
    /// ranks within the ghost cutoff (1: the next ones; more where sub-domains are thinner
    /// than the cutoff, as LAMMPS' multiple swaps): the same on every rank.
    hops: [usize; 3],
}

impl Decomp {
    pub fn new(comm: Arc<dyn Comm>, procs: [usize; 3]) -> Decomp {
        Decomp { comm, procs, layout: Layout::cartesian(procs), splits: procs.map(uniform), sends: Vec::new(), recv_counts: Vec::new(), hops: [1; 3] }
    }
    /// A new processor grid and placing of the ranks, cut uniformly.
    pub fn set_layout(&mut self, layout: Layout) {
        self.procs = layout.procs;
        self.splits = layout.procs.map(uniform);
        self.hops = [1; 3];
        self.layout = layout;
    }
    pub fn layout(&self) -> &Layout {
        &self.layout
    }
    /// The cuts along dimension `d` (fractions of the box).
    pub fn splits(&self, d: usize) -> &[f64] {
        &self.splits[d]
    }
    pub fn rank(&self) -> usize {
        self.comm.rank()
    }
    pub fn coords(&self, rank: usize) -> [usize; 3] {
        self.layout.place(rank)
    }
    pub fn rank_at(&self, c: [usize; 3]) -> usize {
        self.layout.rank_at(c)
    }
    /// Lower and upper bound of sub-domain `c` along `d` (LAMMPS: lo + prd * split[c], the last
    /// one ending exactly at the box's upper bound).
    fn bounds(&self, domain: &Domain, d: usize, c: usize) -> (f64, f64) {
        let p = self.procs[d];
        let prd = domain.hi[d] - domain.lo[d];
        let split = |k: usize| domain.lo[d] + prd * self.splits[d][k];
        let hi = if c + 1 == p { domain.hi[d] } else { split(c + 1) };
        (split(c), hi)
    }
    /// The sub-domain of a rank.
    pub fn subdomain(&self, domain: &Domain, rank: usize) -> ([f64; 3], [f64; 3]) {
        let c = self.coords(rank);
        let mut lo = domain.lo;
        let mut hi = domain.hi;
        for d in 0..3 {
            (lo[d], hi[d]) = self.bounds(domain, d, c[d]);
        }
        (lo, hi)
    }
    /// The rank whose sub-domain holds the point `x` of the box (outside the box: the nearest
    /// edge rank).
    pub fn owner(&self, domain: &Domain, x: &[f64; 3]) -> usize {
        self.owner_in(&frame(domain), &in_frame(domain, *x))
    }
    /// [`Decomp::owner`] of a position `x` in `frame` (see [`frame`]).
    fn owner_in(&self, domain: &Domain, x: &[f64; 3]) -> usize {
        let mut c = [0usize; 3];
        for d in 0..3 {
            let p = self.procs[d];
            // the last sub-domain whose lower bound is at or below x (NaN: the first), by
            // bisection: the lower bounds rise with k
            let (mut lo, mut hi) = (0, p);
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                if x[d] >= self.bounds(domain, d, mid).0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            c[d] = lo;
        }
        self.rank_at(c)
    }
    /// The ranks up to `hops[d]` sub-domains away from this one along each dimension (across
    /// periodic faces too), without itself, in rank order: with one hop the 26 next ones at most.
    fn peers(&self, domain: &Domain, hops: [usize; 3]) -> Vec<usize> {
        let me = self.rank();
        let c = self.coords(me);
        // the grid places along each dimension within reach
        let along: Vec<Vec<usize>> = (0..3)
            .map(|d| {
                let (p, k) = (self.procs[d] as i64, hops[d] as i64);
                let mut v: Vec<usize> = (c[d] as i64 - k..=c[d] as i64 + k)
                    .filter_map(|q| match (0..p).contains(&q) {
                        true => Some(q as usize),
                        false => domain.periodic(d).then(|| q.rem_euclid(p) as usize),
                    })
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            })
            .collect();
        let mut out = Vec::new();
        for &x in &along[0] {
            for &y in &along[1] {
                for &z in &along[2] {
                    out.push(self.rank_at([x, y, z]));
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out.retain(|&r| r != me);
        out
    }

    /// How many sub-domains away along each dimension one can lie within `reach` (in the frame
    /// of the box, see [`frame`]) of another: the next one, or more where the thinnest
    /// sub-domains are thinner than the reach. A sub-domain k hops away is separated from this
    /// one by k - 1 others, each at least the thinnest wide. Every rank has the same cuts, so the
    /// same hops: the relation is symmetric, as the exchange needs.
    fn hops_for(&self, domain: &Domain, reach: [f64; 3]) -> [usize; 3] {
        let mut hops = [1; 3];
        for d in 0..domain.dimension {
            let p = self.procs[d];
            let thinnest = (0..p).map(|c| self.bounds(domain, d, c)).map(|(lo, hi)| hi - lo).fold(f64::INFINITY, f64::min);
            // (floor + 1 rather than ceil: a reach of exactly k widths also touches the next)
            let k = (reach[d] / thinnest).floor();
            hops[d] = if k.is_finite() && k < p as f64 { k as usize + 1 } else { p };
        }
        hops
    }

    /// Atom counts of the owned atoms in [`BALANCE_BINS`] equal bins across the box, per
    /// dimension, summed over the ranks (`all`) or of this rank alone. `domain`: the frame the
    /// positions are in (see [`frame`]).
    pub fn histograms(&self, atoms: &Atoms, domain: &Domain, all: bool) -> [Vec<f64>; 3] {
        self.histograms_of(atoms.x[..atoms.nlocal].iter().copied(), domain, all)
    }
    /// [`Decomp::histograms`] of this rank's atoms at their places in the box (between runs,
    /// where every rank holds every atom).
    pub fn box_histograms(&self, atoms: &Atoms, domain: &Domain) -> [Vec<f64>; 3] {
        self.histograms_of(atoms.x[..atoms.nlocal].iter().map(|&x| in_frame(domain, x)), &frame(domain), false)
    }
    /// [`Decomp::histograms`] of the positions `xs`.
    fn histograms_of(&self, xs: impl Iterator<Item = [f64; 3]>, domain: &Domain, all: bool) -> [Vec<f64>; 3] {
        let mut h = [(); 3].map(|_| vec![0.0; BALANCE_BINS]);
        for x in xs {
            for d in 0..domain.dimension {
                let f = (x[d] - domain.lo[d]) / (domain.hi[d] - domain.lo[d]) * BALANCE_BINS as f64;
                let b = if f.is_nan() || f < 0.0 { 0 } else { (f as usize).min(BALANCE_BINS - 1) };
                h[d][b] += 1.0;
            }
        }
        if all {
            for v in &mut h {
                self.comm.sum(v);
            }
        }
        h
    }

    /// Move the cuts so that each slab of the grid holds the same share of the atoms counted
    /// in `hist` (LAMMPS' `balance shift` on every dimension with more than one rank), no
    /// sub-domain thinner than `cut`. Returns whether a cut moved.
    pub fn balance(&mut self, domain: &Domain, hist: &[Vec<f64>; 3], cut: f64) -> bool {
        let (reach, domain) = (reach(domain, cut), &frame(domain));
        let mut moved = false;
        for d in 0..domain.dimension {
            let p = self.procs[d];
            if p < 2 {
                continue;
            }
            // (a hair more than the cutoff: the widths computed back from the cuts round)
            if let Some(cuts) = balanced_cuts(&hist[d], p, reach[d] / (domain.hi[d] - domain.lo[d]) * (1.0 + 1e-12)) {
                moved |= cuts != self.splits[d];
                self.splits[d] = cuts;
            }
        }
        moved
    }

    /// The largest count of owned atoms on a rank over the mean (1: balanced).
    pub fn imbalance(&self, nlocal: usize) -> f64 {
        let (mut max, mut sum) = ([nlocal as f64], [nlocal as f64]);
        self.comm.max(&mut max);
        self.comm.sum(&mut sum);
        if sum[0] > 0.0 { max[0] * self.comm.size() as f64 / sum[0] } else { 1.0 }
    }

    /// Keep only the owned atoms inside this rank's sub-domain (every rank held them all).
    pub fn distribute(&self, atoms: &mut Atoms, domain: &Domain) {
        let me = self.rank();
        let remove: Vec<bool> = atoms.x[..atoms.nlocal].iter().map(|x| self.owner(domain, x) != me).collect();
        atoms.retain(&remove);
    }

    /// The ranks atoms can go to: the ranks the last ghost exchange reached (the neighbours in
    /// the grid, farther ones where sub-domains are thinner than the ghost cutoff), or
    /// (`anywhere`, after the cuts moved) every other rank.
    fn destinations(&self, domain: &Domain, anywhere: bool) -> Vec<usize> {
        match anywhere {
            true => (0..self.comm.size()).filter(|&r| r != self.rank()).collect(),
            false => self.peers(domain, self.hops),
        }
    }

    /// Send the owned atoms that left this sub-domain to the ranks that now own them (LAMMPS'
    /// `Comm::exchange`): the neighbouring ranks, or any rank (`anywhere`: after balancing).
    /// Positions are wrapped, in `domain`, the frame of the rebuild (see [`frame`]); no ghosts
    /// are present. Returns the IDs of the atoms that left and the ranks they went to.
    pub fn migrate(&self, atoms: &mut Atoms, domain: &Domain, anywhere: bool) -> Result<Vec<(i64, usize)>, String> {
        let me = self.rank();
        let peers = self.destinations(domain, anywhere);
        let mut bufs: Vec<Vec<f64>> = vec![Vec::new(); peers.len()];
        let mut remove = vec![false; atoms.nlocal];
        let mut departed = Vec::new();
        let mut stray = None;
        for i in 0..atoms.nlocal {
            let r = self.owner_in(domain, &atoms.x[i]);
            if r == me {
                continue;
            }
            match peers.iter().position(|&p| p == r) {
                Some(k) => {
                    atoms.pack(i, &mut bufs[k], true);
                    remove[i] = true;
                    departed.push((atoms.tag[i], r));
                }
                None => stray = Some(i),
            }
        }
        // every rank must take part in the exchange before one reports a stray atom
        let got = self.comm.exchange(peers.iter().copied().zip(bufs).collect(), &peers);
        if self.comm.any(stray.is_some()) {
            return Err(match stray {
                Some(i) => format!("atom {} moved past the next sub-domain since the last neighbour build", atoms.tag[i]),
                None => "an atom of another rank moved past the next sub-domain since the last neighbour build".to_string(),
            });
        }
        atoms.retain(&remove);
        for buf in got {
            atoms.unpack_owned(&buf);
        }
        Ok(departed)
    }

    /// Contact histories travel with their atoms (after [`Decomp::migrate`]): each rank an atom
    /// went to gets every contact of this rank that involves the atom, from either side, so the
    /// pairs it now lists find their history at the next alignment.
    pub fn carry_contacts(&self, history: &mut ContactHistory, departed: &[(i64, usize)], domain: &Domain, anywhere: bool) {
        let peers = self.destinations(domain, anywhere);
        let to: std::collections::HashMap<i64, usize> = departed.iter().filter_map(|&(tag, r)| Some((tag, peers.iter().position(|&p| p == r)?))).collect();
        let mut bufs: Vec<Vec<f64>> = vec![Vec::new(); peers.len()];
        if !to.is_empty() {
            for r in history.records() {
                let (a, b) = (to.get(&r.owner).copied(), to.get(&r.partner).copied());
                for k in [a, b.filter(|&k| Some(k) != a)].into_iter().flatten() {
                    pack_contact(&r, &mut bufs[k]);
                }
            }
        }
        let got = self.comm.exchange(peers.iter().copied().zip(bufs).collect(), &peers);
        history.adopt(got.iter().flat_map(|b| unpack_contacts(b)).collect());
    }

    /// Make the ghosts within `cut` of this sub-domain (LAMMPS' `Comm::borders`): every rank
    /// sends each rank within `cut` of it (the next ones, and farther ones where sub-domains are
    /// thinner than `cut`, as LAMMPS' multiple swaps reach them; itself across periodic faces)
    /// the images of its atoms that lie within `cut` of that rank's sub-domain, straight from
    /// their owner. `lamda`: the owned atoms' box fractions on a triclinic box (empty
    /// otherwise), where the images are chosen and made.
    pub fn borders(&mut self, atoms: &mut Atoms, domain: &Domain, cut: f64, lamda: &[[f64; 3]]) {
        let me = self.rank();
        let (f, reach) = (frame(domain), reach(domain, cut));
        self.hops = self.hops_for(&f, reach);
        let mut targets = self.peers(domain, self.hops);
        targets.push(me);
        targets.sort_unstable();
        let tilted = domain.triclinic();
        let pos: &[[f64; 3]] = if tilted { lamda } else { &atoms.x[..atoms.nlocal] };
        debug_assert_eq!(pos.len(), atoms.nlocal);
        let periods = f.periods();
        let shifts: Vec<[i8; 3]> = {
            let range = |d: usize| if d < domain.dimension && domain.periodic(d) { vec![-1i8, 0, 1] } else { vec![0i8] };
            let mut s = Vec::new();
            for a in range(0) {
                for b in range(1) {
                    for c in range(2) {
                        s.push([a, b, c]);
                    }
                }
            }
            s
        };
        // only an atom within `cut` of its own sub-domain's faces can lie within `cut` of
        // another sub-domain or of a periodic face (the sub-domains tile the box)
        let (my_lo, my_hi) = self.subdomain(&f, me);
        let near: Vec<usize> = (0..pos.len()).filter(|&i| (0..domain.dimension).any(|d| !(pos[i][d] >= my_lo[d] + reach[d] && pos[i][d] < my_hi[d] - reach[d]))).collect();
        // the images of each such atom that can reach any sub-domain: itself, and across a
        // periodic face only when it lies within `cut` of the opposite face
        let images: Vec<Vec<[i8; 3]>> = near
            .iter()
            .map(|&i| {
                let x = pos[i];
                shifts
                    .iter()
                    .copied()
                    .filter(|s| (0..3).all(|d| s[d] == 0 || (s[d] > 0 && x[d] < f.lo[d] + reach[d]) || (s[d] < 0 && x[d] >= f.hi[d] - reach[d])))
                    .collect()
            })
            .collect();
        self.sends.clear();
        for &q in &targets {
            let (lo, hi) = self.subdomain(&f, q);
            let mut list = Vec::new();
            for (&i, images) in near.iter().zip(&images) {
                for s in images {
                    if q == me && *s == [0, 0, 0] {
                        continue;
                    }
                    let x = periods.shifted(pos[i], *s);
                    if (0..domain.dimension).all(|d| x[d] >= lo[d] - reach[d] && x[d] < hi[d] + reach[d]) {
                        list.push((i as u32, *s));
                    }
                }
            }
            self.sends.push((q, list));
        }
        // a triclinic box's ghosts are placed from their fractions, as the serial build's
        let bufs = self.pack_sends(atoms, |a, i, s| if tilted { domain.lamda2x(periods.shifted(pos[i], s)) } else { periods.shifted(a.x[i], s) }, |a, i, x, s, out| a.pack_ghost(i, x, s, out));
        self.recv_counts.clear();
        for buf in bufs {
            let before = atoms.nall();
            atoms.unpack_ghosts(&buf);
            self.recv_counts.push(atoms.nall() - before);
        }
    }

    /// Forces on ghosts back to their owners, added to theirs (LAMMPS' reverse communication,
    /// for the bonded interactions a rank computes with ghosts).
    pub fn reverse_forces(&self, atoms: &mut Atoms) {
        let nlocal = atoms.nlocal;
        self.reverse_add(nlocal, atoms.f.as_flattened_mut(), 3);
    }

    /// The ghosts' values of a per-atom array (`width` values per atom, owned atoms then
    /// ghosts) added to their owners': each block of ghosts returns to the rank that sent it,
    /// in the order of its send list.
    pub fn reverse_add(&self, nlocal: usize, data: &mut [f64], width: usize) {
        let mut k = nlocal;
        let blocks = self
            .recv_counts
            .iter()
            .map(|&n| {
                k += n;
                data[(k - n) * width..k * width].to_vec()
            })
            .collect();
        let back = self.swap(blocks);
        for ((_, list), back) in self.sends.iter().zip(back) {
            for (&(i, _), g) in list.iter().zip(back.chunks_exact(width)) {
                let own = &mut data[i as usize * width..(i as usize + 1) * width];
                for d in 0..width {
                    own[d] += g[d];
                }
            }
        }
    }

    /// Fresh ghost positions from their owners (LAMMPS' forward communication of `x`).
    pub fn forward_positions(&self, atoms: &mut Atoms, domain: &Domain) {
        let bufs = self.pack_sends(atoms, at_shift(domain), |_, _, x, _, out| out.extend_from_slice(&x));
        let mut k = atoms.nlocal;
        for buf in bufs {
            for x in buf.chunks_exact(3) {
                atoms.x[k] = [x[0], x[1], x[2]];
                k += 1;
            }
        }
    }

    /// Fresh ghost positions and per-atom state (velocities, SPH/DEM values, ghost fields).
    pub fn forward_state(&self, atoms: &mut Atoms, domain: &Domain) {
        let bufs = self.pack_sends(atoms, at_shift(domain), |a, i, x, s, out| a.pack_ghost(i, x, s, out));
        let nlocal = atoms.nlocal;
        atoms.clear_ghosts();
        for buf in bufs {
            atoms.unpack_ghosts(&buf);
        }
        debug_assert_eq!(atoms.nlocal, nlocal);
    }

    /// Fresh ghost values of one per-atom field, read with `get` and written with `set` (the
    /// densities after a summation pass: LAMMPS' pair sph/rhosum forwards only them).
    pub fn forward_field(&self, atoms: &mut Atoms, domain: &Domain, get: fn(&Atoms) -> &[f64], set: fn(&mut Atoms) -> &mut [f64]) {
        let bufs = self.pack_sends(atoms, at_shift(domain), |a, i, _, _, out| out.push(get(a)[i]));
        let n = atoms.nlocal;
        let values = set(atoms);
        for (k, v) in bufs.into_iter().flatten().enumerate() {
            values[n + k] = v;
        }
    }

    /// The owners' values of one per-atom vector for every ghost, in ghost order, leaving the
    /// ghosts' own copies as they are (fix sph's fresh velocity estimates at a run's setup).
    pub fn owners_vectors(&self, atoms: &Atoms, domain: &Domain, get: fn(&Atoms) -> &[[f64; 3]]) -> Vec<[f64; 3]> {
        let bufs = self.pack_sends(atoms, at_shift(domain), |a, i, _, _, out| out.extend_from_slice(&get(a)[i]));
        bufs.concat().chunks_exact(3).map(|v| [v[0], v[1], v[2]]).collect()
    }

    /// Pack each send list with `pack(atoms, i, x, shift, out)`, `x` the image's position
    /// `place(atoms, i, shift)`, and exchange: the buffers received, in ghost order (by
    /// sending rank).
    fn pack_sends(&self, atoms: &Atoms, place: impl Fn(&Atoms, usize, [i8; 3]) -> [f64; 3], pack: impl Fn(&Atoms, usize, [f64; 3], [i8; 3], &mut Vec<f64>)) -> Vec<Vec<f64>> {
        let bufs = self
            .sends
            .iter()
            .map(|(_, list)| {
                let mut buf = Vec::new();
                for &(i, s) in list {
                    pack(atoms, i as usize, place(atoms, i as usize, s), s, &mut buf);
                }
                buf
            })
            .collect();
        self.swap(bufs)
    }

    /// One buffer for each rank of the send lists (in their order) sent to it, and the one it
    /// sent back received in its place (this rank's own buffer stays).
    fn swap(&self, mut bufs: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
        let me = self.rank();
        let ranks = self.recvs_order();
        let sends = ranks.iter().zip(&mut bufs).filter(|(&q, _)| q != me).map(|(&q, b)| (q, std::mem::take(b))).collect();
        let from: Vec<usize> = ranks.iter().copied().filter(|&r| r != me).collect();
        let mut got = self.comm.exchange(sends, &from).into_iter();
        ranks.iter().zip(bufs).map(|(&r, own)| if r == me { own } else { got.next().unwrap_or_default() }).collect()
    }

    /// The ranks ghosts come from, in ghost order (the same ranks this one sends to).
    fn recvs_order(&self) -> Vec<usize> {
        self.sends.iter().map(|s| s.0).collect()
    }

    /// Every rank's contacts on every rank (at the end of a run, with [`Decomp::gathered`]),
    /// each once: a contact with a ghost is kept by both its owners, from either side.
    pub fn gather_contacts(&self, history: &mut ContactHistory) {
        let mut buf = Vec::new();
        for r in history.records() {
            pack_contact(&r, &mut buf);
        }
        let mut seen = std::collections::HashSet::new();
        let mut all = Vec::new();
        for b in self.comm.allgather(buf) {
            for r in unpack_contacts(&b) {
                let key = if r.owner <= r.partner { (r.owner, r.partner, r.image) } else { (r.partner, r.owner, r.image.map(|m| -m)) };
                if seen.insert(key) {
                    all.push(r);
                }
            }
        }
        history.restore(all);
    }

    /// Every rank's owned atoms, in rank order, on every rank (at the end of a run, so that the
    /// commands between runs see the whole system as in a serial run; and for dumps).
    pub fn gathered(&self, atoms: &Atoms) -> Atoms {
        let mut buf = Vec::new();
        for i in 0..atoms.nlocal {
            atoms.pack(i, &mut buf, true);
        }
        let mut whole = atoms.empty_like();
        for b in self.comm.allgather(buf) {
            whole.unpack_owned(&b);
        }
        // the forces and torques of the last evaluation, which migration does not carry (dumps
        // of fx, and the commands after a run, read them), in the same rank order
        let n = atoms.nlocal;
        let sphere = atoms.features.sphere;
        let mine: Vec<f64> = atoms.f[..n].iter().chain(if sphere { &atoms.torque[..n] } else { &[] }).flatten().copied().collect();
        let mut k = 0;
        for part in self.comm.allgather(mine) {
            let m = part.len() / if sphere { 6 } else { 3 };
            for (j, c) in part.chunks_exact(3).enumerate() {
                let v = [c[0], c[1], c[2]];
                if j < m {
                    whole.f[k + j] = v;
                } else {
                    whole.torque[k + j - m] = v;
                }
            }
            k += m;
        }
        whole
    }
}

/// Cuts at 0, 1/p, 2/p, ..., 1 (LAMMPS' uniform split: c/P, so sub-domains are bitwise those of
/// LAMMPS).
fn uniform(p: usize) -> Vec<f64> {
    (0..=p).map(|k| k as f64 / p as f64).collect()
}

/// Bins of the atom-count histograms the balancer cuts at (per dimension).
pub const BALANCE_BINS: usize = 1024;

/// Cuts that give each of `p` slabs the same share of `hist` (atom counts in equal bins across
/// the box), each slab at least `minw` (a fraction of the box) thick: LAMMPS' `balance shift`
/// for one dimension, from a histogram. None when `p` slabs of `minw` do not fit.
pub fn balanced_cuts(hist: &[f64], p: usize, minw: f64) -> Option<Vec<f64>> {
    if minw * p as f64 > 1.0 {
        return None;
    }
    let total: f64 = hist.iter().sum();
    let nb = hist.len();
    let mut cuts = uniform(p);
    if total > 0.0 {
        // the fraction of the box below which a share k/p of the atoms lies (linear in a bin)
        let mut below = 0.0;
        let mut b = 0;
        for (k, cut) in cuts.iter_mut().enumerate().take(p).skip(1) {
            let want = total * k as f64 / p as f64;
            while b < nb && below + hist[b] < want {
                below += hist[b];
                b += 1;
            }
            let inside = if b < nb && hist[b] > 0.0 { (want - below) / hist[b] } else { 0.0 };
            *cut = ((b as f64 + inside) / nb as f64).clamp(0.0, 1.0);
        }
    }
    // every slab at least minw thick: push cuts up from the bottom, then down from the top
    for k in 1..p {
        cuts[k] = cuts[k].max(cuts[k - 1] + minw);
    }
    for k in (1..p).rev() {
        cuts[k] = cuts[k].min(cuts[k + 1] - minw);
    }
    Some(cuts)
}

/// A contact record as doubles: IDs, image, the number of values, the values.
fn pack_contact(r: &ContactRecord, out: &mut Vec<f64>) {
    out.extend_from_slice(&[r.owner as f64, r.partner as f64, r.image[0] as f64, r.image[1] as f64, r.image[2] as f64, r.values.len() as f64]);
    out.extend_from_slice(&r.values);
}

/// The records packed by [`pack_contact`] in `buf`.
fn unpack_contacts(mut buf: &[f64]) -> Vec<ContactRecord> {
    let mut out = Vec::new();
    while buf.len() >= 6 {
        let n = buf[5] as usize;
        let image = [buf[2] as i32, buf[3] as i32, buf[4] as i32];
        out.push(ContactRecord { owner: buf[0] as i64, partner: buf[1] as i64, image, values: buf[6..6 + n].to_vec() });
        buf = &buf[6 + n..];
    }
    out
}

/// The box in which a rebuild cuts and migrates the atoms: the box itself, or for a triclinic
/// box the box of its fractions ([`Domain::fractions`]), where its atoms then are.
pub fn frame(domain: &Domain) -> Domain {
    if domain.triclinic() { domain.fractions() } else { domain.clone() }
}

/// A point of the box in [`frame`]: its box fractions on a triclinic box.
pub fn in_frame(domain: &Domain, x: [f64; 3]) -> [f64; 3] {
    if domain.triclinic() { domain.x2lamda(x) } else { x }
}

/// How far a distance `cut` reaches along each dimension of [`frame`] (LAMMPS' cutghost).
pub fn reach(domain: &Domain, cut: f64) -> [f64; 3] {
    if domain.triclinic() { domain.lamda_reach(cut) } else { [cut; 3] }
}

/// The position of the image `s` of owned atom `i` between rebuilds: one period per shift
/// along each dimension, as a serial ghost is refreshed.
fn at_shift(domain: &Domain) -> impl Fn(&Atoms, usize, [i8; 3]) -> [f64; 3] {
    let periods = domain.periods();
    move |a, i, s| periods.shifted(a.x[i], s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_owner_is_the_last_sub_domain_starting_at_or_below_x() {
        use crate::engine::domain::BoundaryKind;
        let domain = Domain::new(3, [0.0; 3], [10.0; 3], [[BoundaryKind::Periodic; 2]; 3]);
        let mut d = Decomp::new(Arc::new(crate::engine::comm::Serial), [7, 1, 1]);
        d.splits[0] = vec![0.0, 0.05, 0.05, 0.3, 0.31, 0.6, 0.9, 1.0];
        let linear = |x: f64| (1..7).take_while(|&k| x >= d.bounds(&domain, 0, k).0).last().unwrap_or(0);
        for k in 0..=1200 {
            let x = -1.0 + k as f64 * 0.01;
            assert_eq!(d.owner(&domain, &[x, 5.0, 5.0]), linear(x), "x = {x}");
        }
        for x in [0.5, 3.0, 3.1, 9.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(d.owner(&domain, &[x, 5.0, 5.0]), linear(x), "x = {x}");
        }
    }

    #[test]
    fn balanced_cuts_split_the_counts_evenly_and_keep_the_least_thickness() {
        // all atoms in the lowest quarter, evenly
        let mut hist = vec![0.0; 8];
        hist[0] = 10.0;
        hist[1] = 10.0;
        assert_eq!(balanced_cuts(&hist, 2, 0.0).unwrap(), vec![0.0, 0.125, 1.0]);
        assert_eq!(balanced_cuts(&hist, 4, 0.0).unwrap(), vec![0.0, 0.0625, 0.125, 0.1875, 1.0]);
        // slabs at least 0.1 thick
        let c = balanced_cuts(&hist, 4, 0.1).unwrap();
        assert!(c.windows(2).all(|w| w[1] - w[0] >= 0.1 - 1e-15), "{c:?}");
        assert!(balanced_cuts(&hist, 4, 0.3).is_none());
        // no atoms: uniform
        assert_eq!(balanced_cuts(&[0.0; 8], 2, 0.0).unwrap(), vec![0.0, 0.5, 1.0]);
    }
}
