//! `compute ID group ke`: 0.5 * mvv2e * sum m v^2 over the group.

use super::{expect_no_args, Compute};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};

pub struct ComputeKe {
    id: String,
    groupbit: u32,
}

impl ComputeKe {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group ke")?;
        Ok(ComputeKe { id, groupbit })
    }
}

impl Compute for ComputeKe {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "ke"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        Ok(w.state.kinetic_energy(self.groupbit))
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
