//! `compute ID group temp`: T = sum(m v^2) * mvv2e / (dof * kB), dof = dim*N - extra - fix dof,
//! counted at the start of each run (or at each evaluation with `compute_modify dynamic/dof
//! yes`), as LAMMPS; extra is the dimension unless `compute_modify extra/dof` sets it.

use super::{expect_no_args, Compute};
use crate::engine::state::State;
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};

/// The degrees-of-freedom bookkeeping every temperature compute shares (LAMMPS' Compute
/// `extra_dof`, `dynamic_user`, `dof_compute` at setup).
#[derive(Clone, Copy, Debug, Default)]
pub struct Dof {
    /// Degrees of freedom removed besides those of fixes (`compute_modify extra/dof`; None: the
    /// style's default, the dimension for the centre-of-mass motion).
    pub extra: Option<f64>,
    /// Count at every evaluation (`compute_modify dynamic/dof yes`) instead of once per run,
    /// when atoms are inserted or lost during it.
    pub dynamic: bool,
    /// The count made at the start of the run.
    pub at_setup: Option<f64>,
}

impl Dof {
    /// `count` (the group's own degrees of freedom) less extra (default `default_extra`) and
    /// those fixes remove.
    pub fn total(&self, w: &World, groupbit: u32, count: f64, default_extra: f64) -> f64 {
        count - (self.extra.unwrap_or(default_extra) + w.fix_dof(groupbit))
    }
    /// The count now: the one made at setup unless dynamic (or not set up yet).
    pub fn current(&self, counted: impl FnOnce() -> f64) -> f64 {
        match self.at_setup {
            Some(d) if !self.dynamic => d,
            _ => counted(),
        }
    }
    pub fn modify(&mut self, extra: Option<f64>, dynamic: Option<bool>) {
        if extra.is_some() {
            self.extra = extra;
        }
        if let Some(d) = dynamic {
            self.dynamic = d;
        }
    }
}

/// mvv2e/(dof kB), 0 without degrees of freedom (LAMMPS' tfactor).
pub fn tfactor(w: &World, dof: f64) -> f64 {
    if dof > 0.0 {
        w.state.units.mvv2e / (dof * w.state.units.boltz)
    } else {
        0.0
    }
}

pub struct ComputeTemp {
    id: String,
    groupbit: u32,
    dof: Dof,
}

impl ComputeTemp {
    pub fn new(id: String, groupbit: u32) -> Self {
        ComputeTemp { id, groupbit, dof: Dof::default() }
    }
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group temp")?;
        Ok(Self::new(id, groupbit))
    }
    /// LAMMPS `dof_compute`: dim N - extra - fix dof.
    fn count_dof(&self, w: &World) -> f64 {
        let dim = w.state.dimension as f64;
        self.dof.total(w, self.groupbit, dim * w.state.group_count(self.groupbit) as f64, dim)
    }
    fn current_dof(&self, w: &World) -> f64 {
        self.dof.current(|| self.count_dof(w))
    }
}

/// T = sum(m v^2) mvv2e / (dof kB) of a group, 0 without degrees of freedom.
pub fn temperature_with(w: &World, groupbit: u32, dof: f64) -> f64 {
    sum_mv2(w.state, groupbit) * tfactor(w, dof)
}

/// sum(m v^2) over the owned atoms of a group, added in LAMMPS' local order (so thermostats
/// that scale by the temperature get LAMMPS' bits).
pub fn sum_mv2(state: &State, groupbit: u32) -> f64 {
    let a = &state.atoms;
    let mut t = 0.0;
    for &i in state.lammps_order.indices(a.nlocal).iter() {
        if a.mask[i] & groupbit != 0 {
            let v = a.v[i];
            t += (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * state.mass(i);
        }
    }
    let mut v = [t];
    state.sum_ranks(&mut v);
    v[0]
}

/// One atom's m v_a v_b added to a kinetic tensor (xx yy zz xy xz yz).
pub fn add_tensor(t: &mut [f64; 6], m: f64, v: [f64; 3]) {
    t[0] += m * v[0] * v[0];
    t[1] += m * v[1] * v[1];
    t[2] += m * v[2] * v[2];
    t[3] += m * v[0] * v[1];
    t[4] += m * v[0] * v[2];
    t[5] += m * v[1] * v[2];
}

/// Kinetic energy tensor mvv2e * sum m v_a v_b (xx yy zz xy xz yz).
pub fn ke_tensor(w: &World, groupbit: u32) -> [f64; 6] {
    let a = &w.state.atoms;
    let mut t = [0.0; 6];
    for i in 0..a.nlocal {
        if a.mask[i] & groupbit != 0 {
            add_tensor(&mut t, w.state.mass(i), a.v[i]);
        }
    }
    w.state.sum_ranks(&mut t);
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
        self.dof.at_setup = Some(self.count_dof(w));
    }
    fn temp_spec(&self) -> Option<super::temp_bias::TempSpec> {
        Some(super::temp_bias::TempSpec { extra: self.dof.extra, ..super::temp_bias::TempSpec::plain(self.groupbit) })
    }
    fn modify_dof(&mut self, extra: Option<f64>, dynamic: Option<bool>) {
        self.dof.modify(extra, dynamic);
    }
}
