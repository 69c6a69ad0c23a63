//! A cursor over a command's arguments that turns every mistake into a located diagnostic
//! carrying the command's syntax as its help line.

use crate::ast::{Command, Word};
use crate::diag::{DResult, Diagnostic};
use crate::span::Span;
use crate::suggest::did_you_mean_help;

/// True if `s` is a floating-point number as LAMMPS accepts it (`utils::is_double`):
/// optional sign, digits with an optional point (or a point and digits), optional exponent.
/// `inf`, `nan`, hex and a trailing junk character are rejected.
pub fn is_lammps_float(s: &str) -> bool {
    let b = s.as_bytes();
    let mut i = 0;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let int_start = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    let int_digits = i - int_start;
    let mut frac_digits = 0;
    if i < b.len() && b[i] == b'.' {
        i += 1;
        let f = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        frac_digits = i - f;
    }
    if int_digits + frac_digits == 0 {
        return false;
    }
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        i += 1;
        if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
            i += 1;
        }
        let e = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        if i == e {
            return false;
        }
    }
    i == b.len()
}

/// True if `s` is an integer as LAMMPS accepts it (`utils::is_integer`).
pub fn is_lammps_integer(s: &str) -> bool {
    let t = s.strip_prefix(['+', '-']).unwrap_or(s);
    !t.is_empty() && t.bytes().all(|c| c.is_ascii_digit())
}

/// Parse a word as a LAMMPS floating-point number.
pub fn word_f64(w: &Word, what: &str) -> DResult<f64> {
    if is_lammps_float(&w.text) {
        if let Ok(x) = w.text.parse::<f64>() {
            if x.is_finite() {
                return Ok(x);
            }
        }
    }
    Err(Diagnostic::at(
        w.span,
        format!("expected a number for {what}, found `{}`", w.text),
        "not a number",
    ))
}

/// Parse a word as a LAMMPS integer.
pub fn word_i64(w: &Word, what: &str) -> DResult<i64> {
    if is_lammps_integer(&w.text) {
        if let Ok(x) = w.text.parse::<i64>() {
            return Ok(x);
        }
    }
    Err(Diagnostic::at(
        w.span,
        format!("expected an integer for {what}, found `{}`", w.text),
        "not an integer",
    ))
}

/// Parse a LAMMPS type range (`*`, `n*`, `*m`, `n*m` or `n`) over types `1..=max`,
/// returning the inclusive bounds.
pub fn word_type_range(w: &Word, what: &str, max: usize) -> DResult<(usize, usize)> {
    let t = w.text.as_str();
    let bad = |msg: String| {
        Diagnostic::at(w.span, msg, "bad range")
            .with_help(format!("a range is `*`, `n*`, `*m`, `n*m` or `n` with 1 <= n <= m <= {max}"))
    };
    let parse = |s: &str| -> Result<usize, ()> {
        if s.bytes().all(|c| c.is_ascii_digit()) && !s.is_empty() {
            s.parse::<usize>().map_err(|_| ())
        } else {
            Err(())
        }
    };
    let (lo, hi) = match t.find('*') {
        None => {
            let n = parse(t).map_err(|_| bad(format!("expected a {what} or a range, found `{t}`")))?;
            (n, n)
        }
        Some(k) => {
            let (a, b) = (&t[..k], &t[k + 1..]);
            let lo = if a.is_empty() { 1 } else { parse(a).map_err(|_| bad(format!("invalid {what} range `{t}`")))? };
            let hi = if b.is_empty() { max } else { parse(b).map_err(|_| bad(format!("invalid {what} range `{t}`")))? };
            (lo, hi)
        }
    };
    if lo < 1 || hi > max || lo > hi {
        return Err(bad(format!("{what} range `{t}` is outside 1..{max}")));
    }
    Ok((lo, hi))
}

/// Cursor over the arguments of one command.
pub struct Args<'a> {
    words: &'a [Word],
    pos: usize,
    /// Where a "missing argument" error points when there is no word left.
    anchor: Span,
    /// The syntax of the command, shown as the help line of every error.
    pub syntax: &'a str,
}

impl<'a> Args<'a> {
    pub fn new(cmd: &'a Command, syntax: &'a str) -> Args<'a> {
        Args { words: &cmd.args, pos: 0, anchor: cmd.span, syntax }
    }
    /// A cursor over a slice of words (e.g. the arguments after a style name).
    pub fn from_words(words: &'a [Word], anchor: Span, syntax: &'a str) -> Args<'a> {
        Args { words, pos: 0, anchor, syntax }
    }
    pub fn remaining(&self) -> &'a [Word] {
        &self.words[self.pos..]
    }
    pub fn is_empty(&self) -> bool {
        self.pos >= self.words.len()
    }
    pub fn len_remaining(&self) -> usize {
        self.words.len() - self.pos
    }
    pub fn peek(&self) -> Option<&'a Word> {
        self.words.get(self.pos)
    }
    /// The word just consumed (for errors about a value already parsed).
    pub fn last(&self) -> Option<&'a Word> {
        if self.pos == 0 { None } else { self.words.get(self.pos - 1) }
    }
    /// Skip `n` words.
    pub fn skip(&mut self, n: usize) {
        self.pos = (self.pos + n).min(self.words.len());
    }
    fn help(&self, d: Diagnostic) -> Diagnostic {
        if self.syntax.is_empty() { d } else { d.with_help(format!("syntax: {}", self.syntax)) }
    }
    /// An error at `w` with the command's syntax as help.
    pub fn error_at(&self, w: &Word, message: impl Into<String>, label: impl Into<String>) -> Diagnostic {
        self.help(Diagnostic::at(w.span, message, label))
    }
    /// An error about the command as a whole (e.g. what it would allocate), at its anchor.
    pub fn error_command(&self, message: impl Into<String>, label: impl Into<String>) -> Diagnostic {
        self.help(Diagnostic::at(self.anchor, message, label))
    }
    /// An error for a missing argument, pointing just after the last word.
    pub fn missing(&self, what: &str) -> Diagnostic {
        let span = match self.words.last() {
            Some(w) => Span { file: w.span.file, lo: w.span.hi, hi: w.span.hi + 1 },
            None => Span { file: self.anchor.file, lo: self.anchor.hi, hi: self.anchor.hi + 1 },
        };
        let span = if span.file == self.anchor.file && self.anchor.hi >= span.lo { span } else { self.anchor };
        self.help(Diagnostic::at(span, format!("missing {what}"), format!("expected {what} here")))
    }
    pub fn word(&mut self, what: &str) -> DResult<&'a Word> {
        match self.words.get(self.pos) {
            Some(w) => {
                self.pos += 1;
                Ok(w)
            }
            None => Err(self.missing(what)),
        }
    }
    pub fn str(&mut self, what: &str) -> DResult<&'a str> {
        Ok(self.word(what)?.text.as_str())
    }
    /// A C format of one number (`thermo_modify format float %.6g`), checked as it will be used
    /// (one conversion, widths and precisions within [`crate::numfmt::MAX_FIELD`]).
    pub fn printf_format(&mut self, what: &str) -> DResult<&'a str> {
        let w = self.word(what)?;
        crate::numfmt::format_printf(&w.text, 0.0).map_err(|m| self.error_at(w, m, "bad format"))?;
        Ok(w.text.as_str())
    }
    /// A line of C formats, one number each (`format line "%d %.3f"`), each checked.
    pub fn printf_line(&mut self, what: &str) -> DResult<Vec<String>> {
        let w = self.word(what)?;
        let pieces: Vec<String> = w.text.split_whitespace().map(String::from).collect();
        for p in &pieces {
            crate::numfmt::format_printf(p, 0.0).map_err(|m| self.error_at(w, m, "bad format"))?;
        }
        Ok(pieces)
    }
    pub fn f64(&mut self, what: &str) -> DResult<f64> {
        let w = self.word(what)?;
        word_f64(w, what).map_err(|d| self.help(d))
    }
    pub fn i64(&mut self, what: &str) -> DResult<i64> {
        let w = self.word(what)?;
        word_i64(w, what).map_err(|d| self.help(d))
    }
    /// A float that must satisfy `ok`, with `need` describing the condition (e.g. "> 0").
    pub fn f64_where(&mut self, what: &str, need: &str, ok: impl Fn(f64) -> bool) -> DResult<f64> {
        let x = self.f64(what)?;
        if !ok(x) {
            let w = self.last().unwrap();
            return Err(self.error_at(w, format!("{what} must be {need}, found {}", w.text), format!("must be {need}")));
        }
        Ok(x)
    }
    pub fn positive_f64(&mut self, what: &str) -> DResult<f64> {
        self.f64_where(what, "> 0", |x| x > 0.0)
    }
    pub fn non_negative_f64(&mut self, what: &str) -> DResult<f64> {
        self.f64_where(what, ">= 0", |x| x >= 0.0)
    }
    /// An integer in `lo..=hi`.
    pub fn i64_in(&mut self, what: &str, lo: i64, hi: i64) -> DResult<i64> {
        let x = self.i64(what)?;
        if x < lo || x > hi {
            let w = self.last().unwrap();
            let range = if hi == i64::MAX { format!(">= {lo}") } else { format!("in {lo}..={hi}") };
            return Err(self.error_at(w, format!("{what} must be {range}, found {x}"), format!("must be {range}")));
        }
        Ok(x)
    }
    /// A count of at least `lo` that LAMMPS reads as an `int` (at most 2^31 - 1, as its
    /// `inumeric`, which refuses larger integers as out of range).
    pub fn usize_min(&mut self, what: &str, lo: usize) -> DResult<usize> {
        Ok(self.i64_in(what, lo as i64, i32::MAX as i64)? as usize)
    }
    /// One of `choices`; returns its index. Misspellings get a suggestion.
    pub fn choice(&mut self, what: &str, choices: &[&str]) -> DResult<usize> {
        let w = self.word(what)?;
        match choices.iter().position(|c| *c == w.text) {
            Some(k) => Ok(k),
            None => {
                let mut d = self.error_at(
                    w,
                    format!("unknown {what} `{}`", w.text),
                    format!("expected one of: {}", choices.join(", ")),
                );
                if let Some(h) = did_you_mean_help(&w.text, choices.iter().copied()) {
                    d.help.insert(0, h);
                }
                Err(d)
            }
        }
    }
    /// `yes`/`no` (LAMMPS also accepts `on`/`off`, `true`/`false`, `1`/`0`? only yes/no here).
    pub fn yes_no(&mut self, what: &str) -> DResult<bool> {
        Ok(self.choice(what, &["no", "yes"])? == 1)
    }
    /// A LAMMPS logical (utils::logical): `yes`/`no`, `on`/`off`, `true`/`false`, `1`/`0`.
    pub fn logical(&mut self, what: &str) -> DResult<bool> {
        Ok(self.choice(what, &["yes", "no", "on", "off", "true", "false", "1", "0"])? % 2 == 0)
    }
    /// `on`/`off`.
    pub fn on_off(&mut self, what: &str) -> DResult<bool> {
        Ok(self.choice(what, &["off", "on"])? == 1)
    }
    /// A LAMMPS type range over `1..=max`.
    pub fn type_range(&mut self, what: &str, max: usize) -> DResult<(usize, usize)> {
        let w = self.word(what)?;
        word_type_range(w, what, max).map_err(|d| self.help(d))
    }
    /// The rest of the words as `units box|lattice` keywords, the only keyword a command takes
    /// after its arguments (displace_atoms, fix move); true for lattice units, LAMMPS' default.
    pub fn units_keyword_only(&mut self) -> DResult<bool> {
        let mut lattice_units = true;
        while let Some(w) = self.peek() {
            self.skip(1);
            match w.text.as_str() {
                "units" => lattice_units = self.choice("units", &["box", "lattice"])? == 1,
                _ => return Err(self.unknown_keyword(w, &["units"])),
            }
        }
        Ok(lattice_units)
    }
    /// Error if words are left over.
    pub fn finish(&self) -> DResult<()> {
        match self.words.get(self.pos) {
            None => Ok(()),
            Some(w) => {
                let last = self.words.last().unwrap();
                let span = w.span.to(last.span);
                Err(self.help(Diagnostic::at(span, format!("unexpected argument `{}`", w.text), "not expected here")))
            }
        }
    }
    /// An unknown keyword in a keyword/value list.
    pub fn unknown_keyword(&self, w: &Word, known: &[&str]) -> Diagnostic {
        let mut d = self.error_at(w, format!("unknown keyword `{}`", w.text), format!("expected one of: {}", known.join(", ")));
        if let Some(h) = did_you_mean_help(&w.text, known.iter().copied()) {
            d.help.insert(0, h);
        }
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::FileId;

    fn words(s: &str) -> Vec<Word> {
        let mut out = vec![];
        let mut pos = 0;
        for t in s.split(' ') {
            out.push(Word::new(t, Span::new(FileId(0), pos, pos + t.len())));
            pos += t.len() + 1;
        }
        out
    }

    #[test]
    fn lammps_number_rules() {
        for s in ["1", "-1.5", "+.5", "5.", "1e-5", "2.6E+3", "0.0"] {
            assert!(is_lammps_float(s), "{s}");
        }
        for s in ["", ".", "e5", "1e", "inf", "nan", "1.0x", "0x10", "1,0", "--1"] {
            assert!(!is_lammps_float(s), "{s}");
        }
        assert!(is_lammps_integer("-12") && !is_lammps_integer("1.0"));
    }

    #[test]
    fn type_ranges() {
        let w = words("* 2* *3 2*3 4 0* 3*2 5");
        let r: Vec<_> = w.iter().map(|w| word_type_range(w, "type", 4).ok()).collect();
        assert_eq!(r, vec![Some((1, 4)), Some((2, 4)), Some((1, 3)), Some((2, 3)), Some((4, 4)), None, None, None]);
    }

    #[test]
    fn cursor_errors() {
        let w = words("1.0 abc");
        let mut a = Args::from_words(&w, Span::default(), "cmd A B");
        assert_eq!(a.f64("A").unwrap(), 1.0);
        let e = a.f64("B").unwrap_err();
        assert!(e.message.contains("expected a number for B"));
        assert_eq!(e.help, vec!["syntax: cmd A B".to_string()]);
        let e = a.f64("C").unwrap_err();
        assert!(e.message.contains("missing C"));
    }
}
