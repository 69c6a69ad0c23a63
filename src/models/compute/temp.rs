//! `compute ID group temp`: T = sum(m v^2) * mvv2e / (dof * kB), dof = dim*N - dim - fix dof.

use super::{expect_no_args, Compute};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};

pub struct ComputeTemp {
    id: String,
    groupbit: u32,
}

impl ComputeTemp {
    pub fn new(id: String, groupbit: u32) -> Self {
        ComputeTemp { id, groupbit }
    }
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group temp")?;
        Ok(Self::new(id, groupbit))
    }
}

/// LAMMPS' temperature of a group with its degrees of freedom.
pub fn temperature(w: &World, groupbit: u32) -> (f64, f64) {
    let a = &w.state.atoms;
    let mut t = 0.0;
    for i in 0..a.nlocal {
        if a.mask[i] & groupbit != 0 {
            let v = a.v[i];
            t += (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * w.state.mass(i);
        }
    }
    let dim = w.state.dimension as f64;
    let dof = dim * w.state.group_count(groupbit) as f64 - (dim + w.fix_dof(groupbit));
    let tfactor = if dof > 0.0 { w.state.units.mvv2e / (dof * w.state.units.boltz) } else { 0.0 };
    (t * tfactor, dof)
}

/// Kinetic energy tensor mvv2e * sum m v_a v_b (xx yy zz xy xz yz).
pub fn ke_tensor(w: &World, groupbit: u32) -> [f64; 6] {
    let a = &w.state.atoms;
    let mut t = [0.0; 6];
    for i in 0..a.nlocal {
        if a.mask[i] & groupbit != 0 {
            let m = w.state.mass(i);
            let v = a.v[i];
            t[0] += m * v[0] * v[0];
            t[1] += m * v[1] * v[1];
            t[2] += m * v[2] * v[2];
            t[3] += m * v[0] * v[1];
            t[4] += m * v[0] * v[2];
            t[5] += m * v[1] * v[2];
        }
    }
    for x in &mut t {
        *x *= w.state.units.mvv2e;
    }
    t
}

impl Compute for ComputeTemp {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "temp"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        Ok(temperature(w, self.groupbit).0)
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        Ok(ke_tensor(w, self.groupbit).to_vec())
    }
    /// The kinetic energy tensor is extensive; the temperature is not.
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_some()
    }
    fn dof(&self, w: &World) -> Option<f64> {
        Some(temperature(w, self.groupbit).1)
    }
}
