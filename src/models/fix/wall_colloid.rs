//! The colloid wall of `fix wall/region ... colloid`: a sphere of radius `rad` (per atom) made of
//! Lennard-Jones material against a flat half-space of it (LAMMPS' FixWallRegion::colloid,
//! integrated 12-6 interaction; Hamaker constant 4 pi^2 eps). The energy is shifted by the
//! point-particle 9-3 value at the cutoff, as LAMMPS does.

use super::wall_flat::powint;

pub struct Colloid {
    coeff: [f64; 4],
    offset: f64,
}

impl Colloid {
    pub fn new(epsilon: f64, sigma: f64, cutoff: f64) -> Colloid {
        let coeff = [-4.0 / 315.0 * epsilon * powint(sigma, 6), -2.0 / 3.0 * epsilon, epsilon * powint(sigma, 6) / 7560.0, epsilon / 6.0];
        let rinv = 1.0 / cutoff;
        let r2inv = rinv * rinv;
        let r4inv = r2inv * r2inv;
        let offset = coeff[2] * r4inv * r4inv * rinv - coeff[3] * r2inv * rinv;
        Colloid { coeff, offset }
    }

    /// Force magnitude and energy for a particle of radius `rad` whose centre is `r` > `rad`
    /// from the wall.
    pub fn force_energy(&self, r: f64, rad: f64) -> (f64, f64) {
        let c = &self.coeff;
        let new_coeff2 = c[1] * rad * rad * rad;
        let diam = 2.0 * rad;
        let rad2 = rad * rad;
        let rad4 = rad2 * rad2;
        let rad8 = rad4 * rad4;
        let delta2 = rad2 - r * r;
        let rinv = 1.0 / delta2;
        let r2inv = rinv * rinv;
        let r4inv = r2inv * r2inv;
        let r8inv = r4inv * r4inv;
        let poly = rad8 * rad + 27.0 * rad4 * rad2 * rad * r * r + 63.0 * rad4 * rad * powint(r, 4) + 21.0 * rad2 * rad * powint(r, 6);
        let fwall = c[0] * poly * r8inv - new_coeff2 * r2inv;
        let r2 = 0.5 * diam - r;
        let rinv2 = 1.0 / r2;
        let r2inv2 = rinv2 * rinv2;
        let r4inv2 = r2inv2 * r2inv2;
        let r3 = r + 0.5 * diam;
        let rinv3 = 1.0 / r3;
        let r2inv3 = rinv3 * rinv3;
        let r4inv3 = r2inv3 * r2inv3;
        let lj = (-3.5 * diam + r) * r4inv2 * r2inv2 * rinv2 + (3.5 * diam + r) * r4inv3 * r2inv3 * rinv3;
        let vdw = (-diam * r + r2 * r3 * ((-r2).ln() - r3.ln())) * (-rinv2) * rinv3;
        (fwall, c[2] * lj - c[3] * vdw - self.offset)
    }
}
