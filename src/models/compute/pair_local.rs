//! `compute ID group pair/local value ... [cutoff type|radius]`: one row per pair of group
//! atoms within the pair style's cutoff of their types (or, with `cutoff radius`, whose spheres
//! overlap), as LAMMPS' compute pair/local, read by `dump local` and `compute reduce`. Values:
//! `dist`, `dx dy dz` (x_i - x_j), and from the pair style's `single` (LAMMPS' Pair::single)
//! `eng`, `force` (r fpair: positive repulsive), `fx fy fz` (the force on i) and `pN` (the
//! style's N-th extra value: pair granular's tangential, rolling and twisting parts, the classic
//! granular styles' tangential force and relative velocities).
//!
//! The pairs are compute property/local's (each once, special pairs of weight 0 left out), in
//! dmhs' list order: LAMMPS' rows come from a list of its own binning, so the same set of pairs
//! in another order, and a pair of owned atoms may be listed from its other atom (dx, fx, the
//! tangential parts change sign with it); a pair with a periodic image comes from the atom
//! LAMMPS lists it from, whose partner is a ghost with the ghost's velocity.

use super::Compute;
use crate::models::pair::PairInput;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "compute ID group pair/local value ... [cutoff type|radius]  (values: dist dx dy dz eng force fx fy fz pN)";

#[derive(Clone, Copy, Debug, PartialEq)]
enum Value {
    Dist,
    Dx(usize),
    Eng,
    Force,
    F(usize),
    /// `pN`, from 0
    Extra(usize),
}

const NAMED: [(&str, Value); 9] = [
    ("dist", Value::Dist),
    ("dx", Value::Dx(0)),
    ("dy", Value::Dx(1)),
    ("dz", Value::Dx(2)),
    ("eng", Value::Eng),
    ("force", Value::Force),
    ("fx", Value::F(0)),
    ("fy", Value::F(1)),
    ("fz", Value::F(2)),
];

pub struct ComputePairLocal {
    id: String,
    groupbit: u32,
    values: Vec<Value>,
    /// `cutoff radius`: pairs that overlap, not within the type cutoff.
    radius_cut: bool,
    /// Some value needs the pair style's single (all but dist and dx dy dz).
    single: bool,
}

impl ComputePairLocal {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mut values = Vec::new();
        while let Some(word) = a.peek() {
            let t = word.text.as_str();
            let v = if let Some((_, v)) = NAMED.iter().find(|(n, _)| *n == t) {
                *v
            } else if let Some(n) = t.strip_prefix('p').filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit())) {
                match n.parse::<usize>() {
                    Ok(n) if n >= 1 => Value::Extra(n - 1),
                    _ => return Err(a.error_at(word, format!("Invalid keyword `{t}` in compute pair/local command"), "pN needs N >= 1")),
                }
            } else {
                break;
            };
            a.skip(1);
            values.push(v);
        }
        if values.is_empty() {
            let mut d = a.missing("a value (dist dx dy dz eng force fx fy fz pN)");
            if let Some(word) = a.peek() {
                let names: Vec<&str> = NAMED.iter().map(|(n, _)| *n).collect();
                d = a.error_at(word, format!("Invalid keyword `{}` in compute pair/local command", word.text), "expected a value");
                if let Some(h) = dmhs_parser::suggest::did_you_mean_help(&word.text, names) {
                    d = d.with_help(h);
                }
            }
            return Err(d);
        }
        let mut radius_cut = false;
        while let Some(word) = a.peek() {
            if word.text != "cutoff" {
                return Err(a.unknown_keyword(word, &["cutoff"]));
            }
            a.skip(1);
            radius_cut = a.choice("cutoff", &["type", "radius"])? == 1;
        }
        if radius_cut && !w.state.atoms.features.sphere {
            return Err(a.error_at(&cmd.name, "Compute pair/local requires atom attribute radius", "needs atom_style sphere"));
        }
        let single = values.iter().any(|v| !matches!(v, Value::Dist | Value::Dx(_)));
        Ok(ComputePairLocal { id, groupbit, values, radius_cut, single })
    }
}

impl Compute for ComputePairLocal {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "pair/local"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn local_cols(&self) -> Option<usize> {
        Some(if self.values.len() == 1 { 0 } else { self.values.len() })
    }
    fn local(&self, w: &World, _ev: Option<&mut dyn dmhs_parser::EvalContext>) -> Result<Vec<Vec<f64>>, String> {
        let s = w.state;
        let a = &s.atoms;
        let list = &s.neighbor.list;
        let pair = match w.pair {
            Some(p) if s.neighbor.cutforce > 0.0 => p,
            _ => return Err(format!("compute pair/local {}: No pair style is defined for compute pair/local", self.id)),
        };
        if self.single {
            let Some(extra) = pair.single_extra().map(|n| n.min(crate::models::pair::MAX_SINGLE_EXTRA)) else {
                return Err(format!("compute pair/local {}: Pair style {} does not support compute pair/local", self.id, pair.style()));
            };
            if let Some(n) = self.values.iter().find_map(|v| match v {
                Value::Extra(n) if *n >= extra => Some(n + 1),
                _ => None,
            }) {
                return Err(format!("compute pair/local {}: Pair style does not have extra field requested by compute pair/local (p{n}; pair style {} has {extra})", self.id, pair.style()));
            }
        }
        super::need_lists(s, self)?;
        let freeze_bit = crate::models::fix::freeze_bit(w.fixes.iter());
        let input = PairInput::of_state(s, freeze_bit, true, false);
        let stride = list.ntypes + 1;
        let mut rows = Vec::new();
        let mut failed = None;
        super::group_pairs_once(s, self.groupbit, |i, j, rsq, level| {
            if failed.is_some() {
                return;
            }
            let inside = if self.radius_cut {
                let radsum = a.radius[i] + a.radius[j];
                rsq < radsum * radsum
            } else {
                rsq < list.cutsq[a.typ[i] * stride + a.typ[j]]
            };
            if !inside {
                return;
            }
            let one = if self.single {
                match pair.single(&input, i, j, rsq, s.special_bonds.coul[level], s.special_bonds.lj[level]) {
                    Ok(one) => one,
                    Err(why) => {
                        failed = Some(why);
                        return;
                    }
                }
            } else {
                Default::default()
            };
            let del = [a.x[i][0] - a.x[j][0], a.x[i][1] - a.x[j][1], a.x[i][2] - a.x[j][2]];
            rows.push(
                self.values
                    .iter()
                    .map(|v| match *v {
                        Value::Dist => rsq.sqrt(),
                        Value::Dx(d) => del[d],
                        Value::Eng => one.eng,
                        Value::Force => rsq.sqrt() * one.fpair,
                        Value::F(d) => del[d] * one.fpair,
                        Value::Extra(n) => one.extra[n],
                    })
                    .collect(),
            );
        });
        match failed {
            Some(why) => Err(format!("compute pair/local {}: {why}", self.id)),
            None => Ok(rows),
        }
    }
}
