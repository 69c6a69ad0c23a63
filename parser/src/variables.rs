//! The variable store: the `variable` and `next` commands, and what `$x`, `${name}` and
//! `v_name` read, as LAMMPS 22 Jul 2025 does (src/variable.cpp `set()`, `next()`,
//! `retrieve()`, `compute_equal()`).
//!
//! Styles: `index`, `loop` (N, N1 N2, `pad`), `string`, `equal`, `internal`, `format`,
//! `getenv`, `atom`/`vector` (stored for per-atom use; they have no single value), and
//! `atomfile` (per-atom values read from a file by atom ID, [`Variables::define_atomfile`]).
//! Redefinition follows LAMMPS: `index` and `loop` are ignored when the name exists (so a
//! `-var` on the command line wins); `string`, `equal`, `internal`, `format`, `getenv`, `atom`,
//! `vector` replace a variable of the same style; another style is an error.
//!
//! Text and numbers: `${a}` of an equal-style variable is its value printed with `%.15g`, and
//! `v_a` in a formula reads that text back (so `v_a` is the value rounded to 15 digits), except
//! for `internal` variables, whose value is used as is.
//!
//! `variable NAME string VALUE`: LAMMPS substitutes `$x`, `${x}` and `$(...)` in VALUE when
//! the variable is defined, even inside quotes; the caller does that before calling
//! [`Variables::command`] (substitution needs the interpreter).

use crate::ast::Word;
use crate::context::EvalContext;
use crate::diag::{DResult, Diagnostic};
use crate::expr::{self, ExprError};
use crate::numfmt;
use crate::random_mars::{RanMars, SEED_RANGE};
use crate::span::Span;
use crate::suggest::did_you_mean_help;

/// LAMMPS keeps a formatted value in a buffer of this many bytes (with the terminating NUL).
const VALUELENGTH: usize = 64;

#[derive(Clone, Debug, PartialEq)]
enum Style {
    /// Values and the index of the current one.
    Index { values: Vec<String>, which: usize },
    /// Current value is `which + 1`; exhausted when `which` reaches `last`; zero-padded to `pad` digits.
    Loop { which: i64, last: i64, pad: usize },
    Str(String),
    Equal(String),
    Internal(f64),
    /// Name of an equal-style variable and a C format.
    Format { var: String, fmt: String },
    Getenv(String),
    Atom(String),
    Vector(String),
    AtomFile(AtomFile),
}

/// An `atomfile` variable: the file, the line its next set starts at, and the current set's
/// values by atom ID (the atoms that existed when it was read; others read 0, as LAMMPS' per-atom
/// store gives new atoms).
#[derive(Clone, Debug, PartialEq)]
pub struct AtomFile {
    path: std::path::PathBuf,
    next_line: usize,
    values: std::collections::HashMap<i64, f64>,
}

impl AtomFile {
    /// LAMMPS' VarReader::read_peratom from line `start` (0-based): comments and blank lines
    /// up to the count N, then N lines `ID value` (an ID above the largest atom ID is an
    /// error; IDs of no atom are skipped). None at the end of the file.
    fn read(path: &std::path::Path, start: usize, (ids, max_id): (&[i64], i64)) -> Result<Option<AtomFile>, String> {
        let name = path.display();
        let text = std::fs::read_to_string(path).map_err(|e| format!("Cannot open file variable file {name}: {e}"))?;
        let lines: Vec<&str> = text.lines().collect();
        let mut k = start;
        let count = loop {
            let Some(l) = lines.get(k) else { return Ok(None) };
            k += 1;
            let t = l.split('#').next().unwrap_or("").trim();
            if !t.is_empty() {
                break t.parse::<i64>().ok().filter(|&n| n >= 0).ok_or_else(|| format!("{name}:{k}: expected the number of lines of a set of per-atom values, found `{t}`"))?;
            }
        };
        let owned: std::collections::HashSet<i64> = ids.iter().copied().collect();
        let mut values = std::collections::HashMap::new();
        for _ in 0..count {
            let Some(l) = lines.get(k) else { return Err(format!("{name}: Atomfile variable could not read values ({count} lines announced, the file ends at line {})", lines.len())) };
            k += 1;
            let mut w = l.split_whitespace();
            let (Some(Ok(tag)), Some(Ok(value))) = (w.next().map(|t| t.parse::<i64>()), w.next().map(|t| t.parse::<f64>())) else {
                return Err(format!("{name}:{k}: Invalid atomfile line '{l}': expected an atom ID and a value"));
            };
            if tag <= 0 || tag > max_id {
                return Err(format!("{name}:{k}: Invalid atom ID {tag} in variable file"));
            }
            if owned.contains(&tag) {
                values.insert(tag, value);
            }
        }
        Ok(Some(AtomFile { path: path.to_path_buf(), next_line: k, values }))
    }
}

impl Style {
    fn name(&self) -> &'static str {
        match self {
            Style::Index { .. } => "index",
            Style::Loop { .. } => "loop",
            Style::Str(_) => "string",
            Style::Equal(_) => "equal",
            Style::Internal(_) => "internal",
            Style::Format { .. } => "format",
            Style::Getenv(_) => "getenv",
            Style::Atom(_) => "atom",
            Style::Vector(_) => "vector",
            Style::AtomFile(_) => "atomfile",
        }
    }
}

#[derive(Clone, Debug)]
struct Var {
    name: String,
    style: Style,
    /// Being evaluated (for the circular-dependency check).
    busy: bool,
}

/// All variables of a run, in definition order.
#[derive(Debug, Default)]
pub struct Variables {
    vars: Vec<Var>,
    /// The generator of equal-style `random()` and `normal()`: one for all formulas, seeded by
    /// the first call that draws (later seeds are ignored), as LAMMPS' Variable::randomequal.
    random_equal: Option<RanMars>,
}

const STYLES: &[&str] = &["index", "loop", "string", "equal", "internal", "format", "getenv", "atom", "vector", "atomfile", "delete"];
/// LAMMPS styles that dmhs does not implement.
const UNSUPPORTED_STYLES: &[&str] = &["world", "universe", "uloop", "file", "python", "timer"];

fn syntax_of(style: &str) -> &'static str {
    match style {
        "index" => "variable NAME index VALUE1 VALUE2 ...",
        "loop" => "variable NAME loop N [pad]  or  variable NAME loop N1 N2 [pad]",
        "string" => "variable NAME string TEXT",
        "equal" => "variable NAME equal FORMULA",
        "internal" => "variable NAME internal VALUE",
        "format" => "variable NAME format VARIABLE FORMAT  (FORMAT like %.3f, %10.4e, %g)",
        "getenv" => "variable NAME getenv ENVIRONMENT_VARIABLE",
        "atom" => "variable NAME atom FORMULA",
        "vector" => "variable NAME vector FORMULA",
        "atomfile" => "variable NAME atomfile FILE",
        "delete" => "variable NAME delete",
        _ => "variable NAME STYLE ARGS...  (STYLE: index, loop, string, equal, internal, format, getenv, atom, vector, atomfile, delete)",
    }
}

/// A span just after the last word (where a missing argument belongs).
fn after(words: &[Word]) -> Span {
    match words.last() {
        Some(w) => Span { file: w.span.file, lo: w.span.hi, hi: w.span.hi + 1 },
        None => Span::default(),
    }
}

fn missing(args: &[Word], what: &str, style: &str) -> Diagnostic {
    let msg = if style.is_empty() {
        "Illegal variable command: missing argument(s)".to_string()
    } else {
        format!("Illegal variable {style} command: missing argument(s)")
    };
    Diagnostic::at(after(args), msg, format!("expected {what} here")).with_help(format!("syntax: {}", syntax_of(style)))
}

/// LAMMPS' error for a style with a fixed number of words (name and style included).
fn check_count(args: &[Word], n: usize, style: &str) -> DResult<()> {
    if args.len() == n {
        return Ok(());
    }
    let msg = format!("Illegal variable command: expected {n} arguments but found {}", args.len());
    let d = if args.len() < n {
        Diagnostic::at(after(args), msg, "an argument is missing here")
    } else {
        let span = args[n].span.to(args[args.len() - 1].span);
        Diagnostic::at(span, msg, "not expected here")
    };
    Err(d.with_help(format!("syntax: {}", syntax_of(style))))
}

/// LAMMPS' rule for a new variable's name: letters, digits and underscores.
fn check_name(w: &Word) -> DResult<()> {
    let name = &w.text;
    if name.is_empty() || !name.bytes().all(|c| c.is_ascii_alphanumeric() || c == b'_') {
        return Err(Diagnostic::at(w.span, format!("Variable name '{name}' must have only letters, numbers, or underscores"), "invalid name"));
    }
    Ok(())
}

fn parse_int(w: &Word) -> DResult<i64> {
    if crate::args::is_lammps_integer(&w.text) {
        if let Ok(v) = w.text.parse::<i64>() {
            if i32::try_from(v).is_ok() {
                return Ok(v);
            }
        }
    }
    Err(Diagnostic::at(
        w.span,
        format!("Expected integer parameter instead of '{}' in input script or data file", w.text),
        "not an integer",
    )
    .with_help(format!("syntax: {}", syntax_of("loop"))))
}

fn parse_float(w: &Word) -> DResult<f64> {
    if crate::args::is_lammps_float(&w.text) {
        if let Ok(v) = w.text.parse::<f64>() {
            if v.is_finite() {
                return Ok(v);
            }
            return Err(Diagnostic::at(
                w.span,
                format!("Floating point number {} in input script or data file is out of range", w.text),
                "out of range",
            ));
        }
    }
    Err(Diagnostic::at(
        w.span,
        format!("Expected floating point parameter instead of '{}' in input script or data file", w.text),
        "not a number",
    )
    .with_help(format!("syntax: {}", syntax_of("internal"))))
}

impl Variables {
    /// The equal-style generator, made from `seed` (LAMMPS' int cast of the formula's third
    /// argument) at the first draw, with LAMMPS' messages for a bad seed.
    pub fn random_equal(&mut self, seed: f64) -> Result<&mut RanMars, String> {
        if self.random_equal.is_none() {
            let seed = seed as i32;
            if seed <= 0 {
                return Err("Invalid math function in variable formula".into());
            }
            if !SEED_RANGE.contains(&(seed as i64)) {
                return Err("Invalid seed for Marsaglia random # generator".into());
            }
            self.random_equal = Some(RanMars::new(seed));
        }
        Ok(self.random_equal.as_mut().expect("made above"))
    }
    fn find(&self, name: &str) -> Option<usize> {
        self.vars.iter().position(|v| v.name == name)
    }
    fn get(&self, name: &str) -> Option<&Var> {
        self.vars.iter().find(|v| v.name == name)
    }
    fn set_busy(&mut self, name: &str, busy: bool) {
        if let Some(i) = self.find(name) {
            self.vars[i].busy = busy;
        }
    }
    fn remove(&mut self, name: &str) {
        self.vars.retain(|v| v.name != name);
    }

    /// The `variable` command; `args` are its words after the command name.
    pub fn command(&mut self, args: &[Word]) -> DResult<()> {
        if args.len() < 2 {
            return Err(missing(args, if args.is_empty() { "a variable name" } else { "a style" }, ""));
        }
        let name = args[0].text.as_str();
        let style_word = &args[1];
        let style = style_word.text.as_str();
        let existing = self.find(name);
        let new_style = match style {
            "delete" => {
                if args.len() != 2 {
                    let span = args[2].span.to(args[args.len() - 1].span);
                    return Err(Diagnostic::at(
                        span,
                        format!("Illegal variable delete command: expected 2 arguments but found {}", args.len()),
                        "not expected here",
                    )
                    .with_help(format!("syntax: {}", syntax_of("delete"))));
                }
                // deleting a variable that does not exist is fine
                self.remove(name);
                return Ok(());
            }
            "index" => {
                if args.len() < 3 {
                    return Err(missing(args, "at least one value", "index"));
                }
                if existing.is_some() {
                    return Ok(());
                }
                Style::Index { values: args[2..].iter().map(|w| w.text.clone()).collect(), which: 0 }
            }
            "loop" => {
                if existing.is_some() {
                    return Ok(());
                }
                self.loop_style(args)?
            }
            "string" => {
                check_count(args, 3, style)?;
                Style::Str(args[2].text.clone())
            }
            "getenv" => {
                check_count(args, 3, style)?;
                Style::Getenv(args[2].text.clone())
            }
            "internal" => {
                check_count(args, 3, style)?;
                Style::Internal(parse_float(&args[2])?)
            }
            "equal" | "atom" | "vector" => {
                if args.len() < 3 {
                    return Err(missing(args, "a formula", style));
                }
                // several words are one formula
                let text = args[2..].iter().map(|w| w.text.as_str()).collect::<Vec<_>>().join(" ");
                match style {
                    "equal" => Style::Equal(text),
                    "atom" => Style::Atom(text),
                    _ => Style::Vector(text),
                }
            }
            "format" => {
                check_count(args, 4, style)?;
                self.format_style(args)?
            }
            "atomfile" => {
                return Err(Diagnostic::at(style_word.span, "atomfile variables are defined through the interpreter (they read a file)", "internal").with_help(format!("syntax: {}", syntax_of(style))));
            }
            _ if UNSUPPORTED_STYLES.contains(&style) => {
                return Err(Diagnostic::at(
                    style_word.span,
                    format!("variable style `{style}` is not supported by dmhs"),
                    "not supported",
                )
                .with_help(format!("supported styles: {}", STYLES.join(", "))));
            }
            _ => {
                let mut d = Diagnostic::at(style_word.span, format!("Unknown variable style: {style}"), "unknown style")
                    .with_help(format!("syntax: {}", syntax_of("")));
                if let Some(h) = did_you_mean_help(style, STYLES.iter().copied()) {
                    d.help.insert(0, h);
                }
                return Err(d);
            }
        };
        if let Some(i) = existing {
            let old = self.vars[i].style.name();
            if old != new_style.name() {
                return Err(Diagnostic::at(
                    style_word.span,
                    format!("Cannot redefine variable {name} with a different style"),
                    format!("`{name}` is a{} {old} variable", if old.starts_with(['a', 'e', 'i']) { "n" } else { "" }),
                )
                .with_help(format!("delete it first with `variable {name} delete`")));
            }
            self.vars[i].style = new_style;
            return Ok(());
        }
        check_name(&args[0])?;
        self.vars.push(Var { name: name.to_string(), style: new_style, busy: false });
        Ok(())
    }

    /// `loop N [pad]` or `loop N1 N2 [pad]`.
    fn loop_style(&self, args: &[Word]) -> DResult<Style> {
        let n = args.len();
        let pad_at = |k: usize| n == k + 1 && args[k].text == "pad";
        let (first, last, padded) = if n == 3 || (n == 4 && pad_at(3)) {
            let last = parse_int(&args[2])?;
            if last <= 0 {
                return Err(Diagnostic::at(args[2].span, format!("Invalid variable loop argument: {last}"), "must be > 0")
                    .with_help(format!("syntax: {}", syntax_of("loop"))));
            }
            (1, last, n == 4)
        } else if n == 4 || (n == 5 && pad_at(4)) {
            let first = parse_int(&args[2])?;
            let last = parse_int(&args[3])?;
            if first > last || last < 0 {
                return Err(Diagnostic::at(
                    args[2].span.to(args[3].span),
                    format!("Illegal variable loop command: {first} > {last}"),
                    "N1 must be <= N2 and N2 >= 0",
                )
                .with_help(format!("syntax: {}", syntax_of("loop"))));
            }
            (first, last, n == 5)
        } else if n < 3 {
            return Err(missing(args, "the number of iterations", "loop"));
        } else {
            let span = args[4].span.to(args[n - 1].span);
            return Err(Diagnostic::at(span, "Illegal variable loop command: too many arguments", "not expected here")
                .with_help(format!("syntax: {}", syntax_of("loop"))));
        };
        let pad = if padded { last.to_string().len() } else { 0 };
        Ok(Style::Loop { which: first - 1, last, pad })
    }

    /// `format VAR FMT`: VAR must exist and be equal-style (or internal), FMT one conversion.
    fn format_style(&self, args: &[Word]) -> DResult<Style> {
        let name = &args[0].text;
        let var = &args[2];
        match self.get(&var.text) {
            None => {
                let mut d = Diagnostic::at(
                    var.span,
                    format!("Variable {name}: format variable {} does not exist", var.text),
                    "no such variable",
                );
                if let Some(h) = did_you_mean_help(&var.text, self.vars.iter().map(|v| v.name.as_str())) {
                    d = d.with_help(h);
                }
                return Err(d);
            }
            Some(v) if !matches!(v.style, Style::Equal(_) | Style::Internal(_)) => {
                return Err(Diagnostic::at(
                    var.span,
                    format!("Variable {name}: format variable {} has incompatible style", var.text),
                    format!("a {} variable", v.style.name()),
                )
                .with_help("the formatted variable must be equal-style or internal"));
            }
            Some(_) => {}
        }
        let fmt = &args[3];
        if !numfmt::is_format_style_spec(&fmt.text) {
            return Err(Diagnostic::at(fmt.span, "Incorrect conversion in format string", "not a single %e, %f or %g")
                .with_help("the format is one conversion such as %.3f, %10.4e, %-12g (flags: space, -)"));
        }
        if let Err(m) = numfmt::format_printf(&fmt.text, 0.0) {
            return Err(Diagnostic::at(fmt.span, m, "bad format"));
        }
        Ok(Style::Format { var: var.text.clone(), fmt: fmt.text.clone() })
    }

    /// The `next` command: advance each listed variable (in order, once per mention). Returns
    /// true if any was exhausted; exhausted variables are deleted (so a later `variable ...
    /// index` can define them again).
    pub fn next(&mut self, args: &[Word]) -> DResult<bool> {
        if args.is_empty() {
            return Err(Diagnostic::error("Illegal next command: missing argument(s)")
                .with_help("syntax: next VARIABLE1 VARIABLE2 ..."));
        }
        let mut first_style = None;
        for w in args {
            let Some(v) = self.get(&w.text) else {
                let mut d = Diagnostic::at(w.span, format!("Invalid variable '{}' in next command", w.text), "no such variable");
                if let Some(h) = did_you_mean_help(&w.text, self.vars.iter().map(|v| v.name.as_str())) {
                    d = d.with_help(h);
                }
                return Err(d);
            };
            let s = v.style.name();
            match first_style {
                None => first_style = Some(s),
                Some(f) if f != s => {
                    return Err(Diagnostic::at(w.span, "All variables in next command must have same style", format!("a {s} variable"))
                        .with_help(format!("`{}` is a {f} variable", args[0].text)));
                }
                _ => {}
            }
        }
        let style = first_style.unwrap_or("index");
        if style != "index" && style != "loop" {
            return Err(Diagnostic::at(
                args[0].span,
                format!("Variable {} has invalid style {style} for next command", args[0].text),
                format!("a {style} variable"),
            )
            .with_help("next advances index and loop variables"));
        }
        let mut exhausted = false;
        for w in args {
            let Some(i) = self.find(&w.text) else { continue };
            let done = match &mut self.vars[i].style {
                Style::Index { values, which } => {
                    *which += 1;
                    *which >= values.len()
                }
                Style::Loop { which, last, .. } => {
                    *which += 1;
                    *which >= *last
                }
                _ => false,
            };
            if done {
                exhausted = true;
                self.vars.remove(i);
            }
        }
        Ok(exhausted)
    }

    /// `variable NAME atomfile FILE` (`path` resolved by the caller; `ids` the atoms' IDs
    /// now and the largest atom ID): the file's first set of per-atom values. A name that exists is left alone, as
    /// LAMMPS does.
    pub fn define_atomfile(&mut self, args: &[Word], path: &std::path::Path, ids: (&[i64], i64)) -> DResult<()> {
        check_count(args, 3, "atomfile")?;
        let name = args[0].text.as_str();
        if self.find(name).is_some() {
            return Ok(());
        }
        check_name(&args[0])?;
        let file = AtomFile::read(path, 0, ids)
            .map_err(|m| Diagnostic::at(args[2].span, m, "this file"))?
            .ok_or_else(|| Diagnostic::at(args[2].span, "Atomfile variable could not read values", "no set of values in this file"))?;
        self.vars.push(Var { name: name.to_string(), style: Style::AtomFile(file), busy: false });
        Ok(())
    }

    /// `next` of atomfile variables (`ids` the atoms' IDs now): each reads its file's next set;
    /// one at the end of its file is deleted. Returns true if any was.
    pub fn next_atomfile(&mut self, args: &[Word], ids: (&[i64], i64)) -> DResult<bool> {
        let mut exhausted = false;
        for w in args {
            let Some(i) = self.find(&w.text) else { continue };
            let Style::AtomFile(f) = &self.vars[i].style else {
                return Err(Diagnostic::at(w.span, "All variables in next command must have same style", format!("a {} variable", self.vars[i].style.name())));
            };
            match AtomFile::read(&f.path, f.next_line, ids).map_err(|m| Diagnostic::at(w.span, m, "reading the next set"))? {
                Some(next) => self.vars[i].style = Style::AtomFile(next),
                None => {
                    exhausted = true;
                    self.vars.remove(i);
                }
            }
        }
        Ok(exhausted)
    }

    /// The current values of an atomfile variable by atom ID (an atom not listed reads 0).
    pub fn atomfile_values(&self, name: &str) -> Option<&std::collections::HashMap<i64, f64>> {
        match &self.get(name)?.style {
            Style::AtomFile(f) => Some(&f.values),
            _ => None,
        }
    }

    /// An index variable from the command line (`-var NAME V1 V2 ...`): defined before the
    /// script runs, so the script's own `variable NAME index ...` is ignored.
    pub fn define_index(&mut self, name: &str, values: Vec<String>) {
        if values.is_empty() || self.find(name).is_some() {
            return;
        }
        self.vars.push(Var { name: name.to_string(), style: Style::Index { values, which: 0 }, busy: false });
    }

    pub fn exists(&self, name: &str) -> bool {
        self.find(name).is_some()
    }

    /// Set an internal-style variable (created if it does not exist; a variable of another
    /// style is left alone).
    pub fn set_internal(&mut self, name: &str, value: f64) {
        match self.find(name) {
            Some(i) => {
                if let Style::Internal(v) = &mut self.vars[i].style {
                    *v = value;
                }
            }
            None => self.vars.push(Var { name: name.to_string(), style: Style::Internal(value), busy: false }),
        }
    }

    /// Names of all variables, in definition order.
    pub fn names(&self) -> Vec<String> {
        self.vars.iter().map(|v| v.name.clone()).collect()
    }

    /// The style of a variable (`"index"`, `"loop"`, `"string"`, `"equal"`, `"internal"`,
    /// `"format"`, `"getenv"`, `"atom"`, `"vector"`).
    pub fn style(&self, name: &str) -> Option<&'static str> {
        self.get(name).map(|v| v.style.name())
    }

    /// True for the variables [`compute_equal`] can evaluate (equal and internal).
    pub fn is_equal_style(&self, name: &str) -> bool {
        matches!(self.get(name).map(|v| &v.style), Some(Style::Equal(_) | Style::Internal(_)))
    }

    /// The formula of an equal-, atom- or vector-style variable.
    pub fn formula(&self, name: &str) -> Option<&str> {
        match &self.get(name)?.style {
            Style::Equal(t) | Style::Atom(t) | Style::Vector(t) => Some(t),
            _ => None,
        }
    }
}

/// The style of a variable through a context.
pub fn style_of(ctx: &mut dyn EvalContext, name: &str) -> Option<&'static str> {
    ctx.variables().style(name)
}

fn circular(name: &str) -> String {
    format!("Variable {name}: has a circular dependency")
}

/// LAMMPS' message for an error while evaluating variable `name`.
fn named_error(name: &str, e: ExprError) -> String {
    if e.bare {
        e.message
    } else {
        format!("Variable {name}: {}", e.message)
    }
}

/// Evaluate the formula of variable `name` with the circular-dependency flag set.
fn eval_formula(ctx: &mut dyn EvalContext, name: &str, text: &str) -> Result<f64, String> {
    ctx.variables().set_busy(name, true);
    let r = expr::evaluate(text, ctx);
    ctx.variables().set_busy(name, false);
    r.map_err(|e| named_error(name, e))
}

/// The text `$x` / `${name}` substitutes: `None` if there is no such variable (or it has no
/// single value: atom and vector styles). Errors are LAMMPS messages.
pub fn retrieve(ctx: &mut dyn EvalContext, name: &str) -> Result<Option<String>, String> {
    let Some(var) = ctx.variables().get(name).cloned() else { return Ok(None) };
    if var.busy {
        return Err(circular(name));
    }
    let text = match var.style {
        Style::Index { values, which } => values.get(which).cloned(),
        Style::Loop { which, pad, .. } => Some(format!("{:0pad$}", which + 1)),
        Style::Str(s) => Some(s),
        Style::Getenv(v) => Some(std::env::var(&v).unwrap_or_default()),
        Style::Internal(v) => Some(numfmt::format_g(v, 15)),
        Style::Atom(_) | Style::AtomFile(_) => None,
        // LAMMPS: "[v1,v2,...]", each value in fmt's shortest form
        Style::Vector(_) => {
            let v = ctx.vector_variable(name)?;
            Some(format!("[{}]", v.iter().map(|&x| numfmt::shortest(x)).collect::<Vec<_>>().join(",")))
        }
        Style::Equal(text) => Some(numfmt::format_g(eval_formula(ctx, name, &text)?, 15)),
        Style::Format { var, fmt } => {
            match ctx.variables().style(&var) {
                None => return Err(format!("Variable {name}: format variable {var} does not exist")),
                Some("equal" | "internal") => {}
                Some(_) => return Err(format!("Variable {name}: format variable {var} has incompatible style")),
            }
            ctx.variables().set_busy(name, true);
            let v = compute_equal(ctx, &var);
            ctx.variables().set_busy(name, false);
            let mut s = numfmt::format_printf(&fmt, v?).map_err(|m| format!("Variable {name}: {m}"))?;
            // LAMMPS prints into a buffer of VALUELENGTH bytes
            while s.len() > VALUELENGTH - 1 {
                s.pop();
            }
            Some(s)
        }
    };
    Ok(text)
}

/// The numeric value of an equal-style or internal variable (what thermo output, fixes and
/// `format` variables use): the formula evaluated at full precision.
pub fn compute_equal(ctx: &mut dyn EvalContext, name: &str) -> Result<f64, String> {
    let Some(var) = ctx.variables().get(name).cloned() else {
        return Err(format!("Variable {name} does not exist"));
    };
    if var.busy {
        return Err(circular(name));
    }
    match var.style {
        Style::Equal(text) => eval_formula(ctx, name, &text),
        Style::Internal(v) => Ok(v),
        s => Err(format!("Variable {name} is {}-style, not equal-style", s.name())),
    }
}

/// The value of `v_name` inside a formula: internal variables directly, every other style
/// through its text (which must be a number).
pub fn formula_value(ctx: &mut dyn EvalContext, name: &str) -> Result<f64, String> {
    let Some(var) = ctx.variables().get(name).cloned() else {
        return Err(format!("Invalid variable reference v_{name} in variable formula"));
    };
    if var.busy {
        return Err(circular(name));
    }
    match var.style {
        Style::Internal(v) => return Ok(v),
        Style::Atom(_) => return Err(format!("Variable {name}: Atom-style variable in equal-style variable formula")),
        Style::AtomFile(_) => return Err(format!("Variable {name}: Atomfile-style variable in equal-style variable formula")),
        Style::Vector(_) => return Err(format!("Variable {name}: Vector-style variable in equal-style variable formula")),
        _ => {}
    }
    let Some(text) = retrieve(ctx, name)? else {
        return Err(format!("Variable {name}: Invalid variable evaluation in variable formula"));
    };
    if !crate::args::is_lammps_float(&text) {
        return Err(format!("Variable {name}: Non-numeric variable value in variable formula"));
    }
    let (neg, digits) = match text.as_bytes()[0] {
        b'-' => (true, &text[1..]),
        b'+' => (false, &text[1..]),
        _ => (false, &text[..]),
    };
    let v = expr::strtod_prefix(digits).map_err(|_| format!("Variable {name}: value {text} is out of the range of a double"))?;
    Ok(if neg { -v } else { v })
}

#[cfg(test)]
mod tests;
