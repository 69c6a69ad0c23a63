//! Particles as a struct of arrays. Owned ("local") atoms come first, ghost images of
//! periodic neighbours after them, exactly as LAMMPS arranges `x`, `v`, `f`.
//!
//! Which optional arrays exist is decided once by `atom_style` (see [`AtomFeatures`]); an
//! absent feature keeps its vectors empty so a scene pays only for what it uses.

use crate::engine::domain::Periods;

/// Optional per-atom properties, switched on by the atom style.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AtomFeatures {
    /// molecule ID (bond, angle, molecular, full)
    pub molecule: bool,
    /// charge (full, charge)
    pub charge: bool,
    /// bonds / angles / dihedrals allowed
    pub bonds: bool,
    pub angles: bool,
    pub dihedrals: bool,
    /// radius, per-atom mass, angular velocity, torque (sphere)
    pub sphere: bool,
    /// rho, drho, esph, desph, cv, vest (sph)
    pub sph: bool,
    /// orientation quaternion (bpm/sphere)
    pub quat: bool,
}

impl AtomFeatures {
    /// True if mass is per atom (`rmass`) rather than per type.
    pub fn per_atom_mass(&self) -> bool {
        self.sphere
    }
    pub fn molecular(&self) -> bool {
        self.bonds || self.angles || self.dihedrals
    }
}

/// Extra per-atom storage owned by a fix or compute (e.g. `fix move` original positions):
/// kept here so sorting and deleting atoms permutes it with everything else.
#[derive(Clone, Debug)]
pub struct ExtraArray {
    pub name: String,
    pub stride: usize,
    /// `stride` values per atom: owned atoms, then (if `ghosts`) ghost images.
    pub data: Vec<f64>,
    /// Ghost images carry the values too (for fields that pair styles read on neighbours).
    pub ghosts: bool,
}

#[derive(Clone, Debug, Default)]
pub struct Atoms {
    pub features: AtomFeatures,
    /// Number of owned atoms; indices `nlocal..` are ghosts.
    pub nlocal: usize,
    /// For each ghost (index `k - nlocal`): the owned atom it images and its periodic shift.
    pub ghost_owner: Vec<u32>,
    pub ghost_shift: Vec<[i8; 3]>,

    pub tag: Vec<i64>,
    /// Atom type, 1-based as in LAMMPS.
    pub typ: Vec<usize>,
    /// Group membership bits (bit 0 = group `all`).
    pub mask: Vec<u32>,
    pub x: Vec<[f64; 3]>,
    pub v: Vec<[f64; 3]>,
    pub f: Vec<[f64; 3]>,
    pub image: Vec<[i32; 3]>,

    pub molecule: Vec<i64>,
    pub q: Vec<f64>,

    pub radius: Vec<f64>,
    pub rmass: Vec<f64>,
    pub omega: Vec<[f64; 3]>,
    pub torque: Vec<[f64; 3]>,
    /// Orientation (w, i, j, k), LAMMPS' `quat` of atom_style bpm/sphere; (1, 0, 0, 0) when made.
    pub quat: Vec<[f64; 4]>,

    pub rho: Vec<f64>,
    pub drho: Vec<f64>,
    pub esph: Vec<f64>,
    pub desph: Vec<f64>,
    pub cv: Vec<f64>,
    pub vest: Vec<[f64; 3]>,

    pub extra: Vec<ExtraArray>,
}

/// Values for one new atom (fields absent from the style are ignored).
#[derive(Clone, Debug)]
pub struct NewAtom {
    pub tag: i64,
    pub typ: usize,
    pub x: [f64; 3],
    pub v: [f64; 3],
    pub image: [i32; 3],
    pub molecule: i64,
    pub q: f64,
    pub radius: f64,
    pub rmass: f64,
    pub rho: f64,
    pub esph: f64,
    pub cv: f64,
}

impl NewAtom {
    pub fn at(tag: i64, typ: usize, x: [f64; 3]) -> NewAtom {
        // defaults as LAMMPS' create_atoms gives them: sphere diameter 1, density 1; sph cv 1
        NewAtom {
            tag,
            typ,
            x,
            v: [0.0; 3],
            image: [0; 3],
            molecule: 0,
            q: 0.0,
            radius: 0.5,
            rmass: std::f64::consts::PI * 4.0 / 3.0 * 0.125,
            rho: 0.0,
            esph: 0.0,
            cv: 1.0,
        }
    }
}

impl Atoms {
    pub fn new(features: AtomFeatures) -> Atoms {
        Atoms { features, ..Atoms::default() }
    }
    /// Owned plus ghost atoms.
    pub fn nall(&self) -> usize {
        self.x.len()
    }
    pub fn nghost(&self) -> usize {
        self.x.len() - self.nlocal
    }

    /// Append an owned atom. Must be called with no ghosts present.
    pub fn push(&mut self, a: &NewAtom) {
        debug_assert_eq!(self.nghost(), 0);
        let ft = self.features;
        self.tag.push(a.tag);
        self.typ.push(a.typ);
        self.mask.push(1);
        self.x.push(a.x);
        self.v.push(a.v);
        self.f.push([0.0; 3]);
        self.image.push(a.image);
        if ft.molecule {
            self.molecule.push(a.molecule);
        }
        if ft.charge {
            self.q.push(a.q);
        }
        if ft.sphere {
            self.radius.push(a.radius);
            self.rmass.push(a.rmass);
            self.omega.push([0.0; 3]);
            self.torque.push([0.0; 3]);
        }
        if ft.quat {
            self.quat.push([1.0, 0.0, 0.0, 0.0]);
        }
        if ft.sph {
            self.rho.push(a.rho);
            self.drho.push(0.0);
            self.esph.push(a.esph);
            self.desph.push(0.0);
            self.cv.push(a.cv);
            self.vest.push([0.0; 3]);
        }
        for e in &mut self.extra {
            e.data.extend(std::iter::repeat(0.0).take(e.stride));
        }
        self.nlocal += 1;
    }

    /// Room for `more` atoms beyond those present in every array, so that adding them (ghosts
    /// of a rebuild) does not double each array's capacity: an array that must grow grows to
    /// what is needed plus 1/16 (a few more ghosts at the next rebuild fit without a copy).
    /// Empty arrays are left alone, as in [`Atoms::permute`]: those of features the atom style
    /// lacks, and the ghost-only ones before the first ghost.
    pub fn reserve(&mut self, more: usize) {
        fn grow<T>(v: &mut Vec<T>, more: usize, per: usize) {
            let need = v.len() + more * per;
            if !v.is_empty() && v.capacity() < need {
                v.reserve_exact(need - v.len() + need / 16);
            }
        }
        grow(&mut self.ghost_owner, more, 1);
        grow(&mut self.ghost_shift, more, 1);
        grow(&mut self.tag, more, 1);
        grow(&mut self.typ, more, 1);
        grow(&mut self.mask, more, 1);
        grow(&mut self.x, more, 1);
        grow(&mut self.v, more, 1);
        grow(&mut self.f, more, 1);
        grow(&mut self.image, more, 1);
        grow(&mut self.molecule, more, 1);
        grow(&mut self.q, more, 1);
        grow(&mut self.radius, more, 1);
        grow(&mut self.rmass, more, 1);
        grow(&mut self.omega, more, 1);
        grow(&mut self.torque, more, 1);
        grow(&mut self.quat, more, 1);
        grow(&mut self.rho, more, 1);
        grow(&mut self.drho, more, 1);
        grow(&mut self.esph, more, 1);
        grow(&mut self.desph, more, 1);
        grow(&mut self.cv, more, 1);
        grow(&mut self.vest, more, 1);
        for e in self.extra.iter_mut().filter(|e| e.ghosts) {
            grow(&mut e.data, more, e.stride);
        }
    }

    /// Remove all ghosts (before atoms are added, removed or reordered).
    pub fn clear_ghosts(&mut self) {
        let n = self.nlocal;
        self.ghost_owner.clear();
        self.ghost_shift.clear();
        self.tag.truncate(n);
        self.typ.truncate(n);
        self.mask.truncate(n);
        self.x.truncate(n);
        self.v.truncate(n);
        self.f.truncate(n);
        self.image.truncate(n);
        let ft = self.features;
        if ft.molecule {
            self.molecule.truncate(n);
        }
        if ft.charge {
            self.q.truncate(n);
        }
        if ft.sphere {
            self.radius.truncate(n);
            self.rmass.truncate(n);
            self.omega.truncate(n);
            self.torque.truncate(n);
        }
        if ft.quat {
            self.quat.truncate(n);
        }
        if ft.sph {
            self.rho.truncate(n);
            self.drho.truncate(n);
            self.esph.truncate(n);
            self.desph.truncate(n);
            self.cv.truncate(n);
            self.vest.truncate(n);
        }
        for e in &mut self.extra {
            e.data.truncate(n * e.stride);
        }
    }

    /// Add a ghost image of owned atom `owner` shifted by `shift` box periods; per-atom
    /// values are copied, the position is the image LAMMPS' forward communication makes.
    pub fn push_ghost(&mut self, owner: usize, shift: [i8; 3], periods: Periods) {
        let x = periods.shifted(self.x[owner], shift);
        self.push_ghost_at(owner, shift, x);
    }

    /// [`Atoms::push_ghost`] at a given position (a triclinic box's rebuild places its ghosts
    /// from box fractions).
    pub fn push_ghost_at(&mut self, owner: usize, shift: [i8; 3], x: [f64; 3]) {
        self.ghost_owner.push(owner as u32);
        self.ghost_shift.push(shift);
        self.tag.push(self.tag[owner]);
        self.typ.push(self.typ[owner]);
        self.mask.push(self.mask[owner]);
        self.x.push(x);
        self.v.push(self.v[owner]);
        self.f.push([0.0; 3]);
        self.image.push(self.image[owner]);
        let ft = self.features;
        if ft.molecule {
            self.molecule.push(self.molecule[owner]);
        }
        if ft.charge {
            self.q.push(self.q[owner]);
        }
        if ft.sphere {
            self.radius.push(self.radius[owner]);
            self.rmass.push(self.rmass[owner]);
            self.omega.push(self.omega[owner]);
            self.torque.push([0.0; 3]);
        }
        if ft.quat {
            self.quat.push(self.quat[owner]);
        }
        if ft.sph {
            self.rho.push(self.rho[owner]);
            self.drho.push(0.0);
            self.esph.push(self.esph[owner]);
            self.desph.push(0.0);
            self.cv.push(self.cv[owner]);
            self.vest.push(self.vest[owner]);
        }
        for e in self.extra.iter_mut().filter(|e| e.ghosts) {
            let s = e.stride;
            e.data.extend_from_within(owner * s..(owner + 1) * s);
        }
    }

    /// Refresh ghost positions from their owners (LAMMPS' forward communication of `x`).
    pub fn forward_positions(&mut self, periods: Periods) {
        let n = self.nlocal;
        let (local, ghosts) = self.x.split_at_mut(n);
        for (k, g) in ghosts.iter_mut().enumerate() {
            *g = periods.shifted(local[self.ghost_owner[k] as usize], self.ghost_shift[k]);
        }
    }

    /// Copy a per-atom vector field from owners to ghosts.
    pub fn forward_field<T: Copy>(field: &mut [T], nlocal: usize, owner: &[u32]) {
        let (local, ghosts) = field.split_at_mut(nlocal);
        for (g, &o) in ghosts.iter_mut().zip(owner) {
            *g = local[o as usize];
        }
    }

    /// Refresh the per-atom values that pair styles may read on ghosts (velocities and the
    /// SPH/DEM state); called every step when ghosts exist.
    pub fn forward_state(&mut self) {
        let n = self.nlocal;
        let own = &self.ghost_owner;
        Self::forward_field(&mut self.v, n, own);
        let ft = self.features;
        if ft.sphere {
            Self::forward_field(&mut self.omega, n, own);
            Self::forward_field(&mut self.radius, n, own);
            Self::forward_field(&mut self.rmass, n, own);
        }
        if ft.quat {
            Self::forward_field(&mut self.quat, n, own);
        }
        if ft.sph {
            Self::forward_field(&mut self.rho, n, own);
            Self::forward_field(&mut self.esph, n, own);
            Self::forward_field(&mut self.cv, n, own);
            Self::forward_field(&mut self.vest, n, own);
        }
        for e in self.extra.iter_mut().filter(|e| e.ghosts) {
            let s = e.stride;
            let (local, ghosts) = e.data.split_at_mut(n * s);
            for (k, &o) in own.iter().enumerate() {
                let o = o as usize;
                ghosts[k * s..(k + 1) * s].copy_from_slice(&local[o * s..(o + 1) * s]);
            }
        }
    }

    /// Append atom `i`'s values to `out` as doubles (a rank sends atoms this way): all of them
    /// for an owned atom that moves to another rank; for a ghost (`owned` false) what ghosts
    /// carry. Forces, torques and rates are not sent: they are computed again after the move.
    pub fn pack(&self, i: usize, out: &mut Vec<f64>, owned: bool) {
        self.pack_at(i, self.x[i], out, owned);
    }

    /// [`Atoms::pack`] of a ghost image of atom `i` at `x`, the periodic image `shift` of it
    /// (kept as the ghost's `ghost_shift`, which names contacts by image).
    pub fn pack_ghost(&self, i: usize, x: [f64; 3], shift: [i8; 3], out: &mut Vec<f64>) {
        self.pack_at(i, x, out, false);
        out.extend(shift.iter().map(|&s| s as f64));
    }

    fn pack_at(&self, i: usize, x: [f64; 3], out: &mut Vec<f64>, owned: bool) {
        let ft = self.features;
        // IDs, types, masks and image flags are exact in a double (IDs up to 2^53)
        out.extend_from_slice(&[self.tag[i] as f64, self.typ[i] as f64, self.mask[i] as f64]);
        out.extend_from_slice(&x);
        out.extend_from_slice(&self.v[i]);
        out.extend(self.image[i].iter().map(|&m| m as f64));
        if ft.molecule {
            out.push(self.molecule[i] as f64);
        }
        if ft.charge {
            out.push(self.q[i]);
        }
        if ft.sphere {
            out.extend_from_slice(&[self.radius[i], self.rmass[i]]);
            out.extend_from_slice(&self.omega[i]);
        }
        if ft.quat {
            out.extend_from_slice(&self.quat[i]);
        }
        if ft.sph {
            out.extend_from_slice(&[self.rho[i], self.esph[i], self.cv[i]]);
            out.extend_from_slice(&self.vest[i]);
        }
        for e in self.extra.iter().filter(|e| owned || e.ghosts) {
            out.extend_from_slice(&e.data[i * e.stride..(i + 1) * e.stride]);
        }
    }

    /// Read one atom packed by [`Atoms::pack_at`] from the front of `buf` and append it with
    /// `push` (owned: every extra array; ghost: those ghosts carry); returns the rest of `buf`.
    fn unpack_one<'b>(&mut self, buf: &'b [f64], owned: bool) -> &'b [f64] {
        let ft = self.features;
        let mut k = 0;
        let mut take = |n: usize| {
            let s = &buf[k..k + n];
            k += n;
            s
        };
        let head = take(3);
        let (tag, typ, mask) = (head[0] as i64, head[1] as usize, head[2] as u32);
        let t = take(3);
        let x = [t[0], t[1], t[2]];
        let t = take(3);
        let v = [t[0], t[1], t[2]];
        let t = take(3);
        let image = [t[0] as i32, t[1] as i32, t[2] as i32];
        self.tag.push(tag);
        self.typ.push(typ);
        self.mask.push(mask);
        self.x.push(x);
        self.v.push(v);
        self.f.push([0.0; 3]);
        self.image.push(image);
        if ft.molecule {
            self.molecule.push(take(1)[0] as i64);
        }
        if ft.charge {
            self.q.push(take(1)[0]);
        }
        if ft.sphere {
            let t = take(5);
            self.radius.push(t[0]);
            self.rmass.push(t[1]);
            self.omega.push([t[2], t[3], t[4]]);
            self.torque.push([0.0; 3]);
        }
        if ft.quat {
            let t = take(4);
            self.quat.push([t[0], t[1], t[2], t[3]]);
        }
        if ft.sph {
            let t = take(6);
            self.rho.push(t[0]);
            self.drho.push(0.0);
            self.esph.push(t[1]);
            self.desph.push(0.0);
            self.cv.push(t[2]);
            self.vest.push([t[3], t[4], t[5]]);
        }
        for e in self.extra.iter_mut().filter(|e| owned || e.ghosts) {
            e.data.extend_from_slice(take(e.stride));
        }
        if !owned {
            let t = take(3);
            self.ghost_shift.push([t[0] as i8, t[1] as i8, t[2] as i8]);
        }
        &buf[k..]
    }

    /// Append the owned atoms packed in `buf` (no ghosts may be present).
    pub fn unpack_owned(&mut self, mut buf: &[f64]) {
        debug_assert_eq!(self.nghost(), 0);
        while !buf.is_empty() {
            buf = self.unpack_one(buf, true);
            self.nlocal += 1;
        }
    }

    /// Append the ghosts packed in `buf` with [`Atoms::pack_ghost`] (they have no owner here:
    /// `ghost_owner` is not kept for them; `ghost_shift` is).
    pub fn unpack_ghosts(&mut self, mut buf: &[f64]) {
        while !buf.is_empty() {
            buf = self.unpack_one(buf, false);
        }
    }

    /// No atoms, with the same atom style and extra per-atom arrays (to be filled with
    /// [`Atoms::unpack_owned`]).
    pub fn empty_like(&self) -> Atoms {
        let extra = self.extra.iter().map(|e| ExtraArray { name: e.name.clone(), stride: e.stride, data: Vec::new(), ghosts: e.ghosts }).collect();
        Atoms { features: self.features, extra, ..Atoms::default() }
    }

    /// Reorder owned atoms: new position `k` takes old atom `order[k]`. No ghosts allowed.
    pub fn permute(&mut self, order: &[usize]) {
        debug_assert_eq!(self.nghost(), 0);
        fn apply<T: Copy>(v: &mut Vec<T>, order: &[usize]) {
            if v.is_empty() {
                return;
            }
            // the new array keeps the old one's capacity, the room ghosts take after a rebuild
            let keep = v.capacity();
            let old = std::mem::replace(v, Vec::with_capacity(keep));
            v.extend(order.iter().map(|&i| old[i]));
        }
        apply(&mut self.tag, order);
        apply(&mut self.typ, order);
        apply(&mut self.mask, order);
        apply(&mut self.x, order);
        apply(&mut self.v, order);
        apply(&mut self.f, order);
        apply(&mut self.image, order);
        apply(&mut self.molecule, order);
        apply(&mut self.q, order);
        apply(&mut self.radius, order);
        apply(&mut self.rmass, order);
        apply(&mut self.omega, order);
        apply(&mut self.torque, order);
        apply(&mut self.quat, order);
        apply(&mut self.rho, order);
        apply(&mut self.drho, order);
        apply(&mut self.esph, order);
        apply(&mut self.desph, order);
        apply(&mut self.cv, order);
        apply(&mut self.vest, order);
        for e in &mut self.extra {
            let keep = e.data.capacity();
            let old = std::mem::replace(&mut e.data, Vec::with_capacity(keep));
            let s = e.stride;
            for &i in order {
                e.data.extend_from_slice(&old[i * s..(i + 1) * s]);
            }
        }
        self.nlocal = order.len();
    }

    /// Delete the owned atoms for which `remove` is true (order of the rest is kept).
    pub fn retain(&mut self, remove: &[bool]) {
        let order: Vec<usize> = (0..self.nlocal).filter(|&i| !remove[i]).collect();
        self.permute(&order);
    }

    /// Register (or find) an extra per-atom array for owned atoms only; returns its index.
    /// Call with no ghosts present.
    pub fn extra_array(&mut self, name: &str, stride: usize) -> usize {
        self.extra_field(name, stride, false)
    }

    /// Register (or find) an extra per-atom array; `ghosts`: ghost images carry it too (it is
    /// refreshed with the velocities every step). Call with no ghosts present.
    pub fn extra_field(&mut self, name: &str, stride: usize, ghosts: bool) -> usize {
        if let Some(k) = self.extra.iter().position(|e| e.name == name) {
            self.extra[k].ghosts |= ghosts;
            return k;
        }
        self.extra.push(ExtraArray { name: name.to_string(), stride, data: vec![0.0; self.nlocal * stride], ghosts });
        self.extra.len() - 1
    }

    /// Index of an extra array by name.
    pub fn find_extra(&self, name: &str) -> Option<usize> {
        self.extra.iter().position(|e| e.name == name)
    }
    pub fn remove_extra(&mut self, name: &str) {
        self.extra.retain(|e| e.name != name);
    }

    /// Mass of atom `i`: per-atom `rmass` if the style has it, else the per-type mass.
    #[inline]
    pub fn mass(&self, i: usize, type_mass: &[f64]) -> f64 {
        if self.features.per_atom_mass() { self.rmass[i] } else { type_mass[self.typ[i]] }
    }

    /// Largest atom ID.
    pub fn max_tag(&self) -> i64 {
        self.tag[..self.nlocal].iter().copied().max().unwrap_or(0)
    }

    /// The largest molecule ID of the owned atoms (0 without molecule IDs or atoms): new
    /// molecules are numbered after it.
    pub fn max_molecule(&self) -> i64 {
        if !self.features.molecule {
            return 0;
        }
        self.molecule[..self.nlocal].iter().copied().max().unwrap_or(0).max(0)
    }

    /// Map from atom ID to local index of the owned atoms (IDs must be unique and positive).
    pub fn tag_map(&self) -> TagMap {
        TagMap::new(&self.tag[..self.nlocal])
    }
}

/// The largest atom ID: LAMMPS' `MAXTAGINT` in its default build (`LAMMPS_SMALLBIG`, where the
/// ID type `tagint` is a 32-bit int), 2^31 - 1. Data and restart files with larger IDs are refused.
pub const MAX_ATOM_ID: i64 = dmhs_parser::data_file::MAX_ATOM_ID;

/// Dense keys for atom IDs, for tables indexed by ID. When the IDs are dense the key is the ID
/// itself and a table has an entry per possible ID (LAMMPS' `atom_modify map array`); when
/// the largest ID is far above the number of IDs a hash map numbers the IDs instead (LAMMPS'
/// `map hash`), so that a few atoms with IDs near 2^31 do not need gigabytes. Dense: the largest
/// ID is at most [`IdKeys::DENSE_MIN`] (LAMMPS' switch to a hash is at 1,000,000) or at most
/// twice the number of IDs (dmhs keeps arrays for large dense systems, whose lookups are in
/// the neighbour build).
#[derive(Clone, Debug)]
pub enum IdKeys {
    /// key = ID, for IDs 0..=max
    Dense { max: usize },
    /// key = the number of the ID in the hash
    Sparse(std::collections::HashMap<i64, u32>),
}

impl Default for IdKeys {
    fn default() -> Self {
        IdKeys::Dense { max: 0 }
    }
}

impl IdKeys {
    /// A largest ID up to this gives an array whatever the number of atoms.
    pub const DENSE_MIN: i64 = 1_000_000;

    /// Keys for `ids` (positive; repeats get one key).
    pub fn new(ids: &[i64]) -> IdKeys {
        let max = ids.iter().copied().max().unwrap_or(0).max(0);
        if max <= Self::DENSE_MIN.max(2 * ids.len() as i64) {
            return IdKeys::Dense { max: max as usize };
        }
        let mut m = std::collections::HashMap::with_capacity(ids.len());
        for &id in ids {
            let next = m.len() as u32;
            m.entry(id).or_insert(next);
        }
        IdKeys::Sparse(m)
    }
    /// Number of keys (the length of a table indexed by key).
    pub fn len(&self) -> usize {
        match self {
            IdKeys::Dense { max } => max + 1,
            IdKeys::Sparse(m) => m.len(),
        }
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The key of `id`, if it is one of the IDs (dense: any ID in 0..=max).
    #[inline]
    pub fn key(&self, id: i64) -> Option<usize> {
        match self {
            IdKeys::Dense { max } => (id >= 0 && id as usize <= *max).then_some(id as usize),
            IdKeys::Sparse(m) => m.get(&id).map(|&k| k as usize),
        }
    }
}

/// Atom-ID -> local-index map (LAMMPS' `atom_modify map array`, or `map hash` for sparse IDs:
/// see [`IdKeys`]).
#[derive(Clone, Debug, Default)]
pub struct TagMap {
    keys: IdKeys,
    index: Vec<u32>,
}

impl TagMap {
    /// Map from `tags[i]` to `i`.
    pub fn new(tags: &[i64]) -> TagMap {
        let keys = IdKeys::new(tags);
        let mut index = vec![u32::MAX; keys.len()];
        for (i, &t) in tags.iter().enumerate() {
            if let Some(k) = keys.key(t) {
                index[k] = i as u32;
            }
        }
        TagMap { keys, index }
    }
    #[inline]
    pub fn get(&self, tag: i64) -> Option<usize> {
        match self.index.get(self.keys.key(tag)?) {
            Some(&i) if i != u32::MAX => Some(i as usize),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn id_maps_are_arrays_for_dense_ids_and_hashes_for_sparse_ones() {
        let dense = TagMap::new(&[3, 1, 2]);
        assert!(matches!(dense.keys, IdKeys::Dense { max: 3 }));
        assert_eq!((dense.get(1), dense.get(2), dense.get(3), dense.get(0), dense.get(4), dense.get(-1)), (Some(1), Some(2), Some(0), None, None, None));
        // a few atoms with IDs near LAMMPS' largest: no entry per possible ID
        let sparse = TagMap::new(&[1, MAX_ATOM_ID, 1_000_000_000]);
        assert!(matches!(sparse.keys, IdKeys::Sparse(_)));
        assert_eq!(sparse.index.len(), 3);
        assert_eq!((sparse.get(MAX_ATOM_ID), sparse.get(1_000_000_000), sparse.get(1), sparse.get(2)), (Some(1), Some(2), Some(0), None));
        // LAMMPS' threshold (an array up to ID 1,000,000), and dmhs keeps arrays for dense large systems
        assert!(matches!(IdKeys::new(&[1_000_000]), IdKeys::Dense { .. }));
        assert!(matches!(IdKeys::new(&[1_000_001]), IdKeys::Sparse(_)));
        let big: Vec<i64> = (1..=600_000).chain([1_200_000]).collect();
        assert!(matches!(IdKeys::new(&big), IdKeys::Dense { max: 1_200_000 }));
    }

    #[test]
    fn ghosts_copy_owner_and_shift_position() {
        let mut a = Atoms::new(AtomFeatures { sph: true, ..Default::default() });
        let mut n = NewAtom::at(7, 2, [0.25, 1.0, 0.0]);
        n.rho = 1000.0;
        a.push(&n);
        a.push_ghost(0, [1, 0, 0], Periods { prd: [10.0, 5.0, 1.0], tilt: None });
        assert_eq!(a.nlocal, 1);
        assert_eq!(a.nghost(), 1);
        assert_eq!(a.x[1], [10.25, 1.0, 0.0]);
        assert_eq!(a.tag[1], 7);
        assert_eq!(a.rho[1], 1000.0);
        a.x[0][0] = 0.5;
        a.forward_positions(Periods { prd: [10.0, 5.0, 1.0], tilt: None });
        assert_eq!(a.x[1][0], 10.5);
        a.clear_ghosts();
        assert_eq!(a.nall(), 1);
    }

    #[test]
    fn permute_moves_every_field() {
        let mut a = Atoms::new(AtomFeatures { molecule: true, ..Default::default() });
        let k = a.extra_array("xorig", 3);
        for t in 1..=3 {
            let mut n = NewAtom::at(t, 1, [t as f64, 0.0, 0.0]);
            n.molecule = 10 * t;
            a.push(&n);
        }
        a.extra[k].data = vec![1., 1., 1., 2., 2., 2., 3., 3., 3.];
        a.permute(&[2, 0, 1]);
        assert_eq!(a.tag, vec![3, 1, 2]);
        assert_eq!(a.molecule, vec![30, 10, 20]);
        assert_eq!(a.extra[k].data, vec![3., 3., 3., 1., 1., 1., 2., 2., 2.]);
        let m = a.tag_map();
        assert_eq!(m.get(3), Some(0));
        assert_eq!(m.get(4), None);
    }
}

#[cfg(test)]
mod extra_tests {
    use super::*;
    #[test]
    fn ghost_fields_follow_their_owners() {
        let mut a = Atoms::new(AtomFeatures::default());
        a.push(&NewAtom::at(1, 1, [0.1, 0.0, 0.0]));
        a.push(&NewAtom::at(2, 1, [0.9, 0.0, 0.0]));
        let c = a.extra_field("conc", 1, true);
        let p = a.extra_array("private", 2);
        a.extra[c].data = vec![0.25, 0.75];
        a.push_ghost(1, [-1, 0, 0], Periods { prd: [1.0; 3], tilt: None });
        assert_eq!(a.extra[c].data, vec![0.25, 0.75, 0.75]);
        assert_eq!(a.extra[p].data.len(), 4);
        a.extra[c].data[1] = 0.5;
        a.forward_state();
        assert_eq!(a.extra[c].data[2], 0.5);
        a.clear_ghosts();
        assert_eq!(a.extra[c].data, vec![0.25, 0.5]);
    }
}
