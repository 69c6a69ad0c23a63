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

/// Group entries by chunk (`chunk_of[i]` = chunk of owned atom i); entries that need a periodic
/// image or a ghost go to the leftovers, so chunk entries read positions directly. Within a chunk, entries are
/// taken with a stride of N (0, N, 2N, ..., then 1, N+1, ...): interactions along a chain
/// (bond k and k+1 share an atom) would otherwise form one long dependency through the force
/// accumulators and run at the latency of sqrt/acos instead of their throughput.
pub fn slab<E: Copy, const N: usize>(entries: &[E], atoms: impl Fn(&E) -> [u32; N], shifted: impl Fn(&E) -> bool, chunk_of: &[u32], nchunks: usize) -> Slabbed<E> {
    // per entry: (grouping, chunk), grouping 0 near, 1 wide, 2 leftover
    let mut target: Vec<(u8, u32)> = Vec::with_capacity(entries.len());
    let mut leftover = Vec::new();
    for e in entries {
        let idx = atoms(e);
        let (lo, hi) = (*idx.iter().min().unwrap() as usize, *idx.iter().max().unwrap() as usize);
        // a ghost (a distributed run's) is in no chunk
        let (c, ch) = (chunk_of[lo], chunk_of.get(hi).copied().unwrap_or(u32::MAX - 1));
        let span = ch.saturating_sub(c) as usize;
        if shifted(e) || span >= WIDE {
            target.push((2, 0));
            leftover.push(*e);
        } else {
            target.push(((span > 1) as u8, c));
        }
    }
    let (near, offsets) = group::<E, N>(entries, &target, 0, nchunks);
    let (wide, wide_offsets) = group::<E, N>(entries, &target, 1, nchunks);
    Slabbed { entries: near, offsets, wide, wide_offsets, leftover }
}

/// The entries whose target grouping is `which`, ordered by chunk, each chunk with the stride
/// of N (see [`slab`]); and the chunk offsets.
fn group<E: Copy, const N: usize>(entries: &[E], target: &[(u8, u32)], which: u8, nchunks: usize) -> (Vec<E>, Vec<u32>) {
    let mut counts = vec![0u32; nchunks + 1];
    for &(g, c) in target {
        if g == which {
            counts[c as usize + 1] += 1;
        }
    }
    for c in 0..nchunks {
        counts[c + 1] += counts[c];
    }
    let offsets = counts.clone();
    let mut fill = counts;
    let total = offsets[nchunks] as usize;
    let Some(&first) = entries.iter().zip(target).find(|(_, t)| t.0 == which).map(|(e, _)| e) else {
        return (vec![], offsets);
    };
    let mut out = vec![first; total];
    for (e, &(g, c)) in entries.iter().zip(target) {
        if g == which {
            out[fill[c as usize] as usize] = *e;
            fill[c as usize] += 1;
        }
    }
    let mut scratch = Vec::new();
    for c in 0..nchunks {
        let chunk = &mut out[offsets[c] as usize..offsets[c + 1] as usize];
        scratch.clear();
        for pass in 0..N {
            scratch.extend(chunk.iter().skip(pass).step_by(N).copied());
        }
        chunk.copy_from_slice(&scratch);
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

