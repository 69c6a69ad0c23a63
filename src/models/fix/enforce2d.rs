//! `fix ID group enforce2d`: zero the z components of velocity and force (and the x, y
//! components of angular velocity and torque) so a 2D system stays in its plane.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub struct FixEnforce2d {
    id: String,
    groupbit: u32,
}

impl FixEnforce2d {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        Args::from_words(args, cmd.span, "fix ID group enforce2d").finish()?;
        Ok(FixEnforce2d { id, groupbit })
    }
}

impl Fix for FixEnforce2d {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "enforce2d"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn min_role(&self) -> super::MinRole {
        super::MinRole::PostForce
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        if state.dimension == 3 {
            return Err("fix enforce2d cannot be used in a 3d simulation".into());
        }
        Ok(())
    }
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let a = &mut state.atoms;
        let n = a.nlocal;
        let groupbit = self.groupbit;
        // plain slices: through `a`, every store made the compiler reload the arrays' addresses
        let (mask, v, f) = (&a.mask[..n], &mut a.v[..n], &mut a.f[..n]);
        for ((m, vi), fi) in mask.iter().zip(v.iter_mut()).zip(f.iter_mut()) {
            if m & groupbit != 0 {
                vi[2] = 0.0;
                fi[2] = 0.0;
            }
        }
        if a.features.sphere {
            let (mask, omega, torque) = (&a.mask[..n], &mut a.omega[..n], &mut a.torque[..n]);
            for ((m, wi), ti) in mask.iter().zip(omega.iter_mut()).zip(torque.iter_mut()) {
                if m & groupbit != 0 {
                    wi[0] = 0.0;
                    wi[1] = 0.0;
                    ti[0] = 0.0;
                    ti[1] = 0.0;
                }
            }
        }
        Ok(())
    }
}
