//! `minimize`: LAMMPS' energy minimizers (min_style cg, sd and fire) in LAMMPS' order of
//! floating-point operations, so the iterates match LAMMPS' to round-off. The setup, the force
//! evaluation and the stopping tests are LAMMPS' Min class; the line searches (cg, sd) are in
//! `linesearch.rs`, the damped dynamics in `fire.rs`.
//!
//! Per-atom sums run over the atoms in LAMMPS' local order (`state.lammps_order`), so that the
//! sums round as LAMMPS' do. The minimizer's own per-atom vectors (start of the line search,
//! previous force, search direction) follow the atoms when a rebuild reorders them.

mod fire;
mod linesearch;

use crate::models::fix::MinRole;
use crate::sim::{RunError, SetupError, Simulation};
use crate::engine::domain::Domain;
use crate::engine::timing::Stage;
use std::time::Instant;

/// `min_style`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MinStyle {
    Cg,
    Sd,
    Fire,
}

impl MinStyle {
    pub fn name(self) -> &'static str {
        match self {
            MinStyle::Cg => "cg",
            MinStyle::Sd => "sd",
            MinStyle::Fire => "fire",
        }
    }
}

/// `min_modify line`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineSearch {
    Backtrack,
    Quadratic,
}

/// `min_modify norm`: the force norm of the force tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Norm {
    /// Euclidean norm of the 3N vector.
    Two,
    /// Largest force vector of one atom.
    Max,
    /// Largest force component.
    Inf,
}

/// `min_modify integrator` of fire.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Integrator {
    EulerImplicit,
    Verlet,
    Leapfrog,
    EulerExplicit,
}

impl Integrator {
    pub fn name(self) -> &'static str {
        match self {
            Integrator::EulerImplicit => "eulerimplicit",
            Integrator::Verlet => "verlet",
            Integrator::Leapfrog => "leapfrog",
            Integrator::EulerExplicit => "eulerexplicit",
        }
    }
}

/// The minimizer's settings: `min_style` and `min_modify` (LAMMPS' defaults; `min_style`
/// resets them, as LAMMPS makes a new minimizer).
#[derive(Clone, Debug)]
pub struct MinSettings {
    pub style: MinStyle,
    pub line: LineSearch,
    pub dmax: f64,
    pub norm: Norm,
    pub delaystep: i64,
    pub dtgrow: f64,
    pub dtshrink: f64,
    pub alpha0: f64,
    pub alphashrink: f64,
    pub tmax: f64,
    pub tmin: f64,
    pub integrator: Integrator,
    pub halfstepback: bool,
    pub initialdelay: bool,
    pub vdfmax: i64,
}

impl Default for MinSettings {
    fn default() -> Self {
        MinSettings {
            style: MinStyle::Cg,
            line: LineSearch::Quadratic,
            dmax: 0.1,
            norm: Norm::Two,
            delaystep: 20,
            dtgrow: 1.1,
            dtshrink: 0.5,
            alpha0: 0.25,
            alphashrink: 0.99,
            tmax: 10.0,
            tmin: 0.02,
            integrator: Integrator::EulerImplicit,
            halfstepback: true,
            initialdelay: true,
            vdfmax: 2000,
        }
    }
}

/// The arguments of `minimize etol ftol maxiter maxeval`.
#[derive(Clone, Copy, Debug)]
pub struct MinimizeOptions {
    pub etol: f64,
    pub ftol: f64,
    pub maxiter: i64,
    pub maxeval: i64,
}

/// Why a minimization stopped (LAMMPS' stop conditions and their words).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stop {
    MaxIter,
    MaxEval,
    Etol,
    Ftol,
    Downhill,
    ZeroAlpha,
    ZeroForce,
    ZeroQuad,
    MaxVdotf,
}

impl Stop {
    pub fn text(self) -> &'static str {
        match self {
            Stop::MaxIter => "max iterations",
            Stop::MaxEval => "max force evaluations",
            Stop::Etol => "energy tolerance",
            Stop::Ftol => "force tolerance",
            Stop::Downhill => "search direction is not downhill",
            Stop::ZeroAlpha => "linesearch alpha is zero",
            Stop::ZeroForce => "forces are zero",
            Stop::ZeroQuad => "quadratic factors are zero",
            Stop::MaxVdotf => "max iterations with v.f negative",
        }
    }
}

/// EPS_ENERGY of LAMMPS: the smallest normalisation of the energy tolerance.
const EPS_ENERGY: f64 = 1.0e-8;

/// The energy tolerance test of LAMMPS' minimizers.
fn energy_converged(etol: f64, ecurrent: f64, eprevious: f64) -> bool {
    (ecurrent - eprevious).abs() < etol * 0.5 * (ecurrent.abs() + eprevious.abs() + EPS_ENERGY)
}

/// The state of one minimization (LAMMPS' Min members).
pub(crate) struct Min {
    pub opts: MinimizeOptions,
    pub set: MinSettings,
    /// Energies and `fdoth` are divided by the atom count (thermo_modify norm yes).
    normflag: bool,
    natoms: f64,
    /// Fixes applied after each force evaluation (LAMMPS' min_post_force).
    fixes: Vec<usize>,
    pub ecurrent: f64,
    pub eprevious: f64,
    pub einitial: f64,
    pub niter: i64,
    pub neval: i64,
    pub alpha_final: f64,
    /// Last step of the minimization (first + maxiter).
    pub last: i64,
    /// Per-atom vectors kept by the style (x0, g, h of the line search; fire uses none).
    pub vectors: Vec<Vec<[f64; 3]>>,
    /// Fixes with extra global degrees of freedom (fix box/relax), in definition order, each
    /// with the offset of its own in the extra vectors.
    extra: Vec<(usize, usize)>,
    /// The extra degrees of freedom's forces, previous forces and search direction (LAMMPS'
    /// fextra, gextra, hextra).
    fextra: Vec<f64>,
    gextra: Vec<f64>,
    hextra: Vec<f64>,
    /// The box where the line search started (LAMMPS' FixMinimize::store_box).
    box0: Option<Domain>,
}

impl Min {
    /// Local indices in LAMMPS' order.
    fn order(sim: &Simulation) -> Vec<usize> {
        sim.state.lammps_order.indices(sim.state.atoms.nlocal).into_owned()
    }

    /// Squared 2-norm of the forces (LAMMPS' fnorm_sqr: one running sum over the 3N vector,
    /// then the extra degrees of freedom's).
    pub fn fnorm_sqr(&self, sim: &Simulation) -> f64 {
        let f = &sim.state.atoms.f;
        let mut s = 0.0;
        for i in Self::order(sim) {
            for c in f[i] {
                s += c * c;
            }
        }
        for c in &self.fextra {
            s += c * c;
        }
        s
    }

    /// Largest squared force component (LAMMPS' fnorm_inf).
    pub fn fnorm_inf(&self, sim: &Simulation) -> f64 {
        let f = &sim.state.atoms.f;
        let mut m: f64 = 0.0;
        for i in Self::order(sim) {
            for c in f[i] {
                let v = c * c;
                m = if v > m { v } else { m };
            }
        }
        for c in &self.fextra {
            let v = c * c;
            m = if v > m { v } else { m };
        }
        m
    }

    /// Largest squared force of one atom, or of an extra degree of freedom (LAMMPS' fnorm_max,
    /// which reads every third of them: fextra[0], [3], ...; its quirk kept).
    pub fn fnorm_max(&self, sim: &Simulation) -> f64 {
        let f = &sim.state.atoms.f;
        let mut m: f64 = 0.0;
        for i in Self::order(sim) {
            let v = f[i][0] * f[i][0] + f[i][1] * f[i][1] + f[i][2] * f[i][2];
            m = if v > m { v } else { m };
        }
        for c in self.fextra.iter().step_by(3) {
            let v = c * c;
            m = if v > m { v } else { m };
        }
        m
    }

    /// The force tolerance test with the chosen norm; `two` is the squared 2-norm when the
    /// caller has it already.
    fn force_converged(&self, sim: &Simulation, two: Option<f64>) -> bool {
        if self.opts.ftol <= 0.0 {
            return false;
        }
        let fdotf = match self.set.norm {
            Norm::Max => self.fnorm_max(sim),
            Norm::Inf => self.fnorm_inf(sim),
            Norm::Two => two.unwrap_or_else(|| self.fnorm_sqr(sim)),
        };
        fdotf < self.opts.ftol * self.opts.ftol
    }

    /// The potential energy of the last evaluation (with the fixes' under `fix_modify energy
    /// yes`, as LAMMPS' thermo_pe) plus the extra degrees of freedom's (whose forces it sets),
    /// normalised as thermo's.
    fn energy(&mut self, sim: &mut Simulation) -> Result<f64, RunError> {
        let mut e = sim.world().pe();
        if !self.extra.is_empty() {
            let virial = sim.world().virial();
            let mut eng = 0.0;
            for &(k, off) in &self.extra {
                let fix = sim.fixes[k].min_extra().expect("a fix with extra degrees of freedom");
                let n = fix.min_dof();
                eng += fix.min_energy(&sim.state, &virial, &mut self.fextra[off..off + n]).map_err(|m| RunError::new(sim.state.step, m))?;
            }
            e += eng;
        }
        Ok(if self.normflag { e / self.natoms } else { e })
    }

    /// The extra degrees of freedom keep their values where the line search starts (LAMMPS'
    /// min_store).
    fn store_extra(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        for &(k, _) in &self.extra {
            let step = sim.state.step;
            let fix = sim.fixes[k].min_extra().expect("a fix with extra degrees of freedom");
            fix.min_store(&sim.state).map_err(|m| RunError::new(step, m))?;
        }
        Ok(())
    }

    /// The extra degrees of freedom at their stored start plus alpha hextra (LAMMPS'
    /// Modify::min_step).
    fn step_extra(&mut self, sim: &mut Simulation, alpha: f64) -> Result<(), RunError> {
        let step = sim.state.step;
        for &(k, off) in &self.extra {
            let fix = sim.fixes[k].min_extra().expect("a fix with extra degrees of freedom");
            let n = fix.min_dof();
            fix.min_step(&mut sim.state, alpha, &self.hextra[off..off + n]).map_err(|m| RunError::new(step, m))?;
        }
        Ok(())
    }

    /// The largest alpha the extra degrees of freedom allow (LAMMPS' Modify::max_alpha).
    fn max_alpha_extra(&self, sim: &mut Simulation) -> f64 {
        let mut alpha = 1.0e20;
        for &(k, off) in &self.extra {
            let fix = sim.fixes[k].min_extra().expect("a fix with extra degrees of freedom");
            let one = fix.max_alpha(&self.hextra[off..off + fix.min_dof()]);
            alpha = if alpha < one { alpha } else { one };
        }
        alpha
    }

    /// After a successful line search: the fixes renew their reference state if due, and the
    /// energy and forces are evaluated again if one did (LAMMPS' min_reset_ref).
    fn reset_ref(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        let step = sim.state.step;
        let begin = self.last - self.opts.maxiter;
        let mut renewed = false;
        for &(k, _) in &self.extra {
            let fix = sim.fixes[k].min_extra().expect("a fix with extra degrees of freedom");
            renewed |= fix.min_reset_ref(&sim.state, begin).map_err(|m| RunError::new(step, m))?;
        }
        if renewed {
            self.ecurrent = self.energy_force(sim, true)?;
        }
        Ok(())
    }

    /// LAMMPS' Min::energy_force: reneighbour if an atom moved more than half the skin (else
    /// refresh the ghosts), forces and energies, the fixes' min_post_force; returns the energy.
    /// `reset`: atoms wrapped across a periodic face keep their line-search start x0 as a
    /// nearby image (LAMMPS' fix MINIMIZE reset_coords).
    pub fn energy_force(&mut self, sim: &mut Simulation, reset: bool) -> Result<f64, RunError> {
        let step = sim.state.step;
        let moving = sim.state.domain.as_ref().filter(|_| !self.extra.is_empty());
        if sim.state.neighbor.decide_in(&sim.state.neigh_settings, &sim.state.atoms, moving) {
            sim.timers.stamp();
            let n = sim.state.atoms.nlocal;
            let order = sim.rebuild_at(false)?;
            sim.timers.charge(Stage::Neigh);
            if sim.state.atoms.nlocal != n {
                return Err(RunError::new(step, format!("atoms were lost during the minimization ({} of {n} left)", sim.state.atoms.nlocal)));
            }
            if order.len() == n {
                for v in self.vectors.iter_mut() {
                    *v = order.iter().map(|&k| v[k]).collect();
                }
            }
            if reset && !self.vectors.is_empty() {
                self.reset_coords(sim);
            }
        } else {
            sim.timers.stamp();
            let periods = sim.state.domain.as_ref().expect("a box").periods();
            sim.state.atoms.forward_positions(periods);
            if sim.needs_ghost_state() {
                sim.state.atoms.forward_state();
            }
            sim.timers.charge(Stage::Comm);
        }
        sim.compute_forces(true, true)?;
        self.post_force(sim)?;
        self.energy(sim)
    }

    fn post_force(&self, sim: &mut Simulation) -> Result<(), RunError> {
        sim.timers.stamp();
        for &k in &self.fixes {
            sim.with_fix(k, |f, s, c| f.post_force(s, c))?;
        }
        sim.timers.charge(Stage::Modify);
        Ok(())
    }

    /// x0 of an atom that was wrapped is moved by the length of the line search's starting
    /// box, so that x0 + alpha h is the wrapped atom's line (LAMMPS' minimum image of x - x0
    /// in the box FixMinimize::store_box kept, its tilts too).
    fn reset_coords(&mut self, sim: &Simulation) {
        let d = self.box0.as_ref().or(sim.state.domain.as_ref()).expect("a box");
        let x = &sim.state.atoms.x;
        for (i, x0) in self.vectors[0].iter_mut().enumerate() {
            let dx0 = [x[i][0] - x0[0], x[i][1] - x0[1], x[i][2] - x0[2]];
            let mut dx = dx0;
            d.minimum_image(&mut dx);
            for k in 0..3 {
                if dx[k] != dx0[k] {
                    x0[k] = x[i][k] - dx[k];
                }
            }
        }
    }
}

impl Simulation {
    /// The fixes applied while minimizing; a fix LAMMPS would apply and dmhs does not is an
    /// error.
    fn min_fixes(&self) -> Result<Vec<usize>, SetupError> {
        let mut applied = Vec::new();
        for (k, f) in self.fixes.iter().enumerate() {
            match f.min_role() {
                MinRole::Inert => {}
                MinRole::PostForce => applied.push(k),
                MinRole::Refused(why) => return Err(why.into()),
            }
        }
        Ok(applied)
    }

    /// The `minimize` command (LAMMPS' Minimize::command with Min::setup, run, cleanup and
    /// the summary of Finish).
    pub fn minimize(&mut self, opts: &MinimizeOptions) -> Result<(), RunError> {
        // after a fix halt with `error soft`, as LAMMPS' run
        if self.state.halted {
            return Ok(());
        }
        let first = self.state.step;
        let Some(last) = first.checked_add(opts.maxiter) else {
            return Err(RunError::setup(first, format!("minimize: too many iterations: step {first} + {} is past the largest step", opts.maxiter).into()));
        };
        self.state.run_window = Some((first, last));
        self.init_run().map_err(|e| RunError::setup(first, e))?;
        let fixes = self.min_fixes().map_err(|e| RunError::setup(first, e))?;
        let set = self.min.clone();
        if set.style == MinStyle::Fire {
            fire::check(&set).map_err(|e| RunError::setup(first, e.into()))?;
        }
        // LAMMPS reneighbours by distance at every evaluation while minimizing
        let neigh = self.state.neigh_settings.clone();
        if neigh.every != 1 || neigh.delay != 0 || !neigh.check {
            self.out.print("WARNING: Using 'neigh_modify every 1 delay 0 check yes' setting during minimization");
        }
        (self.state.neigh_settings.every, self.state.neigh_settings.delay, self.state.neigh_settings.check) = (1, 0, true);
        let dtinit = self.state.dt;
        let result = self.minimize_inner(opts, set, fixes, first, last);
        self.state.neigh_settings = neigh;
        self.state.dt = dtinit;
        self.out.flush();
        result
    }

    fn minimize_inner(&mut self, opts: &MinimizeOptions, set: MinSettings, fixes: Vec<usize>, first: i64, last: i64) -> Result<(), RunError> {
        let natoms = self.state.natoms() as f64;
        let normflag = crate::output::thermo::normalize(&self.thermo, &self.state);
        // the fixes' extra global degrees of freedom (fix box/relax)
        let mut extra = Vec::new();
        let mut nextra = 0;
        for (k, f) in self.fixes.iter_mut().enumerate() {
            if let Some(e) = f.min_extra() {
                extra.push((k, nextra));
                nextra += e.min_dof();
            }
        }
        let mut m = Min {
            opts: *opts,
            set,
            normflag,
            natoms,
            fixes,
            ecurrent: 0.0,
            eprevious: 0.0,
            einitial: 0.0,
            niter: 0,
            neval: 0,
            alpha_final: 0.0,
            last,
            vectors: Vec::new(),
            extra,
            fextra: vec![0.0; nextra],
            gextra: vec![0.0; nextra],
            hextra: vec![0.0; nextra],
            box0: None,
        };
        self.out.print(&format!("Setting up {} style minimization ...\n  Unit style    : {}\n  Current step  : {}", m.set.style.name(), self.state.units.name(), first));
        if nextra > 0 {
            if m.set.style == MinStyle::Fire {
                return Err(RunError::setup(first, "cannot use a damped dynamics min style (fire) with fix box/relax: use min_style cg or sd".to_string().into()));
            }
            self.out.print(&format!("WARNING: Energy due to {nextra} extra global DOFs will be included in minimizer energies"));
        }
        let mut fire = match m.set.style {
            MinStyle::Fire => Some(fire::Fire::new(self, &m)),
            _ => None,
        };
        // setup: lists, forces and energies of the current state, the fixes' min_setup
        self.timers.stamp();
        self.rebuild_at(true)?;
        // the setup's build is not counted (LAMMPS' Min::setup zeroes ncalls after it)
        self.state.neighbor.nbuilds = 0;
        self.timers.charge(Stage::Neigh);
        self.setup_computes_after_build();
        self.state.natoms_expected = self.state.atoms.nlocal;
        self.compute_forces(true, false)?;
        m.post_force(self)?;
        let mem = crate::sim::memory::bytes_per_rank(self) as f64 / (1024.0 * 1024.0);
        self.out.print(&format!("Per MPI rank memory allocation (min/avg/max) = {mem:.4} | {mem:.4} | {mem:.4} Mbytes"));
        if let Some(h) = self.thermo.header() {
            self.out.print(&h);
        }
        self.output_now(true, last, false)?;
        m.ecurrent = m.energy(self)?;
        m.einitial = m.ecurrent;
        let fnorm2_init = m.fnorm_sqr(self).sqrt();
        let fnorminf_init = m.fnorm_inf(self).sqrt();

        self.timers.reset();
        let t0 = Instant::now();
        self.loop_start = Some(t0);
        let stop = match fire.as_mut() {
            Some(fire) => fire.iterate(self, &mut m, opts.maxiter)?,
            None => linesearch::iterate(self, &mut m, opts.maxiter)?,
        };
        let mut nsteps = opts.maxiter;
        if stop != Stop::MaxIter {
            // stopped early: forces of the final state (again) and the last output now
            nsteps = m.niter;
            m.ecurrent = m.energy_force(self, false)?;
            self.output_now(true, self.state.step, true)?;
        }
        let loop_time = t0.elapsed().as_secs_f64();
        self.loop_start = None;
        if let Some(f) = self.thermo.footer() {
            self.out.print(f);
        }
        let efinal = m.ecurrent;
        let fnorm2_final = m.fnorm_sqr(self).sqrt();
        let fnorminf_final = m.fnorm_inf(self).sqrt();
        self.last_loop_seconds = loop_time;
        self.last_loop_steps = nsteps;
        let g8 = crate::output::format::g8;
        let e = |v: f64| format!("{:>18}", dmhs_parser::numfmt::format_g(v, 15));
        self.out.print(&format!(
            "Loop time of {} on 1 procs for {} steps with {} atoms\n",
            crate::output::format::g6(loop_time),
            nsteps,
            self.state.atoms.nlocal
        ));
        let stats = format!(
            "Minimization stats:\n  Stopping criterion = {}\n  Energy initial, next-to-last, final = \n    {} {} {}\n  Force two-norm initial, final = {} {}\n  Force max component initial, final = {} {}\n  Final line search alpha, max atom move = {} {}\n  Iterations, force evaluations = {} {}\n",
            stop.text(),
            e(m.einitial),
            e(m.eprevious),
            e(efinal),
            g8(fnorm2_init),
            g8(fnorm2_final),
            g8(fnorminf_init),
            g8(fnorminf_final),
            g8(m.alpha_final),
            g8(m.alpha_final * fnorminf_final),
            m.niter,
            m.neval
        );
        self.print_run_summary(loop_time, 0, Some(&stats), None);
        self.min_stats = Some(MinStats { stop, niter: m.niter, neval: m.neval, einitial: m.einitial, efinal });
        Ok(())
    }
}

/// What the last minimization did (for tests and the Python module).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MinStats {
    pub stop: Stop,
    pub niter: i64,
    pub neval: i64,
    pub einitial: f64,
    pub efinal: f64,
}
