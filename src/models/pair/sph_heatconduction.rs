//! `pair_style sph/heatconduction [kernel K]` — SPH heat conduction between particles (LAMMPS SPH
//! package), `pair_coeff I J D h`:
//! de_i = 2 m_i m_j/(m_i + m_j) (rho_i + rho_j)/(rho_i rho_j) D (e_i - e_j) wfd, de_j = -de_i
//! (esph is extensive; temperatures come from compute sph/t/atom as esph/cv).

use super::sph::{compute_sph, lanes, parse_kernel, Batch, Kernel, Packed, PairTable, SphContribution, SphKernel, Support, SupportLanes, LANES};
use super::{PairInput, PairModify, PairOutput, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style sph/heatconduction [kernel lucy|cubic|wendland2]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J D h";

pub struct SphHeatConduction {
    kernel: Kernel,
    /// (D, h) per pair
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    n: usize,
    dim3: bool,
}

impl SphHeatConduction {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let kernel = parse_kernel(&mut a)?;
        Ok(SphHeatConduction { kernel, pairs: PairTable::empty(), cutsq: vec![], n: 0, dim3: true })
    }
}

impl SphKernel for SphHeatConduction {
    /// a = rho, b = esph.
    #[inline(always)]
    fn pack(&self, input: &PairInput, i: usize) -> Packed {
        let a = input.atoms;
        Packed { x: a.x[i], v: [0.0; 3], a: a.rho[i], b: a.esph[i] }
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        &self.cutsq[ti * (self.n + 1)..(ti + 1) * (self.n + 1)]
    }
    #[inline(always)]
    fn pair_lanes<const D: usize>(&self, input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>) -> SphContribution<D> {
        let dh: [(f64, f64); LANES] = std::array::from_fn(|l| *self.pairs.get(ti, b.tj[l]));
        // LAMMPS computes 1/h per pair: Support::new does the same arithmetic
        let sup = SupportLanes::gather(|l| Support::new(dh[l].1));
        let wfd = self.kernel.wfd_lanes(&b.r, &sup, self.dim3);
        let imass = input.type_mass[ti];
        let jmass = b.m;
        let de = lanes(|l| 2.0 * imass * jmass[l] / (imass + jmass[l]));
        let de = lanes(|l| de[l] * ((pi.a + b.a[l]) / (pi.a * b.a[l])));
        let de = lanes(|l| de[l] * (dh[l].0 * (pi.b - b.b[l]) * wfd[l]));
        SphContribution { de_i: de, de_j: lanes(|l| -de[l]), ..SphContribution::default() }
    }
}

impl PairStyle for SphHeatConduction {
    fn style(&self) -> &str {
        "sph/heatconduction"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = COEFF_SYNTAX;
        let d = args.f64("D (diffusion coefficient)")?;
        let h = args.positive_f64("h (kernel support)")?;
        args.finish()?;
        self.pairs.put_range(ilo, ihi, jlo, jhi, (d, h)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        Ok(())
    }
    fn init_sim(&mut self, setup: &super::PairSetup) -> Result<(), String> {
        super::sph::check_setup(setup, self.style())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.pairs.check_all(ntypes, active, "sph/heatconduction")?;
        self.pairs.grow(ntypes)?;
        self.n = ntypes;
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, active, |p| p.1)?;
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
        compute_sph(self, input, out);
        Tally::default()
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        format!("sph/heatconduction (kernel {})", self.kernel.name())
    }
}
