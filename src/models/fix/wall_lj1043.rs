//! The 10-4-3 wall of Magda et al.: E = 2 pi eps [2/5 (sigma/r)^10 - (sigma/r)^4 minus
//! sqrt2 sigma^3 / (3 (r + 0.61/sqrt2 sigma)^3)], shifted to zero at the cutoff:
//! `fix wall/lj1043` (wall_flat.rs; it ignores particles behind the wall) and
//! `fix wall/region ... lj1043`.

use super::wall_flat::{Params, WallPotential};
use std::f64::consts::{PI, SQRT_2};

pub struct Lj1043 {
    /// LAMMPS' coeff1..coeff7.
    c: [f64; 7],
    offset: f64,
    /// pow(x, -n): libm's in fix wall/lj1043, powint in fix wall/region.
    pow: fn(f64, i32) -> f64,
}

impl Lj1043 {
    pub fn new(p: &Params) -> Lj1043 {
        let (eps, s, pw) = (p.epsilon, p.sigma, p.pow);
        let two_pi = 2.0 * PI;
        let (c1, c2) = (two_pi * 2.0 / 5.0 * eps * pw(s, 10), two_pi * eps * pw(s, 4));
        let (c3, c4) = (two_pi * SQRT_2 / 3.0 * eps * pw(s, 3), 0.61 / SQRT_2 * s);
        let c = [c1, c2, c3, c4, c1 * 10.0, c2 * 4.0, c3 * 3.0];
        let rinv = 1.0 / p.cutoff;
        let r2inv = rinv * rinv;
        let r4inv = r2inv * r2inv;
        let offset = c1 * r4inv * r4inv * r2inv - c2 * r4inv - c3 * pw(p.cutoff + c4, -3);
        Lj1043 { c, offset, pow: pw }
    }
}

impl WallPotential for Lj1043 {
    fn force_energy(&self, r: f64) -> (f64, f64) {
        let c = &self.c;
        let rinv = 1.0 / r;
        let r2inv = rinv * rinv;
        let r4inv = r2inv * r2inv;
        let r10inv = r4inv * r4inv * r2inv;
        let f = c[4] * r10inv * rinv - c[5] * r4inv * rinv - c[6] * (self.pow)(r + c[3], -4);
        (f, c[0] * r10inv - c[1] * r4inv - c[2] * (self.pow)(r + c[3], -3) - self.offset)
    }
    fn skips_behind(&self) -> bool {
        true
    }
}
