//! `fix ID group heat/flow constant cp` or `... heat/flow type cp1 ... cpN` (LAMMPS' fix
//! heat/flow): integrates the per-atom temperature from the heat flow of the granular heat
//! models, T += dt Q / (cp m), at the end of each step (final_integrate), with the specific heat
//! cp of all atoms or of each type. The heat flow is zeroed before every force computation (LAMMPS
//! does it in this fix's pre_force; the force stage zeroes it here) and the temperatures reach
//! the ghosts with the per-atom state of the next step. Needs `fix property/atom temperature
//! heatflow`.

use super::{Fix, FixCtx, FixHooks, MinRole};
use crate::engine::fields::{HEATFLOW, TEMPERATURE};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult};

pub const SYNTAX: &str = "fix ID group heat/flow constant cp | type cp1 cp2 ... cpN";

pub struct FixHeatFlow {
    id: String,
    groupbit: u32,
    /// specific heat per type (index 0 unused); one value repeated for `constant`
    cp: Vec<f64>,
}

impl FixHeatFlow {
    pub fn from_lammps(id: String, groupbit: u32, args: &[dmhs_parser::Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let ntypes = state.ntypes;
        let cp = match a.choice("specific heat style", &["constant", "type"])? {
            0 => vec![a.non_negative_f64("cp (specific heat)")?; ntypes + 1],
            _ => {
                let mut cp = vec![0.0];
                for t in 1..=ntypes {
                    cp.push(a.non_negative_f64(&format!("cp of type {t} (one per atom type, {ntypes} in all)"))?);
                }
                cp
            }
        };
        a.finish()?;
        Ok(FixHeatFlow { id, groupbit, cp })
    }
}

impl Fix for FixHeatFlow {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "heat/flow"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { final_integrate: true, ..FixHooks::default() }
    }
    fn min_role(&self) -> MinRole {
        MinRole::Inert
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        let a = &state.atoms;
        if a.field(TEMPERATURE).is_none() || a.field(HEATFLOW).is_none() {
            return Err(format!("fix {} heat/flow needs per-atom temperature and heatflow: add `fix ID all property/atom temperature heatflow`", self.id));
        }
        if self.cp.len() <= state.ntypes {
            return Err(format!("fix {} heat/flow has specific heats for {} atom types, the box has {}", self.id, self.cp.len() - 1, state.ntypes));
        }
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let (Some(kt), Some(kq)) = (state.atoms.field(TEMPERATURE), state.atoms.field(HEATFLOW)) else {
            return Err(RunError::new(state.step, format!("fix {} heat/flow: the temperature or heatflow values were removed", self.id)));
        };
        let dt = state.dt;
        let q = std::mem::take(&mut state.atoms.extra[kq].data);
        for i in 0..state.atoms.nlocal {
            let a = &state.atoms;
            if a.mask[i] & self.groupbit != 0 {
                let m = a.mass(i, &state.type_mass);
                let cp = self.cp[a.typ[i]];
                state.atoms.extra[kt].data[i] += dt * q[i] / (cp * m);
            }
        }
        state.atoms.extra[kq].data = q;
        Ok(())
    }
}
