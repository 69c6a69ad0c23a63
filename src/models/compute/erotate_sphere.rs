//! `compute ID group erotate/sphere`: rotational kinetic energy of finite-size spheres,
//! 0.5 mvv2e sum I w^2 with I = 0.4 m r^2 (solid spheres, also in 2D, as LAMMPS).

use super::{expect_no_args, Compute};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Diagnostic, Word};

pub struct ComputeErotateSphere {
    id: String,
    groupbit: u32,
}

impl ComputeErotateSphere {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group erotate/sphere")?;
        if !w.state.atoms.features.sphere {
            return Err(Diagnostic::at(cmd.span, "compute erotate/sphere requires atom attributes radius, rmass and omega (atom_style sphere)", "no sphere attributes"));
        }
        Ok(ComputeErotateSphere { id, groupbit })
    }
}

impl Compute for ComputeErotateSphere {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "erotate/sphere"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        let a = &w.state.atoms;
        let mut e = 0.0;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let o = a.omega[i];
                e += (o[0] * o[0] + o[1] * o[1] + o[2] * o[2]) * a.radius[i] * a.radius[i] * a.rmass[i];
            }
        }
        let mut v = [e];
        w.state.sum_ranks(&mut v);
        Ok(v[0] * (0.5 * w.state.units.mvv2e * 0.4))
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
