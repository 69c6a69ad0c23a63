//! The 9-3 Lennard-Jones wall E = eps [2/15 (sigma/r)^9 - (sigma/r)^3], shifted to zero at the
//! cutoff: `fix wall/lj93` (wall_flat.rs) and `fix wall/region ... lj93`.

use super::wall_flat::{Params, WallPotential};

pub struct Lj93 {
    coeff: [f64; 4],
    offset: f64,
}

impl Lj93 {
    /// LAMMPS' precompute: the force and energy prefactors and the energy at the cutoff.
    pub fn new(p: &Params) -> Lj93 {
        let (eps, s) = (p.epsilon, p.sigma);
        let coeff = [6.0 / 5.0 * eps * (p.pow)(s, 9), 3.0 * eps * (p.pow)(s, 3), 2.0 / 15.0 * eps * (p.pow)(s, 9), eps * (p.pow)(s, 3)];
        let rinv = 1.0 / p.cutoff;
        let r2inv = rinv * rinv;
        let r4inv = r2inv * r2inv;
        let offset = coeff[2] * r4inv * r4inv * rinv - coeff[3] * r2inv * rinv;
        Lj93 { coeff, offset }
    }
}

impl WallPotential for Lj93 {
    fn force_energy(&self, r: f64) -> (f64, f64) {
        let c = &self.coeff;
        let rinv = 1.0 / r;
        let r2inv = rinv * rinv;
        let r4inv = r2inv * r2inv;
        let r10inv = r4inv * r4inv * r2inv;
        (c[0] * r10inv - c[1] * r4inv, c[2] * r4inv * r4inv * rinv - c[3] * r2inv * rinv - self.offset)
    }
}
