//! The two thermostats that scale the group's velocities at the end of a step towards a target
//! temperature and count the energy they remove (the scalar, extensive), with LAMMPS' operations
//! (fix_temp_rescale.cpp, fix_temp_berendsen.cpp):
//!
//! * `fix ID group temp/rescale N Tstart Tstop window fraction`: every N steps, when T is more
//!   than `window` from the target, scale so that T moves `fraction` of the way to it;
//! * `fix ID group temp/berendsen Tstart Tstop damp`: every step, scale by
//!   lambda = sqrt(1 + dt/damp (T_target/T - 1)) (Berendsen's weak coupling).

use super::thermostat::{GroupTemp, Target};
use super::{Fix, FixCtx, FixHooks};
use crate::models::compute::temp_bias::TempSpec;
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

enum Law {
    Rescale { nevery: i64, window: f64, fraction: f64 },
    Berendsen { period: f64 },
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
    /// `style` is temp/rescale or temp/berendsen.
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command) -> DResult<Self> {
        let rescale = style.text == "temp/rescale";
        let syntax = if rescale { "fix ID group temp/rescale N Tstart Tstop window fraction" } else { "fix ID group temp/berendsen Tstart Tstop damp" };
        let mut a = Args::from_words(args, cmd.span, syntax);
        let nevery = if rescale { a.i64_in("N (steps between rescales)", 1, i64::MAX)? } else { 1 };
        let target = Target::parse(&mut a)?;
        let (law, style) = if rescale {
            let window = a.f64("window")?;
            (Law::Rescale { nevery, window, fraction: a.f64("fraction")? }, "temp/rescale")
        } else {
            (Law::Berendsen { period: a.positive_f64("damp")? }, "temp/berendsen")
        };
        a.finish()?;
        Ok(FixTempScale { id, groupbit, style, target, law, temp: GroupTemp::new(groupbit), energy: 0.0 })
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
        };
        self.temp.scale(state, self.groupbit, factor)
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.energy)
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
    /// LAMMPS' write_restart of both styles: the energy removed so far.
    fn write_restart(&self) -> Option<Vec<f64>> {
        Some(vec![self.energy])
    }
    fn restart(&mut self, list: &[f64]) {
        if let Some(&e) = list.first() {
            self.energy = e;
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
