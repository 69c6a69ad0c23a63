//! The internal fix `GROUP_name` of `group name dynamic parent [region R] [var V] [every N]`
//! (LAMMPS' FixGroup): at setup and every N steps at post_integrate, an atom belongs to the
//! group when it is in the parent group, inside region R and V is non-zero for it.

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
    every: i64,
}

impl FixGroup {
    pub fn new(name: &str, parent: u32, gbit: u32, region: Option<String>, var: Option<String>, every: i64) -> FixGroup {
        FixGroup { id: format!("GROUP_{name}"), parent, gbit, region, var, every }
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
        for i in 0..a.nlocal {
            let inside = a.mask[i] & self.parent != 0
                && region.as_ref().is_none_or(|r| r.matches(a.x[i]))
                && var.as_ref().is_none_or(|v| v[i] != 0.0);
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
        FixHooks { post_integrate: true, ..FixHooks::default() }
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
        Ok(())
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.set_group(state, ctx)
    }
    fn post_integrate(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
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
