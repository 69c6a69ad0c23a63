//! `compute ID group temp/region region-ID`: the temperature of the group's atoms inside the
//! region, dof = dim (atoms inside) - extra counted at each evaluation (fixes' dof are not
//! removed), as LAMMPS' compute_temp_region.cpp; an atom outside is all bias, so a thermostat
//! given this compute with `fix_modify temp` leaves it alone.

use super::temp_bias::{Bias, ComputeTempBias};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<ComputeTempBias> {
    let mut a = Args::from_words(args, cmd.span, "compute ID group temp/region region-ID");
    let r = a.word("region ID")?;
    if !w.state.regions.iter().any(|x| x.id == r.text) {
        return Err(a.error_at(r, format!("Region {} for compute temp/region does not exist", r.text), "unknown region"));
    }
    a.finish()?;
    Ok(ComputeTempBias::new(id, "temp/region", groupbit, Bias::Region(r.text.clone())))
}
