//! minimize, min_style and min_modify.

use super::need_box;
use crate::sim::minimize::{Integrator, LineSearch, MinSettings, MinStyle, MinimizeOptions, Norm};
use crate::sim::Simulation;
use dmhs_parser::commands::{unknown_style, StyleKind};
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap};

pub const MINIMIZE_SYNTAX: &str = "minimize etol ftol maxiter maxeval";
pub const MIN_MODIFY_SYNTAX: &str = "min_modify keyword value ... (dmax, line backtrack|quadratic, norm two|max|inf, delaystep, dtgrow, dtshrink, alpha0, alphashrink, tmax, tmin, integrator eulerimplicit|verlet|leapfrog|eulerexplicit, halfstepback yes|no, initialdelay yes|no, vdfmax, abcfire no)";

pub fn parse_minimize(cmd: &Command) -> DResult<MinimizeOptions> {
    let mut a = Args::new(cmd, MINIMIZE_SYNTAX);
    let etol = a.non_negative_f64("etol (energy tolerance)")?;
    let ftol = a.non_negative_f64("ftol (force tolerance)")?;
    let maxiter = a.i64_in("maxiter (most iterations)", 0, i32::MAX as i64)?;
    let maxeval = a.i64_in("maxeval (most force evaluations)", 0, i32::MAX as i64)?;
    a.finish()?;
    Ok(MinimizeOptions { etol, ftol, maxiter, maxeval })
}

pub fn minimize(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let opts = parse_minimize(cmd)?;
    if sim.state.check_only {
        sim.init_run().map_err(|e| Diagnostic::at(cmd.span, e.message, "this minimize"))?;
        sim.out.print(&format!("check: minimize {} iterations from step {} (not run)", opts.maxiter, sim.state.step));
        return Ok(());
    }
    sim.minimize(&opts).map_err(|e| super::run_cmds::run_failure(sim, &e, cmd))
}

/// `min_style cg|sd|fire`: a new minimizer, so min_modify settings return to their defaults
/// (as in LAMMPS).
pub fn min_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "min_style cg|sd|fire");
    let w = a.word("minimizer style")?;
    let style = match w.text.as_str() {
        "cg" => MinStyle::Cg,
        "sd" => MinStyle::Sd,
        "fire" => MinStyle::Fire,
        _ => return Err(unknown_style(StyleKind::Minimize, w, &["cg", "sd", "fire"])),
    };
    a.finish()?;
    sim.min = MinSettings { style, ..MinSettings::default() };
    Ok(())
}

pub fn min_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, MIN_MODIFY_SYNTAX);
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    let mut s = sim.min.clone();
    const KEYWORDS: &[&str] = &["dmax", "line", "norm", "delaystep", "dtgrow", "dtshrink", "alpha0", "alphashrink", "tmax", "tmin", "integrator", "halfstepback", "initialdelay", "vdfmax", "abcfire"];
    while let Some(kw) = a.peek() {
        a.skip(1);
        match kw.text.as_str() {
            "dmax" => s.dmax = a.positive_f64("dmax")?,
            "line" => {
                let w = a.word("line search style")?;
                s.line = match w.text.as_str() {
                    "backtrack" => LineSearch::Backtrack,
                    "quadratic" => LineSearch::Quadratic,
                    "forcezero" | "spin_cubic" | "spin_none" => {
                        return Err(a.error_at(w, format!("min_modify line {} is not supported: dmhs has backtrack and quadratic", w.text), "not supported"))
                    }
                    _ => return Err(a.error_at(w, format!("unknown line search style `{}`", w.text), "expected backtrack or quadratic")),
                }
            }
            "norm" => s.norm = [Norm::Two, Norm::Max, Norm::Inf][a.choice("norm", &["two", "max", "inf"])?],
            "delaystep" => s.delaystep = a.i64_in("delaystep", 0, i32::MAX as i64)?,
            "dtgrow" => s.dtgrow = a.f64("dtgrow")?,
            "dtshrink" => s.dtshrink = a.f64("dtshrink")?,
            "alpha0" => s.alpha0 = a.f64("alpha0")?,
            "alphashrink" => s.alphashrink = a.f64("alphashrink")?,
            "tmax" => s.tmax = a.f64("tmax")?,
            "tmin" => s.tmin = a.f64("tmin")?,
            "integrator" => {
                s.integrator = [Integrator::EulerImplicit, Integrator::Verlet, Integrator::Leapfrog, Integrator::EulerExplicit][a.choice("integrator", &["eulerimplicit", "verlet", "leapfrog", "eulerexplicit"])?]
            }
            "halfstepback" => s.halfstepback = a.yes_no("halfstepback")?,
            "initialdelay" => s.initialdelay = a.yes_no("initialdelay")?,
            "vdfmax" => s.vdfmax = a.i64("vdfmax")?,
            "abcfire" => {
                if a.yes_no("abcfire")? {
                    let w = a.last().expect("the value just read");
                    return Err(a.error_at(w, "min_modify abcfire yes is not supported (dmhs has FIRE 2.0 without the ABC correction)", "not supported"));
                }
            }
            "alpha_damp" | "discrete_factor" | "fire" => {
                return Err(a.error_at(kw, format!("min_modify {} (a spin minimizer's keyword) is not supported", kw.text), "not supported"));
            }
            _ => return Err(a.unknown_keyword(kw, KEYWORDS)),
        }
    }
    sim.min = s;
    Ok(())
}
