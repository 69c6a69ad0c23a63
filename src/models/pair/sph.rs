//! Shared parts of the SPH pair styles (LAMMPS' SPH package): the smoothing kernels, the
//! per-type Tait parameters with LAMMPS' storage quirks, coefficient parsing, and the
//! engine-owned SPH pair loop.
//!
//! Notation as in LAMMPS: `h` is the pair_coeff cutoff (the kernel's support radius), and
//! `wfd = (1/r) dW/dr` (the missing factor r comes back through `x_ij` in forces and
//! `v_ij . x_ij` in rates).

pub use crate::engine::par::lanes::{lanes, L, LANES};
pub use super::sph_loop::{compute_sph, dot_lanes, Batch, SphContribution};
use super::{PairInput, PairSetup, Rate};
use std::ops::{Div, Mul, Sub};
use dmhs_parser::{Args, DResult, Diagnostic, Word};

/// The smoothing kernel of the force and rate terms. `Lucy` is what LAMMPS uses; the others are
/// a dmhs extension (`pair_style sph/... kernel cubic|wendland2`), documented in docs/commands.md.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// W = K/h^d (1 + 3q)(1 - q)^3, K = 5/pi (2D), 105/(16 pi) (3D); q = r/h.
    Lucy,
    /// Monaghan's cubic B-spline with support h (smoothing length h/2).
    Cubic,
    /// Wendland C2: W = K/h^d (1 - q)^4 (1 + 4q), K = 7/pi (2D), 21/(2 pi) (3D).
    Wendland2,
}

impl Kernel {
    pub fn name(self) -> &'static str {
        match self {
            Kernel::Lucy => "lucy",
            Kernel::Cubic => "cubic",
            Kernel::Wendland2 => "wendland2",
        }
    }

    /// `(1/r) dW/dr` for a pair at squared distance `rsq < h^2`, in LAMMPS' arithmetic for Lucy.
    #[inline(always)]
    pub fn wfd(self, rsq: f64, h: f64, dim3: bool) -> f64 {
        let ih = 1.0 / h;
        self.wfd_with(rsq, &Support { h, ih, ihsq: ih * ih }, dim3)
    }

    /// [`Kernel::wfd`] with the support's inverse powers precomputed (same bits: LAMMPS computes
    /// ih = 1/h and ihsq = ih*ih per pair, identically).
    #[inline(always)]
    pub fn wfd_with(self, rsq: f64, s: &Support, dim3: bool) -> f64 {
        let r = rsq.sqrt();
        match (self, dim3) {
            (Kernel::Lucy, false) => lucy_wfd_2d(r, s.h, s.ihsq),
            (Kernel::Lucy, true) => lucy_wfd_3d(r, s.h, s.ih, s.ihsq),
            (Kernel::Wendland2, _) => wendland2_wfd(r, s.h, dim3),
            (Kernel::Cubic, _) => cubic_wfd(r, s.h, dim3),
        }
    }

    /// [`Kernel::wfd_with`] for a batch of pairs, lane by lane (the kernel and dimension are
    /// chosen once per batch, so the compiler vectorizes each arm; the same operations per lane
    /// give the same bits). `r` is the pairs' distance, [`Batch::r`].
    #[inline(always)]
    pub fn wfd_lanes(self, r: &L, s: &SupportLanes, dim3: bool) -> L {
        let r = *r;
        match (self, dim3) {
            (Kernel::Lucy, false) => lucy_wfd_2d(r, s.h, s.ihsq),
            (Kernel::Lucy, true) => lucy_wfd_3d(r, s.h, s.ih, s.ihsq),
            (Kernel::Wendland2, false) => lanes(|l| wendland2_wfd(r[l], s.h[l], false)),
            (Kernel::Wendland2, true) => lanes(|l| wendland2_wfd(r[l], s.h[l], true)),
            (Kernel::Cubic, false) => lanes(|l| cubic_wfd(r[l], s.h[l], false)),
            (Kernel::Cubic, true) => lanes(|l| cubic_wfd(r[l], s.h[l], true)),
        }
    }

    /// `W(r)` (for tests and for density summation with non-Lucy kernels).
    pub fn w(self, r: f64, h: f64, dim3: bool) -> f64 {
        let q = r / h;
        if q >= 1.0 {
            return 0.0;
        }
        let pi = std::f64::consts::PI;
        match self {
            Kernel::Lucy => {
                let k = if dim3 { 105.0 / (16.0 * pi * h * h * h) } else { 5.0 / (pi * h * h) };
                k * (1.0 + 3.0 * q) * (1.0 - q).powi(3)
            }
            Kernel::Wendland2 => {
                let k = if dim3 { 21.0 / (2.0 * pi * h * h * h) } else { 7.0 / (pi * h * h) };
                k * (1.0 - q).powi(4) * (1.0 + 4.0 * q)
            }
            Kernel::Cubic => {
                let hs = 0.5 * h;
                let s = r / hs;
                let sigma = if dim3 { 1.0 / (pi * hs * hs * hs) } else { 10.0 / (7.0 * pi * hs * hs) };
                if s < 1.0 { sigma * (1.0 - 1.5 * s * s + 0.75 * s * s * s) } else { sigma * 0.25 * (2.0 - s).powi(3) }
            }
        }
    }
}

/// Lucy's `(1/r) dW/dr` in 2D at distance r, in LAMMPS' order of operations; for one pair
/// (f64) or a batch ([`L`]), the same operations either way.
#[inline(always)]
fn lucy_wfd_2d<T: Copy + Sub<Output = T> + Mul<Output = T>>(r: T, h: T, ihsq: T) -> T
where
    f64: Mul<T, Output = T>,
{
    let w = h - r;
    -19.098593171027440292 * w * w * ihsq * ihsq * ihsq
}

/// Lucy's `(1/r) dW/dr` in 3D at distance r, in LAMMPS' order of operations (f64 or [`L`]).
#[inline(always)]
fn lucy_wfd_3d<T: Copy + Sub<Output = T> + Mul<Output = T>>(r: T, h: T, ih: T, ihsq: T) -> T
where
    f64: Mul<T, Output = T>,
{
    let w = h - r;
    -25.066903536973515383 * w * w * ihsq * ihsq * ihsq * ih
}

/// Wendland C2: dW/dr = -20 K q (1-q)^3 / h^(d+1), so (1/r) dW/dr = -20 K (1-q)^3 / h^(d+2).
#[inline(always)]
fn wendland2_wfd(r: f64, h: f64, dim3: bool) -> f64 {
    let q = r / h;
    let u = 1.0 - q;
    let k = if dim3 { 21.0 / (2.0 * std::f64::consts::PI) } else { 7.0 / std::f64::consts::PI };
    let hd2 = if dim3 { h.powi(5) } else { h.powi(4) };
    -20.0 * k * u * u * u / hd2
}

/// Cubic B-spline with support h = 2 hs; W = sigma/hs^d f(s), s = r/hs.
#[inline(always)]
fn cubic_wfd(r: f64, h: f64, dim3: bool) -> f64 {
    let hs = 0.5 * h;
    let s = r / hs;
    let sigma = if dim3 { 1.0 / std::f64::consts::PI } else { 10.0 / (7.0 * std::f64::consts::PI) };
    // (1/s) df/ds, both branches computed and one selected (branch-free in lanes)
    let inner = -3.0 + 2.25 * s;
    let outer = -0.75 * (2.0 - s) * (2.0 - s) / s;
    let dfds_over_s = if s < 1.0 { inner } else { outer };
    let hsd2 = if dim3 { hs.powi(5) } else { hs.powi(4) };
    sigma * dfds_over_s / hsd2
}

/// Kernel supports of a batch, lane by lane.
#[derive(Clone, Copy, Debug, Default)]
pub struct SupportLanes {
    pub h: L,
    pub ih: L,
    pub ihsq: L,
}

impl SupportLanes {
    /// Gather the supports of the batch's type pairs with `sup(lane)`.
    #[inline(always)]
    pub fn gather(sup: impl Fn(usize) -> Support) -> SupportLanes {
        let s: [Support; LANES] = std::array::from_fn(sup);
        SupportLanes { h: lanes(|l| s[l].h), ih: lanes(|l| s[l].ih), ihsq: lanes(|l| s[l].ihsq) }
    }
}

/// A kernel support radius with its inverse powers.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Support {
    pub h: f64,
    pub ih: f64,
    pub ihsq: f64,
}

impl Support {
    pub fn new(h: f64) -> Support {
        let ih = 1.0 / h;
        Support { h, ih, ihsq: ih * ih }
    }
}

/// Values per type pair (I, J in 0..=n), knowing which rows I hold one value for every partner
/// type J >= 1 (the common case: one `pair_coeff * *`), so that a batch needs no per-lane lookup.
#[derive(Clone, Debug, Default)]
pub struct PerTypePair<T> {
    stride: usize,
    val: Vec<T>,
    uniform: Vec<bool>,
}

impl<T: Copy + PartialEq> PerTypePair<T> {
    /// The table of `f(i, j)` for types `0..=n`.
    pub fn new(n: usize, f: impl Fn(usize, usize) -> T) -> Result<Self, String> {
        let stride = n + 1;
        let mut val = super::type_pair_vec(n, f(0, 0))?;
        for (k, v) in val.iter_mut().enumerate() {
            *v = f(k / stride, k % stride);
        }
        let uniform = (0..stride).map(|i| n >= 1 && (1..=n).all(|j| val[i * stride + j] == val[i * stride + 1])).collect();
        Ok(PerTypePair { stride, val, uniform })
    }
    #[inline(always)]
    pub fn get(&self, i: usize, j: usize) -> T {
        self.val[i * self.stride + j]
    }
    /// The values for type `ti` against the types `tj` of a batch.
    #[inline(always)]
    pub fn batch(&self, ti: usize, tj: &[usize; LANES]) -> [T; LANES] {
        if self.uniform[ti] {
            [self.get(ti, 1); LANES]
        } else {
            std::array::from_fn(|l| self.get(ti, tj[l]))
        }
    }
}

/// The value of a `kernel` keyword: lucy, cubic or wendland2.
pub fn kernel_choice(a: &mut Args) -> DResult<Kernel> {
    Ok(match a.choice("kernel", &["lucy", "cubic", "wendland2"])? {
        0 => Kernel::Lucy,
        1 => Kernel::Cubic,
        _ => Kernel::Wendland2,
    })
}

/// Parse the optional `kernel NAME` extension keyword of an SPH pair style.
/// The check every SPH pair style makes before a run (LAMMPS refuses an SPH pair style without
/// the SPH atom attributes at set-up): the style reads and writes the SPH per-atom arrays.
pub fn check_setup(setup: &PairSetup, style: &str) -> Result<(), String> {
    if !setup.atoms.features.sph {
        return Err(format!("pair {style} requires atom attributes rho, drho, esph, desph, cv (atom_style sph, or hybrid with sph)"));
    }
    Ok(())
}

pub fn parse_kernel(a: &mut Args) -> DResult<Kernel> {
    let mut kernel = Kernel::Lucy;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "kernel" => kernel = kernel_choice(a)?,
            _ => return Err(a.unknown_keyword(w, &["kernel"])),
        }
    }
    Ok(kernel)
}

/// Options of the Tait styles: the kernel and the `pmin P` extension (dmhs): the pressure is
/// clipped from below, P = max(P_Tait, pmin). `pmin 0` removes the tension that makes a
/// stretching free jet (falling stream) clump and burst with weakly compressible SPH.
pub fn parse_tait_options(a: &mut Args) -> DResult<(Kernel, Option<f64>)> {
    let mut kernel = Kernel::Lucy;
    let mut pmin = None;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "kernel" => kernel = kernel_choice(a)?,
            "pmin" => pmin = Some(a.f64("pmin (lowest pressure)")?),
            _ => return Err(a.unknown_keyword(w, &["kernel", "pmin"])),
        }
    }
    Ok((kernel, pmin))
}

/// The Tait P/rho^2 with the optional lower pressure bound of [`parse_tait_options`].
#[inline(always)]
pub fn tait_p_over_rho2_min(rho: f64, rho0: f64, b: f64, pmin: Option<f64>) -> f64 {
    let p = tait_p_over_rho2(rho, rho0, b);
    match pmin {
        Some(m) if p * rho * rho < m => m / (rho * rho),
        _ => p,
    }
}

/// The record of particle i for the Tait styles (sph/taitwater and /morris): a = rho,
/// b = the Tait P/rho^2 (0 for a type without rho0).
#[inline(always)]
pub fn tait_pack(types: &TaitTypes, pmin: Option<f64>, input: &PairInput, i: usize) -> Packed {
    let a = input.atoms;
    let t = a.typ[i];
    let rho0 = types.rho0.get(t).copied().unwrap_or(0.0);
    let p = if rho0 == 0.0 { 0.0 } else { tait_p_over_rho2_min(a.rho[i], rho0, types.b[t], pmin) };
    Packed { x: a.x[i], v: a.vest[i], a: a.rho[i], b: p }
}

/// [`tait_pack`] of particles `i0..i0 + LANES` (to `each`, as [`SphKernel::pack_lanes`]), with
/// the pressures as lane vectors: the same operations per lane, so the same bits, with one vector
/// division where the scalar code makes four (the divisions' latency dominated the per-particle
/// preparation).
#[inline(always)]
pub fn tait_pack_lanes(types: &TaitTypes, pmin: Option<f64>, input: &PairInput, i0: usize, mut each: impl FnMut(usize, &Packed)) {
    if pmin.is_some() {
        for l in 0..LANES {
            each(l, &tait_pack(types, pmin, input, i0 + l));
        }
        return;
    }
    let a = input.atoms;
    let t: [usize; LANES] = std::array::from_fn(|l| a.typ[i0 + l]);
    let rho = lanes(|l| a.rho[i0 + l]);
    let rho0 = lanes(|l| types.rho0.get(t[l]).copied().unwrap_or(0.0));
    let b = lanes(|l| types.b.get(t[l]).copied().unwrap_or(0.0));
    let p = tait_p_over_rho2(rho, rho0, b);
    for l in 0..LANES {
        each(l, &Packed { x: a.x[i0 + l], v: a.vest[i0 + l], a: rho[l], b: if rho0[l] == 0.0 { 0.0 } else { p[l] } });
    }
}

/// LAMMPS' Tait equation of state written as P/rho^2 (`fi` in pair_sph_taitwater.cpp):
/// t = rho/rho0; f = t^3; B (f^2 t - 1) / rho^2. For one particle (f64) or four ([`L`]), the
/// same operations either way.
#[inline(always)]
pub fn tait_p_over_rho2<T: Copy + Mul<Output = T> + Div<Output = T> + Sub<f64, Output = T>>(rho: T, rho0: T, b: T) -> T {
    let tmp = rho / rho0;
    let f = tmp * tmp * tmp;
    b * (f * f * tmp - 1.0) / (rho * rho)
}

/// Monaghan's artificial viscosity term Pi of sph/taitwater and sph/idealgas, for approaching
/// pairs only (v.x < 0; +0 otherwise): mu = h v.x/(r^2 + eps), Pi = coef mu/(rho_i + rho_j), with
/// eps = 0.01 h^2 and coef = -alpha (c_i + c_j), in LAMMPS' order of operations.
#[inline(always)]
pub fn monaghan_lanes(coef: L, h: L, dvdr: L, rsq: L, eps: L, rho_sum: L) -> L {
    let mu = h * dvdr / (rsq + eps);
    dvdr.lt_or_zero(&L::splat(0.0), &(coef * mu / rho_sum))
}

/// The pair coefficients and pair term of the equation-of-state styles with Monaghan viscosity
/// and `pair_coeff I J alpha h` (sph/idealgas, sph/lj): each style gives P/rho^2 of both
/// particles and the sum of their sound speeds; the rest is LAMMPS' common pair code.
pub struct ViscousPairs {
    pub kernel: Kernel,
    /// (alpha, h) per pair
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    /// Per type pair: the support, 0.01 h^2 and -alpha (LAMMPS' arithmetic).
    derived: PerTypePair<(Support, f64, f64)>,
    n: usize,
    pub dim3: bool,
}

pub const VISCOUS_COEFF_SYNTAX: &str = "pair_coeff I J alpha h";

impl ViscousPairs {
    pub fn new(kernel: Kernel) -> Self {
        ViscousPairs { kernel, pairs: PairTable::empty(), cutsq: vec![], derived: PerTypePair::default(), n: 0, dim3: true }
    }
    /// `pair_coeff I J alpha h`.
    pub fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = VISCOUS_COEFF_SYNTAX;
        let alpha = args.f64("alpha (artificial viscosity)")?;
        let h = args.positive_f64("h (kernel support)")?;
        args.finish()?;
        self.pairs.put_range(ilo, ihi, jlo, jhi, (alpha, h)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        Ok(())
    }
    pub fn init(&mut self, ntypes: usize, active: Option<&[bool]>, style: &str) -> Result<(), String> {
        self.pairs.check_all(ntypes, active, style)?;
        self.pairs.grow(ntypes)?;
        self.n = ntypes;
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, active, |p| p.1)?;
        let pairs = &self.pairs;
        self.derived = PerTypePair::new(ntypes, |i, j| {
            if i == 0 || j == 0 {
                return (Support::default(), 0.0, 0.0);
            }
            let (alpha, h) = *pairs.get(i, j);
            // LAMMPS: rsq + 0.01*h*h and -viscosity*(c_i + c_j)*mu, left to right
            (Support::new(h), 0.01 * h * h, -alpha)
        })?;
        Ok(())
    }
    /// The kernel support of a type pair after `init`.
    pub fn support(&self, i: usize, j: usize) -> Support {
        self.derived.get(i, j).0
    }
    #[inline(always)]
    pub fn cutsq_row(&self, ti: usize) -> &[f64] {
        &self.cutsq[ti * (self.n + 1)..(ti + 1) * (self.n + 1)]
    }
    pub fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.cutsq.get(it * (self.n + 1) + jt).map(|c| c.sqrt()).unwrap_or(0.0)
    }
    /// The pair term for P/rho^2 `fi`, `fj` and the sound speeds' sum `csum`:
    /// F_i = -m_i m_j (fi + fj + Pi) wfd x_ij, drho as the Tait styles, de_i = de_j = -F.v/2.
    #[inline(always)]
    pub fn pair<const D: usize>(&self, input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>, fi: L, fj: L, csum: L) -> SphContribution<D> {
        let d: [(Support, f64, f64); LANES] = self.derived.batch(ti, &b.tj);
        let sup = SupportLanes::gather(|l| d[l].0);
        let (eps, neg_alpha) = (lanes(|l| d[l].1), lanes(|l| d[l].2));
        let del = &b.del;
        let wfd = self.kernel.wfd_lanes(&b.r, &sup, self.dim3);
        let imass = input.type_mass[ti];
        let jmass = b.m;
        let vel: [L; D] = std::array::from_fn(|k| pi.v[k] - b.v[k]);
        let dvdr = dot_lanes(del, &vel);
        let fvisc = monaghan_lanes(neg_alpha * csum, sup.h, dvdr, b.rsq, eps, pi.a + b.a);
        let fpair = -imass * jmass * (fi + fj + fvisc) * wfd;
        let de = -0.5 * fpair * dvdr;
        SphContribution {
            f: std::array::from_fn(|k| del[k] * fpair),
            fpair,
            drho_i: jmass * dvdr * wfd,
            drho_j: imass * dvdr * wfd,
            de_i: de,
            de_j: de,
        }
    }
}

/// Per-pair coefficients: `set` and the values of `pair_coeff I J ...`.
#[derive(Clone, Debug)]
pub struct PairTable<T: Clone> {
    pub n: usize,
    pub set: Vec<bool>,
    pub val: Vec<T>,
}

impl<T: Clone + Default> PairTable<T> {
    pub fn new(n: usize) -> Result<Self, String> {
        Ok(PairTable { n, set: super::type_pair_vec(n, false)?, val: super::type_pair_vec(n, T::default())? })
    }
    /// No types yet (a style before its first pair_coeff).
    pub fn empty() -> Self {
        PairTable { n: 0, set: vec![false], val: vec![T::default()] }
    }
    #[inline(always)]
    pub fn get(&self, i: usize, j: usize) -> &T {
        &self.val[i * (self.n + 1) + j]
    }
    pub fn is_set(&self, i: usize, j: usize) -> bool {
        self.set[i * (self.n + 1) + j]
    }
    pub fn put(&mut self, i: usize, j: usize, v: T) {
        let s = self.n + 1;
        self.val[i * s + j] = v.clone();
        self.val[j * s + i] = v;
        self.set[i * s + j] = true;
        self.set[j * s + i] = true;
    }
    /// `pair_coeff ilo:ihi jlo:jhi`: set `v` for every pair I <= J of the ranges (growing the
    /// table as needed).
    pub fn put_range(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, v: T) -> Result<(), String> {
        self.grow(ihi.max(jhi))?;
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.put(i, j, v.clone());
            }
        }
        Ok(())
    }
    /// Grow to `n` types keeping what is set.
    pub fn grow(&mut self, n: usize) -> Result<(), String> {
        if n <= self.n {
            return Ok(());
        }
        let mut t = PairTable::new(n)?;
        for i in 0..=self.n {
            for j in 0..=self.n {
                if self.is_set(i, j) {
                    t.put(i, j, self.get(i, j).clone());
                }
            }
        }
        *self = t;
        Ok(())
    }
    /// Every pair I <= J of `1..=n` (within `active` if given) must be set.
    pub fn check_all(&self, n: usize, active: Option<&[bool]>, style: &str) -> Result<(), String> {
        for i in 1..=n {
            for j in i..=n {
                if let Some(a) = active {
                    if !a[i * (n + 1) + j] {
                        continue;
                    }
                }
                if i > self.n || j > self.n || !self.is_set(i, j) {
                    return Err(format!("pair {style} coefficients for types {i} {j} are not set (SPH styles do not mix: every pair must be given)"));
                }
            }
        }
        Ok(())
    }
}

/// Per-type Tait parameters (LAMMPS stores rho0, c0 and B per type I: the last pair_coeff whose
/// I range includes a type wins, whatever its J range).
#[derive(Clone, Debug, Default)]
pub struct TaitTypes {
    pub rho0: Vec<f64>,
    pub c0: Vec<f64>,
    pub b: Vec<f64>,
}

impl TaitTypes {
    pub fn grow(&mut self, n: usize) {
        if self.rho0.len() < n + 1 {
            self.rho0.resize(n + 1, 0.0);
            self.c0.resize(n + 1, 0.0);
            self.b.resize(n + 1, 0.0);
        }
    }
    pub fn set(&mut self, lo: usize, hi: usize, rho0: f64, c0: f64) {
        self.grow(hi);
        // LAMMPS: B = c0^2 rho0 / 7
        let b = c0 * c0 * rho0 / 7.0;
        for i in lo..=hi {
            self.rho0[i] = rho0;
            self.c0[i] = c0;
            self.b[i] = b;
        }
    }
}

/// `pair_coeff I J rho0 c0 X h` of sph/taitwater (X = alpha) and sph/taitwater/morris (X = mu).
pub fn tait_coeff(ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args, syntax: &'static str, x_name: &str, types: &mut TaitTypes, pairs: &mut PairTable<(f64, f64)>) -> DResult<()> {
    args.syntax = syntax;
    let rho0 = args.f64("rho0")?;
    let c0 = args.f64("c0 (sound speed)")?;
    let x = args.f64(x_name)?;
    let h = args.positive_f64("h (kernel support)")?;
    args.finish()?;
    pairs.put_range(ilo, ihi, jlo, jhi, (x, h)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
    types.set(ilo, ihi, rho0, c0);
    Ok(())
}

/// A non-positive density would make the Tait term infinite: report it at the coefficient.
pub fn check_positive(w: &Word, x: f64, what: &str) -> DResult<()> {
    if x <= 0.0 {
        return Err(Diagnostic::at(w.span, format!("{what} must be > 0"), "must be > 0"));
    }
    Ok(())
}

/// What the SPH loop reads of one particle, packed into one cache line: position, a velocity
/// (the estimate `vest`), and two scalars chosen by the style (e.g. rho and the Tait P/rho^2).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(64))]
pub struct Packed {
    pub x: [f64; 3],
    pub v: [f64; 3],
    pub a: f64,
    pub b: f64,
}

/// Per-pair physics of an SPH style, called by [`compute_sph`].
pub trait SphKernel: Sync {
    /// The record of particle i (owned or ghost).
    fn pack(&self, input: &PairInput, i: usize) -> Packed;
    /// `each(l, record)` for the particles `i0 + l`, l in `0..LANES` ([`Self::pack`] of each,
    /// unless the style computes them together). A callback rather than an array of records:
    /// the array went through the stack.
    #[inline(always)]
    fn pack_lanes(&self, input: &PairInput, i0: usize, mut each: impl FnMut(usize, &Packed)) {
        for l in 0..LANES {
            each(l, &self.pack(input, i0 + l));
        }
    }
    /// Squared cutoffs of type pairs (ti, 0..=ntypes) (0: no interaction).
    fn cutsq_row(&self, ti: usize) -> &[f64];
    /// The contributions of a batch of pairs (i, j) inside the cutoff, written lane by lane with
    /// [`lanes`] so that the compiler evaluates the lanes together.
    fn pair_lanes<const D: usize>(&self, input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>) -> SphContribution<D>;
    /// What the contribution's two scalar rates (`drho_*`, `de_*`) add to: drho/dt and
    /// d(esph)/dt unless the style says otherwise (None: the rate is not kept).
    fn rates(&self) -> [Option<Rate>; 2] {
        [Some(Rate::Density), Some(Rate::Energy)]
    }
    /// Whether the force is along the pair (`f = fpair del`). A style whose force is not (Morris
    /// viscosity, along v_ij) tallies the global virial from its whole force under newton on,
    /// as LAMMPS' F dot r does; its per-atom virial stays ev_tally's fpair.
    const CENTRAL: bool = true;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integral of W over the plane or space, by rings/shells (midpoint rule).
    fn integral(k: Kernel, h: f64, dim3: bool) -> f64 {
        let n = 20000;
        let dr = h / n as f64;
        (0..n)
            .map(|m| {
                let r = (m as f64 + 0.5) * dr;
                let shell = if dim3 { 4.0 * std::f64::consts::PI * r * r } else { 2.0 * std::f64::consts::PI * r };
                k.w(r, h, dim3) * shell * dr
            })
            .sum()
    }

    #[test]
    fn pmin_clips_the_tait_pressure_from_below() {
        // B = c0^2 rho0 / 7 with c0 = 20, rho0 = 1000
        let (rho0, b) = (1000.0, 400.0 * 1000.0 / 7.0);
        // rho = 0.9 rho0: P = B (0.9^7 - 1) = -29811.6 Pa (tension)
        let p = tait_p_over_rho2(900.0, rho0, b) * 900.0 * 900.0;
        assert!((p - b * (0.9f64.powi(7) - 1.0)).abs() < 1e-9 * b);
        assert!((p + 29811.6).abs() < 0.01, "{p}");
        assert_eq!(tait_p_over_rho2_min(900.0, rho0, b, Some(0.0)), 0.0);
        assert_eq!(tait_p_over_rho2_min(900.0, rho0, b, Some(-1.0e4)) * 900.0 * 900.0, -1.0e4);
        // compression is untouched: rho = 1.1 rho0, P = B (1.1^7 - 1) = 54212.4 Pa
        assert_eq!(tait_p_over_rho2_min(1100.0, rho0, b, Some(0.0)), tait_p_over_rho2(1100.0, rho0, b));
        assert!((tait_p_over_rho2(1100.0, rho0, b) * 1100.0 * 1100.0 - 54212.4).abs() < 0.01);
        assert_eq!(tait_p_over_rho2_min(900.0, rho0, b, None), tait_p_over_rho2(900.0, rho0, b));
    }

    #[test]
    fn kernels_are_normalised() {
        for k in [Kernel::Lucy, Kernel::Cubic, Kernel::Wendland2] {
            for dim3 in [false, true] {
                let s = integral(k, 1.7, dim3);
                assert!((s - 1.0).abs() < 1e-6, "{k:?} dim3={dim3}: {s}");
            }
        }
    }

    #[test]
    fn wfd_is_the_derivative_of_w_over_r() {
        let h = 1.3;
        for k in [Kernel::Lucy, Kernel::Cubic, Kernel::Wendland2] {
            for dim3 in [false, true] {
                for &r in &[0.05, 0.3, 0.6, 0.65, 0.9, 1.25] {
                    let e = 1e-6;
                    let dwdr = (k.w(r + e, h, dim3) - k.w(r - e, h, dim3)) / (2.0 * e);
                    let got = k.wfd(r * r, h, dim3);
                    assert!((got - dwdr / r).abs() <= 1e-6 * (1.0 + (dwdr / r).abs()), "{k:?} dim3={dim3} r={r}: {got} vs {}", dwdr / r);
                }
            }
        }
    }

    #[test]
    fn lucy_is_lammps_arithmetic() {
        // LAMMPS pair_sph_taitwater.cpp, 2D, evaluated step by step
        let (h, rsq): (f64, f64) = (0.03, 0.0004);
        let ih = 1.0 / h;
        let ihsq = ih * ih;
        let w = h - rsq.sqrt();
        let lammps = -19.098593171027440292 * w * w * ihsq * ihsq * ihsq;
        assert_eq!(Kernel::Lucy.wfd(rsq, h, false).to_bits(), lammps.to_bits());
    }

    #[test]
    fn tait_matches_the_formula_sheet() {
        let (rho0, c) = (1000.0, 20.0);
        let b = c * c * rho0 / 7.0;
        let rho: f64 = 1003.0;
        let p = b * ((rho / rho0).powi(7) - 1.0);
        assert!((tait_p_over_rho2(rho, rho0, b) - p / (rho * rho)).abs() < 1e-12 * (p / (rho * rho)).abs());
    }
}
