//! `fix ID group dmhs/swell rhow`: particles swell with the water they absorb (the paper's
//! cleaning model: "their volume increases proportionally to the water absorbed"):
//!
//!   V_i = V0_i + w_i / rhow,   r_i = (3 V_i / 4 pi)^(1/3) in 3D,  r_i = (V_i / pi)^(1/2) in 2D
//!
//! (2D volumes are per unit depth), with V0_i the dry volume from the radius the particle had
//! when the fix was defined and w_i its water mass (`fix dmhs/diffusion`). rhow is the density
//! of the absorbed water in the units of w per volume: the water density if c is a mass per
//! volume, 1 if c is a volume fraction. Water that leaves (w < 0 relative to dry) never shrinks
//! a particle below its dry volume. The radius is updated at the end of every step (and at
//! setup), so contact (pair granular, gran/*, fix wall/gran) and `dmhs/lj/wet ... swell` see the
//! swollen size; the growth r - r0 is kept for dmhs/lj/wet in the ghost-carried array
//! `dmhs/growth`. The mass is not changed (the paper neglects the water's mass in the balance).
//! Granular cutoffs come from the radii at the start of each run: growth within one run must stay
//! within the neighbour skin.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use crate::engine::fields::{GROWTH, WATER};
use crate::engine::water::{radius_of_volume, volume_of_radius};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "fix ID group dmhs/swell rhow";

pub struct FixSwell {
    id: String,
    groupbit: u32,
    rhow: f64,
    /// per-atom dry volume (extra array name)
    store: String,
}

impl FixSwell {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let rhow = a.positive_f64("rhow (density of the absorbed water)")?;
        a.finish()?;
        if !state.atoms.features.sphere {
            return Err(Diagnostic::at(style.span, "fix dmhs/swell needs an atom style with radii (sphere)", "atom style has no radius"));
        }
        if !state.atoms.features.sph {
            return Err(Diagnostic::at(style.span, "fix dmhs/swell needs an atom style with SPH attributes (the water field)", "atom style has no rho"));
        }
        let store = format!("dmhs/swell:{id}");
        let fresh = state.atoms.find_extra(&store).is_none();
        state.atoms.clear_ghosts();
        state.lists_valid = false;
        crate::engine::water::ensure_fields(&mut state.atoms);
        state.atoms.add_field(GROWTH);
        let k = state.atoms.extra_array(&store, 1);
        if fresh {
            // read_restart brings the stored dry volumes back; a new fix takes the current radii
            let dim = state.dimension;
            for i in 0..state.atoms.nlocal {
                state.atoms.extra[k].data[i] = volume_of_radius(state.atoms.radius[i], dim);
            }
        }
        Ok(FixSwell { id, groupbit, rhow, store })
    }

    fn apply(&self, state: &mut State) -> Result<(), RunError> {
        let dim = state.dimension;
        let a = &mut state.atoms;
        let (Some(kv), Some(kw), Some(kg)) = (a.find_extra(&self.store), a.field(WATER), a.field(GROWTH)) else {
            return Err(RunError::new(state.step, "fix dmhs/swell: its per-atom arrays were removed"));
        };
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let v0 = a.extra[kv].data[i];
            if v0 <= 0.0 {
                // an atom created after the fix: its current size is its dry size
                a.extra[kv].data[i] = volume_of_radius(a.radius[i], dim);
                continue;
            }
            let r0 = radius_of_volume(v0, dim);
            let v = v0 + (a.extra[kw].data[i] / self.rhow).max(0.0);
            let r = radius_of_volume(v, dim);
            a.radius[i] = r;
            a.extra[kg].data[i] = r - r0;
        }
        Ok(())
    }
}

impl Fix for FixSwell {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "dmhs/swell"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn setup_pre_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.apply(state)?;
        // ghosts were made before this hook: give them the new sizes
        state.forward_ghost_state();
        Ok(())
    }
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.apply(state)
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.remove_extra(&self.store);
    }
}
