//! The internal fix `GROUP_name` of `group name dynamic parent [region R] [var V] [property P]
//! [every N]` (LAMMPS' FixGroup): at setup and every N steps at post_force (after the step's
//! wrap into the periodic box, in fix order), an atom belongs
//! to the group when it is in the parent group, inside region R, V is non-zero for it and so is
//! its custom per-atom value P (`i_P` or `d_P` of fix property/atom, or a model's, e.g. mdr's
//! `d_psi`; LAMMPS' find_custom).

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};

pub struct FixGroup {
    id: String,
    /// The parent group (the fix's group in LAMMPS).
    parent: u32,
    /// The dynamic group's bit.
    gbit: u32,
    region: Option<String>,
    var: Option<String>,
    /// The custom per-atom value's name without its `i_`/`d_` prefix.
    property: Option<String>,
    every: i64,
}

/// The per-atom array of custom value `name` (`i_name`, else `d_name`), if the atoms have one.
pub fn find_custom(atoms: &crate::engine::atoms::Atoms, name: &str) -> Option<usize> {
    atoms.find_extra(&format!("i_{name}")).or_else(|| atoms.find_extra(&format!("d_{name}")))
}

impl FixGroup {
    pub fn new(name: &str, parent: u32, gbit: u32, region: Option<String>, var: Option<String>, property: Option<String>, every: i64) -> FixGroup {
        FixGroup { id: format!("GROUP_{name}"), parent, gbit, region, var, property, every }
    }

    fn set_group(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let step = state.step;
        let err = |e: String| RunError::new(step, e);
        let var = match &self.var {
            Some(v) => Some(ctx.eval(state, self, |w, ev| crate::models::atom_formula::atom_variable(v, w, ev))?),
            None => None,
        };
        // a copy of the region, moved to this step (LAMMPS' prematch)
        let region = match &self.region {
            Some(id) => {
                let mut r = state.regions.iter().find(|r| &r.id == id).cloned().ok_or_else(|| err(format!("region {id} for dynamic group does not exist")))?;
                let me: &dyn Fix = self;
                r.prematch(&mut |name| ctx.equal(state, me, name)).map_err(|e| err(format!("{}: region {id}: {e}", self.id)))?;
                Some(r)
            }
            None => None,
        };
        let a = &mut state.atoms;
        let prop = match &self.property {
            Some(p) => Some(find_custom(a, p).ok_or_else(|| err(format!("group dynamic: custom property vector {p} does not exist")))?),
            None => None,
        };
        for i in 0..a.nlocal {
            let inside = a.mask[i] & self.parent != 0
                && region.as_ref().is_none_or(|r| r.matches(a.x[i]))
                && var.as_ref().is_none_or(|v| v[i] != 0.0)
                && prop.is_none_or(|k| a.extra[k].data[i] != 0.0);
            if inside {
                a.mask[i] |= self.gbit;
            } else {
                a.mask[i] &= !self.gbit;
            }
        }
        Ok(())
    }
}

impl Fix for FixGroup {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "GROUP"
    }
    fn groupbit(&self) -> u32 {
        self.parent
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        // LAMMPS: else the order of the FixGroup fixes would matter
        if state.groups.bit_is_dynamic(self.parent) {
            let name = state.groups.names().find(|&(k, _)| 1 << k == self.parent).map(|(_, n)| n.to_string()).unwrap_or_default();
            return Err(format!("Dynamic group parent group {name} cannot be dynamic"));
        }
        if let Some(r) = &self.region {
            if !state.regions.iter().any(|x| &x.id == r) {
                return Err(format!("Region {r} for dynamic group {} does not exist", &self.id[6..]));
            }
        }
        if let Some(p) = &self.property {
            if find_custom(&state.atoms, p).is_none() {
                return Err(format!("Group dynamic command custom property vector {p} does not exist (a fix property/atom i_{p} or d_{p})"));
            }
        }
        Ok(())
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.set_group(state, ctx)
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.every == 0 {
            self.set_group(state, ctx)?;
        }
        Ok(())
    }
    fn min_role(&self) -> super::MinRole {
        super::MinRole::Inert
    }
    fn describe(&self) -> String {
        format!("fix {} (dynamic group, every {} steps)", self.id, self.every)
    }
}
