//! `compute ID group displace/atom`: each atom's displacement from where it was when the
//! compute was defined (unwrapped with image flags): dx, dy, dz and its length, as LAMMPS'
//! compute displace/atom. Atoms outside the group get zeros.

use super::{Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};
use std::collections::HashMap;

pub struct ComputeDisplaceAtom {
    id: String,
    groupbit: u32,
    /// Unwrapped positions at definition, by atom ID.
    original: HashMap<i64, [f64; 3]>,
}

impl ComputeDisplaceAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        super::expect_no_args(args, cmd, "compute ID group displace/atom")?;
        let s = w.state;
        let d = s.domain.as_ref().expect("computes are defined after the box");
        let at = &s.atoms;
        let original = (0..at.nlocal).filter(|&i| at.mask[i] & groupbit != 0).map(|i| (at.tag[i], d.unmap(at.x[i], at.image[i]))).collect();
        Ok(ComputeDisplaceAtom { id, groupbit, original })
    }
}

impl Compute for ComputeDisplaceAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "displace/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(4)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let s = w.state;
        let d = s.domain.as_ref().ok_or("no simulation box")?;
        let (at, periods) = (&s.atoms, d.periods());
        let mut data = vec![0.0; 4 * at.nlocal];
        for i in 0..at.nlocal {
            if at.mask[i] & self.groupbit == 0 {
                continue;
            }
            // an atom created later has no reference: it has not moved (LAMMPS' set_arrays)
            let Some(o) = self.original.get(&at.tag[i]) else { continue };
            let u = periods.unmap(at.x[i], at.image[i]);
            let (dx, dy, dz) = (u[0] - o[0], u[1] - o[1], u[2] - o[2]);
            let r = &mut data[4 * i..4 * i + 4];
            r[0] = dx;
            r[1] = dy;
            r[2] = dz;
            r[3] = (dx * dx + dy * dy + dz * dz).sqrt();
        }
        Ok(PerAtom { cols: 4, data })
    }
}
