//! `fix ID group addforce fx fy fz [every N] [region R]`: adds a constant (or equal-style
//! variable) force; f_ID is minus the work term, f_ID[1..3] the force before the addition.

use super::value::FixValue;
use super::{Fix, FixCtx, FixHooks, ThermoTally};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group addforce fx fy fz [every N] [region region-ID]";

pub struct FixAddForce {
    id: String,
    groupbit: u32,
    value: [FixValue; 3],
    every: i64,
    region: Option<String>,
    /// -sum(F . x_unwrapped), then the original force sum.
    foriginal: [f64; 4],
    tally: ThermoTally,
}

impl FixAddForce {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mut value = [FixValue::Null, FixValue::Null, FixValue::Null];
        for (k, what) in ["fx", "fy", "fz"].iter().enumerate() {
            let w = a.word(what)?;
            value[k] = FixValue::parse(w, what, false).map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))?;
        }
        let mut every = 1;
        let mut region = None;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "every" => every = a.i64_in("every", 1, i64::MAX)?,
                "region" => region = Some(super::setforce::find_region(&mut a, state)?),
                _ => return Err(a.unknown_keyword(w, &["every", "region"])),
            }
        }
        Ok(FixAddForce { id, groupbit, value, every, region, foriginal: [0.0; 4], tally: ThermoTally::new(true) })
    }
}

impl Fix for FixAddForce {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "addforce"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    /// LAMMPS applies it while minimizing (its energy counts only with fix_modify energy).
    fn min_role(&self) -> super::MinRole {
        match self.value.iter().all(|v| matches!(v, FixValue::Const(_) | FixValue::Null)) {
            true => super::MinRole::PostForce,
            false => super::MinRole::Refused(format!("fix {} (addforce): a variable force needs LAMMPS' `energy` keyword in a minimization, which dmhs does not have", self.id)),
        }
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.every != 0 {
            return Ok(());
        }
        let mut fv = [0.0; 3];
        for k in 0..3 {
            fv[k] = ctx.value(state, self, &self.value[k])?.unwrap_or(0.0);
        }
        let domain = state.domain.clone().ok_or_else(|| RunError::new(state.step, "no box"))?;
        let region = super::setforce::region_now(&state.regions, state.step, &self.id, &self.region)?;
        let a = &mut state.atoms;
        self.foriginal = [0.0; 4];
        self.tally.v_init();
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            if let Some(r) = region {
                if !r.matches(a.x[i]) {
                    continue;
                }
            }
            let u = domain.unmap(a.x[i], a.image[i]);
            self.foriginal[0] -= fv[0] * u[0] + fv[1] * u[1] + fv[2] * u[2];
            let f = &mut a.f[i];
            self.foriginal[1] += f[0];
            self.foriginal[2] += f[1];
            self.foriginal[3] += f[2];
            f[0] += fv[0];
            f[1] += fv[1];
            f[2] += fv[2];
            self.tally.v_tally([fv[0] * u[0], fv[1] * u[1], fv[2] * u[2], fv[0] * u[1], fv[0] * u[2], fv[1] * u[2]]);
        }
        Ok(())
    }
    fn scalar(&self, state: &State) -> Option<f64> {
        Some(state.summed_over_ranks(self.foriginal[0]))
    }
    fn vector(&self, state: &State, i: usize) -> Option<f64> {
        (1..=3).contains(&i).then(|| state.summed_over_ranks(self.foriginal[i]))
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
    fn thermo_tally(&self) -> Option<&ThermoTally> {
        Some(&self.tally)
    }
    fn thermo_tally_mut(&mut self) -> Option<&mut ThermoTally> {
        Some(&mut self.tally)
    }
}
