//! `pair_style bpm/spring [anharmonic yes|no]` (LAMMPS BPM package): a repulsive spring with
//! velocity damping between particles closer than the cutoff, the contact force of bonded
//! particle models. For r < cut, along del = x_i - x_j:
//!   F = k (cut - r) [+ ka (cut - r)^3 with `anharmonic yes`] - gamma (del . dv / r) w,
//!   w = 1 - (r^2/cut^2)^4 (the damping fades out at the cutoff),
//! times the special-bond lj weight (a pair of weight 0, e.g. bonded with special_bonds lj 0 1 1,
//! is skipped). Energy k/2 (cut - r)^2 [+ ka/4 (cut - r)^4], weighted alike (as LAMMPS 22 Jul 2025
//! tallies it; earlier versions tallied 0). `pair_coeff I J k cut gamma [ka]`; unset I,J
//! pairs mix (cut as a distance, k, gamma and ka as energies with the cutoffs as sigmas).

use super::{compute_pairs, PairInput, PairKernel, PairModify, PairOutput, PairResult, PairSetup, PairStyle, Tally, TypeTable};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style bpm/spring [anharmonic yes|no]";

#[derive(Clone, Copy, Debug, Default)]
struct Coeff {
    set: bool,
    k: f64,
    cut: f64,
    gamma: f64,
    ka: f64,
}

#[derive(Clone, Debug)]
pub struct PairBpmSpring {
    anharmonic: bool,
    coeff: TypeTable<Coeff>,
    /// The coefficients of every type pair after mixing (`init`).
    pairs: TypeTable<Coeff>,
}

impl PairBpmSpring {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<PairBpmSpring> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mut anharmonic = false;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "anharmonic" => anharmonic = a.yes_no("anharmonic")?,
                _ => return Err(a.unknown_keyword(w, &["anharmonic"])),
            }
        }
        Ok(PairBpmSpring { anharmonic, coeff: TypeTable::empty(), pairs: TypeTable::empty() })
    }

    fn coeff_syntax(&self) -> &'static str {
        if self.anharmonic { "pair_coeff I J k cut gamma ka" } else { "pair_coeff I J k cut gamma" }
    }
}

impl PairKernel for PairBpmSpring {
    #[inline]
    fn pair(&self, input: &PairInput, i: usize, j: usize, del: [f64; 3], rsq: f64, factor: f64) -> Option<PairResult> {
        if factor == 0.0 {
            return None;
        }
        let a = input.atoms;
        let c = self.pairs.get(a.typ[i], a.typ[j]);
        let cutsq = c.cut * c.cut;
        if !(rsq < cutsq) {
            return None;
        }
        let r = rsq.sqrt();
        let rinv = 1.0 / r;
        let dr = c.cut - r;
        let mut fpair = c.k * dr;
        let mut energy = 0.5 * c.k * dr * dr;
        if self.anharmonic {
            fpair += c.ka * dr * dr * dr;
            energy += 0.25 * c.ka * dr * dr * dr * dr;
        }
        let mut smooth = rsq / cutsq;
        smooth *= smooth;
        smooth *= smooth;
        smooth = 1.0 - smooth;
        let (vi, vj) = (a.v[i], a.v[j]);
        let dv = [vi[0] - vj[0], vi[1] - vj[1], vi[2] - vj[2]];
        let dot = del[0] * dv[0] + del[1] * dv[1] + del[2] * dv[2];
        fpair -= c.gamma * dot * smooth * rinv;
        fpair *= factor * rinv;
        Some(PairResult { f: [del[0] * fpair, del[1] * fpair, del[2] * fpair], energy: factor * energy, ..PairResult::default() })
    }
}

impl PairStyle for PairBpmSpring {
    fn style(&self) -> &str {
        "bpm/spring"
    }

    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.coeff.grow(ihi.max(jhi)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        args.syntax = self.coeff_syntax();
        let k = args.f64("k")?;
        let cut = args.positive_f64("the cutoff cut")?;
        let gamma = args.f64("gamma")?;
        let ka = if self.anharmonic { args.f64("ka")? } else { 0.0 };
        args.finish()?;
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.coeff.set(i, j, Coeff { set: true, k, cut, gamma, ka });
            }
        }
        Ok(())
    }

    fn init_sim(&mut self, setup: &PairSetup) -> Result<(), String> {
        if !setup.comm_vel {
            return Err("pair bpm/spring requires ghost atoms store velocity: add `comm_modify vel yes`".into());
        }
        Ok(())
    }

    fn init(&mut self, ntypes: usize, modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.coeff.grow(ntypes)?;
        let mut pairs = TypeTable::new(ntypes)?;
        for i in 1..=ntypes {
            for j in i..=ntypes {
                if active.is_some_and(|a| !a[i * (ntypes + 1) + j]) {
                    continue;
                }
                let mut c = *self.coeff.get(i, j);
                if !c.set {
                    let (ci, cj) = (*self.coeff.get(i, i), *self.coeff.get(j, j));
                    if i == j || !ci.set || !cj.set {
                        return Err(format!("pair bpm/spring coefficients for types {i} {j} are not set"));
                    }
                    let mix = |a: f64, b: f64| modify.mix.energy(a, b, ci.cut, cj.cut);
                    c = Coeff { set: false, k: mix(ci.k, cj.k), cut: modify.mix.distance(ci.cut, cj.cut), gamma: mix(ci.gamma, cj.gamma), ka: mix(ci.ka, cj.ka) };
                }
                pairs.set(i, j, c);
            }
        }
        self.pairs = pairs;
        Ok(())
    }

    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.pairs.get(it, jt).cut
    }

    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        compute_pairs(self, input, out, None)
    }

    fn contact_stiffness(&self) -> Option<f64> {
        let n = self.pairs.n;
        (1..=n).flat_map(|i| (i..=n).map(move |j| (i, j))).map(|(i, j)| self.pairs.get(i, j).k).filter(|k| *k > 0.0).reduce(f64::max)
    }

    fn describe(&self) -> String {
        let mut s = format!("bpm/spring{}", if self.anharmonic { " anharmonic yes" } else { "" });
        s += &super::pair_lines(self.coeff.n, |i, j| self.coeff.get(i, j).set, |i, j| {
            let c = self.coeff.get(i, j);
            format!("k {} cut {} gamma {}{}", c.k, c.cut, c.gamma, if self.anharmonic { format!(" ka {}", c.ka) } else { String::new() })
        });
        s
    }
}
