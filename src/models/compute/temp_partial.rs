//! `compute ID group temp/partial xflag yflag zflag`: the temperature of the velocity
//! components flagged 1; the others are a bias (removed by thermostats given this compute with
//! `fix_modify temp`). dof = nper N - nper/dim (fix dof + extra), nper the flagged count, as
//! LAMMPS' compute_temp_partial.cpp; the vector is the kinetic tensor of the flagged components.

use super::temp_bias::{Bias, ComputeTempBias};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "compute ID group temp/partial xflag yflag zflag (each 0 or 1)";

pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<ComputeTempBias> {
    let mut a = Args::from_words(args, cmd.span, SYNTAX);
    let mut keep = [false; 3];
    for (k, name) in ["xflag", "yflag", "zflag"].iter().enumerate() {
        keep[k] = a.i64_in(name, 0, 1)? == 1;
    }
    if keep[2] && w.state.dimension == 2 {
        return Err(a.error_at(&args[2], "Compute temp/partial cannot use vz for 2d systems", "must be 0 in 2d"));
    }
    a.finish()?;
    Ok(ComputeTempBias::new(id, "temp/partial", groupbit, Bias::Partial(keep)))
}
