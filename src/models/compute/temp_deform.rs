//! `compute ID group temp/deform`: the temperature of the velocities left after the streaming
//! velocity of a box that fix deform changes is taken away: at box fractions l the stream is
//! h_rate l + h_ratelo (LAMMPS' compute_temp_deform.cpp, term by term). dof as compute temp;
//! the vector is the kinetic tensor of the thermal velocities. Fix nvt/sllod thermostats with
//! it; thermostats given it with `fix_modify temp` remove and restore the stream.

use super::expect_no_args;
use super::temp_bias::{Bias, ComputeTempBias};
use dmhs_parser::{Command, DResult, Word};

pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<ComputeTempBias> {
    expect_no_args(args, cmd, "compute ID group temp/deform")?;
    Ok(ComputeTempBias::new(id, "temp/deform", groupbit, Bias::Deform))
}
