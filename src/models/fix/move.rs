//! `fix ID group move STYLE args [units box|lattice]`: prescribed motion of a group, as LAMMPS'
//! fix move. Positions come from the unwrapped position each atom had when the fix was defined
//! (the time origin) and the time since; components a style leaves free (NULL) are integrated
//! as by fix nve.
//!
//! * `linear Vx Vy Vz`: x = x0 + V t, v = V.
//! * `wiggle Ax Ay Az period`: x = x0 + A sin(w t), v = A w cos(w t), w = 2 pi / period.
//! * `rotate Px Py Pz Rx Ry Rz period`: rotation about the axis R through P; sets v, and the
//!   angular velocity of finite-size spheres and the orientation of bpm/sphere particles.
//! * `transrot Vx Vy Vz Px Py Pz Rx Ry Rz period`: rotate, then translate by V t (the axis
//!   moves with V).
//! * `variable v_dx v_dy v_dz v_vx v_vy v_vz`: equal-style variables (or NULL). Per dimension:
//!   both given, x = x0 + d and v = vel; displacement only, x = x0 + d (v untouched);
//!   velocity only, v = vel and x += dt v; neither, fix nve.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::quat::{quatquat, rotate_about_axis, Quat};
use crate::engine::state::{RunError, State};
use dmhs_parser::args::word_f64;
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "fix ID group move linear Vx Vy Vz | wiggle Ax Ay Az period | rotate Px Py Pz Rx Ry Rz period | transrot Vx Vy Vz Px Py Pz Rx Ry Rz period | variable v_dx v_dy v_dz v_vx v_vy v_vz [units box|lattice]";

/// The rotation of `rotate` and `transrot`.
#[derive(Clone, Debug)]
struct Rotation {
    point: [f64; 3],
    /// unit vector along the axis
    runit: [f64; 3],
}

#[derive(Clone, Debug)]
enum Motion {
    Linear([Option<f64>; 3]),
    Wiggle([Option<f64>; 3]),
    Rotate(Rotation),
    Transrot([f64; 3], Rotation),
    /// displacement and velocity variable names
    Variable([Option<String>; 3], [Option<String>; 3]),
}

pub struct FixMove {
    id: String,
    groupbit: u32,
    motion: Motion,
    /// 2 pi / period (wiggle, rotate, transrot)
    omega_rotate: f64,
    time_origin: i64,
    /// name of the per-atom array holding the original unwrapped positions, and a 4th value
    /// per atom, 1 once the fix has set them (0: an atom added since, see [`FixMove::adopt`])
    store: String,
    /// name of the per-atom array holding the original orientations (rotations of bpm/sphere)
    qstore: Option<String>,
}

fn number(w: &Word, what: &str) -> DResult<f64> {
    word_f64(w, what).map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))
}

/// A number or NULL.
fn optional(a: &mut Args, what: &str) -> DResult<Option<f64>> {
    let w = a.word(what)?;
    if w.text == "NULL" { Ok(None) } else { number(w, what).map(Some) }
}

fn numbers<const N: usize>(a: &mut Args, what: [&str; N]) -> DResult<[f64; N]> {
    let mut out = [0.0; N];
    for (k, name) in what.iter().enumerate() {
        out[k] = number(a.word(name)?, name)?;
    }
    Ok(out)
}

/// The period (> 0, as LAMMPS requires) and its angular frequency.
fn period(a: &mut Args, style: &str) -> DResult<f64> {
    let w = a.word("period")?;
    let p = number(w, "period")?;
    if !(p > 0.0) {
        return Err(a.error_at(w, format!("illegal fix move {style} period {}", w.text), "the period must be > 0"));
    }
    Ok(std::f64::consts::TAU / p)
}

/// The point and the unit axis of a rotation (LAMMPS' runit, the axis over its length).
fn rotation<'w>(a: &mut Args<'w>) -> DResult<(Rotation, &'w Word)> {
    let point = numbers(a, ["Px", "Py", "Pz"])?;
    let first = a.peek();
    let axis = numbers(a, ["Rx", "Ry", "Rz"])?;
    let len = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let at = first.expect("three axis words were read");
    if len == 0.0 {
        return Err(a.error_at(at, "zero length rotation vector with fix move", "Rx Ry Rz must not all be 0"));
    }
    Ok((Rotation { point, runit: [axis[0] / len, axis[1] / len, axis[2] / len] }, at))
}

/// The name of a per-atom array of the fix, and whether it holds values already. An array of
/// this ID that is there when no fix of the ID exists comes from a restart file (an unfixed fix
/// removes its own): kept, as LAMMPS restores its per-atom restart data. A fix replacing one of
/// the same ID starts afresh (the old one's arrays are removed before it is made). The `:next`
/// name is what a replacing fix used before that order; restart files may still hold it.
fn store_name(state: &State, base: &str, replacing: bool) -> (String, bool) {
    let alt = format!("{base}:next");
    let found = |n: &str| state.atoms.find_extra(n).is_some();
    match (replacing, found(base)) {
        (true, _) => (base.to_string(), false),
        (false, _) if found(&alt) => (alt, true),
        (false, restored) => (base.to_string(), restored),
    }
}

/// `v_name` or NULL (variable style).
fn variable(a: &mut Args, what: &str) -> DResult<Option<String>> {
    let w = a.word(what)?;
    if w.text == "NULL" {
        return Ok(None);
    }
    match w.text.strip_prefix("v_") {
        Some(name) if !name.is_empty() => Ok(Some(name.to_string())),
        _ => Err(a.error_at(w, format!("fix move variable: expected v_name or NULL for {what}, found `{}`", w.text), "v_name or NULL")),
    }
}

impl FixMove {
    /// `replacing`: a fix move of this ID exists (LAMMPS deletes it first: this one starts afresh).
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, replacing: bool, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let style = a.word("move style")?;
        let two_d = state.dimension == 2;
        let refuse_2d = |a: &Args, w: &Word, what: &str| -> Diagnostic { a.error_at(w, format!("fix move cannot {what} for a 2d problem"), "not in 2d") };
        let mut omega_rotate = 0.0;
        let mut motion = match style.text.as_str() {
            "linear" => {
                let v = [optional(&mut a, "Vx")?, optional(&mut a, "Vy")?, optional(&mut a, "Vz")?];
                if two_d && v[2].is_some_and(|z| z != 0.0) {
                    return Err(refuse_2d(&a, style, "set linear z motion"));
                }
                Motion::Linear(v)
            }
            "wiggle" => {
                let amp = [optional(&mut a, "Ax")?, optional(&mut a, "Ay")?, optional(&mut a, "Az")?];
                omega_rotate = period(&mut a, "wiggle")?;
                if two_d && amp[2].is_some_and(|z| z != 0.0) {
                    return Err(refuse_2d(&a, style, "set wiggle z motion"));
                }
                Motion::Wiggle(amp)
            }
            "rotate" | "transrot" => {
                let vel = if style.text == "transrot" { Some(numbers(&mut a, ["Vx", "Vy", "Vz"])?) } else { None };
                let (rot, axis_word) = rotation(&mut a)?;
                // LAMMPS names the rotate period in both styles' message
                omega_rotate = period(&mut a, "rotate")?;
                if two_d && (rot.runit[0] != 0.0 || rot.runit[1] != 0.0) {
                    return Err(refuse_2d(&a, axis_word, "rotate around a non z-axis"));
                }
                if two_d && vel.is_some_and(|v| v[2] != 0.0) {
                    return Err(refuse_2d(&a, style, "set linear z motion"));
                }
                match vel {
                    Some(v) => Motion::Transrot(v, rot),
                    None => Motion::Rotate(rot),
                }
            }
            "variable" => {
                let d = [variable(&mut a, "v_dx")?, variable(&mut a, "v_dy")?, variable(&mut a, "v_dz")?];
                let v = [variable(&mut a, "v_vx")?, variable(&mut a, "v_vy")?, variable(&mut a, "v_vz")?];
                if two_d && (d[2].is_some() || v[2].is_some()) {
                    return Err(refuse_2d(&a, style, "define a z or vz variable"));
                }
                Motion::Variable(d, v)
            }
            other => return Err(a.error_at(style, format!("unknown fix move style `{other}`"), "expected linear, wiggle, rotate, transrot or variable")),
        };
        let lattice_units = a.units_keyword_only()?;
        // LAMMPS scales velocities, amplitudes and the rotation point by the lattice spacings
        // (variables are never scaled)
        if lattice_units {
            let scale = state.lattice_scale().map_err(|e| a.error_at(style, e, "needs a lattice (or `units box`)"))?;
            let scale_opt = |c: &mut [Option<f64>; 3]| c.iter_mut().zip(scale).for_each(|(c, s)| *c = c.map(|c| c * s));
            let scale_all = |c: &mut [f64; 3]| c.iter_mut().zip(scale).for_each(|(c, s)| *c *= s);
            match &mut motion {
                Motion::Linear(v) | Motion::Wiggle(v) => scale_opt(v),
                Motion::Rotate(r) => scale_all(&mut r.point),
                Motion::Transrot(v, r) => {
                    scale_all(v);
                    scale_all(&mut r.point);
                }
                Motion::Variable(..) => {}
            }
        }
        let rotates = matches!(motion, Motion::Rotate(_) | Motion::Transrot(..));
        let domain = state.domain.clone().ok_or_else(|| a.error_at(&cmd.name, "fix move needs a simulation box", "no box yet"))?;
        state.atoms.clear_ghosts();
        state.lists_valid = false;
        let (store, restored) = store_name(state, &format!("fix_move:{id}"), replacing);
        let k = state.atoms.extra_array(&store, 4);
        for i in (0..state.atoms.nlocal).filter(|_| !restored) {
            if state.atoms.mask[i] & groupbit != 0 {
                let u = domain.unmap(state.atoms.x[i], state.atoms.image[i]);
                state.atoms.extra[k].data[4 * i..4 * i + 3].copy_from_slice(&u);
            }
            state.atoms.extra[k].data[4 * i + 3] = 1.0;
        }
        // the orientations a rotation turns (LAMMPS' qoriginal of atoms with a quat)
        let qstore = (rotates && state.atoms.features.quat).then(|| {
            let (name, restored) = store_name(state, &format!("fix_move_quat:{id}"), replacing);
            let k = state.atoms.extra_array(&name, 4);
            for i in (0..state.atoms.nlocal).filter(|_| !restored) {
                if state.atoms.mask[i] & groupbit != 0 {
                    state.atoms.extra[k].data[4 * i..4 * i + 4].copy_from_slice(&state.atoms.quat[i]);
                }
            }
            name
        });
        Ok(FixMove { id, groupbit, motion, omega_rotate, time_origin: state.step, store, qstore })
    }

    /// Atoms added since the last step (fix pour, deposit, create_atoms): their original
    /// positions are backed up from where they were made to the time origin, as LAMMPS'
    /// set_arrays does when they are made. They were made on the step before this one (in the
    /// previous step's pre_exchange, or by a command between runs) and have not moved since.
    fn adopt(&self, state: &mut State, domain: &crate::engine::domain::Domain, k: usize, kq: Option<usize>) -> Result<(), RunError> {
        let made = state.step - 1;
        let delta = (made - self.time_origin) as f64 * state.dt;
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.extra[k].data[4 * i + 3] != 0.0 {
                continue;
            }
            a.extra[k].data[4 * i + 3] = 1.0;
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let mut x0 = domain.unmap(a.x[i], a.image[i]);
            let mut q0 = kq.map(|_| a.quat[i]);
            if made != self.time_origin {
                match &self.motion {
                    Motion::Variable(..) => return Err(RunError::new(state.step, format!("fix {}: cannot add atoms to fix move variable (LAMMPS refuses it too)", self.id))),
                    Motion::Linear(c) => (0..3).for_each(|d| x0[d] -= c[d].map_or(0.0, |v| v * delta)),
                    Motion::Wiggle(c) => {
                        let sine = (self.omega_rotate * delta).sin();
                        (0..3).for_each(|d| x0[d] -= c[d].map_or(0.0, |am| am * sine));
                    }
                    // LAMMPS 22 Jul 2025 turns transrot's atoms back as rotate's (the
                    // translation is not undone) and leaves the stored orientation of a
                    // bpm/sphere atom 0 (so its quat becomes 0): both kept for parity
                    Motion::Rotate(r) | Motion::Transrot(_, r) => {
                        let arg = -self.omega_rotate * delta;
                        let (c, disp) = rotate_about_axis(&r.point, &r.runit, &x0, arg.sin(), arg.cos());
                        x0 = [r.point[0] + c[0] + disp[0], r.point[1] + c[1] + disp[1], r.point[2] + c[2] + disp[2]];
                        q0 = q0.map(|_| [0.0; 4]);
                    }
                }
            }
            a.extra[k].data[4 * i..4 * i + 3].copy_from_slice(&x0);
            if let (Some(kq), Some(q)) = (kq, q0) {
                a.extra[kq].data[4 * i..4 * i + 4].copy_from_slice(&q);
            }
        }
        Ok(())
    }

    /// Which components final_integrate leaves to fix nve (LAMMPS' x/y/zflag).
    fn free(&self) -> [bool; 3] {
        match &self.motion {
            Motion::Linear(c) | Motion::Wiggle(c) => [c[0].is_none(), c[1].is_none(), c[2].is_none()],
            Motion::Rotate(_) | Motion::Transrot(..) => [false; 3],
            Motion::Variable(d, v) => [0, 1, 2].map(|k| d[k].is_none() && v[k].is_none()),
        }
    }

    /// The current values of the variable style's variables.
    fn variables(&self, state: &State, ctx: &mut FixCtx) -> Result<([Option<f64>; 3], [Option<f64>; 3]), RunError> {
        let Motion::Variable(d, v) = &self.motion else { return Ok(([None; 3], [None; 3])) };
        let mut eval = |name: &Option<String>| -> Result<Option<f64>, RunError> {
            match name {
                None => Ok(None),
                Some(n) => ctx.equal(state, self, n).map(Some).map_err(|e| {
                    let note = if e.contains("atom-style") { " (dmhs' fix move takes equal-style variables only)" } else { "" };
                    RunError::new(state.step, format!("fix {} move variable: v_{n}: {e}{note}", self.id))
                }),
            }
        };
        Ok(([eval(&d[0])?, eval(&d[1])?, eval(&d[2])?], [eval(&v[0])?, eval(&v[1])?, eval(&v[2])?]))
    }
}

/// Position and velocity of a point at `x0` rotated by the angle whose sine and cosine are
/// given (LAMMPS' order: projection on the axis, then the in-plane part turned).
fn rotate(r: &Rotation, omega: f64, x0: &[f64], sine: f64, cosine: f64) -> ([f64; 3], [f64; 3]) {
    let (p, u) = (r.point, r.runit);
    let (c, disp) = rotate_about_axis(&p, &u, x0, sine, cosine);
    let x = [p[0] + c[0] + disp[0], p[1] + c[1] + disp[1], p[2] + c[2] + disp[2]];
    let v = [omega * (u[1] * disp[2] - u[2] * disp[1]), omega * (u[2] * disp[0] - u[0] * disp[2]), omega * (u[0] * disp[1] - u[1] * disp[0])];
    (x, v)
}

impl Fix for FixMove {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "move"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn time_integrate(&self) -> bool {
        true
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn initial_integrate(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let delta = (state.step - self.time_origin) as f64 * state.dt;
        let dtv = state.dt;
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let (dvar, vvar) = self.variables(state, ctx)?;
        let domain = state.domain.clone().ok_or_else(|| RunError::new(state.step, "no box"))?;
        let per_atom = state.atoms.features.per_atom_mass();
        let lost = || RunError::new(state.step, "fix move lost its stored values");
        let k = state.atoms.find_extra(&self.store).ok_or_else(lost)?;
        let kq = match &self.qstore {
            Some(name) => Some(state.atoms.find_extra(name).ok_or_else(lost)?),
            None => None,
        };
        self.adopt(state, &domain, k, kq)?;
        let arg = self.omega_rotate * delta;
        let (sine, cosine) = (arg.sin(), arg.cos());
        // the rotation of orientations, by the half angle
        let qrotate = |u: [f64; 3]| -> Quat {
            let (qs, qc) = ((0.5 * arg).sin(), (0.5 * arg).cos());
            [qc, u[0] * qs, u[1] * qs, u[2] * qs]
        };
        let omega = self.omega_rotate;
        let a = &mut state.atoms;
        let spheres = a.features.sphere;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let xold = a.x[i];
            let x0 = &a.extra[k].data[4 * i..4 * i + 3];
            let m = if per_atom { a.rmass[i] } else { state.type_mass[a.typ[i]] };
            let dtfm = dtf / m;
            // fix nve on one component
            let nve = |v: &mut f64, x: &mut f64, f: f64| {
                *v += dtfm * f;
                *x += dtv * *v;
            };
            match &self.motion {
                Motion::Linear(vel) => {
                    for d in 0..3 {
                        match vel[d] {
                            Some(v) => {
                                a.v[i][d] = v;
                                a.x[i][d] = x0[d] + v * delta;
                            }
                            None => nve(&mut a.v[i][d], &mut a.x[i][d], a.f[i][d]),
                        }
                    }
                }
                Motion::Wiggle(amp) => {
                    for d in 0..3 {
                        match amp[d] {
                            Some(am) => {
                                a.v[i][d] = am * omega * cosine;
                                a.x[i][d] = x0[d] + am * sine;
                            }
                            None => nve(&mut a.v[i][d], &mut a.x[i][d], a.f[i][d]),
                        }
                    }
                }
                Motion::Rotate(r) | Motion::Transrot(_, r) => {
                    let (mut x, mut v) = rotate(r, omega, x0, sine, cosine);
                    if spheres && a.radius[i] > 0.0 {
                        a.omega[i] = [omega * r.runit[0], omega * r.runit[1], omega * r.runit[2]];
                    }
                    if let Some(kq) = kq {
                        let q0: Quat = a.extra[kq].data[4 * i..4 * i + 4].try_into().expect("4 values");
                        a.quat[i] = quatquat(&qrotate(r.runit), &q0);
                    }
                    // transrot: the axis moves with the velocity
                    if let Motion::Transrot(vel, _) = &self.motion {
                        for d in 0..3 {
                            v[d] += vel[d];
                            x[d] += vel[d] * delta;
                        }
                    }
                    a.x[i] = x;
                    a.v[i] = v;
                }
                Motion::Variable(..) => {
                    for d in 0..3 {
                        match (dvar[d], vvar[d]) {
                            (Some(dx), vel) => {
                                if let Some(vel) = vel {
                                    a.v[i][d] = vel;
                                }
                                a.x[i][d] = x0[d] + dx;
                            }
                            (None, Some(vel)) => {
                                a.v[i][d] = vel;
                                a.x[i][d] += dtv * vel;
                            }
                            (None, None) => nve(&mut a.v[i][d], &mut a.x[i][d], a.f[i][d]),
                        }
                    }
                }
            }
            domain.remap_near(&mut a.x[i], &xold);
        }
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let free = self.free();
        if !free.iter().any(|&f| f) {
            return Ok(());
        }
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let per_atom = state.atoms.features.per_atom_mass();
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let m = if per_atom { a.rmass[i] } else { state.type_mass[a.typ[i]] };
            let dtfm = dtf / m;
            for d in 0..3 {
                if free[d] {
                    a.v[i][d] += dtfm * a.f[i][d];
                }
            }
        }
        Ok(())
    }
    /// LAMMPS' global restart state: the time origin (the per-atom arrays travel with the atoms).
    fn write_restart(&self) -> Option<Vec<f64>> {
        Some(vec![self.time_origin as f64])
    }
    fn restart(&mut self, values: &[f64]) {
        if let Some(&t) = values.first() {
            self.time_origin = t as i64;
        }
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.remove_extra(&self.store);
        if let Some(q) = &self.qstore {
            state.atoms.remove_extra(q);
        }
    }
}
