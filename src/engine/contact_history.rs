//! The engine-owned contact history of granular pair styles: a few values per contact (the
//! tangential spring of gran/hooke/history and granular) that must follow the contact from step
//! to step.
//!
//! * Between neighbour-list rebuilds the values sit next to the list: chunk `c` of the store holds
//!   a touch flag and `size` values per entry of chunk `c` of the list, so the pair loop reads and
//!   writes them by entry index (no lookups) and chunks stay independent under the slab schedule.
//! * At a rebuild atoms are re-sorted and wrapped, so entries move. A contact is identified by the
//!   atom IDs of its two atoms and the periodic image of the partner, written as the difference of
//!   "effective images" (image flags minus the ghost shift), which does not change when either atom
//!   is wrapped. The store keeps the IDs and effective images of every atom index as they were at
//!   the last rebuild, so it can name its contacts after the atoms have moved.
//! * A contact is stored from the side of the atom that lists it. Listed from the other side, its
//!   values are negated (tangential springs flip sign with the pair, LAMMPS' default history
//!   transfer), except those the model marks as kept (LAMMPS' transfer_history_factor +1: a
//!   contact radius, a rolling or twisting spring, which do not depend on the order of the pair). A pair with a periodic image is listed by both owned atoms (each keeps its
//!   own record); a pair of owned atoms is listed once.
//! * Values marked `flip` (see [`ContactHistory::set_flips`]) are negated when LAMMPS' own list
//!   moves the pair to its other atom, whatever dmhs does: LAMMPS 22 Jul 2025 transfers rolling
//!   and twisting springs with factor -1 although they do not depend on the order of the pair.
//!   The store then remembers, per entry, which atom LAMMPS lists the pair from
//!   ([`ListSides`]), and names its contacts from LAMMPS' listing atom.
//! * Only contacts that touch after the rebuild are looked up: the pair loop zeroes the history of
//!   every pair that does not touch, so carrying anything else would change nothing.
//! * [`ContactHistory::records`] lists the contacts by key (for write_restart);
//!   [`ContactHistory::restore`] takes them back and applies them at the next rebuild;
//!   [`ContactHistory::adopt`] adds those that arrived with atoms from other ranks.

use crate::engine::atoms::{Atoms, IdKeys};
use crate::engine::lammps_order::ListSides;
use crate::engine::neighbor::{ChunkList, NeighList, NEIGH_MASK};

/// Touch flags and values aligned with one chunk of the neighbour list.
#[derive(Clone, Debug, Default)]
pub struct HistoryChunk {
    pub touch: Vec<u8>,
    pub values: Vec<f64>,
    /// per entry: LAMMPS lists the pair from its atom i (only with `flip` values)
    pub side: Vec<bool>,
}

/// One contact by key, as written to restart files.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactRecord {
    /// Atom ID of the atom that lists the contact.
    pub owner: i64,
    pub partner: i64,
    /// Effective image of the owner minus that of the partner (see the module comment).
    pub image: [i32; 3],
    pub values: Vec<f64>,
}

#[derive(Clone, Debug, Default)]
pub struct ContactHistory {
    size: usize,
    /// per value: the same from the other side (not negated)
    keep: Vec<bool>,
    /// per value: negated when LAMMPS' list moves the pair to its other atom
    flip: Vec<bool>,
    pub chunks: Vec<HistoryChunk>,
    /// Atom ID and effective image of every atom index (owned, then ghosts) at the last rebuild.
    tags: Vec<i64>,
    eimg: Vec<[i32; 3]>,
    /// The list the chunks are aligned with (a copy: the engine replaces its list before the
    /// store is told about the rebuild).
    list: Vec<ChunkList>,
    /// Contacts from a restart file, applied at the next rebuild.
    pending: Option<Vec<ContactRecord>>,
    /// `pending` came from the same style named again, not from a restart file.
    carried: bool,
}

impl ContactHistory {
    /// A store for `size` values per contact.
    pub fn new(size: usize) -> ContactHistory {
        ContactHistory { size, keep: vec![false; size], ..ContactHistory::default() }
    }

    /// Change the values per contact and which of them keep their sign from the other side
    /// (`keep.len()` values). A new size drops the stored contacts (they are aligned again at
    /// the next rebuild); contacts pending from a restart file stay, and must have that size.
    pub fn set_layout(&mut self, keep: Vec<bool>) -> Result<(), String> {
        let mismatch = self.pending.as_ref().and_then(|p| p.iter().find(|r| r.values.len() != keep.len()));
        if mismatch.is_some() && self.carried {
            // a style named again with other models: its old contacts do not fit, start afresh
            self.pending = None;
        } else if let Some(r) = mismatch {
            return Err(format!("the restart file's contact histories keep {} values per contact; this pair style keeps {}", r.values.len(), keep.len()));
        }
        if keep.len() != self.size {
            self.size = keep.len();
            self.chunks.clear();
            self.list.clear();
        }
        self.keep = keep;
        Ok(())
    }

    /// The values (`flip.len()` of them, as the layout) that LAMMPS negates when its list moves
    /// a pair to the other atom, although dmhs keeps them (see the module comment).
    pub fn set_flips(&mut self, flip: Vec<bool>) {
        self.flip = flip;
    }

    fn flips(&self) -> bool {
        self.flip.iter().any(|&f| f)
    }

    pub fn size(&self) -> usize {
        self.size
    }

    /// Every touching contact, by key, in list order (contacts restored from a restart file and
    /// not yet applied are returned as they are). With `flip` values a contact is named from
    /// the atom LAMMPS lists it from (a record of the other atom is turned round, after them).
    pub fn records(&self) -> Vec<ContactRecord> {
        if let Some(p) = &self.pending {
            return p.clone();
        }
        let mut out = Vec::new();
        let mut turned = Vec::new();
        for (chunk, hist) in self.list.iter().zip(&self.chunks) {
            for i in chunk.start..chunk.end {
                let k0 = chunk.first_entry(i);
                for (k, &jraw) in chunk.neighbors(i).iter().enumerate() {
                    let e = k0 + k;
                    if hist.touch[e] == 0 {
                        continue;
                    }
                    let j = (jraw & NEIGH_MASK) as usize;
                    let values = &hist.values[e * self.size..(e + 1) * self.size];
                    if hist.side.get(e) == Some(&false) {
                        // a periodic pair's record of the listing atom, if any, comes first
                        turned.push(ContactRecord {
                            owner: self.tags[j],
                            partner: self.tags[i],
                            image: sub3i(self.eimg[j], self.eimg[i]),
                            values: values.iter().zip(&self.keep).map(|(&v, &keep)| if keep { v } else { -v }).collect(),
                        });
                        continue;
                    }
                    out.push(ContactRecord { owner: self.tags[i], partner: self.tags[j], image: sub3i(self.eimg[i], self.eimg[j]), values: values.to_vec() });
                }
            }
        }
        out.append(&mut turned);
        out
    }

    /// Contacts to apply at the next rebuild (from a restart file), replacing the stored ones.
    pub fn restore(&mut self, records: Vec<ContactRecord>) {
        self.pending = Some(records);
        self.carried = false;
    }

    /// The contacts of the same style named again (`pair_style`): applied as [`Self::restore`]
    /// does, or dropped if the new style's models keep another number of values.
    pub fn carry(&mut self, records: Vec<ContactRecord>) {
        self.pending = Some(records);
        self.carried = true;
    }

    /// Contacts that arrived with atoms from other ranks (a distributed run), applied with the
    /// stored ones at the next rebuild.
    pub fn adopt(&mut self, arrived: Vec<ContactRecord>) {
        if arrived.is_empty() {
            return;
        }
        let mut all = self.records();
        all.extend(arrived);
        self.pending = Some(all);
    }

    /// The touch flag and values stored for the entry of owned atom i that lists j (LAMMPS'
    /// lookup in pair single); None when i's entries do not hold j.
    pub fn entry(&self, i: usize, j: usize) -> Option<(bool, &[f64])> {
        let (c, chunk) = self.list.iter().enumerate().find(|(_, ch)| (ch.start..ch.end).contains(&i))?;
        let k = chunk.neighbors(i).iter().position(|&e| (e & NEIGH_MASK) as usize == j)?;
        let e = chunk.first_entry(i) + k;
        let h = self.chunks.get(c)?;
        Some((h.touch.get(e).is_some_and(|&t| t != 0), h.values.get(e * self.size..(e + 1) * self.size)?))
    }

    /// Number of contacts currently touching.
    pub fn ntouching(&self) -> usize {
        self.chunks.iter().map(|c| c.touch.iter().filter(|&&t| t != 0).count()).sum()
    }

    /// Carry the contacts over to a freshly built list. `touching(i, j)` says whether listed pair
    /// (i, j) is in contact now (the same test as the pair loop's); `sides` are LAMMPS' (used
    /// with `flip` values).
    pub fn rebuilt(&mut self, atoms: &Atoms, list: &NeighList, sides: Option<&ListSides>, touching: impl Fn(usize, usize) -> bool + Sync) {
        let size = self.size;
        let sides = sides.filter(|_| self.flips());
        let records = match self.pending.take() {
            Some(r) => r,
            None => self.records(),
        };
        // records grouped by owner ID: offsets over the keys of the atoms' IDs (the ID itself
        // for dense IDs); records of owners that are not atoms now are never looked up
        let keys = IdKeys::new(&atoms.tag);
        let nkeys = keys.len();
        let mut start = vec![0u32; nkeys + 1];
        for r in &records {
            if let Some(k) = keys.key(r.owner) {
                start[k + 1] += 1;
            }
        }
        for t in 0..nkeys {
            start[t + 1] += start[t];
        }
        let mut fill = start.clone();
        let mut by_owner: Vec<u32> = vec![0; records.len()];
        for (k, r) in records.iter().enumerate() {
            if let Some(key) = keys.key(r.owner) {
                by_owner[fill[key] as usize] = k as u32;
                fill[key] += 1;
            }
        }
        let find = |owner: i64, partner: i64, image: [i32; 3]| -> Option<&ContactRecord> {
            let t = keys.key(owner)?;
            by_owner[start[t] as usize..start[t + 1] as usize]
                .iter()
                .map(|&k| &records[k as usize])
                .find(|r| r.partner == partner && r.image == image && r.values.len() == size)
        };

        // the new atoms' keys
        let n = atoms.nlocal;
        self.tags.clear();
        self.tags.extend_from_slice(&atoms.tag);
        self.eimg.clear();
        self.eimg.extend_from_slice(&atoms.image[..n]);
        for (k, s) in atoms.ghost_shift.iter().enumerate() {
            let img = atoms.image[n + k];
            self.eimg.push([img[0] - s[0] as i32, img[1] - s[1] as i32, img[2] - s[2] as i32]);
        }

        let tags = &self.tags;
        let eimg = &self.eimg;
        let keep = &self.keep;
        let flip = &self.flip;
        let x = &atoms.x;
        self.chunks = crate::engine::par::team::map(list.chunks.iter().collect(), |chunk| {
                let len = chunk.len();
                let mut h = HistoryChunk { touch: vec![0; len], values: vec![0.0; len * size], side: vec![] };
                if let Some(sides) = sides {
                    for i in chunk.start..chunk.end {
                        h.side.extend(chunk.neighbors(i).iter().map(|&jraw| sides.first(i, (jraw & NEIGH_MASK) as usize, x)));
                    }
                }
                if records.is_empty() {
                    return h;
                }
                for i in chunk.start..chunk.end {
                    let k0 = chunk.first_entry(i);
                    for (k, &jraw) in chunk.neighbors(i).iter().enumerate() {
                        let j = (jraw & NEIGH_MASK) as usize;
                        if !touching(i, j) {
                            continue;
                        }
                        let e = k0 + k;
                        let image = sub3i(eimg[i], eimg[j]);
                        let dst = &mut h.values[e * size..(e + 1) * size];
                        // records are named from the atom LAMMPS listed the pair from; LAMMPS'
                        // lister now takes its own record (a pair with a periodic image may have
                        // one per atom), else the other's, which moved
                        let listed_by_i = h.side.get(e).copied();
                        let own = || find(tags[i], tags[j], image);
                        let other = || find(tags[j], tags[i], neg3i(image));
                        let (r, from_i) = match listed_by_i {
                            Some(false) => match other() {
                                Some(r) => (r, false),
                                None => match own() {
                                    Some(r) => (r, true),
                                    None => continue,
                                },
                            },
                            _ => match own() {
                                Some(r) => (r, true),
                                None => match other() {
                                    Some(r) => (r, false),
                                    None => continue,
                                },
                            },
                        };
                        if from_i {
                            dst.copy_from_slice(&r.values);
                        } else {
                            for ((d, s), &keep) in dst.iter_mut().zip(&r.values).zip(keep) {
                                *d = if keep { *s } else { -*s };
                            }
                        }
                        let moved = listed_by_i.is_some_and(|by_i| by_i != from_i);
                        h.touch[e] = 1;
                        if moved {
                            for (d, _) in dst.iter_mut().zip(flip).filter(|(_, &f)| f) {
                                *d = -*d;
                            }
                        }
                    }
                }
                h
            });
        self.list.clone_from(&list.chunks);
    }

    /// The chunks as a window for the slab schedule (chunk `c` of the store goes with chunk `c`
    /// of the list).
    pub fn chunks_mut(&mut self) -> crate::engine::par::ChunksMut<'_, HistoryChunk> {
        crate::engine::par::ChunksMut::new(&mut self.chunks)
    }
}

#[inline]
fn sub3i(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
fn neg3i(a: [i32; 3]) -> [i32; 3] {
    [-a[0], -a[1], -a[2]]
}
