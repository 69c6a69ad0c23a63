//! The integrator of `fix rigid/nve/small`, `rigid/nvt/small`, `rigid/npt/small` and
//! `rigid/nph/small` (LAMMPS' FixRigidNHSmall, 22 Jul 2025; Kamberaj et al., J. Chem. Phys. 122,
//! 224114 (2005); Miller et al., J. Chem. Phys. 116, 8649 (2002)). The bodies are set up and
//! their atoms placed as by rigid/small (rigid_small.rs); what differs is the step: the
//! orientation moves with its conjugate quaternion momentum by the NO_SQUISH splitting (free
//! rotations about body axes 3, 2, 1, 2, 3). With `temp Tstart Tstop Tdamp` the bodies'
//! translational and rotational kinetic energies each drive a Nose-Hoover chain (`tparam Tchain
//! Titer Torder`, default 10 1 3); with `iso|aniso|x|y|z Pstart Pstop Pdamp` a barostat
//! (its own chain, `pchain`, default 10) scales the box about its centre by half steps around
//! the placing of the atoms, and the bodies' momenta with it. The chains are integrated with
//! Yoshida-Suzuki weights.

use super::box_stress::{dilate_box, Couple};
use super::rigid_small::Body;
use crate::engine::quat;
use crate::engine::state::State;

/// Principal moments below this count no rotational degree of freedom (LAMMPS' EPSILON).
const EPSILON: f64 = 1.0e-7;

/// `temp Tstart Tstop Tdamp`: a Nose-Hoover chain on the translational and one on the
/// rotational kinetic energy.
#[derive(Clone, Debug)]
pub struct Chains {
    pub t_start: f64,
    pub t_stop: f64,
    pub t_freq: f64,
    q_t: Vec<f64>,
    q_r: Vec<f64>,
    eta_t: Vec<f64>,
    eta_r: Vec<f64>,
    eta_dot_t: Vec<f64>,
    eta_dot_r: Vec<f64>,
    f_eta_t: Vec<f64>,
    f_eta_r: Vec<f64>,
}

impl Chains {
    pub fn new(t_start: f64, t_stop: f64, t_period: f64, t_chain: usize) -> Self {
        let z = vec![0.0; t_chain];
        Chains { t_start, t_stop, t_freq: 1.0 / t_period, q_t: z.clone(), q_r: z.clone(), eta_t: z.clone(), eta_r: z.clone(), eta_dot_t: z.clone(), eta_dot_r: z.clone(), f_eta_t: z.clone(), f_eta_r: z }
    }
}

/// `iso|aniso|x|y|z Pstart Pstop Pdamp`, `couple`, `dilate`, `pchain`: the barostat.
#[derive(Clone, Debug)]
pub struct Baro {
    pub p_start: [f64; 3],
    pub p_stop: [f64; 3],
    pub p_flag: [bool; 3],
    p_freq: [f64; 3],
    pub couple: Couple,
    /// The scalar pressure is coupled (LAMMPS' pstyle ISO: couple xyz, or xy in 2d).
    pub iso: bool,
    /// `dilate group`: the group bit of the atoms remapped with the box (None: all).
    pub dilate: Option<u32>,
    epsilon_mass: [f64; 3],
    epsilon: [f64; 3],
    epsilon_dot: [f64; 3],
    q_b: Vec<f64>,
    eta_b: Vec<f64>,
    eta_dot_b: Vec<f64>,
    f_eta_b: Vec<f64>,
    p_target: [f64; 3],
    p_hydro: f64,
    /// The coupled current pressure, measured by the caller.
    pub p_current: [f64; 3],
    /// The degrees of freedom of that pressure's temperature (group all), counted at setup.
    pub dof: f64,
    p_freq_max: f64,
    pdim: usize,
    vol0: f64,
    mtk_term1: f64,
    mtk_term2: f64,
}

impl Baro {
    pub fn new(p_start: [f64; 3], p_stop: [f64; 3], p_period: [f64; 3], p_flag: [bool; 3], couple: Couple, dilate: Option<u32>, p_chain: usize, dimension: usize) -> Self {
        let p_freq = std::array::from_fn(|k| if p_flag[k] { 1.0 / p_period[k] } else { 0.0 });
        let iso = matches!(couple, Couple::Xyz) || (dimension == 2 && matches!(couple, Couple::Xy));
        let z = vec![0.0; p_chain];
        Baro {
            p_start,
            p_stop,
            p_flag,
            p_freq,
            couple,
            iso,
            dilate,
            epsilon_mass: [0.0; 3],
            epsilon: [0.0; 3],
            epsilon_dot: [0.0; 3],
            q_b: z.clone(),
            eta_b: z.clone(),
            eta_dot_b: z.clone(),
            f_eta_b: z,
            p_target: [0.0; 3],
            p_hydro: 0.0,
            p_current: [0.0; 3],
            dof: 0.0,
            p_freq_max: 0.0,
            pdim: p_flag.iter().filter(|&&f| f).count(),
            vol0: 0.0,
            mtk_term1: 0.0,
            mtk_term2: 0.0,
        }
    }

    /// LAMMPS' compute_press_target.
    fn press_target(&mut self, fraction: f64) {
        self.p_hydro = 0.0;
        for i in 0..3 {
            if self.p_flag[i] {
                self.p_target[i] = self.p_start[i] + fraction * (self.p_stop[i] - self.p_start[i]);
                self.p_hydro += self.p_target[i];
            }
        }
        self.p_hydro /= self.pdim as f64;
    }
}

/// LAMMPS' maclaurin_series: sinh(x)/x to the x^8 term.
fn maclaurin_series(x: f64) -> f64 {
    let x2 = x * x;
    let x4 = x2 * x2;
    1.0 + (1.0 / 6.0) * x2 + (1.0 / 120.0) * x4 + (1.0 / 5040.0) * x2 * x4 + (1.0 / 362880.0) * x4 * x4
}

/// Half a step of a chain link's velocity driven by its force and damped by the next link's
/// velocity, exp(-c tmp) per quarter (c = 1 for the thermostats' chains, 1/2 for the barostat's
/// in LAMMPS).
fn chain_kick(eta_dot: f64, f_eta: f64, next_eta_dot: f64, wdti2: f64, wdti4: f64, c: f64) -> f64 {
    let tmp = wdti4 * next_eta_dot;
    let ms = maclaurin_series(tmp);
    let s = (-c * tmp).exp();
    let s2 = s * s;
    eta_dot * s2 + wdti2 * f_eta * s * ms
}

/// One Yoshida-Suzuki sweep of a chain of masses `q` and forces `f` (LAMMPS' loops of
/// nhc_temp_integrate and nhc_press_integrate), `kt` the target of links beyond the first.
fn chain_sweep(eta: &mut [f64], eta_dot: &mut [f64], f_eta: &mut [f64], q: &[f64], kt: f64, (w1, w2, w4): (f64, f64, f64), c: f64) {
    let n = eta.len();
    eta_dot[n - 1] += w2 * f_eta[n - 1];
    for k in 1..n {
        eta_dot[n - k - 1] = chain_kick(eta_dot[n - k - 1], f_eta[n - k - 1], eta_dot[n - k], w2, w4, c);
    }
    for k in 0..n {
        eta[k] += w1 * eta_dot[k];
    }
    for k in 1..n {
        f_eta[k] = q[k - 1] * eta_dot[k - 1] * eta_dot[k - 1] - kt;
        f_eta[k] /= q[k];
    }
    for k in 0..n - 1 {
        eta_dot[k] = chain_kick(eta_dot[k], f_eta[k], eta_dot[k + 1], w2, w4, c);
        f_eta[k + 1] = (q[k] * eta_dot[k] * eta_dot[k] - kt) / q[k + 1];
    }
    eta_dot[n - 1] += w2 * f_eta[n - 1];
}

/// fix rigid's per-body force and torque switches (1 on, 0 off), None for the /small styles.
pub type Flags<'a> = Option<(&'a [[f64; 3]], &'a [[f64; 3]])>;

/// Body `n`'s switches (all on without flags: a multiplication by 1 changes no bit).
fn body_flags(flags: Flags, n: usize) -> ([f64; 3], [f64; 3]) {
    flags.map_or(([1.0; 3], [1.0; 3]), |(f, t)| (f[n], t[n]))
}

/// The state of the NO_SQUISH integrator over the fix's bodies.
#[derive(Clone, Debug)]
pub struct RigidNh {
    pub chains: Option<Chains>,
    pub baro: Option<Baro>,
    /// `fix_modify dynamic/dof yes`: recount the degrees of freedom every step.
    pub dynamic: bool,
    t_iter: usize,
    /// Yoshida-Suzuki weights (3 or 5) and their step fractions.
    w: Vec<f64>,
    wdti1: Vec<f64>,
    wdti2: Vec<f64>,
    wdti4: Vec<f64>,
    t_target: f64,
    nf_t: i64,
    nf_r: i64,
    akin_t: f64,
    akin_r: f64,
}

/// Timestep factors (LAMMPS' dtv, dtf, dtq).
pub struct Steps {
    pub dtv: f64,
    pub dtf: f64,
    pub dtq: f64,
}

impl RigidNh {
    /// `tparam`'s Titer and Torder (checked by the caller: 1 or more; 3 or 5).
    pub fn new(chains: Option<Chains>, baro: Option<Baro>, t_iter: usize, t_order: usize) -> Self {
        let w = if t_order == 3 {
            let w0 = 1.0 / (2.0 - 2.0f64.powf(1.0 / 3.0));
            vec![w0, 1.0 - 2.0 * w0, w0]
        } else {
            let w0 = 1.0 / (4.0 - 4.0f64.powf(1.0 / 3.0));
            vec![w0, w0, 1.0 - 4.0 * w0, w0, w0]
        };
        let n = w.len();
        RigidNh { chains, baro, dynamic: false, t_iter, w, wdti1: vec![0.0; n], wdti2: vec![0.0; n], wdti4: vec![0.0; n], t_target: 0.0, nf_t: 0, nf_r: 0, akin_t: 0.0, akin_r: 0.0 }
    }

    fn stat(&self) -> bool {
        self.chains.is_some() || self.baro.is_some()
    }

    /// Translational and rotational degrees of freedom of the bodies (LAMMPS' compute_dof).
    fn compute_dof(&mut self, bodies: &[Body], dimension: usize) {
        let n = bodies.len() as i64;
        self.nf_t = dimension as i64 * n;
        self.nf_r = if dimension == 3 {
            let zero = bodies.iter().map(|b| b.inertia.iter().filter(|i| i.abs() < EPSILON).count() as i64).sum::<i64>();
            3 * n - zero
        } else {
            n
        };
    }

    fn g_f(&self) -> i64 {
        self.nf_t + self.nf_r
    }

    fn kinetic(&mut self, bodies: &[Body]) {
        let (mut t, mut r) = (0.0, 0.0);
        for b in bodies {
            t += b.mass * (b.vcm[0] * b.vcm[0] + b.vcm[1] * b.vcm[1] + b.vcm[2] * b.vcm[2]);
            r += b.angmom[0] * b.omega[0] + b.angmom[1] * b.omega[1] + b.angmom[2] * b.omega[2];
        }
        (self.akin_t, self.akin_r) = (t, r);
    }

    fn temp_target(&mut self, fraction: f64) {
        if let Some(c) = &self.chains {
            self.t_target = c.t_start + fraction * (c.t_stop - c.t_start);
        }
    }

    /// LAMMPS' FixRigidNHSmall::init for the barostat: its largest frequency and the
    /// reference volume (kept from the first run).
    pub fn init(&mut self, volume: f64) {
        if let Some(b) = self.baro.as_mut() {
            b.p_freq_max = b.p_freq.iter().fold(0.0, |m: f64, &f| m.max(f));
            if b.vol0 == 0.0 {
                b.vol0 = volume;
            }
        }
    }

    /// LAMMPS' FixRigidNHSmall::setup after rigid/small's: the degrees of freedom, each body's
    /// conjugate quaternion momentum from its angular momentum, the target temperature (nph:
    /// `t_now`, the temperature of group all, 1 if zero), the chains' and the barostat's masses
    /// and forces; the barostat's first box force from `p_current` (set by the caller).
    pub fn setup(&mut self, bodies: &mut [Body], dimension: usize, u: &crate::engine::units::Units, fraction: f64, dt: f64, t_now: f64, volume: f64) {
        self.compute_dof(bodies, dimension);
        for b in bodies.iter_mut() {
            let mbody = quat::transpose_matvec_cols(&b.ex, &b.ey, &b.ez, &b.angmom);
            b.conjqm = quat::quatvec(&b.quat, &mbody);
            for c in b.conjqm.iter_mut() {
                *c *= 2.0;
            }
        }
        if self.stat() {
            self.kinetic(bodies);
        }
        if self.chains.is_some() {
            self.temp_target(fraction);
        } else if self.baro.is_some() {
            self.t_target = if t_now == 0.0 { 1.0 } else { t_now };
        }
        let (nf_t, nf_r, g_f) = (self.nf_t as f64, self.nf_r as f64, self.g_f());
        let kt = u.boltz * self.t_target;
        if let Some(c) = self.chains.as_mut() {
            let t_mass = kt / (c.t_freq * c.t_freq);
            c.q_t[0] = nf_t * t_mass;
            c.q_r[0] = nf_r * t_mass;
            for i in 1..c.q_t.len() {
                c.q_t[i] = t_mass;
                c.q_r[i] = t_mass;
            }
            for i in 1..c.q_t.len() {
                c.f_eta_t[i] = (c.q_t[i - 1] * c.eta_dot_t[i - 1] * c.eta_dot_t[i - 1] - kt) / c.q_t[i];
                c.f_eta_r[i] = (c.q_r[i - 1] * c.eta_dot_r[i - 1] * c.eta_dot_r[i - 1] - kt) / c.q_r[i];
            }
        }
        if let Some(b) = self.baro.as_mut() {
            for i in 0..3 {
                if b.p_flag[i] {
                    b.epsilon_mass[i] = (g_f + dimension as i64) as f64 * kt / (b.p_freq[i] * b.p_freq[i]);
                    b.epsilon[i] = b.vol0.ln() / dimension as f64;
                }
            }
            let tb_mass = kt / (b.p_freq_max * b.p_freq_max);
            b.q_b[0] = (dimension * dimension) as f64 * tb_mass;
            for i in 1..b.q_b.len() {
                b.q_b[i] = tb_mass;
                b.f_eta_b[i] = (b.q_b[i] * b.eta_dot_b[i - 1] * b.eta_dot_b[i - 1] - kt) / b.q_b[i];
            }
        }
        if self.stat() {
            for j in 0..self.w.len() {
                self.wdti1[j] = self.w[j] * dt / self.t_iter as f64;
                self.wdti2[j] = self.wdti1[j] / 2.0;
                self.wdti4[j] = self.wdti1[j] / 4.0;
            }
        }
        if self.baro.is_some() {
            self.epsilon_dot(u, 0.5 * dt, volume, fraction);
        }
    }

    /// The momenta's half-step scaling by the chains and the box (LAMMPS' scale_t, scale_r).
    fn scales(&self, dtq: f64) -> ([f64; 3], f64) {
        let (mut scale_t, mut scale_r) = ([1.0; 3], 1.0);
        if let Some(c) = &self.chains {
            scale_t = [(-dtq * c.eta_dot_t[0]).exp(); 3];
            scale_r = (-dtq * c.eta_dot_r[0]).exp();
        }
        if let Some(b) = &self.baro {
            for k in 0..3 {
                scale_t[k] *= (-dtq * (b.epsilon_dot[k] + b.mtk_term2)).exp();
            }
            scale_r *= (-dtq * (b.pdim as f64 * b.mtk_term2)).exp();
        }
        (scale_t, scale_r)
    }

    /// The first half of the step (LAMMPS' initial_integrate, steps 1.1 to 1.13 of Kamberaj
    /// et al.), then the chains' full step. The caller then remaps the box (with a barostat),
    /// places the atoms (set_xv) and remaps again.
    /// `flags`: fix rigid's per-body force and torque switches (FixRigidNH multiplies them into
    /// the kick and the torque; None for the /small styles).
    #[allow(clippy::too_many_arguments)]
    pub fn initial_integrate(&mut self, bodies: &mut [Body], s: &Steps, dimension: usize, u: &crate::engine::units::Units, fraction: f64, flags: Flags) {
        let dtf2 = s.dtf * 2.0;
        let (scale_t, scale_r) = self.scales(s.dtq);
        let scale_v: Option<[f64; 3]> = self.baro.as_ref().map(|b| {
            std::array::from_fn(|k| {
                let tmp = s.dtq * b.epsilon_dot[k];
                s.dtv * tmp.exp() * maclaurin_series(tmp)
            })
        });
        let stat = self.stat();
        for (n, b) in bodies.iter_mut().enumerate() {
            let (ff, tf) = body_flags(flags, n);
            let dtfm = s.dtf / b.mass;
            for k in 0..3 {
                b.vcm[k] += dtfm * b.fcm[k] * ff[k];
            }
            if stat {
                for k in 0..3 {
                    b.vcm[k] *= scale_t[k];
                }
            }
            match scale_v {
                None => {
                    for k in 0..3 {
                        b.xcm[k] += s.dtv * b.vcm[k];
                    }
                }
                Some(v) => {
                    for k in 0..3 {
                        b.xcm[k] += v[k] * b.vcm[k];
                    }
                }
            }
            for k in 0..3 {
                b.torque[k] *= tf[k];
            }
            let tbody = quat::transpose_matvec_cols(&b.ex, &b.ey, &b.ez, &b.torque);
            let fquat = quat::quatvec(&b.quat, &tbody);
            for c in 0..4 {
                b.conjqm[c] += dtf2 * fquat[c];
            }
            if stat {
                for c in 0..4 {
                    b.conjqm[c] *= scale_r;
                }
            }
            for (k, dt) in [(3, s.dtq), (2, s.dtq), (1, s.dtv), (2, s.dtq), (3, s.dtq)] {
                quat::no_squish_rotate(k, &mut b.conjqm, &mut b.quat, &b.inertia, dt);
            }
            [b.ex, b.ey, b.ez] = quat::q_to_exyz(&b.quat);
            Self::angmom_from_conjqm(b);
        }
        if stat {
            self.kinetic(bodies);
        }
        if self.chains.is_some() {
            self.temp_target(fraction);
            if self.dynamic {
                self.compute_dof(bodies, dimension);
            }
            self.nhc_temp_integrate(u);
        }
        if self.baro.is_some() {
            self.nhc_press_integrate(u, dimension);
        }
    }

    /// The second half kick (LAMMPS' final_integrate), after the bodies' forces and torques
    /// are summed. The caller then sets the atoms' velocities (set_v) and, with a barostat,
    /// measures the pressure and calls [`RigidNh::end_of_final`].
    pub fn final_integrate(&mut self, bodies: &mut [Body], s: &Steps, flags: Flags) {
        let dtf2 = s.dtf * 2.0;
        let (scale_t, scale_r) = self.scales(s.dtq);
        let stat = self.stat();
        for (n, b) in bodies.iter_mut().enumerate() {
            let (ff, tf) = body_flags(flags, n);
            let dtfm = s.dtf / b.mass;
            if stat {
                for k in 0..3 {
                    b.vcm[k] *= scale_t[k];
                }
            }
            for k in 0..3 {
                b.vcm[k] += dtfm * b.fcm[k] * ff[k];
            }
            for k in 0..3 {
                b.torque[k] *= tf[k];
            }
            let tbody = quat::transpose_matvec_cols(&b.ex, &b.ey, &b.ez, &b.torque);
            let fquat = quat::quatvec(&b.quat, &tbody);
            if stat {
                for c in 0..4 {
                    b.conjqm[c] = scale_r * b.conjqm[c] + dtf2 * fquat[c];
                }
            } else {
                for c in 0..4 {
                    b.conjqm[c] += dtf2 * fquat[c];
                }
            }
            Self::angmom_from_conjqm(b);
        }
        if self.baro.is_some() {
            self.kinetic(bodies);
        }
    }

    /// After the pressure was measured into `baro.p_current`: the target pressure and the box
    /// velocity's half step (the end of LAMMPS' final_integrate).
    pub fn end_of_final(&mut self, u: &crate::engine::units::Units, dtq: f64, volume: f64, fraction: f64) {
        self.epsilon_dot(u, dtq, volume, fraction);
    }

    /// LAMMPS' compute_press_target then nh_epsilon_dot.
    fn epsilon_dot(&mut self, u: &crate::engine::units::Units, dtq: f64, volume: f64, fraction: f64) {
        let g_f = self.g_f();
        let (akin_t, akin_r) = (self.akin_t, self.akin_r);
        let Some(b) = self.baro.as_mut() else { return };
        b.press_target(fraction);
        if g_f == 0 {
            return;
        }
        b.mtk_term1 = (akin_t + akin_r) * u.mvv2e / g_f as f64;
        let scale = (-1.0 * dtq * b.eta_dot_b[0]).exp();
        for i in 0..3 {
            if b.p_flag[i] {
                let mut f_epsilon = (b.p_current[i] - b.p_hydro) * volume / u.nktv2p + b.mtk_term1;
                f_epsilon /= b.epsilon_mass[i];
                b.epsilon_dot[i] += dtq * f_epsilon;
                b.epsilon_dot[i] *= scale;
            }
        }
        b.mtk_term2 = 0.0;
        for i in 0..3 {
            if b.p_flag[i] {
                b.mtk_term2 += b.epsilon_dot[i];
            }
        }
        b.mtk_term2 /= g_f as f64;
    }

    /// LAMMPS' remap: half a step of the box about its centre, the atoms (all, or the dilate
    /// group's) and the bodies' centres with it in box fractions.
    pub fn remap(&mut self, state: &mut State, bodies: &mut [Body], dtq: f64) -> Result<(), String> {
        let Some(b) = self.baro.as_mut() else { return Ok(()) };
        for i in 0..3 {
            b.epsilon[i] += dtq * b.epsilon_dot[i];
        }
        let dom = state.domain.as_ref().ok_or("no simulation box")?;
        let scale = std::array::from_fn(|i| b.p_flag[i].then(|| (0.5 * (dom.lo[i] + dom.hi[i]), (dtq * b.epsilon_dot[i]).exp())));
        let dilation = dilate_box(state, scale, None, None, b.dilate)?;
        for body in bodies.iter_mut() {
            dilation.apply(&mut body.xcm);
        }
        Ok(())
    }

    /// Angular momentum (space frame) and angular velocity from the conjugate momentum.
    fn angmom_from_conjqm(b: &mut Body) {
        let mbody = quat::invquatvec(&b.quat, &b.conjqm);
        b.angmom = quat::matvec_cols(&b.ex, &b.ey, &b.ez, &mbody);
        for k in 0..3 {
            b.angmom[k] *= 0.5;
        }
        b.omega = quat::angmom_to_omega(&b.angmom, &b.ex, &b.ey, &b.ez, &b.inertia);
    }

    /// LAMMPS' nhc_temp_integrate (Kamberaj et al.'s update_nhcp): the chains advance a full
    /// step, driven by the bodies' kinetic energies.
    fn nhc_temp_integrate(&mut self, u: &crate::engine::units::Units) {
        if self.g_f() == 0 {
            return;
        }
        let (nf_t, nf_r) = (self.nf_t as f64, self.nf_r as f64);
        let (akin_t, akin_r, t_target, t_iter) = (self.akin_t, self.akin_r, self.t_target, self.t_iter);
        let Some(c) = self.chains.as_mut() else { return };
        let n = c.q_t.len();
        let kt = u.boltz * t_target;
        let (gfkt_t, gfkt_r) = (nf_t * kt, nf_r * kt);
        let t_mass = u.boltz * t_target / (c.t_freq * c.t_freq);
        c.q_t[0] = nf_t * t_mass;
        c.q_r[0] = nf_r * t_mass;
        for i in 1..n {
            c.q_t[i] = t_mass;
            c.q_r[i] = t_mass;
        }
        c.f_eta_t[0] = (akin_t * u.mvv2e - gfkt_t) / c.q_t[0];
        c.f_eta_r[0] = (akin_r * u.mvv2e - gfkt_r) / c.q_r[0];
        for _ in 0..t_iter {
            for j in 0..self.w.len() {
                let w = (self.wdti1[j], self.wdti2[j], self.wdti4[j]);
                chain_sweep(&mut c.eta_t, &mut c.eta_dot_t, &mut c.f_eta_t, &c.q_t, kt, w, 1.0);
                chain_sweep(&mut c.eta_r, &mut c.eta_dot_r, &mut c.f_eta_r, &c.q_r, kt, w, 1.0);
            }
        }
    }

    /// LAMMPS' nhc_press_integrate (Kamberaj et al.'s update_nhcb): the barostat's chain,
    /// driven by the box's kinetic energy.
    fn nhc_press_integrate(&mut self, u: &crate::engine::units::Units, dimension: usize) {
        let (g_f, t_target, t_iter) = (self.g_f(), self.t_target, self.t_iter);
        let Some(b) = self.baro.as_mut() else { return };
        let kt = u.boltz * t_target;
        let tb_mass = kt / (b.p_freq_max * b.p_freq_max);
        b.q_b[0] = (dimension * dimension) as f64 * tb_mass;
        for i in 1..b.q_b.len() {
            b.q_b[i] = tb_mass;
            b.f_eta_b[i] = b.q_b[i - 1] * b.eta_dot_b[i - 1] * b.eta_dot_b[i - 1] - kt;
            b.f_eta_b[i] /= b.q_b[i];
        }
        let mut kecurrent = 0.0;
        for i in 0..3 {
            if b.p_flag[i] {
                b.epsilon_mass[i] = (g_f + dimension as i64) as f64 * kt / (b.p_freq[i] * b.p_freq[i]);
                kecurrent += b.epsilon_mass[i] * b.epsilon_dot[i] * b.epsilon_dot[i];
            }
        }
        kecurrent /= b.pdim as f64;
        b.f_eta_b[0] = (kecurrent - kt) / b.q_b[0];
        for _ in 0..t_iter {
            for j in 0..self.w.len() {
                let w = (self.wdti1[j], self.wdti2[j], self.wdti4[j]);
                chain_sweep(&mut b.eta_b, &mut b.eta_dot_b, &mut b.f_eta_b, &b.q_b, kt, w, 0.5);
            }
        }
    }

    /// The energy of the extended system (LAMMPS' FixRigidNHSmall::compute_scalar): the bodies'
    /// translational and quaternion kinetic energies, then [`RigidNh::extended`].
    pub fn scalar(&self, bodies: &[Body], u: &crate::engine::units::Units, volume: f64) -> f64 {
        let (mut ke_t, mut ke_q) = (0.0, 0.0);
        for b in bodies {
            let (v, q) = (b.vcm, b.quat);
            ke_t += b.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for k in 1..4 {
                let pkq = match k {
                    1 => [-q[1], q[0], q[3], -q[2]],
                    2 => [-q[2], -q[3], q[0], q[1]],
                    _ => [-q[3], q[2], -q[1], q[0]],
                };
                let p = b.conjqm;
                let mut tmp = p[0] * pkq[0] + p[1] * pkq[1] + p[2] * pkq[2] + p[3] * pkq[3];
                tmp *= tmp;
                if b.inertia[k - 1].abs() < 1e-6 {
                    tmp = 0.0;
                } else {
                    tmp /= 8.0 * b.inertia[k - 1];
                }
                ke_q += tmp;
            }
        }
        self.extended((ke_t + ke_q) * u.mvv2e, u, volume)
    }

    /// `energy` (the bodies' part: rigid/small's kinetic energies, fix rigid's temperature)
    /// plus the chains' energies and the barostat's (its kinetic energy, P0 V and its chain),
    /// added in LAMMPS' order.
    pub fn extended(&self, mut energy: f64, u: &crate::engine::units::Units, volume: f64) -> f64 {
        let kt = u.boltz * self.t_target;
        if let Some(c) = &self.chains {
            energy += kt * (self.nf_t as f64 * c.eta_t[0] + self.nf_r as f64 * c.eta_r[0]);
            for i in 1..c.eta_t.len() {
                energy += kt * (c.eta_t[i] + c.eta_r[i]);
            }
            for i in 0..c.eta_t.len() {
                energy += 0.5 * c.q_t[i] * (c.eta_dot_t[i] * c.eta_dot_t[i]);
                energy += 0.5 * c.q_r[i] * (c.eta_dot_r[i] * c.eta_dot_r[i]);
            }
        }
        if let Some(b) = &self.baro {
            let mut e = 0.0;
            for i in 0..3 {
                if b.p_flag[i] {
                    e += b.epsilon_mass[i] * b.epsilon_dot[i] * b.epsilon_dot[i];
                }
            }
            energy += e * (0.5 / b.pdim as f64);
            let p0 = (b.p_target[0] + b.p_target[1] + b.p_target[2]) / 3.0;
            energy += p0 * volume / u.nktv2p;
            for i in 0..b.eta_b.len() {
                energy += kt * b.eta_b[i];
                energy += 0.5 * b.q_b[i] * (b.eta_dot_b[i] * b.eta_dot_b[i]);
            }
        }
        energy
    }

    /// LAMMPS' write_restart: the thermostat flag, its chain length and per link eta_t, eta_r,
    /// eta_dot_t, eta_dot_r; the barostat flag, epsilon, epsilon_dot, its chain length and per
    /// link eta_b, eta_dot_b.
    pub fn write_restart(&self) -> Vec<f64> {
        let mut list = vec![];
        match &self.chains {
            Some(c) => {
                list.extend([1.0, c.eta_t.len() as f64]);
                for i in 0..c.eta_t.len() {
                    list.extend([c.eta_t[i], c.eta_r[i], c.eta_dot_t[i], c.eta_dot_r[i]]);
                }
            }
            None => list.push(0.0),
        }
        match &self.baro {
            Some(b) => {
                list.push(1.0);
                list.extend(b.epsilon);
                list.extend(b.epsilon_dot);
                list.push(b.eta_b.len() as f64);
                for i in 0..b.eta_b.len() {
                    list.extend([b.eta_b[i], b.eta_dot_b[i]]);
                }
            }
            None => list.push(0.0),
        }
        list
    }

    /// LAMMPS' restart: the chains come back when their lengths match.
    pub fn restart(&mut self, list: &[f64]) {
        let mut it = list.iter().copied();
        let Some(tflag) = it.next() else { return };
        if tflag != 0.0 {
            let Some(m) = it.next() else { return };
            let values: Vec<f64> = it.by_ref().take(4 * m as usize).collect();
            if let Some(c) = self.chains.as_mut().filter(|c| c.eta_t.len() == m as usize && values.len() == 4 * m as usize) {
                for i in 0..c.eta_t.len() {
                    let v = &values[4 * i..4 * i + 4];
                    (c.eta_t[i], c.eta_r[i], c.eta_dot_t[i], c.eta_dot_r[i]) = (v[0], v[1], v[2], v[3]);
                }
            }
        }
        let Some(pflag) = it.next() else { return };
        if pflag != 0.0 {
            let eps: Vec<f64> = it.by_ref().take(6).collect();
            let Some(m) = it.next() else { return };
            let values: Vec<f64> = it.by_ref().take(2 * m as usize).collect();
            if eps.len() == 6 {
                if let Some(b) = self.baro.as_mut() {
                    b.epsilon.copy_from_slice(&eps[..3]);
                    b.epsilon_dot.copy_from_slice(&eps[3..]);
                }
            }
            if let Some(b) = self.baro.as_mut().filter(|b| b.eta_b.len() == m as usize && values.len() == 2 * m as usize) {
                for i in 0..b.eta_b.len() {
                    (b.eta_b[i], b.eta_dot_b[i]) = (values[2 * i], values[2 * i + 1]);
                }
            }
        }
    }
}
