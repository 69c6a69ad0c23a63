//! `fix ID group spring/rg K RG0|NULL`: a harmonic restraint on the group's radius of gyration,
//! E = K (Rg - RG0)^2, as LAMMPS' fix spring/rg: each atom gets
//! F_i = -2 K (1 - RG0/Rg) (x_i - x_cm) m_i / M (unwrapped positions, M the group's mass).
//! RG0 NULL takes the group's Rg when the first run starts. f_ID is RG0.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use crate::models::compute::gyration;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group spring/rg K RG0|NULL";

pub struct FixSpringRg {
    id: String,
    groupbit: u32,
    k: f64,
    /// None until the first run when given as NULL.
    rg0: Option<f64>,
}

impl FixSpringRg {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let k = a.f64("K")?;
        let rg0 = match a.peek().map(|w| w.text.as_str()) {
            Some("NULL") => {
                a.skip(1);
                None
            }
            _ => Some(a.f64("RG0")?),
        };
        a.finish()?;
        Ok(FixSpringRg { id, groupbit, k, rg0 })
    }
}

impl Fix for FixSpringRg {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "spring/rg"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        if self.rg0.is_none() {
            self.rg0 = Some(gyration::radius(state, self.groupbit)?);
        }
        Ok(())
    }
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let step = state.step;
        let rg0 = self.rg0.ok_or_else(|| RunError::new(step, format!("fix spring/rg {}: RG0 not set", self.id)))?;
        let (xcm, masstotal) = state.group_xcm(self.groupbit);
        let rg = gyration::radius_about(state, self.groupbit, xcm, masstotal).map_err(|e| RunError::new(step, e))?;
        if masstotal <= 0.0 {
            return Ok(());
        }
        let term1 = 2.0 * self.k * (1.0 - rg0 / rg);
        let periods = state.domain.as_ref().map_or(Default::default(), |d| d.periods());
        let (a, type_mass) = (&mut state.atoms, &state.type_mass);
        for i in (0..a.nlocal).filter(|&i| a.mask[i] & self.groupbit != 0) {
            let u = periods.unmap(a.x[i], a.image[i]);
            let massfrac = a.mass(i, type_mass) / masstotal;
            for d in 0..3 {
                a.f[i][d] -= term1 * (u[d] - xcm[d]) * massfrac;
            }
        }
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        self.rg0
    }
}
