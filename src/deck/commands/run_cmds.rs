//! run and reset_timestep.

use super::need_box;
use crate::sim::run::RunOptions;
use crate::sim::{RunError, SetupError, Simulation};
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap};

pub const RUN_SYNTAX: &str = "run N [upto] [start N1] [stop N2] [pre yes|no] [post yes|no]";

pub fn parse_run(cmd: &Command) -> DResult<RunOptions> {
    let mut a = Args::new(cmd, RUN_SYNTAX);
    let w = a.word("N")?;
    let n = dmhs_parser::args::word_i64(w, "N (number of steps)").map_err(|d| d.with_help(format!("syntax: {RUN_SYNTAX}")))?;
    if n < 0 {
        return Err(a.error_at(w, "run N must be >= 0", "negative"));
    }
    let mut o = RunOptions::steps(n);
    while let Some(kw) = a.peek() {
        a.skip(1);
        match kw.text.as_str() {
            "upto" => o.upto = true,
            "start" => o.start = Some(a.i64("start step")?),
            "stop" => o.stop = Some(a.i64("stop step")?),
            "pre" => o.pre = a.yes_no("pre")?,
            "post" => o.post = a.yes_no("post")?,
            _ => return Err(a.unknown_keyword(kw, &["upto", "start", "stop", "pre", "post"])),
        }
    }
    Ok(o)
}

pub fn run(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let opts = parse_run(cmd)?;
    if sim.state.check_only {
        return sim.check_run(&opts).map_err(|e| setup_error(&e, cmd));
    }
    sim.run(&opts).map_err(|e| run_failure(sim, &e, cmd))
}

/// How a run, rerun or minimize that failed is reported at its command `cmd`: refused before
/// the first step, a deck error (as `dmhs check` reports it); stopped later, a runtime failure.
pub(super) fn run_failure(sim: &mut Simulation, e: &RunError, cmd: &Command) -> Diagnostic {
    match &e.setup {
        Some(setup) => setup_error(setup, cmd),
        None => {
            sim.runtime_failed = true;
            let what = cmd.name();
            Diagnostic::at(cmd.span, format!("{what} stopped at step {}: {}", e.step, e.message), format!("this {what}")).with_note("results written before the failure (log, dumps) are kept")
        }
    }
}

/// A check before the run refused the deck: shown at the command that set up what is wrong
/// (when known) and at the run (or rerun, minimize).
fn setup_error(e: &SetupError, run: &Command) -> Diagnostic {
    let what = run.name();
    match e.at {
        Some(at) => Diagnostic::at(at, e.message.clone(), "defined here").with_label(run.span, format!("checked before this {what}")),
        None => Diagnostic::at(run.span, e.message.clone(), format!("this {what}")),
    }
}

pub fn reset_timestep(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "reset_timestep N [time t]");
    let n = a.i64_in("N", 0, i64::MAX)?;
    let mut time = None;
    while let Some(kw) = a.peek() {
        a.skip(1);
        match kw.text.as_str() {
            "time" => time = Some(a.f64("time")?),
            _ => return Err(a.unknown_keyword(kw, &["time"])),
        }
    }
    sim.reset_timestep(n, false).map_err(|e| Diagnostic::at(cmd.span, e, "reset here"))?;
    if let Some(t) = time {
        sim.state.atime = t;
    }
    Ok(())
}

/// `run_style verlet` (the default, LAMMPS' velocity-Verlet, the only integrator dmhs has);
/// any other style is a located error.
pub fn run_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let mut a = Args::new(cmd, "run_style verlet");
    let w = a.word("integrator style")?;
    if w.text != "verlet" {
        return Err(a
            .error_at(w, format!("run_style {} is not supported: dmhs has one integrator, velocity-Verlet (run_style verlet)", w.text), "not supported")
            .with_help("remove the run_style line or use run_style verlet"));
    }
    a.finish()
}
