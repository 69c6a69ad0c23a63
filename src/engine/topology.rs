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
}

/// Values of [`Bond::history`] (LAMMPS' largest `nhistory` of a BPM style, bpm/rotational's).
pub const BOND_HISTORY: usize = 4;

impl Bond {
    pub fn new(typ: usize, atoms: [i64; 2]) -> Bond {
        Bond { typ, atoms, history: [0.0; BOND_HISTORY] }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Angle {
    pub typ: usize,
    pub atoms: [i64; 3],
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dihedral {
    pub typ: usize,
    pub atoms: [i64; 4],
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
    pub fn is_empty(&self) -> bool {
        self.bonds.is_empty() && self.angles.is_empty() && self.dihedrals.is_empty()
    }
}
