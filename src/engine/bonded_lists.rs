//! The bonded interactions of the owned atoms with local indices and periodic shifts, grouped
//! by slab chunk: rebuilt with the neighbour lists, read by the bonded pass and topology fixes.

/// One interaction: local indices of its atoms, the periodic shift of each (relative to the
/// reference atom), and its type.
#[derive(Clone, Copy, Debug)]
pub struct Entry<const N: usize> {
    pub atoms: [u32; N],
    pub shift: [[i8; 3]; N],
    pub typ: usize,
    /// Index of the interaction's record in the topology (per-bond history lives there).
    pub rec: u32,
}

impl<const N: usize> Entry<N> {
    /// Some atom is taken at a periodic image.
    pub fn shifted(&self) -> bool {
        self.shift.iter().any(|s| *s != [0; 3])
    }
}

/// Interactions grouped by the slab chunk of their lowest-index atom. Those whose atoms all
/// lie in that chunk or the next run with the pair loop's even/odd schedule: chunk `c` holds
/// `entries[offsets[c]..offsets[c+1]]`. Those reaching two or three chunks further (an angle or
/// a dihedral along the slab axis, where chunks are about one cutoff thick) run afterwards on a
/// schedule of [`WIDE`]-chunk windows: chunk `c` holds `wide[wide_offsets[c]..wide_offsets[c+1]]`.
/// The rest (interactions across a periodic boundary, with a ghost, or longer still) are done
/// last, in order.
#[derive(Clone, Debug)]
pub struct Slabbed<E> {
    pub entries: Vec<E>,
    pub offsets: Vec<u32>,
    pub wide: Vec<E>,
    pub wide_offsets: Vec<u32>,
    pub leftover: Vec<E>,
}

/// Chunks a task of the wide schedule writes to: an interaction of chunk `c` reaches at most
/// chunk `c + WIDE - 1`.
pub const WIDE: usize = 4;

impl<E> Default for Slabbed<E> {
    fn default() -> Self {
        Slabbed { entries: vec![], offsets: vec![0], wide: vec![], wide_offsets: vec![0], leftover: vec![] }
    }
}

impl<E> Slabbed<E> {
    pub fn len(&self) -> usize {
        self.entries.len() + self.wide.len() + self.leftover.len()
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    pub fn nchunks(&self) -> usize {
        self.offsets.len() - 1
    }
    /// Every interaction: the chunks' in chunk order, the wide ones in chunk order, the rest.
    pub fn all(&self) -> impl Iterator<Item = &E> {
        self.entries.iter().chain(&self.wide).chain(&self.leftover)
    }
}

impl<const N: usize> Slabbed<Entry<N>> {
    /// Keep the entries for which `keep` gives a new record index (records were removed from
    /// the topology), in order; chunk boundaries follow.
    pub fn retain_records(&mut self, keep: impl Fn(u32) -> Option<u32>) {
        retain_grouped(&mut self.entries, &mut self.offsets, &keep);
        retain_grouped(&mut self.wide, &mut self.wide_offsets, &keep);
        self.leftover.retain_mut(|e| match keep(e.rec) {
            Some(rec) => {
                e.rec = rec;
                true
            }
            None => false,
        });
    }
}

/// [`Slabbed::retain_records`] of one grouping.
fn retain_grouped<const N: usize>(entries: &mut Vec<Entry<N>>, offsets: &mut [u32], keep: &impl Fn(u32) -> Option<u32>) {
    let mut out = 0;
    let mut start = 0;
    for c in 0..offsets.len() - 1 {
        let end = offsets[c + 1] as usize;
        for k in start..end {
            if let Some(rec) = keep(entries[k].rec) {
                entries[out] = Entry { rec, ..entries[k] };
                out += 1;
            }
        }
        start = end;
        offsets[c + 1] = out as u32;
    }
    entries.truncate(out);
}

/// The interactions of chunk `c` (none if the kind has fewer chunks).
pub fn chunk<E>(s: &Slabbed<E>, c: usize) -> &[E] {
    of_chunk(&s.entries, &s.offsets, c)
}

/// The wide interactions of chunk `c` (none if the kind has fewer chunks).
pub fn wide_chunk<E>(s: &Slabbed<E>, c: usize) -> &[E] {
    of_chunk(&s.wide, &s.wide_offsets, c)
}

/// Chunk `c` of entries grouped by `offsets`.
fn of_chunk<'a, E>(entries: &'a [E], offsets: &[u32], c: usize) -> &'a [E] {
    if c + 1 < offsets.len() {
        &entries[offsets[c] as usize..offsets[c + 1] as usize]
    } else {
        &[]
    }
}

/// Group entries (`parts`, one after the other) by chunk (`chunk_of[i]` = chunk of owned atom
/// i); entries that need a periodic image or a ghost go to the leftovers, so chunk entries read
/// positions directly. Within a chunk, entries are taken with a stride of N (0, N, 2N, ..., then
/// 1, N+1, ...): interactions along a chain (bond k and k+1 share an atom) would otherwise form
/// one long dependency through the force accumulators and run at the latency of sqrt/acos
/// instead of their throughput.
///
/// `reuse`: the previous lists, whose memory (still in cache: the pass read it every step) is
/// written again.
pub fn slab<E: Copy, const N: usize>(parts: &[Vec<E>], atoms: impl Fn(&E) -> [u32; N], shifted: impl Fn(&E) -> bool, chunk_of: &[u32], nchunks: usize, reuse: Slabbed<E>) -> Slabbed<E> {
    let Slabbed { entries: near, offsets, wide: wide_out, wide_offsets, mut leftover } = reuse;
    leftover.clear();
    // per entry its chunk if it is a near one (else NOT_NEAR), with the count of each chunk (at
    // c + 1); the few wide ones with their chunks, and the leftovers, as they come
    const NOT_NEAR: u32 = u32::MAX;
    let mut near_chunk: Vec<u32> = Vec::with_capacity(parts.iter().map(Vec::len).sum());
    let mut near_counts = vec![0u32; nchunks + 1];
    let mut wide: Vec<(u32, E)> = Vec::new();
    for e in parts.iter().flatten() {
        let idx = atoms(e);
        let (lo, hi) = (*idx.iter().min().unwrap() as usize, *idx.iter().max().unwrap() as usize);
        // a ghost (a distributed run's) is in no chunk
        let (c, ch) = (chunk_of[lo], chunk_of.get(hi).copied().unwrap_or(u32::MAX - 1));
        let span = ch.saturating_sub(c) as usize;
        if shifted(e) || span >= WIDE {
            near_chunk.push(NOT_NEAR);
            leftover.push(*e);
        } else if span > 1 {
            near_chunk.push(NOT_NEAR);
            wide.push((c, *e));
        } else {
            near_chunk.push(c);
            near_counts[c as usize + 1] += 1;
        }
    }
    let (near, offsets) = place::<E, N>(parts.iter().flatten().zip(&near_chunk).filter(|(_, &c)| c != NOT_NEAR).map(|(e, &c)| (c, e)), near_counts, near, offsets);
    let mut wide_counts = vec![0u32; nchunks + 1];
    wide.iter().for_each(|&(c, _)| wide_counts[c as usize + 1] += 1);
    let (wide, wide_offsets) = place::<E, N>(wide.iter().map(|(c, e)| (*c, e)), wide_counts, wide_out, wide_offsets);
    Slabbed { entries: near, offsets, wide, wide_offsets, leftover }
}

/// The entries (each with its chunk, in order) at their places: ordered by chunk, each chunk
/// with the stride of N (see [`slab`]); and the chunk offsets. `counts[c + 1]`: the entries of
/// chunk c. `out` and `offsets`: vectors to fill.
fn place<'a, E: Copy + 'a, const N: usize>(entries: impl Iterator<Item = (u32, &'a E)>, counts: Vec<u32>, mut out: Vec<E>, mut offsets: Vec<u32>) -> (Vec<E>, Vec<u32>) {
    let nchunks = counts.len() - 1;
    offsets.clear();
    offsets.push(0);
    for c in 0..nchunks {
        offsets.push(offsets[c] + counts[c + 1]);
    }
    out.clear();
    let mut seen = vec![0u32; nchunks];
    for (c, e) in entries {
        let c = c as usize;
        let (n, m) = ((offsets[c + 1] - offsets[c]) as usize, seen[c] as usize);
        seen[c] += 1;
        // the m-th entry of the chunk is the (m / N)-th of pass m % N, after the passes before
        // (pass q takes entries q, q + N, ...: ceil((n - q) / N) of them)
        let pass = m % N;
        let before: usize = (0..pass).map(|q| (n - q).div_ceil(N)).sum();
        let at = offsets[c] as usize + before + m / N;
        if out.is_empty() {
            // any entry fills the room first: every place is written
            out.resize(offsets[nchunks] as usize, *e);
        }
        out[at] = *e;
    }
    (out, offsets)
}

#[derive(Clone, Debug, Default)]
pub struct BondedLists {
    pub bonds: Slabbed<Entry<2>>,
    pub angles: Slabbed<Entry<3>>,
    pub dihedrals: Slabbed<Entry<4>>,
    /// The bonds in serial LAMMPS' bond-list order (`newton_bond off`), for the styles whose
    /// results hang on the order of the sums (the BPM styles); empty for the others.
    pub lammps_bonds: Vec<Listed>,
}

/// A bond as serial LAMMPS lists it with `newton_bond off`: once, by the atom of lower local
/// index, or (a bond to a periodic image) once by each atom, the force going to that atom only.
#[derive(Clone, Copy, Debug)]
pub struct Listed {
    /// Atoms and shifts; the listing atom has no shift.
    pub entry: Entry<2>,
    /// Which of the two atoms receive the bond's force.
    pub apply: [bool; 2],
    /// A copy of the record's `Bond::history`, kept in list order so the BPM pass reads it
    /// without a scattered read of the topology record; the pass writes both.
    pub history: [f64; crate::engine::topology::BOND_HISTORY],
}


#[cfg(test)]
mod tests {
    use super::*;

    /// The grouping as first written: entries by chunk with a counting sort, then each chunk
    /// reordered with the stride of N through a scratch copy.
    fn reference<const N: usize>(entries: &[Entry<N>], chunk_of: &[u32], nchunks: usize) -> Slabbed<Entry<N>> {
        let mut target = vec![];
        let mut leftover = vec![];
        for e in entries {
            let (lo, hi) = (*e.atoms.iter().min().unwrap() as usize, *e.atoms.iter().max().unwrap() as usize);
            let (c, ch) = (chunk_of[lo], chunk_of.get(hi).copied().unwrap_or(u32::MAX - 1));
            let span = ch.saturating_sub(c) as usize;
            if e.shifted() || span >= WIDE {
                target.push((2, 0));
                leftover.push(*e);
            } else {
                target.push(((span > 1) as u8, c));
            }
        }
        let group = |which: u8| {
            let mut offsets = vec![0u32; nchunks + 1];
            let mut out = vec![];
            for c in 0..nchunks {
                let chunk: Vec<Entry<N>> = entries.iter().zip(&target).filter(|(_, t)| **t == (which, c as u32)).map(|(e, _)| *e).collect();
                for pass in 0..N {
                    out.extend(chunk.iter().skip(pass).step_by(N).copied());
                }
                offsets[c + 1] = out.len() as u32;
            }
            (out, offsets)
        };
        let ((near, offsets), (wide, wide_offsets)) = (group(0), group(1));
        Slabbed { entries: near, offsets, wide, wide_offsets, leftover }
    }

    fn recs<const N: usize>(s: &Slabbed<Entry<N>>) -> [Vec<u32>; 3] {
        [&s.entries, &s.wide, &s.leftover].map(|v| v.iter().map(|e| e.rec).collect())
    }

    #[test]
    fn slab_places_entries_as_the_counting_sort_and_stride_did() {
        // 60 atoms in 12 chunks of 5; angles of nearby atoms, some reaching 2-4 chunks
        // further, some shifted, in several parts; and the previous lists' memory reused
        let chunk_of: Vec<u32> = (0..60).map(|i| i / 5).collect();
        let mut seed = 11u64;
        let mut next = |m: u64| {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 33) % m
        };
        let entries: Vec<Entry<3>> = (0..500)
            .map(|k| {
                let a = next(60) as u32;
                let reach = [3, 3, 3, 12, 18][next(5) as usize];
                let b = (a + next(reach) as u32).min(59);
                let c = a.saturating_sub(next(4) as u32);
                let shift = if next(9) == 0 { [[0; 3], [1, 0, 0], [0; 3]] } else { [[0; 3]; 3] };
                Entry { atoms: [a, b, c], shift, typ: 1, rec: k }
            })
            .collect();
        let want = reference(&entries, &chunk_of, 12);
        let parts = vec![entries[..123].to_vec(), vec![], entries[123..].to_vec()];
        let old = slab(&[entries[..40].to_vec()], |e: &Entry<3>| e.atoms, Entry::shifted, &chunk_of, 12, Slabbed::default());
        let got = slab(&parts, |e: &Entry<3>| e.atoms, Entry::shifted, &chunk_of, 12, old);
        assert!(!want.wide.is_empty() && !want.leftover.is_empty() && want.entries.len() > 300);
        assert_eq!(recs(&got), recs(&want));
        assert_eq!((got.offsets, got.wide_offsets), (want.offsets, want.wide_offsets));
        // no entries at all
        let none = slab::<Entry<3>, 3>(&[], |e| e.atoms, Entry::shifted, &chunk_of, 12, Slabbed::default());
        assert_eq!((none.len(), none.offsets.len(), none.wide_offsets.len()), (0, 13, 13));
    }
}
