//! `pair_style soft Rc` — a cosine hill, E = A [1 + cos(pi r / rc)] for r < rc, used to push
//! overlapping atoms apart. Arithmetic in LAMMPS' pair_soft order; unset cross terms mix A
//! geometrically (always) and rc by the mixing rule.

use super::{compute_central, CentralKernel, PairInput, PairModify, PairOutput, PairStyle, Tally, TypeTable};
use dmhs_parser::{Args, Command, DResult, Word};
use std::f64::consts::PI;

pub const SYNTAX: &str = "pair_style soft Rc";
pub const COEFF_SYNTAX: &str = "pair_coeff I J A [Rc]";

#[derive(Clone, Copy, Debug, Default)]
struct Coeff {
    set: bool,
    prefactor: f64,
    cut: f64,
}

#[derive(Clone, Copy, Debug, Default)]
pub struct Derived {
    cutsq: f64,
    cut: f64,
    prefactor: f64,
}

#[derive(Clone, Debug)]
pub struct Soft {
    cut_global: f64,
    coeff: TypeTable<Coeff>,
    derived: TypeTable<Derived>,
}

impl Soft {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Soft> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let cut_global = a.positive_f64("the global cutoff Rc")?;
        a.finish()?;
        Ok(Soft { cut_global, coeff: TypeTable::empty(), derived: TypeTable::empty() })
    }
}

impl CentralKernel for Soft {
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
        let r = rsq.sqrt();
        let arg = PI * r / p.cut;
        let fpair = if r > 0.0 { factor * p.prefactor * arg.sin() * PI / p.cut / r } else { 0.0 };
        let e = if EFLAG { factor * p.prefactor * (1.0 + arg.cos()) } else { 0.0 };
        (fpair, e)
    }
}

impl PairStyle for Soft {
    fn style(&self) -> &str {
        "soft"
    }

    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.coeff.grow(ihi.max(jhi)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        args.syntax = COEFF_SYNTAX;
        let prefactor = args.f64("A")?;
        let cut = if args.is_empty() { self.cut_global } else { args.positive_f64("the cutoff Rc")? };
        args.finish()?;
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.coeff.set(i, j, Coeff { set: true, prefactor, cut });
            }
        }
        Ok(())
    }

    /// `a`: the prefactor A (an unset cross term is mixed again by `init`, as LAMMPS' init_one).
    fn adapt_get(&self, param: &str, i: usize, j: usize) -> Option<f64> {
        (param == "a" && i.max(j) <= self.coeff.n).then(|| self.coeff.get(i, j).prefactor)
    }
    fn adapt_set(&mut self, param: &str, i: usize, j: usize, value: f64) -> bool {
        if param != "a" || i.max(j) > self.coeff.n {
            return false;
        }
        let c = *self.coeff.get(i, j);
        self.coeff.set(i, j, Coeff { prefactor: value, ..c });
        true
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
                        return Err(format!("pair soft coefficients for types {i} {j} are not set"));
                    }
                    c.prefactor = (ci.prefactor * cj.prefactor).sqrt();
                    c.cut = modify.mix.distance(ci.cut, cj.cut);
                }
                derived.set(i, j, Derived { cutsq: c.cut * c.cut, cut: c.cut, prefactor: c.prefactor });
            }
        }
        self.derived = derived;
        Ok(())
    }

    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.derived.get(it, jt).cut
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

    fn data_coeffs(&self, it: usize) -> Option<String> {
        let c = self.coeff.get(it, it);
        Some(super::lj_cut::fmt17(c.prefactor))
    }

    fn describe(&self) -> String {
        let mut s = format!("soft {}", self.cut_global);
        s += &super::pair_lines(self.coeff.n, |_, _| true, |i, j| {
            let c = self.coeff.get(i, j);
            format!("A {} cut {}{}", c.prefactor, c.cut, if c.set { "" } else { " (mixed)" })
        });
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn soft_force_is_minus_the_energy_slope() {
        let p = Derived { cutsq: 4.0, cut: 2.0, prefactor: 3.0 };
        let (r, h) = (0.7f64, 1e-6);
        let e = |r: f64| Soft::eval::<true>(&p, r * r, 1.0, &(), &()).1;
        let (fpair, e0) = Soft::eval::<true>(&p, r * r, 1.0, &(), &());
        assert!((e0 - 3.0 * (1.0 + (PI * r / 2.0).cos())).abs() < 1e-14);
        let slope = (e(r + h) - e(r - h)) / (2.0 * h);
        assert!((fpair * r + slope).abs() < 1e-8, "{} {}", fpair * r, slope);
        assert_eq!(Soft::eval::<true>(&p, 0.0, 1.0, &(), &()).0, 0.0);
    }
}
