//! `pair_style sph/taitwater [kernel K]` — SPH with the Tait equation of state and Monaghan's
//! artificial viscosity (LAMMPS SPH package), `pair_coeff I J rho0 c0 alpha h`.
//!
//! For a pair with v_ij . x_ij < 0: mu = h v.x/(r^2 + 0.01 h^2),
//! Pi = -alpha (c_i + c_j) mu / (rho_i + rho_j); F_i = -m_i m_j (P_i/rho_i^2 + P_j/rho_j^2 + Pi) wfd x_ij;
//! drho_i = m_j v.x wfd; de_i = de_j = -F.v/2 (velocities are the estimates `vest`).

use super::sph::{compute_sph, lanes, monaghan_lanes, parse_tait_options, tait_coeff, tait_pack, tait_pack_lanes, dot_lanes, Batch, Kernel, L, Packed, PairTable, SphContribution, SphKernel, Support, SupportLanes, PerTypePair, TaitTypes, LANES};
use super::{PairInput, PairModify, PairOutput, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style sph/taitwater [kernel lucy|cubic|wendland2] [pmin P]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J rho0 c0 alpha h";

pub struct SphTaitwater {
    kernel: Kernel,
    /// `pmin P` (dmhs extension): lowest pressure
    pmin: Option<f64>,
    types: TaitTypes,
    /// (alpha, h) per pair
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    /// Per type pair, precomputed with LAMMPS' arithmetic: the support, 0.01 h^2, and
    /// -alpha (c_i + c_j).
    derived: PerTypePair<(Support, f64, f64)>,
    n: usize,
    dim3: bool,
}

impl SphTaitwater {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let (kernel, pmin) = parse_tait_options(&mut a)?;
        Ok(SphTaitwater { kernel, pmin, types: TaitTypes::default(), pairs: PairTable::empty(), cutsq: vec![], derived: PerTypePair::default(), n: 0, dim3: true })
    }
}

impl SphKernel for SphTaitwater {
    /// a = rho, b = the Tait P/rho^2 (computed once per particle; LAMMPS recomputes it per
    /// pair with the same arithmetic).
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
        let d: [(Support, f64, f64); LANES] = self.derived.batch(ti, &b.tj);
        let sup = SupportLanes::gather(|l| d[l].0);
        let (eps, visc_c) = (lanes(|l| d[l].1), lanes(|l| d[l].2));
        let (del, rsq) = (&b.del, &b.rsq);
        let wfd = self.kernel.wfd_lanes(&b.r, &sup, self.dim3);
        let imass = input.type_mass[ti];
        let jmass = b.m;
        let vi = pi.v;
        // Monaghan viscosity for approaching pairs only: computed for all and selected. The same
        // operations in two spellings, chosen by what measured faster (the bits are the same): in
        // 2D whole-vector operations; in 3D lane by lane, where the vector form made the compiler
        // spill (dambreak3d: 19.5e6 stores per step against 12.5e6, and slower)
        let (f, fpair, drho_i, drho_j, de) = if D == 2 {
            let vel: [L; D] = std::array::from_fn(|k| vi[k] - b.v[k]);
            let dvdr = dot_lanes(del, &vel);
            let fvisc = monaghan_lanes(visc_c, sup.h, dvdr, *rsq, eps, pi.a + b.a);
            let fpair = -imass * jmass * (pi.b + b.b + fvisc) * wfd;
            let f: [L; D] = std::array::from_fn(|k| del[k] * fpair);
            (f, fpair, jmass * dvdr * wfd, imass * dvdr * wfd, -0.5 * fpair * dvdr)
        } else {
            let vel: [L; D] = std::array::from_fn(|k| lanes(|l| vi[k] - b.v[k][l]));
            let dvdr = dot_lanes(del, &vel);
            let mu = lanes(|l| sup.h[l] * dvdr[l] / (rsq[l] + eps[l]));
            let fvisc = lanes(|l| if dvdr[l] < 0.0 { visc_c[l] * mu[l] / (pi.a + b.a[l]) } else { 0.0 });
            let fpair = lanes(|l| -imass * jmass[l] * (pi.b + b.b[l] + fvisc[l]) * wfd[l]);
            let f: [L; D] = std::array::from_fn(|k| lanes(|l| del[k][l] * fpair[l]));
            (f, fpair, lanes(|l| jmass[l] * dvdr[l] * wfd[l]), lanes(|l| imass * dvdr[l] * wfd[l]), lanes(|l| -0.5 * fpair[l] * dvdr[l]))
        };
        SphContribution {
            f,
            fpair,
            drho_i,
            drho_j,
            de_i: de,
            de_j: de,
        }
    }
}

impl PairStyle for SphTaitwater {
    fn style(&self) -> &str {
        "sph/taitwater"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        tait_coeff(ilo, ihi, jlo, jhi, args, COEFF_SYNTAX, "alpha (artificial viscosity)", &mut self.types, &mut self.pairs)
    }
    fn init_sim(&mut self, setup: &super::PairSetup) -> Result<(), String> {
        super::sph::check_setup(setup, self.style())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.pairs.check_all(ntypes, active, "sph/taitwater")?;
        self.pairs.grow(ntypes)?;
        self.types.grow(ntypes);
        self.n = ntypes;
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, active, |p| p.1)?;
        let (pairs, c0) = (&self.pairs, &self.types.c0);
        self.derived = PerTypePair::new(ntypes, |i, j| {
            if i == 0 || j == 0 {
                return (Support::default(), 0.0, 0.0);
            }
            let (alpha, h) = *pairs.get(i, j);
            // LAMMPS: rsq + 0.01*h*h and -viscosity*(c_i + c_j)*mu, left to right
            (Support::new(h), 0.01 * h * h, -alpha * (c0[i] + c0[j]))
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
        let mut s = format!("sph/taitwater (kernel {}{})", self.kernel.name(), self.pmin.map(|p| format!(", pmin {p}")).unwrap_or_default());
        for i in 1..=self.n {
            s += &format!("\n    type {i}: rho0 {} c0 {}", self.types.rho0[i], self.types.c0[i]);
        }
        s
    }
    fn sph_info(&self) -> Option<super::SphInfo> {
        Some(super::SphInfo::from_tait(&self.types, &self.pairs, self.n, None))
    }
}
