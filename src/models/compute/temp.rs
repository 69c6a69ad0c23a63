//! `compute ID group temp`: T = sum(m v^2) * mvv2e / (dof * kB), dof = dim*N - extra - fix dof,
//! counted at the start of each run (or at each evaluation with `compute_modify dynamic/dof
//! yes`), as LAMMPS; extra is the dimension unless `compute_modify extra/dof` sets it.

use super::{expect_no_args, Compute};
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};

pub struct ComputeTemp {
    id: String,
    groupbit: u32,
    /// Degrees of freedom removed besides those of fixes (`compute_modify extra/dof`; LAMMPS'
    /// default is the dimension: the centre-of-mass motion).
    extra_dof: Option<f64>,
    /// Count the degrees of freedom at every evaluation (`compute_modify dynamic/dof yes`)
    /// instead of once per run, when atoms are inserted or lost during it.
    dynamic: bool,
    /// The count made at the start of the run.
    dof_at_setup: Option<f64>,
}

impl ComputeTemp {
    pub fn new(id: String, groupbit: u32) -> Self {
        ComputeTemp { id, groupbit, extra_dof: None, dynamic: false, dof_at_setup: None }
    }
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group temp")?;
        Ok(Self::new(id, groupbit))
    }
    /// LAMMPS `dof_compute`: dim N - extra - fix dof.
    fn count_dof(&self, w: &World) -> f64 {
        let dim = w.state.dimension as f64;
        dim * w.state.group_count(self.groupbit) as f64 - (self.extra_dof.unwrap_or(dim) + w.fix_dof(self.groupbit))
    }
    fn current_dof(&self, w: &World) -> f64 {
        match self.dof_at_setup {
            Some(d) if !self.dynamic => d,
            _ => self.count_dof(w),
        }
    }
}

/// T = sum(m v^2) mvv2e / (dof kB) of a group, 0 without degrees of freedom.
pub fn temperature_with(w: &World, groupbit: u32, dof: f64) -> f64 {
    let a = &w.state.atoms;
    let mut t = 0.0;
    for i in 0..a.nlocal {
        if a.mask[i] & groupbit != 0 {
            let v = a.v[i];
            t += (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * w.state.mass(i);
        }
    }
    let tfactor = if dof > 0.0 { w.state.units.mvv2e / (dof * w.state.units.boltz) } else { 0.0 };
    t * tfactor
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
        Ok(temperature_with(w, self.groupbit, self.current_dof(w)))
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        Ok(ke_tensor(w, self.groupbit).to_vec())
    }
    /// The kinetic energy tensor is extensive; the temperature is not.
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_some()
    }
    fn dof(&self, w: &World) -> Option<f64> {
        Some(self.current_dof(w))
    }
    fn setup(&mut self, w: &World) {
        self.dof_at_setup = Some(self.count_dof(w));
    }
    fn modify_dof(&mut self, extra: Option<f64>, dynamic: Option<bool>) {
        if extra.is_some() {
            self.extra_dof = extra;
        }
        if let Some(d) = dynamic {
            self.dynamic = d;
        }
    }
}
