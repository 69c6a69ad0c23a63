//! `fix ID group deform N dim style args ... [remap x|none] [flip yes|no] [units lattice|box]`:
//! the box lengths changed every N steps at the end of the step, each controlled dimension
//! towards its target of the run (LAMMPS'
//! FixDeform on an orthogonal box, same arithmetic). Styles: final lo hi, delta dlo dhi,
//! scale f, vel v, erate r, trate r, volume, wiggle A Tp, variable v_len v_rate. With `remap
//! x` (default) the atoms of the group follow the box in box-fraction coordinates.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::domain::{BoundaryKind, Dilation};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group deform N x|y|z final lo hi | delta dlo dhi | scale f | vel v | erate r | trate r | volume | wiggle A Tp | variable v_len v_rate ... [remap x|none] [flip yes|no] [units lattice|box]";

#[derive(Clone, Debug, Default, PartialEq)]
enum Style {
    #[default]
    None,
    Final(f64, f64),
    Delta(f64, f64),
    Scale(f64),
    Vel(f64),
    Erate(f64),
    Trate(f64),
    Volume,
    Wiggle(f64, f64),
    Variable(String, String),
}

/// How a `volume` dimension follows the others (LAMMPS' substyles): from the one other that
/// changes (the third fixed), from both others, or shared with another `volume` dimension.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
enum VolumeFrom {
    #[default]
    OneFromOne,
    OneFromTwo,
    TwoFromOne,
}

/// One dimension's settings and the run's start, stop and target values.
#[derive(Clone, Debug, Default)]
struct Dim {
    style: Style,
    substyle: VolumeFrom,
    fixed: usize,
    dynamic1: usize,
    dynamic2: usize,
    lo_initial: f64,
    hi_initial: f64,
    vol_initial: f64,
    lo_start: f64,
    hi_start: f64,
    vol_start: f64,
    lo_stop: f64,
    hi_stop: f64,
    lo_target: f64,
    hi_target: f64,
}

pub struct FixDeform {
    id: String,
    groupbit: u32,
    nevery: i64,
    set: [Dim; 3],
    remap: bool,
}

impl FixDeform {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let d = state.domain().map_err(|m| a.error_command(format!("fix deform: {m}"), "no box"))?;
        if d.triclinic() {
            return Err(a.error_command("fix deform on a triclinic box is not supported yet", "triclinic box"));
        }
        let nevery = a.i64_in("N", 1, i32::MAX as i64)?;
        let mut set: [Dim; 3] = Default::default();
        let mut controlled: Vec<(usize, &Word)> = Vec::new();
        while let Some(w) = a.peek() {
            let dim = match w.text.as_str() {
                "x" => 0,
                "y" => 1,
                "z" => 2,
                "xy" | "xz" | "yz" => return Err(a.error_at(w, "Fix deform tilt factors require triclinic box (dmhs has orthogonal boxes only)", "needs a triclinic box")),
                _ => break,
            };
            a.skip(1);
            let s = a.word("deformation style")?;
            set[dim].style = match s.text.as_str() {
                "final" => Style::Final(a.f64("lo")?, a.f64("hi")?),
                "delta" => Style::Delta(a.f64("dlo")?, a.f64("dhi")?),
                "scale" => Style::Scale(a.f64("scale factor")?),
                "vel" => Style::Vel(a.f64("velocity")?),
                "erate" => Style::Erate(a.f64("engineering strain rate")?),
                "trate" => Style::Trate(a.f64("true strain rate")?),
                "volume" => Style::Volume,
                "wiggle" => {
                    let amp = a.f64("amplitude")?;
                    let period = a.f64_where("period", "> 0", |p| p > 0.0)?;
                    Style::Wiggle(amp, period)
                }
                "variable" => {
                    let mut name = |what: &str| -> DResult<String> {
                        let w = a.word(what)?;
                        match w.text.strip_prefix("v_") {
                            Some(n) if !n.is_empty() => Ok(n.to_string()),
                            _ => Err(a.error_at(w, format!("Illegal fix deform variable name {}", w.text), "expected v_name")),
                        }
                    };
                    let (h, rate) = (name("length variable")?, name("rate variable")?);
                    Style::Variable(h, rate)
                }
                _ => return Err(a.error_at(s, format!("Illegal fix deform command argument: {}", s.text), "final, delta, scale, vel, erate, trate, volume, wiggle or variable")),
            };
            controlled.push((dim, w));
        }
        // options
        let (mut remap, mut lattice_units) = (true, true);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "remap" => {
                    let v = a.word("remap")?;
                    remap = match v.text.as_str() {
                        "x" => true,
                        "none" => false,
                        "v" => return Err(a.error_at(v, "fix deform remap v (velocities of atoms crossing the box remapped by the box's rate, for SLLOD) is not supported by dmhs", "x or none")),
                        _ => return Err(a.error_at(v, format!("unknown fix deform remap `{}`", v.text), "x or none")),
                    };
                }
                "flip" => {
                    a.logical("flip")?;
                }
                "units" => lattice_units = a.choice("units", &["box", "lattice"])? == 1,
                _ => return Err(a.unknown_keyword(w, &["remap", "flip", "units"])),
            }
        }
        for &(k, w) in &controlled {
            if d.boundary[k].iter().any(|b| matches!(b, BoundaryKind::Shrink | BoundaryKind::ShrinkMin)) {
                return Err(a.error_at(w, "Cannot use fix deform on a shrink-wrapped boundary", "shrink-wrapped"));
            }
        }
        // lengths and velocities in lattice units
        let uses_lengths = set.iter().any(|s| matches!(s.style, Style::Final(..) | Style::Delta(..) | Style::Vel(_) | Style::Wiggle(..)));
        let map = if uses_lengths && lattice_units { state.lattice_scale().map_err(|m| a.error_command(m, "lattice"))? } else { [1.0; 3] };
        for (k, s) in set.iter_mut().enumerate() {
            let m = map[k];
            s.style = match s.style.clone() {
                Style::Final(lo, hi) => Style::Final(lo * m, hi * m),
                Style::Delta(lo, hi) => Style::Delta(lo * m, hi * m),
                Style::Vel(v) => Style::Vel(v * m),
                Style::Wiggle(amp, p) => Style::Wiggle(amp * m, p),
                other => other,
            };
        }
        // a volume dimension follows the others
        for i in 0..3 {
            if set[i].style != Style::Volume {
                continue;
            }
            let (o1, o2) = ((i + 1) % 3, (i + 2) % 3);
            let idle = |s: &Style| matches!(s, Style::None | Style::Volume);
            if idle(&set[o1].style) && idle(&set[o2].style) {
                let w = controlled.iter().find(|c| c.0 == i).map(|c| c.1).unwrap_or(&cmd.name);
                return Err(a.error_at(w, "Fix deform volume setting is invalid: another dimension must change", "volume needs a changing dimension"));
            }
            let (sub, fixed, d1, d2) = if set[o1].style == Style::None {
                (VolumeFrom::OneFromOne, o1, o2, 0)
            } else if set[o2].style == Style::None {
                (VolumeFrom::OneFromOne, o2, o1, 0)
            } else if set[o1].style == Style::Volume {
                (VolumeFrom::TwoFromOne, o1, o2, 0)
            } else if set[o2].style == Style::Volume {
                (VolumeFrom::TwoFromOne, o2, o1, 0)
            } else {
                (VolumeFrom::OneFromTwo, 0, o1, o2)
            };
            (set[i].substyle, set[i].fixed, set[i].dynamic1, set[i].dynamic2) = (sub, fixed, d1, d2);
        }
        let prd = d.prd();
        for (k, s) in set.iter_mut().enumerate() {
            s.lo_initial = d.lo[k];
            s.hi_initial = d.hi[k];
            s.vol_initial = prd[0] * prd[1] * prd[2];
        }
        Ok(FixDeform { id, groupbit, nevery, set, remap })
    }

    /// The run's window: (begin, end) steps (LAMMPS' beginstep, endstep).
    fn window(state: &State) -> (i64, i64) {
        state.run_window.unwrap_or((state.step, state.step))
    }

    /// LAMMPS' update_box: the targets of this step, then the box and the atoms.
    fn update_box(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let step = state.step;
        let (begin, end) = Self::window(state);
        let nsteps = (step - begin) as f64;
        let nsteps_total = (end - begin) as f64;
        let dt = state.dt;
        let mut delta = nsteps;
        if delta != 0.0 {
            delta /= nsteps_total;
        }
        let d = state.domain().map_err(|m| RunError::new(step, m))?.clone();
        // strain-controlled dimensions
        for i in 0..3 {
            let s = &self.set[i];
            let (lo, hi) = match s.style.clone() {
                Style::None => (d.lo[i], d.hi[i]),
                Style::Trate(rate) => {
                    let delt = nsteps * dt;
                    let shift = 0.5 * ((s.hi_start - s.lo_start) * (rate * delt).exp());
                    (0.5 * (s.lo_start + s.hi_start) - shift, 0.5 * (s.lo_start + s.hi_start) + shift)
                }
                Style::Wiggle(amp, period) => {
                    let delt = nsteps * dt;
                    let shift = 0.5 * amp * (std::f64::consts::TAU * delt / period).sin();
                    (s.lo_start - shift, s.hi_start + shift)
                }
                Style::Variable(h, rate) => {
                    let del = ctx.equal(state, self, &h).map_err(|m| RunError::new(step, format!("fix deform {}: {m}", self.id)))?;
                    // the rate (LAMMPS' h_rate, read by SLLOD) is evaluated as LAMMPS does
                    ctx.equal(state, self, &rate).map_err(|m| RunError::new(step, format!("fix deform {}: {m}", self.id)))?;
                    let s = &self.set[i];
                    (s.lo_start - 0.5 * del, s.hi_start + 0.5 * del)
                }
                Style::Volume => (s.lo_target, s.hi_target),
                _ => (s.lo_start + delta * (s.lo_stop - s.lo_start), s.hi_start + delta * (s.hi_stop - s.hi_start)),
            };
            self.set[i].lo_target = lo;
            self.set[i].hi_target = hi;
        }
        // volume-controlled dimensions
        for i in 0..3 {
            if self.set[i].style != Style::Volume {
                continue;
            }
            let s = &self.set[i];
            let (d1, d2, fx) = (&self.set[s.dynamic1], &self.set[s.dynamic2], &self.set[s.fixed]);
            let v0 = s.vol_start;
            let shift = match s.substyle {
                VolumeFrom::OneFromOne => 0.5 * (v0 / (d1.hi_target - d1.lo_target) / (fx.hi_start - fx.lo_start)),
                VolumeFrom::OneFromTwo => 0.5 * (v0 / (d1.hi_target - d1.lo_target) / (d2.hi_target - d2.lo_target)),
                VolumeFrom::TwoFromOne => 0.5 * (v0 * (s.hi_start - s.lo_start) / (d1.hi_target - d1.lo_target) / (fx.hi_start - fx.lo_start)).sqrt(),
            };
            let mid = 0.5 * (s.lo_start + s.hi_start);
            self.set[i].lo_target = mid - shift;
            self.set[i].hi_target = mid + shift;
        }
        let dom = state.domain.as_mut().ok_or_else(|| RunError::new(step, "fix deform: no box"))?;
        for i in 0..3 {
            if self.set[i].style != Style::None {
                dom.lo[i] = self.set[i].lo_target;
                dom.hi[i] = self.set[i].hi_target;
            }
        }
        let prd_new = dom.prd();
        if (0..3).any(|k| !(prd_new[k] > 0.0)) {
            return Err(RunError::new(step, format!("fix deform {}: the box length became {:?} (not positive)", self.id, prd_new)));
        }
        // the group's owned atoms follow the box in box fractions
        if self.remap {
            let dilation = Dilation::new(&d, dom);
            let at = &mut state.atoms;
            for i in (0..at.nlocal).filter(|&i| at.mask[i] & self.groupbit != 0) {
                dilation.apply(&mut at.x[i]);
            }
        }
        Ok(())
    }
}

impl Fix for FixDeform {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "deform"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn changes_box(&self) -> bool {
        true
    }
    /// LAMMPS' init: the start and stop of each dimension over the run (from the box now, or
    /// from when the fix was defined under `run ... start`).
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        if ctx.other_fixes().any(|f| f.style() == "deform") {
            return Err("More than one fix deform".into());
        }
        let d = state.domain()?;
        let (begin, end) = Self::window(state);
        let delt = (end - begin) as f64 * state.dt;
        let prd = d.prd();
        let first = state.step == begin;
        for i in 0..3 {
            let s = &mut self.set[i];
            if first {
                s.lo_start = d.lo[i];
                s.hi_start = d.hi[i];
                s.vol_start = prd[0] * prd[1] * prd[2];
            } else {
                s.lo_start = s.lo_initial;
                s.hi_start = s.hi_initial;
                s.vol_start = s.vol_initial;
            }
            let (lo, hi) = (s.lo_start, s.hi_start);
            match s.style {
                Style::Final(flo, fhi) => (s.lo_stop, s.hi_stop) = (flo, fhi),
                Style::Delta(dlo, dhi) => (s.lo_stop, s.hi_stop) = (lo + dlo, hi + dhi),
                Style::Scale(f) => {
                    let shift = 0.5 * f * (hi - lo);
                    (s.lo_stop, s.hi_stop) = (0.5 * (lo + hi) - shift, 0.5 * (lo + hi) + shift);
                }
                Style::Vel(v) => (s.lo_stop, s.hi_stop) = (lo - 0.5 * delt * v, hi + 0.5 * delt * v),
                Style::Erate(r) => {
                    let shift = 0.5 * delt * r * (hi - lo);
                    (s.lo_stop, s.hi_stop) = (lo - shift, hi + shift);
                    if s.hi_stop <= s.lo_stop {
                        return Err("Final box dimension due to fix deform is < 0.0".into());
                    }
                }
                Style::Trate(r) => {
                    let shift = 0.5 * ((hi - lo) * (r * delt).exp());
                    (s.lo_stop, s.hi_stop) = (0.5 * (lo + hi) - shift, 0.5 * (lo + hi) + shift);
                }
                Style::Wiggle(amp, period) => {
                    let shift = 0.5 * amp * (std::f64::consts::TAU * delt / period).sin();
                    (s.lo_stop, s.hi_stop) = (lo - shift, hi + shift);
                }
                Style::None | Style::Volume | Style::Variable(..) => {}
            }
        }
        Ok(())
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        self.update_box(state, ctx)
    }
}
