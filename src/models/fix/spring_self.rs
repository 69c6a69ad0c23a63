//! `fix ID group spring/self K [xyz|xy|xz|yz|x|y|z]`: each atom of the group tethered to the
//! unwrapped position it had when the fix was defined by a spring of constant K along the
//! chosen directions, as LAMMPS' fix spring/self: F = -K d, f_ID = sum K d^2 / 2 over the
//! group (summed over the ranks). The anchors are a per-atom array that travels with the atoms
//! (and is kept in restart files). `fix_modify energy yes` adds f_ID to pe; the virial and an
//! equal-style K are refused.

use super::{Fix, FixCtx, FixHooks, ThermoTally};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group spring/self K [xyz|xy|xz|yz|x|y|z]  (K > 0)";

pub struct FixSpringSelf {
    id: String,
    groupbit: u32,
    k: f64,
    /// The directions the springs act along.
    dirs: [bool; 3],
    /// Name of the per-atom array of anchors (unwrapped positions) in `Atoms::extra`.
    store: String,
    /// This rank's share of the energy.
    espring: f64,
    /// Energy only (LAMMPS' fix_modify energy).
    tally: ThermoTally,
}

impl FixSpringSelf {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if let Some(w) = a.peek().filter(|w| w.text.starts_with("v_")) {
            return Err(a.error_at(w, "fix spring/self with an equal-style K is not supported yet", "a number > 0"));
        }
        let k = a.f64_where("K", "> 0", |k| k > 0.0)?;
        let dirs = match a.peek() {
            None => [true; 3],
            Some(_) => match a.choice("direction", &["xyz", "xy", "xz", "yz", "x", "y", "z"])? {
                0 => [true, true, true],
                1 => [true, true, false],
                2 => [true, false, true],
                3 => [false, true, true],
                4 => [true, false, false],
                5 => [false, true, false],
                _ => [false, false, true],
            },
        };
        a.finish()?;
        let domain = state.domain.clone().ok_or_else(|| a.error_at(&cmd.name, "fix spring/self needs a simulation box", "no box yet"))?;
        let store = format!("fix_spring_self:{id}");
        // an array of this name with no fix of the ID comes from a restart file: kept, as
        // LAMMPS restores its per-atom restart data (a replaced fix removed its own first)
        let restored = state.atoms.find_extra(&store).is_some();
        let kx = state.atoms.extra_array(&store, 3);
        let atoms = &mut state.atoms;
        for i in (0..atoms.nlocal).filter(|_| !restored) {
            let u = if atoms.mask[i] & groupbit != 0 { domain.unmap(atoms.x[i], atoms.image[i]) } else { [0.0; 3] };
            atoms.extra[kx].data[3 * i..3 * i + 3].copy_from_slice(&u);
        }
        Ok(FixSpringSelf { id, groupbit, k, dirs, store, espring: 0.0, tally: ThermoTally::default() })
    }
}

impl Fix for FixSpringSelf {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "spring/self"
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
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let step = state.step;
        let domain = state.domain.as_ref().ok_or_else(|| RunError::new(step, "no box"))?;
        let kx = state.atoms.find_extra(&self.store).ok_or_else(|| RunError::new(step, format!("fix {} spring/self lost its anchors", self.id)))?;
        let a = &mut state.atoms;
        let mut e = 0.0;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let u = domain.unmap(a.x[i], a.image[i]);
            let x0 = &a.extra[kx].data[3 * i..3 * i + 3];
            let d: [f64; 3] = std::array::from_fn(|k| if self.dirs[k] { u[k] - x0[k] } else { 0.0 });
            for k in 0..3 {
                a.f[i][k] -= self.k * d[k];
            }
            e += self.k * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        }
        self.espring = 0.5 * e;
        Ok(())
    }
    fn scalar(&self, state: &State) -> Option<f64> {
        Some(state.summed_over_ranks(self.espring))
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
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.remove_extra(&self.store);
    }
}
