//! LAMMPS' Marsaglia generator (`RanMars`, RANMAR of F. James, Comp. Phys. Comm. 60, 329
//! (1990)): the stream LAMMPS uses per processor (seeded `seed + rank`) for molecule
//! orientations, thermostat noise and the like. Same seed, same numbers, bit for bit.

pub struct RanMars {
    u: [f64; 98],
    i97: usize,
    j97: usize,
    c: f64,
    cd: f64,
    cm: f64,
    /// The second number of the last Gaussian pair, when not used yet.
    second: Option<f64>,
}

impl RanMars {
    /// The largest seed LAMMPS accepts.
    pub const MAX_SEED: i64 = 900_000_000;

    /// A generator for `seed` in 1..=900000000 (`Err` with LAMMPS' message otherwise).
    pub fn new(seed: i64) -> Result<RanMars, String> {
        if seed <= 0 || seed > Self::MAX_SEED {
            return Err(format!("invalid seed {seed} for the Marsaglia random number generator (expected 1 to {})", Self::MAX_SEED));
        }
        let seed = seed as i32;
        let ij = (seed - 1) / 30082;
        let kl = (seed - 1) - 30082 * ij;
        let mut i = (ij / 177) % 177 + 2;
        let mut j = ij % 177 + 2;
        let mut k = (kl / 169) % 178 + 1;
        let mut l = kl % 169;
        let mut u = [0.0; 98];
        for slot in u.iter_mut().skip(1) {
            let mut s = 0.0;
            let mut t = 0.5;
            for _ in 0..24 {
                let m = ((i * j) % 179) * k % 179;
                i = j;
                j = k;
                k = m;
                l = (53 * l + 1) % 169;
                if (l * m) % 64 >= 32 {
                    s += t;
                }
                t *= 0.5;
            }
            *slot = s;
        }
        let mut r = RanMars {
            u,
            i97: 97,
            j97: 33,
            c: 362436.0 / 16777216.0,
            cd: 7654321.0 / 16777216.0,
            cm: 16777213.0 / 16777216.0,
            second: None,
        };
        r.uniform();
        Ok(r)
    }

    /// A number in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        let mut uni = self.u[self.i97] - self.u[self.j97];
        if uni < 0.0 {
            uni += 1.0;
        }
        self.u[self.i97] = uni;
        self.i97 -= 1;
        if self.i97 == 0 {
            self.i97 = 97;
        }
        self.j97 -= 1;
        if self.j97 == 0 {
            self.j97 = 97;
        }
        self.c -= self.cd;
        if self.c < 0.0 {
            self.c += self.cm;
        }
        uni -= self.c;
        if uni < 0.0 {
            uni += 1.0;
        }
        uni
    }

    /// A standard normal number (polar Box-Muller; the pair's second number is kept for the
    /// next call, as LAMMPS does).
    pub fn gaussian(&mut self) -> f64 {
        if let Some(s) = self.second.take() {
            return s;
        }
        loop {
            let v1 = 2.0 * self.uniform() - 1.0;
            let v2 = 2.0 * self.uniform() - 1.0;
            let rsq = v1 * v1 + v2 * v2;
            if rsq < 1.0 && rsq != 0.0 {
                let fac = (-2.0 * rsq.ln() / rsq).sqrt();
                self.second = Some(v1 * fac);
                return v2 * fac;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_out_of_range_are_refused() {
        assert!(RanMars::new(0).is_err());
        assert!(RanMars::new(900_000_001).is_err());
        assert!(RanMars::new(900_000_000).is_ok());
    }

    #[test]
    fn uniform_numbers_are_in_the_unit_interval_and_average_one_half() {
        let mut r = RanMars::new(12345).unwrap();
        let n = 100_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let x = r.uniform();
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        // standard error of the mean: 1/sqrt(12 n) = 9.1e-4
        assert!((sum / n as f64 - 0.5).abs() < 5e-3);
    }
}
