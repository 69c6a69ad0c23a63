//! What the thermostat fixes share: the temperature compute each creates on its group
//! (LAMMPS' `ID_temp`, style temp, or the compute `fix_modify temp` names), and the target temperature ramped over a run.

use super::value::FixValue;
use crate::models::compute::temp_bias::{self, TempSpec};
use super::{Fix, FixCtx};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, DResult};

/// The fix's own `compute ID_temp group temp` (dim N - dim - fixes' dof, counted at the start
/// of a run), or after `fix_modify temp CID` the measure of compute CID, with its bias removed
/// while the fix scales velocities. T is summed in LAMMPS' atom order.
#[derive(Clone, Debug)]
pub struct GroupTemp {
    pub spec: TempSpec,
    pub dof: f64,
}

impl GroupTemp {
    pub fn new(groupbit: u32) -> GroupTemp {
        GroupTemp { spec: TempSpec::plain(groupbit), dof: 0.0 }
    }
    /// LAMMPS' `dof_compute` (at init of a run).
    pub fn count_dof(&mut self, state: &State, ctx: &FixCtx) {
        let fix_dof: f64 = ctx.other_fixes().map(|f| f.dof_removed(state, self.spec.groupbit)).sum();
        self.dof = self.spec.dof(state, fix_dof);
    }
    /// `fix_modify temp`: measure as another temperature compute does.
    pub fn replace(&mut self, spec: TempSpec) {
        self.spec = spec;
    }
    /// The current temperature (0 without degrees of freedom); temp/region recounts `dof`.
    pub fn compute(&mut self, state: &State) -> Result<f64, RunError> {
        let (t, dof) = self.spec.temperature(state, self.dof).map_err(|e| RunError::new(state.step, e))?;
        self.dof = dof;
        Ok(t)
    }
    /// v *= factor for the owned atoms of `groupbit` (the fix's group), the compute's bias
    /// removed before and restored after (LAMMPS' remove_bias / restore_bias around the scaling).
    pub fn scale(&self, state: &mut State, groupbit: u32, factor: f64) -> Result<(), RunError> {
        match self.spec.field(state, groupbit).map_err(|e| RunError::new(state.step, e))? {
            None => super::temp_scale::scale_group(state, groupbit, factor),
            Some(bias) => {
                let a = &mut state.atoms;
                let n = a.nlocal;
                temp_bias::remove(&mut a.v[..n], &a.mask[..n], groupbit, &bias);
                super::temp_scale::scale_group(state, groupbit, factor);
                let a = &mut state.atoms;
                temp_bias::restore(&mut a.v[..n], &a.mask[..n], groupbit, &bias);
            }
        }
        Ok(())
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
