//! `fix ID group momentum N [linear xflag yflag zflag] [angular] [rescale]`: every N steps, at
//! the end of the step, zero the group's linear momentum (the flagged components of its
//! centre-of-mass velocity) and/or its angular momentum about its centre of mass (v_i -= omega x
//! r_i, unwrapped positions), and with `rescale` scale the velocities back to the kinetic energy
//! before (LAMMPS' fix momentum). Sums run over the atoms in LAMMPS' local order, as LAMMPS'
//! Group functions make them, so the same bits.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::group_rotation;
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "fix ID group momentum N [linear xflag yflag zflag] [angular] [rescale]";

pub struct FixMomentum {
    id: String,
    groupbit: u32,
    nevery: i64,
    /// the components `linear` zeroes (None: no `linear`)
    linear: Option<[bool; 3]>,
    angular: bool,
    rescale: bool,
}

impl FixMomentum {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64_in("N (steps between removals)", 1, i64::MAX)?;
        let (mut linear, mut angular, mut rescale) = (None, false, false);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "linear" => {
                    let mut flags = [false; 3];
                    for (f, what) in flags.iter_mut().zip(["xflag", "yflag", "zflag"]) {
                        *f = a.i64_in(what, 0, 1)? == 1;
                    }
                    linear = Some(flags);
                }
                "angular" => angular = true,
                "rescale" => rescale = true,
                _ => return Err(a.unknown_keyword(w, &["linear", "angular", "rescale"])),
            }
        }
        if linear.is_none() && !angular {
            return Err(Diagnostic::at(cmd.span, "fix momentum requires `linear` or `angular`", "nothing to zero").with_help(SYNTAX));
        }
        Ok(FixMomentum { id, groupbit, nevery, linear, angular, rescale })
    }

    /// sum of m v^2 over the group (LAMMPS' order).
    fn twice_ke(&self, state: &State, order: &[usize]) -> f64 {
        let a = &state.atoms;
        let mut ke = [0.0];
        for &i in order {
            if a.mask[i] & self.groupbit != 0 {
                let v = a.v[i];
                ke[0] += state.mass(i) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            }
        }
        state.sum_ranks(&mut ke);
        ke[0]
    }
}

impl Fix for FixMomentum {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "momentum"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        if !state.groups.bit_is_dynamic(self.groupbit) && state.group_count(self.groupbit) == 0 {
            return Err(format!("fix momentum {}: the group has no atoms", self.id));
        }
        Ok(())
    }
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        let order = state.lammps_order.indices(state.atoms.nlocal).into_owned();
        let bit = self.groupbit;
        let ekin_old = if self.rescale { self.twice_ke(state, &order) } else { 0.0 };
        if let Some(flags) = self.linear {
            let vc = state.group_vcm(bit);
            let a = &mut state.atoms;
            for &i in &order {
                if a.mask[i] & bit != 0 {
                    for d in 0..3 {
                        if flags[d] {
                            a.v[i][d] -= vc[d];
                        }
                    }
                }
            }
        }
        if self.angular {
            let fail = |e: String| RunError::new(state.step, format!("fix momentum {}: {e}", self.id));
            // an empty (dynamic) group has no rotation to remove
            let Some(r) = group_rotation::of_group(state, bit) else { return Ok(()) };
            let (cm, w) = (r.cm, r.omega().map_err(fail)?);
            let periods = state.domain.as_ref().map_or(Default::default(), |d| d.periods());
            let a = &mut state.atoms;
            for &i in &order {
                if a.mask[i] & bit != 0 {
                    group_rotation::remove_rotation(&mut a.v[i], periods.unmap(a.x[i], a.image[i]), cm, w);
                }
            }
        }
        if self.rescale {
            let ekin_new = self.twice_ke(state, &order);
            let factor = if ekin_new != 0.0 { (ekin_old / ekin_new).sqrt() } else { 1.0 };
            let a = &mut state.atoms;
            for &i in &order {
                if a.mask[i] & bit != 0 {
                    for d in 0..3 {
                        a.v[i][d] *= factor;
                    }
                }
            }
        }
        Ok(())
    }
}
