//! The law of `fix ID group temp/csvr Tstart Tstop Tdamp seed` (the fix itself is
//! temp_scale.rs' FixTempScale): the canonical sampling through velocity rescaling thermostat of Bussi, Donadio and Parrinello (2007), as LAMMPS' fix temp/csvr. At the
//! end of every step the group's velocities are scaled by lambda, with lambda^2 drawn so that
//! the kinetic energy K relaxes towards the target over Tdamp with the canonical distribution's
//! noise: with c1 = exp(-dt/Tdamp), c2 = (1 - c1) K_target / K / dof, r1 a Gaussian number and
//! r2 the sum of dof - 1 squared Gaussians (drawn as LAMMPS draws them, from its Marsaglia
//! stream seeded with `seed`), lambda^2 = c1 + c2 (r1^2 + r2) + 2 r1 sqrt(c1 c2).

use crate::engine::random_mars::RanMars;

/// Tdamp and the random stream of one fix temp/csvr.
pub struct Csvr {
    pub period: f64,
    random: RanMars,
}

impl Csvr {
    pub fn new(period: f64, seed: i32) -> Csvr {
        Csvr { period, random: RanMars::new(seed) }
    }
    /// The random stream's state, for restart files (LAMMPS writes it too).
    pub fn random_state(&self) -> Vec<f64> {
        self.random.state()
    }
    pub fn set_random_state(&mut self, s: &[f64]) -> bool {
        self.random.set_state(s)
    }

    /// A Gamma(ia, 1) number (the sum of 2 ia squared Gaussians over 2): a product of uniforms
    /// below 6, else the rejection method of Numerical Recipes, in LAMMPS' order of draws.
    fn gamma(&mut self, ia: i64) -> f64 {
        if ia < 1 {
            return 0.0;
        }
        let r = &mut self.random;
        if ia < 6 {
            let mut x = 1.0;
            for _ in 0..ia {
                x *= r.uniform();
            }
            // -ln of the smallest normal number, where the product underflows
            return if x < 2.2250759805e-308 { 708.4 } else { -x.ln() };
        }
        let am = (ia - 1) as f64;
        let s = (2.0 * am + 1.0).sqrt();
        loop {
            let (v1, y, x) = loop {
                let (v1, v2) = loop {
                    let v1 = r.uniform();
                    let v2 = 2.0 * r.uniform() - 1.0;
                    if v1 * v1 + v2 * v2 <= 1.0 {
                        break (v1, v2);
                    }
                };
                let y = v2 / v1;
                let x = s * y + am;
                if x > 0.0 {
                    break (v1, y, x);
                }
            };
            let lg = am * (x / am).ln() - s * y;
            if lg < -700.0 || v1 < 0.00001 {
                continue;
            }
            let e = (1.0 + y * y) * lg.exp();
            if r.uniform() <= e {
                return x;
            }
        }
    }

    /// The sum of `n` squared Gaussian numbers.
    fn sum_noises(&mut self, n: i64) -> f64 {
        match n {
            n if n <= 0 => 0.0,
            1 => {
                let g = self.random.gaussian();
                g * g
            }
            n if n % 2 == 0 => 2.0 * self.gamma(n / 2),
            n => {
                let g = self.random.gaussian();
                2.0 * self.gamma((n - 1) / 2) + g * g
            }
        }
    }

    /// lambda for kinetic energies `old` -> `new` (LAMMPS' resamplekin).
    pub fn resample(&mut self, dt: f64, old: f64, new: f64, tdof: f64) -> f64 {
        let c1 = (-dt / self.period).exp();
        let c2 = (1.0 - c1) * new / old / tdof;
        let r1 = self.random.gaussian();
        // LAMMPS passes dof - 1 to an int: truncated
        let r2 = self.sum_noises((tdof - 1.0) as i64);
        (c1 + c2 * (r1 * r1 + r2) + 2.0 * r1 * (c1 * c2).sqrt()).sqrt()
    }
}
