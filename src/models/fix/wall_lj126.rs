//! The 12-6 Lennard-Jones wall E = 4 eps [(sigma/r)^12 - (sigma/r)^6], shifted to zero at the
//! cutoff: `fix wall/lj126` (wall_flat.rs) and `fix wall/region ... lj126`.

use super::wall_flat::{Params, WallPotential};

pub struct Lj126 {
    coeff: [f64; 4],
    offset: f64,
}

impl Lj126 {
    pub fn new(p: &Params) -> Lj126 {
        let (eps, s) = (p.epsilon, p.sigma);
        let coeff = [48.0 * eps * (p.pow)(s, 12), 24.0 * eps * (p.pow)(s, 6), 4.0 * eps * (p.pow)(s, 12), 4.0 * eps * (p.pow)(s, 6)];
        let r2inv = 1.0 / (p.cutoff * p.cutoff);
        let r6inv = r2inv * r2inv * r2inv;
        let offset = r6inv * (coeff[2] * r6inv - coeff[3]);
        Lj126 { coeff, offset }
    }
}

impl WallPotential for Lj126 {
    fn force_energy(&self, r: f64) -> (f64, f64) {
        let c = &self.coeff;
        let rinv = 1.0 / r;
        let r2inv = rinv * rinv;
        let r6inv = r2inv * r2inv * r2inv;
        (r6inv * (c[0] * r6inv - c[1]) * rinv, r6inv * (c[2] * r6inv - c[3]) - self.offset)
    }
}
