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
    /// a per-atom compute or fix column
    PerAtom(super::PerAtomRef),
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
            if let Some(r) = super::PerAtomRef::parse(t, world) {
                inputs.push(Input::PerAtom(r.map_err(|e| a.error_at(w, e, "not a per-atom value"))?));
            } else if t.starts_with("v_") || t.starts_with("d_") || t.starts_with("i_") {
                return Err(a.error_at(w, format!("reduce input `{t}` is not supported yet (only attributes, per-atom computes and fixes)"), "not supported"));
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
            Input::PerAtom(r) => {
                let p = r.values(w)?;
                (0..a.nlocal).filter(|&i| a.mask[i] & self.groupbit != 0).map(|i| r.get(&p, i)).collect()
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
