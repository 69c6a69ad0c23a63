//! `pair_style lj/cut Rc` — the 12-6 Lennard-Jones potential, truncated at Rc:
//! E = 4 eps [(sigma/r)^12 - (sigma/r)^6] (- E(Rc) with `pair_modify shift yes`).
//! Arithmetic in LAMMPS' order (lj1 = 48 eps sigma^12, lj2 = 24 eps sigma^6, ...).

use super::{compute_central, CentralKernel, PairInput, PairModify, PairOutput, PairStyle, Tally, TypeTable};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style lj/cut Rc";
pub const COEFF_SYNTAX: &str = "pair_coeff I J epsilon sigma [Rc]";

#[derive(Clone, Copy, Debug, Default)]
struct Coeff {
    set: bool,
    epsilon: f64,
    sigma: f64,
    cut: f64,
}

#[derive(Clone, Copy, Debug, Default)]
pub struct Derived {
    cutsq: f64,
    lj1: f64,
    lj2: f64,
    lj3: f64,
    lj4: f64,
    offset: f64,
}

#[derive(Clone, Debug)]
pub struct LjCut {
    cut_global: f64,
    coeff: TypeTable<Coeff>,
    derived: TypeTable<Derived>,
}

impl LjCut {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<LjCut> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let cut_global = a.positive_f64("the global cutoff Rc")?;
        a.finish()?;
        Ok(LjCut { cut_global, coeff: TypeTable::empty(), derived: TypeTable::empty() })
    }
}

impl CentralKernel for LjCut {
    type Params = Derived;
    type Site = ();
    fn sites(&self, input: &PairInput) -> Vec<()> {
        vec![(); input.atoms.nall()]
    }
    #[inline(always)]
    fn row(&self, ti: usize) -> &[Derived] {
        self.derived.row(ti)
    }
    #[inline(always)]
    fn cutsq(p: &Derived, _: &(), _: &()) -> f64 {
        p.cutsq
    }
    #[inline(always)]
    fn eval<const EFLAG: bool>(p: &Derived, rsq: f64, factor: f64, _: &(), _: &()) -> (f64, f64) {
        let r2inv = 1.0 / rsq;
        let r6inv = r2inv * r2inv * r2inv;
        let forcelj = r6inv * (p.lj1 * r6inv - p.lj2);
        let fpair = factor * forcelj * r2inv;
        let e = if EFLAG { factor * (r6inv * (p.lj3 * r6inv - p.lj4) - p.offset) } else { 0.0 };
        (fpair, e)
    }
}

impl PairStyle for LjCut {
    fn style(&self) -> &str {
        "lj/cut"
    }

    /// fix adapt's `epsilon` and `sigma` (LAMMPS' PairLJCut::extract); a mixed pair is mixed
    /// again from the adapted pairs of like types at init, as LAMMPS' init_one.
    fn adapt_get(&self, param: &str, i: usize, j: usize) -> Option<f64> {
        let c = (i.max(j) <= self.coeff.n).then(|| self.coeff.get(i, j))?;
        match param {
            "epsilon" => Some(c.epsilon),
            "sigma" => Some(c.sigma),
            _ => None,
        }
    }
    fn adapt_set(&mut self, param: &str, i: usize, j: usize, value: f64) -> bool {
        if i.max(j) > self.coeff.n {
            return false;
        }
        let mut c = *self.coeff.get(i, j);
        match param {
            "epsilon" => c.epsilon = value,
            "sigma" => c.sigma = value,
            _ => return false,
        }
        self.coeff.set(i, j, c);
        true
    }

    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.coeff.grow(ihi.max(jhi)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        args.syntax = COEFF_SYNTAX;
        let epsilon = args.f64("epsilon")?;
        let sigma = args.f64("sigma")?;
        let cut = if args.is_empty() { self.cut_global } else { args.positive_f64("the cutoff Rc")? };
        args.finish()?;
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.coeff.set(i, j, Coeff { set: true, epsilon, sigma, cut });
            }
        }
        Ok(())
    }

    fn init(&mut self, ntypes: usize, modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.coeff.grow(ntypes)?;
        let mut derived = TypeTable::new(ntypes)?;
        for i in 1..=ntypes {
            for j in i..=ntypes {
                if let Some(a) = active {
                    if !a[i * (ntypes + 1) + j] {
                        continue;
                    }
                }
                let mut c = *self.coeff.get(i, j);
                if !c.set {
                    let (ci, cj) = (self.coeff.get(i, i), self.coeff.get(j, j));
                    if i == j || !ci.set || !cj.set {
                        return Err(format!("pair lj/cut coefficients for types {i} {j} are not set"));
                    }
                    c.epsilon = modify.mix.energy(ci.epsilon, cj.epsilon, ci.sigma, cj.sigma);
                    c.sigma = modify.mix.distance(ci.sigma, cj.sigma);
                    c.cut = modify.mix.distance(ci.cut, cj.cut);
                }
                let s = c.sigma;
                let e = c.epsilon;
                let offset = if modify.shift && c.cut > 0.0 {
                    let ratio = s / c.cut;
                    4.0 * e * (ratio.powf(12.0) - ratio.powf(6.0))
                } else {
                    0.0
                };
                derived.set(
                    i,
                    j,
                    Derived {
                        cutsq: c.cut * c.cut,
                        lj1: 48.0 * e * s.powf(12.0),
                        lj2: 24.0 * e * s.powf(6.0),
                        lj3: 4.0 * e * s.powf(12.0),
                        lj4: 4.0 * e * s.powf(6.0),
                        offset,
                    },
                );
                if i != j {
                    // keep the mixed values so write_data and check can show them
                    let mut m = c;
                    m.set = self.coeff.get(i, j).set;
                    self.coeff.set(i, j, Coeff { set: m.set, ..c });
                }
            }
        }
        self.derived = derived;
        Ok(())
    }

    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.derived.get(it, jt).cutsq.sqrt()
    }

    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        compute_central(self, input, out.f)
    }

    fn tally_peratom(&mut self, input: &PairInput, out: &mut crate::engine::tally::PerAtomTally) -> Result<(), String> {
        super::peratom::central_peratom(self, input, out);
        Ok(())
    }
    fn single_extra(&self) -> Option<usize> {
        Some(0)
    }
    fn single(&self, input: &PairInput, i: usize, j: usize, rsq: f64, _factor_coul: f64, factor_lj: f64) -> Result<super::Single, String> {
        let t = &input.atoms.typ;
        Ok(super::central_single(self, t[i], t[j], rsq, factor_lj, &(), &()))
    }

    fn well_stiffness(&self) -> Option<f64> {
        let n = self.coeff.n;
        (1..=n).flat_map(|i| (i..=n).map(move |j| (i, j))).map(|(i, j)| self.coeff.get(i, j)).map(|c| well_stiffness(c.epsilon, c.sigma, c.cut)).filter(|k| *k > 0.0).reduce(f64::max)
    }

    fn data_coeffs(&self, it: usize) -> Option<String> {
        let c = self.coeff.get(it, it);
        Some(format!("{} {}", fmt17(c.epsilon), fmt17(c.sigma)))
    }

    fn describe(&self) -> String {
        let mut s = format!("lj/cut {}", self.cut_global);
        s += &super::pair_lines(self.coeff.n, |_, _| true, |i, j| {
            let c = self.coeff.get(i, j);
            format!("epsilon {} sigma {} cut {}{}", c.epsilon, c.sigma, c.cut, if c.set { "" } else { " (mixed)" })
        });
        s
    }
}

/// V''(r_min) of 4 eps [(sigma/r)^12 - (sigma/r)^6] at r_min = 2^(1/6) sigma: 72 eps/(2^(1/3) sigma^2)
/// = 57.15 eps/sigma^2, the spring of the well; 0 when the cutoff leaves no well (a purely
/// repulsive WCA wall, cut at r_min, has no oscillation) or the result is zero or not finite.
pub fn well_stiffness(epsilon: f64, sigma: f64, cut: f64) -> f64 {
    let k = 72.0 * epsilon / (2f64.cbrt() * sigma * sigma);
    let has_well = cut > 2f64.powf(1.0 / 6.0) * sigma.abs() * (1.0 + 1e-9);
    if has_well && k.is_finite() { k.max(0.0) } else { 0.0 }
}

/// Shortest text that reads back to the same double.
pub fn fmt17(x: f64) -> String {
    format!("{x:?}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::pair::MixRule;

    #[test]
    fn lj_values_match_closed_form() {
        let mut lj = LjCut { cut_global: 2.5, coeff: TypeTable::new(1).unwrap(), derived: TypeTable::new(1).unwrap() };
        lj.coeff.set(1, 1, Coeff { set: true, epsilon: 1.0, sigma: 1.0, cut: 2.5 });
        lj.init(1, &PairModify { mix: MixRule::Geometric, shift: true }, None).unwrap();
        let r: f64 = 1.1;
        let (fpair, e) = LjCut::eval::<true>(lj.derived.get(1, 1), r * r, 1.0, &(), &());
        let f_exact = 24.0 * (2.0 * r.powi(-13) - r.powi(-7));
        assert!((fpair * r - f_exact).abs() < 1e-12);
        let e_cut = 4.0 * (2.5f64.powi(-12) - 2.5f64.powi(-6));
        assert!((e - (4.0 * (r.powi(-12) - r.powi(-6)) - e_cut)).abs() < 1e-12);
        assert!(2.5 * 2.5 >= LjCut::cutsq(lj.derived.get(1, 1), &(), &()));
    }

    #[test]
    fn geometric_mixing() {
        let mut lj = LjCut { cut_global: 2.5, coeff: TypeTable::new(2).unwrap(), derived: TypeTable::new(2).unwrap() };
        lj.coeff.set(1, 1, Coeff { set: true, epsilon: 1.0, sigma: 1.0, cut: 2.5 });
        lj.coeff.set(2, 2, Coeff { set: true, epsilon: 4.0, sigma: 2.0, cut: 5.0 });
        lj.init(2, &PairModify::default(), None).unwrap();
        assert_eq!(lj.coeff.get(1, 2).epsilon, 2.0);
        assert_eq!(lj.coeff.get(1, 2).sigma, 2f64.sqrt());
        assert_eq!(lj.cutoff(1, 2), (2.5f64 * 5.0).sqrt());
    }
}
