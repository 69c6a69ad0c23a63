//! `pair_style dmhs/sph/diffusion [kernel K]`, `pair_coeff I J D h`: SPH diffusion of water
//! between particles, the paper's Eq 26 (Alexiadis 2015):
//!
//!   dw_i/dt = sum_j V_i V_j (D_i + D_j) (c_i - c_j) wfd(r_ij),   dw_j/dt gets the opposite,
//!
//! with V = m/rho (per-type mass, SPH density), c = w rho/m (Eq 27), wfd = (1/r) dW/dr (< 0, so
//! water flows down the concentration gradient) and D_i + D_j = 2 D_IJ, the pair's coefficient.
//! This is Brookshaw's SPH Laplacian: for a uniform D it gives dc/dt = D lap(c).
//! D = 0 for type pairs that do not exchange water (walls). The rates go to `dmhs/dwater`;
//! `fix dmhs/diffusion` integrates them.

use super::sph::{compute_sph, lanes, parse_kernel, Batch, Kernel, Packed, PairTable, SphContribution, SphKernel, Support, SupportLanes, LANES};
use super::{PairInput, PairModify, PairOutput, PairSetup, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style dmhs/sph/diffusion [kernel lucy|cubic|wendland2]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J D h  (D: diffusion coefficient of the pair, h: kernel support)";

pub struct SphDiffusion {
    kernel: Kernel,
    /// (2 D, h) per pair
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    n: usize,
    dim3: bool,
    /// Index of the water array in the atoms' extra arrays (found per compute).
    kw: usize,
}

impl SphDiffusion {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let kernel = parse_kernel(&mut a)?;
        Ok(SphDiffusion { kernel, pairs: PairTable::empty(), cutsq: vec![], n: 0, dim3: true, kw: 0 })
    }
}

impl SphKernel for SphDiffusion {
    /// a = V = m/rho, b = c = w/V.
    #[inline(always)]
    fn pack(&self, input: &PairInput, i: usize) -> Packed {
        let a = input.atoms;
        let vol = input.type_mass[a.typ[i]] / a.rho[i];
        Packed { x: a.x[i], v: [0.0; 3], a: vol, b: a.extra[self.kw].data[i] / vol }
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        &self.cutsq[ti * (self.n + 1)..(ti + 1) * (self.n + 1)]
    }
    #[inline(always)]
    fn pair_lanes<const D: usize>(&self, _input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>) -> SphContribution<D> {
        let dh: [(f64, f64); LANES] = std::array::from_fn(|l| *self.pairs.get(ti, b.tj[l]));
        let sup = SupportLanes::gather(|l| Support::new(dh[l].1));
        let wfd = self.kernel.wfd_lanes(&b.r, &sup, self.dim3);
        let dw = lanes(|l| pi.a * b.a[l] * dh[l].0 * (pi.b - b.b[l]) * wfd[l]);
        SphContribution { de_i: dw, de_j: lanes(|l| -dw[l]), ..SphContribution::default() }
    }
    /// The second rate is the water-mass rate dw/dt.
    fn rates(&self) -> [Option<super::Rate>; 2] {
        [None, Some(super::Rate::Field(crate::engine::fields::WATER_RATE))]
    }
}

impl PairStyle for SphDiffusion {
    fn style(&self) -> &str {
        "dmhs/sph/diffusion"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = COEFF_SYNTAX;
        let d = args.non_negative_f64("D (diffusion coefficient)")?;
        let h = args.positive_f64("h (kernel support)")?;
        args.finish()?;
        self.pairs.put_range(ilo, ihi, jlo, jhi, (2.0 * d, h)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        Ok(())
    }
    fn init_sim(&mut self, setup: &PairSetup) -> Result<(), String> {
        let a = setup.atoms;
        super::sph::check_setup(setup, self.style())?;
        if crate::engine::water::water(a).is_none() {
            return Err("pair dmhs/sph/diffusion: no particle carries water (define fix dmhs/diffusion, or set ... dmhs/conc)".into());
        }
        // only particles of types that exchange water need a volume m/rho
        let n = self.pairs.n;
        let exchanges = |t: usize| t <= n && (1..=n).any(|j| self.pairs.is_set(t, j) && self.pairs.get(t, j).0 > 0.0);
        if let Some(i) = (0..a.nlocal).find(|&i| a.rho[i] <= 0.0 && exchanges(a.typ[i])) {
            return Err(format!("pair dmhs/sph/diffusion: atom {} has density {} (V = m/rho needs rho > 0)", a.tag[i], a.rho[i]));
        }
        Ok(())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.pairs.check_all(ntypes, active, "dmhs/sph/diffusion")?;
        self.pairs.grow(ntypes)?;
        self.n = ntypes;
        // D = 0 pairs exchange nothing: leave them out of the list
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, active, |p| if p.0 > 0.0 { p.1 } else { 0.0 })?;
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
        // init_sim checked that the field exists
        let Some(kw) = input.atoms.field(crate::engine::fields::WATER) else { return Tally::default() };
        self.kw = kw;
        compute_sph(self, input, out);
        Tally::default()
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        format!("dmhs/sph/diffusion (kernel {})", self.kernel.name())
    }
    /// Explicit diffusion: the Fick deck (Lucy, h = 2.6 dx) is stable at D dt/h^2 = 0.104 and
    /// unstable at 0.118; the limit keeps a factor 2: dt <= 0.05 h^2/D, the smallest over pairs.
    fn dt_limits(&self) -> Vec<crate::models::Limit> {
        let mut worst: Option<(f64, f64, f64)> = None;
        for i in 1..=self.pairs.n {
            for j in i..=self.pairs.n {
                let (d2, h) = *self.pairs.get(i, j);
                if self.pairs.is_set(i, j) && d2 > 0.0 {
                    let dt = 0.05 * h * h / (0.5 * d2);
                    if worst.map(|w| dt < w.0).unwrap_or(true) {
                        worst = Some((dt, h, 0.5 * d2));
                    }
                }
            }
        }
        worst
            .map(|(dt, h, d)| vec![crate::models::Limit { model: "water diffusion".into(), rule: format!("explicit 0.05 h^2/D (h = {h}, D = {d})"), dt_max: dt }])
            .unwrap_or_default()
    }
}
