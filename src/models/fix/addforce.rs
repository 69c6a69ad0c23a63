//! `fix ID group addforce fx fy fz [every N] [region R] [energy v_E]`: adds a force, each
//! component a constant, an equal-style variable or an atom-style variable (one value per atom);
//! f_ID is minus the work term (with constant forces), the sum of the atom-style variable E
//! (with `energy`), f_ID[1..3] the force before the addition.

use super::value::{Evaluated, FixValue};
use super::{Fix, FixCtx, FixHooks, ThermoTally};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group addforce fx fy fz [every N] [region region-ID] [energy v_name]";

pub struct FixAddForce {
    id: String,
    groupbit: u32,
    value: [FixValue; 3],
    every: i64,
    region: Option<String>,
    /// `energy v_name`: the atom-style variable whose sum is the potential energy.
    energy: Option<String>,
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
        let mut energy = None;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "every" => every = a.i64_in("every", 1, i64::MAX)?,
                "region" => region = Some(super::setforce::find_region(&mut a, state)?),
                "energy" => {
                    let e = a.word("energy (v_name of an atom-style variable)")?;
                    match e.text.strip_prefix("v_") {
                        Some(name) => energy = Some(name.to_string()),
                        None => return Err(a.error_at(e, "fix addforce energy takes v_name of an atom-style variable", "not a variable")),
                    }
                    if value.iter().all(|v| matches!(v, FixValue::Const(_))) {
                        return Err(a.error_at(e, "Cannot use variable energy with constant force in fix addforce", "the forces are constants"));
                    }
                }
                _ => return Err(a.unknown_keyword(w, &["every", "region", "energy"])),
            }
        }
        Ok(FixAddForce { id, groupbit, value, every, region, energy, foriginal: [0.0; 4], tally: ThermoTally::new(true) })
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
    /// LAMMPS applies it while minimizing (its energy counts only with fix_modify energy); a
    /// variable force needs the `energy` keyword there (LAMMPS: "Must use variable energy").
    fn min_role(&self) -> super::MinRole {
        match self.value.iter().all(|v| matches!(v, FixValue::Const(_) | FixValue::Null)) || self.energy.is_some() {
            true => super::MinRole::PostForce,
            false => super::MinRole::Refused(format!("fix {} (addforce): Must use variable energy with fix addforce (a variable force in a minimization needs `energy v_name`)", self.id)),
        }
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.every != 0 {
            return Ok(());
        }
        let constant = self.value.iter().all(|v| matches!(v, FixValue::Const(_)));
        // the variables are evaluated x, y, z, then the energy, as LAMMPS does
        let [vx, vy, vz] = [0, 1, 2].map(|k| ctx.value_per_atom(state, self, &self.value[k]));
        let g = [vx?, vy?, vz?];
        let energy = match &self.energy {
            Some(name) => match ctx.value_per_atom(state, self, &FixValue::Variable(name.clone()))? {
                e @ Evaluated::PerAtom(_) => Some(e),
                _ => return Err(RunError::new(state.step, format!("fix addforce {}: Variable for fix addforce is invalid style (energy v_{name} must be atom-style)", self.id))),
            },
            None => None,
        };
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
            let g = [0, 1, 2].map(|k| g[k].at(i).unwrap_or(0.0));
            // LAMMPS sums the work in one expression for constant forces, term by term otherwise
            if constant {
                self.foriginal[0] -= g[0] * u[0] + g[1] * u[1] + g[2] * u[2];
            } else if let Some(e) = &energy {
                self.foriginal[0] += e.at(i).unwrap_or(0.0);
            } else {
                self.foriginal[0] -= g[0] * u[0];
                self.foriginal[0] -= g[1] * u[1];
                self.foriginal[0] -= g[2] * u[2];
            }
            let f = &mut a.f[i];
            self.foriginal[1] += f[0];
            self.foriginal[2] += f[1];
            self.foriginal[3] += f[2];
            f[0] += g[0];
            f[1] += g[1];
            f[2] += g[2];
            self.tally.v_tally([g[0] * u[0], g[1] * u[1], g[2] * u[2], g[0] * u[1], g[0] * u[2], g[1] * u[2]]);
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
