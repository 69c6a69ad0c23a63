//! `compute ID group ke`: 0.5 * mvv2e * sum m v^2 over the group.

use super::{expect_no_args, Compute};
use crate::sim::Simulation;
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
    fn scalar(&self, sim: &Simulation) -> Result<f64, String> {
        Ok(sim.kinetic_energy(self.groupbit))
    }
}
