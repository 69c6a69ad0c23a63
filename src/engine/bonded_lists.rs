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

/// Interactions grouped by the slab chunk of their lowest-index atom, when all their atoms
/// lie in that chunk or the next (so chunks can run with the pair loop's even/odd schedule);
/// the rest (e.g. interactions spanning a periodic boundary) are done afterwards in order.
/// Chunk `c` holds `entries[offsets[c]..offsets[c+1]]`.
#[derive(Clone, Debug)]
pub struct Slabbed<E> {
    pub entries: Vec<E>,
    pub offsets: Vec<u32>,
    pub leftover: Vec<E>,
}

impl<E> Default for Slabbed<E> {
    fn default() -> Self {
        Slabbed { entries: vec![], offsets: vec![0], leftover: vec![] }
    }
}

impl<E> Slabbed<E> {
    pub fn len(&self) -> usize {
        self.entries.len() + self.leftover.len()
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    pub fn nchunks(&self) -> usize {
        self.offsets.len() - 1
    }
}

impl<const N: usize> Slabbed<Entry<N>> {
    /// Keep the entries for which `keep` gives a new record index (records were removed from
    /// the topology), in order; chunk boundaries follow.
    pub fn retain_records(&mut self, keep: impl Fn(u32) -> Option<u32>) {
        let mut out = 0;
        let mut start = 0;
        for c in 0..self.nchunks() {
            let end = self.offsets[c + 1] as usize;
            for k in start..end {
                if let Some(rec) = keep(self.entries[k].rec) {
                    self.entries[out] = Entry { rec, ..self.entries[k] };
                    out += 1;
                }
            }
            start = end;
            self.offsets[c + 1] = out as u32;
        }
        self.entries.truncate(out);
        self.leftover.retain_mut(|e| match keep(e.rec) {
            Some(rec) => {
                e.rec = rec;
                true
            }
            None => false,
        });
    }
}

/// The interactions of chunk `c` (none if the kind has fewer chunks).
pub fn chunk<E>(s: &Slabbed<E>, c: usize) -> &[E] {
    if c + 1 < s.offsets.len() {
        &s.entries[s.offsets[c] as usize..s.offsets[c + 1] as usize]
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
    let mut target: Vec<u32> = Vec::with_capacity(entries.len());
    let mut counts = vec![0u32; nchunks + 1];
    let mut leftover = Vec::new();
    for e in entries {
        let idx = atoms(e);
        let (lo, hi) = (*idx.iter().min().unwrap() as usize, *idx.iter().max().unwrap() as usize);
        // a ghost (a distributed run's) is in no chunk
        let (c, ch) = (chunk_of[lo], chunk_of.get(hi).copied().unwrap_or(u32::MAX - 1));
        if ch <= c + 1 && !shifted(e) {
            target.push(c);
            counts[c as usize + 1] += 1;
        } else {
            target.push(u32::MAX);
            leftover.push(*e);
        }
    }
    for c in 0..nchunks {
        counts[c + 1] += counts[c];
    }
    let offsets = counts.clone();
    let mut fill = counts;
    let total = offsets[nchunks] as usize;
    let Some(&first) = entries.iter().zip(&target).find(|(_, &t)| t != u32::MAX).map(|(e, _)| e) else {
        return Slabbed { entries: vec![], offsets, leftover };
    };
    let mut out = vec![first; total];
    for (e, &t) in entries.iter().zip(&target) {
        if t != u32::MAX {
            out[fill[t as usize] as usize] = *e;
            fill[t as usize] += 1;
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
    Slabbed { entries: out, offsets, leftover }
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

