//! `fix ID group viscous gamma [scale type ratio ...]`: drag f -= gamma_type * v
//! (Stokes drag with gamma = 6 pi mu r).

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group viscous gamma [scale type ratio ...]";

pub struct FixViscous {
    id: String,
    groupbit: u32,
    /// Per type (index 0 unused).
    gamma: Vec<f64>,
}

impl FixViscous {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let g = a.f64("gamma")?;
        let mut gamma = vec![g; state.ntypes + 1];
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "scale" => {
                    let t = a.i64_in("atom type", 1, state.ntypes as i64)? as usize;
                    let ratio = a.f64("ratio")?;
                    gamma[t] = g * ratio;
                }
                _ => return Err(a.unknown_keyword(w, &["scale"])),
            }
        }
        Ok(FixViscous { id, groupbit, gamma })
    }
}

impl Fix for FixViscous {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "viscous"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    /// LAMMPS applies it while minimizing (-gamma v with the velocities as they are).
    fn min_role(&self) -> super::MinRole {
        super::MinRole::PostForce
    }
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let drag = self.gamma[a.typ[i]];
                let v = a.v[i];
                let f = &mut a.f[i];
                f[0] -= drag * v[0];
                f[1] -= drag * v[1];
                f[2] -= drag * v[2];
            }
        }
        Ok(())
    }
}
