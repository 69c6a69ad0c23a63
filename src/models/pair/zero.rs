//! `pair_style zero Rc [nocoeff]` — no forces, but a neighbour list with cutoff Rc (as LAMMPS).

use super::{PairInput, PairModify, PairOutput, PairStyle, Tally, TypeTable};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style zero Rc [nocoeff] [full]";

#[derive(Clone, Debug)]
pub struct PairZero {
    cut_global: f64,
    nocoeff: bool,
    cut: TypeTable<Option<f64>>,
}

impl PairZero {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<PairZero> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let cut_global = a.non_negative_f64("the cutoff Rc")?;
        let mut nocoeff = false;
        while let Some(w) = a.peek() {
            match w.text.as_str() {
                "nocoeff" => nocoeff = true,
                "full" => {}
                _ => return Err(a.unknown_keyword(w, &["nocoeff", "full"])),
            }
            a.skip(1);
        }
        Ok(PairZero { cut_global, nocoeff, cut: TypeTable::empty() })
    }
}

impl PairStyle for PairZero {
    fn style(&self) -> &str {
        "zero"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.cut.grow(ihi.max(jhi)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        let c = if !self.nocoeff && !args.is_empty() { args.non_negative_f64("the cutoff Rc")? } else { self.cut_global };
        if !self.nocoeff {
            args.finish()?;
        }
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.cut.set(i, j, Some(c));
            }
        }
        Ok(())
    }
    fn init(&mut self, ntypes: usize, modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        let mut t = TypeTable::new(ntypes)?;
        for i in 1..=ntypes {
            for j in i..=ntypes {
                if let Some(a) = active {
                    if !a[i * (ntypes + 1) + j] {
                        continue;
                    }
                }
                let get = |a: usize, b: usize| if a <= self.cut.n && b <= self.cut.n { *self.cut.get(a, b) } else { None };
                let c = match get(i, j) {
                    Some(c) => c,
                    None => match (get(i, i), get(j, j)) {
                        (Some(a), Some(b)) if i != j => modify.mix.distance(a, b),
                        _ => return Err(format!("pair zero coefficients for types {i} {j} are not set")),
                    },
                };
                t.set(i, j, Some(c));
            }
        }
        self.cut = t;
        Ok(())
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.cut.get(it, jt).unwrap_or(0.0)
    }
    fn compute(&mut self, _input: &PairInput, _out: &mut PairOutput) -> Tally {
        Tally::default()
    }
    fn tally_peratom(&mut self, _input: &PairInput, _out: &mut crate::engine::tally::PerAtomTally) -> Result<(), String> {
        Ok(())
    }
    /// LAMMPS' PairZero::single: no energy, no force.
    fn single_extra(&self) -> Option<usize> {
        Some(0)
    }
    fn single(&self, _input: &PairInput, _i: usize, _j: usize, _rsq: f64, _factor_coul: f64, _factor_lj: f64) -> Result<super::Single, String> {
        Ok(super::Single::default())
    }
}
