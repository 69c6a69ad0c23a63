//! The harmonic wall E = eps (rc - r)^2 for r < rc (sigma is read and unused, as LAMMPS):
//! `fix wall/harmonic` (wall_flat.rs) and `fix wall/region ... harmonic`.

use super::wall_flat::{Params, WallPotential};

pub struct Harmonic {
    epsilon: f64,
    cutoff: f64,
}

impl Harmonic {
    pub fn new(p: &Params) -> Harmonic {
        Harmonic { epsilon: p.epsilon, cutoff: p.cutoff }
    }
}

impl WallPotential for Harmonic {
    fn force_energy(&self, r: f64) -> (f64, f64) {
        let dr = self.cutoff - r;
        (2.0 * self.epsilon * dr, self.epsilon * dr * dr)
    }
}
