//! `compute ID group temp/ramp vdim vlo vhi dim clo chi [units lattice|box]`: the temperature
//! after the ramped velocity profile is taken away: along `dim`, the `vdim` velocity component
//! has the bias vlo + f (vhi - vlo), f = (x_dim - clo)/(chi - clo) clamped to [0, 1], as LAMMPS'
//! compute_temp_ramp.cpp (lattice units by default, each value scaled by the lattice spacing
//! of its direction). dof as compute temp; the vector is the kinetic tensor of the thermal
//! velocities; thermostats given it with `fix_modify temp` remove and restore the bias.

use super::temp_bias::{Bias, ComputeTempBias, Ramp};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "compute ID group temp/ramp vdim vlo vhi dim clo chi [units lattice|box]  (vdim: vx|vy|vz, dim: x|y|z)";

pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<ComputeTempBias> {
    let mut a = Args::from_words(args, cmd.span, SYNTAX);
    let vdim = a.choice("vdim", &["vx", "vy", "vz"])?;
    let (vlo, vhi) = (a.f64("vlo")?, a.f64("vhi")?);
    let dim = a.choice("dim", &["x", "y", "z"])?;
    let (clo, chi) = (a.f64("clo")?, a.f64("chi")?);
    let mut lattice = true;
    while let Some(k) = a.peek() {
        a.skip(1);
        match k.text.as_str() {
            "units" => lattice = a.choice("units", &["lattice", "box"])? == 0,
            _ => return Err(a.unknown_keyword(k, &["units"])),
        }
    }
    let scale = if lattice {
        w.state.lattice_scale().map_err(|_| a.error_at(&cmd.name, "Use of compute temp/ramp with undefined lattice", "units lattice needs a lattice"))?
    } else {
        [1.0; 3]
    };
    let ramp = Ramp { vdim, vlo: scale[vdim] * vlo, vhi: scale[vdim] * vhi, dim, clo: scale[dim] * clo, chi: scale[dim] * chi };
    Ok(ComputeTempBias::new(id, "temp/ramp", groupbit, Bias::Ramp(ramp)))
}
