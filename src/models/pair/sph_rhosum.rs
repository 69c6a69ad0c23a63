//! `pair_style sph/rhosum N` — SPH density by summation every N steps (LAMMPS SPH package),
//! `pair_coeff I J h`: rho_i = m_i W(0) + sum_j m_j W_ij with LAMMPS' quartic kernel
//! W = K (1 - r^2/h^2)^4, K = 2.1541870227086614782/h^3 (3D), 1.5915494309189533576/h^2 (2D).
//! It runs on the setup step too (when step % N == 0); N = 0 never runs. Under hybrid/overlay
//! only atoms of types with rhosum coefficients are summed, over neighbours of those types.

use super::sph::PairTable;
use super::{compute_scalar, PairInput, PairModify, PairOutput, PairStyle, ScalarKernel, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style sph/rhosum N";
pub const COEFF_SYNTAX: &str = "pair_coeff I J h";

pub struct SphRhoSum {
    every: i64,
    /// h per pair
    pairs: PairTable<f64>,
    cutsq: Vec<f64>,
    n: usize,
}

impl SphRhoSum {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let every = a.i64_in("N (steps between density summations)", 0, i64::MAX)?;
        a.finish()?;
        Ok(SphRhoSum { every, pairs: PairTable::empty(), cutsq: vec![], n: 0 })
    }
}

/// The pair term m_j W_ij of i's sum (and m_i W_ij of j's), in LAMMPS' arithmetic.
impl ScalarKernel for SphRhoSum {
    fn cutsq(&self) -> &[f64] {
        &self.cutsq
    }
    fn eval(&self, input: &PairInput, ti: usize, tj: usize, rsq: f64) -> (f64, f64) {
        let h = *self.pairs.get(ti, tj);
        let ih = 1.0 / h;
        let ihsq = ih * ih;
        let mut wf = 1.0 - rsq * ihsq;
        wf = wf * wf;
        wf = wf * wf;
        wf = if input.dimension == 3 { 2.1541870227086614782 * wf * ihsq * ih } else { 1.5915494309189533576 * wf * ihsq };
        (input.type_mass[tj] * wf, input.type_mass[ti] * wf)
    }
}

impl PairStyle for SphRhoSum {
    fn style(&self) -> &str {
        "sph/rhosum"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = COEFF_SYNTAX;
        let h = args.positive_f64("h (kernel support)")?;
        args.finish()?;
        self.pairs.put_range(ilo, ihi, jlo, jhi, h).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        Ok(())
    }
    fn init_sim(&mut self, setup: &super::PairSetup) -> Result<(), String> {
        super::sph::check_setup(setup, self.style())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.pairs.check_all(ntypes, active, "sph/rhosum")?;
        self.pairs.grow(ntypes)?;
        self.n = ntypes;
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, active, |h| *h)?;
        Ok(())
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.cutsq.get(it * (self.n + 1) + jt).map(|c| c.sqrt()).unwrap_or(0.0)
    }
    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, _input: &PairInput, _out: &mut PairOutput) -> Tally {
        Tally::default()
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn density_pass(&mut self, input: &PairInput, rho: &mut [f64]) -> bool {
        if self.every == 0 || input.step % self.every != 0 {
            return false;
        }
        let a = input.atoms;
        let n = self.n;
        let stride = n + 1;
        let dim3 = input.dimension == 3;
        // atoms of a type with any rhosum pair restart from their self term
        let summed: Vec<bool> = (0..=n).map(|t| t > 0 && (1..=n).any(|u| self.cutsq[t * stride + u] > 0.0)).collect();
        for i in 0..a.nlocal {
            let t = a.typ[i];
            if !summed[t] {
                continue;
            }
            let h = if self.pairs.is_set(t, t) { *self.pairs.get(t, t) } else { 0.0 };
            if h > 0.0 {
                let wf = if dim3 { 2.1541870227086614782 / (h * h * h) } else { 1.5915494309189533576 / (h * h) };
                rho[i] = input.type_mass[t] * wf;
            }
        }
        compute_scalar(self, input, rho);
        true
    }
}
