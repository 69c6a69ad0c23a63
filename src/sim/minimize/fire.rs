//! min_style fire: LAMMPS' FIRE 2.0 damped dynamics (Guénolé et al. 2020) with its
//! min_modify parameters: velocities mixed towards the force while v.f > 0 and the time step
//! grown after `delaystep` such steps; v.f <= 0 resets alpha, shrinks the step, moves the
//! atoms half a step back and stops them. No atom moves more than dmax per step.

use super::{energy_converged, Integrator, Min, MinSettings, Stop};
use crate::sim::{RunError, Simulation};

/// LAMMPS' checks of the parameters when the minimization starts.
pub(super) fn check(s: &MinSettings) -> Result<(), String> {
    if s.tmax < s.tmin {
        return Err("min_modify: tmax has to be larger than tmin".into());
    }
    if s.dtgrow < 1.0 {
        return Err("min_modify: dtgrow has to be larger than 1.0".into());
    }
    if s.dtshrink > 1.0 {
        return Err("min_modify: dtshrink has to be smaller than 1.0".into());
    }
    Ok(())
}

pub(super) struct Fire {
    dt: f64,
    dtmax: f64,
    dtmin: f64,
    alpha: f64,
    last_negative: i64,
    ntimestep_start: i64,
    vdotf_negatif: i64,
    /// The velocities were zeroed: they are estimated from the forces before the step limit.
    flagv0: bool,
}

impl Fire {
    /// LAMMPS' MinFire::init and setup_style: parameters in the log, velocities zeroed.
    pub fn new(sim: &mut Simulation, m: &Min) -> Fire {
        let s = &m.set;
        let dt = sim.state.dt;
        let yes = |b: bool| if b { "yes" } else { "no" };
        let g = crate::output::format::g;
        sim.out.print(&format!(
            "  Parameters for fire:\n    dmax delaystep dtgrow dtshrink alpha0 alphashrink tmax tmin    integrator halfstepback abcfire\n    {} {} {} {} {} {} {} {} {} {} no",
            g(s.dmax), s.delaystep, g(s.dtgrow), g(s.dtshrink), g(s.alpha0), g(s.alphashrink), g(s.tmax), g(s.tmin), s.integrator.name(), yes(s.halfstepback)
        ));
        let n = sim.state.atoms.nlocal;
        for v in &mut sim.state.atoms.v[..n] {
            *v = [0.0; 3];
        }
        let step = sim.state.step;
        Fire { dt, dtmax: s.tmax * dt, dtmin: s.tmin * dt, alpha: s.alpha0, last_negative: step, ntimestep_start: step, vdotf_negatif: 0, flagv0: true }
    }

    /// v = dtf/m f for every atom (dtf/m per atom as LAMMPS: dtf / mass).
    fn set_v_from_f(sim: &mut Simulation, dtf: f64) {
        let n = sim.state.atoms.nlocal;
        for i in 0..n {
            let dtfm = dtf / sim.state.mass(i);
            let f = sim.state.atoms.f[i];
            sim.state.atoms.v[i] = [dtfm * f[0], dtfm * f[1], dtfm * f[2]];
        }
    }

    pub fn iterate(&mut self, sim: &mut Simulation, m: &mut Min, maxiter: i64) -> Result<Stop, RunError> {
        let s = m.set.clone();
        let ftm2v = sim.state.units.ftm2v;
        m.alpha_final = 0.0;
        if s.integrator == Integrator::Leapfrog {
            m.energy_force(sim, false)?;
            m.neval += 1;
            Self::set_v_from_f(sim, -0.5 * self.dt * ftm2v);
        }
        for _ in 0..maxiter {
            sim.state.step += 1;
            let ntimestep = sim.state.step;
            m.niter += 1;
            let n = sim.state.atoms.nlocal;
            let order = Min::order(sim);
            let (mut vdotf, mut scale1, mut scale2) = (0.0, 0.0, 0.0);
            {
                let a = &sim.state.atoms;
                for &i in &order {
                    let (v, f) = (a.v[i], a.f[i]);
                    vdotf += v[0] * f[0] + v[1] * f[1] + v[2] * f[2];
                }
            }
            if vdotf > 0.0 {
                // mix v towards the force; grow the step after delaystep good steps
                let (mut vdotv, mut fdotf) = (0.0, 0.0);
                self.vdotf_negatif = 0;
                let a = &sim.state.atoms;
                for &i in &order {
                    let v = a.v[i];
                    vdotv += v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
                }
                for &i in &order {
                    let f = a.f[i];
                    fdotf += f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
                }
                scale1 = 1.0 - self.alpha;
                scale2 = if fdotf <= 1e-20 { 0.0 } else { self.alpha * (vdotv / fdotf).sqrt() };
                if ntimestep - self.last_negative > s.delaystep {
                    let grown = self.dt * s.dtgrow;
                    self.dt = if grown < self.dtmax { grown } else { self.dtmax };
                    sim.state.dt = self.dt;
                    self.alpha *= s.alphashrink;
                }
            } else {
                // uphill: reset alpha, shrink the step (after the initial delay), half a step
                // back, stop
                self.last_negative = ntimestep;
                let delayed = !(ntimestep - self.ntimestep_start < s.delaystep && s.initialdelay);
                if delayed {
                    self.alpha = s.alpha0;
                    if self.dt * s.dtshrink >= self.dtmin {
                        self.dt *= s.dtshrink;
                        sim.state.dt = self.dt;
                    }
                }
                self.vdotf_negatif += 1;
                if s.vdfmax > 0 && self.vdotf_negatif > s.vdfmax {
                    return Ok(Stop::MaxVdotf);
                }
                let a = &mut sim.state.atoms;
                if s.halfstepback {
                    let half = 0.5 * self.dt;
                    for i in 0..n {
                        for k in 0..3 {
                            a.x[i][k] -= half * a.v[i][k];
                        }
                    }
                }
                for v in &mut a.v[..n] {
                    *v = [0.0; 3];
                }
                self.flagv0 = true;
            }
            if self.flagv0 {
                // velocities from the forces here, to limit the step
                m.energy_force(sim, false)?;
                m.neval += 1;
                Self::set_v_from_f(sim, self.dt * ftm2v);
            }
            let mut dtv = self.dt;
            for i in 0..n {
                let v = sim.state.atoms.v[i];
                let (a0, a1, a2) = (v[0].abs(), v[1].abs(), v[2].abs());
                let vmax = if a0 > a1 { a0 } else { a1 };
                let vmax = if vmax > a2 { vmax } else { a2 };
                if dtv * vmax > s.dmax {
                    dtv = s.dmax / vmax;
                }
            }
            if self.flagv0 {
                for v in &mut sim.state.atoms.v[..n] {
                    *v = [0.0; 3];
                }
            }
            let mix = vdotf > 0.0;
            match s.integrator {
                Integrator::EulerImplicit | Integrator::Leapfrog => {
                    self.kick_drift(sim, dtv * ftm2v, dtv, mix, scale1, scale2, true);
                    m.eprevious = m.ecurrent;
                    m.ecurrent = m.energy_force(sim, false)?;
                    m.neval += 1;
                }
                Integrator::Verlet => {
                    let dtf = 0.5 * dtv * ftm2v;
                    self.kick_drift(sim, dtf, dtv, mix, scale1, scale2, true);
                    m.eprevious = m.ecurrent;
                    m.ecurrent = m.energy_force(sim, false)?;
                    m.neval += 1;
                    for i in 0..n {
                        let dtfm = dtf / sim.state.mass(i);
                        let f = sim.state.atoms.f[i];
                        let v = &mut sim.state.atoms.v[i];
                        for k in 0..3 {
                            v[k] += dtfm * f[k];
                        }
                    }
                }
                Integrator::EulerExplicit => {
                    self.kick_drift(sim, dtv * ftm2v, dtv, mix, scale1, scale2, false);
                    m.eprevious = m.ecurrent;
                    m.ecurrent = m.energy_force(sim, false)?;
                    m.neval += 1;
                }
            }
            self.flagv0 = false;
            if m.opts.etol > 0.0 && ntimestep - self.last_negative > s.delaystep && energy_converged(m.opts.etol, m.ecurrent, m.eprevious) {
                return Ok(Stop::Etol);
            }
            if m.force_converged(sim, None) {
                return Ok(Stop::Ftol);
            }
            if sim.output_due(ntimestep, m.last) {
                sim.timers.stamp();
                sim.output_now(false, m.last, false)?;
                sim.timers.charge(crate::engine::timing::Stage::Output);
            }
        }
        Ok(Stop::MaxIter)
    }

    /// One atom at a time: v += dtf/m f, mixing v = scale1 v + scale2 f while v.f > 0, and
    /// x += dtv v (`kick_first`); explicit Euler mixes and drifts first, then kicks.
    #[allow(clippy::too_many_arguments)]
    fn kick_drift(&self, sim: &mut Simulation, dtf: f64, dtv: f64, mix: bool, scale1: f64, scale2: f64, kick_first: bool) {
        let n = sim.state.atoms.nlocal;
        for i in 0..n {
            let dtfm = dtf / sim.state.mass(i);
            let a = &mut sim.state.atoms;
            let f = a.f[i];
            let v = &mut a.v[i];
            if kick_first {
                for k in 0..3 {
                    v[k] += dtfm * f[k];
                }
            }
            if mix {
                for k in 0..3 {
                    v[k] = scale1 * v[k] + scale2 * f[k];
                }
            }
            let x = &mut a.x[i];
            for k in 0..3 {
                x[k] += dtv * v[k];
            }
            if !kick_first {
                for k in 0..3 {
                    v[k] += dtfm * f[k];
                }
            }
        }
    }
}
