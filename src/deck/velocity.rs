//! The `velocity` command: binds the algorithms of `velocity_create` to the simulation.

use crate::deck::velocity_create::{SetArg, Velocity, VelocityAtoms, VelocityEnv, VelocityStyle, VelocityTemp};
use crate::engine::state::State;
use crate::models::compute::temp_bias::{Bias, TempSpec};
use crate::sim::Simulation;
use dmhs_parser::{Command, DResult, Diagnostic, SourceMap, Word};

/// The `temp ID` compute measured on the velocities velocity is changing (they are copied into
/// the state, which is otherwise the one the command runs on).
struct ComputeTemp<'a> {
    state: &'a mut State,
    spec: TempSpec,
    dof: f64,
}

impl ComputeTemp<'_> {
    fn load(&mut self, v: &[[f64; 3]]) {
        self.state.atoms.v = v.to_vec();
    }
}

impl VelocityTemp for ComputeTemp<'_> {
    fn temperature(&mut self, v: &[[f64; 3]]) -> Result<f64, String> {
        self.load(v);
        Ok(self.spec.temperature(self.state, self.dof)?.0)
    }
    fn bias(&mut self, v: &[[f64; 3]]) -> Result<Vec<[f64; 3]>, String> {
        self.load(v);
        Ok(self.spec.field(self.state, self.spec.groupbit)?.unwrap_or_else(|| vec![[0.0; 3]; v.len()]))
    }
    fn reapply(&mut self, v: &mut [[f64; 3]]) {
        self.spec.reapply(self.state, v);
    }
}

pub fn velocity_command(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut vel = Velocity::from_lammps(cmd, sim.state.dimension, sim.state.lattice.as_ref())?;
    let gw = &cmd.args[0];
    let bit = sim.state.groups.bit(&vel.group).ok_or_else(|| Diagnostic::at(gw.span, format!("group `{}` does not exist", vel.group), "unknown group"))?;
    sim.state.atoms.clear_ghosts();
    if let VelocityStyle::Set { v } = &mut vel.style {
        for arg in v.iter_mut() {
            if let SetArg::Variable(w) = arg {
                *arg = set_variable(sim, &w.clone())?;
            }
        }
    }
    let n = sim.state.atoms.nlocal;
    let selected: Vec<bool> = (0..n).map(|i| sim.state.atoms.mask[i] & bit != 0).collect();
    let mass: Vec<f64> = (0..n).map(|i| sim.state.mass(i)).collect();
    // degrees of freedom of a compute temp over the group (velocity's own, or bias yes')
    let d = sim.state.dimension as f64;
    let dof = d * sim.state.group_count(bit) as f64 - (d + sim.world().fix_dof(bit));
    // the `temp ID` compute: its measure and degrees of freedom counted afresh, as LAMMPS' velocity
    let tc = match &vel.opts.temp {
        Some(id) => {
            let k = sim.find_compute(id).ok_or_else(|| Diagnostic::at(cmd.span, format!("Could not find velocity temperature compute ID `{id}`"), "unknown compute"))?;
            sim.setup_computes(Some(k));
            let (spec, cdof, style) = {
                let world = sim.world();
                let c = &sim.computes[k];
                (c.temp_spec(), c.dof(&world), c.style().to_string())
            };
            let (Some(spec), Some(cdof)) = (spec, cdof) else {
                return Err(Diagnostic::at(cmd.span, format!("velocity temperature compute `{id}` ({style}) is not a temperature dmhs' velocity takes (temp, temp/partial, temp/com, temp/region)"), "not a translational temperature"));
            };
            if spec.groupbit != bit {
                sim.out.print("WARNING: Mismatch between velocity and compute groups");
            }
            if vel.opts.bias && spec.bias == Bias::None {
                return Err(Diagnostic::at(cmd.span, format!("Velocity temperature ID `{id}` does not calculate a velocity bias (bias yes)"), "no bias"));
            }
            Some((spec, cdof))
        }
        None if vel.opts.bias => return Err(Diagnostic::at(cmd.span, "Cannot use velocity bias command without temp keyword", "bias yes needs temp ID")),
        None => None,
    };
    let env = VelocityEnv { dimension: sim.state.dimension, boltz: sim.state.units.boltz, mvv2e: sim.state.units.mvv2e, periods: sim.state.domain.as_ref().unwrap().periods(), dof };
    let mut v = std::mem::take(&mut sim.state.atoms.v);
    let (ids, x, image) = (sim.state.atoms.tag.clone(), sim.state.atoms.x.clone(), sim.state.atoms.image.clone());
    let atoms = VelocityAtoms { ids: &ids, x: &x, image: &image, mass: &mass, selected: &selected };
    let r = match tc {
        Some((spec, dof)) => {
            let mut t = ComputeTemp { state: &mut sim.state, spec, dof };
            vel.apply(&mut v, &atoms, &env, Some(&mut t))
        }
        None => vel.apply(&mut v, &atoms, &env, None),
    };
    sim.state.atoms.v = v;
    r
}

/// A `velocity set` component `v_name`: an equal-style variable's value or an atom-style one's
/// values over the local atoms.
fn set_variable(sim: &mut Simulation, w: &Word) -> DResult<SetArg> {
    use crate::deck::commands::atoms_cmds::{equal_or_atom_variable, SetValue};
    Ok(match equal_or_atom_variable(sim, w, "velocity set")? {
        SetValue::One(x) => SetArg::Value(x),
        SetValue::PerAtom(v) => SetArg::PerAtom(v),
    })
}
