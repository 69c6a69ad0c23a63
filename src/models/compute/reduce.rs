//! `compute ID group reduce mode input1 input2 ...`: sum/min/max/ave/sumsq/avesq/sumabs/aveabs
//! of per-atom quantities over a group; a scalar for one input, a vector for several.

use super::{property::Field, Compute};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID group reduce sum|min|max|ave|sumsq|avesq|sumabs|aveabs input1 input2 ...  (x vx fx ... c_ID c_ID[N])";

/// LAMMPS' initial value for min/max reductions (also the result for an empty group).
const BIG: f64 = 1.0e20;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Sum,
    Min,
    Max,
    Ave,
    SumSq,
    AveSq,
    SumAbs,
    AveAbs,
}

#[derive(Clone, Debug)]
enum Input {
    Attr(Field),
    /// per-atom compute and its column (0-based; `None` for a per-atom vector)
    Compute(String, Option<usize>),
}

pub struct ComputeReduce {
    id: String,
    groupbit: u32,
    mode: Mode,
    inputs: Vec<Input>,
}

impl ComputeReduce {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, world: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mode = match a.choice("reduction mode", &["sum", "min", "max", "ave", "sumsq", "avesq", "sumabs", "aveabs"])? {
            0 => Mode::Sum,
            1 => Mode::Min,
            2 => Mode::Max,
            3 => Mode::Ave,
            4 => Mode::SumSq,
            5 => Mode::AveSq,
            6 => Mode::SumAbs,
            _ => Mode::AveAbs,
        };
        let mut inputs = Vec::new();
        while let Some(w) = a.peek() {
            a.skip(1);
            let t = w.text.as_str();
            if let Some(rest) = t.strip_prefix("c_") {
                let (cid, col) = match rest.find('[') {
                    Some(k) if rest.ends_with(']') => {
                        let n: usize = rest[k + 1..rest.len() - 1].parse().map_err(|_| a.error_at(w, format!("bad column index in `{t}`"), "expected c_ID[N]"))?;
                        (&rest[..k], Some(n))
                    }
                    _ => (rest, None),
                };
                let c = world.compute(cid).ok_or_else(|| a.error_at(w, format!("compute `{cid}` does not exist"), "unknown compute"))?;
                let cols = c.peratom_cols().ok_or_else(|| a.error_at(w, format!("compute `{cid}` does not compute per-atom values"), "not per-atom"))?;
                let col = match col {
                    None if cols == 1 => None,
                    None => return Err(a.error_at(w, format!("compute `{cid}` has {cols} per-atom columns: pick one with c_{cid}[N]"), "needs a column")),
                    Some(n) if n >= 1 && n <= cols => Some(n - 1),
                    Some(n) => return Err(a.error_at(w, format!("column {n} is out of range 1..{cols}"), "bad column")),
                };
                inputs.push(Input::Compute(cid.to_string(), col));
            } else if t.starts_with("f_") || t.starts_with("v_") || t.starts_with("d_") || t.starts_with("i_") {
                return Err(a.error_at(w, format!("reduce input `{t}` is not supported yet (only attributes and per-atom computes)"), "not supported"));
            } else if ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"].contains(&t) || Field::parse(t).is_some() {
                let f = Field::parse(t).unwrap();
                f.check(world.state).map_err(|e| a.error_at(w, e, "not available"))?;
                inputs.push(Input::Attr(f));
            } else {
                return Err(a.error_at(w, format!("unknown reduce input `{t}`"), "expected an attribute or c_ID"));
            }
        }
        if inputs.is_empty() {
            return Err(a.missing("an input"));
        }
        Ok(ComputeReduce { id, groupbit, mode, inputs })
    }

    fn reduce_one(&self, w: &World, input: &Input) -> Result<f64, String> {
        let a = &w.state.atoms;
        let values: Vec<f64> = match input {
            Input::Attr(f) => (0..a.nlocal).filter(|&i| a.mask[i] & self.groupbit != 0).map(|i| f.value(w.state, i)).collect(),
            Input::Compute(cid, col) => {
                let p = w.compute(cid).ok_or_else(|| format!("compute `{cid}` does not exist"))?.peratom(w)?;
                let c = col.unwrap_or(0);
                (0..a.nlocal).filter(|&i| a.mask[i] & self.groupbit != 0).map(|i| p.get(i, c)).collect()
            }
        };
        let n = values.len() as f64;
        let sum = |g: fn(f64) -> f64| values.iter().fold(0.0, |s, &v| s + g(v));
        Ok(match self.mode {
            Mode::Sum => sum(|v| v),
            Mode::SumSq => sum(|v| v * v),
            Mode::SumAbs => sum(f64::abs),
            Mode::Min => values.iter().fold(BIG, |m, &v| if v < m { v } else { m }),
            Mode::Max => values.iter().fold(-BIG, |m, &v| if v > m { v } else { m }),
            Mode::Ave | Mode::AveSq | Mode::AveAbs => {
                let s = match self.mode {
                    Mode::Ave => sum(|v| v),
                    Mode::AveSq => sum(|v| v * v),
                    _ => sum(f64::abs),
                };
                if n > 0.0 { s / n } else { s }
            }
        })
    }
}

impl Compute for ComputeReduce {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "reduce"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        if self.inputs.len() != 1 {
            return Err(format!("compute {} reduces {} inputs: it is a vector, use c_{}[N]", self.id, self.inputs.len(), self.id));
        }
        self.reduce_one(w, &self.inputs[0])
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        if self.inputs.len() == 1 {
            return Err(format!("compute {} has a single input: it is a scalar, use c_{}", self.id, self.id));
        }
        self.inputs.iter().map(|inp| self.reduce_one(w, inp)).collect()
    }
    /// Sums are extensive, minima, maxima and averages are not (as LAMMPS).
    fn extensive(&self, _index: Option<usize>) -> bool {
        matches!(self.mode, Mode::Sum | Mode::SumSq | Mode::SumAbs)
    }
}
