//! `fix ID group dt/reset N Tmin Tmax Xmax [units box|lattice] [emax E]`: every N steps (and
//! at the run's setup) choose dt so that no atom of the group moves more than Xmax in a step,
//! with LAMMPS' operations (fix_dt_reset.cpp). Per atom, dt is the smaller of Xmax/|v| and
//! sqrt(2 Xmax m / (ftm2v |f|)) (and, with emax, E / sqrt(|f|^2 |v|^2 ftm2v mvv2e)), then
//! shrunk so that the step's displacement dt v + dt^2 f/(2m) is at most Xmax; the smallest over
//! the group, clamped to [Tmin, Tmax] (NULL: no bound), becomes the timestep. The scalar is the
//! step at which dt last changed; `time` keeps counting across the changes (LAMMPS'
//! update_time, here `State::atime`/`atimestep`).

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group dt/reset N Tmin Tmax Xmax [units box|lattice] [emax E]  (Tmin, Tmax: number or NULL)";

/// LAMMPS' BIG: the bound of an atom that neither moves nor feels a force.
const BIG: f64 = 1.0e20;

pub struct FixDtReset {
    id: String,
    groupbit: u32,
    nevery: i64,
    tmin: Option<f64>,
    tmax: Option<f64>,
    /// Xmax in box units.
    xmax: f64,
    emax: Option<f64>,
    /// The step at which dt last changed (the scalar).
    laststep: i64,
}

impl FixDtReset {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64_in("N (steps between resets)", 1, i64::MAX)?;
        let bound = |a: &mut Args, what: &str| -> DResult<Option<f64>> {
            match a.peek() {
                Some(w) if w.text == "NULL" => {
                    a.skip(1);
                    Ok(None)
                }
                _ => a.non_negative_f64(what).map(Some),
            }
        };
        let tmin = bound(&mut a, "Tmin")?;
        let tmax = bound(&mut a, "Tmax")?;
        if let (Some(lo), Some(hi)) = (tmin, tmax) {
            if lo >= hi {
                let w = a.last().expect("Tmax was read");
                return Err(a.error_at(w, format!("Tmax ({hi}) must be larger than Tmin ({lo})"), "must be > Tmin"));
            }
        }
        let mut xmax = a.positive_f64("Xmax")?;
        let (mut lattice_units, mut emax) = (true, None);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "units" => lattice_units = a.choice("units", &["box", "lattice"])? == 1,
                "emax" => emax = Some(a.positive_f64("emax")?),
                _ => return Err(a.unknown_keyword(w, &["units", "emax"])),
            }
        }
        if lattice_units {
            // LAMMPS scales by xlattice (1 under the default `lattice none 1.0`)
            xmax *= state.lattice_scale().map_err(|e| a.error_at(&cmd.name, e, "needs a lattice (or `units box`)"))?[0];
        }
        Ok(FixDtReset { id, groupbit, nevery, tmin, tmax, xmax, emax, laststep: state.step })
    }

    /// The new timestep of the group's atoms, clamped (LAMMPS' end_of_step), in LAMMPS' local order
    /// of operations per atom; the minimum does not depend on the order of the atoms.
    fn choose(&self, state: &State) -> f64 {
        let a = &state.atoms;
        let (ftm2v, mvv2e) = (state.units.ftm2v, state.units.mvv2e);
        let per_atom = a.features.per_atom_mass();
        let mut dtmin = BIG;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let massinv = if per_atom { 1.0 / a.rmass[i] } else { 1.0 / state.type_mass[a.typ[i]] };
            let (v, f) = (a.v[i], a.f[i]);
            let vsq = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            let fsq = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
            let dtv = if vsq > 0.0 { self.xmax / vsq.sqrt() } else { BIG };
            let dtf = if fsq > 0.0 { (2.0 * self.xmax / (ftm2v * fsq.sqrt() * massinv)).sqrt() } else { BIG };
            let mut dt = dtv.min(dtf);
            if let Some(emax) = self.emax {
                if vsq > 0.0 && fsq > 0.0 {
                    let dte = emax / (fsq * vsq).sqrt() / (ftm2v * mvv2e).sqrt();
                    dt = dt.min(dte);
                }
            }
            let dtsq = dt * dt;
            let del = [0, 1, 2].map(|k| dt * v[k] + 0.5 * dtsq * massinv * f[k] * ftm2v);
            let delr = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
            if delr > self.xmax {
                dt *= self.xmax / delr;
            }
            dtmin = dtmin.min(dt);
        }
        // the least over the ranks (LAMMPS' MPI_Allreduce MPI_MIN), then clamped
        let mut all = [dtmin];
        state.min_ranks(&mut all);
        let mut dt = all[0];
        if let Some(lo) = self.tmin {
            dt = dt.max(lo);
        }
        if let Some(hi) = self.tmax {
            dt = dt.min(hi);
        }
        dt
    }

    fn reset(&mut self, state: &mut State) {
        let dt = self.choose(state);
        if dt == state.dt {
            return;
        }
        self.laststep = state.step;
        // the time reached so far was made with the old dt (LAMMPS' update_time)
        state.atime = state.time();
        state.atimestep = state.step;
        state.dt = dt;
    }
}

impl Fix for FixDtReset {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "dt/reset"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn setup(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.reset(state);
        Ok(())
    }
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery == 0 {
            self.reset(state);
        }
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.laststep as f64)
    }
}
