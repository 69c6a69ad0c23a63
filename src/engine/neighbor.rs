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

use crate::engine::atoms::{Atoms, IdKeys};
use crate::engine::domain::Domain;
use crate::engine::special::{minimum_image_check, PairAction, SpecialFlag, SpecialList};
use crate::engine::par::bounded::{Entries, Entry, Scope, INDEX_BITS, INDEX_MASK};

/// Builds (and edits) of neighbour lists in the process: each list's `generation`.
static BUILDS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

/// Bits of a neighbour entry that hold the special-bond level (as LAMMPS' SBBITS).
pub const SPECIAL_SHIFT: u32 = INDEX_BITS;
pub const NEIGH_MASK: u32 = INDEX_MASK;
/// Bytes per atom that must still be free after a list is built (room for the copies of
/// per-atom arrays that follow it in a rebuild and a step).
const HEADROOM_PER_ATOM: usize = 256;

/// Special level of a neighbour entry: 0 = ordinary pair, 1/2/3 = 1-2/1-3/1-4 neighbours.
#[inline]
pub fn special_level(j: u32) -> usize {
    (j >> SPECIAL_SHIFT) as usize
}

/// Special partner lists by atom ID (flattened: `partners[offsets[k]..offsets[k+1]]` are the
/// partners, with their level, of the atom whose ID has key `k` in `keys`: the ID itself for
/// dense IDs, see [`IdKeys`]) and what the list does with each level.
#[derive(Clone, Debug)]
pub struct SpecialTable {
    pub keys: IdKeys,
    pub offsets: Vec<u32>,
    pub partners: Vec<(i64, u8)>,
    pub flags: [SpecialFlag; 4],
    /// Every list is symmetric (true unless `special_bonds angle/dihedral yes` trimmed one
    /// side), so only atom i's list needs searching.
    pub symmetric: bool,
    /// Unique in the process for each table made or edited: what a neighbour build derived
    /// from a table ([`ActingCache`]) knows when it is stale.
    generation: u64,
}

/// Tables made or edited: each table's `generation`.
static SPECIAL_TABLES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

fn next_special_generation() -> u64 {
    SPECIAL_TABLES.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

impl Default for SpecialTable {
    fn default() -> Self {
        SpecialTable { keys: IdKeys::default(), offsets: vec![], partners: vec![], flags: [SpecialFlag::Normal; 4], symmetric: true, generation: next_special_generation() }
    }
}

impl SpecialTable {
    /// Flatten per-atom lists (`lists[k]` belongs to atom ID `ids[k]`).
    pub fn from_lists(ids: &[i64], lists: Vec<SpecialList>, flags: [SpecialFlag; 4], symmetric: bool) -> SpecialTable {
        let keys = IdKeys::new(ids);
        let mut by_key: Vec<Option<SpecialList>> = vec![None; keys.len()];
        for (k, l) in lists.into_iter().enumerate() {
            if let Some(key) = keys.key(ids[k]) {
                by_key[key] = Some(l);
            }
        }
        let mut offsets = Vec::with_capacity(keys.len() + 1);
        let mut partners = Vec::new();
        offsets.push(0u32);
        for l in &by_key {
            if let Some(l) = l {
                for &t in &l.ids {
                    partners.push((t, l.level(t).unwrap_or(0)));
                }
            }
            offsets.push(partners.len() as u32);
        }
        SpecialTable { keys, offsets, partners, flags, symmetric, generation: next_special_generation() }
    }
    pub fn is_empty(&self) -> bool {
        self.partners.is_empty()
    }
    /// Atoms `p` and `q` are no longer 1-2 partners (a bond between them broke; LAMMPS' fix
    /// update/special/bonds). Their other partners keep their levels.
    pub fn remove_one_two(&mut self, p: i64, q: i64) {
        self.generation = next_special_generation();
        for (a, b) in [(p, q), (q, p)] {
            let Some(t) = self.keys.key(a) else { continue };
            if t + 1 >= self.offsets.len() {
                continue;
            }
            let (lo, hi) = (self.offsets[t] as usize, self.offsets[t + 1] as usize);
            if let Some(e) = self.partners[lo..hi].iter_mut().find(|e| e.0 == b && e.1 == 1) {
                e.1 = 0;
            }
        }
    }
    /// Atom `itag`'s partners and their levels (0: a 1-2 partner whose bond broke).
    pub fn partners_of(&self, itag: i64) -> impl Iterator<Item = (i64, u8)> + '_ {
        let range = match self.keys.key(itag) {
            Some(t) if t + 1 < self.offsets.len() => self.offsets[t] as usize..self.offsets[t + 1] as usize,
            _ => 0..0,
        };
        self.partners[range].iter().copied()
    }
    /// The special level (0: none, 1-3) of atom `jtag` in atom `itag`'s list.
    #[inline]
    pub(crate) fn level(&self, itag: i64, jtag: i64) -> u8 {
        let Some(t) = self.keys.key(itag) else { return 0 };
        if t + 1 >= self.offsets.len() {
            return 0;
        }
        self.partners[self.offsets[t] as usize..self.offsets[t + 1] as usize].iter().find(|p| p.0 == jtag).map(|p| p.1).unwrap_or(0)
    }
    /// The partners of atom `itag` that change a pair (their level's flag excludes or weights
    /// it), appended to `out`, each ID as `level` finds it (its first entry): a neighbour build
    /// reads atom i's list once, then looks up only these for each of its pairs.
    fn acting_partners(&self, itag: i64, out: &mut Vec<(i64, u8)>) {
        let Some(t) = self.keys.key(itag) else { return };
        if t + 1 >= self.offsets.len() {
            return;
        }
        let list = &self.partners[self.offsets[t] as usize..self.offsets[t + 1] as usize];
        for (m, &(tag, level)) in list.iter().enumerate() {
            let acts = level != 0 && !matches!(self.flags[level as usize], SpecialFlag::Normal);
            if acts && !list[..m].iter().any(|p| p.0 == tag) {
                out.push((tag, level));
            }
        }
    }
    /// The action for pair (i, j): atom i's list is searched first (LAMMPS `find_special`);
    /// dmhs also searches atom j's when lists can be one-sided (`special_bonds angle yes`),
    /// so the result does not depend on which atom of the pair owns the list entry.
    #[inline]
    fn action(&self, itag: i64, jtag: i64, far_image: bool) -> PairAction {
        let mut level = self.level(itag, jtag);
        if level == 0 && !self.symmetric {
            level = self.level(jtag, itag);
        }
        self.flag_action(level, || far_image)
    }
    /// The action for a pair of partners at `level`; `far_image()` is asked only when the
    /// level excludes or weights the pair (a periodic image beyond half the box is kept).
    #[inline]
    fn flag_action(&self, level: u8, far_image: impl Fn() -> bool) -> PairAction {
        if level == 0 {
            return PairAction::Keep;
        }
        match self.flags[level as usize] {
            SpecialFlag::Normal => PairAction::Keep,
            _ if far_image() => PairAction::Keep,
            SpecialFlag::Exclude => PairAction::Exclude,
            SpecialFlag::Weighted => PairAction::Weighted(level),
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
    pub fn excluded(&self, a: &Atoms, i: usize, j: usize) -> bool {
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
    /// `neighbor skin multi` (lists as `bin` here; `comm_modify mode multi` requires it, as LAMMPS).
    pub multi: bool,
}

impl NeighborSettings {
    pub fn new(skin: f64) -> NeighborSettings {
        NeighborSettings { skin, every: 1, delay: 0, check: true, once: false, binsize: 0.0, exclusions: Exclusions::default(), multi: false }
    }
}

/// The neighbours of a contiguous range of owned atoms (one slab chunk). Its entries are
/// checked against the atoms they index when it is made, so loops read per-atom arrays
/// through them unchecked ([`crate::engine::par::bounded`]).
#[derive(Clone, Debug, Default)]
pub struct ChunkList {
    /// Owned atoms `start..end`.
    pub start: usize,
    pub end: usize,
    /// `offsets[k]..offsets[k+1]` indexes the entries of atom `start + k`.
    offsets: Vec<u32>,
    /// Neighbour index with the special level in the top two bits.
    neigh: Entries,
}

impl ChunkList {
    /// The list of atoms `start..end` whose neighbours are `neigh[offsets[k]..offsets[k + 1]]`,
    /// indexing `nall` atoms of which `nlocal` are owned.
    pub fn new(start: usize, end: usize, offsets: Vec<u32>, neigh: Vec<u32>, nlocal: usize, nall: usize) -> ChunkList {
        assert!(offsets.len() == end - start + 1 && offsets.windows(2).all(|w| w[0] <= w[1]) && offsets.last().is_none_or(|&o| o as usize == neigh.len()));
        ChunkList { start, end, offsets, neigh: Entries::new(neigh, nlocal, nall) }
    }
    /// The entries of atom `i` (index and special level).
    #[inline]
    pub fn neighbors(&self, i: usize) -> &[u32] {
        &self.neigh.raw()[self.span(i)]
    }
    /// The chunk's entries as values of scope `s`, checked against the scope once (for a loop
    /// over all its atoms).
    #[inline]
    pub fn view<'id>(&self, s: &Scope<'id>) -> ChunkView<'id, '_> {
        ChunkView { list: self, entries: self.neigh.view(s, 0..self.neigh.len()) }
    }
    #[inline]
    fn span(&self, i: usize) -> std::ops::Range<usize> {
        let k = i - self.start;
        self.offsets[k] as usize..self.offsets[k + 1] as usize
    }
    /// Position of atom `i`'s first entry among the chunk's entries (per-entry data such as
    /// contact histories are stored in that order).
    #[inline]
    pub fn first_entry(&self, i: usize) -> usize {
        self.offsets[i - self.start] as usize
    }
    /// Clear the special level of atom `i`'s entries whose atom `hit` accepts.
    pub fn clear_special(&mut self, i: usize, hit: impl Fn(usize) -> bool) {
        for k in self.span(i) {
            let j = self.neigh.raw()[k];
            if j > NEIGH_MASK && hit((j & NEIGH_MASK) as usize) {
                self.neigh.clear_level(k);
            }
        }
    }
    /// All entries of the chunk.
    pub fn len(&self) -> usize {
        self.neigh.len()
    }
    pub fn is_empty(&self) -> bool {
        self.neigh.is_empty()
    }
    pub fn raw(&self) -> &[u32] {
        self.neigh.raw()
    }
    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.neigh.capacity() * 4 + self.offsets.capacity() * 4
    }
}

/// A chunk's entries viewed in one scope ([`ChunkList::view`]).
pub struct ChunkView<'id, 'a> {
    list: &'a ChunkList,
    entries: &'a [Entry<'id>],
}

impl<'id, 'a> ChunkView<'id, 'a> {
    /// The entries of atom `i`.
    #[inline]
    pub fn of(&self, i: usize) -> &'a [Entry<'id>] {
        &self.entries[self.list.span(i)]
    }
}

/// The half neighbour list, cut into slab chunks.
#[derive(Clone, Debug, Default)]
pub struct NeighList {
    pub chunks: Vec<ChunkList>,
    /// Squared list cutoff (cutoff + skin)^2 per type pair, row-major over `0..=ntypes`.
    pub cutneighsq: Vec<f64>,
    /// Squared force cutoff per type pair, as the list was built for (LAMMPS' pair cutsq).
    pub cutsq: Vec<f64>,
    pub ntypes: usize,
    /// Some entry carries a special-bond level.
    pub has_special: bool,
    /// Build number, unique in the process (0: never built): lists derived from this one
    /// (hybrid sub-lists) know when they are stale.
    pub generation: u64,
}

impl NeighList {
    /// Chunk boundaries for the slab schedule: chunk c holds atoms `bounds[c]..bounds[c + 1]`.
    pub fn bounds(&self) -> Vec<usize> {
        // one allocation of the final size (collect then push reallocated, on every pass)
        let mut b = Vec::with_capacity(self.chunks.len() + 1);
        b.extend(self.chunks.iter().map(|c| c.start));
        b.push(self.chunks.last().map(|c| c.end).unwrap_or(0));
        b
    }
    /// The slab schedule's invariant (see [`crate::engine::par`]): every owned partner of an
    /// atom of chunk c lies in chunk c or c + 1.
    pub fn check_slab_invariant(&self) -> Result<(), String> {
        crate::engine::par::check_slab_invariant(&self.bounds(), |c| self.chunks[c].raw(), |j| (j & NEIGH_MASK) as usize)
    }
    /// Clear the special level of owned atom `i`'s entries whose atom `hit` accepts (LAMMPS'
    /// fix update/special/bonds after a bond broke); lists derived from this one are remade.
    pub fn clear_special(&mut self, i: usize, hit: impl Fn(usize) -> bool) {
        if let Some(c) = self.chunks.iter_mut().find(|c| (c.start..c.end).contains(&i)) {
            c.clear_special(i, hit);
            self.generation = BUILDS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
    }
    pub fn npairs(&self) -> usize {
        self.chunks.iter().map(|c| c.len()).sum()
    }
    /// The pairs as LAMMPS' half list counts them for its "Neighs" line: special pairs whose
    /// weights `lj` and `coul` are both 0 left out (LAMMPS does not list them), and a pair with
    /// a ghost, which each owner lists here, counted half on each side under `newton on` (LAMMPS
    /// stores it once) and whole under `newton off` (LAMMPS stores it on both sides too).
    pub fn lammps_count(&self, nlocal: usize, lj: &[f64; 4], coul: &[f64; 4], newton_pair: bool) -> f64 {
        let mut owned = 0usize;
        let mut ghost = 0usize;
        for c in &self.chunks {
            for i in c.start..c.end {
                for &e in c.neighbors(i) {
                    let level = special_level(e);
                    if lj[level] == 0.0 && coul[level] == 0.0 {
                        continue;
                    }
                    if ((e & NEIGH_MASK) as usize) < nlocal {
                        owned += 1;
                    } else {
                        ghost += 1;
                    }
                }
            }
        }
        owned as f64 + if newton_pair { 0.5 } else { 1.0 } * ghost as f64
    }

    /// The entries whose type pair `keep` marks (row-major over `0..=ntypes`), in the same
    /// chunks and order (LAMMPS' skip lists for hybrid sub-styles).
    pub fn filtered(&self, typ: &[usize], keep: &[bool]) -> NeighList {
        let stride = self.ntypes + 1;
        NeighList { generation: self.generation, ..self.retained(|i, j| keep[typ[i] * stride + typ[j]]) }
    }

    /// The entries (owned atom i, partner j) that `keep` accepts, in the same chunks and order,
    /// as a list of its own (a new generation).
    pub fn retained(&self, keep: impl Fn(usize, usize) -> bool) -> NeighList {
        let chunks = self
            .chunks
            .iter()
            .map(|c| {
                let mut offsets = Vec::with_capacity(c.end - c.start + 1);
                let mut neigh = Vec::with_capacity(c.len());
                offsets.push(0);
                for i in c.start..c.end {
                    neigh.extend(c.neighbors(i).iter().filter(|&&j| keep(i, (j & NEIGH_MASK) as usize)));
                    offsets.push(neigh.len() as u32);
                }
                ChunkList::new(c.start, c.end, offsets, neigh, c.neigh.owned(), c.neigh.bound())
            })
            .collect();
        NeighList { chunks, generation: BUILDS.fetch_add(1, std::sync::atomic::Ordering::Relaxed), ..self.clone_header() }
    }

    /// Everything but the entries.
    fn clone_header(&self) -> NeighList {
        NeighList { chunks: Vec::new(), cutneighsq: self.cutneighsq.clone(), cutsq: self.cutsq.clone(), ntypes: self.ntypes, has_special: self.has_special, generation: self.generation }
    }
}

/// Neighbour-list state across steps.
#[derive(Clone, Debug, Default)]
pub struct Neighbor {
    pub list: NeighList,
    /// Positions at the last build (for the distance check).
    xhold: Vec<[f64; 3]>,
    /// The box's corners at the last build (for the distance check while a fix changes the
    /// box).
    corners_hold: [[f64; 3]; 8],
    /// Steps since the last build.
    pub ago: i64,
    pub nbuilds: u64,
    /// Builds triggered on the first step they were allowed (LAMMPS' "dangerous builds").
    pub ndanger: u64,
    /// Largest list cutoff (pair cutoff + skin): the ghost shell thickness.
    pub cutneighmax: f64,
    /// Largest pair cutoff (LAMMPS' `cutforce`), without the skin.
    pub cutforce: f64,
    /// Per-bin counts and starts, kept between builds: a sparse system has millions of bins,
    /// and arrays made afresh each build were paged in and out every time.
    bins: BinScratch,
    /// The acting special partners of the owned atoms.
    acting: ActingCache,
}

/// The special partners that act on pairs ([`SpecialTable::acting_partners`]) of each owned
/// atom of the last build, in that build's order, carried through the next build's sort: a
/// build reads them in atom order, where the table by ID was read at random (a cache miss per
/// atom, 10% of a rebuild of a bead-spring melt). A row is reused only for the same table and
/// the same atom ID.
#[derive(Clone, Debug, Default)]
struct ActingCache {
    /// The table's generation the rows come from.
    generation: u64,
    /// Owned atom `i` of the last build had ID `tags[i]` and the partners
    /// `partners[at[i]..at[i + 1]]`.
    tags: Vec<i64>,
    at: Vec<u32>,
    partners: Vec<(i64, u8)>,
    /// The previous build's arrays, reused.
    spare_at: Vec<u32>,
    spare_partners: Vec<(i64, u8)>,
}

impl ActingCache {
    /// Rows for the owned atoms with IDs `tag`, sorted by the build: new atom `k` was atom
    /// `order[k]` before.
    fn update(&mut self, special: &SpecialTable, order: &[usize], tag: &[i64]) {
        let valid = self.generation == special.generation;
        let (mut at, mut partners) = (std::mem::take(&mut self.spare_at), std::mem::take(&mut self.spare_partners));
        at.clear();
        partners.clear();
        at.push(0);
        for (k, &o) in order.iter().enumerate() {
            if valid && self.tags.get(o) == Some(&tag[k]) {
                partners.extend_from_slice(&self.partners[self.at[o] as usize..self.at[o + 1] as usize]);
            } else {
                special.acting_partners(tag[k], &mut partners);
            }
            at.push(partners.len() as u32);
        }
        self.spare_at = std::mem::replace(&mut self.at, at);
        self.spare_partners = std::mem::replace(&mut self.partners, partners);
        self.tags.clear();
        self.tags.extend_from_slice(tag);
        self.generation = special.generation;
    }
    /// The acting partners of owned atom `i`.
    #[inline]
    fn of(&self, i: usize) -> &[(i64, u8)] {
        &self.partners[self.at[i] as usize..self.at[i + 1] as usize]
    }
}

/// The per-bin arrays of a build (see [`Neighbor::build`]): one index for the owned atoms, one
/// for the ghosts.
#[derive(Clone, Debug, Default)]
struct BinScratch {
    local: BinIndex,
    ghost: BinIndex,
}

/// Items (atoms) sorted by bin, and where each bin's items start: a stable counting sort (items
/// of one bin keep their order). Dense: the start of every bin of the grid. By lines, for grids
/// whose lines of bins along the fastest axis are mostly empty (a few bodies in a large box,
/// a pour's first grains, where counting and summing every bin was most of a build): the starts
/// of the bins of the occupied lines only. Both give the same order and the same ranges.
#[derive(Clone, Debug, Default)]
struct BinIndex {
    /// Bins per line along the fastest axis.
    per_line: usize,
    /// Dense: `starts[b]..starts[b + 1]` are the places of the items of bin `b`. By lines: the
    /// same for the bins of occupied lines only, line `l`'s `per_line + 1` entries from
    /// `block[l]` on.
    starts: Vec<u32>,
    /// By lines: where each line's entries start in `starts` (`EMPTY` for a line without
    /// items); empty when dense.
    block: Vec<u32>,
    fill: Vec<u32>,
}

impl BinIndex {
    const EMPTY: u32 = u32::MAX;
    /// Fewer bins than this many per item: dense, without counting lines.
    const DENSE_BINS_PER_ITEM: usize = 8;

    /// Sorts items with bins `keys` (on `grid`) by bin: returns the sorted order (`order[k]`:
    /// the item that goes to place `k`).
    fn sort(&mut self, grid: &Grid, keys: &[u32]) -> Vec<usize> {
        self.sort_in(grid.nb[grid.order[2]], grid.total, keys, None)
    }

    /// [`BinIndex::sort`] on lines of `per_line` bins (`total` bins, a multiple of it), by lines
    /// if `by_lines` says so or, when it is None, if at most half the lines hold items.
    fn sort_in(&mut self, per_line: usize, total: usize, keys: &[u32], by_lines: Option<bool>) -> Vec<usize> {
        self.per_line = per_line;
        self.block.clear();
        let lines = total / per_line;
        let pl = per_line as u32;
        // which lines hold items (counted only where that can choose lines)
        let used = |fill: &mut Vec<u32>| {
            zeroed(fill, lines);
            for &k in keys {
                fill[(k / pl) as usize] = 1;
            }
        };
        let mut counted = false;
        let by_lines = by_lines.unwrap_or_else(|| {
            total >= Self::DENSE_BINS_PER_ITEM * keys.len() && {
                used(&mut self.fill);
                counted = true;
                2 * self.fill.iter().filter(|&&c| c > 0).count() <= lines
            }
        });
        let entries = if by_lines {
            if !counted {
                used(&mut self.fill);
            }
            let mut next = 0;
            self.block.extend(self.fill.iter().map(|&u| {
                if u == 0 {
                    return Self::EMPTY;
                }
                next += pl + 1;
                next - (pl + 1)
            }));
            next as usize
        } else {
            total + 1
        };
        // where an item is counted: at its bin, or at its bin among the occupied lines' bins
        let place = |block: &[u32], k: u32| -> usize {
            if by_lines {
                (block[(k / pl) as usize] + k % pl) as usize
            } else {
                k as usize
            }
        };
        zeroed(&mut self.starts, entries);
        for &k in keys {
            self.starts[place(&self.block, k) + 1] += 1;
        }
        // one running sum over all entries: a line's first entry (no item is counted there)
        // takes the end of the line before. The sum is kept in a register (`v[b + 1] += v[b]`
        // waits for the store of the step before, which made this loop most of a small
        // system's list build)
        let mut sum = 0;
        for c in self.starts.iter_mut() {
            sum += *c;
            *c = sum;
        }
        self.fill.clear();
        self.fill.extend_from_slice(&self.starts);
        let mut order = vec![0usize; keys.len()];
        for (i, &k) in keys.iter().enumerate() {
            let slot = &mut self.fill[place(&self.block, k)];
            order[*slot as usize] = i;
            *slot += 1;
        }
        order
    }

    /// Whether the index is by lines.
    fn by_lines(&self) -> bool {
        !self.block.is_empty()
    }

    /// The places of the items in bins `b0..=b1` of line `line` (of the grid's lines along its
    /// fastest axis; read only by lines).
    #[inline(always)]
    fn range(&self, line: usize, b0: usize, b1: usize) -> (usize, usize) {
        if self.block.is_empty() {
            return (self.starts[b0] as usize, self.starts[b1 + 1] as usize);
        }
        debug_assert_eq!((line, line), (b0 / self.per_line, b1 / self.per_line));
        let block = self.block[line];
        if block == Self::EMPTY {
            return (0, 0);
        }
        let first = line * self.per_line;
        let at = block as usize;
        (self.starts[at + b0 - first] as usize, self.starts[at + b1 - first + 1] as usize)
    }
}

/// `v` as `n` zeros, reusing its allocation.
fn zeroed(v: &mut Vec<u32>, n: usize) {
    v.clear();
    v.resize(n, 0);
}

/// Where the ghosts of a build come from.
pub enum Ghosts<'a> {
    /// Periodic images of the owned atoms, made by the build (one rank).
    Periodic,
    /// [`Ghosts::Periodic`] of a triclinic box, made as LAMMPS makes them: the owned atoms'
    /// positions arrive as box fractions, wrapped into `[0, 1)`; the build places them and
    /// their images with lamda2x. `resorted`: LAMMPS sorts its atoms on this rebuild, which
    /// takes them to box coordinates and back first.
    Tilted { resorted: bool },
    /// Made by `make(atoms, ghost cutoff, lamda)` once the owned atoms are sorted (the ranks of
    /// a decomposed run exchange them); `sub` is this rank's sub-domain, which the bins cover.
    /// On a triclinic box the owned atoms arrive as box fractions (as for [`Ghosts::Tilted`]),
    /// `sub` is in box fractions, and `make` gets the sorted atoms' fractions.
    Given { sub: ([f64; 3], [f64; 3]), make: &'a mut dyn FnMut(&mut Atoms, f64, &[[f64; 3]]) },
}

/// Error raised while building lists (reported by the engine with the step number).
#[derive(Debug, Clone, PartialEq)]
pub enum NeighError {
    /// The ghost shell is thicker than the periodic box.
    BoxTooSmall { dim: usize, cut: f64, length: f64 },
    /// Non-finite coordinates.
    BadPosition { index: usize },
    /// The region to bin (the box, or the atoms' extent, widened by the cutoff) is too large
    /// for bins of any size dmhs can count (its extent overflows).
    TooLarge { lo: [f64; 3], hi: [f64; 3], cut: f64 },
    /// The list does not fit in memory: `entries` were listed when the allocator refused more
    /// (a cutoff + skin that reaches most of the system).
    OutOfMemory { entries: usize, cut: f64 },
    /// The list fits, with `entries` in all, but leaves too little memory for the rest of the
    /// rebuild and the step.
    NoRoomAfter { entries: usize, cut: f64 },
}

impl Neighbor {
    /// LAMMPS `Neighbor::decide`: is a rebuild due on this step?
    pub fn decide(&mut self, settings: &NeighborSettings, atoms: &Atoms) -> bool {
        self.decide_in(settings, atoms, None)
    }

    /// [`Neighbor::decide`]; `moving`: the box now, when a fix changes it between builds
    /// (LAMMPS' boxcheck): an atom may then move only half of what the skin leaves after the
    /// box's corners moved.
    pub fn decide_in(&mut self, settings: &NeighborSettings, atoms: &Atoms, moving: Option<&Domain>) -> bool {
        self.ago += 1;
        if self.ago >= settings.delay && self.ago % settings.every == 0 {
            if settings.once {
                return false;
            }
            if !settings.check {
                return true;
            }
            let triggersq = match moving {
                None => {
                    let trigger = 0.5 * settings.skin;
                    trigger * trigger
                }
                Some(d) => {
                    let hold = &self.corners_hold;
                    let corner = |a: &[f64; 3], b: &[f64; 3]| {
                        let (dx, dy, dz) = (a[0] - b[0], a[1] - b[1], a[2] - b[2]);
                        (dx * dx + dy * dy + dz * dz).sqrt()
                    };
                    let moved = if d.triclinic() {
                        // LAMMPS' two largest corner moves, as it finds them (a move that is not
                        // the largest so far counts as the second only when it beats it)
                        let (mut d1, mut d2) = (0.0, 0.0);
                        for (c, h) in d.corners().iter().zip(hold) {
                            let m = corner(c, h);
                            if m > d1 {
                                d1 = m;
                            } else if m > d2 {
                                d2 = m;
                            }
                        }
                        d1 + d2
                    } else {
                        corner(&d.lo, &hold[0]) + corner(&d.hi, &hold[7])
                    };
                    let delta = 0.5 * (settings.skin - moved);
                    let delta = if delta < 0.0 { 0.0 } else { delta };
                    delta * delta
                }
            };
            let m = atoms.nlocal.min(self.xhold.len());
            let (x, hold) = (&atoms.x[..m], &self.xhold[..m]);
            let moved = crate::engine::par::any_index(x.len(), |i| {
                let dx = x[i][0] - hold[i][0];
                let dy = x[i][1] - hold[i][1];
                let dz = x[i][2] - hold[i][2];
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
    /// `cut_pair(i, j)` is the interaction cutoff per type pair (0 = no interaction): the
    /// list holds the pairs within it plus the skin, or with `sizes` (LAMMPS' size lists of
    /// granular styles) the pairs within their current radii sum plus the skin, found within
    /// the type cutoffs' reach. Returns the permutation applied to owned atoms
    /// (`new k <- old order[k]`).
    #[allow(clippy::too_many_arguments)]
    pub fn build(
        &mut self,
        atoms: &mut Atoms,
        domain: &Domain,
        settings: &NeighborSettings,
        ntypes: usize,
        cut_pair: &dyn Fn(usize, usize) -> f64,
        sizes: bool,
        special: &SpecialTable,
    ) -> Result<Vec<usize>, NeighError> {
        if domain.triclinic() {
            for x in &mut atoms.x[..atoms.nlocal] {
                *x = domain.x2lamda(*x);
            }
            return self.build_with(atoms, domain, settings, ntypes, cut_pair, sizes, special, Ghosts::Tilted { resorted: false });
        }
        self.build_with(atoms, domain, settings, ntypes, cut_pair, sizes, special, Ghosts::Periodic)
    }

    /// [`Neighbor::build`] with the ghosts made as `ghosts` says.
    #[allow(clippy::too_many_arguments)]
    pub fn build_with(
        &mut self,
        atoms: &mut Atoms,
        domain: &Domain,
        settings: &NeighborSettings,
        ntypes: usize,
        cut_pair: &dyn Fn(usize, usize) -> f64,
        sizes: bool,
        special: &SpecialTable,
        mut ghosts: Ghosts,
    ) -> Result<Vec<usize>, NeighError> {
        atoms.clear_ghosts();
        // the old list indexes the ghosts just cleared: freed before the new one is made, so
        // that a rebuild does not hold two lists
        self.list.chunks = Vec::new();
        let n = atoms.nlocal;
        for (i, x) in atoms.x.iter().enumerate() {
            if !(x[0].is_finite() && x[1].is_finite() && x[2].is_finite()) {
                return Err(NeighError::BadPosition { index: i });
            }
        }
        // a triclinic box's owned atoms arrive as box fractions: kept for their images, and
        // placed in the box
        let tilted = matches!(ghosts, Ghosts::Tilted { .. }) || (matches!(ghosts, Ghosts::Given { .. }) && domain.triclinic());
        let mut lamda: Vec<[f64; 3]> = Vec::new();
        if tilted {
            lamda = atoms.x[..n].to_vec();
            if let Ghosts::Tilted { resorted: true } = ghosts {
                for l in &mut lamda {
                    *l = domain.x2lamda(domain.lamda2x(*l));
                }
            }
            for (x, l) in atoms.x[..n].iter_mut().zip(&lamda) {
                *x = domain.lamda2x(*l);
            }
        }

        // list cutoffs per type pair
        let stride = ntypes + 1;
        let mut cutneighsq = vec![0.0; stride * stride];
        let mut cutsq = vec![0.0; stride * stride];
        let mut cutmax: f64 = 0.0;
        self.cutforce = 0.0;
        for it in 1..=ntypes {
            for jt in 1..=ntypes {
                let c = cut_pair(it, jt);
                cutsq[it * stride + jt] = c * c;
                self.cutforce = self.cutforce.max(c);
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
        let periods = domain.periods();
        // the ghost shell in box fractions (a triclinic box's width across dimension d is
        // cutmax / reach[d])
        let reach = domain.lamda_reach(cutmax);
        for d in 0..dim {
            let too_small = if tilted { reach[d] > 1.0 } else { cutmax > prd[d] };
            if domain.periodic(d) && too_small {
                let length = if tilted { cutmax / reach[d] } else { prd[d] };
                return Err(NeighError::BoxTooSmall { dim: d, cut: cutmax, length });
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
        // a triclinic box's ghosts lie around it (or around the rank's sub-domain) within the
        // shell in box fractions
        let shell = tilted.then(|| match &ghosts {
            Ghosts::Given { sub, .. } => domain.bbox(std::array::from_fn(|d| sub.0[d] - reach[d]), std::array::from_fn(|d| sub.1[d] + reach[d])),
            _ => domain.bbox(reach.map(|r| -r), reach.map(|r| 1.0 + r)),
        });
        for d in 0..dim {
            if let Some((blo, bhi)) = shell {
                lo[d] = lo[d].min(blo[d]);
                hi[d] = hi[d].max(bhi[d]);
            } else if domain.periodic(d) {
                lo[d] = lo[d].min(domain.lo[d]);
                hi[d] = hi[d].max(domain.hi[d]);
            }
            if let (Ghosts::Given { sub, .. }, false) = (&ghosts, tilted) {
                lo[d] = lo[d].min(sub.0[d]);
                hi[d] = hi[d].max(sub.1[d]);
            }
            lo[d] -= cutmax;
            hi[d] += cutmax;
        }
        let binsize = if settings.binsize > 0.0 { settings.binsize } else if cutmax > 0.0 { cutmax / 3.0 } else { 1.0 };
        let grid = Grid::new(lo, hi, binsize, dim, cutmax).ok_or(NeighError::TooLarge { lo, hi, cut: cutmax })?;

        // sort owned atoms by bin: bins are numbered slab axis first, so this is slab order
        let keys: Vec<u32> = atoms.x[..n].iter().map(|x| grid.bin(x) as u32).collect();
        // stable: atoms of one bin keep their order; `bin_of`: the bin of each owned atom in
        // its new place
        let BinScratch { local, ghost } = &mut self.bins;
        let order = local.sort(&grid, &keys);
        atoms.permute(&order);
        let bin_of: Vec<u32> = order.iter().map(|&o| keys[o]).collect();
        if tilted {
            lamda = order.iter().map(|&o| lamda[o]).collect();
        }

        // ghosts, dimension by dimension so edges and corners get images too (LAMMPS borders())
        if let Ghosts::Given { make, .. } = &mut ghosts {
            make(atoms, cutmax, &lamda);
        } else if tilted && cutmax > 0.0 {
            // in box fractions, each dimension's images of the atoms and of the images made
            // so far, as LAMMPS' borders(); placed with lamda2x
            let mut made: Vec<(usize, [i8; 3], [f64; 3])> = Vec::new();
            for d in 0..dim {
                if !domain.periodic(d) {
                    continue;
                }
                let count = made.len();
                for k in 0..n + count {
                    let (owner, shift, l) = if k < n { (k, [0i8; 3], lamda[k]) } else { made[k - n] };
                    if l[d] < reach[d] {
                        let (mut s, mut g) = (shift, l);
                        s[d] = 1;
                        g[d] += 1.0;
                        made.push((owner, s, g));
                    }
                    if l[d] >= 1.0 - reach[d] {
                        let (mut s, mut g) = (shift, l);
                        s[d] = -1;
                        g[d] -= 1.0;
                        made.push((owner, s, g));
                    }
                }
            }
            atoms.reserve(made.len());
            for (owner, s, g) in made {
                atoms.push_ghost_at(owner, s, domain.lamda2x(g));
            }
        } else if cutmax > 0.0 {
            for d in 0..dim {
                if !domain.periodic(d) {
                    continue;
                }
                let count = atoms.nall();
                // an atom this near a face has an image beyond the opposite one
                let near = |x: &[f64; 3]| (x[d] < domain.lo[d] + cutmax, x[d] >= domain.hi[d] - cutmax);
                atoms.reserve(atoms.x.iter().map(&near).map(|(lo, hi)| lo as usize + hi as usize).sum());
                for k in 0..count {
                    let (near_lo, near_hi) = near(&atoms.x[k]);
                    if !near_lo && !near_hi {
                        continue;
                    }
                    let (owner, shift) = if k < n {
                        (k, [0i8; 3])
                    } else {
                        (atoms.ghost_owner[k - n] as usize, atoms.ghost_shift[k - n])
                    };
                    if near_lo {
                        let mut s = shift;
                        s[d] = 1;
                        atoms.push_ghost(owner, s, periods);
                    }
                    if near_hi {
                        let mut s = shift;
                        s[d] = -1;
                        atoms.push_ghost(owner, s, periods);
                    }
                }
            }
        }

        // ghosts are counting-sorted into their own bins
        let nall = atoms.nall();
        let ghost_bin: Vec<u32> = atoms.x[n..].iter().map(|x| grid.bin(x) as u32).collect();
        let ghosts_by_bin: Vec<u32> = ghost.sort(&grid, &ghost_bin).into_iter().map(|k| (n + k) as u32).collect();
        let (local, ghost) = (&*local, &*ghost);

        // stencil rows: runs of consecutive bins along the fastest grid axis within reach;
        // atoms of consecutive bins are consecutive (owned atoms are sorted by bin, ghosts are
        // counting-sorted), so each row is one contiguous range of candidates
        let rows = grid.stencil_rows(cutmax);
        // owned partners come from the forward half: rows after the atom's own row, and the
        // atom's own row from its bin on (later atoms of its own bin only)
        let own_row_end = rows.iter().find(|r| r.0 <= 0 && r.1 >= 0).map(|r| r.1).unwrap_or(0);
        let forward: Vec<(i64, i64, i64)> = rows.iter().copied().filter(|r| r.0 > 0).collect();
        // the line of bins along the fastest axis that each bin lies on (a row lies on one)
        let line_len = grid.nb[grid.order[2]];
        let lines_used = local.by_lines() || ghost.by_lines();

        // slab chunks: consecutive planes along the slab axis, at least `reach` planes thick
        let thick = grid.reach[grid.axis].max(1) as usize;
        // atoms are sorted by bin: the chunk (two divisions) changes only where the bin does
        let mut bounds = vec![0usize];
        let mut last = bin_of.first().map(|&b| (b, grid.plane(b) / thick));
        for (i, &b) in bin_of.iter().enumerate().skip(1) {
            let Some((lb, lc)) = last else { break };
            if b != lb {
                let c = grid.plane(b) / thick;
                if c != lc {
                    bounds.push(i);
                }
                last = Some((b, c));
            }
        }
        bounds.push(n);
        if n == 0 {
            bounds = vec![0, 0];
        }

        // the faces ghosts lie beyond: the periodic ones of the box, or every face of the
        // sub-domain of a rank of a decomposed run
        let ghost_faces: Vec<(usize, f64, f64)> = match &ghosts {
            Ghosts::Periodic => (0..dim).filter(|&d| domain.periodic(d)).map(|d| (d, domain.lo[d], domain.hi[d])).collect(),
            // a tilted face is not a plane of constant x, y or z: every atom looks
            Ghosts::Tilted { .. } => (0..dim).filter(|&d| domain.periodic(d)).map(|d| (d, f64::INFINITY, f64::NEG_INFINITY)).collect(),
            Ghosts::Given { .. } if tilted => (0..dim).map(|d| (d, f64::INFINITY, f64::NEG_INFINITY)).collect(),
            Ghosts::Given { sub, .. } => (0..dim).map(|d| (d, sub.0[d], sub.1[d])).collect(),
        };
        let a: &Atoms = atoms;
        let excl = &settings.exclusions;
        let use_special = !special.is_empty();
        // symmetric special lists: a pair within the cutoff is looked up among the partners of
        // atom i that act on pairs (read once per atom i, as LAMMPS reads its special list)
        let by_acting = use_special && special.symmetric;
        if by_acting {
            self.acting.update(special, &order, &atoms.tag[..n]);
        }
        let acting_cache = &self.acting;
        let skin = settings.skin;
        // a size list reads every atom's radius (ghosts' too)
        let radius: &[f64] = if sizes { &a.radius[..nall] } else { &[] };
        let chunks: Result<Vec<ChunkList>, usize> = crate::engine::par::team::map(bounds.windows(2).collect::<Vec<_>>(), |w| {
                let (start, end) = (w[0], w[1]);
                let mut offsets = Vec::with_capacity(end - start + 1);
                let mut neigh = Vec::new();
                // a list too large for memory is an error, not an abort: every growth is asked
                // of the allocator first
                let refused = std::cell::Cell::new(false);
                let room = |neigh: &mut Vec<u32>, more: usize| {
                    let ok = !refused.get() && neigh.try_reserve(more).is_ok();
                    refused.set(!ok);
                    ok
                };
                if !room(&mut neigh, (end - start) * 48) {
                    return Err(0);
                }
                offsets.push(0u32);
                let mut spans: Vec<(usize, usize)> = Vec::with_capacity(forward.len() + 1);
                for i in start..end {
                    let xi = a.x[i];
                    let ti = a.typ[i];
                    let row = &cutneighsq[ti * stride..(ti + 1) * stride];
                    let bi = bin_of[i] as i64;
                    // (a division per atom only where an index needs lines)
                    let li = if lines_used { bi / line_len as i64 } else { 0 };
                    let acting: &[(i64, u8)] = if by_acting { acting_cache.of(i) } else { &[] };
                    // what special bonds do to the pair with atom j (`far_image`: j is a ghost
                    // beyond half the box, asked only for a pair the bonds would change)
                    let special_action = |j: usize, far_image: &dyn Fn() -> bool| {
                        if by_acting {
                            // most atoms have no or few acting partners: the test is skipped or short
                            match acting.iter().find(|p| p.0 == a.tag[j]) {
                                Some(&(_, level)) => special.flag_action(level, far_image),
                                None => PairAction::Keep,
                            }
                        } else if use_special {
                            special.action(a.tag[i], a.tag[j], far_image())
                        } else {
                            PairAction::Keep
                        }
                    };
                    let consider = |j: usize, neigh: &mut Vec<u32>| {
                        let xj = a.x[j];
                        let dx = xi[0] - xj[0];
                        let dy = xi[1] - xj[1];
                        let dz = xi[2] - xj[2];
                        let rsq = dx * dx + dy * dy + dz * dz;
                        let reach = if sizes {
                            let cut = radius[i] + radius[j] + skin;
                            cut * cut
                        } else {
                            row[a.typ[j]]
                        };
                        if rsq > reach {
                            return;
                        }
                        if !excl.is_empty() && excl.excluded(a, i, j) {
                            return;
                        }
                        let mut entry = j as u32;
                        match special_action(j, &|| j >= n && minimum_image_check(domain, [dx, dy, dz])) {
                            PairAction::Keep => {}
                            PairAction::Exclude => return,
                            PairAction::Weighted(level) => entry |= (level as u32) << SPECIAL_SHIFT,
                        }
                        if neigh.len() < neigh.capacity() || room(neigh, 1) {
                            neigh.push(entry);
                        }
                    };
                    // owned partners, each span a contiguous index range: later atoms of the own
                    // row, then the forward rows (the empty ones left out; looked up once, read
                    // twice below)
                    spans.clear();
                    spans.push((i + 1, local.range(li as usize, bi as usize, (bi + own_row_end) as usize).1));
                    spans.extend(forward.iter().map(|&(r0, r1, l)| local.range((li + l) as usize, (bi + r0) as usize, (bi + r1) as usize)).filter(|(j0, j1)| j1 > j0));
                    if !excl.is_empty() {
                        for &(j0, j1) in &spans {
                            (j0..j1).for_each(|j| consider(j, &mut neigh));
                        }
                    } else {
                        // without exclusions every candidate of the atom is written and kept only
                        // if within the cutoff (branch-free: the hit rate is about 1 in 4, badly
                        // predicted), into room made once per atom; special bonds then act on
                        // the few kept
                        let total: usize = spans.iter().map(|&(j0, j1)| j1 - j0).sum();
                        if total > 0 && room(&mut neigh, total) {
                            let len = neigh.len();
                            neigh.resize(len + total, 0);
                            let slots = &mut neigh[len..];
                            let rsq = |xj: &[f64; 3]| {
                                let dx = xi[0] - xj[0];
                                let dy = xi[1] - xj[1];
                                let dz = xi[2] - xj[2];
                                dx * dx + dy * dy + dz * dz
                            };
                            // kept <= k (the candidates before this one): the write lands in `slots`
                            let (mut kept, mut k) = (0usize, 0usize);
                            for &(j0, j1) in spans.iter().filter(|(j0, j1)| j1 > j0) {
                                // slices taken before the loop: read through `a`, their
                                // addresses were reloaded after every store
                                let xs = &a.x[j0..j1];
                                if sizes {
                                    let ri = radius[i];
                                    for (m, (xj, &rj)) in xs.iter().zip(&radius[j0..j1]).enumerate() {
                                        let cut = ri + rj + skin;
                                        slots[kept.min(k + m)] = (j0 + m) as u32;
                                        kept += (rsq(xj) <= cut * cut) as usize;
                                    }
                                } else {
                                    for (m, (xj, &tj)) in xs.iter().zip(&a.typ[j0..j1]).enumerate() {
                                        slots[kept.min(k + m)] = (j0 + m) as u32;
                                        kept += (rsq(xj) <= row[tj]) as usize;
                                    }
                                }
                                k += j1 - j0;
                            }
                            if use_special {
                                // in place and in order, as `consider` would have kept them
                                let mut out = 0;
                                for r in 0..kept {
                                    let j = slots[r];
                                    // an owned partner is never a far image
                                    slots[out] = match special_action(j as usize, &|| false) {
                                        PairAction::Keep => j,
                                        PairAction::Exclude => continue,
                                        PairAction::Weighted(level) => j | (level as u32) << SPECIAL_SHIFT,
                                    };
                                    out += 1;
                                }
                                kept = out;
                            }
                            neigh.truncate(len + kept);
                        }
                    }
                    // ghost partners: every bin in reach (ghosts lie within cutmax outside a
                    // face, so only atoms that near a face can see one)
                    let near_face = ghost_faces.iter().any(|&(d, lo, hi)| xi[d] < lo + cutmax || xi[d] >= hi - cutmax);
                    if near_face {
                        for &(r0, r1, l) in &rows {
                            let (b0, b1) = ((bi + r0) as usize, (bi + r1) as usize);
                            let (g0, g1) = ghost.range((li + l) as usize, b0, b1);
                            for &g in &ghosts_by_bin[g0..g1] {
                                consider(g as usize, &mut neigh);
                            }
                        }
                    }
                    if refused.get() {
                        return Err(neigh.len());
                    }
                    offsets.push(neigh.len() as u32);
                }
                Ok(ChunkList::new(start, end, offsets, neigh, n, nall))
            })
            .into_iter()
            .collect();
        let chunks = chunks.map_err(|entries| NeighError::OutOfMemory { entries, cut: cutmax })?;
        // the rest of the rebuild and of the step allocate per-atom arrays (copies of positions,
        // LAMMPS' order, bonded lists): when the list took the last of the memory, say so here
        // rather than abort on one of those allocations
        let entries: usize = chunks.iter().map(|c| c.raw().len()).sum();
        if Vec::<u8>::new().try_reserve_exact(nall.saturating_mul(HEADROOM_PER_ATOM)).is_err() {
            return Err(NeighError::NoRoomAfter { entries, cut: cutmax });
        }

        let has_special = use_special && chunks.iter().any(|c| c.raw().iter().any(|&j| j > NEIGH_MASK));
        // unique over the process, so no derived list can mistake a new build for its own
        let generation = BUILDS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        self.list = NeighList { chunks, cutneighsq, cutsq, ntypes, has_special, generation };
        debug_assert_eq!(self.list.check_slab_invariant(), Ok(()));
        self.xhold.clear();
        self.xhold.extend_from_slice(&atoms.x[..n]);
        // (an orthogonal box keeps its own bounds: lamda2x of the upper corner rounds)
        self.corners_hold = if domain.triclinic() {
            domain.corners()
        } else {
            let mut c = [domain.lo; 8];
            c[7] = domain.hi;
            c
        };
        self.ago = 0;
        self.nbuilds += 1;
        Ok(order)
    }
}

/// A regular grid of bins covering `lo..hi` plus a margin of `reach` bins on each side, so
/// that a stencil around any atom's bin stays inside the grid. Bins are numbered with the slab
/// axis (the dimension with the most bins) varying slowest.
struct Grid {
    lo: [f64; 3],
    size: [f64; 3],
    inv: [f64; 3],
    nb: [usize; 3],
    reach: [i64; 3],
    total: usize,
    /// The slab axis, then the other two dimensions (slowest to fastest).
    axis: usize,
    order: [usize; 3],
}

impl Grid {
    /// The largest number of bins (margins included); larger grids get larger bins.
    const MAX_BINS: f64 = (1u64 << 24) as f64;

    /// None if the extent `hi - lo` is not finite (a box of 1e308 widened by the cutoff, or
    /// from -1e308 to 1e308), so no bin size covers it with a countable number of bins.
    fn new(lo: [f64; 3], hi: [f64; 3], binsize: f64, dim: usize, cut: f64) -> Option<Grid> {
        let mut nb = [1usize; 3];
        let mut size = [1.0; 3];
        let mut ext = [0.0; 3];
        let mut bs = [binsize; 3];
        if !(0..dim).all(|d| (hi[d] - lo[d]).is_finite()) || !(binsize > 0.0 && cut.is_finite()) {
            return None;
        }
        // keep the bin count bounded for very sparse systems: counted in floating point, so
        // that a huge box cannot overflow the count; doubling from any positive size reaches
        // a finite extent within about 2100 steps per dimension
        loop {
            let mut count = [1.0f64; 3];
            // with the margins of `reach` bins on both sides: a box long in one dimension
            // (1e9 x 8 x 8) had 2^24 bins along it, times 7 x 7 with its margins (3 GB)
            let mut total = [1.0f64; 3];
            for d in 0..dim {
                ext[d] = (hi[d] - lo[d]).max(bs[d]);
                count[d] = (ext[d] / bs[d]).floor().max(1.0);
                total[d] = count[d] + 2.0 * (cut / (ext[d] / count[d])).ceil();
            }
            if total[0] * total[1] * total[2] <= Self::MAX_BINS {
                for d in 0..dim {
                    nb[d] = count[d] as usize;
                    size[d] = ext[d] / nb[d] as f64;
                }
                break;
            }
            // coarser bins along the dimension with the most only: a box huge in one
            // dimension keeps fine bins in the others (one bin across 40,000 atoms of a
            // strip made every build O(N^2))
            let d = (0..dim).max_by(|&a, &b| total[a].total_cmp(&total[b])).unwrap_or(0);
            bs[d] *= 2.0;
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
        let axis = (0..dim).max_by_key(|&d| nb[d]).unwrap_or(0);
        // the fastest-varying axis is an active one, so stencil rows are long (in 2D: z, with
        // one bin, goes in the middle)
        let mut rest: Vec<usize> = (0..3).filter(|&d| d != axis).collect();
        if dim == 2 {
            rest.sort_by_key(|&d| if d == 2 { 0 } else { 1 });
        }
        Some(Grid { lo: glo, size, inv, nb, reach, total: nb[0] * nb[1] * nb[2], axis, order: [axis, rest[0], rest[1]] })
    }
    /// Bin coordinate of `x` along `d`, inside the margins: every point binned lies in
    /// `lo..hi`, whose bins are `reach..nb - reach`, but with bins far larger than the cutoff
    /// (a box of 1e30) rounding can put a point near `lo` one bin lower, and its stencil would
    /// then reach below bin 0. Clamped in floating point, so no value overflows the cast.
    #[inline]
    fn coord(&self, x: f64, d: usize) -> usize {
        let (first, last) = (self.reach[d] as usize, self.nb[d] - 1 - self.reach[d] as usize);
        let c = ((x - self.lo[d]) * self.inv[d]).floor().max(first as f64);
        (c as usize).min(last)
    }
    #[inline]
    fn bin(&self, x: &[f64; 3]) -> usize {
        let [a, b, c] = self.order;
        (self.coord(x[a], a) * self.nb[b] + self.coord(x[b], b)) * self.nb[c] + self.coord(x[c], c)
    }
    /// Slab plane of a bin.
    #[inline]
    fn plane(&self, bin: u32) -> usize {
        bin as usize / (self.nb[self.order[1]] * self.nb[self.order[2]])
    }
    /// The stencil as rows along the fastest axis: `(first, last)` bin-index offsets of each
    /// run of bins whose closest point can be within `cut`, in increasing order, and the offset
    /// of the row's line (of bins along the fastest axis).
    fn stencil_rows(&self, cut: f64) -> Vec<(i64, i64, i64)> {
        let [a, b, c] = self.order;
        let (nbb, nbc) = (self.nb[b] as i64, self.nb[c] as i64);
        let gap = |k: i64, d: usize| if k == 0 { 0.0 } else { (k.abs() - 1) as f64 * self.size[d] };
        let within = |ga: f64, gb: f64, gc: f64| ga * ga + gb * gb + gc * gc <= cut * cut * (1.0 + 1e-12);
        let mut rows = Vec::new();
        for ka in -self.reach[a]..=self.reach[a] {
            for kb in -self.reach[b]..=self.reach[b] {
                let (ga, gb) = (gap(ka, a), gap(kb, b));
                if !within(ga, gb, 0.0) {
                    continue;
                }
                let kmax = (0..=self.reach[c]).rev().find(|&k| within(ga, gb, gap(k, c))).unwrap_or(0);
                let base = (ka * nbb + kb) * nbc;
                rows.push((base - kmax, base + kmax, ka * nbb + kb));
            }
        }
        rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::atoms::{AtomFeatures, NewAtom};
    use crate::engine::domain::BoundaryKind;

    /// Uniform numbers in [0, 1) from a 64-bit LCG: random test systems, the same each run.
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Lists of random periodic boxes, thin and wide, keep the slab invariant (in debug builds
    /// the builder asserts it too).
    #[test]
    fn every_owned_partner_lies_in_the_same_or_the_next_chunk() {
        let mut rand = uniform(12345);
        for (len, n) in [([6.0, 6.0, 6.0], 300), ([40.0, 5.0, 5.0], 2000), ([3.1, 3.1, 30.0], 500)] {
            let domain = Domain::new(3, [0.0; 3], len, [[BoundaryKind::Periodic; 2]; 3]);
            let mut atoms = Atoms::new(AtomFeatures::default());
            for k in 0..n {
                atoms.push(&NewAtom::at(k as i64 + 1, 1, [rand() * len[0], rand() * len[1], rand() * len[2]]));
            }
            let mut neighbor = Neighbor::default();
            neighbor.build(&mut atoms, &domain, &NeighborSettings::new(0.3), 1, &|_, _| 1.2, false, &SpecialTable::default()).unwrap();
            assert!(neighbor.list.chunks.len() >= 2, "{len:?}: {} chunks", neighbor.list.chunks.len());
            assert_eq!(neighbor.list.check_slab_invariant(), Ok(()));
        }
    }

    /// A size list (granular styles) holds exactly the pairs within their radii sum + skin,
    /// images across the periodic faces included, and a sphere grown past its type's cutoff
    /// is listed with the partners it reaches within the type cutoffs' reach.
    #[test]
    fn size_lists_hold_the_pairs_within_their_radii_sum_and_skin() {
        let mut rand = uniform(777);
        let len = [7.0, 6.0, 5.0];
        let domain = Domain::new(3, [0.0; 3], len, [[BoundaryKind::Periodic; 2]; 3]);
        let mut atoms = Atoms::new(AtomFeatures { sphere: true, ..AtomFeatures::default() });
        for k in 0..400 {
            let mut a = NewAtom::at(k as i64 + 1, 1, [rand() * len[0], rand() * len[1], rand() * len[2]]);
            // radii up to 0.5 (the type cutoff 1.0 covers them), three grown to 0.6
            a.radius = if k % 130 == 7 { 0.6 } else { 0.3 + 0.2 * rand() };
            atoms.push(&a);
        }
        let skin = 0.3;
        let mut neighbor = Neighbor::default();
        neighbor.build(&mut atoms, &domain, &NeighborSettings::new(skin), 1, &|_, _| 1.0, true, &SpecialTable::default()).unwrap();
        let (n, a) = (atoms.nlocal, &atoms);
        let owner = |j: usize| if j < n { j } else { a.ghost_owner[j - n] as usize };
        let mut listed = std::collections::BTreeSet::new();
        for c in &neighbor.list.chunks {
            for i in c.start..c.end {
                for &e in c.neighbors(i) {
                    let j = (e & NEIGH_MASK) as usize;
                    let rsq: f64 = (0..3).map(|d| (a.x[i][d] - a.x[j][d]).powi(2)).sum();
                    let cut = a.radius[i] + a.radius[j] + skin;
                    assert!(rsq <= cut * cut, "{i} {j} listed beyond their radii sum + skin");
                    // a pair across a periodic face is listed by both owners
                    listed.insert((a.tag[i].min(a.tag[owner(j)]), a.tag[i].max(a.tag[owner(j)])));
                }
            }
        }
        // every pair within reach, by the minimum image
        let mut expected = 0;
        let mut grown = 0;
        let mut beyond = 0;
        for i in 0..n {
            for j in i + 1..n {
                let rsq: f64 = (0..3)
                    .map(|d| {
                        let dx = a.x[i][d] - a.x[j][d];
                        (dx - len[d] * (dx / len[d]).round()).powi(2)
                    })
                    .sum();
                let cut = a.radius[i] + a.radius[j] + skin;
                let is_listed = listed.contains(&(a.tag[i].min(a.tag[j]), a.tag[i].max(a.tag[j])));
                if rsq <= cut * cut && rsq.sqrt() <= 1.0 + skin {
                    expected += 1;
                    grown += (a.radius[i] == 0.6 || a.radius[j] == 0.6) as usize;
                    assert!(is_listed, "{} {} not listed", a.tag[i], a.tag[j]);
                } else if rsq <= cut * cut {
                    // beyond the type cutoffs' reach: listed where the bins reach it
                    beyond += is_listed as usize;
                }
            }
        }
        assert_eq!(listed.len(), expected + beyond);
        assert!(grown > 0);
        // the type-cutoff list holds more
        neighbor.build(&mut atoms, &domain, &NeighborSettings::new(skin), 1, &|_, _| 1.0, false, &SpecialTable::default()).unwrap();
        assert!(neighbor.list.lammps_count(n, &[1.0; 4], &[1.0; 4], true) > expected as f64 * 1.2);
    }

    /// Special levels looked up among atom i's acting partners (read once per atom, carried
    /// through the sort of the next build) give the entries of the per-pair search of both
    /// atoms' lists, also after a build that reuses the rows and after a 1-2 pair is removed.
    #[test]
    fn acting_partners_give_the_entries_of_the_per_pair_search() {
        let mut rand = uniform(777);
        let len = [7.0, 6.0, 6.5];
        let domain = Domain::new(3, [0.0; 3], len, [[BoundaryKind::Periodic; 2]; 3]);
        // chains of 10 atoms, IDs in chain order, a random walk of steps near 1
        let (nchain, clen) = (30, 10i64);
        let mut atoms = Atoms::new(AtomFeatures::default());
        for c in 0..nchain {
            let mut x = [rand() * len[0], rand() * len[1], rand() * len[2]];
            for k in 0..clen {
                atoms.push(&NewAtom::at(c * clen + k + 1, 1, x));
                for (d, v) in x.iter_mut().enumerate() {
                    *v = (*v + rand() - 0.5).rem_euclid(len[d]);
                }
            }
        }
        let ids: Vec<i64> = atoms.tag.clone();
        let lists: Vec<SpecialList> = ids
            .iter()
            .map(|&t| {
                let (c0, k) = ((t - 1) / clen * clen + 1, (t - 1) % clen);
                let mut l = SpecialList { ids: vec![], n: [0; 3] };
                for lvl in 1..=3i64 {
                    for p in [k - lvl, k + lvl] {
                        if (0..clen).contains(&p) {
                            l.ids.push(c0 + p);
                        }
                    }
                    l.n[lvl as usize - 1] = l.ids.len();
                }
                l
            })
            .collect();
        let flags = [SpecialFlag::Normal, SpecialFlag::Exclude, SpecialFlag::Weighted, SpecialFlag::Normal];
        let mut by_acting = SpecialTable::from_lists(&ids, lists.clone(), flags, true);
        let mut per_pair = SpecialTable::from_lists(&ids, lists, flags, false);
        let settings = NeighborSettings::new(0.3);
        let entries = |atoms: &mut Atoms, neighbor: &mut Neighbor, table: &SpecialTable| {
            neighbor.build(atoms, &domain, &settings, 1, &|_, _| 1.2, false, table).unwrap();
            let mut e: Vec<(i64, i64, usize)> = Vec::new();
            for c in &neighbor.list.chunks {
                for i in c.start..c.end {
                    e.extend(c.neighbors(i).iter().map(|&j| (atoms.tag[i], atoms.tag[(j & NEIGH_MASK) as usize], special_level(j))));
                }
            }
            e
        };
        let (mut a1, mut a2) = (atoms.clone(), atoms);
        let (mut n1, mut n2) = (Neighbor::default(), Neighbor::default());
        for round in 0..3 {
            let (e1, e2) = (entries(&mut a1, &mut n1, &by_acting), entries(&mut a2, &mut n2, &per_pair));
            assert_eq!(e1, e2, "round {round}");
            assert!(e1.iter().any(|e| e.2 == 2) && !e1.iter().any(|e| e.2 == 1), "round {round}");
            // atoms 4 and 5 (a 1-2 pair, excluded) are listed once their bond is gone
            assert_eq!(e1.iter().any(|e| (e.0, e.1) == (4, 5) || (e.0, e.1) == (5, 4)), round == 2, "round {round}");
            // move the atoms a little, so the next build sorts them anew
            for a in [&mut a1, &mut a2] {
                for x in a.x.iter_mut() {
                    x[0] = (x[0] + 0.37).rem_euclid(len[0]);
                }
            }
            if round == 1 {
                let (p, q) = (4, 5);
                by_acting.remove_one_two(p, q);
                per_pair.remove_one_two(p, q);
            }
        }
    }

    /// A box long in one dimension only (8.4 x 8.4 x 3.6e9, from a fuzzed `region` line): the
    /// grid, margins included, stays within MAX_BINS (it was 49 x 2^24 bins, 3 GB), and a
    /// close pair far along the long axis is listed.
    #[test]
    fn bin_index_by_lines_gives_the_dense_order_and_ranges() {
        let mut r = uniform(11);
        let (per_line, lines) = (13usize, 40usize);
        let total = per_line * lines;
        for nitems in [0usize, 1, 5, 30, 200, 2000] {
            // items on a few lines only, or anywhere
            for lines_used in [3usize, lines] {
                let keys: Vec<u32> = (0..nitems).map(|_| ((r() * lines_used as f64) as usize * per_line + (r() * per_line as f64) as usize) as u32).collect();
                let (mut dense, mut sparse) = (BinIndex::default(), BinIndex::default());
                let od = dense.sort_in(per_line, total, &keys, Some(false));
                let os = sparse.sort_in(per_line, total, &keys, Some(true));
                assert_eq!(od, os);
                assert!(od.windows(2).all(|w| (keys[w[0]], w[0]) < (keys[w[1]], w[1])), "stable by bin");
                for line in 0..lines {
                    for a in 0..per_line {
                        for b in a..per_line {
                            let (b0, b1) = (line * per_line + a, line * per_line + b);
                            let (d, s) = (dense.range(line, b0, b1), sparse.range(line, b0, b1));
                            assert!(d == s || (d.0 == d.1 && s.0 == s.1), "bins {b0}..={b1}: {d:?} {s:?}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn long_thin_boxes_keep_the_bin_count_bounded() {
        let g = Grid::new([0.0; 3], [8.4, 8.4, 3.6e9], 2.8 / 3.0, 3, 2.8).unwrap();
        assert!(g.total as f64 <= Grid::MAX_BINS, "{} bins", g.total);
        // only the long dimension gets coarser bins (40,000 atoms of a strip in one bin made
        // each build O(N^2))
        let g = Grid::new([0.0; 3], [1e19, 400.0, 0.5], 1.1 / 3.0, 2, 1.1).unwrap();
        assert!(g.total as f64 <= Grid::MAX_BINS && g.nb[1] > 1000, "{:?}", g.nb);
        let domain = Domain::new(3, [0.0; 3], [8.4, 8.4, 3.6e9], [[BoundaryKind::Periodic; 2]; 3]);
        let mut atoms = Atoms::new(AtomFeatures::default());
        atoms.push(&NewAtom::at(1, 1, [1.0, 1.0, 2.0e9]));
        atoms.push(&NewAtom::at(2, 1, [2.0, 1.0, 2.0e9]));
        let mut neighbor = Neighbor::default();
        neighbor.build(&mut atoms, &domain, &NeighborSettings::new(0.3), 1, &|_, _| 2.5, false, &SpecialTable::default()).unwrap();
        let pairs: usize = neighbor.list.chunks.iter().map(|c| c.neigh.len()).sum();
        assert_eq!(pairs, 1);
    }

    /// Boxes of 1e30..1e308 with a close pair near a face: bin counts and indices stay in range
    /// (the bins are far larger than the cutoff and rounding must not put an atom in a margin
    /// bin), and the pair is listed; an extent that overflows a double is an error.
    #[test]
    fn huge_boxes_bin_without_overflow() {
        for l in [1e30, 1e100, 1e308] {
            let domain = Domain::new(3, [0.0; 3], [l; 3], [[BoundaryKind::Periodic; 2]; 3]);
            let mut atoms = Atoms::new(AtomFeatures::default());
            for (k, x) in [[1.0, 1.0, 1.0], [2.0, 1.0, 1.0], [1.0, 1.0, l * 0.9999999]].into_iter().enumerate() {
                atoms.push(&NewAtom::at(k as i64 + 1, 1, x));
            }
            let mut neighbor = Neighbor::default();
            neighbor.build(&mut atoms, &domain, &NeighborSettings::new(0.3), 1, &|_, _| 2.5, false, &SpecialTable::default()).unwrap();
            let pairs: usize = neighbor.list.chunks.iter().map(|c| c.neigh.len()).sum();
            assert_eq!(pairs, 1, "box {l}");
        }
        let domain = Domain::new(3, [0.0; 3], [4.0; 3], [[BoundaryKind::Shrink; 2]; 3]);
        let mut atoms = Atoms::new(AtomFeatures::default());
        atoms.push(&NewAtom::at(1, 1, [-1e308, 1.0, 1.0]));
        atoms.push(&NewAtom::at(2, 1, [1e308, 1.0, 1.0]));
        let e = Neighbor::default().build(&mut atoms, &domain, &NeighborSettings::new(0.3), 1, &|_, _| 2.5, false, &SpecialTable::default());
        assert!(matches!(e, Err(NeighError::TooLarge { cut, .. }) if cut == 2.8), "{e:?}");
    }
}
