//! `fix ID group deform N dim style args ... [remap x|v|none] [flip yes|no] [units lattice|box]`:
//! the box lengths (and a triclinic box's tilts) changed every N steps at the end of the step,
//! each controlled one towards its target of the run (LAMMPS' FixDeform, same arithmetic).
//! Length styles: final lo hi, delta dlo dhi, scale f, vel v, erate r, trate r, volume, wiggle
//! A Tp, variable v_len v_rate; tilt styles (xy xz yz): final t, delta dt, vel v, erate r,
//! trate r, wiggle A Tp, variable v_tilt v_rate. With `remap x` (default) the atoms of the group
//! follow the box in box fractions; with `remap v` they stay, and an atom of the group that
//! crosses a periodic face changes velocity by the box's rate (for fix nvt/sllod). The box's
//! rate (LAMMPS' h_rate, read by compute temp/deform and fix nvt/sllod) is set as LAMMPS sets
//! it: at init for the styles of constant rate, every step for trate, wiggle and variable.
//! With `flip yes` (default) a tilt beyond half the box length flips to its equivalent on the
//! other side on the next step (LAMMPS' pre_exchange), the atoms remapped and their image flags
//! carried over.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::domain::{BoundaryKind, BoxRate, Dilation};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group deform N x|y|z final lo hi | delta dlo dhi | scale f | vel v | erate r | trate r | volume | wiggle A Tp | variable v_len v_rate ... xy|xz|yz final t | delta dt | vel v | erate r | trate r | wiggle A Tp | variable v_tilt v_rate ... [remap x|v|none] [flip yes|no] [units lattice|box]";

/// One tilt's settings and the run's start, stop and target values (LAMMPS' set[3..5]).
#[derive(Clone, Debug, Default)]
struct Tilt {
    style: Style,
    initial: f64,
    start: f64,
    stop: f64,
    target: f64,
}

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

/// What follows the box: the group's positions (LAMMPS' X_REMAP), the velocities of the
/// group's atoms that cross a periodic face (V_REMAP), or nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Remap {
    X,
    V,
    None,
}

pub struct FixDeform {
    id: String,
    groupbit: u32,
    nevery: i64,
    set: [Dim; 3],
    /// xy, xz, yz
    tilt: [Tilt; 3],
    remap: Remap,
    flip: bool,
    /// The box's rate (LAMMPS' h_rate and h_ratelo).
    rate: BoxRate,
    /// The tilts to flip to and the flips (xy, xz, yz: +1, -1 or 0) at the next step's
    /// pre_exchange, with that step.
    pending_flip: Option<([f64; 3], [i32; 3], i64)>,
}

impl FixDeform {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let d = state.domain().map_err(|m| a.error_command(format!("fix deform: {m}"), "no box"))?;
        let nevery = a.i64_in("N", 1, i32::MAX as i64)?;
        let mut set: [Dim; 3] = Default::default();
        let mut tilt: [Tilt; 3] = Default::default();
        let mut controlled: Vec<(usize, &Word)> = Vec::new();
        while let Some(w) = a.peek() {
            let dim = match w.text.as_str() {
                "x" => 0,
                "y" => 1,
                "z" => 2,
                "xy" => 3,
                "xz" => 4,
                "yz" => 5,
                _ => break,
            };
            if dim >= 3 && !d.triclinic() {
                return Err(a.error_at(w, "Fix deform tilt factors require triclinic box", "needs a triclinic box").with_help("make it triclinic first: change_box all triclinic"));
            }
            a.skip(1);
            let s = a.word("deformation style")?;
            if dim >= 3 && matches!(s.text.as_str(), "scale" | "volume") {
                return Err(a.error_at(s, format!("Illegal fix deform command argument: {}", s.text), "final, delta, vel, erate, trate, wiggle or variable for a tilt"));
            }
            let style = match s.text.as_str() {
                "final" | "delta" if dim >= 3 => {
                    let v = a.f64("tilt")?;
                    if s.text == "final" { Style::Final(v, v) } else { Style::Delta(v, v) }
                }
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
            if dim < 3 {
                set[dim].style = style;
            } else {
                tilt[dim - 3].style = style;
            }
            controlled.push((dim, w));
        }
        // options
        let (mut remap, mut lattice_units, mut flip) = (Remap::X, true, true);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "remap" => {
                    let v = a.word("remap")?;
                    remap = match v.text.as_str() {
                        "x" => Remap::X,
                        "v" => Remap::V,
                        "none" => Remap::None,
                        _ => return Err(a.error_at(v, format!("unknown fix deform remap `{}`", v.text), "x, v or none")),
                    };
                }
                "flip" => flip = a.logical("flip")?,
                "units" => lattice_units = a.choice("units", &["box", "lattice"])? == 1,
                _ => return Err(a.unknown_keyword(w, &["remap", "flip", "units"])),
            }
        }
        for &(k, w) in &controlled {
            if k >= 3 {
                continue;
            }
            if d.boundary[k].iter().any(|b| matches!(b, BoundaryKind::Shrink | BoundaryKind::ShrinkMin)) {
                return Err(a.error_at(w, "Cannot use fix deform on a shrink-wrapped boundary", "shrink-wrapped"));
            }
        }
        // lengths and velocities in lattice units
        let lengthy = |s: &Style| matches!(s, Style::Final(..) | Style::Delta(..) | Style::Vel(_) | Style::Wiggle(..));
        let uses_lengths = set.iter().any(|s| lengthy(&s.style)) || tilt.iter().any(|t| lengthy(&t.style));
        let map = if uses_lengths && lattice_units { state.lattice_scale().map_err(|m| a.error_command(m, "lattice"))? } else { [1.0; 3] };
        // xy and xz in x spacings, yz in y ones
        for (k, t) in tilt.iter_mut().enumerate() {
            let m = map[if k == 2 { 1 } else { 0 }];
            t.style = match t.style.clone() {
                Style::Final(v, _) => Style::Final(v * m, v * m),
                Style::Delta(v, _) => Style::Delta(v * m, v * m),
                Style::Vel(v) => Style::Vel(v * m),
                Style::Wiggle(amp, p) => Style::Wiggle(amp * m, p),
                other => other,
            };
        }
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
        for (k, t) in tilt.iter_mut().enumerate() {
            t.initial = d.tilts()[k];
        }
        Ok(FixDeform { id, groupbit, nevery, set, tilt, remap, flip, rate: BoxRate::default(), pending_flip: None })
    }

    /// LAMMPS' apply_strain and update_domain for the tilts: this step's targets, each moved
    /// by whole box lengths to lie nearest the current tilt, then the flip to do at the next
    /// step if one leaves half a box length.
    fn tilt_targets(&mut self, state: &State, ctx: &mut FixCtx, delt: f64, delta: f64) -> Result<(), RunError> {
        let step = state.step;
        let d = state.domain().map_err(|m| RunError::new(step, m))?;
        let now = d.tilts();
        let h = d.h();
        for k in 0..3 {
            let t = &self.tilt[k];
            // LAMMPS' h index of this tilt: xy 5, xz 4, yz 3
            let ih = 5 - k;
            let target = match t.style.clone() {
                Style::None => now[k],
                Style::Trate(rate) => {
                    self.rate.h_rate[ih] = rate * h[ih];
                    t.start * (rate * delt).exp()
                }
                Style::Wiggle(amp, period) => {
                    self.rate.h_rate[ih] = wiggle_rate(amp, period, delt);
                    t.start + amp * (std::f64::consts::TAU * delt / period).sin()
                }
                Style::Variable(v, rate) => {
                    let del = ctx.equal(state, self, &v).map_err(|m| RunError::new(step, format!("fix deform {}: {m}", self.id)))?;
                    self.rate.h_rate[ih] = ctx.equal(state, self, &rate).map_err(|m| RunError::new(step, format!("fix deform {}: {m}", self.id)))?;
                    self.tilt[k].start + del
                }
                _ => t.start + delta * (t.stop - t.start),
            };
            self.tilt[k].target = target;
        }
        // LAMMPS' order yz, xz, xy; each against its second dimension's new length (y for yz,
        // x for the others) and the tilt's share of the old one
        for k in [2, 1, 0] {
            let idenom = if k == 2 { 1 } else { 0 };
            let denom = self.set[idenom].hi_target - self.set[idenom].lo_target;
            let current = h[5 - k] / h[idenom];
            let t = &mut self.tilt[k].target;
            while *t / denom - current > 0.0 {
                *t -= denom;
            }
            while *t / denom - current < 0.0 {
                *t += denom;
            }
            if (*t / denom - 1.0 - current).abs() < (*t / denom - current).abs() {
                *t -= denom;
            }
        }
        if self.flip {
            let xprd = self.set[0].hi_target - self.set[0].lo_target;
            let yprd = self.set[1].hi_target - self.set[1].lo_target;
            let (xinv, yinv) = (1.0 / xprd, 1.0 / yprd);
            let [xy, xz, yz] = [self.tilt[0].target, self.tilt[1].target, self.tilt[2].target];
            let out = |v: f64| !(-0.5..=0.5).contains(&v);
            if out(yz * yinv) || out(xz * xinv) || out(xy * xinv) {
                let (mut fxy, mut fxz, mut fyz) = (xy, xz, yz);
                let (mut m, mut n, mut p) = (0, 0, 0);
                if d.periodic(1) {
                    if fyz * yinv < -0.5 {
                        fyz += yprd;
                        fxz += fxy;
                        p = 1;
                    } else if fyz * yinv > 0.5 {
                        fyz -= yprd;
                        fxz -= fxy;
                        p = -1;
                    }
                }
                if d.periodic(0) {
                    // xz, then xy, each by one x length (LAMMPS' two separate tests)
                    let back = |t: &mut f64, flag: &mut i32| {
                        if *t * xinv < -0.5 {
                            *t += xprd;
                            *flag = 1;
                        }
                        if *t * xinv > 0.5 {
                            *t -= xprd;
                            *flag = -1;
                        }
                    };
                    back(&mut fxz, &mut n);
                    back(&mut fxy, &mut m);
                }
                if m != 0 || n != 0 || p != 0 {
                    self.pending_flip = Some(([fxy, fxz, fyz], [m, n, p], step + 1));
                }
            }
        }
        Ok(())
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
        let h = d.h();
        // strain-controlled dimensions; the styles of changing rate set it (before the box
        // changes: trate's is the rate times the old length)
        for i in 0..3 {
            let s = &self.set[i];
            let (lo, hi) = match s.style.clone() {
                Style::None => (d.lo[i], d.hi[i]),
                Style::Trate(rate) => {
                    let delt = nsteps * dt;
                    let shift = 0.5 * ((s.hi_start - s.lo_start) * (rate * delt).exp());
                    self.rate.h_rate[i] = rate * h[i];
                    self.rate.h_ratelo[i] = -0.5 * self.rate.h_rate[i];
                    (0.5 * (s.lo_start + s.hi_start) - shift, 0.5 * (s.lo_start + s.hi_start) + shift)
                }
                Style::Wiggle(amp, period) => {
                    let delt = nsteps * dt;
                    let shift = 0.5 * amp * (std::f64::consts::TAU * delt / period).sin();
                    self.rate.h_rate[i] = wiggle_rate(amp, period, delt);
                    self.rate.h_ratelo[i] = -0.5 * self.rate.h_rate[i];
                    (s.lo_start - shift, s.hi_start + shift)
                }
                Style::Variable(h, rate) => {
                    let del = ctx.equal(state, self, &h).map_err(|m| RunError::new(step, format!("fix deform {}: {m}", self.id)))?;
                    self.rate.h_rate[i] = ctx.equal(state, self, &rate).map_err(|m| RunError::new(step, format!("fix deform {}: {m}", self.id)))?;
                    self.rate.h_ratelo[i] = -0.5 * self.rate.h_rate[i];
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
        if d.triclinic() {
            self.tilt_targets(state, ctx, nsteps * dt, delta)?;
        }
        let dom = state.domain.as_mut().ok_or_else(|| RunError::new(step, "fix deform: no box"))?;
        dom.rate.h_rate = self.rate.h_rate;
        dom.rate.h_ratelo = self.rate.h_ratelo;
        for i in 0..3 {
            if self.set[i].style != Style::None {
                dom.lo[i] = self.set[i].lo_target;
                dom.hi[i] = self.set[i].hi_target;
            }
        }
        if let Some(tilts) = dom.tilt.as_mut() {
            for k in 0..3 {
                if self.tilt[k].style != Style::None {
                    tilts[k] = self.tilt[k].target;
                }
            }
        }
        let prd_new = dom.prd();
        if (0..3).any(|k| !(prd_new[k] > 0.0)) {
            return Err(RunError::new(step, format!("fix deform {}: the box length became {:?} (not positive)", self.id, prd_new)));
        }
        // the group's owned atoms follow the box in box fractions
        if self.remap == Remap::X {
            let dilation = Dilation::new(&d, dom);
            let at = &mut state.atoms;
            for i in (0..at.nlocal).filter(|&i| at.mask[i] & self.groupbit != 0) {
                dilation.apply(&mut at.x[i]);
            }
        }
        Ok(())
    }
}

/// A wiggle's rate of change at time `delt`: 2 pi / T A cos(2 pi delt / T) (LAMMPS' order).
fn wiggle_rate(amp: f64, period: f64, delt: f64) -> f64 {
    std::f64::consts::TAU / period * amp * (std::f64::consts::TAU * delt / period).cos()
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
        // (a flip is done before the atoms are wrapped on the next step)
        FixHooks { end_of_step: true, pre_exchange: self.tilt.iter().any(|t| t.style != Style::None) && self.flip, ..FixHooks::default() }
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
        // the tilts' start and stop: erate strains xy by the y length, xz and yz by the z one
        let now = d.tilts();
        let lz = self.set[2].hi_start - self.set[2].lo_start;
        let ly = self.set[1].hi_start - self.set[1].lo_start;
        for k in 0..3 {
            let t = &mut self.tilt[k];
            t.start = if first { now[k] } else { t.initial };
            t.stop = match t.style {
                Style::Final(v, _) => v,
                Style::Delta(v, _) => t.start + v,
                Style::Vel(v) => t.start + delt * v,
                Style::Erate(r) => t.start + delt * r * if k == 0 { ly } else { lz },
                Style::Trate(r) => {
                    if t.start == 0.0 {
                        return Err("Cannot use fix deform trate on a box with zero tilt".into());
                    }
                    t.start * (r * delt).exp()
                }
                Style::Wiggle(amp, period) => t.start + amp * (std::f64::consts::TAU * delt / period).sin(),
                _ => t.start,
            };
        }
        // LAMMPS' check of yz against the y length when xy changes too (a flip of xy would
        // shift yz's images)
        let (xy, yz) = (&self.tilt[0], &self.tilt[2]);
        if xy.style != Style::None && yz.style != Style::None && self.flip {
            if matches!(yz.style, Style::Variable(..)) {
                return Err("Fix deform cannot use yz variable with xy".into());
            }
            if !matches!(yz.style, Style::Wiggle(..)) {
                let y = &self.set[1];
                let too_much = |len: f64| yz.stop / len < -0.5 || yz.stop / len > 0.5;
                if too_much(y.hi_start - y.lo_start) || (y.style != Style::None && too_much(y.hi_stop - y.lo_stop)) {
                    return Err("Fix deform is changing yz too much with xy".into());
                }
            }
        }
        // the box's rate where it is constant over the run; the other styles set theirs every
        // step (0 until then), as LAMMPS' init
        let mut rate = BoxRate::default();
        let per_time = |stop: f64, start: f64| if delt != 0.0 { (stop - start) / delt } else { 0.0 };
        for (i, s) in self.set.iter().enumerate() {
            if matches!(s.style, Style::Final(..) | Style::Delta(..) | Style::Scale(_) | Style::Vel(_) | Style::Erate(_)) {
                let (dlo, dhi) = (per_time(s.lo_stop, s.lo_start), per_time(s.hi_stop, s.hi_start));
                rate.h_rate[i] = dhi - dlo;
                rate.h_ratelo[i] = dlo;
            }
        }
        for (k, t) in self.tilt.iter().enumerate() {
            if matches!(t.style, Style::Final(..) | Style::Delta(..) | Style::Vel(_) | Style::Erate(_)) {
                rate.h_rate[5 - k] = per_time(t.stop, t.start);
            }
        }
        self.rate = rate;
        Ok(())
    }
    fn box_rate(&self) -> Option<BoxRate> {
        Some(BoxRate { vremap: (self.remap == Remap::V).then_some(self.groupbit), ..self.rate })
    }
    fn deform_remap(&self) -> Option<Remap> {
        Some(self.remap)
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        self.update_box(state, ctx)
    }
    fn next_reneighbor(&self) -> Option<i64> {
        self.pending_flip.map(|p| p.2)
    }
    /// LAMMPS' pre_exchange: the flip decided at the last step's end, with the image flags
    /// carried over so that unwrapped positions stay, and every atom remapped into the box.
    fn pre_exchange(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let Some((tilts, [m, n, p], at)) = self.pending_flip else { return Ok(()) };
        if state.step != at {
            return Ok(());
        }
        self.pending_flip = None;
        for k in 0..3 {
            self.tilt[k].target = tilts[k];
        }
        super::box_stress::flip_box(state, tilts, [m, n, p]).map_err(|e| RunError::new(state.step, format!("fix deform: {e}")))
    }
}
