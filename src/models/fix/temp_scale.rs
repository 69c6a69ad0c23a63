//! The three thermostats that scale the group's velocities at the end of a step towards a target
//! temperature and count the energy they remove (the scalar, extensive), with LAMMPS' operations
//! (fix_temp_rescale.cpp, fix_temp_berendsen.cpp, fix_temp_csvr.cpp):
//!
//! * `fix ID group temp/rescale N Tstart Tstop window fraction`: every N steps, when T is more
//!   than `window` from the target, scale so that T moves `fraction` of the way to it;
//! * `fix ID group temp/berendsen Tstart Tstop damp`: every step, scale by
//!   lambda = sqrt(1 + dt/damp (T_target/T - 1)) (Berendsen's weak coupling);
//! * `fix ID group temp/csvr Tstart Tstop Tdamp seed`: every step, scale by a lambda drawn so
//!   that the kinetic energy samples the canonical distribution (Bussi's stochastic velocity
//!   rescaling, temp_csvr.rs).

use super::thermostat::{GroupTemp, Target};
use super::{Fix, FixCtx, FixHooks};
use crate::models::compute::temp_bias::TempSpec;
use crate::engine::state::{RunError, State};
use crate::engine::random_mars::SEED_RANGE;
use dmhs_parser::{Args, Command, DResult, Word};

enum Law {
    Rescale { nevery: i64, window: f64, fraction: f64 },
    Berendsen { period: f64 },
    Csvr(super::temp_csvr::Csvr),
}

pub struct FixTempScale {
    id: String,
    groupbit: u32,
    style: &'static str,
    target: Target,
    law: Law,
    temp: GroupTemp,
    energy: f64,
}

impl FixTempScale {
    /// `style` is temp/rescale, temp/berendsen or temp/csvr.
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command) -> DResult<Self> {
        let syntax = match style.text.as_str() {
            "temp/rescale" => "fix ID group temp/rescale N Tstart Tstop window fraction",
            "temp/berendsen" => "fix ID group temp/berendsen Tstart Tstop damp",
            _ => "fix ID group temp/csvr Tstart Tstop Tdamp seed  (Tdamp > 0, seed > 0)",
        };
        let mut a = Args::from_words(args, cmd.span, syntax);
        let nevery = if style.text == "temp/rescale" { a.i64_in("N (steps between rescales)", 1, i64::MAX)? } else { 1 };
        let target = Target::parse(&mut a)?;
        let (law, style) = match style.text.as_str() {
            "temp/rescale" => {
                let window = a.f64("window")?;
                (Law::Rescale { nevery, window, fraction: a.f64("fraction")? }, "temp/rescale")
            }
            "temp/berendsen" => (Law::Berendsen { period: a.positive_f64("damp")? }, "temp/berendsen"),
            _ => {
                let period = a.positive_f64("Tdamp")?;
                let seed = a.i64_in("seed", *SEED_RANGE.start(), *SEED_RANGE.end())? as i32;
                (Law::Csvr(super::temp_csvr::Csvr::new(period, seed)), "temp/csvr")
            }
        };
        a.finish()?;
        Ok(FixTempScale { id, groupbit, style, target, law, temp: GroupTemp::new(groupbit), energy: 0.0 })
    }
}

impl FixTempScale {
    /// One temp/csvr step in LAMMPS' order: the target, T, then nothing to do without degrees
    /// of freedom (T = 0 is not refused, as in LAMMPS).
    fn csvr_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let t_target = self.target.now(state, self, ctx, "temp/csvr")?;
        let t_current = self.temp.compute(state)?;
        let efactor = 0.5 * self.temp.dof * state.units.boltz;
        let (old, new) = (t_current * efactor, t_target * efactor);
        let Law::Csvr(law) = &mut self.law else { return Ok(()) };
        if self.temp.dof < 1.0 {
            return Ok(());
        }
        let lamda = law.resample(state.dt, old, new, self.temp.dof);
        self.temp.scale(state, self.groupbit, lamda)?;
        self.energy += old * (1.0 - lamda * lamda);
        Ok(())
    }
}

impl Fix for FixTempScale {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        self.style
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn modify_temp(&mut self, spec: TempSpec) -> Result<(), String> {
        self.temp.replace(spec);
        Ok(())
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        self.temp.count_dof(state, ctx);
        Ok(())
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if let Law::Rescale { nevery, .. } = self.law {
            if state.step % nevery != 0 {
                return Ok(());
            }
        }
        if matches!(self.law, Law::Csvr(_)) {
            return self.csvr_step(state, ctx);
        }
        let t_current = self.temp.compute(state)?;
        let tdof = self.temp.dof;
        // nothing to do without degrees of freedom
        if tdof < 1.0 {
            return Ok(());
        }
        if t_current == 0.0 {
            return Err(RunError::new(state.step, format!("computed temperature for fix {} cannot be 0.0", self.style)));
        }
        let t_target = self.target.now(state, self, ctx, self.style)?;
        let efactor = 0.5 * state.units.boltz * tdof;
        let factor = match self.law {
            Law::Rescale { window, fraction, .. } => {
                if (t_current - t_target).abs() <= window {
                    return Ok(());
                }
                let t_target = t_current - fraction * (t_current - t_target);
                self.energy += (t_current - t_target) * efactor;
                (t_target / t_current).sqrt()
            }
            Law::Berendsen { period } => {
                let lamda = (1.0 + state.dt / period * (t_target / t_current - 1.0)).sqrt();
                self.energy += t_current * (1.0 - lamda * lamda) * efactor;
                lamda
            }
            Law::Csvr(_) => unreachable!("temp/csvr steps in csvr_step"),
        };
        self.temp.scale(state, self.groupbit, factor)
    }
    fn couples_energy(&self) -> bool {
        true
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.energy)
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
    /// LAMMPS' write_restart of the three styles: the energy removed so far; temp/csvr then
    /// its random stream's state (a run restarted goes on with the same numbers).
    fn write_restart(&self) -> Option<Vec<f64>> {
        let mut list = vec![self.energy];
        if let Law::Csvr(law) = &self.law {
            list.extend(law.random_state());
        }
        Some(list)
    }
    fn restart(&mut self, list: &[f64]) {
        if let Some(&e) = list.first() {
            self.energy = e;
        }
        if let Law::Csvr(law) = &mut self.law {
            // a state that is not one (a file from another style) leaves the seed's stream
            law.set_random_state(&list[list.len().min(1)..]);
        }
    }
}

/// v *= factor for the owned atoms of a group.
pub fn scale_group(state: &mut State, groupbit: u32, factor: f64) {
    let a = &mut state.atoms;
    for i in 0..a.nlocal {
        if a.mask[i] & groupbit != 0 {
            let v = &mut a.v[i];
            v[0] *= factor;
            v[1] *= factor;
            v[2] *= factor;
        }
    }
}
