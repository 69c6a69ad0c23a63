//! `compute ID group erotate/sphere/atom`: per-atom rotational kinetic energy of finite-size
//! spheres, (w . w) r^2 m times 0.5 mvv2e 0.4 (LAMMPS' order; 0 outside the group).

use super::{expect_no_args, Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Diagnostic, Word};

pub struct ComputeErotateSphereAtom {
    id: String,
    groupbit: u32,
}

impl ComputeErotateSphereAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group erotate/sphere/atom")?;
        if !w.state.atoms.features.sphere {
            return Err(Diagnostic::at(cmd.span, "compute erotate/sphere/atom requires atom style sphere (radius, rmass and omega)", "no sphere attributes"));
        }
        Ok(ComputeErotateSphereAtom { id, groupbit })
    }
}

impl Compute for ComputeErotateSphereAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "erotate/sphere/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let a = &w.state.atoms;
        let pfactor = 0.5 * w.state.units.mvv2e * 0.4;
        let data = (0..a.nlocal)
            .map(|i| match a.mask[i] & self.groupbit {
                0 => 0.0,
                _ => {
                    let o = a.omega[i];
                    (o[0] * o[0] + o[1] * o[1] + o[2] * o[2]) * a.radius[i] * a.radius[i] * a.rmass[i] * pfactor
                }
            })
            .collect();
        Ok(PerAtom { cols: 1, data })
    }
}
