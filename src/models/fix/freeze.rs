//! `fix ID group freeze`: zeroes the force and torque of the group's spheres after the forces of
//! each step (LAMMPS' fix freeze); f_ID[1..3] is the total force it removed. Granular pair
//! styles read its group: a contact with a frozen sphere uses the other sphere's mass as m_eff.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "fix ID group freeze";

pub struct FixFreeze {
    id: String,
    groupbit: u32,
    foriginal: [f64; 3],
}

impl FixFreeze {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        Args::from_words(args, cmd.span, SYNTAX).finish()?;
        if !state.atoms.features.sphere {
            return Err(Diagnostic::at(cmd.span, "fix freeze requires atom style sphere (atoms with torque)", "no torque").with_help("use atom_style sphere"));
        }
        Ok(FixFreeze { id, groupbit, foriginal: [0.0; 3] })
    }
}

impl Fix for FixFreeze {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "freeze"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn init(&mut self, _state: &State, ctx: &FixCtx) -> Result<(), String> {
        // pair styles read one freeze group (LAMMPS' error)
        match ctx.other_fixes().any(|f| f.style() == "freeze") {
            true => Err("more than one fix freeze".into()),
            false => Ok(()),
        }
    }
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let a = &mut state.atoms;
        self.foriginal = [0.0; 3];
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                for k in 0..3 {
                    self.foriginal[k] += a.f[i][k];
                }
                a.f[i] = [0.0; 3];
                a.torque[i] = [0.0; 3];
            }
        }
        Ok(())
    }
    fn vector(&self, state: &State, i: usize) -> Option<f64> {
        (1..=3).contains(&i).then(|| state.summed_over_ranks(self.foriginal[i - 1]))
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
