//! `compute ID group temp/com`: the temperature after the group's centre-of-mass velocity is
//! subtracted (the bias thermostats remove with `fix_modify temp`); dof = dim N - extra - fix
//! dof, as LAMMPS' compute_temp_com.cpp.

use super::expect_no_args;
use super::temp_bias::{Bias, ComputeTempBias};
use dmhs_parser::{Command, DResult, Word};

pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<ComputeTempBias> {
    expect_no_args(args, cmd, "compute ID group temp/com")?;
    Ok(ComputeTempBias::new(id, "temp/com", groupbit, Bias::Com))
}
