//! `fix ID group vector Nevery value ... [nmax N]`: every Nevery steps (multiples of Nevery,
//! the setup of a run included) the global values `c_ID`, `c_ID[I]`, `f_ID`, `f_ID[I]` and
//! equal-style `v_name` are stored as one more element of a global vector (one value) or one
//! more row of a global array (several), as LAMMPS' fix vector; with `nmax` only the last N are
//! kept. The group is ignored. Read with `f_ID[i]`, `f_ID[i][j]` and the special functions
//! (`trap(f_ID)` integrates a time series).

use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, DResult};

pub const SYNTAX: &str = "fix ID group vector Nevery value1 [value2 ...] [nmax N]  (value: c_ID, c_ID[I], f_ID, f_ID[I], v_name)";

/// One input: a compute's or fix's global scalar or vector element, or an equal-style variable.
enum Value {
    Compute(String, Option<usize>),
    Fix(String, Option<usize>),
    Variable(String),
}

pub struct FixVector {
    id: String,
    groupbit: u32,
    nevery: i64,
    values: Vec<Value>,
    extensive: bool,
    nmax: Option<usize>,
    /// The next step that stores a row.
    nextstep: i64,
    rows: std::collections::VecDeque<Vec<f64>>,
}

impl FixVector {
    pub fn from_lammps(d: FixDef, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(d.args, d.cmd.span, SYNTAX);
        let nevery = a.i64_in("Nevery", 1, i64::MAX)?;
        let mut values = Vec::new();
        let mut extensive = None;
        while let Some(w) = a.peek() {
            let t = w.text.as_str();
            if !(t.starts_with("c_") || t.starts_with("f_") || t.starts_with("v_")) {
                break;
            }
            a.skip(1);
            let rest = &t[2..];
            let (id, index) = super::value::split_index(rest, w, &a)?;
            let (value, ext) = match &t[..2] {
                "c_" => {
                    let c = d.computes.iter().find(|c| c.id() == id).ok_or_else(|| a.error_at(w, "Compute ID for fix vector does not exist", "unknown compute"))?;
                    if let (Some(i), Some(n)) = (index, c.size_vector()) {
                        if i > n {
                            return Err(a.error_at(w, "Fix vector compute vector is accessed out-of-range", "out of range"));
                        }
                    }
                    (Value::Compute(id.to_string(), index), c.extensive(index))
                }
                "f_" => {
                    let f = d.fixes.iter().find(|f| f.id() == id).ok_or_else(|| a.error_at(w, "Fix ID for fix vector does not exist", "unknown fix"))?;
                    if index.is_some_and(|i| f.size_vector() > 0 && i > f.size_vector()) {
                        return Err(a.error_at(w, "Fix vector fix vector is accessed out-of-range", "out of range"));
                    }
                    if nevery % f.global_freq() != 0 {
                        return Err(a.error_at(w, format!("Fix for fix vector not computed at compatible time: fix {id} is current every {} steps", f.global_freq()), "Nevery"));
                    }
                    (Value::Fix(id.to_string(), index), f.extensive(index))
                }
                _ => {
                    if index.is_some() {
                        return Err(a.error_at(w, "fix vector: an element of a vector-style variable (v_name[I]) is not supported by dmhs", "vector variable"));
                    }
                    (Value::Variable(id.to_string()), false)
                }
            };
            if extensive.is_some_and(|e| e != ext) {
                return Err(a.error_at(w, "Fix vector cannot set output array intensive/extensive from these inputs", "mixed"));
            }
            extensive = Some(ext);
            values.push(value);
        }
        if values.is_empty() {
            return Err(a.missing("a value (c_ID, c_ID[I], f_ID, f_ID[I] or v_name)"));
        }
        let mut nmax = None;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "nmax" => nmax = Some(a.usize_min("nmax length", 1)?),
                _ => return Err(a.unknown_keyword(w, &["nmax"])),
            }
        }
        // the first multiple of Nevery from now
        let nextstep = (state.step + nevery - 1).div_euclid(nevery) * nevery;
        Ok(FixVector { id: d.id, groupbit: d.groupbit, nevery, values, extensive: extensive.unwrap_or(false), nmax, nextstep, rows: Default::default() })
    }

    fn store(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step != self.nextstep {
            return Ok(());
        }
        let row = ctx.eval(state, self, |_, ev| {
            self.values
                .iter()
                .map(|v| match v {
                    Value::Compute(id, i) => ev.compute_value(id, *i),
                    Value::Fix(id, i) => ev.fix_value(id, *i),
                    Value::Variable(name) => dmhs_parser::variables::compute_equal(ev, name),
                })
                .collect::<Result<Vec<f64>, String>>()
                .map_err(|e| format!("fix vector {}: {e}", self.id))
        })?;
        if self.nmax.is_some_and(|n| self.rows.len() == n) {
            self.rows.pop_front();
        }
        self.rows.push_back(row);
        self.nextstep += self.nevery;
        Ok(())
    }
}

impl Fix for FixVector {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "vector"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        // LAMMPS checks the variables when the fix is defined; dmhs when a run starts
        let names: Vec<&str> = self.values.iter().filter_map(|v| if let Value::Variable(n) = v { Some(n.as_str()) } else { None }).collect();
        let styles = ctx.eval(state, self, |_, ev| Ok(names.iter().map(|n| ev.variables().style(n)).collect::<Vec<_>>()))?;
        for (n, st) in names.iter().zip(styles) {
            let err = |m: String| RunError::new(state.step, format!("fix vector {}: {m}", self.id));
            match st {
                None => return Err(err(format!("Variable name {n} for fix vector does not exist"))),
                Some("equal") => {}
                Some(_) => return Err(err(format!("Fix vector variable {n} is not equal-style variable"))),
            }
        }
        self.store(state, ctx)
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.store(state, ctx)
    }
    fn global_freq(&self) -> i64 {
        self.nevery
    }
    fn wants_energy(&self, step: i64) -> bool {
        step == self.nextstep
    }
    fn size_vector(&self) -> usize {
        if self.values.len() == 1 {
            self.rows.len()
        } else {
            0
        }
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        if self.values.len() > 1 || i == 0 {
            return None;
        }
        self.rows.get(i - 1).map(|r| r[0])
    }
    fn size_array(&self) -> Option<(usize, usize)> {
        (self.values.len() > 1).then(|| (self.rows.len(), self.values.len()))
    }
    fn array(&self, _state: &State, i: usize, j: usize) -> Option<f64> {
        if self.values.len() == 1 || i == 0 || j == 0 || j > self.values.len() {
            return None;
        }
        self.rows.get(i - 1).map(|r| r[j - 1])
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        self.extensive
    }
    fn array_extensive(&self) -> bool {
        self.extensive
    }
}
