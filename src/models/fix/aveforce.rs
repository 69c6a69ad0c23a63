//! `fix ID group aveforce fx fy fz [region R]`: every atom of the group (and region) gets the
//! group's average force plus (fx, fy, fz) in each component that is not NULL; constants or
//! equal-style variables. f_ID[1..3] is the group's total force before it was averaged.

use super::setforce::{parse_components, region_now};
use super::value::FixValue;
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group aveforce fx|NULL fy|NULL fz|NULL [region region-ID]";

pub struct FixAveForce {
    id: String,
    groupbit: u32,
    value: [FixValue; 3],
    region: Option<String>,
    /// Total force and atom count of the participating atoms, summed over ranks (LAMMPS'
    /// foriginal_all).
    foriginal: [f64; 4],
}

impl FixAveForce {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let (value, region) = parse_components(args, cmd, SYNTAX, state)?;
        Ok(FixAveForce { id, groupbit, value, region, foriginal: [0.0; 4] })
    }
}

impl Fix for FixAveForce {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "aveforce"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    /// LAMMPS applies it after each force evaluation of a minimization too (min_post_force).
    fn min_role(&self) -> super::MinRole {
        super::MinRole::PostForce
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let region = region_now(&state.regions, state.step, &self.id, &self.region)?;
        let a = &state.atoms;
        let inside = |i: usize| a.mask[i] & self.groupbit != 0 && region.is_none_or(|r| r.matches(a.x[i]));
        let mut sum = [0.0; 4];
        for i in (0..a.nlocal).filter(|&i| inside(i)) {
            let f = a.f[i];
            sum[0] += f[0];
            sum[1] += f[1];
            sum[2] += f[2];
            sum[3] += 1.0;
        }
        let members: Vec<usize> = (0..a.nlocal).filter(|&i| inside(i)).collect();
        state.sum_ranks(&mut sum);
        self.foriginal = sum;
        let ncount = sum[3] as i64;
        if ncount == 0 {
            return Ok(());
        }
        // the variables are read only when some atom takes part, as LAMMPS does
        let mut fave = [None; 3];
        for k in 0..3 {
            fave[k] = ctx.value(state, self, &self.value[k])?.map(|v| sum[k] / ncount as f64 + v);
        }
        let f = &mut state.atoms.f;
        for i in members {
            for k in 0..3 {
                if let Some(v) = fave[k] {
                    f[i][k] = v;
                }
            }
        }
        Ok(())
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        (1..=3).contains(&i).then(|| self.foriginal[i - 1])
    }
    fn size_vector(&self) -> usize {
        3
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
