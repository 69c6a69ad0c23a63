//! The `velocity` command: binds the algorithms of `velocity_create` to the simulation.

use crate::sim::Simulation;
use crate::deck::velocity_create::{Velocity, VelocityAtoms, VelocityEnv};
use dmhs_parser::{Command, DResult, Diagnostic, SourceMap};

pub fn velocity_command(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let vel = Velocity::from_lammps(cmd, sim.dimension, sim.lattice.as_ref())?;
    let gw = &cmd.args[0];
    let bit = sim.groups.bit(&vel.group).ok_or_else(|| Diagnostic::at(gw.span, format!("group `{}` does not exist", vel.group), "unknown group"))?;
    sim.atoms.clear_ghosts();
    let n = sim.atoms.nlocal;
    let selected: Vec<bool> = (0..n).map(|i| sim.atoms.mask[i] & bit != 0).collect();
    let mass: Vec<f64> = (0..n).map(|i| sim.mass(i)).collect();
    // degrees of freedom of the temperature compute (`temp ID` or a default compute temp)
    let dof = match &vel.opts.temp {
        Some(id) => {
            let k = sim.find_compute(id).ok_or_else(|| Diagnostic::at(cmd.span, format!("compute `{id}` does not exist"), "unknown compute"))?;
            sim.computes[k].dof(sim).ok_or_else(|| Diagnostic::at(cmd.span, format!("compute `{id}` is not a temperature compute"), "not a temperature"))?
        }
        None => {
            let d = sim.dimension as f64;
            d * sim.group_count(bit) as f64 - (d + sim.fix_dof(bit))
        }
    };
    let env = VelocityEnv { dimension: sim.dimension, boltz: sim.units.boltz, mvv2e: sim.units.mvv2e, prd: sim.domain.as_ref().unwrap().prd(), dof };
    let mut v = std::mem::take(&mut sim.atoms.v);
    let atoms = VelocityAtoms { ids: &sim.atoms.tag, x: &sim.atoms.x, image: &sim.atoms.image, mass: &mass, selected: &selected };
    let r = vel.apply(&mut v, &atoms, &env);
    sim.atoms.v = v;
    r
}
