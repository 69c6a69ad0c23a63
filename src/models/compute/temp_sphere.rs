//! `compute ID group temp/sphere [dof all|rotate]`: the temperature of finite-size spheres with
//! their rotation, as LAMMPS: T = (sum m v^2 + sum I w^2) mvv2e/(dof kB) with I = 0.4 m r^2; a
//! sphere has 6 degrees of freedom in 3D (3 in 2D), a point particle (radius 0) 3 (2); `dof
//! rotate` counts rotation only (3 or 1 per sphere, no centre-of-mass correction). The vector is
//! the kinetic energy tensor with the rotational part. The velocity `bias` keyword is refused.

use super::temp::{tfactor, Dof};
use super::Compute;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

const INERTIA: f64 = 0.4;
const SYNTAX: &str = "compute ID group temp/sphere [dof all|rotate]";

pub struct ComputeTempSphere {
    id: String,
    groupbit: u32,
    /// Rotation only (`dof rotate`).
    rotate_only: bool,
    dof: Dof,
}

impl ComputeTempSphere {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mut rotate_only = false;
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "dof" => rotate_only = a.choice("dof mode", &["all", "rotate"])? == 1,
                "bias" => return Err(a.error_at(k, "compute temp/sphere `bias` is not supported yet (temp/sphere with a bias compute)", "not supported")),
                _ => return Err(a.unknown_keyword(k, &["dof", "bias"])),
            }
        }
        if !w.state.atoms.features.sphere {
            return Err(Diagnostic::at(cmd.span, "compute temp/sphere requires atom style sphere", "no sphere attributes"));
        }
        Ok(ComputeTempSphere { id, groupbit, rotate_only, dof: Dof::default() })
    }

    /// LAMMPS `dof_compute`: per-particle counts less extra (0 for `dof rotate`) and fix dof.
    fn count_dof(&self, w: &World) -> f64 {
        let a = &w.state.atoms;
        let three_d = w.state.dimension == 3;
        let (sphere, point) = match (three_d, self.rotate_only) {
            (true, false) => (6, 3),
            (true, true) => (3, 0),
            (false, false) => (3, 2),
            (false, true) => (1, 0),
        };
        let count: i64 = (0..a.nlocal).filter(|&i| a.mask[i] & self.groupbit != 0).map(|i| if a.radius[i] == 0.0 { point } else { sphere }).sum();
        let mut count = [count as f64];
        w.state.sum_ranks(&mut count);
        let default_extra = if self.rotate_only { 0.0 } else { w.state.dimension as f64 };
        self.dof.total(w, self.groupbit, count[0], default_extra)
    }
}

/// t += w (xx yy zz xy xz yz) of `v`, in LAMMPS' order of operations.
fn add_outer(t: &mut [f64; 6], w: f64, v: [f64; 3]) {
    t[0] += w * v[0] * v[0];
    t[1] += w * v[1] * v[1];
    t[2] += w * v[2] * v[2];
    t[3] += w * v[0] * v[1];
    t[4] += w * v[0] * v[2];
    t[5] += w * v[1] * v[2];
}

impl Compute for ComputeTempSphere {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "temp/sphere"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        let a = &w.state.atoms;
        let mut t = 0.0;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let (v, o, m, r) = (a.v[i], a.omega[i], a.rmass[i], a.radius[i]);
                if !self.rotate_only {
                    t += (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * m;
                }
                t += (o[0] * o[0] + o[1] * o[1] + o[2] * o[2]) * INERTIA * m * r * r;
            }
        }
        let mut t = [t];
        w.state.sum_ranks(&mut t);
        let t = t[0];
        let dof = self.dof.current(|| self.count_dof(w));
        if dof < 0.0 && w.state.group_count(self.groupbit) > 0 {
            return Err(format!("compute {}: temperature degrees of freedom < 0", self.id));
        }
        Ok(t * tfactor(w, dof))
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        let a = &w.state.atoms;
        let mut t = [0.0; 6];
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let (v, o) = (a.v[i], a.omega[i]);
                if !self.rotate_only {
                    add_outer(&mut t, a.rmass[i], v);
                }
                add_outer(&mut t, INERTIA * a.rmass[i] * a.radius[i] * a.radius[i], o);
            }
        }
        w.state.sum_ranks(&mut t);
        Ok(t.map(|x| x * w.state.units.mvv2e).to_vec())
    }
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_some()
    }
    fn dof(&self, w: &World) -> Option<f64> {
        Some(self.dof.current(|| self.count_dof(w)))
    }
    fn setup(&mut self, w: &World) {
        self.dof.at_setup = Some(self.count_dof(w));
    }
    fn modify_dof(&mut self, extra: Option<f64>, dynamic: Option<bool>) {
        self.dof.modify(extra, dynamic);
    }
}
