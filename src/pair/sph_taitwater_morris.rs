//! `pair_style sph/taitwater/morris [kernel K]` — SPH with the Tait equation of state and Morris'
//! laminar viscosity (LAMMPS SPH package), `pair_coeff I J rho0 c0 mu h` (mu: dynamic viscosity).
//!
//! F_i = -m_i m_j (P_i/rho_i^2 + P_j/rho_j^2) wfd x_ij + 2 mu m_i m_j wfd / (rho_i rho_j) v_ij;
//! de_i = de_j = -(fpair v.x + fvisc |v_ij|^2)/2 (velocities are the estimates `vest`).

use super::sph::{compute_sph, parse_kernel, tait_coeff, tait_p_over_rho2, Kernel, PairTable, SphContribution, SphKernel, TaitTypes};
use super::{PairInput, PairModify, PairOutput, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style sph/taitwater/morris [kernel lucy|cubic|wendland2]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J rho0 c0 mu h";

pub struct SphTaitwaterMorris {
    kernel: Kernel,
    types: TaitTypes,
    /// (mu, h) per pair
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    n: usize,
    dim3: bool,
}

impl SphTaitwaterMorris {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let kernel = parse_kernel(&mut a)?;
        Ok(SphTaitwaterMorris { kernel, types: TaitTypes::default(), pairs: PairTable::new(0), cutsq: vec![], n: 0, dim3: true })
    }
}

impl SphKernel for SphTaitwaterMorris {
    #[inline(always)]
    fn prepare(&self, input: &PairInput, i: usize) -> f64 {
        let t = input.atoms.typ[i];
        if self.types.rho0.get(t).copied().unwrap_or(0.0) == 0.0 {
            return 0.0;
        }
        tait_p_over_rho2(input.atoms.rho[i], self.types.rho0[t], self.types.b[t])
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        &self.cutsq[ti * (self.n + 1)..(ti + 1) * (self.n + 1)]
    }
    #[inline(always)]
    fn pair(&self, input: &PairInput, i: usize, j: usize, ti: usize, tj: usize, fi: f64, fj: f64, del: [f64; 3], rsq: f64) -> SphContribution {
        let a = input.atoms;
        let (mu, h) = *self.pairs.get(ti, tj);
        let wfd = self.kernel.wfd(rsq, h, self.dim3);
        let (imass, jmass) = (input.type_mass[ti], input.type_mass[tj]);
        let (vi, vj) = (a.vest[i], a.vest[j]);
        let vel = [vi[0] - vj[0], vi[1] - vj[1], vi[2] - vj[2]];
        let dvdr = del[0] * vel[0] + del[1] * vel[1] + del[2] * vel[2];
        // LAMMPS' order: fvisc = 2 mu / (rho_i rho_j); fvisc *= m_i m_j wfd
        let mut fvisc = 2.0 * mu / (a.rho[i] * a.rho[j]);
        fvisc *= imass * jmass * wfd;
        let fpair = -imass * jmass * (fi + fj) * wfd;
        let de = -0.5 * (fpair * dvdr + fvisc * (vel[0] * vel[0] + vel[1] * vel[1] + vel[2] * vel[2]));
        SphContribution {
            f: [del[0] * fpair + vel[0] * fvisc, del[1] * fpair + vel[1] * fvisc, del[2] * fpair + vel[2] * fvisc],
            fpair,
            drho_i: jmass * dvdr * wfd,
            drho_j: imass * dvdr * wfd,
            de_i: de,
            de_j: de,
        }
    }
}

impl PairStyle for SphTaitwaterMorris {
    fn style(&self) -> &str {
        "sph/taitwater/morris"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        tait_coeff(ilo, ihi, jlo, jhi, args, COEFF_SYNTAX, "mu (dynamic viscosity)", &mut self.types, &mut self.pairs)
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.pairs.check_all(ntypes, active, "sph/taitwater/morris")?;
        self.pairs.grow(ntypes);
        self.types.grow(ntypes);
        self.n = ntypes;
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, active, |p| p.1);
        Ok(())
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.cutsq.get(it * (self.n + 1) + jt).map(|c| c.sqrt()).unwrap_or(0.0)
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        self.dim3 = input.dimension == 3;
        compute_sph(self, input, out)
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        let mut s = format!("sph/taitwater/morris (kernel {})", self.kernel.name());
        for i in 1..=self.n {
            s += &format!("\n    type {i}: rho0 {} c0 {}", self.types.rho0[i], self.types.c0[i]);
        }
        s
    }
    fn sph_info(&self) -> Option<super::SphInfo> {
        Some(super::SphInfo::from_tait(&self.types, &self.pairs, self.n, Some(())))
    }
}
