//! `compute ID group vacf`: the velocity auto-correlation of the group, <vx(0) vx(t)>,
//! <vy(0) vy(t)>, <vz(0) vz(t)> and their sum, averaged over the group's atoms as counted at
//! the start of each run, as LAMMPS' compute vacf. The velocities at time 0 are those when the
//! compute was defined (zero for atoms outside the group then); an atom created later starts
//! from its velocity when first seen (LAMMPS: at its creation).

use super::{expect_no_args, Compute};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};
use std::collections::HashMap;
use std::sync::Mutex;

pub struct ComputeVacf {
    id: String,
    groupbit: u32,
    /// The velocities at time 0 by atom ID (new atoms are added when first seen).
    origin: Mutex<HashMap<i64, [f64; 3]>>,
    /// Atoms in the group at the start of the run (LAMMPS' nvacf, set in init).
    count: usize,
}

impl ComputeVacf {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group vacf")?;
        let a = &w.state.atoms;
        let origin = (0..a.nlocal).map(|i| (a.tag[i], if a.mask[i] & groupbit != 0 { a.v[i] } else { [0.0; 3] })).collect();
        Ok(ComputeVacf { id, groupbit, origin: Mutex::new(origin), count: w.state.group_count(groupbit) })
    }
}

impl Compute for ComputeVacf {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "vacf"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn setup(&mut self, w: &World) {
        self.count = w.state.group_count(self.groupbit);
    }
    fn size_vector(&self) -> Option<usize> {
        Some(4)
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        let s = w.state;
        let a = &s.atoms;
        let mut origin = self.origin.lock().map_err(|_| format!("compute vacf {}: poisoned state", self.id))?;
        let mut c = [0.0; 4];
        for &i in s.lammps_order.indices(a.nlocal).iter().filter(|&&i| a.mask[i] & self.groupbit != 0) {
            let v0 = *origin.entry(a.tag[i]).or_insert(a.v[i]);
            let p = [a.v[i][0] * v0[0], a.v[i][1] * v0[1], a.v[i][2] * v0[2]];
            c[0] += p[0];
            c[1] += p[1];
            c[2] += p[2];
            c[3] += p[0] + p[1] + p[2];
        }
        s.sum_ranks(&mut c);
        if self.count > 0 {
            let n = self.count as f64;
            c.iter_mut().for_each(|v| *v /= n);
        }
        Ok(c.to_vec())
    }
}
