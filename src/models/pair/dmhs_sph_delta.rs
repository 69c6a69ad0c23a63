//! `pair_style dmhs/sph/delta molteni|fourtakas [g gx gy gz] [kernel K]`,
//! `pair_coeff I J rho0 c0 delta h`: delta-SPH density diffusion, a term added to the continuity
//! equation of an SPH density style (sph/taitwater, sph/taitwater/morris) under `hybrid/overlay`.
//! It only adds to drho; forces and energies are the density style's.
//!
//! Molteni & Colagrossi (2009), with psi_ij = 2 (rho_j - rho_i) (x_j - x_i)/|x_ij|^2 and
//! grad_i W = (x_i - x_j) wfd (wfd = (1/r) dW/dr < 0):
//!
//!   D_i = delta h_s c0 sum_j psi_ij . grad_i W_ij V_j = delta h c0 sum_j (rho_i - rho_j) wfd V_j,
//!
//! h_s = h/2 the smoothing length of a kernel of support h (the pair_coeff h, as in every SPH
//! style), so that delta means what it means in DualSPHysics (support 2 h_s); V_j = m_j/rho_j.
//!
//! Fourtakas et al. (2019), DualSPHysics' DDT: the dynamic part of the density difference only,
//! (rho_i - rho_j) + rho^H_ji with rho^H_ji = rho^H_j - rho^H_i the hydrostatic difference of
//! the pair. Here it is taken through the Tait equation of state (gamma 7, B = c0^2 rho0/7) from
//! the pair's mean pressure P = (P_i + P_j)/2 and the hydrostatic pressure difference
//! P_j - P_i = rho0 g . (x_j - x_i):
//!
//!   rho^H_ji = rho0 [(s + q)^(1/7) - (s - q)^(1/7)],  s = ((rho_i/rho0)^7 + (rho_j/rho0)^7)/2,
//!   q = (P_j - P_i)/(2B) = -7 g . x_ij / (2 c0^2).
//!
//! Fourtakas writes the Tait inverse around P_i = 0, rho0 [(1 + (P_j - P_i)/B)^(1/7) - 1]: that is
//! antisymmetric in i, j only to O(((P_j - P_i)/B)^2) and leaves O(P/B) on a Tait hydrostatic
//! column; the mean pressure makes the term exactly antisymmetric and exactly zero there. (The
//! DualSPHysics source was not read; the forms here are the papers'.)
//!
//! Per pair, drho_i = K V_j and drho_j = -K V_i (K the pair's coefficient times its density
//! difference times wfd), so sum_i V_i drho_i = 0: the term moves mass sum_i V_i rho_i between
//! particles and creates none.

use super::sph::{compute_sph, lanes, Batch, Kernel, Packed, PairTable, PerTypePair, SphContribution, SphKernel, Support, SupportLanes, TaitTypes, L, LANES};
use super::{PairInput, PairModify, PairOutput, PairSetup, PairStyle, Rate, Tally};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "pair_style dmhs/sph/delta molteni|fourtakas [g gx gy gz] [kernel lucy|cubic|wendland2]  (g: gravity vector, fourtakas only)";
pub const COEFF_SYNTAX: &str = "pair_coeff I J rho0 c0 delta h  (delta in (0, 1], typically 0.1; h: kernel support)";

/// Which density difference is diffused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// the whole difference (Molteni & Colagrossi 2009)
    Molteni,
    /// the dynamic difference, total minus hydrostatic (Fourtakas et al. 2019)
    Fourtakas,
}

pub struct SphDelta {
    form: Form,
    kernel: Kernel,
    /// gravity (fourtakas)
    g: [f64; 3],
    /// rho0, c0 per type
    types: TaitTypes,
    /// (delta, h) per pair
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    /// Per type pair: support, delta h c0, mean rho0, -7/(2 c0^2) (c0 and rho0 the pair's means).
    derived: PerTypePair<(Support, f64, f64, f64)>,
    n: usize,
    dim3: bool,
}

/// The density difference the term diffuses for one pair, the sign of rho_i - rho_j:
/// Molteni's total one, or Fourtakas' dynamic one ([`hydrostatic_difference`] added); `r` is
/// rho/rho0 of each particle.
#[inline(always)]
pub fn diffused_difference(form: Form, rho_i: f64, rho_j: f64, r_i: f64, r_j: f64, rho0: f64, q: f64) -> f64 {
    let d = rho_i - rho_j;
    match form {
        Form::Molteni => d,
        Form::Fourtakas => d + hydrostatic_difference(r_i, r_j, rho0, q),
    }
}

/// Binomial coefficients of (1 + x)^(1/7): the odd ones, for (1+x)^(1/7) - (1-x)^(1/7).
const A7: f64 = 1.0 / 7.0;
const C3: f64 = A7 * (A7 - 1.0) * (A7 - 2.0) / 6.0;
const C5: f64 = C3 * (A7 - 3.0) * (A7 - 4.0) / 20.0;
const C7: f64 = C5 * (A7 - 5.0) * (A7 - 6.0) / 42.0;
const C9: f64 = C7 * (A7 - 7.0) * (A7 - 8.0) / 72.0;

/// rho^H_j - rho^H_i of the module text, from r = rho/rho0 of both particles and
/// q = (P_j - P_i)/(2B): rho0 [(s + q)^(1/7) - (s - q)^(1/7)] with s = (r_i^7 + r_j^7)/2,
/// written s^(1/7) [(1 + x)^(1/7) - (1 - x)^(1/7)], x = q/s: s^(1/7) by two Newton steps from
/// (r_i + r_j)/2 (relative error below 1e-15 for density differences of a few %) and the bracket
/// by its odd series to x^9 (error below 1e-13 for |x| <= 0.1; beyond, powf). Two powf per pair
/// made the term 5x the cost of the molteni form. Exactly antisymmetric: s and the mean are
/// symmetric in i, j and the series is odd in x (x^2 is the same either way), as is the powf
/// difference.
#[inline(always)]
pub fn hydrostatic_difference(r_i: f64, r_j: f64, rho0: f64, q: f64) -> f64 {
    let p7 = |r: f64| {
        let r2 = r * r;
        r2 * r2 * r2 * r
    };
    let s = 0.5 * (p7(r_i) + p7(r_j));
    let x = q / s;
    if x.abs() > 0.1 || s <= 0.0 {
        return rho0 * ((s + q).max(0.0).powf(A7) - (s - q).max(0.0).powf(A7));
    }
    let mut y = 0.5 * (r_i + r_j);
    for _ in 0..2 {
        let y6 = {
            let y2 = y * y;
            y2 * y2 * y2
        };
        y -= (y6 * y - s) / (7.0 * y6);
    }
    let x2 = x * x;
    rho0 * y * (2.0 * x * (A7 + x2 * (C3 + x2 * (C5 + x2 * (C7 + x2 * C9)))))
}

impl SphDelta {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let form = match a.choice("delta-SPH form", &["molteni", "fourtakas"])? {
            0 => Form::Molteni,
            _ => Form::Fourtakas,
        };
        let mut kernel = Kernel::Lucy;
        let mut g = None;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "kernel" => kernel = super::sph::kernel_choice(&mut a)?,
                "g" => {
                    if form == Form::Molteni {
                        return Err(a.error_at(w, "keyword `g` applies to the fourtakas form only (molteni diffuses the whole density difference)", "fourtakas only"));
                    }
                    g = Some([a.f64("gx")?, a.f64("gy")?, a.f64("gz")?]);
                }
                _ => return Err(a.unknown_keyword(w, &["kernel", "g"])),
            }
        }
        if form == Form::Fourtakas && g.is_none() {
            return Err(Diagnostic::at(cmd.span, "the fourtakas form needs the gravity vector: add `g gx gy gz` (the fix gravity acceleration, e.g. g 0 -9.81 0)", "no gravity given").with_help(format!("syntax: {SYNTAX}")));
        }
        Ok(SphDelta { form, kernel, g: g.unwrap_or([0.0; 3]), types: TaitTypes::default(), pairs: PairTable::empty(), cutsq: vec![], derived: PerTypePair::default(), n: 0, dim3: true })
    }
}

impl SphKernel for SphDelta {
    /// a = rho, b = rho/rho0 (0 for a type without rho0).
    #[inline(always)]
    fn pack(&self, input: &PairInput, i: usize) -> Packed {
        let a = input.atoms;
        let rho0 = self.types.rho0.get(a.typ[i]).copied().unwrap_or(0.0);
        let r = if rho0 > 0.0 { a.rho[i] / rho0 } else { 0.0 };
        Packed { x: a.x[i], v: [0.0; 3], a: a.rho[i], b: r }
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        &self.cutsq[ti * (self.n + 1)..(ti + 1) * (self.n + 1)]
    }
    #[inline(always)]
    fn pair_lanes<const D: usize>(&self, input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>) -> SphContribution<D> {
        let d: [(Support, f64, f64, f64); LANES] = self.derived.batch(ti, &b.tj);
        let sup = SupportLanes::gather(|l| d[l].0);
        let wfd = self.kernel.wfd_lanes(&b.r, &sup, self.dim3);
        let diff: L = match self.form {
            Form::Molteni => lanes(|l| pi.a - b.a[l]),
            Form::Fourtakas => {
                // g . x_ij
                let gdel = lanes(|l| (0..D).fold(0.0, |s, k| s + self.g[k] * b.del[k][l]));
                lanes(|l| diffused_difference(Form::Fourtakas, pi.a, b.a[l], pi.b, b.b[l], d[l].2, d[l].3 * gdel[l]))
            }
        };
        let k = lanes(|l| d[l].1 * diff[l] * wfd[l]);
        let vol_i = input.type_mass[ti] / pi.a;
        SphContribution { drho_i: lanes(|l| k[l] * (b.m[l] / b.a[l])), drho_j: lanes(|l| -k[l] * vol_i), ..SphContribution::default() }
    }
    /// Only drho/dt.
    fn rates(&self) -> [Option<Rate>; 2] {
        [Some(Rate::Density), None]
    }
}

impl PairStyle for SphDelta {
    fn style(&self) -> &str {
        "dmhs/sph/delta"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = COEFF_SYNTAX;
        let rho0 = args.positive_f64("rho0")?;
        let c0 = args.positive_f64("c0 (sound speed)")?;
        // (0, 1]: 0 is no diffusion (leave the style out); above 1 the diffusion number
        // delta h c0 dt/h^2 exceeds the acoustic CFL number c0 dt/h, and the literature's
        // values are 0.1 (Molteni & Colagrossi, Antuono, DualSPHysics' default)
        let delta = args.f64_where("delta (diffusion coefficient)", "in (0, 1]", |x| x > 0.0 && x <= 1.0)?;
        let h = args.positive_f64("h (kernel support)")?;
        args.finish()?;
        self.pairs.put_range(ilo, ihi, jlo, jhi, (delta, h)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        self.types.set(ilo, ihi, rho0, c0);
        Ok(())
    }
    fn init_sim(&mut self, setup: &PairSetup) -> Result<(), String> {
        super::sph::check_setup(setup, self.style())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        // alone it would integrate a density nothing else changes: it must overlay a density style
        let Some(active) = active else {
            return Err("pair dmhs/sph/delta only adds density diffusion to an SPH density style: use it under pair_style hybrid/overlay with sph/taitwater or sph/taitwater/morris".into());
        };
        // only the assigned pairs need coefficients (hybrid/overlay assigns exactly those given)
        self.pairs.check_all(ntypes, Some(active), "dmhs/sph/delta")?;
        self.pairs.grow(ntypes)?;
        self.types.grow(ntypes);
        self.n = ntypes;
        // rho0 and c0 are per type I of a pair_coeff (as in the Tait styles)
        for i in 1..=ntypes {
            for j in 1..=ntypes {
                if active[i * (ntypes + 1) + j] && self.pairs.is_set(i, j) && self.types.rho0[i] == 0.0 {
                    return Err(format!("pair dmhs/sph/delta: type {i} has no rho0 and c0 (they are set per type I of pair_coeff I J: give a pair_coeff with {i} in its first range)"));
                }
            }
        }
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, Some(active), |p| p.1)?;
        let (pairs, t) = (&self.pairs, &self.types);
        self.derived = PerTypePair::new(ntypes, |i, j| {
            if i == 0 || j == 0 || !pairs.is_set(i, j) {
                return (Support::default(), 0.0, 0.0, 0.0);
            }
            let (delta, h) = *pairs.get(i, j);
            let c0 = 0.5 * (t.c0[i] + t.c0[j]);
            let rho0 = 0.5 * (t.rho0[i] + t.rho0[j]);
            // delta h_s c0 psi . grad W with h_s = h/2 and psi's factor 2: delta h c0 per unit wfd
            (Support::new(h), delta * h * c0, rho0, -3.5 / (c0 * c0))
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
        compute_sph(self, input, out);
        Tally::default()
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        let form = match self.form {
            Form::Molteni => "molteni".to_string(),
            Form::Fourtakas => format!("fourtakas, g {} {} {}", self.g[0], self.g[1], self.g[2]),
        };
        let mut s = format!("dmhs/sph/delta ({form}, kernel {})", self.kernel.name());
        for i in 1..=self.n {
            if self.types.rho0[i] > 0.0 {
                s += &format!("\n    type {i}: rho0 {} c0 {}", self.types.rho0[i], self.types.c0[i]);
            }
        }
        s
    }
    fn diffuses_density(&self) -> Option<Vec<f64>> {
        Some(self.types.rho0.clone())
    }
    /// delta h_s c0 = delta h c0 / 2 of the pair t-t: D_i is kappa times Brookshaw's SPH
    /// Laplacian of rho (2 sum_j V_j (rho_i - rho_j) wfd).
    fn density_diffusivity(&self, t: usize) -> f64 {
        if t == 0 || t > self.pairs.n || !self.pairs.is_set(t, t) || t >= self.types.c0.len() {
            return 0.0;
        }
        let (delta, h) = *self.pairs.get(t, t);
        0.5 * delta * h * self.types.c0[t]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hydrostatic_difference_is_antisymmetric_and_exact_on_the_tait_column() {
        let (rho0, c0, g) = (1000.0f64, 8.0f64, 9.81f64);
        let b = c0 * c0 * rho0 / 7.0;
        // particles at depths 0.01 and 0.0124 m below the surface, Tait densities of rho0 g depth
        let rho = |depth: f64| rho0 * (1.0 + rho0 * g * depth / b).powf(1.0 / 7.0);
        for (zi, zj) in [(-0.0124f64, -0.01f64), (-0.5, -0.45), (-40.0, -4.0)] {
            let (ri, rj) = (rho(-zi), rho(-zj));
            // g = (0, 0, -g): g . x_ij = -g (z_i - z_j)
            let q = -3.5 / (c0 * c0) * (-g * (zi - zj));
            let h_ji = hydrostatic_difference(ri / rho0, rj / rho0, rho0, q);
            let h_ij = hydrostatic_difference(rj / rho0, ri / rho0, rho0, -q);
            assert_eq!(h_ji.to_bits(), (-h_ij).to_bits());
            // the series and Newton steps against the direct powers
            let s = 0.5 * ((ri / rho0).powi(7) + (rj / rho0).powi(7));
            let direct = rho0 * ((s + q).powf(1.0 / 7.0) - (s - q).powf(1.0 / 7.0));
            assert!((h_ji - direct).abs() <= 1e-12 * direct.abs(), "{zi} {zj}: {h_ji} vs {direct}");
            // the dynamic difference of the column is zero to round-off
            let dyn_ij = diffused_difference(Form::Fourtakas, ri, rj, ri / rho0, rj / rho0, rho0, q);
            assert!(dyn_ij.abs() <= 1e-12 * rho0, "{dyn_ij}");
            assert!((ri - rj) > 1e-3, "the column has a density difference: {}", ri - rj);
            assert_eq!(diffused_difference(Form::Fourtakas, rj, ri, rj / rho0, ri / rho0, rho0, -q).to_bits(), (-dyn_ij).to_bits());
            assert_eq!(diffused_difference(Form::Molteni, ri, rj, 0.0, 0.0, rho0, q), ri - rj);
        }
    }
}
