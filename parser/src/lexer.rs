//! Reading an input script the way LAMMPS reads it (`Input::file`, `parse`, `substitute`,
//! `nextword` in src/input.cpp), keeping the source position of every byte.
//!
//! The steps, in LAMMPS' order:
//! 1. [`split_lines`]: physical lines become logical commands. A line whose last printable
//!    character is `&` continues on the next line, and the next line's text (leading blanks
//!    included) replaces the `&`. A line with an odd number of `"""` continues too, joined
//!    by a newline. Trailing whitespace is trimmed.
//! 2. [`strip_comment`]: `#` outside quotes ends the command; a quote without its partner is
//!    an error.
//! 3. [`ascii_substitute`]: a few Unicode spaces, quotes and minus signs become ASCII.
//! 4. [`substitute`]: `$x`, `${name}`, `$(expr)`, `$(expr:%fmt)` outside quotes.
//! 5. [`split_words`]: words split at whitespace; a word that starts with a quote runs to
//!    the matching quote, which is removed.
//!
//! Every step works on [`Located`] text, so a word made by substitution points at the
//! `${...}` the user wrote.

use crate::ast::Word;
use crate::context::EvalContext;
use crate::diag::{DResult, Diagnostic};
use crate::span::{FileId, Span};
use std::ops::Range;

/// Text with the source span of each of its bytes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Located {
    text: String,
    spans: Vec<Span>,
}

impl Located {
    pub fn new() -> Located {
        Located::default()
    }
    /// `text` as it stands in `file` at byte offset `base`.
    pub fn from_source(file: FileId, text: &str, base: usize) -> Located {
        let spans = (0..text.len()).map(|i| Span::new(file, base + i, base + i + 1)).collect();
        Located { text: text.to_string(), spans }
    }
    pub fn text(&self) -> &str {
        &self.text
    }
    pub fn len(&self) -> usize {
        self.text.len()
    }
    pub fn is_empty(&self) -> bool {
        self.text.is_empty()
    }
    /// Append `s`, every byte of it attributed to `span`.
    pub fn push_str(&mut self, s: &str, span: Span) {
        self.text.push_str(s);
        self.spans.extend(std::iter::repeat_n(span, s.len()));
    }
    /// Append bytes `range` of `other` (on character boundaries).
    pub fn push_slice(&mut self, other: &Located, range: Range<usize>) {
        self.text.push_str(&other.text[range.clone()]);
        self.spans.extend_from_slice(&other.spans[range]);
    }
    pub fn slice(&self, range: Range<usize>) -> Located {
        Located { text: self.text[range.clone()].to_string(), spans: self.spans[range].to_vec() }
    }
    fn truncate(&mut self, n: usize) {
        self.text.truncate(n);
        self.spans.truncate(n);
    }
    /// The source span covering bytes `range` (zero-width at the position if empty).
    pub fn span(&self, range: Range<usize>) -> Span {
        if range.start >= range.end {
            return match self.spans.get(range.start) {
                Some(s) => Span { hi: s.lo, ..*s },
                None => self.spans.last().map(|s| Span { lo: s.hi, ..*s }).unwrap_or_default(),
            };
        }
        let end = range.end.min(self.spans.len());
        let Some(&first) = self.spans.get(range.start) else { return self.span(end..end) };
        self.spans[range.start..end].iter().fold(first, |acc, s| acc.to(*s))
    }
    /// The span of the whole text.
    pub fn full_span(&self) -> Span {
        self.span(0..self.len())
    }
}

/// One logical command line of a file, before comment stripping and substitution.
#[derive(Clone, Debug, PartialEq)]
pub struct LogicalLine {
    pub text: Located,
    pub span: Span,
}

/// C `isspace` in the "C" locale.
fn is_c_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r' | 0x0b | 0x0c)
}

/// Number of `"""` in `s`, counted left to right without overlap (LAMMPS `numtriple`).
fn count_triple(s: &str) -> usize {
    s.matches("\"\"\"").count()
}

/// Where the next physical line lands when a command continues.
enum Continue {
    /// Replaces the `&` at this byte.
    Ampersand(usize),
    /// Goes after a newline put just after the last printable byte at this index.
    Triple(usize),
}

/// Split a file into logical commands as `Input::file()` reads them.
pub fn split_lines(file: FileId, src: &str) -> Vec<LogicalLine> {
    let whole = Located::from_source(file, src, 0);
    let bytes = src.as_bytes();
    let mut out = vec![];
    let mut pos = 0;
    while pos < bytes.len() {
        let mut line = Located::new();
        let mut ntriple = 0;
        let mut pending: Option<Continue> = None;
        // At the end of the file in the middle of a continuation, LAMMPS keeps the text as
        // read (the `&` included), so a cut is only applied once the next line exists.
        while pos < bytes.len() {
            let end = src[pos..].find('\n').map(|k| pos + k + 1).unwrap_or(bytes.len());
            match pending.take() {
                Some(Continue::Ampersand(m)) => line.truncate(m),
                Some(Continue::Triple(m)) => {
                    let newline_span = line.spans[m + 1];
                    line.truncate(m + 1);
                    line.push_str("\n", newline_span);
                }
                None => {}
            }
            let mstart = line.len();
            line.push_slice(&whole, pos..end);
            pos = end;
            if !line.text.ends_with('\n') {
                break; // last line without a newline: taken as it is
            }
            ntriple += count_triple(&line.text[mstart..]);
            // last printable byte of the whole accumulated line
            let lb = line.text.as_bytes();
            let mut m = lb.len();
            while m > 0 && is_c_space(lb[m - 1]) {
                m -= 1;
            }
            if m > 0 && lb[m - 1] == b'&' {
                pending = Some(Continue::Ampersand(m - 1));
                continue;
            }
            if ntriple % 2 == 1 && m > 0 {
                pending = Some(Continue::Triple(m - 1));
                continue;
            }
            line.truncate(m);
            break;
        }
        let span = line.full_span();
        out.push(LogicalLine { text: line, span });
    }
    out
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Quote {
    Single,
    Double,
    Triple,
}

impl Quote {
    fn at(b: &[u8], i: usize) -> Option<Quote> {
        match b.get(i) {
            Some(b'\'') => Some(Quote::Single),
            Some(b'"') if b[i..].starts_with(b"\"\"\"") => Some(Quote::Triple),
            Some(b'"') => Some(Quote::Double),
            _ => None,
        }
    }
    fn delim(self) -> &'static str {
        match self {
            Quote::Single => "'",
            Quote::Double => "\"",
            Quote::Triple => "\"\"\"",
        }
    }
    fn name(self) -> &'static str {
        match self {
            Quote::Single => "single quote",
            Quote::Double => "double quote",
            Quote::Triple => "triple quote",
        }
    }
    /// Byte index of the closing delimiter for a quote opening at `i`.
    fn closing(self, text: &str, i: usize) -> Option<usize> {
        let from = i + self.delim().len();
        text[from..].find(self.delim()).map(|k| from + k)
    }
}

fn unmatched(line: &Located, at: usize, q: Quote) -> Diagnostic {
    Diagnostic::at(line.span(at..at + q.delim().len()), format!("unmatched {}", q.name()), "this quote is never closed")
        .with_help("close the quote on the same command line; text in \"\"\" triple quotes may span lines")
}

/// Remove a `#` comment outside quotes (`Input::parse`).
pub fn strip_comment(line: &Located) -> DResult<Located> {
    let b = line.text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'#' {
            return Ok(line.slice(0..i));
        }
        match Quote::at(b, i) {
            Some(q) => {
                let close = q.closing(&line.text, i).ok_or_else(|| unmatched(line, i, q))?;
                i = close + q.delim().len();
            }
            None => i += 1,
        }
    }
    Ok(line.clone())
}

/// Replace the Unicode characters LAMMPS knows (`utils::utf8_subst`) by ASCII.
/// Returns the new text and whether the line had any non-ASCII character.
/// (LAMMPS drops the lead byte of other non-ASCII characters; they are kept here.)
pub fn ascii_substitute(line: &Located) -> (Located, bool) {
    if line.text.is_ascii() {
        return (line.clone(), false);
    }
    let mut out = Located::new();
    for (i, c) in line.text.char_indices() {
        let n = c.len_utf8();
        let ascii = match c {
            '\u{00A0}' | '\u{2000}'..='\u{200B}' | '\u{202F}' | '\u{2060}' | '\u{2063}' | '\u{FEFF}' => Some(" "),
            '\u{02D6}' | '\u{2064}' => Some("+"),
            '\u{02D7}' | '\u{2212}' => Some("-"),
            '\u{2018}' | '\u{2019}' => Some("'"),
            '\u{201C}' | '\u{201D}' => Some("\""),
            _ => None,
        };
        match ascii {
            Some(a) => out.push_str(a, line.span(i..i + n)),
            None => out.push_slice(line, i..i + n),
        }
    }
    (out, true)
}

/// Expand `$x`, `${name}`, `$(expr)` and `$(expr:%fmt)` outside quotes (`Input::substitute`).
/// `progress`, when given, receives the line after each substitution (what `echo` shows).
pub fn substitute(
    line: &Located,
    ctx: &mut dyn EvalContext,
    mut progress: Option<&mut dyn FnMut(&str)>,
) -> DResult<Located> {
    let text = line.text.as_str();
    let b = text.as_bytes();
    let mut out = Located::new();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'$' => {
                let (value, end) = expand_one(line, i, ctx)?;
                out.push_str(&value, line.span(i..end));
                i = end;
                if let Some(p) = progress.as_mut() {
                    p(&format!("{}{}", out.text, &text[end..]));
                }
            }
            b'\'' | b'"' => {
                let q = Quote::at(b, i).unwrap();
                let close = q.closing(text, i).ok_or_else(|| unmatched(line, i, q))?;
                let end = close + q.delim().len();
                out.push_slice(line, i..end);
                i = end;
            }
            _ => {
                let next = text[i..].find(['$', '\'', '"']).map(|k| i + k).unwrap_or(b.len());
                out.push_slice(line, i..next);
                i = next;
            }
        }
    }
    Ok(out)
}

/// Expand the `$` reference starting at byte `i`; returns its text and the byte after it.
fn expand_one(line: &Located, i: usize, ctx: &mut dyn EvalContext) -> DResult<(String, usize)> {
    let text = line.text.as_str();
    match text.as_bytes().get(i + 1) {
        Some(b'{') => {
            let Some(k) = text[i + 2..].find('}') else {
                return Err(Diagnostic::at(line.span(i..i + 2), "unterminated `${`", "no closing `}`")
                    .with_help("write a variable reference as ${name}"));
            };
            let end = i + 2 + k + 1;
            let name = &text[i + 2..end - 1];
            Ok((variable_text(line, i..end, name, ctx)?, end))
        }
        Some(b'(') => immediate(line, i, ctx),
        Some(_) => {
            let c = text[i + 1..].chars().next().unwrap();
            let end = i + 1 + c.len_utf8();
            if !(c.is_ascii_alphanumeric() || c == '_') {
                return Err(Diagnostic::at(line.span(i..end), format!("`${c}` is not a variable reference"), "expected a name after `$`")
                    .with_help("write $x for a one-letter variable, ${name} for a longer one, $(expression) for a formula"));
            }
            let mut d = match variable_text(line, i..end, &c.to_string(), ctx) {
                Ok(v) => return Ok((v, end)),
                Err(d) => d,
            };
            if text[end..].starts_with(|n: char| n.is_ascii_alphanumeric() || n == '_') {
                d = d.with_note(format!("`${c}` is the one-letter variable `{c}`; write ${{...}} around a longer name"));
            }
            Err(d)
        }
        None => Err(Diagnostic::at(line.span(i..i + 1), "`$` at the end of the line", "expected a variable name after `$`")
            .with_help("write $x for a one-letter variable, ${name} for a longer one, $(expression) for a formula")),
    }
}

/// The text of variable `name`, referenced by the bytes `at` of `line`.
fn variable_text(line: &Located, at: Range<usize>, name: &str, ctx: &mut dyn EvalContext) -> DResult<String> {
    let span = line.span(at);
    match crate::variables::retrieve(ctx, name) {
        Ok(Some(v)) => Ok(v),
        Ok(None) => Err(Diagnostic::at(span, format!("undefined variable `{name}`"), "no variable of this name")
            .with_help(format!("define it before this line (`variable {name} ...`) or on the command line (`-var {name} VALUE`)"))),
        Err(m) => Err(Diagnostic::at(span, format!("cannot substitute variable `{name}`: {m}"), "here")),
    }
}

/// `$(expr)` or `$(expr:%fmt)` starting at byte `i`.
fn immediate(line: &Located, i: usize, ctx: &mut dyn EvalContext) -> DResult<(String, usize)> {
    let text = line.text.as_str();
    let b = text.as_bytes();
    // the closing parenthesis at depth 0, as LAMMPS counts them
    let mut depth = 0i32;
    let mut k = i + 2;
    while k < b.len() && (b[k] != b')' || depth != 0) {
        match b[k] {
            b'(' => depth += 1,
            b')' => depth -= 1,
            _ => {}
        }
        k += 1;
    }
    if k >= b.len() {
        return Err(Diagnostic::at(line.span(i..i + 2), "unterminated `$(`", "no matching `)`")
            .with_help("an immediate expression is written $(formula) or $(formula:%.6g)"));
    }
    let end = k + 1;
    let inner = &text[i + 2..k];
    let (expr_len, fmt) = match inner.rfind(':') {
        Some(c) if inner[c + 1..].starts_with('%') => (c, Some(c + 1)),
        _ => (inner.len(), None),
    };
    let expr_start = i + 2;
    let x = crate::expr::evaluate(&inner[..expr_len], ctx).map_err(|e| {
        let lo = expr_start + e.offset.min(expr_len);
        let hi = (lo + e.len.max(1)).min(expr_start + expr_len).max(lo);
        Diagnostic::at(line.span(lo..hi), e.message, "here")
    })?;
    let value = match fmt {
        None => crate::numfmt::format_g(x, 20),
        Some(f) => {
            let fmt_range = expr_start + f..k;
            format_immediate(&inner[f..], x).map_err(|m| {
                Diagnostic::at(line.span(fmt_range), m, "bad format")
                    .with_help("the format is % with an optional width, a precision and one of e f g E F G, e.g. %.6g or %12.4e")
            })?
        }
    };
    Ok((value, end))
}

/// Apply a `$(...:fmt)` format: `%[0-9 ]*.[0-9]+[efgEFG]` then literal text (LAMMPS passes
/// the whole format to `snprintf`).
fn format_immediate(fmt: &str, x: f64) -> Result<String, String> {
    let b = fmt.as_bytes();
    let mut i = 1;
    while i < b.len() && (b[i].is_ascii_digit() || b[i] == b' ') {
        i += 1;
    }
    let dot = i < b.len() && b[i] == b'.';
    let digits_from = i + 1;
    if dot {
        i += 1;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
    }
    let ok = dot && i > digits_from && i < b.len() && b"efgEFG".contains(&b[i]);
    if !ok {
        return Err(format!("invalid format `{fmt}` for an immediate variable"));
    }
    let suffix = &fmt[i + 1..];
    if suffix.replace("%%", "").contains('%') {
        return Err(format!("format `{fmt}` has more than one conversion"));
    }
    let mut s = crate::numfmt::format_printf(&fmt[..=i], x)?;
    s.push_str(&suffix.replace("%%", "%"));
    Ok(s)
}

/// One word of a command, quotes removed.
#[derive(Clone, Debug, PartialEq)]
pub struct LexWord {
    /// The text inside the quotes (for `print`, `if` and `include`, which substitute it again).
    pub text: Located,
    /// The word as written, quotes included.
    pub span: Span,
    pub quoted: bool,
}

impl LexWord {
    pub fn as_str(&self) -> &str {
        self.text.text()
    }
    pub fn to_word(&self) -> Word {
        Word { text: self.text.text.clone(), span: self.span, quoted: self.quoted }
    }
}

/// Split a line into words (`Input::nextword`).
pub fn split_words(line: &Located) -> DResult<Vec<LexWord>> {
    let text = line.text.as_str();
    let b = text.as_bytes();
    let mut words = vec![];
    let mut i = 0;
    loop {
        while i < b.len() && is_c_space(b[i]) {
            i += 1;
        }
        if i >= b.len() {
            return Ok(words);
        }
        match Quote::at(b, i) {
            Some(q) => {
                let close = q.closing(text, i).ok_or_else(|| unmatched(line, i, q))?;
                let n = q.delim().len();
                let next = close + n;
                if next < b.len() && !is_c_space(b[next]) {
                    let after = text[next..].chars().next().map(char::len_utf8).unwrap_or(1);
                    return Err(Diagnostic::at(line.span(next..next + after), "a closing quote must be followed by a space", "expected a space before this")
                        .with_label(line.span(close..next), "the quote closes here")
                        .with_help("a quoted word ends at its closing quote; quote the whole word or put a space after the quote"));
                }
                words.push(LexWord { text: line.slice(i + n..close), span: line.span(i..next), quoted: true });
                i = next;
            }
            None => {
                let start = i;
                while i < b.len() && !is_c_space(b[i]) {
                    i += 1;
                }
                words.push(LexWord { text: line.slice(start..i), span: line.span(start..i), quoted: false });
            }
        }
    }
}

/// Comment stripping, ASCII substitution, `$` substitution (when `ctx` is given) and word
/// splitting of one command line, as `Input::parse` does it. The flag tells whether the line
/// had non-ASCII characters.
pub fn parse_line(
    line: &Located,
    ctx: Option<&mut dyn EvalContext>,
    progress: Option<&mut dyn FnMut(&str)>,
) -> DResult<(Vec<LexWord>, bool)> {
    let stripped = strip_comment(line)?;
    let (ascii, non_ascii) = ascii_substitute(&stripped);
    let expanded = match ctx {
        Some(ctx) => substitute(&ascii, ctx, progress)?,
        None => ascii,
    };
    Ok((split_words(&expanded)?, non_ascii))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::SourceMap;
    use crate::variables::Variables;

    struct Ctx(Variables);
    impl EvalContext for Ctx {
        fn variables(&mut self) -> &mut Variables {
            &mut self.0
        }
    }
    fn ctx(defs: &[(&str, &str)]) -> Ctx {
        let mut v = Variables::default();
        for (n, val) in defs {
            v.define_index(n, vec![val.to_string()]);
        }
        Ctx(v)
    }
    fn lines(src: &str) -> Vec<String> {
        split_lines(FileId(0), src).into_iter().map(|l| l.text.text).collect()
    }
    fn words(src: &str, c: &mut Ctx) -> DResult<Vec<String>> {
        let line = Located::from_source(FileId(0), src, 0);
        let (w, _) = parse_line(&line, Some(c), None)?;
        Ok(w.iter().map(|w| w.as_str().to_string()).collect())
    }

    #[test]
    fn continuation_text_lands_where_the_ampersand_was() {
        // observed with lmp -echo screen: "print a&\nb" echoes "print ab",
        // "print a   &  \n    b" echoes "print a       b"
        assert_eq!(lines("print a&\nb\n"), vec!["print ab"]);
        assert_eq!(lines("print a   &  \n    b\n"), vec!["print a       b"]);
        assert_eq!(lines("print a &\n# c\nb\n"), vec!["print a # c", "b"]);
        assert_eq!(lines("print a &\n\nx\n"), vec!["print a", "x"]);
        assert_eq!(lines("a\r\nb &\r\nc\r\n"), vec!["a", "b c"]);
    }

    #[test]
    fn continuation_at_end_of_file_keeps_the_ampersand() {
        // lmp: "print a &" + EOF -> "Unknown print keyword: &"
        assert_eq!(lines("print a &\n"), vec!["print a &\n"]);
        assert_eq!(lines("print a &"), vec!["print a &"]);
    }

    #[test]
    fn triple_quotes_span_lines() {
        // lmp echoes 'print """line1\nline2\n  line3"""' (trailing blanks of line2 trimmed)
        assert_eq!(lines("print \"\"\"line1\nline2   \n  line3\"\"\"\nx\n"), vec!["print \"\"\"line1\nline2\n  line3\"\"\"", "x"]);
        // blank lines inside triple quotes vanish (the trim runs back over the whole line)
        assert_eq!(lines("print \"\"\"a\n\n   \n b\"\"\"\n"), vec!["print \"\"\"a\n b\"\"\""]);
        // a continuation after a closing quote
        assert_eq!(lines("print \"x\"&\n   \"y\"\n"), vec!["print \"x\"   \"y\""]);
    }

    #[test]
    fn comments_and_quotes() {
        let mut c = ctx(&[]);
        assert_eq!(words("print \"a # b\" # comment", &mut c).unwrap(), vec!["print", "a # b"]);
        assert_eq!(words("print 'x y' \"\" \"\"\"p \"q\" r\"\"\"", &mut c).unwrap(), vec!["print", "x y", "", "p \"q\" r"]);
        // a quote inside a word still opens a quoted region: `a"b c"d` is two words
        assert_eq!(words("print a\"b c\"d", &mut c).unwrap(), vec!["print", "a\"b", "c\"d"]);
        assert!(words("print don't", &mut c).unwrap_err().message.contains("unmatched single quote"));
        assert!(words("print 'a'b", &mut c).unwrap_err().message.contains("followed by a space"));
    }

    #[test]
    fn substitution() {
        let mut c = ctx(&[("a", "2"), ("name", "lj/cut")]);
        assert_eq!(words("x $ab ${name} $(1/3) $(2/3:%10.4e) $(1/3:%.3f_x)", &mut c).unwrap(),
            vec!["x", "2b", "lj/cut", "0.33333333333333331483", "6.6667e-01", "0.333_x"]);
        // not inside quotes
        assert_eq!(words("print '$a' \"${name}\"", &mut c).unwrap(), vec!["print", "$a", "${name}"]);
        // a substituted value is split into words afterwards
        let mut c = ctx(&[("s", "a b")]);
        assert_eq!(words("print ${s}", &mut c).unwrap(), vec!["print", "a", "b"]);
    }

    #[test]
    fn substitution_errors_are_located() {
        let mut sm = SourceMap::new();
        let src = "region box block ${lo} 1";
        let f = sm.add("in.x", src);
        let line = Located::from_source(f, src, 0);
        let e = parse_line(&line, Some(&mut ctx(&[])), None).unwrap_err();
        assert_eq!(sm.location(e.primary_span().unwrap()), "in.x:1:18");
        assert_eq!(sm.snippet(e.primary_span().unwrap()), "${lo}");
        for (src, msg) in [("a ${lo", "unterminated `${`"), ("a $(1+1", "unterminated `$(`"), ("a $(1:%d)", "invalid format"), ("a $", "end of the line")] {
            let line = Located::from_source(f, src, 0);
            let e = parse_line(&line, Some(&mut ctx(&[])), None).unwrap_err();
            assert!(e.message.contains(msg), "{src}: {}", e.message);
        }
    }

    #[test]
    fn substituted_word_points_at_its_reference() {
        let mut sm = SourceMap::new();
        let src = "mass * $(2*v_x)";
        let f = sm.add("in.x", src);
        let mut c = ctx(&[("x", "3")]);
        let line = Located::from_source(f, src, 0);
        let (w, _) = parse_line(&line, Some(&mut c), None).unwrap();
        assert_eq!(w[2].as_str(), "6");
        assert_eq!(sm.snippet(w[2].span), "$(2*v_x)");
    }

    #[test]
    fn progress_lines_like_echo() {
        let mut c = ctx(&[("a", "2")]);
        let line = Located::from_source(FileId(0), "print ${a}b$(v_a*2)", 0);
        let mut seen = vec![];
        let mut p = |s: &str| seen.push(s.to_string());
        parse_line(&line, Some(&mut c), Some(&mut p)).unwrap();
        // lmp -echo screen prints exactly these two lines
        assert_eq!(seen, vec!["print 2b$(v_a*2)", "print 2b4"]);
    }

    #[test]
    fn unicode_spaces_and_quotes_become_ascii() {
        let mut c = ctx(&[]);
        assert_eq!(words("print\u{00A0}\u{201C}a b\u{201D} \u{2212}1", &mut c).unwrap(), vec!["print", "a b", "-1"]);
    }
}
