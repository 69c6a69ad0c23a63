//! `fix ID group dmhs/diffusion`: integrates the water mass w of the group's particles with the
//! rates dw/dt of `pair_style dmhs/sph/diffusion` (paper Eq 26), in half steps as fix sph
//! integrates the internal energy: w += dt/2 dw/dt at the start of the step (rate of the last
//! force pass) and again after the force pass. Particles outside the group keep their water
//! (a reservoir: the paper neglects the loss of the water particles, which are in excess).
//! Defining the fix creates the per-particle water field (0 until `set ... dmhs/conc`).
//! Scalar `f_ID`: the total water mass sum w_i over the group.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use crate::engine::fields::{WATER, WATER_RATE};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "fix ID group dmhs/diffusion";

pub struct FixDiffusion {
    id: String,
    groupbit: u32,
}

impl FixDiffusion {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        Args::from_words(args, cmd.span, SYNTAX).finish()?;
        if !state.atoms.features.sph {
            return Err(Diagnostic::at(style.span, "fix dmhs/diffusion needs an atom style with SPH attributes (c = w rho/m uses the SPH density)", "atom style has no rho"));
        }
        if state.atoms.field(WATER).is_none() {
            state.lists_valid = false;
        }
        crate::engine::water::ensure_fields(&mut state.atoms);
        Ok(FixDiffusion { id, groupbit })
    }

    fn half_step(&self, state: &mut State) -> Result<(), RunError> {
        let dth = 0.5 * state.dt;
        let a = &mut state.atoms;
        let (kw, kd) = match (a.field(WATER), a.field(WATER_RATE)) {
            (Some(kw), Some(kd)) => (kw, kd),
            _ => return Err(RunError::new(state.step, "fix dmhs/diffusion: the water field was removed")),
        };
        let dw = std::mem::take(&mut a.extra[kd].data);
        let w = &mut a.extra[kw].data;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                w[i] += dth * dw[i];
            }
        }
        a.extra[kd].data = dw;
        Ok(())
    }
}

impl Fix for FixDiffusion {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "dmhs/diffusion"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        if state.atoms.field(WATER).is_none() {
            return Err("the water field is missing (was the fix defined before read_restart?)".into());
        }
        Ok(())
    }
    fn initial_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.half_step(state)
    }
    fn final_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.half_step(state)
    }
    fn scalar(&self, state: &State) -> Option<f64> {
        let a = &state.atoms;
        let w = crate::engine::water::water(a)?;
        let mut total = [(0..a.nlocal).filter(|&i| a.mask[i] & self.groupbit != 0).map(|i| w[i]).sum()];
        state.sum_ranks(&mut total);
        Some(total[0])
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
