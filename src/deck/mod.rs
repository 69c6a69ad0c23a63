//! Running an input deck: the interpreter (flow control, variables) drives the simulation.

pub mod check;
pub mod commands;
pub mod create_atoms;
pub mod data;
pub mod dump_reader;
pub mod molecule;
pub mod read_dump;
pub mod restart;
pub mod velocity;
pub mod velocity_create;

use crate::sim::Simulation;
use dmhs_parser::interp::{Exit, Interpreter};
use dmhs_parser::Diagnostic;
use std::path::{Path, PathBuf};

/// How to run a deck.
#[derive(Clone, Debug, Default)]
pub struct DeckOptions {
    /// `-var NAME VALUE...` definitions (index-style variables).
    pub vars: Vec<(String, Vec<String>)>,
    /// Write to the screen.
    pub screen: bool,
    /// Log file (None: no log).
    pub log: Option<PathBuf>,
    /// Resolve relative paths in the deck against this directory (None: working directory).
    pub base_dir: Option<PathBuf>,
    /// Parse and build without running (`dmhs check`): `run` commands are skipped and
    /// errors are collected rather than stopping at the first.
    pub check_only: bool,
    /// Capture the per-atom forces after the setup of the first run.
    pub capture: bool,
    /// Keep screen text in `Simulation::out.captured`.
    pub capture_text: bool,
    /// `-echo screen|log|both|none`.
    pub echo: Option<(bool, bool)>,
    /// Keep every executed command in `Simulation::command_log`.
    pub record_commands: bool,
}

/// Why a deck did not complete.
#[derive(Debug)]
pub struct DeckFailure {
    pub diagnostics: Vec<Diagnostic>,
    /// The diagnostics rendered with source lines.
    pub rendered: String,
    /// A run failed (as opposed to an error in the deck itself).
    pub runtime: bool,
}

/// The result of a deck: the simulation as the deck left it, the `quit` status, and the
/// errors recorded in check mode.
pub struct DeckRun {
    pub sim: Simulation,
    pub interp: Interpreter,
    pub quit: Option<i32>,
    pub check_errors: Vec<Diagnostic>,
    /// Check mode: errors that only follow from a refused definition, with where it was.
    pub follow_ons: Vec<(Diagnostic, dmhs_parser::Span)>,
}

/// A simulation and an interpreter set up as `opts` says, before any command: the pair that
/// `run_text` drives, and that a library user (the Python module) feeds commands to with
/// `interp.run_source`/`execute_line`.
pub fn prepare(opts: &DeckOptions) -> Result<(Simulation, Interpreter), String> {
    let mut sim = Simulation::new();
    sim.out.screen = opts.screen;
    if opts.capture_text {
        sim.out.captured = Some(String::new());
    }
    if let Some(log) = &opts.log {
        sim.out.set_log(Some(log), false).map_err(|e| format!("cannot open log file {}: {e}", log.display()))?;
    }
    sim.base_dir = opts.base_dir.clone();
    sim.want_capture = opts.capture;
    sim.state.check_only = opts.check_only;
    if opts.record_commands {
        sim.command_log = Some(Vec::new());
    }
    for (name, values) in &opts.vars {
        sim.variables.define_index(name, values.clone());
    }
    let mut interp = Interpreter::new();
    interp.set_base_dir(opts.base_dir.clone());
    interp.set_keep_going(opts.check_only);
    interp.set_writes_files(!opts.check_only);
    if let Some((s, l)) = opts.echo {
        interp.set_echo(s, l);
    }
    Ok((sim, interp))
}

/// Run a deck given as text (`name` is shown in error locations).
pub fn run_text(name: &str, text: &str, opts: &DeckOptions) -> Result<DeckRun, DeckFailure> {
    run_text_on(name, text, opts, None)
}

/// [`run_text`] as one rank of the ranks `comm` connects (None: alone).
pub fn run_text_on(name: &str, text: &str, opts: &DeckOptions, comm: Option<std::sync::Arc<dyn crate::engine::comm::Comm>>) -> Result<DeckRun, DeckFailure> {
    use crate::engine::par::team;
    if !team::installed() {
        // a thread of a rayon pool runs the deck with as many threads as the pool has (`dmhs
        // -threads N`, the tests' pools); any other thread alone
        let threads = if rayon::current_thread_index().is_some() { rayon::current_num_threads() } else { 1 };
        return team::with_threads(threads, || run_text_on(name, text, opts, comm));
    }
    // the log and the screen are rank 0's
    let quiet = DeckOptions { log: None, screen: false, ..opts.clone() };
    let opts = if comm.as_ref().is_some_and(|c| c.rank() > 0) { &quiet } else { opts };
    let (mut sim, mut interp) = prepare(opts).map_err(|e| DeckFailure { rendered: format!("error: {e}\n"), diagnostics: vec![Diagnostic::error(e)], runtime: true })?;
    if let Some(c) = comm {
        sim.set_comm(c);
    }
    sim.out.print(&format!("dmhs {} (LAMMPS-compatible input)", env!("CARGO_PKG_VERSION")));
    let result = interp.run_source(name, text, &mut sim);
    finish(sim, interp, result)
}

/// Run a deck file.
pub fn run_file(path: &Path, opts: &DeckOptions) -> Result<DeckRun, DeckFailure> {
    run_file_on(path, opts, None)
}

/// [`run_file`] as one rank of the ranks `comm` connects (None: alone).
pub fn run_file_on(path: &Path, opts: &DeckOptions, comm: Option<std::sync::Arc<dyn crate::engine::comm::Comm>>) -> Result<DeckRun, DeckFailure> {
    let text = std::fs::read(path).map_err(|e| {
        let msg = format!("cannot read input script {}: {e}", path.display());
        DeckFailure { rendered: format!("error: {msg}\n"), diagnostics: vec![Diagnostic::error(msg)], runtime: false }
    })?;
    run_text_on(&path.to_string_lossy(), &String::from_utf8_lossy(&text), opts, comm)
}

fn finish(
    mut sim: Simulation,
    interp: Interpreter,
    result: Result<dmhs_parser::interp::Outcome, Vec<Diagnostic>>,
) -> Result<DeckRun, DeckFailure> {
    sim.out.flush();
    match result {
        Ok(outcome) => {
            let quit = match outcome.exit {
                Exit::Quit(c) => Some(c),
                Exit::EndOfInput => None,
            };
            Ok(DeckRun { sim, interp, quit, check_errors: outcome.errors, follow_ons: outcome.follow_ons })
        }
        Err(diags) => {
            let rendered: String = diags.iter().map(|d| d.render(interp.sources())).collect::<Vec<_>>().join("\n");
            // the log ends with the error the screen shows
            sim.out.log_only(&rendered);
            sim.out.flush();
            Err(DeckFailure { diagnostics: diags, rendered, runtime: sim.runtime_failed })
        }
    }
}

/// `orthogonal box = (xlo ylo zlo) to (xhi yhi zhi)`, or `triclinic box = ... with tilt (xy xz
/// yz)`, as LAMMPS prints a box (8 significant digits).
pub(crate) fn box_text(d: &crate::engine::domain::Domain) -> String {
    let g8 = crate::output::format::g8;
    let corners = format!("({} {} {}) to ({} {} {})", g8(d.lo[0]), g8(d.lo[1]), g8(d.lo[2]), g8(d.hi[0]), g8(d.hi[1]), g8(d.hi[2]));
    match d.tilt {
        None => format!("orthogonal box = {corners}"),
        Some([xy, xz, yz]) => format!("triclinic box = {corners} with tilt ({} {} {})", g8(xy), g8(xz), g8(yz)),
    }
}

/// LAMMPS' Domain::set_initial_box checks of a triclinic box: no z tilts in 2d (an error),
/// and a warning when a periodic dimension is skewed by more than half a box length; and
/// shrink-wrapped faces, which dmhs does not support on a triclinic box yet.
pub(crate) fn tilt_check(d: &crate::engine::domain::Domain) -> Result<Option<String>, String> {
    let Some([xy, xz, yz]) = d.tilt else { return Ok(None) };
    if d.dimension == 2 && (xz != 0.0 || yz != 0.0) {
        return Err("Cannot skew triclinic box in z for 2d simulation".into());
    }
    let p = d.prd();
    if ((xy / p[1]).abs() > 0.5 && d.periodic(1)) || ((xz.abs() + yz.abs()) / p[2] > 0.5 && d.periodic(2)) {
        return Ok(Some("WARNING: Triclinic box skew is large. LAMMPS will run inefficiently.".into()));
    }
    Ok(None)
}
