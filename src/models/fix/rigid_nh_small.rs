//! The integrator of `fix rigid/nve/small` and `fix rigid/nvt/small` (LAMMPS' FixRigidNHSmall,
//! 22 Jul 2025; Kamberaj et al., J. Chem. Phys. 122, 224114 (2005); Miller et al., J. Chem.
//! Phys. 116, 8649 (2002)). The bodies are set up and their atoms placed as by rigid/small
//! (rigid_small.rs); what differs is the step: the orientation moves with its conjugate
//! quaternion momentum by the NO_SQUISH splitting (free rotations about body axes 3, 2, 1, 2, 3),
//! and with `temp Tstart Tstop Tdamp` the bodies' translational and rotational kinetic energies
//! each drive a Nose-Hoover chain (`tparam Tchain Titer Torder`, default 10 1 3), integrated with
//! Yoshida-Suzuki weights, which scale the momenta at each half step. The barostatted
//! rigid/npt/small and rigid/nph/small are not here.

use super::rigid_small::Body;
use crate::engine::quat;

/// Principal moments below this count no rotational degree of freedom (LAMMPS' EPSILON).
const EPSILON: f64 = 1.0e-7;

/// A Nose-Hoover chain pair, one on the translational and one on the rotational kinetic energy.
#[derive(Clone, Debug)]
pub struct Chains {
    pub t_start: f64,
    pub t_stop: f64,
    pub t_freq: f64,
    pub t_iter: usize,
    /// Yoshida-Suzuki weights (3 or 5).
    w: Vec<f64>,
    wdti1: Vec<f64>,
    wdti2: Vec<f64>,
    wdti4: Vec<f64>,
    q_t: Vec<f64>,
    q_r: Vec<f64>,
    eta_t: Vec<f64>,
    eta_r: Vec<f64>,
    eta_dot_t: Vec<f64>,
    eta_dot_r: Vec<f64>,
    f_eta_t: Vec<f64>,
    f_eta_r: Vec<f64>,
    t_target: f64,
}

impl Chains {
    /// `temp Tstart Tstop Tdamp` with `tparam Tchain Titer Torder` (checked by the caller).
    pub fn new(t_start: f64, t_stop: f64, t_period: f64, t_chain: usize, t_iter: usize, t_order: usize) -> Self {
        let w = if t_order == 3 {
            let w0 = 1.0 / (2.0 - 2.0f64.powf(1.0 / 3.0));
            vec![w0, 1.0 - 2.0 * w0, w0]
        } else {
            let w0 = 1.0 / (4.0 - 4.0f64.powf(1.0 / 3.0));
            vec![w0, w0, 1.0 - 4.0 * w0, w0, w0]
        };
        let zeros = vec![0.0; t_chain];
        Chains {
            t_start,
            t_stop,
            t_freq: 1.0 / t_period,
            t_iter,
            wdti1: vec![0.0; w.len()],
            wdti2: vec![0.0; w.len()],
            wdti4: vec![0.0; w.len()],
            w,
            q_t: zeros.clone(),
            q_r: zeros.clone(),
            eta_t: zeros.clone(),
            eta_r: zeros.clone(),
            eta_dot_t: zeros.clone(),
            eta_dot_r: zeros.clone(),
            f_eta_t: zeros.clone(),
            f_eta_r: zeros,
            t_target: 0.0,
        }
    }
}

/// LAMMPS' maclaurin_series: sinh(x)/x to the x^8 term.
fn maclaurin_series(x: f64) -> f64 {
    let x2 = x * x;
    let x4 = x2 * x2;
    1.0 + (1.0 / 6.0) * x2 + (1.0 / 120.0) * x4 + (1.0 / 5040.0) * x2 * x4 + (1.0 / 362880.0) * x4 * x4
}

/// Half a step of a chain's velocity `k` driven by its force, damped by the next link
/// (`s * s` and `s * ms`: LAMMPS' exact exponential of the coupled update).
fn chain_kick(eta_dot: f64, f_eta: f64, next_eta_dot: f64, wdti2: f64, wdti4: f64) -> f64 {
    let tmp = wdti4 * next_eta_dot;
    let ms = maclaurin_series(tmp);
    let s = (-1.0 * tmp).exp();
    let s2 = s * s;
    eta_dot * s2 + wdti2 * f_eta * s * ms
}

/// The state of the NO_SQUISH integrator over the fix's bodies.
#[derive(Clone, Debug)]
pub struct RigidNh {
    pub chains: Option<Chains>,
    /// `fix_modify dynamic/dof yes`: recount the degrees of freedom every step.
    pub dynamic: bool,
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
    pub fn new(chains: Option<Chains>) -> Self {
        RigidNh { chains, dynamic: false, nf_t: 0, nf_r: 0, akin_t: 0.0, akin_r: 0.0 }
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

    fn kinetic(&mut self, bodies: &[Body]) {
        let (mut t, mut r) = (0.0, 0.0);
        for b in bodies {
            t += b.mass * (b.vcm[0] * b.vcm[0] + b.vcm[1] * b.vcm[1] + b.vcm[2] * b.vcm[2]);
            r += b.angmom[0] * b.omega[0] + b.angmom[1] * b.omega[1] + b.angmom[2] * b.omega[2];
        }
        (self.akin_t, self.akin_r) = (t, r);
    }

    /// LAMMPS' FixRigidNHSmall::setup after rigid/small's: the degrees of freedom, each body's
    /// conjugate quaternion momentum from its angular momentum, and the chains' masses and
    /// forces at the run's starting temperature.
    pub fn setup(&mut self, bodies: &mut [Body], dimension: usize, boltz: f64, fraction: f64, dt: f64) {
        self.compute_dof(bodies, dimension);
        for b in bodies.iter_mut() {
            let mbody = quat::transpose_matvec_cols(&b.ex, &b.ey, &b.ez, &b.angmom);
            b.conjqm = quat::quatvec(&b.quat, &mbody);
            for c in b.conjqm.iter_mut() {
                *c *= 2.0;
            }
        }
        if self.chains.is_some() {
            self.kinetic(bodies);
        }
        let (nf_t, nf_r) = (self.nf_t as f64, self.nf_r as f64);
        let Some(c) = self.chains.as_mut() else { return };
        c.t_target = c.t_start + fraction * (c.t_stop - c.t_start);
        let kt = boltz * c.t_target;
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
        for j in 0..c.w.len() {
            c.wdti1[j] = c.w[j] * dt / c.t_iter as f64;
            c.wdti2[j] = c.wdti1[j] / 2.0;
            c.wdti4[j] = c.wdti1[j] / 4.0;
        }
    }

    /// The chains' damping of the translational and rotational momenta over half a step.
    fn scales(&self, dtq: f64) -> Option<(f64, f64)> {
        let c = self.chains.as_ref()?;
        Some(((-dtq * c.eta_dot_t[0]).exp(), (-dtq * c.eta_dot_r[0]).exp()))
    }

    /// The first half of the step (LAMMPS' initial_integrate, steps 1.1 to 1.13 of Kamberaj
    /// et al.), then the chains' full step. The caller then places the atoms (set_xv).
    pub fn initial_integrate(&mut self, bodies: &mut [Body], s: &Steps, dimension: usize, boltz: f64, mvv2e: f64, fraction: f64) {
        let dtf2 = s.dtf * 2.0;
        let scale = self.scales(s.dtq);
        for b in bodies.iter_mut() {
            let dtfm = s.dtf / b.mass;
            for k in 0..3 {
                b.vcm[k] += dtfm * b.fcm[k];
            }
            if let Some((scale_t, _)) = scale {
                for k in 0..3 {
                    b.vcm[k] *= scale_t;
                }
            }
            for k in 0..3 {
                b.xcm[k] += s.dtv * b.vcm[k];
            }
            let tbody = quat::transpose_matvec_cols(&b.ex, &b.ey, &b.ez, &b.torque);
            let fquat = quat::quatvec(&b.quat, &tbody);
            for c in 0..4 {
                b.conjqm[c] += dtf2 * fquat[c];
            }
            if let Some((_, scale_r)) = scale {
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
        if self.chains.is_some() {
            self.kinetic(bodies);
            if self.dynamic {
                self.compute_dof(bodies, dimension);
            }
            self.nhc_temp_integrate(boltz, mvv2e, fraction);
        }
    }

    /// The second half kick (LAMMPS' final_integrate), after the bodies' forces and torques
    /// are summed. The caller then sets the atoms' velocities (set_v).
    pub fn final_integrate(&mut self, bodies: &mut [Body], s: &Steps) {
        let dtf2 = s.dtf * 2.0;
        let scale = self.scales(s.dtq);
        for b in bodies.iter_mut() {
            let dtfm = s.dtf / b.mass;
            if let Some((scale_t, _)) = scale {
                for k in 0..3 {
                    b.vcm[k] *= scale_t;
                }
            }
            for k in 0..3 {
                b.vcm[k] += dtfm * b.fcm[k];
            }
            let tbody = quat::transpose_matvec_cols(&b.ex, &b.ey, &b.ez, &b.torque);
            let fquat = quat::quatvec(&b.quat, &tbody);
            match scale {
                Some((_, scale_r)) => {
                    for c in 0..4 {
                        b.conjqm[c] = scale_r * b.conjqm[c] + dtf2 * fquat[c];
                    }
                }
                None => {
                    for c in 0..4 {
                        b.conjqm[c] += dtf2 * fquat[c];
                    }
                }
            }
            Self::angmom_from_conjqm(b);
        }
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
    fn nhc_temp_integrate(&mut self, boltz: f64, mvv2e: f64, fraction: f64) {
        let (nf_t, nf_r) = (self.nf_t as f64, self.nf_r as f64);
        let (akin_t, akin_r) = (self.akin_t, self.akin_r);
        let Some(c) = self.chains.as_mut() else { return };
        c.t_target = c.t_start + fraction * (c.t_stop - c.t_start);
        if self.nf_t + self.nf_r == 0 {
            return;
        }
        let n = c.q_t.len();
        let kt = boltz * c.t_target;
        let (gfkt_t, gfkt_r) = (nf_t * kt, nf_r * kt);
        let t_mass = boltz * c.t_target / (c.t_freq * c.t_freq);
        c.q_t[0] = nf_t * t_mass;
        c.q_r[0] = nf_r * t_mass;
        for i in 1..n {
            c.q_t[i] = t_mass;
            c.q_r[i] = t_mass;
        }
        c.f_eta_t[0] = (akin_t * mvv2e - gfkt_t) / c.q_t[0];
        c.f_eta_r[0] = (akin_r * mvv2e - gfkt_r) / c.q_r[0];
        for _ in 0..c.t_iter {
            for j in 0..c.w.len() {
                let (w1, w2, w4) = (c.wdti1[j], c.wdti2[j], c.wdti4[j]);
                c.eta_dot_t[n - 1] += w2 * c.f_eta_t[n - 1];
                c.eta_dot_r[n - 1] += w2 * c.f_eta_r[n - 1];
                for k in 1..n {
                    c.eta_dot_t[n - k - 1] = chain_kick(c.eta_dot_t[n - k - 1], c.f_eta_t[n - k - 1], c.eta_dot_t[n - k], w2, w4);
                    c.eta_dot_r[n - k - 1] = chain_kick(c.eta_dot_r[n - k - 1], c.f_eta_r[n - k - 1], c.eta_dot_r[n - k], w2, w4);
                }
                for k in 0..n {
                    c.eta_t[k] += w1 * c.eta_dot_t[k];
                    c.eta_r[k] += w1 * c.eta_dot_r[k];
                }
                for k in 1..n {
                    c.f_eta_t[k] = c.q_t[k - 1] * c.eta_dot_t[k - 1] * c.eta_dot_t[k - 1] - kt;
                    c.f_eta_t[k] /= c.q_t[k];
                    c.f_eta_r[k] = c.q_r[k - 1] * c.eta_dot_r[k - 1] * c.eta_dot_r[k - 1] - kt;
                    c.f_eta_r[k] /= c.q_r[k];
                }
                for k in 0..n - 1 {
                    c.eta_dot_t[k] = chain_kick(c.eta_dot_t[k], c.f_eta_t[k], c.eta_dot_t[k + 1], w2, w4);
                    c.f_eta_t[k + 1] = (c.q_t[k] * c.eta_dot_t[k] * c.eta_dot_t[k] - kt) / c.q_t[k + 1];
                    c.eta_dot_r[k] = chain_kick(c.eta_dot_r[k], c.f_eta_r[k], c.eta_dot_r[k + 1], w2, w4);
                    c.f_eta_r[k + 1] = (c.q_r[k] * c.eta_dot_r[k] * c.eta_dot_r[k] - kt) / c.q_r[k + 1];
                }
                c.eta_dot_t[n - 1] += w2 * c.f_eta_t[n - 1];
                c.eta_dot_r[n - 1] += w2 * c.f_eta_r[n - 1];
            }
        }
    }

    /// The energy of the extended system (LAMMPS' compute_scalar): the bodies' translational
    /// and quaternion kinetic energies, and with a thermostat the chains' energies.
    pub fn scalar(&self, bodies: &[Body], boltz: f64, mvv2e: f64) -> f64 {
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
        let mut energy = (ke_t + ke_q) * mvv2e;
        if let Some(c) = &self.chains {
            let kt = boltz * c.t_target;
            energy += kt * (self.nf_t as f64 * c.eta_t[0] + self.nf_r as f64 * c.eta_r[0]);
            for i in 1..c.eta_t.len() {
                energy += kt * (c.eta_t[i] + c.eta_r[i]);
            }
            for i in 0..c.eta_t.len() {
                energy += 0.5 * c.q_t[i] * (c.eta_dot_t[i] * c.eta_dot_t[i]);
                energy += 0.5 * c.q_r[i] * (c.eta_dot_r[i] * c.eta_dot_r[i]);
            }
        }
        energy
    }

    /// LAMMPS' write_restart: the thermostat flag, then the chain length and per link eta_t,
    /// eta_r, eta_dot_t, eta_dot_r, then the barostat flag (0).
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
        list.push(0.0);
        list
    }

    /// LAMMPS' restart: the chains come back when their length matches.
    pub fn restart(&mut self, list: &[f64]) {
        let Some(c) = self.chains.as_mut() else { return };
        if list.first() != Some(&1.0) || list.len() < 2 {
            return;
        }
        let m = list[1] as usize;
        if m != c.eta_t.len() || list.len() < 2 + 4 * m {
            return;
        }
        for i in 0..m {
            let v = &list[2 + 4 * i..6 + 4 * i];
            (c.eta_t[i], c.eta_r[i], c.eta_dot_t[i], c.eta_dot_r[i]) = (v[0], v[1], v[2], v[3]);
        }
    }
}
