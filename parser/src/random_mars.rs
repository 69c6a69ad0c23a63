//! Marsaglia's RANMAR generator exactly as LAMMPS' `RanMars` computes it (James, Comp. Phys.
//! Comm. 60, 329 (1990)): the same lagged-Fibonacci table built from the seed, the same
//! carry sequence, the same polar Box-Muller. Fix langevin draws its forces from it, so the
//! numbers (and their order) must be LAMMPS'.

/// LAMMPS' `RanMars` generator state.
#[derive(Clone, Debug, PartialEq)]
pub struct RanMars {
    u: [f64; 98],
    i97: usize,
    j97: usize,
    c: f64,
    cd: f64,
    cm: f64,
    save: bool,
    second: f64,
}

/// The seeds LAMMPS accepts (it stops with "Invalid seed" outside).
pub const SEED_RANGE: std::ops::RangeInclusive<i64> = 1..=900_000_000;

impl RanMars {
    /// A generator seeded with `seed` in [`SEED_RANGE`] (callers check user seeds and report
    /// the error at the seed's word).
    pub fn new(seed: i32) -> RanMars {
        assert!(SEED_RANGE.contains(&(seed as i64)), "RanMars seed out of range: {seed}");
        let mut u = [0.0; 98];
        let ij = (seed - 1) / 30082;
        let kl = (seed - 1) - 30082 * ij;
        let mut i = (ij / 177) % 177 + 2;
        let mut j = ij % 177 + 2;
        let mut k = (kl / 169) % 178 + 1;
        let mut l = kl % 169;
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
            save: false,
            second: 0.0,
        };
        // LAMMPS discards one number in the constructor
        r.uniform();
        r
    }

    /// Uniform deviate in [0, 1).
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

    /// Gaussian deviate with zero mean and unit variance (polar Box-Muller; the second value
    /// of each pair is returned by the next call).
    pub fn gaussian(&mut self) -> f64 {
        if self.save {
            self.save = false;
            return self.second;
        }
        let (first, second) = super::random_park::polar_pair(|| self.uniform());
        self.second = second;
        self.save = true;
        first
    }

    /// The generator's state as LAMMPS' RanMars::get_state lists it (u[0..98], i97, j97, c, cd,
    /// cm: 103 numbers; a saved second Gaussian value is not part of it).
    pub fn state(&self) -> Vec<f64> {
        let mut s = self.u.to_vec();
        s.extend([self.i97 as f64, self.j97 as f64, self.c, self.cd, self.cm]);
        s
    }

    /// Restore a [`RanMars::state`] (LAMMPS' set_state: the saved Gaussian value is left as
    /// it is). False, with nothing changed, if `s` is not such a state.
    pub fn set_state(&mut self, s: &[f64]) -> bool {
        let index = |x: f64| (x.fract() == 0.0 && (1.0..=97.0).contains(&x)).then_some(x as usize);
        let (Some(i97), Some(j97)) = (s.get(98).copied().and_then(index), s.get(99).copied().and_then(index)) else { return false };
        if s.len() != 103 {
            return false;
        }
        self.u.copy_from_slice(&s[..98]);
        (self.i97, self.j97, self.c, self.cd, self.cm) = (i97, j97, s[100], s[101], s[102]);
        true
    }

    /// Mark `ntarget` of `n` items at random (LAMMPS' `RanMars::select_subset`, one process):
    /// passes over an active set, each item flipping with probability `thresh`, adding while too
    /// few are marked and removing while too many, until exactly `ntarget` are. An item that
    /// does not flip in a pass leaves the active sets, as in LAMMPS. `ntarget <= n`.
    pub fn select_subset(&mut self, ntarget: usize, n: usize) -> Vec<bool> {
        let mut mark = vec![false; n];
        // the active sets as linked lists through `next` (index 0: unmarked, 1: marked)
        let mut next: Vec<Option<usize>> = (1..=n).map(|k| (k < n).then_some(k)).collect();
        let mut first: [Option<usize>; 2] = [(n > 0).then_some(0), None];
        let mut active = [n, 0];
        let mut nmark = 0usize;
        while nmark != ntarget {
            let add = ntarget > nmark;
            let mode = if add { 0 } else { 1 };
            let want = if add { ntarget - nmark } else { nmark - ntarget };
            let thresh = (1.0 * want as f64 / active[mode] as f64).clamp(0.01, 0.99);
            let mut new_active = [0usize; 2];
            let mut new_first: [Option<usize>; 2] = [None, None];
            let mut new_last: [Option<usize>; 2] = [None, None];
            let mut index = first[mode];
            let mut nflip = 0;
            while let Some(k) = index {
                if self.uniform() < thresh {
                    mark[k] = add;
                    nflip += 1;
                }
                index = next[k];
                let which = mark[k] as usize;
                new_active[which] += 1;
                if new_first[which].is_none() {
                    new_first[which] = Some(k);
                }
                if let Some(l) = new_last[which] {
                    next[l] = Some(k);
                }
                new_last[which] = Some(k);
                next[k] = None;
                active = new_active;
                first = new_first;
            }
            if add { nmark += nflip } else { nmark -= nflip }
        }
        mark
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_deviates_lie_in_the_unit_interval_with_the_right_mean() {
        let mut r = RanMars::new(12345);
        let n = 200_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let x = r.uniform();
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        let mean = sum / n as f64;
        // standard error of the mean is 1/sqrt(12 n) = 6.5e-4
        assert!((mean - 0.5).abs() < 4e-3, "mean {mean}");
    }

    #[test]
    fn different_seeds_give_different_streams_and_equal_seeds_the_same() {
        let (mut a, mut b, mut c) = (RanMars::new(7), RanMars::new(7), RanMars::new(8));
        let (xa, xb, xc) = (a.uniform(), b.uniform(), c.uniform());
        assert_eq!(xa, xb);
        assert_ne!(xa, xc);
    }

    #[test]
    fn every_value_is_a_multiple_of_two_to_the_minus_24() {
        // RANMAR works on 24-bit fractions: the table, the carry and their differences are exact
        let mut r = RanMars::new(4928459);
        for _ in 0..1000 {
            let x = r.uniform() * 16777216.0;
            assert_eq!(x, x.trunc());
        }
    }
}
