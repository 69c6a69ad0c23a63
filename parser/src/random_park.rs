//! The Park–Miller minimal-standard generator exactly as LAMMPS' `RanPark` computes it:
//! the same integer recurrence (Schrage's method), the same conversion to a double, the same
//! polar Box–Muller for Gaussians and the same coordinate-hash reseeding, so that
//! `velocity ... create` and `create_atoms ... random` reproduce LAMMPS' numbers bit for bit.

const IA: i32 = 16807;
const IM: i32 = 2147483647;
const IQ: i32 = 127773;
const IR: i32 = 2836;

/// LAMMPS' `RanPark` generator state.
#[derive(Clone, Debug, PartialEq)]
pub struct RanPark {
    seed: i32,
    /// A second Gaussian is kept from the last polar pair.
    save: bool,
    second: f64,
}

impl RanPark {
    /// A generator with `seed`, which must be positive (callers check user seeds and report
    /// the error at the seed's word; a non-positive seed here is a programming error).
    pub fn new(seed: i32) -> RanPark {
        assert!(seed > 0, "RanPark seed must be positive, got {seed}");
        RanPark { seed, save: false, second: 0.0 }
    }

    /// Uniform deviate in (0, 1): one step of `seed = 16807 * seed mod (2^31 - 1)`.
    pub fn uniform(&mut self) -> f64 {
        let k = self.seed / IQ;
        self.seed = IA * (self.seed - k * IQ) - IR * k;
        if self.seed < 0 {
            self.seed += IM;
        }
        // LAMMPS multiplies by the constant 1/IM (not a division by IM).
        (1.0 / IM as f64) * self.seed as f64
    }

    /// Gaussian deviate with zero mean and unit variance (polar Box–Muller; the second
    /// value of each pair is returned by the next call).
    pub fn gaussian(&mut self) -> f64 {
        if self.save {
            self.save = false;
            return self.second;
        }
        let (first, second) = polar_pair(|| self.uniform());
        self.second = second;
        self.save = true;
        first
    }

    /// Restart the sequence from `seed` (positive).
    pub fn reset(&mut self, seed: i32) {
        assert!(seed > 0, "RanPark seed must be positive, got {seed}");
        self.seed = seed;
        self.save = false;
    }

    /// Reseed from a base seed and a position (LAMMPS `RanPark::reset(int, double*)`): a
    /// Jenkins one-at-a-time hash over the bytes of the int and the three doubles, then five
    /// warm-up draws. This is what makes `velocity ... loop geom` independent of atom order.
    pub fn reset_coord(&mut self, ibase: i32, coord: [f64; 3]) {
        let mut hash: u32 = 0;
        // LAMMPS reads the bytes through a (signed) `char *`, so bytes >= 128 enter the
        // sum sign-extended; the native (little-endian) byte order is used as in memory.
        let mut mix = |b: u8| {
            hash = hash.wrapping_add(b as i8 as i32 as u32);
            hash = hash.wrapping_add(hash << 10);
            hash ^= hash >> 6;
        };
        for b in ibase.to_ne_bytes() {
            mix(b);
        }
        for c in coord {
            for b in c.to_ne_bytes() {
                mix(b);
            }
        }
        hash = hash.wrapping_add(hash << 3);
        hash ^= hash >> 11;
        hash = hash.wrapping_add(hash << 15);
        // LAMMPS keeps 27 bits (mask 0x7ffffff) although its comment says 31.
        self.seed = (hash & 0x7ffffff) as i32;
        if self.seed == 0 {
            self.seed = 1;
        }
        for _ in 0..5 {
            self.uniform();
        }
        self.save = false;
    }

    /// The current integer state (LAMMPS `RanPark::state`).
    pub fn state(&self) -> i32 {
        self.seed
    }
}

/// Two Gaussian deviates from uniform ones by LAMMPS' polar Box-Muller (RanPark and RanMars
/// alike): the first is returned at once, the second by the next call.
pub fn polar_pair(mut uniform: impl FnMut() -> f64) -> (f64, f64) {
    let (v1, v2, rsq) = loop {
        let v1 = 2.0 * uniform() - 1.0;
        let v2 = 2.0 * uniform() - 1.0;
        let rsq = v1 * v1 + v2 * v2;
        if rsq < 1.0 && rsq != 0.0 {
            break (v1, v2, rsq);
        }
    };
    let fac = (-2.0 * rsq.ln() / rsq).sqrt();
    (v2 * fac, v1 * fac)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimal_standard_check_value() {
        // Park & Miller's published check: seed 1 gives 1043618065 after 10000 draws.
        let mut r = RanPark::new(1);
        for _ in 0..10000 {
            r.uniform();
        }
        assert_eq!(r.state(), 1043618065);
    }

    #[test]
    fn first_uniforms_match_lammps() {
        // seed 12345: first states 207482415, 1790989824, ...
        let mut r = RanPark::new(12345);
        assert_eq!(r.uniform(), 207482415.0 * (1.0 / 2147483647.0));
        assert_eq!(r.state(), 207482415);
        r.uniform();
        assert_eq!(r.state(), 1790989824);
    }

    #[test]
    fn gaussian_pairs_are_returned_in_order() {
        let mut a = RanPark::new(987);
        let g1 = a.gaussian();
        let g2 = a.gaussian();
        let mut b = RanPark::new(987);
        let (v1, v2, rsq) = loop {
            let (v1, v2) = (2.0 * b.uniform() - 1.0, 2.0 * b.uniform() - 1.0);
            let rsq: f64 = v1 * v1 + v2 * v2;
            if rsq < 1.0 && rsq != 0.0 {
                break (v1, v2, rsq);
            }
        };
        let fac = (-2.0 * rsq.ln() / rsq).sqrt();
        assert_eq!(g1, v2 * fac);
        assert_eq!(g2, v1 * fac);
    }
}
