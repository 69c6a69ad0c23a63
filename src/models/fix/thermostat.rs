//! What the thermostat fixes share: the temperature compute each creates on its group
//! (LAMMPS' `ID_temp`, style temp), and the target temperature ramped over a run.

use super::value::FixValue;
use super::{Fix, FixCtx};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, DResult};

/// The fix's own `compute ID_temp group temp`: degrees of freedom counted at the start of a
/// run (dim N - dim - fixes' dof), T summed in LAMMPS' atom order.
#[derive(Clone, Copy, Debug, Default)]
pub struct GroupTemp {
    pub groupbit: u32,
    /// Degrees of freedom removed besides the fixes' (None: the dimension).
    pub extra: Option<f64>,
    pub dof: f64,
}

impl GroupTemp {
    pub fn new(groupbit: u32) -> GroupTemp {
        GroupTemp { groupbit, extra: None, dof: 0.0 }
    }
    /// LAMMPS' `dof_compute` (at init of a run).
    pub fn count_dof(&mut self, state: &State, ctx: &FixCtx) {
        let dim = state.dimension as f64;
        let fix_dof: f64 = ctx.other_fixes().map(|f| f.dof_removed(state, self.groupbit)).sum();
        self.dof = dim * state.group_count(self.groupbit) as f64 - (self.extra.unwrap_or(dim) + fix_dof);
    }
    /// `fix_modify temp`: the group and extra degrees of freedom of another `compute temp`.
    pub fn replace(&mut self, groupbit: u32, extra: Option<f64>) {
        (self.groupbit, self.extra) = (groupbit, extra);
    }
    /// The current temperature (0 without degrees of freedom).
    pub fn compute(&self, state: &State) -> f64 {
        let tfactor = if self.dof > 0.0 { state.units.mvv2e / (self.dof * state.units.boltz) } else { 0.0 };
        crate::models::compute::temp::sum_mv2(state, self.groupbit) * tfactor
    }
}

/// Fraction of the current run done: LAMMPS' `(ntimestep - beginstep) / (endstep - beginstep)`.
pub fn run_fraction(state: &State) -> f64 {
    let (begin, end) = state.run_window.unwrap_or((state.step, state.step));
    let mut delta = (state.step - begin) as f64;
    if delta != 0.0 {
        delta /= (end - begin) as f64;
    }
    delta
}

/// `Tstart Tstop`: Tstart a number or `v_name` (an equal-style variable, which then gives the
/// target and Tstop is unused, as in LAMMPS).
#[derive(Clone, Debug)]
pub struct Target {
    pub start: FixValue,
    pub stop: f64,
}

impl Target {
    pub fn parse(a: &mut Args) -> DResult<Target> {
        let w = a.word("Tstart")?.clone();
        let start = FixValue::parse(&w, "Tstart", false)?;
        let stop = a.f64("Tstop")?;
        Ok(Target { start, stop })
    }
    /// The target now; a variable must not be negative.
    pub fn now(&self, state: &State, running: &dyn Fix, ctx: &mut FixCtx, style: &str) -> Result<f64, RunError> {
        match &self.start {
            FixValue::Const(t0) => Ok(t0 + run_fraction(state) * (self.stop - t0)),
            v => {
                let t = ctx.value(state, running, v)?.unwrap_or(0.0);
                if t < 0.0 {
                    return Err(RunError::new(state.step, format!("fix {style} variable returned negative temperature {t}")));
                }
                Ok(t)
            }
        }
    }
}
