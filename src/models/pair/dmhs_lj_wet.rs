//! `pair_style dmhs/lj/wet Rc [conc max|mean] [scale adhesion|all] [swell dmax]`,
//! `pair_coeff I J epsilon sigma cth [Rc]`: Lennard-Jones adhesion weakened by water (the
//! cleaning model of Alexiadis 2015: adhesion falls linearly with the water concentration and
//! vanishes at c = cth, 0.5 in the paper).
//!
//! With LJ(s) = 4 eps [(sigma/s)^12 - (sigma/s)^6], s_min = 2^(1/6) sigma, the pair's
//! concentration c_ij (`conc max`: max(c_i, c_j), the default, so a wet particle lets go of a dry
//! wall; `conc mean`: (c_i + c_j)/2) and lambda = max(0, 1 - c_ij/cth):
//! - `scale adhesion` (default): E = E_rep + lambda E_att with the split at the minimum
//!   (Weeks-Chandler-Andersen): E_rep = LJ(s) + eps for s < s_min (0 beyond), E_att = -eps for
//!   s < s_min and LJ(s) beyond. The repulsive core stays whole (wet particles still do not
//!   overlap); the attraction, and only it, goes linearly to 0 at cth.
//! - `scale all`: E = lambda LJ(s) (the whole potential: eps_eff = lambda eps).
//!
//! `pair_modify shift yes` subtracts LJ(Rc) from the attractive part.
//! Swelling (`swell dmax`, with `fix dmhs/swell`): s = r - (g_i + g_j), the distance between the
//! swollen surfaces, where g = r_i - r0_i is each particle's radius growth capped at dmax; the
//! cutoff is Rc + g_i + g_j and the neighbour cutoff Rc + 2 dmax (as LAMMPS' lj/expand shifts
//! the potential by delta). Without `swell`, s = r.
//! c_i = w_i rho_i / m_i (Eq 27, see crate::engine::water); particles without water have c = 0.
//! Unset I,J pairs mix epsilon, sigma and Rc as lj/cut does (`pair_modify mix`), and cth as the
//! arithmetic mean.

use super::{compute_central, CentralKernel, PairInput, PairModify, PairOutput, PairStyle, Tally, TypeTable};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style dmhs/lj/wet Rc [conc max|mean] [scale adhesion|all] [swell dmax]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J epsilon sigma cth [Rc]  (cth: concentration at which adhesion vanishes, > 0)";

#[derive(Clone, Copy, Debug, Default)]
struct Coeff {
    set: bool,
    epsilon: f64,
    sigma: f64,
    cth: f64,
    cut: f64,
}

/// What the kernel needs per type pair.
#[derive(Clone, Copy, Debug, Default)]
pub struct Derived {
    on: bool,
    epsilon: f64,
    sigma: f64,
    inv_cth: f64,
    cut: f64,
    /// s_min^2 = 2^(1/3) sigma^2
    rminsq: f64,
    /// LJ(Rc) with pair_modify shift, else 0
    offset: f64,
    /// The style's `conc max` and `scale all` settings.
    conc_max: bool,
    scale_all: bool,
}

/// What the kernel reads of each atom: its water concentration and its (capped) radius growth.
#[derive(Clone, Copy, Debug, Default)]
pub struct Wet {
    conc: f64,
    growth: f64,
}

pub struct LjWet {
    cut_global: f64,
    conc_max: bool,
    scale_all: bool,
    dmax: Option<f64>,
    coeff: TypeTable<Coeff>,
    derived: TypeTable<Derived>,
}

impl LjWet {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<LjWet> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let cut_global = a.positive_f64("the global cutoff Rc")?;
        let (mut conc_max, mut scale_all, mut dmax) = (true, false, None);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "conc" => conc_max = a.choice("pair concentration", &["max", "mean"])? == 0,
                "scale" => scale_all = a.choice("what the water weakens", &["adhesion", "all"])? == 1,
                "swell" => dmax = Some(a.non_negative_f64("dmax (largest radius growth the interaction follows)")?),
                _ => return Err(a.unknown_keyword(w, &["conc", "scale", "swell"])),
            }
        }
        Ok(LjWet { cut_global, conc_max, scale_all, dmax, coeff: TypeTable::empty(), derived: TypeTable::empty() })
    }
}

/// The pair's force over r (force on i = fpair (x_i - x_j)) and energy at distance r, for
/// surface distance s = r - delta and weakening factor lambda.
#[inline]
fn eval(p: &Derived, r: f64, s: f64, lambda: f64, scale_all: bool) -> (f64, f64) {
    let s2inv = 1.0 / (s * s);
    let sr6 = p.sigma * p.sigma * s2inv;
    let sr6 = sr6 * sr6 * sr6;
    let lj = 4.0 * p.epsilon * (sr6 * sr6 - sr6);
    // -dLJ/ds
    let fs = 24.0 * p.epsilon * (2.0 * sr6 * sr6 - sr6) / s;
    let (f, e) = if scale_all {
        (lambda * fs, lambda * (lj - p.offset))
    } else if s * s < p.rminsq {
        (fs, lj + p.epsilon - lambda * (p.epsilon + p.offset))
    } else {
        (lambda * fs, lambda * (lj - p.offset))
    };
    (f / r, e)
}

impl CentralKernel for LjWet {
    type Params = Derived;
    type Site = Wet;
    /// Concentrations and capped growths of owned atoms and ghosts.
    fn sites(&self, input: &PairInput) -> Vec<Wet> {
        let a = input.atoms;
        let nall = a.nall();
        let conc = |i: usize| match crate::engine::water::water(a) {
            Some(w) if a.features.sph => crate::engine::water::conc_of(w[i], a.rho[i], input.type_mass[a.typ[i]]),
            _ => 0.0,
        };
        let growth = match (self.dmax, a.field(crate::engine::fields::GROWTH)) {
            (Some(dmax), Some(k)) => Some((dmax, &a.extra[k].data[..nall])),
            _ => None,
        };
        (0..nall).map(|i| Wet { conc: conc(i), growth: growth.map(|(dmax, g)| g[i].clamp(0.0, dmax)).unwrap_or(0.0) }).collect()
    }
    #[inline(always)]
    fn row(&self, ti: usize) -> &[Derived] {
        self.derived.row(ti)
    }
    /// The cutoff follows the swollen surfaces: Rc + g_i + g_j.
    #[inline(always)]
    fn cutsq(p: &Derived, si: &Wet, sj: &Wet) -> f64 {
        let rc = p.cut + (si.growth + sj.growth);
        if p.on { rc * rc } else { 0.0 }
    }
    #[inline(always)]
    fn eval<const EFLAG: bool>(p: &Derived, rsq: f64, factor: f64, si: &Wet, sj: &Wet) -> (f64, f64) {
        let r = rsq.sqrt();
        let delta = si.growth + sj.growth;
        let cij = if p.conc_max { si.conc.max(sj.conc) } else { 0.5 * (si.conc + sj.conc) };
        let lambda = (1.0 - cij * p.inv_cth).max(0.0);
        let (fpair, e) = eval(p, r, r - delta, lambda, p.scale_all);
        (factor * fpair, factor * e)
    }
}

impl PairStyle for LjWet {
    fn style(&self) -> &str {
        "dmhs/lj/wet"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.coeff.grow(ihi.max(jhi)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        args.syntax = COEFF_SYNTAX;
        let epsilon = args.non_negative_f64("epsilon")?;
        let sigma = args.positive_f64("sigma")?;
        let cth = args.positive_f64("cth (concentration at which adhesion vanishes)")?;
        let cut = if args.is_empty() { self.cut_global } else { args.positive_f64("the cutoff Rc")? };
        args.finish()?;
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.coeff.set(i, j, Coeff { set: true, epsilon, sigma, cth, cut });
            }
        }
        Ok(())
    }
    fn init(&mut self, ntypes: usize, modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.coeff.grow(ntypes)?;
        let mut derived = TypeTable::new(ntypes)?;
        for i in 1..=ntypes {
            for j in i..=ntypes {
                if active.map(|a| !a[i * (ntypes + 1) + j]).unwrap_or(false) {
                    continue;
                }
                let mut c = *self.coeff.get(i, j);
                if !c.set {
                    let (ci, cj) = (self.coeff.get(i, i), self.coeff.get(j, j));
                    if i == j || !ci.set || !cj.set {
                        return Err(format!("pair dmhs/lj/wet coefficients for types {i} {j} are not set"));
                    }
                    c.epsilon = modify.mix.energy(ci.epsilon, cj.epsilon, ci.sigma, cj.sigma);
                    c.sigma = modify.mix.distance(ci.sigma, cj.sigma);
                    c.cut = modify.mix.distance(ci.cut, cj.cut);
                    c.cth = 0.5 * (ci.cth + cj.cth);
                }
                let offset = if modify.shift {
                    let r6 = (c.sigma / c.cut).powi(6);
                    4.0 * c.epsilon * (r6 * r6 - r6)
                } else {
                    0.0
                };
                let d = Derived {
                    on: true,
                    epsilon: c.epsilon,
                    sigma: c.sigma,
                    inv_cth: 1.0 / c.cth,
                    cut: c.cut,
                    rminsq: 2f64.powf(1.0 / 3.0) * c.sigma * c.sigma,
                    offset,
                    conc_max: self.conc_max,
                    scale_all: self.scale_all,
                };
                derived.set(i, j, d);
            }
        }
        self.derived = derived;
        Ok(())
    }
    fn well_stiffness(&self) -> Option<f64> {
        let n = self.derived.n;
        (1..=n).flat_map(|i| (i..=n).map(move |j| (i, j))).map(|(i, j)| self.derived.get(i, j)).filter(|d| d.on).map(|d| super::lj_cut::well_stiffness(d.epsilon, d.sigma, d.cut)).filter(|k| *k > 0.0).reduce(f64::max)
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        let d = self.derived.get(it, jt);
        if d.on { d.cut + 2.0 * self.dmax.unwrap_or(0.0) } else { 0.0 }
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        compute_central(self, input, out.f)
    }
    fn tally_peratom(&mut self, input: &PairInput, out: &mut crate::engine::tally::PerAtomTally) -> Result<(), String> {
        super::peratom::central_peratom(self, input, out);
        Ok(())
    }
    fn needs_type_mass(&self) -> bool {
        // c = w rho / m uses the per-type mass, as the diffusion does
        true
    }
    fn describe(&self) -> String {
        format!(
            "dmhs/lj/wet (conc {}, scale {}{})",
            if self.conc_max { "max" } else { "mean" },
            if self.scale_all { "all" } else { "adhesion" },
            self.dmax.map(|d| format!(", swell {d}")).unwrap_or_default()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair(eps: f64, sigma: f64, cut: f64) -> Derived {
        Derived { on: true, epsilon: eps, sigma, inv_cth: 2.0, cut, rminsq: 2f64.powf(1.0 / 3.0) * sigma * sigma, offset: 0.0, conc_max: true, scale_all: false }
    }

    #[test]
    fn dry_pair_is_plain_lj_and_force_is_minus_the_energy_slope() {
        let p = pair(7e-11, 5e-5, 1.25e-4);
        for &r in &[4.8e-5, 5.6e-5, 6.5e-5, 1.0e-4] {
            let (fpair, e) = eval(&p, r, r, 1.0, false);
            let sr6 = (5e-5f64 / r).powi(6);
            let lj = 4.0 * 7e-11 * (sr6 * sr6 - sr6);
            assert!((e - lj).abs() < 1e-12 * 7e-11, "r={r}: {e} vs {lj}");
            for lam in [1.0, 0.6, 0.0] {
                let h = 1e-10;
                let (_, ep) = eval(&p, r + h, r + h, lam, false);
                let (_, em) = eval(&p, r - h, r - h, lam, false);
                let (fp, _) = eval(&p, r, r, lam, false);
                assert!((fp * r + (ep - em) / (2.0 * h)).abs() < 1e-6 * 7e-11 / 5e-5, "r={r} lambda={lam}");
            }
            let _ = fpair;
        }
    }

    #[test]
    fn adhesion_falls_linearly_and_the_core_stays() {
        let p = pair(7e-11, 5e-5, 1.25e-4);
        let r = 7e-5; // beyond the minimum: attractive
        let (f1, _) = eval(&p, r, r, 1.0, false);
        assert!(f1 < 0.0);
        for c in [0.0, 0.1, 0.25, 0.4, 0.5, 0.7] {
            let lambda = (1.0 - c * p.inv_cth).max(0.0);
            let (f, _) = eval(&p, r, r, lambda, false);
            assert!((f - f1 * (1.0 - c / 0.5).max(0.0)).abs() <= 1e-15 * f1.abs(), "c={c}");
        }
        // the repulsive core does not weaken with `scale adhesion`, but does with `scale all`
        let r = 4.9e-5;
        assert_eq!(eval(&p, r, r, 0.0, false).0, eval(&p, r, r, 1.0, false).0);
        assert_eq!(eval(&p, r, r, 0.0, true).0, 0.0);
    }
}
