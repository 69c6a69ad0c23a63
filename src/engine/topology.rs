//! Bonds, angles and dihedrals, stored by atom ID so they survive sorting and wrapping.
//! Atom order inside a record follows the data file (LAMMPS stores a bond on its first atom,
//! an angle and a dihedral on their second atom; forces use the closest image of the other
//! atoms relative to that one).

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bond {
    pub typ: usize,
    pub atoms: [i64; 2],
    /// Per-bond history of the BPM bond styles (LAMMPS' fix bond/history): the reference
    /// length (0 until the style stores it at its first force evaluation), then what else the
    /// style keeps (bpm/rotational: the reference direction).
    pub history: [f64; BOND_HISTORY],
    /// The bond's place in each of its atoms' own bond lists (LAMMPS' `bond_atom[i][m]`, m
    /// here; `u32::MAX` until [`Topology::assign_bond_slots`]). Only the order of an atom's
    /// slots matters: it is the order in which LAMMPS lists the atom's bonds.
    pub slots: [u32; 2],
    /// Turned off by `delete_bonds` (LAMMPS' negative type): kept, and counted in the special
    /// lists, but not computed.
    pub off: bool,
}

/// Values of [`Bond::history`] (LAMMPS' largest `nhistory` of a BPM style, bpm/rotational's).
pub const BOND_HISTORY: usize = 4;

impl Bond {
    pub fn new(typ: usize, atoms: [i64; 2]) -> Bond {
        Bond { typ, atoms, history: [0.0; BOND_HISTORY], slots: [u32::MAX; 2], off: false }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Angle {
    pub typ: usize,
    pub atoms: [i64; 3],
    /// Turned off by `delete_bonds` (see [`Bond::off`]).
    pub off: bool,
}

impl Angle {
    pub fn new(typ: usize, atoms: [i64; 3]) -> Angle {
        Angle { typ, atoms, off: false }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dihedral {
    pub typ: usize,
    pub atoms: [i64; 4],
    /// Turned off by `delete_bonds` (see [`Bond::off`]).
    pub off: bool,
}

impl Dihedral {
    pub fn new(typ: usize, atoms: [i64; 4]) -> Dihedral {
        Dihedral { typ, atoms, off: false }
    }
}

/// Each interaction's record index under the ID of the atom LAMMPS stores it on with
/// `newton_bond on` (atom 1 of a bond, atom 2 of an angle or dihedral), sorted by that ID: a
/// rank of a distributed run finds its own atoms' interactions without walking the others'.
#[derive(Clone, Debug, Default)]
pub struct StoredOn {
    pub bonds: Vec<(i64, u32)>,
    pub angles: Vec<(i64, u32)>,
    pub dihedrals: Vec<(i64, u32)>,
}

impl StoredOn {
    /// The index of the interactions that are on (not turned off by `delete_bonds`).
    pub fn new(t: &Topology) -> StoredOn {
        fn sorted(on: impl Iterator<Item = (i64, bool)>) -> Vec<(i64, u32)> {
            let mut v: Vec<(i64, u32)> = on.enumerate().filter(|(_, (_, off))| !off).map(|(k, (tag, _))| (tag, k as u32)).collect();
            v.sort_unstable();
            v
        }
        StoredOn {
            bonds: sorted(t.bonds.iter().map(|b| (b.atoms[0], b.off))),
            angles: sorted(t.angles.iter().map(|a| (a.atoms[1], a.off))),
            dihedrals: sorted(t.dihedrals.iter().map(|d| (d.atoms[1], d.off))),
        }
    }
    /// The records of `list` stored on atom `tag`, in record order.
    pub fn on(list: &[(i64, u32)], tag: i64) -> impl Iterator<Item = u32> + '_ {
        let from = list.partition_point(|e| e.0 < tag);
        list[from..].iter().take_while(move |e| e.0 == tag).map(|e| e.1)
    }
}

#[derive(Clone, Debug, Default)]
pub struct Topology {
    pub nbondtypes: usize,
    pub nangletypes: usize,
    pub ndihedraltypes: usize,
    pub nimpropertypes: usize,
    pub bonds: Vec<Bond>,
    pub angles: Vec<Angle>,
    pub dihedrals: Vec<Dihedral>,
}

impl Topology {
    /// Drop every record that involves one of `tags` (for delete_atoms).
    pub fn remove_atoms(&mut self, gone: &std::collections::HashSet<i64>) {
        self.bonds.retain(|b| !b.atoms.iter().any(|t| gone.contains(t)));
        self.angles.retain(|a| !a.atoms.iter().any(|t| gone.contains(t)));
        self.dihedrals.retain(|d| !d.atoms.iter().any(|t| gone.contains(t)));
    }
    /// Drop the bonds at record indices `recs` (any order), keeping the others' order.
    pub fn remove_bond_records(&mut self, recs: &[usize]) {
        let mut gone = vec![false; self.bonds.len()];
        for &k in recs {
            gone[k] = true;
        }
        let mut k = 0;
        self.bonds.retain(|_| {
            k += 1;
            !gone[k - 1]
        });
    }
    /// Give each bond without one a slot after the others of its atom, in record order (LAMMPS
    /// appends a new bond to each atom's list, `newton_bond off`).
    pub fn assign_bond_slots(&mut self) {
        if self.bonds.iter().all(|b| b.slots[0] != u32::MAX && b.slots[1] != u32::MAX) {
            return;
        }
        let mut next: std::collections::HashMap<i64, u32> = std::collections::HashMap::new();
        for b in &self.bonds {
            for k in 0..2 {
                if b.slots[k] != u32::MAX {
                    let n = next.entry(b.atoms[k]).or_insert(0);
                    *n = (*n).max(b.slots[k] + 1);
                }
            }
        }
        for b in &mut self.bonds {
            for k in 0..2 {
                if b.slots[k] == u32::MAX {
                    let n = next.entry(b.atoms[k]).or_insert(0);
                    b.slots[k] = *n;
                    *n += 1;
                }
            }
        }
    }

    /// Bond records `recs` leave their atoms' lists, one after the other as LAMMPS' BPM styles
    /// remove a broken bond: the atom's last bond takes the removed one's slot. The records
    /// themselves stay (see [`Topology::remove_bond_records`]).
    pub fn release_bond_slots(&mut self, recs: &[usize]) {
        // sorted, so the scan over every record below finds an atom with a short search
        let mut involved: Vec<i64> = recs.iter().flat_map(|&k| self.bonds[k].atoms).collect();
        involved.sort_unstable();
        involved.dedup();
        let (Some(&lo), Some(&hi)) = (involved.first(), involved.last()) else { return };
        // each involved atom's (slot, record, side) of its live bonds
        let mut lists: Vec<Vec<(u32, usize, usize)>> = vec![vec![]; involved.len()];
        for (k, b) in self.bonds.iter().enumerate() {
            for side in 0..2 {
                let t = b.atoms[side];
                if (lo..=hi).contains(&t) {
                    if let Ok(x) = involved.binary_search(&t) {
                        lists[x].push((b.slots[side], k, side));
                    }
                }
            }
        }
        let mut removed: std::collections::HashSet<usize> = std::collections::HashSet::new();
        for &k in recs {
            for side in 0..2 {
                let (tag, m) = (self.bonds[k].atoms[side], self.bonds[k].slots[side]);
                let Ok(x) = involved.binary_search(&tag) else { continue };
                let list = &mut lists[x];
                list.retain(|&(_, r, _)| !removed.contains(&r));
                if let Some(&(_, last, lside)) = list.iter().filter(|e| e.1 != k).max_by_key(|e| e.0) {
                    if self.bonds[last].slots[lside] > m {
                        self.bonds[last].slots[lside] = m;
                        for e in list.iter_mut().filter(|e| e.1 == last && e.2 == lside) {
                            e.0 = m;
                        }
                    }
                }
            }
            removed.insert(k);
        }
    }

    pub fn is_empty(&self) -> bool {
        self.bonds.is_empty() && self.angles.is_empty() && self.dihedrals.is_empty()
    }
}
