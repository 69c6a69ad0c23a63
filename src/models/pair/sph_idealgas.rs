//! `pair_style sph/idealgas [kernel K]` — SPH for an ideal gas with gamma = 1.4 and Monaghan's
//! artificial viscosity (LAMMPS SPH package), `pair_coeff I J alpha h`.
//!
//! P = (gamma - 1) rho e with e = esph/m the specific internal energy, so P/rho^2 = 0.4 esph/m/rho
//! and the sound speed c = sqrt(0.4 esph/m) (LAMMPS' expression, without the factor gamma).
//! For a pair with v_ij . x_ij < 0: mu = h v.x/(r^2 + 0.01 h^2),
//! Pi = -alpha (c_i + c_j) mu / (rho_i + rho_j); F_i = -m_i m_j (P_i/rho_i^2 + P_j/rho_j^2 + Pi) wfd x_ij;
//! drho_i = m_j v.x wfd; de_i = de_j = -F.v/2 (velocities are the estimates `vest`).

use super::sph::{compute_sph, parse_kernel, Batch, Packed, SphContribution, SphKernel, ViscousPairs, L};
use super::{PairInput, PairModify, PairOutput, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style sph/idealgas [kernel lucy|cubic|wendland2]";

pub struct SphIdealGas {
    pairs: ViscousPairs,
}

impl SphIdealGas {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        Ok(SphIdealGas { pairs: ViscousPairs::new(parse_kernel(&mut a)?) })
    }
}

/// 0.4 esph/m: (gamma - 1) times the specific internal energy, in LAMMPS' order. P/rho^2 is this
/// over rho and the sound speed its square root, both the bits of LAMMPS' expressions.
#[inline(always)]
fn pv_per_rho(esph: f64, m: f64) -> f64 {
    0.4 * esph / m
}

impl SphKernel for SphIdealGas {
    /// a = rho, b = 0.4 esph/m.
    #[inline(always)]
    fn pack(&self, input: &PairInput, i: usize) -> Packed {
        let a = input.atoms;
        Packed { x: a.x[i], v: a.vest[i], a: a.rho[i], b: pv_per_rho(a.esph[i], input.type_mass[a.typ[i]]) }
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        self.pairs.cutsq_row(ti)
    }
    #[inline(always)]
    fn pair_lanes<const D: usize>(&self, input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>) -> SphContribution<D> {
        // LAMMPS: fi = 0.4*esph/m/rho, ci = sqrt(0.4*esph/m), the same for j
        let (fi, ci) = (L::splat(pi.b / pi.a), L::splat(pi.b.sqrt()));
        let (fj, cj) = (b.b / b.a, b.b.sqrt());
        self.pairs.pair(input, pi, ti, b, fi, fj, ci + cj)
    }
}

impl PairStyle for SphIdealGas {
    fn style(&self) -> &str {
        "sph/idealgas"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.pairs.coeff(ilo, ihi, jlo, jhi, args)
    }
    fn init_sim(&mut self, setup: &super::PairSetup) -> Result<(), String> {
        super::sph::check_setup(setup, self.style())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.pairs.init(ntypes, active, "sph/idealgas")
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.pairs.cutoff(it, jt)
    }
    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        self.pairs.dim3 = input.dimension == 3;
        compute_sph(self, input, out)
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        format!("sph/idealgas (kernel {}, gamma 1.4)", self.pairs.kernel.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eos_is_the_ideal_gas_with_gamma_1_4() {
        // the shock tube's left state: rho = 1, m = 1, esph = 2.5 gives p = 1
        let t = pv_per_rho(2.5, 1.0);
        let (rho, p_over_rho2) = (1.0, t / 1.0);
        assert!((p_over_rho2 * rho * rho - 1.0).abs() < 1e-15);
        // right state: rho = 0.25, m = 0.25, esph = 0.625 gives p = 0.4 * 0.25 * 2.5 = 0.25
        let t = pv_per_rho(0.625, 0.25);
        assert!((t / 0.25 * 0.25 * 0.25 - 0.25).abs() < 1e-15);
    }
}
