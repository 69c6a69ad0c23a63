//! `compute ID group ke/rigid fix-ID` and `compute ID group erotate/rigid fix-ID`: the
//! translational (1/2 sum M vcm^2) and rotational (1/2 sum I w_body^2) kinetic energy of the
//! rigid bodies of a fix rigid/small family fix (LAMMPS' extract_ke and extract_erotational,
//! summed in body order, times mvv2e). The compute's group is not used, as in LAMMPS.

use super::Compute;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

/// Which of the bodies' kinetic energies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Part {
    Translational,
    Rotational,
}

pub struct ComputeRigidEnergy {
    id: String,
    groupbit: u32,
    part: Part,
    fix_id: String,
}

impl ComputeRigidEnergy {
    pub fn from_lammps(id: String, groupbit: u32, part: Part, args: &[Word], cmd: &Command) -> DResult<Self> {
        let style = Self::name(part);
        let syntax = format!("compute ID group {style} fix-ID");
        let mut a = Args::from_words(args, cmd.span, &syntax);
        let fix_id = a.word("rigid fix ID")?.text.clone();
        a.finish()?;
        Ok(ComputeRigidEnergy { id, groupbit, part, fix_id })
    }

    fn name(part: Part) -> &'static str {
        match part {
            Part::Translational => "ke/rigid",
            Part::Rotational => "erotate/rigid",
        }
    }
}

impl Compute for ComputeRigidEnergy {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        Self::name(self.part)
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        let style = Self::name(self.part);
        let fix = w.fix(&self.fix_id).ok_or_else(|| format!("fix ID {} for compute {style} does not exist", self.fix_id))?;
        let [ke, erot] = fix.rigid_kinetic().ok_or_else(|| format!("compute {style} with non-rigid fix-ID {}", self.fix_id))?;
        let e = match self.part {
            Part::Translational => ke,
            Part::Rotational => erot,
        };
        Ok(e * w.state.units.mvv2e)
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
