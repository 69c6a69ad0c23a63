//! `fix ID group dmhs/stokes mu`: Stokes drag on each particle of the group (paper Eq 28, the
//! Plinko cell sorter): f_i -= 6 pi mu r_i v_i, with r_i the particle's current radius (so it
//! follows `fix dmhs/swell`). `fix viscous gamma` is the same force with one gamma per type;
//! this fix computes gamma = 6 pi mu r per particle. A particle falling under a body force F
//! reaches the terminal velocity F / (6 pi mu r).

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "fix ID group dmhs/stokes mu  (mu: dynamic viscosity of the surrounding fluid)";

pub struct FixStokes {
    id: String,
    groupbit: u32,
    mu: f64,
}

impl FixStokes {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mu = a.non_negative_f64("mu (dynamic viscosity)")?;
        a.finish()?;
        if !state.atoms.features.sphere {
            return Err(Diagnostic::at(style.span, "fix dmhs/stokes needs an atom style with radii (sphere); use fix viscous with gamma = 6 pi mu r for point particles", "atom style has no radius"));
        }
        Ok(FixStokes { id, groupbit, mu })
    }
}

impl Fix for FixStokes {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "dmhs/stokes"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let k = 6.0 * std::f64::consts::PI * self.mu;
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let gamma = k * a.radius[i];
                let v = a.v[i];
                let f = &mut a.f[i];
                f[0] -= gamma * v[0];
                f[1] -= gamma * v[1];
                f[2] -= gamma * v[2];
            }
        }
        Ok(())
    }
}
