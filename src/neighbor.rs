//! Neighbour search: periodic ghost images, cell binning, and half Verlet lists with a skin,
//! rebuilt by LAMMPS' rules (`neigh_modify every/delay/check`).
//!
//! Layout choices (see docs/performance.md):
//! * Owned atoms are re-sorted into bin order along one "slab" axis at every rebuild.
//! * A pair of owned atoms is listed once (at the lower index); a pair with a ghost is listed
//!   by the owned atom only and forces are applied to owned atoms only (LAMMPS' `newton off`
//!   treatment of ghost pairs), so forces never need to be folded back from ghosts.
//! * The owned atoms are cut into slab chunks at least one cutoff thick. A chunk writes only to
//!   its own atoms and to the next chunk's, so even chunks and then odd chunks can run in
//!   parallel without locks, and every atom receives its contributions in the same order
//!   whatever the number of threads: results are bit-identical across thread counts.

use crate::atoms::Atoms;
use crate::domain::Domain;
use crate::special::{minimum_image_check, pair_action, PairAction, SpecialFlag, SpecialList};
use rayon::prelude::*;

/// Bits of a neighbour entry that hold the special-bond level (as LAMMPS' SBBITS).
pub const SPECIAL_SHIFT: u32 = 30;
pub const NEIGH_MASK: u32 = (1 << SPECIAL_SHIFT) - 1;

/// Special level of a neighbour entry: 0 = ordinary pair, 1/2/3 = 1-2/1-3/1-4 neighbours.
#[inline]
pub fn special_level(j: u32) -> usize {
    (j >> SPECIAL_SHIFT) as usize
}

/// Special partner lists by atom ID and what the list does with each level.
#[derive(Clone, Debug)]
pub struct SpecialTable {
    /// Indexed by atom ID (empty lists for atoms without bonds).
    pub by_tag: Vec<SpecialList>,
    pub flags: [SpecialFlag; 4],
}

impl Default for SpecialTable {
    fn default() -> Self {
        SpecialTable { by_tag: Vec::new(), flags: [SpecialFlag::Normal; 4] }
    }
}

impl SpecialTable {
    pub fn is_empty(&self) -> bool {
        self.by_tag.iter().all(|l| l.ids.is_empty())
    }
    /// The action for pair (i, j): atom i's list is searched first (LAMMPS `find_special`);
    /// dmhs also searches atom j's, so the one-sided lists `special_bonds angle yes` can
    /// produce do not depend on which atom of the pair owns the list entry.
    #[inline]
    fn action(&self, itag: i64, jtag: i64, far_image: bool) -> PairAction {
        let empty = SpecialList::default();
        let li = self.by_tag.get(itag as usize).unwrap_or(&empty);
        match pair_action(&self.flags, li, jtag, far_image) {
            PairAction::Keep if li.level(jtag).is_none() => {
                let lj = self.by_tag.get(jtag as usize).unwrap_or(&empty);
                pair_action(&self.flags, lj, itag, far_image)
            }
            other => other,
        }
    }
}

/// `neigh_modify exclude ...` rules.
#[derive(Clone, Debug, Default)]
pub struct Exclusions {
    /// Excluded type pairs (both orders are excluded).
    pub types: Vec<(usize, usize)>,
    /// Excluded group pairs, as group bitmasks.
    pub groups: Vec<(u32, u32)>,
    /// `molecule/intra GROUP` (true) and `molecule/inter GROUP` (false), as group bitmasks.
    pub molecule: Vec<(u32, bool)>,
}

impl Exclusions {
    pub fn is_empty(&self) -> bool {
        self.types.is_empty() && self.groups.is_empty() && self.molecule.is_empty()
    }
    #[inline]
    fn excluded(&self, a: &Atoms, i: usize, j: usize) -> bool {
        let (ti, tj) = (a.typ[i], a.typ[j]);
        if self.types.iter().any(|&(p, q)| (p == ti && q == tj) || (p == tj && q == ti)) {
            return true;
        }
        let (mi, mj) = (a.mask[i], a.mask[j]);
        if self
            .groups
            .iter()
            .any(|&(g1, g2)| (mi & g1 != 0 && mj & g2 != 0) || (mi & g2 != 0 && mj & g1 != 0))
        {
            return true;
        }
        for &(g, intra) in &self.molecule {
            if mi & g != 0 && mj & g != 0 {
                let same = a.molecule[i] == a.molecule[j];
                if same == intra {
                    return true;
                }
            }
        }
        false
    }
}

/// Settings from `neighbor` and `neigh_modify`.
#[derive(Clone, Debug)]
pub struct NeighborSettings {
    pub skin: f64,
    pub every: i64,
    pub delay: i64,
    pub check: bool,
    pub once: bool,
    /// Bin size given by `neigh_modify binsize` (0 = half the largest cutoff, as LAMMPS).
    pub binsize: f64,
    pub exclusions: Exclusions,
}

impl NeighborSettings {
    pub fn new(skin: f64) -> NeighborSettings {
        NeighborSettings { skin, every: 1, delay: 0, check: true, once: false, binsize: 0.0, exclusions: Exclusions::default() }
    }
}

/// The neighbours of a contiguous range of owned atoms (one slab chunk).
#[derive(Clone, Debug, Default)]
pub struct ChunkList {
    /// Owned atoms `start..end`.
    pub start: usize,
    pub end: usize,
    /// `offsets[k]..offsets[k+1]` indexes `neigh` for atom `start + k`.
    pub offsets: Vec<u32>,
    /// Neighbour index with the special level in the top two bits.
    pub neigh: Vec<u32>,
}

impl ChunkList {
    #[inline]
    pub fn neighbors(&self, i: usize) -> &[u32] {
        let k = i - self.start;
        &self.neigh[self.offsets[k] as usize..self.offsets[k + 1] as usize]
    }
}

/// The half neighbour list, cut into slab chunks.
#[derive(Clone, Debug, Default)]
pub struct NeighList {
    pub chunks: Vec<ChunkList>,
    /// Squared list cutoff (cutoff + skin)^2 per type pair, row-major over `0..=ntypes`.
    pub cutneighsq: Vec<f64>,
    pub ntypes: usize,
}

impl NeighList {
    pub fn npairs(&self) -> usize {
        self.chunks.iter().map(|c| c.neigh.len()).sum()
    }
}

/// Neighbour-list state across steps.
#[derive(Clone, Debug, Default)]
pub struct Neighbor {
    pub list: NeighList,
    /// Positions at the last build (for the distance check).
    xhold: Vec<[f64; 3]>,
    /// Steps since the last build.
    pub ago: i64,
    pub nbuilds: u64,
    /// Builds triggered on the first step they were allowed (LAMMPS' "dangerous builds").
    pub ndanger: u64,
    /// Largest list cutoff (pair cutoff + skin): the ghost shell thickness.
    pub cutneighmax: f64,
}

/// Error raised while building lists (reported by the engine with the step number).
#[derive(Debug, Clone, PartialEq)]
pub enum NeighError {
    /// The ghost shell is thicker than the periodic box.
    BoxTooSmall { dim: usize, cut: f64, length: f64 },
    /// Non-finite coordinates.
    BadPosition { index: usize },
}

impl Neighbor {
    /// LAMMPS `Neighbor::decide`: is a rebuild due on this step?
    pub fn decide(&mut self, settings: &NeighborSettings, atoms: &Atoms) -> bool {
        self.ago += 1;
        if self.ago >= settings.delay && self.ago % settings.every == 0 {
            if settings.once {
                return false;
            }
            if !settings.check {
                return true;
            }
            let trigger = 0.5 * settings.skin;
            let triggersq = trigger * trigger;
            let moved = atoms.x[..atoms.nlocal].iter().zip(&self.xhold).any(|(x, h)| {
                let dx = x[0] - h[0];
                let dy = x[1] - h[1];
                let dz = x[2] - h[2];
                dx * dx + dy * dy + dz * dz > triggersq
            });
            if moved && self.ago == settings.every.max(settings.delay) {
                self.ndanger += 1;
            }
            return moved;
        }
        false
    }

    /// Rebuild: sort owned atoms into slab order, make ghosts, build the half list.
    /// `cutsq_pair(i, j)` is the squared interaction cutoff per type pair (0 = no interaction).
    /// Returns the permutation applied to owned atoms (`new k <- old order[k]`).
    #[allow(clippy::too_many_arguments)]
    pub fn build(
        &mut self,
        atoms: &mut Atoms,
        domain: &Domain,
        settings: &NeighborSettings,
        ntypes: usize,
        cut_pair: &dyn Fn(usize, usize) -> f64,
        special: &SpecialTable,
    ) -> Result<Vec<usize>, NeighError> {
        atoms.clear_ghosts();
        let n = atoms.nlocal;
        for (i, x) in atoms.x.iter().enumerate() {
            if !(x[0].is_finite() && x[1].is_finite() && x[2].is_finite()) {
                return Err(NeighError::BadPosition { index: i });
            }
        }

        // list cutoffs per type pair
        let stride = ntypes + 1;
        let mut cutneighsq = vec![0.0; stride * stride];
        let mut cutmax: f64 = 0.0;
        for it in 1..=ntypes {
            for jt in 1..=ntypes {
                let c = cut_pair(it, jt);
                if c > 0.0 {
                    let cn = c + settings.skin;
                    cutneighsq[it * stride + jt] = cn * cn;
                    cutmax = cutmax.max(cn);
                }
            }
        }
        self.cutneighmax = cutmax;
        let dim = domain.dimension;
        let prd = domain.prd();
        for d in 0..dim {
            if domain.periodic(d) && cutmax > prd[d] {
                return Err(NeighError::BoxTooSmall { dim: d, cut: cutmax, length: prd[d] });
            }
        }

        // grid over the owned atoms' extent widened by the ghost shell
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for x in &atoms.x[..n] {
            for d in 0..3 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        if n == 0 {
            lo = domain.lo;
            hi = domain.hi;
        }
        for d in 0..dim {
            if domain.periodic(d) {
                lo[d] = lo[d].min(domain.lo[d]);
                hi[d] = hi[d].max(domain.hi[d]);
            }
            lo[d] -= cutmax;
            hi[d] += cutmax;
        }
        let binsize = if settings.binsize > 0.0 { settings.binsize } else if cutmax > 0.0 { 0.5 * cutmax } else { 1.0 };
        let grid = Grid::new(lo, hi, binsize, dim, cutmax);
        // slab axis: the active dimension with the most bins
        let axis = (0..dim).max_by_key(|&d| grid.nb[d]).unwrap_or(0);

        // sort owned atoms by (slab plane, bin)
        let keys: Vec<u64> = atoms.x[..n].iter().map(|x| grid.sort_key(x, axis)).collect();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&i| keys[i]);
        atoms.permute(&order);

        // ghosts, dimension by dimension so edges and corners get images too (LAMMPS borders())
        if cutmax > 0.0 {
            for d in 0..dim {
                if !domain.periodic(d) {
                    continue;
                }
                let count = atoms.nall();
                for k in 0..count {
                    let (owner, mut shift) = if k < n {
                        (k, [0i8; 3])
                    } else {
                        (atoms.ghost_owner[k - n] as usize, atoms.ghost_shift[k - n])
                    };
                    let xk = atoms.x[k][d];
                    if xk < domain.lo[d] + cutmax {
                        shift[d] = 1;
                        atoms.push_ghost(owner, shift, prd);
                    }
                    if xk >= domain.hi[d] - cutmax {
                        shift[d] = -1;
                        atoms.push_ghost(owner, shift, prd);
                    }
                }
            }
        }

        // bin all atoms
        let nall = atoms.nall();
        let mut bin_of = vec![0usize; nall];
        let mut counts = vec![0u32; grid.total + 1];
        for (k, x) in atoms.x.iter().enumerate() {
            let b = grid.bin(x);
            bin_of[k] = b;
            counts[b + 1] += 1;
        }
        for b in 0..grid.total {
            counts[b + 1] += counts[b];
        }
        let bin_start = counts.clone();
        let mut fill = counts;
        let mut bin_atoms = vec![0u32; nall];
        for k in 0..nall {
            let b = bin_of[k];
            bin_atoms[fill[b] as usize] = k as u32;
            fill[b] += 1;
        }

        // stencil of bin offsets within reach of the cutoff
        let reach = grid.reach;
        let stencil = grid.stencil(cutmax);

        // slab chunks: consecutive planes along `axis`, at least `reach` planes thick
        let thick = reach[axis].max(1) as usize;
        let plane_of = |i: usize| grid.coord(atoms.x[i][axis], axis) as usize / thick;
        let mut bounds = vec![0usize];
        for i in 1..n {
            if plane_of(i) != plane_of(i - 1) {
                bounds.push(i);
            }
        }
        bounds.push(n);
        if n == 0 {
            bounds = vec![0, 0];
        }

        let a: &Atoms = atoms;
        let excl = &settings.exclusions;
        let use_special = !special.is_empty();
        let chunks: Vec<ChunkList> = bounds
            .windows(2)
            .collect::<Vec<_>>()
            .par_iter()
            .map(|w| {
                let (start, end) = (w[0], w[1]);
                let mut offsets = Vec::with_capacity(end - start + 1);
                let mut neigh = Vec::new();
                offsets.push(0u32);
                for i in start..end {
                    let xi = a.x[i];
                    let ti = a.typ[i];
                    let row = &cutneighsq[ti * stride..(ti + 1) * stride];
                    let bi = bin_of[i];
                    for &off in &stencil {
                        let b = (bi as i64 + off) as usize;
                        for &j in &bin_atoms[bin_start[b] as usize..bin_start[b + 1] as usize] {
                            let j = j as usize;
                            if j < n && j <= i {
                                continue;
                            }
                            let xj = a.x[j];
                            let dx = xi[0] - xj[0];
                            let dy = xi[1] - xj[1];
                            let dz = xi[2] - xj[2];
                            let rsq = dx * dx + dy * dy + dz * dz;
                            if rsq > row[a.typ[j]] {
                                continue;
                            }
                            if !excl.is_empty() && excl.excluded(a, i, j) {
                                continue;
                            }
                            let mut entry = j as u32;
                            if use_special {
                                let far = j >= n && minimum_image_check(domain, [dx, dy, dz]);
                                match special.action(a.tag[i], a.tag[j], far) {
                                    PairAction::Keep => {}
                                    PairAction::Exclude => continue,
                                    PairAction::Weighted(level) => entry |= (level as u32) << SPECIAL_SHIFT,
                                }
                            }
                            neigh.push(entry);
                        }
                    }
                    offsets.push(neigh.len() as u32);
                }
                ChunkList { start, end, offsets, neigh }
            })
            .collect();

        self.list = NeighList { chunks, cutneighsq, ntypes };
        self.xhold.clear();
        self.xhold.extend_from_slice(&atoms.x[..n]);
        self.ago = 0;
        self.nbuilds += 1;
        Ok(order)
    }
}

/// A regular grid of bins covering `lo..hi` plus a margin of `reach` bins on each side, so
/// that a stencil around any atom's bin stays inside the grid.
struct Grid {
    lo: [f64; 3],
    size: [f64; 3],
    inv: [f64; 3],
    nb: [usize; 3],
    reach: [i64; 3],
    total: usize,
}

impl Grid {
    fn new(lo: [f64; 3], hi: [f64; 3], binsize: f64, dim: usize, cut: f64) -> Grid {
        let mut nb = [1usize; 3];
        let mut size = [1.0; 3];
        let mut ext = [0.0; 3];
        let mut binsize = binsize;
        // keep the bin count bounded for very sparse systems
        loop {
            for d in 0..dim {
                ext[d] = (hi[d] - lo[d]).max(binsize);
                nb[d] = ((ext[d] / binsize) as usize).max(1);
                size[d] = ext[d] / nb[d] as f64;
            }
            if nb[0] * nb[1] * nb[2] <= 1 << 24 {
                break;
            }
            binsize *= 2.0;
        }
        let mut reach = [0i64; 3];
        let mut inv = [1.0; 3];
        let mut glo = lo;
        for d in 0..dim {
            reach[d] = (cut / size[d]).ceil() as i64;
            glo[d] = lo[d] - reach[d] as f64 * size[d];
            nb[d] += 2 * reach[d] as usize;
            inv[d] = 1.0 / size[d];
        }
        Grid { lo: glo, size, inv, nb, reach, total: nb[0] * nb[1] * nb[2] }
    }
    #[inline]
    fn coord(&self, x: f64, d: usize) -> usize {
        let c = ((x - self.lo[d]) * self.inv[d]).floor();
        if c <= 0.0 { 0 } else { (c as usize).min(self.nb[d] - 1) }
    }
    #[inline]
    fn bin(&self, x: &[f64; 3]) -> usize {
        let (cx, cy, cz) = (self.coord(x[0], 0), self.coord(x[1], 1), self.coord(x[2], 2));
        (cz * self.nb[1] + cy) * self.nb[0] + cx
    }
    /// Sort key: slab plane along `axis` first, then the bin index.
    fn sort_key(&self, x: &[f64; 3], axis: usize) -> u64 {
        ((self.coord(x[axis], axis) as u64) << 40) | self.bin(x) as u64
    }
    /// Bin-index offsets of every bin whose closest point can be within `cut`.
    fn stencil(&self, cut: f64) -> Vec<i64> {
        let reach = self.reach;
        let mut s = Vec::new();
        let (nx, ny) = (self.nb[0] as i64, self.nb[1] as i64);
        let gap = |k: i64, d: usize| if k == 0 { 0.0 } else { (k.abs() - 1) as f64 * self.size[d] };
        for k in -reach[2]..=reach[2] {
            for j in -reach[1]..=reach[1] {
                for i in -reach[0]..=reach[0] {
                    let (gx, gy, gz) = (gap(i, 0), gap(j, 1), gap(k, 2));
                    if gx * gx + gy * gy + gz * gz <= cut * cut * (1.0 + 1e-12) {
                        s.push((k * ny + j) * nx + i);
                    }
                }
            }
        }
        s
    }
}
