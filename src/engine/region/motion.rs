//! `move v_x v_y v_z` and `rotate v_theta Px Py Pz Rx Ry Rz` of a region: equal-style variables,
//! evaluated once per step by the user of the region (LAMMPS' `prematch`/`pretransform`), that
//! displace and rotate it; and the wall velocity a granular wall feels, inferred by finite
//! difference of the displacement and angle (LAMMPS' `set_velocity`, `velocity_contact`).
//!
//! In LAMMPS' order: a point is moved back first, then rotated back (`inverse`); a point of the
//! region's own frame is rotated first (around the original point P), then moved (`forward`).

use super::{Region, Vec3};
use dmhs_parser::{Args, DResult};

#[derive(Clone, Debug, Default)]
pub struct Motion {
    /// The variables of `move` (None: NULL), if the region moves.
    moving: Option<[Option<String>; 3]>,
    rotation: Option<Rotation>,
    /// Current displacement (`dx dy dz`) and angle (`theta`).
    d: [f64; 3],
    theta: f64,
    vel: Velocity,
}

#[derive(Clone, Debug)]
struct Rotation {
    var: String,
    point: [f64; 3],
    /// The axis as given (LAMMPS' angular velocity is the rate times this, not the unit vector).
    axis: [f64; 3],
    runit: [f64; 3],
}

/// LAMMPS' `prev`, `v`, `omega`, `rpoint` and `vel_timestep`.
#[derive(Clone, Debug, Default)]
struct Velocity {
    /// displacement, angle and (a variable shape's) radius at the previous call
    prev: [f64; 5],
    v: [f64; 3],
    omega: [f64; 3],
    rpoint: [f64; 3],
    /// Step of the last `set_velocity` (None after init: computed again).
    timestep: Option<i64>,
}

fn variable(a: &mut Args, what: &str, null_ok: bool) -> DResult<Option<String>> {
    let w = a.word(what)?;
    if null_ok && w.text == "NULL" {
        return Ok(None);
    }
    match w.text.strip_prefix("v_") {
        Some(name) if !name.is_empty() => Ok(Some(name.to_string())),
        _ => Err(a.error_at(w, format!("region {what} must be an equal-style variable v_name{}, found `{}`", if null_ok { " or NULL" } else { "" }, w.text), "expected v_name")),
    }
}

impl Motion {
    pub fn parse_move(&mut self, a: &mut Args) -> DResult<()> {
        let mut v = [None, None, None];
        for (k, what) in ["move x", "move y", "move z"].iter().enumerate() {
            v[k] = variable(a, what, true)?;
        }
        self.moving = Some(v);
        Ok(())
    }

    pub fn parse_rotate(&mut self, a: &mut Args) -> DResult<()> {
        let var = variable(a, "rotate angle", false)?.unwrap();
        let mut p = [0.0; 6];
        for (k, what) in ["Px", "Py", "Pz", "Rx", "Ry", "Rz"].iter().enumerate() {
            p[k] = a.f64(what)?;
        }
        let axis = [p[3], p[4], p[5]];
        let len = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        if len == 0.0 {
            return Err(a.error_at(a.last().unwrap(), "region cannot have a 0 length rotation vector", "zero axis"));
        }
        let runit = [axis[0] / len, axis[1] / len, axis[2] / len];
        self.rotation = Some(Rotation { var, point: [p[0], p[1], p[2]], axis, runit });
        Ok(())
    }

    /// `units lattice` scales the rotation point (not the axis).
    pub fn scale_point(&mut self, scale: &Vec3) {
        if let Some(r) = &mut self.rotation {
            for d in 0..3 {
                r.point[d] *= scale[d];
            }
        }
    }

    pub fn is_dynamic(&self) -> bool {
        self.moving.is_some() || self.rotation.is_some()
    }

    pub fn rotates(&self) -> bool {
        self.rotation.is_some()
    }

    /// LAMMPS `Region::rotate`: `x` turned by `angle` around the axis through P.
    fn rotate(r: &Rotation, x: [f64; 3], angle: f64) -> [f64; 3] {
        let (sine, cosine) = (angle.sin(), angle.cos());
        let (c, disp) = crate::engine::quat::rotate_about_axis(&r.point, &r.runit, &x, sine, cosine);
        let p = r.point;
        [p[0] + c[0] + disp[0], p[1] + c[1] + disp[1], p[2] + c[2] + disp[2]]
    }

    /// A point of the moved region back in the frame it was defined in (unmove, then unrotate).
    pub fn inverse(&self, mut x: [f64; 3]) -> [f64; 3] {
        if self.moving.is_some() {
            for k in 0..3 {
                x[k] -= self.d[k];
            }
        }
        match &self.rotation {
            Some(r) => Self::rotate(r, x, -self.theta),
            None => x,
        }
    }

    /// A point of the defining frame where the region has taken it (rotate, then move).
    pub fn forward(&self, x: [f64; 3]) -> [f64; 3] {
        let mut x = match &self.rotation {
            Some(r) => Self::rotate(r, x, self.theta),
            None => x,
        };
        if self.moving.is_some() {
            for k in 0..3 {
                x[k] += self.d[k];
            }
        }
        x
    }

    /// LAMMPS `pretransform`: the variables' values now.
    pub fn pretransform(&mut self, equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<(), String> {
        if let Some(vars) = &self.moving {
            for k in 0..3 {
                if let Some(name) = &vars[k] {
                    self.d[k] = equal(name)?;
                }
            }
        }
        if let Some(r) = &self.rotation {
            self.theta = equal(&r.var)?;
        }
        Ok(())
    }

    /// LAMMPS `set_velocity`: velocities from the change since the previous call (zero at step
    /// 0), once per step.
    /// Returns false if they were already computed at this step.
    pub fn set_velocity(&mut self, step: i64, dt: f64) -> bool {
        let v = &mut self.vel;
        if v.timestep == Some(step) {
            return false;
        }
        v.timestep = Some(step);
        if self.moving.is_some() {
            if step > 0 {
                for k in 0..3 {
                    v.v[k] = (self.d[k] - v.prev[k]) / dt;
                }
            } else {
                v.v = [0.0; 3];
            }
            v.prev[..3].copy_from_slice(&self.d);
        }
        if let Some(r) = &self.rotation {
            for k in 0..3 {
                v.rpoint[k] = r.point[k] + self.d[k];
            }
            if step > 0 {
                let angvel = (self.theta - v.prev[3]) / dt;
                for k in 0..3 {
                    v.omega[k] = angvel * r.axis[k];
                }
            } else {
                v.omega = [0.0; 3];
            }
            v.prev[3] = self.theta;
        }
        true
    }

    /// LAMMPS `velocity_contact`: the velocity of the wall at the contact point `x - del`.
    pub fn velocity_contact(&self, x: [f64; 3], del: [f64; 3]) -> [f64; 3] {
        let mut w = [0.0; 3];
        if self.moving.is_some() {
            w = self.vel.v;
        }
        if self.rotation.is_some() {
            let (o, rp) = (self.vel.omega, self.vel.rpoint);
            let xc = [x[0] - del[0], x[1] - del[1], x[2] - del[2]];
            w[0] += o[1] * (xc[2] - rp[2]) - o[2] * (xc[1] - rp[1]);
            w[1] += o[2] * (xc[0] - rp[0]) - o[0] * (xc[2] - rp[2]);
            w[2] += o[0] * (xc[1] - rp[1]) - o[1] * (xc[0] - rp[0]);
        }
        w
    }

    /// LAMMPS `reset_vel`: the previous displacement and angle forgotten (zero).
    pub fn reset_vel(&mut self) {
        self.vel.prev = [0.0; 5];
    }

    /// LAMMPS `Region::init`: the velocities are computed again at the next call.
    pub fn init(&mut self) {
        self.vel.timestep = None;
    }
}

/// Where a shape's variable parameters move its wall: the centre (of a sphere; a point on a
/// cylinder's axis, its axial component 0) in the region's own frame, the radius, and the axis
/// of a cylinder.
#[derive(Clone, Copy, Debug)]
pub struct ShapeFrame {
    pub center: [f64; 3],
    pub radius: f64,
    pub axis: Option<usize>,
}

/// LAMMPS `set_velocity_shape`: the centre moved where the region is, the radius now and at the
/// previous call, and the time step.
#[derive(Clone, Copy, Debug, Default)]
pub struct ShapeVelocity {
    center: [f64; 3],
    radius: f64,
    rprev: f64,
    axis: Option<usize>,
    dt: f64,
}

impl ShapeVelocity {
    /// LAMMPS `velocity_contact_shape`: the wall point `xc` moves with the radius, away from
    /// the centre (not along a cylinder's axis).
    fn add_to(&self, vwall: &mut [f64; 3], xc: [f64; 3]) {
        for d in 0..3 {
            if self.axis == Some(d) {
                continue;
            }
            let del = (xc[d] - self.center[d]) * (1.0 - self.rprev / self.radius);
            vwall[d] += del / self.dt;
        }
    }
}

impl Region {
    /// Whether the region (or a sub-region) moves or changes its shape: LAMMPS `dynamic_check`.
    pub fn is_dynamic(&self) -> bool {
        match &self.kind {
            super::Kind::Shape(_) => self.motion.is_dynamic() || self.varshape(),
            super::Kind::Boolean { subs, .. } => subs.iter().any(Region::is_dynamic),
        }
    }

    /// The wall velocity at contact `del` of the particle at `x`: the region's motion and, for
    /// a contact with a curved wall of a variable shape (`varflag`), its change.
    pub(super) fn wall_velocity(&self, x: [f64; 3], del: [f64; 3], varflag: bool) -> [f64; 3] {
        let mut w = self.motion.velocity_contact(x, del);
        if let (true, Some(sv)) = (varflag, &self.shape_velocity) {
            // LAMMPS 22 Jul 2025 sets the contact point only for a rotating region; otherwise it
            // passes an unset array, which reads as the origin (measured: a shrinking sphere
            // centred at (1, 0, 0) gives LAMMPS' numbers this way, and differs from step 500 of
            // 1000 with the contact point). Reproduced to give LAMMPS' numbers (docs/commands.md).
            let xc = if self.motion.rotates() { [x[0] - del[0], x[1] - del[1], x[2] - del[2]] } else { [0.0; 3] };
            sv.add_to(&mut w, xc);
        }
        w
    }

    /// Whether the region (or a sub-region) rotates: LAMMPS `rotateflag`.
    pub fn rotates(&self) -> bool {
        match &self.kind {
            super::Kind::Shape(_) => self.motion.rotates(),
            super::Kind::Boolean { subs, .. } => subs.iter().any(Region::rotates),
        }
    }

    /// Every region in this one, itself first (mutably).
    fn each_mut(&mut self, f: &mut dyn FnMut(&mut Region)) {
        f(self);
        if let super::Kind::Boolean { subs, .. } = &mut self.kind {
            for s in subs {
                s.each_mut(f);
            }
        }
    }

    /// LAMMPS `prematch`: evaluate the shape and motion variables of the region and its
    /// sub-regions (`shape_update`, then `pretransform`).
    pub fn prematch(&mut self, equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<(), String> {
        let mut result = Ok(());
        self.each_mut(&mut |r| {
            if result.is_ok() {
                result = r.shape_update(&mut *equal).and_then(|_| r.motion.pretransform(&mut *equal));
            }
        });
        result
    }

    /// LAMMPS `set_velocity` (with `set_velocity_shape` for a variable shape), once per step.
    pub fn set_velocity(&mut self, step: i64, dt: f64) {
        self.each_mut(&mut |r| {
            if !r.motion.set_velocity(step, dt) || !r.varshape() {
                return;
            }
            let super::Kind::Shape(shape) = &r.kind else { return };
            let Some(f) = shape.shape_frame() else { return };
            let prev = &mut r.motion.vel.prev[4];
            let rprev = if step > 0 { *prev } else { f.radius };
            *prev = f.radius;
            r.shape_velocity = Some(ShapeVelocity { center: r.motion.forward(f.center), radius: f.radius, rprev, axis: f.axis, dt });
        });
    }

    pub fn reset_vel(&mut self) {
        self.each_mut(&mut |r| r.motion.reset_vel());
    }

    /// LAMMPS `Region::init` of the region and its sub-regions, which a union or intersection
    /// looks up again by ID in `regions` (keeping the motion state of one that is still the same
    /// region); errors name a sub-region that was deleted.
    pub fn init(&mut self, regions: &[Region]) -> Result<(), String> {
        self.motion.init();
        if let super::Kind::Boolean { subs, .. } = &mut self.kind {
            for s in subs.iter_mut() {
                let now = regions.iter().find(|r| r.id == s.id).ok_or_else(|| format!("region {} sub-region `{}` does not exist", self.style, s.id))?;
                if now.serial != s.serial {
                    *s = now.clone();
                }
                s.init(regions)?;
            }
        }
        Ok(())
    }

    /// The equal-style variables the region's motion reads (for checks before a run).
    pub fn motion_variables(&self) -> Vec<String> {
        let mut v = vec![];
        if let Some(m) = &self.motion.moving {
            v.extend(m.iter().flatten().cloned());
        }
        if let Some(r) = &self.motion.rotation {
            v.push(r.var.clone());
        }
        if let Some(sv) = &self.shape_vars {
            v.extend(sv.names.iter().flatten().cloned());
        }
        if let super::Kind::Boolean { subs, .. } = &self.kind {
            for s in subs {
                v.extend(s.motion_variables());
            }
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::region::tests::reg;

    #[test]
    fn rotation_maps_back_and_forth() {
        let mut r = reg("region b block -1 1 -1 1 -1 1 units box rotate v_t 0 0 0 0 0 1", None, None, &[]).unwrap();
        r.prematch(&mut |_| Ok(std::f64::consts::FRAC_PI_4)).unwrap();
        // a corner direction of the turned block is along x
        assert!(r.matches([1.4, 0.0, 0.0]) && !r.matches([1.0, 1.0, 0.0]));
        let x = r.motion.forward(r.motion.inverse([0.3, -0.2, 0.5]));
        assert!((x[0] - 0.3).abs() < 1e-15 && (x[1] + 0.2).abs() < 1e-15 && x[2] == 0.5);
        assert!(r.is_dynamic() && r.rotates());
    }

    #[test]
    fn velocity_by_finite_difference() {
        let mut r = reg("region b block -1 1 -1 1 -1 1 units box move v_x NULL NULL rotate v_t 0 0 0 0 0 2", None, None, &[]).unwrap();
        r.init(&[]).unwrap();
        r.prematch(&mut |n| Ok(if n == "x" { 0.5 } else { 0.1 })).unwrap();
        r.set_velocity(10, 0.5);
        // v = (0.5 - 0) / 0.5; omega = (0.1 - 0) / 0.5 times the axis as given (length 2)
        let w = r.motion.velocity_contact([0.5, 1.0, 0.0], [0.0, 0.0, 0.0]);
        assert!((w[0] - (1.0 - 0.4 * 1.0)).abs() < 1e-15 && (w[1] - 0.4 * 0.0).abs() < 1e-15, "{w:?}");
        r.set_velocity(10, 0.5);
        // at step 0 LAMMPS gives zero velocities
        r.init(&[]).unwrap();
        r.set_velocity(0, 0.5);
        assert_eq!(r.motion.velocity_contact([0.5, 1.0, 0.0], [0.0; 3]), [0.0; 3]);
    }
}
