//! `pair_style sph/lj [kernel K]` — SPH for a Lennard-Jones fluid (LAMMPS SPH package),
//! `pair_coeff I J alpha h`: the pressure and sound speed of Ree's equation of state (F. H. Ree,
//! J. Chem. Phys. 73, 5401 (1980)) at the particle's density and temperature T = esph/cv, a
//! long-range correction for the LJ cutoff h, lrc = -11.1701 (h^-9 - 1.5 h^-3), added to each
//! P/rho^2, and Monaghan's viscosity with the EOS sound speeds:
//! F_i = -m_i m_j (P_i/rho_i^2 + P_j/rho_j^2 + 2 lrc + Pi) wfd x_ij; drho, desph as sph/idealgas.
//!
//! LAMMPS adds lrc to P_i/rho_i^2 once more for every neighbour of i in its half list (the sum
//! grows along the list), so its forces depend on the list order; dmhs adds it once per pair
//! (docs/commands.md, SPH).

use super::sph::{compute_sph, lanes, parse_kernel, Batch, Packed, PerTypePair, SphContribution, SphKernel, Support, ViscousPairs, L};
use super::{PairInput, PairModify, PairOutput, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style sph/lj [kernel lucy|cubic|wendland2]";

pub struct SphLj {
    pairs: ViscousPairs,
    /// lrc per type pair
    lrc: PerTypePair<f64>,
    /// Per particle (owned, then ghosts) of the current pass: P/rho^2 and the sound speed.
    eos: Vec<(f64, f64)>,
}

impl SphLj {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        Ok(SphLj { pairs: ViscousPairs::new(parse_kernel(&mut a)?), lrc: PerTypePair::default(), eos: vec![] })
    }
}

/// Ree's LJ equation of state, LAMMPS' `LJEOS2` in its order of operations: pressure and sound
/// speed (0 where c^2 <= 0) at density rho and temperature e/cv.
pub fn ljeos2(rho: f64, e: f64, cv: f64) -> (f64, f64) {
    let t = e / cv;
    let beta = 1.0 / t;
    let beta_sqrt = beta.sqrt();
    let x = rho * beta_sqrt.sqrt();
    let xsq = x * x;
    let xpow3 = xsq * x;
    let xpow4 = xsq * xsq;
    // d(A/NkT)/dx and d2(A/NkT)/dx2 of the Helmholtz free energy
    let da = 3.629 + 7.264 * x - beta * (3.492 - 18.698 * x + 35.505 * xsq - 31.816 * xpow3 + 11.195 * xpow4) - beta_sqrt * (5.369 + 13.16 * x + 18.525 * xsq - 17.076 * xpow3 + 9.32 * xpow4)
        + 10.4925 * xsq
        + 11.46 * xpow3
        + 2.176 * xpow4 * xpow4 * x;
    let d2a = 7.264 + 20.985 * x + beta * (18.698 - 71.01 * x + 95.448 * xsq - 44.78 * xpow3) - beta_sqrt * (13.16 + 37.05 * x - 51.228 * xsq + 37.28 * xpow3) + 34.38 * xsq + 19.584 * xpow4 * xpow4;
    let p = rho * t * (1.0 + da * x);
    let csq = t * (1.0 + 2.0 * da * x + d2a * x * x);
    (p, if csq > 0.0 { csq.sqrt() } else { 0.0 })
}

/// The long-range correction to P/rho^2 for an LJ fluid cut at h, in LAMMPS' arithmetic.
fn lrc(s: &Support) -> f64 {
    let ihcub = s.ihsq * s.ih;
    -11.1701 * (ihcub * ihcub * ihcub - 1.5 * ihcub)
}

impl SphKernel for SphLj {
    /// a = rho, b = P/rho^2 (of [`PairStyle::compute`]'s EOS pass).
    #[inline(always)]
    fn pack(&self, input: &PairInput, i: usize) -> Packed {
        let a = input.atoms;
        Packed { x: a.x[i], v: a.vest[i], a: a.rho[i], b: self.eos[i].0 }
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        self.pairs.cutsq_row(ti)
    }
    #[inline(always)]
    fn pair_lanes<const D: usize>(&self, input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>) -> SphContribution<D> {
        let lrc = L(self.lrc.batch(ti, &b.tj));
        let (ci, cj) = (self.eos[b.i].1, lanes(|l| self.eos[b.j[l]].1));
        self.pairs.pair(input, pi, ti, b, pi.b + lrc, b.b + lrc, ci + cj)
    }
}

impl PairStyle for SphLj {
    fn style(&self) -> &str {
        "sph/lj"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.pairs.coeff(ilo, ihi, jlo, jhi, args)
    }
    fn init_sim(&mut self, setup: &super::PairSetup) -> Result<(), String> {
        super::sph::check_setup(setup, self.style())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.pairs.init(ntypes, active, "sph/lj")?;
        let pairs = &self.pairs;
        self.lrc = PerTypePair::new(ntypes, |i, j| if i == 0 || j == 0 { 0.0 } else { lrc(&pairs.support(i, j)) })?;
        Ok(())
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.pairs.cutoff(it, jt)
    }
    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        self.pairs.dim3 = input.dimension == 3;
        // the EOS once per particle (LAMMPS evaluates it again for every pair, with the same bits)
        let a = input.atoms;
        self.eos.clear();
        self.eos.extend((0..a.nall()).map(|i| {
            let (p, c) = ljeos2(a.rho[i], a.esph[i], a.cv[i]);
            (p / (a.rho[i] * a.rho[i]), c)
        }));
        compute_sph(self, input, out)
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        format!("sph/lj (kernel {}, Ree 1980 LJ EOS)", self.pairs.kernel.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ree_eos_is_ideal_in_the_dilute_limit() {
        // rho -> 0: p -> rho T, c^2 -> T
        let (p, c) = ljeos2(1e-9, 2.0, 1.0);
        assert!((p / (1e-9 * 2.0) - 1.0).abs() < 1e-7, "{p}");
        assert!((c * c / 2.0 - 1.0).abs() < 1e-7, "{c}");
    }

    #[test]
    fn lrc_vanishes_where_h6_is_two_thirds() {
        let h = 1.5f64.powf(-1.0 / 6.0);
        assert!(lrc(&Support::new(h)).abs() < 1e-13);
        // h = 2.5: -11.1701 (2.5^-9 - 1.5 2.5^-3)
        let want = -11.1701 * (2.5f64.powi(-9) - 1.5 * 2.5f64.powi(-3));
        assert!((lrc(&Support::new(2.5)) - want).abs() < 1e-14);
    }
}
