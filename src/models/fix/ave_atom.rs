//! `fix ID group ave/atom Nevery Nrepeat Nfreq value ...`: per-atom averages of x y z vx vy vz
//! fx fy fz, per-atom compute values (`c_ID`, `c_ID[i]`, `[*]` expands), per-atom fix values
//! (`f_ID`, `f_ID[i]`) and atom-style variables (`v_name`) over Nrepeat samples Nevery steps
//! apart, ending on multiples of Nfreq, as LAMMPS' fix ave/atom. The result, `f_ID` or
//! `f_ID[i]`, is read by dumps and compute reduce. The sums travel with the atoms (an extra
//! per-atom array), so sorting does not mix them up.

use super::sampling::Sampling;
use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::state::{RunError, State};
use crate::models::compute::{PerAtom, PerAtomRef};
use dmhs_parser::{Args, DResult};

pub const SYNTAX: &str = "fix ID group ave/atom Nevery Nrepeat Nfreq value ...  (x y z vx vy vz fx fy fz c_ID c_ID[i] f_ID f_ID[i] v_name)";

#[derive(Clone, Debug)]
enum Value {
    /// Position (0..3), velocity (3..6) or force (6..9) component.
    Attr(usize),
    PerAtom(PerAtomRef),
    /// An atom-style variable, evaluated at each sample.
    Variable(String),
}

pub struct FixAveAtom {
    id: String,
    groupbit: u32,
    sampling: Sampling,
    values: Vec<Value>,
}

impl FixAveAtom {
    fn array_name(&self) -> String {
        format!("ave/atom/{}", self.id)
    }

    pub fn from_lammps(d: FixDef, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(d.args, d.cmd.span, SYNTAX);
        let sampling = Sampling::parse(&mut a, "ave/atom")?;
        let attrs = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"];
        let mut values = Vec::new();
        {
            let world = crate::models::world::World { state, computes: d.computes, fixes: crate::models::world::FixesView::all(d.fixes), bond: None, pair: None };
            while let Some(w) = a.peek() {
                a.skip(1);
                if let Some(k) = attrs.iter().position(|n| *n == w.text) {
                    values.push(Value::Attr(k));
                    continue;
                }
                if let Some(name) = w.text.strip_prefix("v_") {
                    values.push(Value::Variable(name.to_string()));
                    continue;
                }
                // c_ID[*] and f_ID[*]: every column
                let names = match w.text.strip_suffix("[*]") {
                    Some(base) => {
                        let id = &base[2.min(base.len())..];
                        let cols = if base.starts_with("c_") { world.compute(id).and_then(|c| c.peratom_cols()) } else { world.fix(id).and_then(|f| f.peratom_cols()) };
                        let n = cols.ok_or_else(|| a.error_at(w, format!("`{}` does not name a per-atom compute or fix", w.text), "wildcard"))?;
                        (1..=n).map(|k| format!("{base}[{k}]")).collect()
                    }
                    None => vec![w.text.clone()],
                };
                for n in names {
                    match PerAtomRef::parse(&n, &world) {
                        Some(r) => values.push(Value::PerAtom(r.map_err(|e| a.error_at(w, format!("fix ave/atom: {e}"), "not a per-atom value"))?)),
                        None => return Err(a.unknown_keyword(w, &attrs)),
                    }
                }
            }
        }
        if values.is_empty() {
            return Err(a.missing("a value"));
        }
        let mut fix = FixAveAtom { id: d.id, groupbit: d.groupbit, sampling, values };
        let name = fix.array_name();
        let k = state.atoms.extra_field(&name, fix.values.len(), false);
        state.atoms.extra[k].data.fill(0.0);
        fix.sampling.begin(state.step);
        Ok(fix)
    }

    fn sample(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if !self.sampling.due(state.step) {
            return Ok(());
        }
        let step = state.step;
        // the per-atom values of computes and fixes, read before the sums are borrowed
        let inputs: Vec<Option<PerAtom>> = ctx.eval(state, self, |w, ev| {
            self.values
                .iter()
                .map(|v| match v {
                    Value::PerAtom(r) => r.values(w).map(Some),
                    Value::Variable(name) => crate::models::atom_formula::atom_variable_input("ave/atom", name, w, ev).map(|data| Some(PerAtom { cols: 1, data })),
                    Value::Attr(_) => Ok(None),
                })
                .collect()
        })?;
        let n = self.values.len();
        let name = self.array_name();
        let k = state.atoms.find_extra(&name).ok_or_else(|| RunError::new(step, format!("fix ave/atom {}: its per-atom array is gone", self.id)))?;
        let mut sums = std::mem::take(&mut state.atoms.extra[k].data);
        let a = &state.atoms;
        if self.sampling.irepeat == 0 {
            sums.fill(0.0);
        }
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            for (m, v) in self.values.iter().enumerate() {
                sums[i * n + m] += match v {
                    Value::Attr(c) if *c < 3 => a.x[i][*c],
                    Value::Attr(c) if *c < 6 => a.v[i][c - 3],
                    Value::Attr(c) => a.f[i][c - 6],
                    Value::PerAtom(r) => r.get(inputs[m].as_ref().expect("read above"), i),
                    Value::Variable(_) => inputs[m].as_ref().expect("read above").get(i, 0),
                };
            }
        }
        if self.sampling.advance(step) {
            let repeat = self.sampling.nrepeat as f64;
            sums[..a.nlocal * n].iter_mut().for_each(|s| *s /= repeat);
        }
        state.atoms.extra[k].data = sums;
        Ok(())
    }
}

impl Fix for FixAveAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "ave/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        self.sampling.init(state.step);
        Ok(())
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.sample(state, ctx)
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.sample(state, ctx)
    }
    fn wants_energy(&self, step: i64) -> bool {
        self.sampling.due(step)
    }
    fn peratom(&self, state: &State) -> Result<PerAtom, String> {
        let n = self.values.len();
        let k = state.atoms.find_extra(&self.array_name()).ok_or_else(|| format!("fix ave/atom {}: its per-atom array is gone", self.id))?;
        Ok(PerAtom { cols: n, data: state.atoms.extra[k].data[..state.atoms.nlocal * n].to_vec() })
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(self.values.len())
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.remove_extra(&self.array_name());
    }
}
