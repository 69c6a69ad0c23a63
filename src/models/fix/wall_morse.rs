//! The Morse wall E = D0 [e^{-2 alpha (r - r0)} - 2 e^{-alpha (r - r0)}], shifted to zero at the
//! cutoff: `fix wall/morse` (wall_flat.rs) and `fix wall/region ... morse`.

use super::wall_flat::{Params, WallPotential};

pub struct Morse {
    d0: f64,
    alpha: f64,
    r0: f64,
    coeff1: f64,
    offset: f64,
}

impl Morse {
    pub fn new(p: &Params) -> Morse {
        let alpha_dr = -p.alpha * (p.cutoff - p.sigma);
        let offset = p.epsilon * ((2.0 * alpha_dr).exp() - 2.0 * alpha_dr.exp());
        Morse { d0: p.epsilon, alpha: p.alpha, r0: p.sigma, coeff1: 2.0 * p.epsilon * p.alpha, offset }
    }
}

impl WallPotential for Morse {
    fn force_energy(&self, r: f64) -> (f64, f64) {
        let dexp = (-self.alpha * (r - self.r0)).exp();
        (self.coeff1 * (dexp * dexp - dexp), self.d0 * (dexp * dexp - 2.0 * dexp) - self.offset)
    }
}
