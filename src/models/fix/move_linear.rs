//! `fix ID group move linear Vx Vy Vz`: prescribed constant velocity in the given
//! components (NULL components are integrated as by fix nve), positions set from the
//! unwrapped position at the time the fix was defined, as LAMMPS does.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::args::word_f64;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group move linear Vx|NULL Vy|NULL Vz|NULL [units box|lattice]";

pub struct FixMove {
    id: String,
    groupbit: u32,
    vel: [Option<f64>; 3],
    time_origin: i64,
    /// name of the per-atom array holding the original unwrapped positions
    store: String,
}

impl FixMove {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let style = a.word("move style")?;
        if style.text != "linear" {
            let msg = if ["wiggle", "rotate", "variable", "transrot"].contains(&style.text.as_str()) {
                format!("fix move {} is a LAMMPS style that dmhs does not support yet (only `linear`)", style.text)
            } else {
                format!("unknown fix move style `{}`", style.text)
            };
            return Err(a.error_at(style, msg, "expected `linear`"));
        }
        let mut vel = [None; 3];
        for (k, what) in ["Vx", "Vy", "Vz"].iter().enumerate() {
            let w = a.word(what)?;
            vel[k] = if w.text == "NULL" { None } else { Some(word_f64(w, what).map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))?) };
        }
        let lattice_units = a.units_keyword_only()?;
        if lattice_units && vel.iter().any(|v| v.is_some()) {
            let scale = state.lattice_scale().map_err(|e| a.error_at(style, e, "needs a lattice (or `units box`)"))?;
            for d in 0..3 {
                if let Some(v) = &mut vel[d] {
                    *v *= scale[d];
                }
            }
        }
        let domain = state.domain.clone().ok_or_else(|| a.error_at(&cmd.name, "fix move needs a simulation box", "no box yet"))?;
        let store = format!("fix_move:{id}");
        state.atoms.clear_ghosts();
        state.lists_valid = false;
        let k = state.atoms.extra_array(&store, 3);
        for i in 0..state.atoms.nlocal {
            let u = domain.unmap(state.atoms.x[i], state.atoms.image[i]);
            state.atoms.extra[k].data[3 * i..3 * i + 3].copy_from_slice(&u);
        }
        Ok(FixMove { id, groupbit, vel, time_origin: state.step, store })
    }
}

impl Fix for FixMove {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "move"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn initial_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let delta = (state.step - self.time_origin) as f64 * state.dt;
        let dtv = state.dt;
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let domain = state.domain.clone().ok_or_else(|| RunError::new(state.step, "no box"))?;
        let per_atom = state.atoms.features.per_atom_mass();
        let k = state.atoms.extra.iter().position(|e| e.name == self.store).ok_or_else(|| RunError::new(state.step, "fix move lost its stored positions"))?;
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let xold = a.x[i];
            let m = if per_atom { a.rmass[i] } else { state.type_mass[a.typ[i]] };
            let dtfm = dtf / m;
            for d in 0..3 {
                match self.vel[d] {
                    Some(v) => {
                        a.v[i][d] = v;
                        a.x[i][d] = a.extra[k].data[3 * i + d] + v * delta;
                    }
                    None => {
                        a.v[i][d] += dtfm * a.f[i][d];
                        a.x[i][d] += dtv * a.v[i][d];
                    }
                }
            }
            domain.remap_near(&mut a.x[i], &xold);
        }
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let per_atom = state.atoms.features.per_atom_mass();
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let m = if per_atom { a.rmass[i] } else { state.type_mass[a.typ[i]] };
            let dtfm = dtf / m;
            for d in 0..3 {
                if self.vel[d].is_none() {
                    a.v[i][d] += dtfm * a.f[i][d];
                }
            }
        }
        Ok(())
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.remove_extra(&self.store);
    }
}
