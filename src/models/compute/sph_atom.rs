//! `compute ID group sph/rho/atom`, `sph/e/atom`, `sph/t/atom` (LAMMPS SPH package): per-atom
//! density, internal energy, and temperature esph/cv (0 outside the group, and 0 where cv = 0).

use super::{expect_no_args, Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Diagnostic, Word};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum What {
    Rho,
    E,
    T,
}

pub struct ComputeSphAtom {
    id: String,
    groupbit: u32,
    what: What,
}

impl ComputeSphAtom {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        expect_no_args(args, cmd, &format!("compute ID group {}", style.text))?;
        if !w.state.atoms.features.sph {
            return Err(Diagnostic::at(style.span, format!("compute {} needs an atom style with SPH attributes", style.text), "atom style has no rho/esph"));
        }
        let what = match style.text.as_str() {
            "sph/rho/atom" => What::Rho,
            "sph/e/atom" => What::E,
            _ => What::T,
        };
        Ok(ComputeSphAtom { id, groupbit, what })
    }
}

impl Compute for ComputeSphAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        match self.what {
            What::Rho => "sph/rho/atom",
            What::E => "sph/e/atom",
            What::T => "sph/t/atom",
        }
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let a = &w.state.atoms;
        let data = (0..a.nlocal)
            .map(|i| {
                if a.mask[i] & self.groupbit == 0 {
                    return 0.0;
                }
                match self.what {
                    What::Rho => a.rho[i],
                    What::E => a.esph[i],
                    What::T => {
                        if a.cv[i] > 0.0 {
                            a.esph[i] / a.cv[i]
                        } else {
                            0.0
                        }
                    }
                }
            })
            .collect();
        Ok(PerAtom { cols: 1, data })
    }
}
