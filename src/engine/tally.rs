//! Energy and virial tallies of a force evaluation.

/// Energies and virial from one force evaluation (only filled when asked for).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    pub evdwl: f64,
    pub ecoul: f64,
    /// xx, yy, zz, xy, xz, yz
    pub virial: [f64; 6],
}

impl Tally {
    /// A central pair force `fpair (x_i - x_j)` with energy `e`, weighted `w` (1 for an owned
    /// partner, 1/2 for a ghost, which the other side lists too): LAMMPS' `ev_tally`.
    #[inline(always)]
    pub fn central(&mut self, w: f64, e: f64, del: [f64; 3], fpair: f64) {
        self.evdwl += w * e;
        self.virial[0] += w * del[0] * del[0] * fpair;
        self.virial[1] += w * del[1] * del[1] * fpair;
        self.virial[2] += w * del[2] * del[2] * fpair;
        self.virial[3] += w * del[0] * del[1] * fpair;
        self.virial[4] += w * del[0] * del[2] * fpair;
        self.virial[5] += w * del[1] * del[2] * fpair;
    }
    /// The virial of a pair force `f` on i (any direction), weighted as in [`Tally::central`]:
    /// LAMMPS' `ev_tally_xyz`.
    #[inline(always)]
    pub fn xyz(&mut self, w: f64, del: [f64; 3], f: [f64; 3]) {
        self.virial[0] += w * del[0] * f[0];
        self.virial[1] += w * del[1] * f[1];
        self.virial[2] += w * del[2] * f[2];
        self.virial[3] += w * del[0] * f[1];
        self.virial[4] += w * del[0] * f[2];
        self.virial[5] += w * del[1] * f[2];
    }
    pub fn add(&mut self, o: &Tally) {
        self.evdwl += o.evdwl;
        self.ecoul += o.ecoul;
        for k in 0..6 {
            self.virial[k] += o.virial[k];
        }
    }
}

/// Sum tallies in chunk order (deterministic).
pub fn sum_tallies<'a>(parts: impl IntoIterator<Item = &'a Tally>) -> Tally {
    let mut t = Tally::default();
    for p in parts {
        t.add(p);
    }
    t
}


/// Per-atom energies and virials of one force evaluation (LAMMPS' eatom and vatom), by source:
/// made only on steps that tally energies, and only when a compute pe/atom or stress/atom
/// exists. Every value belongs to an owned atom: a pair with a ghost is listed from both
/// sides, so each owner takes its half itself (LAMMPS takes it by reverse communication).
#[derive(Clone, Debug, Default)]
pub struct PerAtomTally {
    /// The step they belong to.
    pub step: i64,
    /// Energies: pair, bond, angle, dihedral.
    pub energy: [Vec<f64>; 4],
    /// Virials (xx, yy, zz, xy, xz, yz): pair, bond, angle, dihedral.
    pub virial: [Vec<[f64; 6]>; 4],
}

impl PerAtomTally {
    pub const PAIR: usize = 0;
    pub const BOND: usize = 1;
    pub const ANGLE: usize = 2;
    pub const DIHEDRAL: usize = 3;

    /// Zero tallies for `n` owned atoms at `step`.
    pub fn new(n: usize, step: i64) -> PerAtomTally {
        PerAtomTally { step, energy: std::array::from_fn(|_| vec![0.0; n]), virial: std::array::from_fn(|_| vec![[0.0; 6]; n]) }
    }

    /// Values per atom in [`PerAtomTally::flat`]: each source's energy and six virials.
    pub const WIDTH: usize = 28;

    /// The tallies atom by atom, each source's energy then its virial (to send to other ranks).
    pub fn flat(&self) -> Vec<f64> {
        let n = self.energy[0].len();
        let mut out = Vec::with_capacity(n * Self::WIDTH);
        for i in 0..n {
            for k in 0..4 {
                out.push(self.energy[k][i]);
                out.extend_from_slice(&self.virial[k][i]);
            }
        }
        out
    }

    /// The tallies of [`PerAtomTally::flat`] values.
    pub fn from_flat(step: i64, flat: &[f64]) -> PerAtomTally {
        let mut t = PerAtomTally::new(flat.len() / Self::WIDTH, step);
        for (i, atom) in flat.chunks_exact(Self::WIDTH).enumerate() {
            for (k, v) in atom.chunks_exact(7).enumerate() {
                t.add(k, i, 1.0, v[0], &[v[1], v[2], v[3], v[4], v[5], v[6]]);
            }
        }
        t
    }

    /// Add a share `w` of energy `e` and virial `v` to atom `i` of source `k`.
    #[inline]
    pub fn add(&mut self, k: usize, i: usize, w: f64, e: f64, v: &[f64; 6]) {
        self.energy[k][i] += w * e;
        let va = &mut self.virial[k][i];
        for m in 0..6 {
            va[m] += w * v[m];
        }
    }
}

/// One pair's energy and virial as a force loop that tallies per atom in its own pass records
/// them (loops with contact histories cannot evaluate a pair twice): atom `i` is owned, `j`
/// takes its half only when owned.
#[derive(Clone, Copy, Debug)]
pub struct PairShare {
    pub i: usize,
    pub j: usize,
    pub e: f64,
    pub v: [f64; 6],
}

impl PairShare {
    /// A central force `fpair (x_i - x_j)` (LAMMPS' `ev_tally`).
    #[inline]
    pub fn central(i: usize, j: usize, e: f64, del: [f64; 3], fpair: f64) -> PairShare {
        PairShare { i, j, e, v: [del[0] * del[0] * fpair, del[1] * del[1] * fpair, del[2] * del[2] * fpair, del[0] * del[1] * fpair, del[0] * del[2] * fpair, del[1] * del[2] * fpair] }
    }
    /// A force `f` on i in any direction (LAMMPS' `ev_tally_xyz`).
    #[inline]
    pub fn xyz(i: usize, j: usize, e: f64, del: [f64; 3], f: [f64; 3]) -> PairShare {
        PairShare { i, j, e, v: [del[0] * f[0], del[1] * f[1], del[2] * f[2], del[0] * f[1], del[0] * f[2], del[1] * f[2]] }
    }
}

impl PerAtomTally {
    /// Half of each recorded pair to each owned atom, in record order.
    pub fn add_pairs(&mut self, shares: &[PairShare]) {
        let nlocal = self.energy[Self::PAIR].len();
        for s in shares {
            self.add(Self::PAIR, s.i, 0.5, s.e, &s.v);
            if s.j < nlocal {
                self.add(Self::PAIR, s.j, 0.5, s.e, &s.v);
            }
        }
    }
}
