//! `pair_style sph/taitwater/morris [kernel K]` — SPH with the Tait equation of state and Morris'
//! laminar viscosity (LAMMPS SPH package), `pair_coeff I J rho0 c0 mu h` (mu: dynamic viscosity).
//!
//! F_i = -m_i m_j (P_i/rho_i^2 + P_j/rho_j^2) wfd x_ij + 2 mu m_i m_j wfd / (rho_i rho_j) v_ij;
//! de_i = de_j = -(fpair v.x + fvisc |v_ij|^2)/2 (velocities are the estimates `vest`).

use super::sph::{compute_sph, parse_kernel, tait_coeff, tait_p_over_rho2, Kernel, Packed, PairTable, SphContribution, SphKernel, Support, TaitTypes};
use super::{at, PairInput, PairModify, PairOutput, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style sph/taitwater/morris [kernel lucy|cubic|wendland2]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J rho0 c0 mu h";

pub struct SphTaitwaterMorris {
    kernel: Kernel,
    types: TaitTypes,
    /// (mu, h) per pair
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    /// Per type pair: mu and the kernel support.
    derived: Vec<(f64, Support)>,
    n: usize,
    dim3: bool,
}

impl SphTaitwaterMorris {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let kernel = parse_kernel(&mut a)?;
        Ok(SphTaitwaterMorris { kernel, types: TaitTypes::default(), pairs: PairTable::new(0), cutsq: vec![], derived: vec![], n: 0, dim3: true })
    }
}

impl SphKernel for SphTaitwaterMorris {
    /// a = rho, b = the Tait P/rho^2.
    #[inline(always)]
    fn pack(&self, input: &PairInput, i: usize) -> Packed {
        let a = input.atoms;
        let t = a.typ[i];
        let rho0 = self.types.rho0.get(t).copied().unwrap_or(0.0);
        let p = if rho0 == 0.0 { 0.0 } else { tait_p_over_rho2(a.rho[i], rho0, self.types.b[t]) };
        Packed { x: a.x[i], v: a.vest[i], a: a.rho[i], b: p }
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        &self.cutsq[ti * (self.n + 1)..(ti + 1) * (self.n + 1)]
    }
    #[inline(always)]
    fn pair(&self, input: &PairInput, pi: &Packed, pj: &Packed, ti: usize, tj: usize, del: [f64; 3], rsq: f64) -> SphContribution {
        let (mu, sup) = at(&self.derived, ti * (self.n + 1) + tj);
        let wfd = self.kernel.wfd_with(rsq, &sup, self.dim3);
        let (imass, jmass) = (at(input.type_mass, ti), at(input.type_mass, tj));
        let (vi, vj) = (pi.v, pj.v);
        let vel = [vi[0] - vj[0], vi[1] - vj[1], vi[2] - vj[2]];
        let dvdr = del[0] * vel[0] + del[1] * vel[1] + del[2] * vel[2];
        // LAMMPS' order: fvisc = 2 mu / (rho_i rho_j); fvisc *= m_i m_j wfd
        let mut fvisc = 2.0 * mu / (pi.a * pj.a);
        fvisc *= imass * jmass * wfd;
        let fpair = -imass * jmass * (pi.b + pj.b) * wfd;
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
        let s = ntypes + 1;
        self.derived = vec![(0.0, Support::default()); s * s];
        for i in 1..=ntypes {
            for j in 1..=ntypes {
                let (mu, h) = *self.pairs.get(i, j);
                self.derived[i * s + j] = (mu, Support::new(h));
            }
        }
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
