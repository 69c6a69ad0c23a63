//! `compute ID group com`: center of mass of the group (unwrapped coordinates).

use super::{expect_no_args, Compute};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};

pub struct ComputeCom {
    id: String,
    groupbit: u32,
}

impl ComputeCom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group com")?;
        Ok(ComputeCom { id, groupbit })
    }
}

impl Compute for ComputeCom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "com"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        Ok(w.state.group_xcm(self.groupbit).0.to_vec())
    }
}
