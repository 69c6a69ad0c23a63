//! read_dump and rerun.

use super::need_box;
use crate::deck::read_dump::{self, DumpSource, KEYWORDS};
use crate::sim::rerun::RerunOptions;
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap};

/// `read_dump file Nstep field ... keyword value ...`: the atoms of one snapshot.
pub fn read_dump(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let syntax = format!("read_dump file Nstep field1 field2 ... {KEYWORDS}");
    let mut a = Args::new(cmd, &syntax);
    let fw = a.word("dump file name")?;
    let nstep = a.i64("Nstep (the snapshot's step)")?;
    let spec = read_dump::parse_spec(sim, &mut a, vec![sim.path(&fw.text)])?;
    if sim.state.check_only {
        return Ok(());
    }
    let file_err = |e: String| Diagnostic::at(fw.span, e, "this dump file");
    let timestep = spec.timestep;
    let mut src = DumpSource::new(spec);
    sim.out.print("Scanning dump file ...");
    if src.seek(nstep, true).map_err(file_err)?.is_none() {
        return Err(Diagnostic::at(cmd.args[1].span, format!("Dump file does not contain requested snapshot: no step {nstep} in `{}`", fw.text), "this step"));
    }
    let snap = src.snapshot(true).map_err(file_err)?;
    if timestep {
        sim.reset_timestep(nstep, false).map_err(|e| Diagnostic::at(cmd.span, e, "read_dump resets the step").with_help("timestep no keeps the step"))?;
    }
    sim.out.print("Reading snapshot from dump file ...");
    let before = sim.state.atoms.nlocal;
    let counts = src.apply(sim, &snap).map_err(file_err)?;
    read_dump::report(sim, before, &counts);
    Ok(())
}

pub const RERUN_SYNTAX: &str = "rerun file1 file2 ... [first N] [last N] [every N] [skip N] [start N] [stop N] [post yes|no] dump field1 field2 ... keyword value ...";

/// `rerun file ... keyword ... dump field ...`: energies, forces and output of each snapshot.
pub fn rerun(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let mut a = Args::new(cmd, RERUN_SYNTAX);
    const KEYS: [&str; 8] = ["first", "last", "every", "skip", "start", "stop", "post", "dump"];
    let mut files = vec![];
    while let Some(w) = a.peek().filter(|w| !KEYS.contains(&w.text.as_str())) {
        files.push(sim.path(&w.text));
        a.skip(1);
    }
    if files.is_empty() {
        return Err(a.missing("dump file name"));
    }
    let mut o = RerunOptions::default();
    loop {
        let Some(w) = a.peek() else {
            return Err(a.error_command("rerun needs the keyword dump and the fields to read, last", "no dump keyword"));
        };
        a.skip(1);
        match w.text.as_str() {
            "first" => o.first = a.i64_in("first", 0, i64::MAX)?,
            "last" => o.last = a.i64_in("last", 0, i64::MAX)?,
            "every" => o.every = a.i64_in("every", 0, i32::MAX as i64)?,
            "skip" => o.skip = a.i64_in("skip", 1, i32::MAX as i64)?,
            "start" => o.start = Some(a.i64_in("start", 0, i64::MAX)?),
            "stop" => o.stop = Some(a.i64_in("stop", 0, i64::MAX)?),
            "post" => o.post = a.yes_no("post")?,
            "dump" => break,
            _ => return Err(a.unknown_keyword(w, &KEYS)),
        }
    }
    if o.first > o.last {
        return Err(a.error_command(format!("rerun first {} is after last {}", o.first, o.last), "first > last"));
    }
    if let (Some(start), Some(stop)) = (o.start, o.stop) {
        if start > stop {
            return Err(a.error_command(format!("rerun start {start} is after stop {stop}"), "start > stop"));
        }
    }
    let spec = read_dump::parse_spec(sim, &mut a, files)?;
    if sim.state.check_only {
        return Ok(());
    }
    let mut src = DumpSource::new(spec);
    sim.rerun(&mut src, &o).map_err(|e| super::run_cmds::run_failure(sim, &e, cmd))
}
