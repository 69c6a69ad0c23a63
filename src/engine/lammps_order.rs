//! The order in which serial LAMMPS stores its owned atoms ("local order"), kept beside dmhs'
//! own order. dmhs sorts its atoms into slab order at every list rebuild; LAMMPS keeps atoms
//! where they were created and reorders them only in `Atom::sort` (at the setup of every run
//! and then every `sortfreq` steps, 1000 by default, on a reneighbouring step), binning them on
//! a grid of half the neighbour cutoff and keeping the previous order inside a bin. Models
//! whose results depend on the atom order (random numbers drawn per atom, sums over atoms)
//! walk the atoms in this order to give LAMMPS' bits.
//!
//! Atoms that appear (create_atoms, read_data, fix pour) are appended in dmhs' order at the
//! time, which is their creation order; atoms that disappear are removed as LAMMPS'
//! `Comm::exchange` removes lost atoms (the last atom moves into the hole). Triclinic boxes are
//! binned as orthogonal ones (LAMMPS bins them over the bounding box of the tilted cell).

use super::atoms::Atoms;
use super::domain::Domain;

/// When a list rebuild sorts LAMMPS' order ([`LammpsOrder::after_rebuild`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sort {
    /// The setup of a run (LAMMPS' Verlet::setup sorts).
    Setup,
    /// A rebuild during a run: every `sortfreq` steps.
    Due,
    /// A rerun snapshot's setup (LAMMPS' setup_minimal does not sort).
    Never,
}

#[derive(Clone, Debug)]
pub struct LammpsOrder {
    /// Atom IDs in LAMMPS' local order.
    ids: Vec<i64>,
    /// dmhs' local index of each atom of `ids`, valid after the last rebuild.
    local: Vec<usize>,
    /// `atom_modify sort Nfreq binsize`: 0 turns sorting off; binsize 0 means half the
    /// neighbour cutoff.
    pub sortfreq: i64,
    pub binsize: f64,
    /// `atom_modify first GROUP`: the group's atoms are kept first (LAMMPS' first_reorder
    /// after every exchange; sorting is then off).
    pub first: Option<String>,
    nextsort: i64,
    /// Which atom of a pair LAMMPS' half list lists it from, as of the last rebuild (made on
    /// request, see [`LammpsOrder::make_sides`]).
    sides: Option<ListSides>,
}

impl Default for LammpsOrder {
    fn default() -> Self {
        LammpsOrder { ids: Vec::new(), local: Vec::new(), sortfreq: 1000, binsize: 0.0, first: None, nextsort: 0, sides: None }
    }
}

impl LammpsOrder {
    /// The order read from a restart file (the map to dmhs' indices follows at the next
    /// rebuild).
    pub fn restored(ids: Vec<i64>, sortfreq: i64, binsize: f64) -> LammpsOrder {
        LammpsOrder { ids, sortfreq, binsize, ..LammpsOrder::default() }
    }

    /// dmhs' local indices of the owned atoms in LAMMPS' order (valid until dmhs reorders or
    /// adds atoms, i.e. between list rebuilds).
    pub fn local(&self) -> &[usize] {
        &self.local
    }

    /// Atom IDs in LAMMPS' order as of the last rebuild (or [`LammpsOrder::before_rebuild`]).
    pub fn ids(&self) -> &[i64] {
        &self.ids
    }

    /// Owned atoms in LAMMPS' order if known for the current atoms, else in dmhs' order.
    pub fn indices(&self, nlocal: usize) -> std::borrow::Cow<'_, [usize]> {
        if self.local.len() == nlocal {
            std::borrow::Cow::Borrowed(&self.local)
        } else {
            std::borrow::Cow::Owned((0..nlocal).collect())
        }
    }

    /// Before dmhs reorders the atoms of a rebuild: drop atoms that are gone (LAMMPS' copy of
    /// the last atom into the hole) and append new ones in their current order.
    pub fn before_rebuild(&mut self, atoms: &Atoms) {
        let owned = &atoms.tag[..atoms.nlocal];
        let now = atoms.tag_map();
        let mut i = 0;
        while i < self.ids.len() {
            if now.get(self.ids[i]).is_none() {
                self.ids.swap_remove(i);
            } else {
                i += 1;
            }
        }
        let known = super::atoms::TagMap::new(&self.ids);
        for &t in owned {
            if known.get(t).is_none() {
                self.ids.push(t);
            }
        }
    }

    /// dmhs' indices of the owned atoms in LAMMPS' order now, between rebuilds too (after
    /// [`LammpsOrder::before_rebuild`]: atoms made since the last rebuild at the end, deleted
    /// ones gone as LAMMPS loses them).
    pub fn current(&mut self, atoms: &Atoms) -> Vec<usize> {
        self.before_rebuild(atoms);
        let map = atoms.tag_map();
        self.ids.iter().map(|&t| map.get(t).expect("every ordered atom is owned")).collect()
    }

    /// Bring the map to dmhs' indices up to date after atoms were added or deleted between
    /// rebuilds ([`LammpsOrder::current`]), so that output in LAMMPS' order lists the atoms
    /// there are now.
    pub fn refresh(&mut self, atoms: &Atoms) {
        self.local = self.current(atoms);
        self.sides = None;
    }

    /// LAMMPS' Atom::first_reorder (after [`LammpsOrder::before_rebuild`]): each atom of the
    /// group (`bit`) found behind the first atom outside it swaps places with that atom.
    pub fn first_reorder(&mut self, atoms: &Atoms, bit: u32) {
        let map = atoms.tag_map();
        let inside = |t: i64| map.get(t).is_some_and(|i| atoms.mask[i] & bit != 0);
        let ids = &mut self.ids;
        let n = ids.len();
        let mut nfirst = 0;
        while nfirst < n && inside(ids[nfirst]) {
            nfirst += 1;
        }
        for i in 0..n {
            if i > nfirst && inside(ids[i]) {
                ids.swap(i, nfirst);
                while nfirst < n && inside(ids[nfirst]) {
                    nfirst += 1;
                }
            }
        }
    }

    /// IDs 1..N in this order (after [`LammpsOrder::before_rebuild`]): LAMMPS' `tag_extend`
    /// of an atomic system whose IDs were all cleared (`delete_atoms ... compress yes`).
    pub fn renumber(&mut self, atoms: &mut Atoms) {
        let map = atoms.tag_map();
        for (k, t) in self.ids.iter_mut().enumerate() {
            let i = map.get(*t).expect("every ordered atom is owned");
            atoms.tag[i] = k as i64 + 1;
            *t = k as i64 + 1;
        }
        self.local.clear();
        self.sides = None;
    }

    /// After dmhs' rebuild at `step`: LAMMPS' `Atom::sort` when it is due (`Sort::Setup`:
    /// always, at the setup of a run; `Sort::Due`: on rebuilds from `nextsort` on;
    /// `Sort::Never`: the setup of a rerun snapshot), then the map to dmhs' indices.
    /// `cutneighmax` is the largest pair cutoff plus skin.
    /// A box with more sort bins than LAMMPS allows (2^31 - 1; LAMMPS stops there) keeps the
    /// order, where dmhs' own bins keep working.
    pub fn after_rebuild(&mut self, atoms: &Atoms, domain: &Domain, cutneighmax: f64, step: i64, sort: Sort) {
        let map = atoms.tag_map();
        let local = |ids: &[i64]| -> Vec<usize> { ids.iter().map(|&t| map.get(t).expect("every ordered atom is owned")).collect() };
        let due = match sort {
            Sort::Setup => true,
            Sort::Due => step >= self.nextsort,
            Sort::Never => false,
        };
        if self.sortfreq > 0 && due {
            let binsize = self.sort_binsize(cutneighmax);
            if binsize > 0.0 {
                self.nextsort = (step / self.sortfreq) * self.sortfreq + self.sortfreq;
                let idx = local(&self.ids);
                let bins = sort_bins(domain, binsize);
                let total = bins.total().filter(|&t| t <= i32::MAX as usize).unwrap_or(1);
                if total > 1 {
                    let key: Vec<usize> = idx.iter().map(|&i| bins.bin(&atoms.x[i])).collect();
                    let mut perm: Vec<usize> = (0..self.ids.len()).collect();
                    // stable: atoms of one bin keep their order (LAMMPS' linked lists)
                    perm.sort_by_key(|&k| key[k]);
                    self.ids = perm.iter().map(|&k| self.ids[k]).collect();
                }
            } else {
                // LAMMPS turns sorting off when there is no cutoff and no bin size
                self.sortfreq = 0;
            }
        }
        self.local = local(&self.ids);
        self.sides = None;
    }

    /// LAMMPS' sort bin size: `atom_modify sort` binsize, else half the list cutoff.
    fn sort_binsize(&self, cutneighmax: f64) -> f64 {
        if self.binsize > 0.0 { self.binsize } else { 0.5 * cutneighmax }
    }

    /// Whether [`LammpsOrder::after_rebuild`] with these arguments sorts the atoms: a sort is
    /// due and has more than one bin. (LAMMPS bins a triclinic box's atoms in box coordinates,
    /// between two conversions of theirs, so their last bits change on that rebuild.)
    pub fn sorts(&self, domain: &Domain, cutneighmax: f64, step: i64, sort: Sort) -> bool {
        let due = match sort {
            Sort::Setup => true,
            Sort::Due => step >= self.nextsort,
            Sort::Never => false,
        };
        let binsize = self.sort_binsize(cutneighmax);
        self.sortfreq > 0 && due && binsize > 0.0 && sort_bins(domain, binsize).total().is_some_and(|t| t > 1 && t <= i32::MAX as usize)
    }

    /// After [`LammpsOrder::after_rebuild`]: LAMMPS' neighbour bins of this rebuild, for
    /// [`ListSides::first`]. `binsize` is `neigh_modify binsize` (0: half of `cutneighmax`);
    /// `newton` is `newton_pair`.
    pub fn make_sides(&mut self, atoms: &Atoms, domain: &Domain, cutneighmax: f64, binsize: f64, newton: bool) {
        let mut rank = vec![0u32; atoms.nlocal];
        for (k, &i) in self.local.iter().enumerate() {
            rank[i] = k as u32;
        }
        self.sides = Some(ListSides::new(domain, if binsize > 0.0 { binsize } else { 0.5 * cutneighmax }, rank, newton));
    }

    /// The sides made at the last rebuild, if asked for.
    pub fn sides(&self) -> Option<&ListSides> {
        self.sides.as_ref()
    }
}

/// Which atom of a pair lists it in LAMMPS' half neighbour list (LAMMPS' standard bins for one
/// process: `NBinStandard::setup_bins`, `coord2bin`, the half stencil and `NPairBin`'s test
/// within a bin; with `newton off` the earlier atom in LAMMPS' order, and each owner its pairs
/// with ghosts). Results that depend on that side (a history value LAMMPS
/// negates when the other atom lists the pair) follow it.
#[derive(Clone, Debug)]
pub struct ListSides {
    lo: [f64; 3],
    hi: [f64; 3],
    n: [i64; 3],
    inv: [f64; 3],
    /// LAMMPS' local index of each owned atom (by dmhs index)
    rank: Vec<u32>,
    newton: bool,
    /// A triclinic box: LAMMPS' `half/bin/newton/tri` lists a pair from the atom below the
    /// other (z, then y, then x), whatever their bins.
    tri: bool,
}

impl ListSides {
    fn new(domain: &Domain, binsize: f64, rank: Vec<u32>, newton: bool) -> ListSides {
        let (lo, hi) = (domain.lo, domain.hi);
        let mut n = [1i64; 3];
        let mut inv = [1.0; 3];
        let bininv = 1.0 / if binsize > 0.0 { binsize } else { hi[0] - lo[0] };
        for d in 0..3 {
            let len = hi[d] - lo[d];
            let nb = if d == 2 && domain.dimension == 2 { 1 } else { (len * bininv) as i64 };
            n[d] = nb.max(1);
            inv[d] = 1.0 / (len / n[d] as f64);
        }
        ListSides { lo, hi, n, inv, rank, newton, tri: domain.triclinic() }
    }

    /// LAMMPS' bin coordinate along `d` (ghosts beyond the box get bins outside it).
    fn coord(&self, x: f64, d: usize) -> i64 {
        if x >= self.hi[d] {
            ((x - self.hi[d]) * self.inv[d]) as i64 + self.n[d]
        } else if x >= self.lo[d] {
            (((x - self.lo[d]) * self.inv[d]) as i64).min(self.n[d] - 1)
        } else {
            ((x - self.lo[d]) * self.inv[d]) as i64 - 1
        }
    }

    /// Whether LAMMPS lists the pair of owned atom `i` and atom `j` (owned, or a ghost at
    /// `x[j]`) from i: j's bin comes after i's (z, then y, then x: the half stencil); in one
    /// bin, an owned j comes later in LAMMPS' order, a ghost j lies above (z, y, x).
    pub fn first(&self, i: usize, j: usize, x: &[[f64; 3]]) -> bool {
        let (xi, xj) = (&x[i], &x[j]);
        if !self.newton {
            return match (self.rank.get(i), self.rank.get(j)) {
                (Some(ri), Some(rj)) => ri < rj,
                _ => true,
            };
        }
        if self.tri {
            for d in [2, 1, 0] {
                if xj[d] != xi[d] {
                    return xj[d] > xi[d];
                }
            }
            return match (self.rank.get(i), self.rank.get(j)) {
                (Some(ri), Some(rj)) => ri < rj,
                _ => true,
            };
        }
        for d in [2, 1, 0] {
            let (bi, bj) = (self.coord(xi[d], d), self.coord(xj[d], d));
            if bi != bj {
                return bj > bi;
            }
        }
        match (self.rank.get(i), self.rank.get(j)) {
            (Some(ri), Some(rj)) => ri < rj,
            _ => {
                for d in [2, 1, 0] {
                    if xj[d] != xi[d] {
                        return xj[d] > xi[d];
                    }
                }
                true
            }
        }
    }
}

/// LAMMPS' `Atom::setup_sort_bins` for one process (its sub-domain is the box).
struct SortBins {
    lo: [f64; 3],
    n: [usize; 3],
    inv: [f64; 3],
}

fn sort_bins(domain: &Domain, binsize: f64) -> SortBins {
    let bininv = 1.0 / binsize;
    let mut n = [1usize; 3];
    let mut inv = [0.0; 3];
    // a triclinic box's bins cover its bounding box
    let (lo, hi) = if domain.triclinic() { domain.bbox([0.0; 3], [1.0; 3]) } else { (domain.lo, domain.hi) };
    for d in 0..3 {
        let len = hi[d] - lo[d];
        let mut nb = (len * bininv) as i64;
        if d == 2 && domain.dimension == 2 {
            nb = 1;
        }
        n[d] = nb.max(1) as usize;
        inv[d] = n[d] as f64 / len;
    }
    SortBins { lo, n, inv }
}

impl SortBins {
    /// Number of bins (None if it overflows).
    fn total(&self) -> Option<usize> {
        self.n[0].checked_mul(self.n[1])?.checked_mul(self.n[2])
    }
    fn bin(&self, x: &[f64; 3]) -> usize {
        let mut c = [0usize; 3];
        for d in 0..3 {
            // C's truncating cast, then clamped into the grid
            let k = ((x[d] - self.lo[d]) * self.inv[d]) as i64;
            c[d] = k.clamp(0, self.n[d] as i64 - 1) as usize;
        }
        (c[2] * self.n[1] + c[1]) * self.n[0] + c[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::atoms::{AtomFeatures, NewAtom};
    use crate::engine::domain::BoundaryKind;

    fn domain(l: f64) -> Domain {
        Domain::new(3, [0.0; 3], [l; 3], [[BoundaryKind::Periodic; 2]; 3])
    }

    #[test]
    fn sort_bins_by_z_then_y_then_x_and_keeps_the_order_inside_a_bin() {
        let mut atoms = Atoms::new(AtomFeatures::default());
        // two bins per dimension (box 4, bin 2)
        for (t, x) in [(1, [3.0, 0.5, 0.5]), (2, [0.5, 0.5, 3.0]), (3, [0.5, 0.5, 0.5]), (4, [1.0, 1.0, 1.0]), (5, [0.5, 3.0, 0.5])] {
            atoms.push(&NewAtom::at(t, 1, x));
        }
        let mut o = LammpsOrder::default();
        o.before_rebuild(&atoms);
        o.after_rebuild(&atoms, &domain(4.0), 4.0, 0, Sort::Setup);
        assert_eq!(o.ids, vec![3, 4, 1, 5, 2]);
        assert_eq!(o.local(), &[2, 3, 0, 4, 1]);
        // not due: the order is kept whatever dmhs does
        o.after_rebuild(&atoms, &domain(4.0), 4.0, 10, Sort::Due);
        assert_eq!(o.ids, vec![3, 4, 1, 5, 2]);
    }

    #[test]
    fn lammps_lists_a_pair_from_the_lower_bin_then_the_earlier_atom() {
        // box 4, cutneighmax 2: bins of 1
        let mut atoms = Atoms::new(AtomFeatures::default());
        for (t, x) in [(1, [0.5, 0.5, 1.5]), (2, [0.6, 0.5, 0.5]), (3, [1.5, 0.5, 0.5]), (4, [1.6, 0.6, 0.6])] {
            atoms.push(&NewAtom::at(t, 1, x));
        }
        let mut o = LammpsOrder { sortfreq: 0, ..LammpsOrder::default() };
        o.before_rebuild(&atoms);
        o.after_rebuild(&atoms, &domain(4.0), 2.0, 0, Sort::Setup);
        o.make_sides(&atoms, &domain(4.0), 2.0, 0.0, true);
        let s = o.sides().unwrap();
        // z first: 2 lists 1; then x: 2 lists 3
        assert!(s.first(1, 0, &atoms.x) && !s.first(0, 1, &atoms.x));
        assert!(s.first(1, 2, &atoms.x) && !s.first(2, 1, &atoms.x));
        // one bin: LAMMPS' order (3 before 4)
        assert!(s.first(2, 3, &atoms.x) && !s.first(3, 2, &atoms.x));
        // newton off: always the earlier atom
        o.make_sides(&atoms, &domain(4.0), 2.0, 0.0, false);
        assert!(o.sides().unwrap().first(0, 1, &atoms.x));
    }

    #[test]
    fn lost_atoms_are_replaced_by_the_last_and_new_atoms_appended() {
        let mut atoms = Atoms::new(AtomFeatures::default());
        for t in 1..=4 {
            atoms.push(&NewAtom::at(t, 1, [0.5; 3]));
        }
        let mut o = LammpsOrder { sortfreq: 0, ..LammpsOrder::default() };
        o.before_rebuild(&atoms);
        atoms.retain(&[false, true, false, false]);
        atoms.push(&NewAtom::at(9, 1, [0.5; 3]));
        o.before_rebuild(&atoms);
        assert_eq!(o.ids, vec![1, 4, 3, 9]);
    }

    #[test]
    fn a_box_with_too_many_sort_bins_keeps_the_order_instead_of_overflowing() {
        let mut atoms = Atoms::new(AtomFeatures::default());
        atoms.push(&NewAtom::at(2, 1, [9e11; 3]));
        atoms.push(&NewAtom::at(1, 1, [0.5; 3]));
        let mut o = LammpsOrder::default();
        o.before_rebuild(&atoms);
        o.after_rebuild(&atoms, &domain(1e12), 1e-3, 0, Sort::Setup);
        assert_eq!(o.ids, vec![2, 1]);
        // with fewer bins the two atoms are sorted
        o.after_rebuild(&atoms, &domain(1e12), 1e11, 0, Sort::Setup);
        assert_eq!(o.ids, vec![1, 2]);
    }
}
