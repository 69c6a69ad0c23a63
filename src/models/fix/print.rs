//! `fix ID group print N|v_name string [file F | append F] [screen yes|no] [title T]`: every N
//! steps (or on the steps an equal-style variable names), the string with its `$` references
//! expanded then, to the screen and log and/or a file, as LAMMPS' fix print.

use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, DResult, Span};
use std::io::Write;

pub const SYNTAX: &str = "fix ID group print N|v_name string [file F | append F] [screen yes|no] [title T]";

pub struct FixPrint {
    id: String,
    groupbit: u32,
    /// Every N steps, or the steps an equal-style variable returns.
    every: Every,
    text: String,
    /// Where the string stands in the deck (errors of its substitutions point there).
    span: Span,
    screen: bool,
    file: Option<std::fs::File>,
    next_print: i64,
}

enum Every {
    N(i64),
    Variable(String),
}

impl FixPrint {
    pub fn from_lammps(d: FixDef, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(d.args, d.cmd.span, SYNTAX);
        let every = match a.peek().and_then(|w| w.text.strip_prefix("v_")) {
            Some(name) => {
                a.skip(1);
                Every::Variable(name.to_string())
            }
            None => Every::N(a.i64_in("N", 1, i64::MAX)?),
        };
        let w = a.word("string")?;
        let (text, span) = (w.text.clone(), w.span);
        let (mut screen, mut file, mut title) = (true, None, None);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "file" | "append" => file = Some((w.text == "append", a.word("file name")?)),
                "screen" => screen = a.yes_no("screen")?,
                "title" => title = Some(a.str("title")?.to_string()),
                _ => return Err(a.unknown_keyword(w, &["file", "append", "screen", "title"])),
            }
        }
        // on ranks only rank 0 opens it (another would truncate or append to it again)
        let file = match file.filter(|_| state.writes_files()) {
            None => None,
            Some((append, w)) => {
                let path = d.path(&w.text);
                let opened = std::fs::OpenOptions::new().write(true).create(true).append(append).truncate(!append).open(&path);
                let mut f = opened.map_err(|e| a.error_at(w, format!("cannot open fix print file {}: {e}", path.display()), "cannot open"))?;
                let head = match title {
                    Some(t) => format!("{t}\n"),
                    None => format!("# Fix print output for fix {}\n", d.id),
                };
                f.write_all(head.as_bytes()).map_err(|e| a.error_at(w, format!("cannot write {}: {e}", path.display()), "cannot write"))?;
                Some(f)
            }
        };
        Ok(FixPrint { id: d.id, groupbit: d.groupbit, every, text, span, screen, file, next_print: -1 })
    }

    /// The next step from the variable, which must lie after `step`.
    fn from_variable(&self, state: &State, ctx: &mut FixCtx, name: &str) -> Result<i64, RunError> {
        let x = ctx.equal(state, self, name).map_err(|e| RunError::new(state.step, format!("fix print {}: variable `{name}`: {e}", self.id)))?;
        let next = x as i64;
        if next <= state.step {
            return Err(RunError::new(state.step, format!("fix print {}: the timestep variable `{name}` returned {next}, not after the current step", self.id)));
        }
        Ok(next)
    }

    fn print(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step != self.next_print {
            return Ok(());
        }
        let (text, span) = (&self.text, self.span);
        let line = ctx.eval(state, self, |_, ev| {
            let located = dmhs_parser::lexer::Located::from_source(span.file, text, span.lo as usize);
            dmhs_parser::lexer::substitute(&located, ev, None).map(|l| l.text().to_string()).map_err(|d| format!("fix print: {}", d.message))
        })?;
        self.next_print = match &self.every {
            Every::N(n) => (state.step / n) * n + n,
            Every::Variable(name) => {
                let name = name.clone();
                self.from_variable(state, ctx, &name)?
            }
        };
        if self.screen {
            state.messages.push(line.clone());
        }
        if let Some(f) = self.file.as_mut() {
            f.write_all(format!("{line}\n").as_bytes())
                .and_then(|_| f.flush())
                .map_err(|e| RunError::new(state.step, format!("fix print {}: error writing the file: {e}", self.id)))?;
        }
        Ok(())
    }
}

impl Fix for FixPrint {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "print"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn setup_pre_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        // LAMMPS' init: the first step to print in this run
        self.next_print = match &self.every {
            Every::N(n) if state.step % n != 0 => (state.step / n) * n + n,
            Every::N(_) => state.step,
            Every::Variable(name) => {
                let name = name.clone();
                self.from_variable(state, ctx, &name)?
            }
        };
        Ok(())
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.print(state, ctx)
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.print(state, ctx)
    }
    fn wants_energy(&self, step: i64) -> bool {
        step == self.next_print
    }
}
