//! The `velocity` command: binds the algorithms of `velocity_create` to the simulation.

use crate::sim::Simulation;
use crate::deck::velocity_create::{Velocity, VelocityAtoms, VelocityEnv};
use dmhs_parser::{Command, DResult, Diagnostic, SourceMap};

pub fn velocity_command(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let vel = Velocity::from_lammps(cmd, sim.state.dimension, sim.state.lattice.as_ref())?;
    let gw = &cmd.args[0];
    let bit = sim.state.groups.bit(&vel.group).ok_or_else(|| Diagnostic::at(gw.span, format!("group `{}` does not exist", vel.group), "unknown group"))?;
    sim.state.atoms.clear_ghosts();
    let n = sim.state.atoms.nlocal;
    let selected: Vec<bool> = (0..n).map(|i| sim.state.atoms.mask[i] & bit != 0).collect();
    let mass: Vec<f64> = (0..n).map(|i| sim.state.mass(i)).collect();
    // degrees of freedom of the temperature compute (`temp ID` or a default compute temp)
    let dof = match &vel.opts.temp {
        Some(id) => {
            // LAMMPS' velocity counts the compute's degrees of freedom afresh
            if let Some(k) = sim.find_compute(id) {
                sim.setup_computes(Some(k));
            }
            let world = sim.world();
            let c = world.compute(id).ok_or_else(|| Diagnostic::at(cmd.span, format!("compute `{id}` does not exist"), "unknown compute"))?;
            c.dof(&world).ok_or_else(|| Diagnostic::at(cmd.span, format!("compute `{id}` is not a temperature compute"), "not a temperature"))?
        }
        None => {
            let d = sim.state.dimension as f64;
            d * sim.state.group_count(bit) as f64 - (d + sim.world().fix_dof(bit))
        }
    };
    let env = VelocityEnv { dimension: sim.state.dimension, boltz: sim.state.units.boltz, mvv2e: sim.state.units.mvv2e, prd: sim.state.domain.as_ref().unwrap().prd(), dof };
    let mut v = std::mem::take(&mut sim.state.atoms.v);
    let atoms = VelocityAtoms { ids: &sim.state.atoms.tag, x: &sim.state.atoms.x, image: &sim.state.atoms.image, mass: &mass, selected: &selected };
    let r = vel.apply(&mut v, &atoms, &env);
    sim.state.atoms.v = v;
    r
}
