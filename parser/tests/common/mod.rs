//! A test host: records the commands it is given and what it would show on the screen.

#![allow(dead_code)]

use dmhs_parser::commands::is_lammps_command;
use dmhs_parser::interp::{Interpreter, Outcome};
use dmhs_parser::variables::Variables;
use dmhs_parser::{Command, DResult, Diagnostic, EvalContext, Host, SourceMap};

#[derive(Default)]
pub struct TestHost {
    pub vars: Variables,
    pub executed: Vec<Command>,
    /// What LAMMPS would write to the screen: print output and (with echo screen) echoed lines.
    pub screen: String,
    /// LAMMPS commands this host pretends not to implement.
    pub unsupported: Vec<&'static str>,
    /// Executing a command of this name fails.
    pub fail_on: Option<&'static str>,
}

impl EvalContext for TestHost {
    fn variables(&mut self) -> &mut Variables {
        &mut self.vars
    }
}

impl Host for TestHost {
    fn execute(&mut self, cmd: &Command, _sources: &mut SourceMap) -> DResult<()> {
        if self.fail_on == Some(cmd.name()) {
            return Err(Diagnostic::at(cmd.name.span, format!("`{}` failed in the test host", cmd.name()), "here"));
        }
        self.executed.push(cmd.clone());
        Ok(())
    }
    fn print(&mut self, text: &str) {
        self.screen.push_str(text);
    }
    fn echo(&mut self, text: &str, screen: bool, _log: bool) {
        if screen {
            self.screen.push_str(text);
        }
    }
    fn supports_command(&self, name: &str) -> bool {
        (is_lammps_command(name) && !self.unsupported.contains(&name)) || name.starts_with("dmhs/")
    }
}

impl TestHost {
    pub fn new() -> TestHost {
        TestHost::default()
    }
    /// The executed commands, each as its words joined by one space.
    pub fn command_lines(&self) -> Vec<String> {
        self.executed
            .iter()
            .map(|c| std::iter::once(c.name()).chain(c.arg_strs()).collect::<Vec<_>>().join(" "))
            .collect()
    }
}

/// Run `text` as a script named `name`; errors come back rendered.
pub fn run(name: &str, text: &str, host: &mut TestHost) -> Result<Outcome, String> {
    let mut interp = Interpreter::new();
    interp.run_source(name, text, host).map_err(|ds| render(&interp, &ds))
}

pub fn render(interp: &Interpreter, ds: &[Diagnostic]) -> String {
    ds.iter().map(|d| d.render(interp.sources())).collect::<Vec<_>>().join("\n")
}
