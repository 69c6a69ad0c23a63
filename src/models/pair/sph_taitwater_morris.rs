//! `pair_style sph/taitwater/morris [kernel K]` — SPH with the Tait equation of state and Morris'
//! laminar viscosity (LAMMPS SPH package), `pair_coeff I J rho0 c0 mu h` (mu: dynamic viscosity).
//!
//! F_i = -m_i m_j (P_i/rho_i^2 + P_j/rho_j^2) wfd x_ij + 2 mu m_i m_j wfd / (rho_i rho_j) v_ij;
//! de_i = de_j = -(fpair v.x + fvisc |v_ij|^2)/2 (velocities are the estimates `vest`).

use super::sph::{compute_sph, lanes, parse_tait_options, tait_coeff, tait_pack, tait_pack_lanes, dot_lanes, Batch, Kernel, L, Packed, PairTable, SphContribution, SphKernel, Support, SupportLanes, PerTypePair, TaitTypes, LANES};
use super::{PairInput, PairModify, PairOutput, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style sph/taitwater/morris [kernel lucy|cubic|wendland2] [pmin P]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J rho0 c0 mu h";

pub struct SphTaitwaterMorris {
    kernel: Kernel,
    /// `pmin P` (dmhs extension): lowest pressure
    pmin: Option<f64>,
    types: TaitTypes,
    /// (mu, h) per pair
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    /// Per type pair: mu and the kernel support.
    derived: PerTypePair<(f64, Support)>,
    n: usize,
    dim3: bool,
}

impl SphTaitwaterMorris {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let (kernel, pmin) = parse_tait_options(&mut a)?;
        Ok(SphTaitwaterMorris { kernel, pmin, types: TaitTypes::default(), pairs: PairTable::empty(), cutsq: vec![], derived: PerTypePair::default(), n: 0, dim3: true })
    }
    /// The dimension, for styles that evaluate this one pair by pair (dmhs/blend).
    pub fn set_dim3(&mut self, dim3: bool) {
        self.dim3 = dim3;
    }
}

impl SphKernel for SphTaitwaterMorris {
    /// The viscous force is along v_ij.
    const CENTRAL: bool = false;
    /// a = rho, b = the Tait P/rho^2.
    #[inline(always)]
    fn pack(&self, input: &PairInput, i: usize) -> Packed {
        tait_pack(&self.types, self.pmin, input, i)
    }
    #[inline(always)]
    fn pack_lanes(&self, input: &PairInput, i0: usize, each: impl FnMut(usize, &Packed)) {
        tait_pack_lanes(&self.types, self.pmin, input, i0, each)
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        &self.cutsq[ti * (self.n + 1)..(ti + 1) * (self.n + 1)]
    }
    #[inline(always)]
    fn pair_lanes<const D: usize>(&self, input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>) -> SphContribution<D> {
        let d: [(f64, Support); LANES] = self.derived.batch(ti, &b.tj);
        let sup = SupportLanes::gather(|l| d[l].1);
        let mu = lanes(|l| d[l].0);
        let del = &b.del;
        let wfd = self.kernel.wfd_lanes(&b.r, &sup, self.dim3);
        let imass = input.type_mass[ti];
        let jmass = b.m;
        let vi = pi.v;
        let vel: [L; D] = std::array::from_fn(|k| vi[k] - b.v[k]);
        let dvdr = dot_lanes(del, &vel);
        // LAMMPS' order: fvisc = 2 mu / (rho_i rho_j); fvisc *= m_i m_j wfd
        let fvisc = 2.0 * mu / (pi.a * b.a);
        let fvisc = fvisc * (imass * jmass * wfd);
        let fpair = -imass * jmass * (pi.b + b.b) * wfd;
        let vsq = dot_lanes(&vel, &vel);
        let de = -0.5 * (fpair * dvdr + fvisc * vsq);
        SphContribution {
            f: std::array::from_fn(|k| del[k] * fpair + vel[k] * fvisc),
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
    fn init_sim(&mut self, setup: &super::PairSetup) -> Result<(), String> {
        super::sph::check_setup(setup, self.style())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.pairs.check_all(ntypes, active, "sph/taitwater/morris")?;
        self.pairs.grow(ntypes)?;
        self.types.grow(ntypes);
        self.n = ntypes;
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, active, |p| p.1)?;
        let pairs = &self.pairs;
        self.derived = PerTypePair::new(ntypes, |i, j| {
            if i == 0 || j == 0 {
                return (0.0, Support::default());
            }
            let (mu, h) = *pairs.get(i, j);
            (mu, Support::new(h))
        })?;
        Ok(())
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.cutsq.get(it * (self.n + 1) + jt).map(|c| c.sqrt()).unwrap_or(0.0)
    }
    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        self.dim3 = input.dimension == 3;
        compute_sph(self, input, out)
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        let mut s = format!("sph/taitwater/morris (kernel {}{})", self.kernel.name(), self.pmin.map(|p| format!(", pmin {p}")).unwrap_or_default());
        for i in 1..=self.n {
            s += &format!("\n    type {i}: rho0 {} c0 {}", self.types.rho0[i], self.types.c0[i]);
        }
        s
    }
    fn sph_info(&self) -> Option<super::SphInfo> {
        Some(super::SphInfo::from_tait(&self.types, &self.pairs, self.n, Some(())))
    }
}
