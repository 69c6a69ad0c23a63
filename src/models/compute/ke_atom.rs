//! `compute ID group ke/atom`: per-atom kinetic energy 0.5 mvv2e m v^2 (0 outside the group),
//! in LAMMPS' order of operations ((0.5 mvv2e) m) (vx^2 + vy^2 + vz^2).

use super::{expect_no_args, Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};

pub struct ComputeKeAtom {
    id: String,
    groupbit: u32,
}

impl ComputeKeAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group ke/atom")?;
        Ok(ComputeKeAtom { id, groupbit })
    }
}

impl Compute for ComputeKeAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "ke/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let (s, a) = (w.state, &w.state.atoms);
        let mvv2e = s.units.mvv2e;
        let data = (0..a.nlocal)
            .map(|i| match a.mask[i] & self.groupbit {
                0 => 0.0,
                _ => {
                    let v = a.v[i];
                    0.5 * mvv2e * s.mass(i) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
                }
            })
            .collect();
        Ok(PerAtom { cols: 1, data })
    }
}
