//! The input-script interpreter: reads files as LAMMPS' `Input` class does and drives a
//! [`Host`] (the engine).
//!
//! It runs the commands that shape the flow of a script itself (`variable`, `next`, `jump`,
//! `label`, `include`, `if`, `print`, `echo`, `quit`, `partition`), refuses `shell` and
//! `python`, and hands every other command to [`Host::execute`].
//!
//! Before a file runs, a pre-pass reports every problem it can see without running anything:
//! unbalanced quotes, unknown command names (with a did-you-mean), LAMMPS commands the host
//! does not support. In keep-going mode (for a `check` command) an error is recorded, its
//! command skipped, and the script goes on.
//!
//! LAMMPS semantics kept here (src/input.cpp):
//! * `jump SELF label` rewinds the current file and skips every command but `label` until the
//!   label is found; no `$` substitution happens while searching. Commands that follow a jump
//!   inside the same `if` are skipped by the search too.
//! * A `next` that exhausts a variable makes the next `jump` a no-op (ends a loop).
//! * `if`, `print` and `include` substitute `$` again in their (usually quoted) arguments.
//! * Relative paths in `include` and `jump` are relative to the current directory.

use crate::ast::{Command, Word};
use crate::args::{is_lammps_integer, word_type_range};
use crate::commands::{is_lammps_command, lammps_commands, unknown_command};
use crate::context::{EvalContext, Host};
use crate::diag::Diagnostic;
use crate::follow_on::Refused;
use crate::lexer::{self, LexWord, Located, LogicalLine};
use crate::span::{FileId, SourceMap, Span};
use crate::suggest::did_you_mean_help;
use std::collections::HashSet;
use std::io::Write;

/// The commands the interpreter runs itself.
pub const FLOW_COMMANDS: [&str; 10] = ["variable", "next", "jump", "label", "include", "if", "print", "echo", "quit", "partition"];

/// LAMMPS commands refused for safety.
pub const REFUSED_COMMANDS: [&str; 2] = ["shell", "python"];

/// Most nested input files (LAMMPS' `LMP_MAXFILE`).
const MAX_NESTING: usize = 16;

/// In keep-going mode, stop after this many errors (a loop that fails every pass would
/// otherwise never end).
const MAX_RECORDED: usize = 100;

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    EndOfInput,
    /// `quit [status]`
    Quit(i32),
}

/// The result of running a script.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    pub exit: Exit,
    /// Errors recorded in keep-going mode (their commands were skipped).
    pub errors: Vec<Diagnostic>,
    /// Keep-going mode: errors that only follow from an earlier refused definition, each with
    /// where that definition was (not counted as errors; `dmhs check` shows them as notes).
    pub follow_ons: Vec<(Diagnostic, Span)>,
}

type Flow = Result<(), Vec<Diagnostic>>;

/// One open input file.
struct Level {
    lines: Vec<LogicalLine>,
    next: usize,
}

pub struct Interpreter {
    sources: SourceMap,
    stack: Vec<Level>,
    /// The label a `jump` searches for, and where that label was written.
    searching: Option<(String, Span)>,
    /// Set by a `next` that exhausted its variable: the next `jump` does nothing.
    jump_skip: bool,
    echo_screen: bool,
    echo_log: bool,
    keep_going: bool,
    /// `print ... file|append` opens its file (not under `dmhs check`).
    writes_files: bool,
    recorded: Vec<Diagnostic>,
    /// Keep-going mode: the refused definitions, and the errors that follow from them.
    refused: Refused,
    follow_ons: Vec<(Diagnostic, Span)>,
    /// Command names the pre-pass already reported (not reported again when reached).
    reported: HashSet<Span>,
    warned_non_ascii: bool,
    quit: Option<i32>,
    /// Directory that relative paths are resolved against (None: the working directory,
    /// as LAMMPS does). Lets a library user run decks from elsewhere without `chdir`.
    base_dir: Option<std::path::PathBuf>,
}

impl Default for Interpreter {
    fn default() -> Self {
        Interpreter::new()
    }
}

fn one(d: Diagnostic) -> Vec<Diagnostic> {
    vec![d]
}

fn words_of(w: &[LexWord]) -> Vec<Word> {
    w.iter().map(LexWord::to_word).collect()
}

/// `utils::logical`: yes/no, on/off, true/false, 1/0.
fn logical(w: &LexWord) -> Result<bool, Vec<Diagnostic>> {
    match w.as_str() {
        "yes" | "on" | "true" | "1" => Ok(true),
        "no" | "off" | "false" | "0" => Ok(false),
        s => Err(one(Diagnostic::at(w.span, format!("expected yes or no, found `{s}`"), "not a boolean")
            .with_help("use yes/no, on/off, true/false or 1/0"))),
    }
}

fn refused(w: &Word) -> Diagnostic {
    let help = if w.text == "shell" {
        "do file and directory work outside the input script"
    } else {
        "compute such values outside and pass them with -var NAME VALUE"
    };
    Diagnostic::at(w.span, format!("`{}` is not supported for safety: dmhs does not run programs from an input script", w.text), "not supported for safety")
        .with_help(help)
}

impl Interpreter {
    pub fn new() -> Interpreter {
        Interpreter {
            sources: SourceMap::new(),
            stack: vec![],
            searching: None,
            jump_skip: false,
            echo_screen: false,
            echo_log: true,
            keep_going: false,
            writes_files: true,
            recorded: vec![],
            refused: Refused::default(),
            follow_ons: vec![],
            reported: HashSet::new(),
            warned_non_ascii: false,
            quit: None,
            base_dir: None,
        }
    }

    /// Resolve relative `include`, `jump` and `print file` paths against `dir`.
    pub fn set_base_dir(&mut self, dir: Option<std::path::PathBuf>) {
        self.base_dir = dir;
    }

    /// A path as the script wrote it, resolved against the base directory.
    pub fn resolve(&self, path: &str) -> std::path::PathBuf {
        match &self.base_dir {
            Some(d) if std::path::Path::new(path).is_relative() => d.join(path),
            _ => std::path::PathBuf::from(path),
        }
    }

    /// Every file read so far (for rendering diagnostics).
    pub fn sources(&self) -> &SourceMap {
        &self.sources
    }
    pub fn sources_mut(&mut self) -> &mut SourceMap {
        &mut self.sources
    }

    /// Keep going after an error: record it, skip its command, continue (for `check`).
    pub fn set_keep_going(&mut self, on: bool) {
        self.keep_going = on;
    }

    /// Whether `print ... file|append` opens its file (`dmhs check` opens none).
    pub fn set_writes_files(&mut self, on: bool) {
        self.writes_files = on;
    }

    /// Where commands are echoed (`-echo` / the `echo` command); LAMMPS' default is the log only.
    pub fn set_echo(&mut self, screen: bool, log: bool) {
        self.echo_screen = screen;
        self.echo_log = log;
    }

    /// Run an input script from a file (a relative path is relative to the current directory).
    pub fn run_file(&mut self, path: &str, host: &mut dyn Host) -> Result<Outcome, Vec<Diagnostic>> {
        let text = match std::fs::read(self.resolve(path)) {
            Ok(b) => String::from_utf8_lossy(&b).into_owned(),
            Err(e) => return Err(one(Diagnostic::error(format!("cannot open input script `{path}`: {e}")))),
        };
        self.run_source(path, &text, host)
    }

    /// Run an input script given as text; `name` is how diagnostics call it.
    pub fn run_source(&mut self, name: &str, text: &str, host: &mut dyn Host) -> Result<Outcome, Vec<Diagnostic>> {
        let file = self.sources.add(name, text);
        self.begin();
        let lines = lexer::split_lines(file, text);
        self.precheck(&lines, host)?;
        self.stack.push(Level { lines, next: 0 });
        let r = self.file_loop(host);
        self.stack.pop();
        self.finish(r)
    }

    /// Only the pre-pass over a script given as text: every problem visible without running it.
    pub fn check_source(&mut self, name: &str, text: &str, host: &dyn Host) -> Vec<Diagnostic> {
        let file = self.sources.add(name, text);
        self.check_lines(&lexer::split_lines(file, text), host)
    }

    /// Run one command line (as LAMMPS' `lammps_command`), e.g. from the host.
    pub fn execute_line(&mut self, text: &str, host: &mut dyn Host) -> Result<Outcome, Vec<Diagnostic>> {
        let file = self.sources.add("<command>", text);
        self.begin();
        let r = self.one(&Located::from_source(file, text, 0), host);
        self.finish(r)
    }

    fn begin(&mut self) {
        self.quit = None;
        self.searching = None;
    }

    fn finish(&mut self, r: Flow) -> Result<Outcome, Vec<Diagnostic>> {
        r?;
        let exit = match self.quit.take() {
            Some(code) => Exit::Quit(code),
            None => Exit::EndOfInput,
        };
        Ok(Outcome { exit, errors: std::mem::take(&mut self.recorded), follow_ons: std::mem::take(&mut self.follow_ons) })
    }

    /// An error: recorded in keep-going mode, returned otherwise.
    fn fail(&mut self, ds: Vec<Diagnostic>) -> Flow {
        if !self.keep_going {
            return Err(ds);
        }
        self.recorded.extend(ds);
        if self.recorded.len() >= MAX_RECORDED {
            let mut all = std::mem::take(&mut self.recorded);
            all.push(Diagnostic::error(format!("too many errors ({MAX_RECORDED}); stopped checking")));
            return Err(all);
        }
        Ok(())
    }

    /// The pre-pass over a file about to run.
    fn precheck(&mut self, lines: &[LogicalLine], host: &dyn Host) -> Flow {
        let problems = self.check_lines(lines, host);
        if problems.is_empty() {
            return Ok(());
        }
        for d in &problems {
            if let Some(s) = d.primary_span() {
                self.reported.insert(s);
            }
        }
        self.fail(problems)
    }

    /// Every problem visible without running: unbalanced quotes, unknown command names,
    /// LAMMPS commands the host does not support. Names that contain `$` are not checked;
    /// commands inside `if` branches are checked for unknown names only (a branch may never run).
    pub fn check_lines(&self, lines: &[LogicalLine], host: &dyn Host) -> Vec<Diagnostic> {
        let mut out = vec![];
        for line in lines {
            let words = match Self::words_unsubstituted(&line.text) {
                Ok(w) => w,
                Err(d) => {
                    out.push(d);
                    continue;
                }
            };
            let Some(first) = words.first() else { continue };
            self.check_name(first, host, true, &mut out);
            if first.as_str() == "if" {
                for branch in if_branches(&words[1..]) {
                    match Self::words_unsubstituted(&branch.text) {
                        Ok(w) => {
                            if let Some(f) = w.first() {
                                self.check_name(f, host, false, &mut out);
                            }
                        }
                        Err(d) => out.push(d),
                    }
                }
            }
        }
        out
    }

    fn words_unsubstituted(text: &Located) -> Result<Vec<LexWord>, Diagnostic> {
        let stripped = lexer::strip_comment(text)?;
        lexer::split_words(&lexer::ascii_substitute(&stripped).0)
    }

    fn check_name(&self, w: &LexWord, host: &dyn Host, top_level: bool, out: &mut Vec<Diagnostic>) {
        let name = w.as_str();
        if REFUSED_COMMANDS.contains(&name) {
            out.push(refused(&w.to_word()));
            return;
        }
        if name.contains('$') || FLOW_COMMANDS.contains(&name) || host.supports_command(name) {
            return;
        }
        if top_level || !is_lammps_command(name) {
            out.push(unknown_command(&w.to_word(), &supported_names(host)));
        }
    }

    /// Read lines from the file on top of the stack until it ends (`Input::file`).
    fn file_loop(&mut self, host: &mut dyn Host) -> Flow {
        loop {
            if self.quit.is_some() {
                return Ok(());
            }
            let Some(level) = self.stack.last_mut() else { return Ok(()) };
            let Some(line) = level.lines.get(level.next) else {
                if let Some((label, span)) = self.searching.take() {
                    let d = Diagnostic::at(span, format!("label `{label}` not found"), "this jump searches for it")
                        .with_help(format!("the jump reads on from the start of the file, skipping commands, until `label {label}`"));
                    self.fail(one(d))?;
                }
                return Ok(());
            };
            let text = line.text.clone();
            level.next += 1;
            self.one(&text, host)?;
        }
    }

    /// Echo, parse and execute one command line (`Input::one`).
    fn one(&mut self, line: &Located, host: &mut dyn Host) -> Flow {
        let scanning = self.searching.is_some();
        let (es, el) = (self.echo_screen, self.echo_log);
        let echo = !scanning && (es || el);
        if echo {
            host.echo(&format!("{}\n", line.text()), es, el);
        }
        let parsed = if scanning {
            lexer::parse_line(line, None, None)
        } else {
            let mut progress: Vec<String> = vec![];
            let mut record = |s: &str| progress.push(format!("{s}\n"));
            let r = lexer::parse_line(line, Some(&mut *host as &mut dyn EvalContext), if echo { Some(&mut record) } else { None });
            for p in progress {
                host.echo(&p, es, el);
            }
            r
        };
        let (words, non_ascii) = match parsed {
            Ok(x) => x,
            Err(d) => {
                let raw: Vec<&str> = line.text().split_whitespace().collect();
                return self.fail_command(&raw, line, d);
            }
        };
        if non_ascii && !scanning && !self.warned_non_ascii {
            self.warned_non_ascii = true;
            let w = Diagnostic::warning("non-ASCII characters in the input")
                .with_label(line.full_span(), "first seen in this command")
                .with_note("Unicode spaces, quotes and minus signs are read as their ASCII equivalents, as LAMMPS does");
            host.warn(w, &self.sources);
        }
        let Some(first) = words.first() else { return Ok(()) };
        if scanning && first.as_str() != "label" {
            return Ok(());
        }
        match self.execute(&words, line, host) {
            Ok(()) => {
                if self.keep_going {
                    self.refused.defined(&words.iter().map(LexWord::as_str).collect::<Vec<_>>());
                }
                Ok(())
            }
            Err(ds) if ds.len() == 1 && self.keep_going => {
                let w: Vec<&str> = words.iter().map(LexWord::as_str).collect();
                self.fail_command(&w, line, ds.into_iter().next().unwrap())
            }
            Err(ds) => self.fail(ds),
        }
    }

    /// A command failed: in keep-going mode, what it would have defined is refused, and its
    /// error is a follow-on when it only follows from an earlier refused definition.
    fn fail_command(&mut self, words: &[&str], line: &Located, d: Diagnostic) -> Flow {
        if !self.keep_going {
            return Err(one(d));
        }
        let cause = self.refused.cause(words, line.text(), &d.message);
        self.refused.refuse(words, d.primary_span().unwrap_or(line.full_span()));
        match cause {
            Some(at) => {
                self.follow_ons.push((d, at));
                Ok(())
            }
            None => self.fail(one(d)),
        }
    }

    fn execute(&mut self, words: &[LexWord], line: &Located, host: &mut dyn Host) -> Flow {
        let cmd = &words[0];
        let args = &words[1..];
        match cmd.as_str() {
            "variable" => {
                // LAMMPS substitutes `$` references in the value of a string-style variable
                // when it is defined, even inside quotes
                let mut w = words_of(args);
                if args.len() >= 3 && args[1].as_str() == "string" && args[2].as_str().contains('$') {
                    let value = lexer::substitute(&args[2].text, host, None).map_err(one)?;
                    w[2].text = value.text().to_string();
                }
                if args.len() >= 2 && args[1].as_str() == "atomfile" {
                    let path = args.get(2).map(|f| self.resolve(f.as_str())).unwrap_or_default();
                    let ids = host.atom_ids();
                    return host.variables().define_atomfile(&w, &path, (&ids.0, ids.1)).map_err(one);
                }
                host.variables().command(&w).map_err(one)
            }
            "next" => {
                let w = words_of(args);
                if args.first().is_some_and(|a| host.variables().style(a.as_str()) == Some("atomfile")) {
                    let ids = host.atom_ids();
                    if host.variables().next_atomfile(&w, (&ids.0, ids.1)).map_err(one)? {
                        self.jump_skip = true;
                    }
                    return Ok(());
                }
                if host.variables().next(&w).map_err(one)? {
                    self.jump_skip = true;
                }
                Ok(())
            }
            "jump" => self.jump(cmd, args, host),
            "label" => self.label(cmd, args),
            "include" => self.include(cmd, args, host),
            "if" => self.if_command(cmd, args, host),
            "print" => self.print(cmd, args, host),
            "echo" => self.echo(cmd, args),
            "quit" => self.quit_command(cmd, args),
            "partition" => self.partition(cmd, args, line, host),
            "shell" | "python" => Err(one(refused(&cmd.to_word()))),
            "run" if args.iter().any(|w| w.as_str() == "every") => self.run_every(cmd, args, host),
            _ => self.host_command(words, host),
        }
    }

    /// `run N [keywords] every M c1 c2 ...` (or `NULL`), as LAMMPS' Run: the run in segments of M
    /// steps, each a run of its own (its ramps over the segment unless `start`/`stop` are
    /// given; a full setup for the first, and for all with `pre yes`; the full summary for the
    /// last, and for all with `post yes`, LAMMPS' defaults being yes), the commands executed
    /// after each segment. The segments stop early when a fix halt ended the runs.
    fn run_every(&mut self, cmd: &LexWord, args: &[LexWord], host: &mut dyn Host) -> Flow {
        let syntax = "syntax: run N [upto] [start N1] [stop N2] [pre yes|no] [post yes|no] every M c1 c2 ... (or NULL)";
        let k = args.iter().position(|w| w.as_str() == "every").expect("called with every");
        let every = &args[k];
        let Some(m) = args.get(k + 1) else {
            return Err(one(Diagnostic::at(every.span, "missing M after `every`", "here").with_help(syntax)));
        };
        let m_steps = match m.as_str().parse::<i64>() {
            Ok(v) if v > 0 => v,
            _ => return Err(one(Diagnostic::at(m.span, format!("run every M must be an integer > 0, found `{}`", m.as_str()), "expected M > 0").with_help(syntax))),
        };
        let commands = &args[k + 2..];
        if commands.is_empty() {
            return Err(one(Diagnostic::at(m.span, "missing commands after `every M` (NULL for none)", "here").with_help(syntax)));
        }
        let commands = if commands.len() == 1 && commands[0].as_str() == "NULL" { &[][..] } else { commands };
        let Some(n_word) = args.first().filter(|_| k > 0) else {
            return Err(one(Diagnostic::at(cmd.span, "missing N for `run`", "here").with_help(syntax)));
        };
        let Ok(n) = n_word.as_str().parse::<i64>() else {
            return Err(one(Diagnostic::at(n_word.span, format!("run N must be an integer, found `{}`", n_word.as_str()), "expected N").with_help(syntax)));
        };
        // the keywords before `every`: upto, pre and post are decided per segment here, the
        // others (start, stop) pass to each segment's run as written
        let (mut upto, mut pre, mut post) = (false, true, true);
        let mut passed: Vec<Word> = vec![];
        let mut i = 1;
        while i < k {
            let w = &args[i];
            match w.as_str() {
                "upto" => upto = true,
                "pre" | "post" if i + 1 < k => {
                    let yes = logical(&args[i + 1])?;
                    if w.as_str() == "pre" { pre = yes } else { post = yes }
                    i += 1;
                }
                _ => passed.push(w.to_word()),
            }
            i += 1;
        }
        let mut nleft = n;
        if upto {
            let now = match host.thermo_keyword("step") {
                Some(Ok(s)) => s as i64,
                _ => return Err(one(Diagnostic::at(n_word.span, "run upto: the current step is not known", "here"))),
            };
            nleft = n - now;
            if nleft < 0 {
                return Err(one(Diagnostic::at(n_word.span, format!("Invalid run command upto value: {n}. Must be >= {now}"), "before the current step")));
            }
        }
        let word = |text: String, span: Span| Word { text, span, quoted: false };
        let mut iter = 0;
        while nleft > 0 || iter == 0 {
            if host.run_halted() {
                break;
            }
            let nsteps = nleft.clamp(0, m_steps);
            let mut run_args = vec![word(nsteps.to_string(), n_word.span)];
            run_args.extend(passed.iter().cloned());
            let yes_no = |b: bool| if b { "yes" } else { "no" }.to_string();
            run_args.push(word("pre".into(), every.span));
            run_args.push(word(yes_no(pre || iter == 0), every.span));
            run_args.push(word("post".into(), every.span));
            run_args.push(word(yes_no(post || nleft <= nsteps), every.span));
            let name = cmd.to_word();
            let command = Command { span: name.span.to(m.span), name, args: run_args };
            host.execute(&command, &mut self.sources).map_err(one)?;
            for c in commands {
                self.one(&c.text, host)?;
                if self.quit.is_some() {
                    return Ok(());
                }
            }
            nleft -= nsteps;
            iter += 1;
        }
        Ok(())
    }

    fn host_command(&mut self, words: &[LexWord], host: &mut dyn Host) -> Flow {
        let name = words[0].to_word();
        if !host.supports_command(&name.text) {
            if self.reported.contains(&name.span) {
                return Ok(()); // the pre-pass reported it (keep-going mode)
            }
            return Err(one(unknown_command(&name, &supported_names(host))));
        }
        let last = words.last().map(|w| w.span).unwrap_or(name.span);
        let command = Command { span: name.span.to(last), name, args: words_of(&words[1..]) };
        host.execute(&command, &mut self.sources).map_err(one)
    }

    /// Load a file for `include` or `jump`; `at` is the word that named it.
    fn load(&mut self, path: &str, at: Span) -> Result<Vec<LogicalLine>, Vec<Diagnostic>> {
        let text = match std::fs::read(self.resolve(path)) {
            Ok(b) => String::from_utf8_lossy(&b).into_owned(),
            Err(e) => {
                return Err(one(Diagnostic::at(at, format!("cannot open input script `{path}`: {e}"), "this file")
                    .with_help("a relative path is relative to the directory dmhs runs in, as in LAMMPS")));
            }
        };
        let file = self.file_id_for(path, text);
        Ok(lexer::split_lines(file, &self.sources.file(file).text))
    }

    /// Reuse the source entry of a file read before with the same text (loops that jump to
    /// a file would otherwise add a copy per pass).
    fn file_id_for(&mut self, path: &str, text: String) -> FileId {
        let mut k = 0;
        while let Some(f) = self.sources.get(FileId(k)) {
            if f.name == path && f.text == text {
                return FileId(k);
            }
            k += 1;
        }
        self.sources.add(path, text)
    }

    fn jump(&mut self, cmd: &LexWord, args: &[LexWord], host: &mut dyn Host) -> Flow {
        if args.is_empty() || args.len() > 2 {
            return Err(one(Diagnostic::at(cmd.span, format!("jump takes 1 or 2 arguments, found {}", args.len()), "here")
                .with_help("syntax: jump file|SELF [label]")));
        }
        if self.jump_skip {
            self.jump_skip = false; // a `next` exhausted its variable: leave the loop
            return Ok(());
        }
        let target = &args[0];
        if self.stack.is_empty() {
            return Err(one(Diagnostic::at(cmd.span, "`jump` needs an input file to jump in", "not reading a file")));
        }
        if target.as_str() != "SELF" {
            let lines = self.load(target.as_str(), target.span)?;
            self.precheck(&lines, host)?;
            *self.stack.last_mut().unwrap() = Level { lines, next: 0 };
        } else {
            self.stack.last_mut().unwrap().next = 0;
        }
        if let Some(label) = args.get(1) {
            self.searching = Some((label.as_str().to_string(), label.span));
        }
        Ok(())
    }

    fn label(&mut self, cmd: &LexWord, args: &[LexWord]) -> Flow {
        if args.len() != 1 {
            return Err(one(Diagnostic::at(cmd.span, format!("label takes 1 argument, found {}", args.len()), "here")
                .with_help("syntax: label ID")));
        }
        if self.searching.as_ref().is_some_and(|(l, _)| l == args[0].as_str()) {
            self.searching = None;
        }
        Ok(())
    }

    fn include(&mut self, cmd: &LexWord, args: &[LexWord], host: &mut dyn Host) -> Flow {
        if args.len() != 1 {
            return Err(one(Diagnostic::at(cmd.span, format!("include takes 1 argument, found {}", args.len()), "here")
                .with_help("syntax: include file")));
        }
        if self.stack.len() >= MAX_NESTING {
            return Err(one(Diagnostic::at(cmd.span, format!("too many nested input files (at most {MAX_NESTING})"), "here")));
        }
        let path = lexer::substitute(&args[0].text, host, None).map_err(one)?;
        let lines = self.load(path.text(), args[0].span)?;
        self.precheck(&lines, host)?;
        self.stack.push(Level { lines, next: 0 });
        let r = self.file_loop(host);
        self.stack.pop();
        r
    }

    fn if_command(&mut self, cmd: &LexWord, args: &[LexWord], host: &mut dyn Host) -> Flow {
        let syntax = "syntax: if \"condition\" then \"command\" ... [elif \"condition\" \"command\" ...] [else \"command\" ...]";
        if args.len() < 3 {
            return Err(one(Diagnostic::at(cmd.span, "missing arguments for `if`", "here").with_help(syntax)));
        }
        let mut test = self.boolean(&args[0], host)?;
        if args[1].as_str() != "then" {
            return Err(one(Diagnostic::at(args[1].span, format!("expected `then`, found `{}`", args[1].as_str()), "expected `then`")
                .with_help(syntax)));
        }
        let is_kw = |w: &LexWord| w.as_str() == "elif" || w.as_str() == "else";
        let n = args.len();
        let mut first = 2;
        let mut kw = &args[1];
        loop {
            let mut end = first;
            while end < n && !is_kw(&args[end]) {
                end += 1;
            }
            if test {
                return self.run_block(kw, &args[first..end], host);
            }
            if end == n {
                return Ok(());
            }
            kw = &args[end];
            if end + 2 > n {
                return Err(one(Diagnostic::at(kw.span, format!("missing arguments after `{}`", kw.as_str()), "here").with_help(syntax)));
            }
            if kw.as_str() == "elif" {
                test = self.boolean(&args[end + 1], host)?;
                first = end + 2;
            } else {
                test = true;
                first = end + 1;
            }
        }
    }

    /// Substitute and evaluate an `if`/`elif` condition.
    fn boolean(&mut self, cond: &LexWord, host: &mut dyn Host) -> Result<bool, Vec<Diagnostic>> {
        let text = lexer::substitute(&cond.text, host, None).map_err(one)?;
        crate::expr::evaluate_boolean(text.text(), host).map_err(|e| {
            let lo = e.offset.min(text.len());
            let hi = (lo + e.len.max(1)).min(text.len());
            one(Diagnostic::at(text.span(lo..hi), e.message, "in this condition"))
        })
    }

    /// Execute the commands of a taken `if` branch (each quoted argument is a full command).
    fn run_block(&mut self, kw: &LexWord, block: &[LexWord], host: &mut dyn Host) -> Flow {
        if block.is_empty() {
            return Err(one(Diagnostic::at(kw.span, format!("no command after `{}`", kw.as_str()), "expected a quoted command after this")));
        }
        if let Some(e) = block.iter().find(|c| c.text.is_empty()) {
            return Err(one(Diagnostic::at(e.span, "empty command in `if`", "nothing to execute")));
        }
        for c in block {
            self.one(&c.text, host)?;
            if self.quit.is_some() {
                break;
            }
        }
        Ok(())
    }

    fn print(&mut self, cmd: &LexWord, args: &[LexWord], host: &mut dyn Host) -> Flow {
        let syntax = "syntax: print string [file|append name] [screen yes|no] [universe yes|no]";
        let Some(first) = args.first() else {
            return Err(one(Diagnostic::at(cmd.span, "missing text for `print`", "here").with_help(syntax)));
        };
        let text = lexer::substitute(&first.text, host, None).map_err(one)?;
        let mut screen = true;
        let mut universe = false;
        let mut file: Option<(std::fs::File, Span)> = None;
        let mut i = 1;
        while i < args.len() {
            let kw = &args[i];
            let Some(value) = args.get(i + 1) else {
                return Err(one(Diagnostic::at(kw.span, format!("missing value after `{}`", kw.as_str()), "here").with_help(syntax)));
            };
            match kw.as_str() {
                "file" | "append" if !self.writes_files => {}
                "file" | "append" => {
                    let path = value.as_str();
                    let full = self.resolve(path);
                    let opened = if kw.as_str() == "file" {
                        std::fs::File::create(&full)
                    } else {
                        std::fs::OpenOptions::new().append(true).create(true).open(&full)
                    };
                    match opened {
                        Ok(f) => file = Some((f, value.span)),
                        Err(e) => return Err(one(Diagnostic::at(value.span, format!("cannot open print file `{path}`: {e}"), "this file"))),
                    }
                }
                "screen" => screen = logical(value)?,
                "universe" => universe = logical(value)?,
                other => {
                    let keys = ["file", "append", "screen", "universe"];
                    let mut d = Diagnostic::at(kw.span, format!("unknown print keyword `{other}`"), "expected file, append, screen or universe");
                    if let Some(h) = did_you_mean_help(other, keys) {
                        d = d.with_help(h);
                    }
                    return Err(one(d.with_help(syntax)));
                }
            }
            i += 2;
        }
        let out = format!("{}\n", text.text());
        if screen {
            host.print(&out);
        }
        if let Some((mut f, span)) = file {
            if let Err(e) = f.write_all(out.as_bytes()) {
                return Err(one(Diagnostic::at(span, format!("cannot write print file: {e}"), "this file")));
            }
        }
        if universe {
            host.print(&out); // one partition: the universe screen and log are the run's own
        }
        Ok(())
    }

    fn echo(&mut self, cmd: &LexWord, args: &[LexWord]) -> Flow {
        let choices = ["none", "screen", "log", "both"];
        let [w] = args else {
            return Err(one(Diagnostic::at(cmd.span, format!("echo takes 1 argument, found {}", args.len()), "here")
                .with_help("syntax: echo none|screen|log|both")));
        };
        (self.echo_screen, self.echo_log) = match w.as_str() {
            "none" => (false, false),
            "screen" => (true, false),
            "log" => (false, true),
            "both" => (true, true),
            other => {
                let mut d = Diagnostic::at(w.span, format!("unknown echo keyword `{other}`"), "expected none, screen, log or both");
                if let Some(h) = did_you_mean_help(other, choices) {
                    d = d.with_help(h);
                }
                return Err(one(d));
            }
        };
        Ok(())
    }

    fn quit_command(&mut self, cmd: &LexWord, args: &[LexWord]) -> Flow {
        let code = match args {
            [] => 0,
            [w] if is_lammps_integer(w.as_str()) => w.as_str().parse::<i32>().map_err(|_| {
                one(Diagnostic::at(w.span, format!("exit status `{}` is out of range", w.as_str()), "here"))
            })?,
            [w] => return Err(one(Diagnostic::at(w.span, format!("expected an integer exit status, found `{}`", w.as_str()), "not an integer"))),
            _ => return Err(one(Diagnostic::at(cmd.span, format!("quit takes 0 or 1 argument, found {}", args.len()), "here")
                .with_help("syntax: quit [status]"))),
        };
        self.quit = Some(code);
        Ok(())
    }

    /// `partition yes|no N command...` with the single partition dmhs runs as.
    fn partition(&mut self, cmd: &LexWord, args: &[LexWord], line: &Located, host: &mut dyn Host) -> Flow {
        if args.len() < 3 {
            return Err(one(Diagnostic::at(cmd.span, "missing arguments for `partition`", "here")
                .with_help("syntax: partition yes|no I1*I2 command ...")));
        }
        let yes = logical(&args[0])?;
        let (lo, hi) = word_type_range(&args[1].to_word(), "partition", 1).map_err(one)?;
        if args[2].as_str() == "partition" {
            return Err(one(Diagnostic::at(args[2].span, "a partition command cannot run another partition command", "here")));
        }
        if (lo..=hi).contains(&1) != yes {
            return Ok(());
        }
        // like LAMMPS: the command is the raw line from the first occurrence of its name
        let Some(k) = line.text().find(args[2].as_str()) else {
            return Err(one(Diagnostic::at(args[2].span, "cannot find this command in the line", "here")));
        };
        self.one(&line.slice(k..line.len()), host)
    }
}

/// The quoted command arguments of an `if` whose arguments are `condition then commands...
/// [elif condition commands...] [else commands...]`.
fn if_branches(args: &[LexWord]) -> Vec<&LexWord> {
    let mut out = vec![];
    if args.get(1).map(LexWord::as_str) != Some("then") {
        return out; // reported when it runs
    }
    let mut i = 2;
    while i < args.len() {
        match args[i].as_str() {
            "elif" => i += 2, // skip the condition
            "else" => i += 1,
            _ => {
                out.push(&args[i]);
                i += 1;
            }
        }
    }
    out
}

/// The LAMMPS command names the host supports, plus the interpreter's own (for did-you-mean).
fn supported_names(host: &dyn Host) -> Vec<&'static str> {
    lammps_commands().iter().copied().filter(|c| FLOW_COMMANDS.contains(c) || host.supports_command(c)).collect()
}
