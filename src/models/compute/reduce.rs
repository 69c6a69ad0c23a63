//! `compute ID group reduce mode input1 input2 ...`: sum/min/max/ave/sumsq/avesq/sumabs/aveabs
//! of per-atom quantities over a group; a scalar for one input, a vector for several.

use super::{property::Field, Compute};
use crate::engine::state::State;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID group reduce sum|min|max|ave|sumsq|avesq|sumabs|aveabs input1 input2 ...  (x vx fx ... c_ID c_ID[N] c_ID[*]) [inputs peratom|local]";

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
    /// a local compute or fix column (compute bond/local): every row, the group ignored
    Local(super::LocalRef),
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
        // the inputs, then the keywords (`inputs local` decides how c_ID and f_ID are read)
        let mut words = Vec::new();
        while let Some(w) = a.peek().filter(|w| w.text != "inputs" && w.text != "replace") {
            a.skip(1);
            words.push(w);
        }
        let mut local = false;
        while let Some(kw) = a.peek() {
            a.skip(1);
            match kw.text.as_str() {
                "inputs" => local = a.choice("inputs", &["peratom", "local"])? == 1,
                "replace" => return Err(a.error_at(kw, "compute reduce replace is not supported yet", "not supported")),
                _ => return Err(a.unknown_keyword(kw, &["inputs", "replace"])),
            }
        }
        let mut inputs = Vec::new();
        for w in words {
            let t = w.text.as_str();
            if local {
                let refs = super::LocalRef::parse(t, world, None)
                    .ok_or_else(|| a.error_at(w, format!("compute reduce inputs local reads c_ID or f_ID, not `{t}`"), "expected a local compute or fix"))?
                    .map_err(|e| a.error_at(w, e, "not a local value"))?;
                if refs.iter().any(|r| !r.fix && world.compute(&r.id).is_some_and(|c| c.local_needs_variables(r.col.unwrap_or(0)))) {
                    return Err(a.error_at(w, format!("compute reduce of a v_NAME column of a local compute (`{t}`) is not supported yet"), "a variable's column"));
                }
                inputs.extend(refs.into_iter().map(Input::Local));
            } else if is_local(t, world) {
                return Err(a.error_at(w, format!("Compute reduce input `{t}` is local data: add `inputs local`"), "does not calculate per-atom values"));
            } else if let Some(r) = super::PerAtomRef::parse(t, world) {
                inputs.push(Input::PerAtom(r.map_err(|e| a.error_at(w, e, "not a per-atom value"))?));
            } else if t.starts_with("v_") || t.starts_with("d_") || t.starts_with("i_") {
                return Err(a.error_at(w, format!("reduce input `{t}` is not supported yet (only attributes, per-atom computes and fixes)"), "not supported"));
            } else if let Some(f) = Field::parse(t).filter(|_| ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"].contains(&t)) {
                f.check(world.state).map_err(|e| a.error_at(w, e, "not available"))?;
                inputs.push(Input::Attr(f));
            } else if Field::parse(t).is_some() {
                // LAMMPS reads only positions, velocities and forces directly
                return Err(a.error_at(w, format!("Unknown compute reduce keyword: {t} (the attributes it reads directly are x, y, z, vx, vy, vz, fx, fy, fz; for `{t}` define `compute ID group property/atom {t}` and reduce c_ID)"), "expected x, y, z, vx, vy, vz, fx, fy, fz, c_ID or f_ID"));
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
            Input::Local(r) => r.rows(w, None)?.iter().map(|row| r.get(row)).collect(),
        };
        // this rank's reduction, then the ranks' (a distributed run; local rows are whole)
        let state = w.state;
        let ranks = !matches!(input, Input::Local(_));
        let sum = |g: fn(f64) -> f64| values.iter().fold(0.0, |s, &v| s + g(v));
        let across = |mut v: [f64; 2], f: fn(&State, &mut [f64])| {
            if ranks {
                f(state, &mut v);
            }
            v
        };
        Ok(match self.mode {
            Mode::Sum => across([sum(|v| v), 0.0], State::sum_ranks)[0],
            Mode::SumSq => across([sum(|v| v * v), 0.0], State::sum_ranks)[0],
            Mode::SumAbs => across([sum(f64::abs), 0.0], State::sum_ranks)[0],
            Mode::Min => across([values.iter().fold(BIG, |m, &v| if v < m { v } else { m }), 0.0], State::min_ranks)[0],
            Mode::Max => across([values.iter().fold(-BIG, |m, &v| if v > m { v } else { m }), 0.0], State::max_ranks)[0],
            Mode::Ave | Mode::AveSq | Mode::AveAbs => {
                let s = match self.mode {
                    Mode::Ave => sum(|v| v),
                    Mode::AveSq => sum(|v| v * v),
                    _ => sum(f64::abs),
                };
                let [s, n] = across([s, values.len() as f64], State::sum_ranks);
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
    fn reads(&self) -> Vec<(bool, String)> {
        self.inputs
            .iter()
            .filter_map(|inp| match inp {
                Input::Attr(_) => None,
                Input::PerAtom(r) => Some((r.fix, r.id.clone())),
                Input::Local(r) => Some((r.fix, r.id.clone())),
            })
            .collect()
    }
    /// Sums are extensive, minima, maxima and averages are not (as LAMMPS).
    fn extensive(&self, _index: Option<usize>) -> bool {
        matches!(self.mode, Mode::Sum | Mode::SumSq | Mode::SumAbs)
    }
}

/// Whether `name` (c_ID, f_ID, with or without a column) names local data rather than per-atom
/// values: a compute or fix that has local output and no per-atom output.
fn is_local(name: &str, w: &World) -> bool {
    let id = |rest: &str| rest.split('[').next().unwrap_or(rest).to_string();
    if let Some(rest) = name.strip_prefix("c_") {
        w.compute(&id(rest)).is_some_and(|c| c.local_cols().is_some() && c.peratom_cols().is_none())
    } else if let Some(rest) = name.strip_prefix("f_") {
        w.fix(&id(rest)).is_some_and(|f| f.local().is_some() && f.peratom_cols().is_none())
    } else {
        false
    }
}
