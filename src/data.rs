//! read_data and write_data (being wired to the data-file format).
use crate::sim::Simulation;
use dmhs_parser::{Command, DResult, Diagnostic, SourceMap};

pub fn read_data(_sim: &mut Simulation, cmd: &Command, _sources: &mut SourceMap) -> DResult<()> {
    Err(Diagnostic::at(cmd.name.span, "read_data is not wired yet", "todo"))
}
pub fn write_data(_sim: &Simulation, _cmd: &Command) -> Result<(), String> {
    Err("write_data is not wired yet".into())
}
