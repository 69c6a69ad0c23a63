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
pub fn sum_tallies(parts: &[Tally]) -> Tally {
    let mut t = Tally::default();
    for p in parts {
        t.add(p);
    }
    t
}

