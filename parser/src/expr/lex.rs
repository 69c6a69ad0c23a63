//! What the formula grammar ([`super::parser`]) and the `if` condition ([`super::boolean`])
//! share: nom's error type for both, the tokens both read (blanks, words, numbers,
//! parentheses), and LAMMPS' conversions of number text (`strtod`, `atof`).
//!
//! Every parser reads a `&str` that is a slice of the whole text, so the byte offset of a
//! piece is `text.offset(piece)` (nom's [`nom::Offset`]).

use nom::branch::alt;
use nom::bytes::complete::{take_till1, take_while, take_while1};
use nom::character::complete::{char, digit0, one_of, satisfy};
use nom::combinator::{opt, recognize};
use nom::error::{ErrorKind, ParseError};
use nom::multi::many0_count;
use nom::sequence::{delimited, pair, terminated, tuple};
use nom::IResult;

use super::ExprError;

/// nom's error for both grammars. `NoMatch` (an `Err::Error`) only steers `alt`, `opt` and the
/// repetitions; what is reported is a `Located` error (an `Err::Failure`, so nothing
/// backtracks past it), built where LAMMPS stops.
#[derive(Debug)]
pub(crate) enum Fail<'t> {
    /// No match at this text.
    NoMatch(&'t str),
    /// Boxed: every parser returns this type, and a small `IResult` is quicker to pass back.
    Located(Box<ExprError>),
}

impl<'t> ParseError<&'t str> for Fail<'t> {
    fn from_error_kind(input: &'t str, _kind: ErrorKind) -> Self {
        Fail::NoMatch(input)
    }
    fn append(_input: &'t str, _kind: ErrorKind, other: Self) -> Self {
        other
    }
}

/// So that `?` on a builder's or a check's `Result<_, ExprError>` stops the parse.
impl From<ExprError> for nom::Err<Fail<'_>> {
    fn from(e: ExprError) -> Self {
        nom::Err::Failure(Fail::Located(Box::new(e)))
    }
}

pub(crate) type PResult<'t, O> = IResult<&'t str, O, Fail<'t>>;

/// Blanks between tokens (C `isspace`: vertical tab and form feed too, which nom's
/// `multispace0` does not take).
pub(crate) fn space(i: &str) -> PResult<'_, &str> {
    take_while(|c| matches!(c, ' ' | '\t' | '\n' | '\r' | '\x0b' | '\x0c'))(i)
}

pub(crate) fn is_word_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// A word: a letter, then letters, digits and underscores.
pub(crate) fn word(i: &str) -> PResult<'_, &str> {
    recognize(pair(satisfy(|c| c.is_ascii_alphabetic()), take_while(is_word_char)))(i)
}

fn is_number_char(c: char) -> bool {
    c.is_ascii_digit() || c == '.'
}

/// `e` or `E`, a sign and digits, as far as they go (LAMMPS' scan; `1e+` is a number).
fn exponent(i: &str) -> PResult<'_, &str> {
    recognize(tuple((one_of("eE"), opt(one_of("+-")), digit0)))(i)
}

/// The text LAMMPS takes as a number: digits and points, then an exponent. Its value is what
/// `strtod` reads from its start ([`strtod_prefix`]), so `1.2.3` is 1.2.
pub(crate) fn number(i: &str) -> PResult<'_, &str> {
    recognize(pair(take_while1(is_number_char), opt(exponent)))(i)
}

/// A minus sign and the number text after it, which may be empty (`-` and `-e5` are read as
/// numbers by the `if` command, and rejected by `strtod`).
pub(crate) fn negative_number(i: &str) -> PResult<'_, &str> {
    recognize(tuple((char('-'), take_while(is_number_char), opt(exponent))))(i)
}

/// Text whose parentheses balance, up to an unmatched `)` or the end (LAMMPS counts
/// parentheses only, whatever lies between them).
pub(crate) fn balanced(i: &str) -> PResult<'_, &str> {
    recognize(many0_count(alt((take_till1(|c| c == '(' || c == ')'), nested))))(i)
}

/// `(`, balanced text, `)`.
pub(crate) fn nested(i: &str) -> PResult<'_, &str> {
    recognize(delimited(char('('), balanced, char(')')))(i)
}

/// The text between the `(` at the start of `i` and its matching `)`. Not a match when `i`
/// does not start with `(`; the error `unclosed` makes when there is no matching `)`.
pub(crate) fn parenthesized<'t>(i: &'t str, unclosed: impl FnOnce() -> ExprError) -> PResult<'t, &'t str> {
    let (inside, _) = char('(')(i)?;
    terminated(balanced, char(')'))(inside).map_err(|_| unclosed().into())
}

/// The value `strtod` reads from the start of `token` (digits, points, exponent), with the
/// checks of C++ `std::stod` that LAMMPS uses: no number at all, overflow and underflow
/// (a result that is not a normal double) are errors (LAMMPS aborts on them).
pub fn strtod_prefix(token: &str) -> Result<f64, String> {
    let b = token.as_bytes();
    let mut i = 0;
    let mut digits = 0;
    let mut nonzero = false;
    let mut scan_digits = |i: &mut usize| {
        while *i < b.len() && b[*i].is_ascii_digit() {
            nonzero |= b[*i] != b'0';
            *i += 1;
            digits += 1;
        }
    };
    scan_digits(&mut i);
    if i < b.len() && b[i] == b'.' {
        i += 1;
        scan_digits(&mut i);
    }
    if digits == 0 {
        return Err(format!("Invalid number `{token}` in variable formula"));
    }
    let mut end = i;
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        let mut j = i + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        let e = j;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        if j > e {
            end = j;
        }
    }
    let text = &token[..end];
    let v: f64 = text.parse().map_err(|_| format!("Invalid number `{token}` in variable formula"))?;
    if v.is_infinite() || (nonzero && !v.is_normal()) {
        return Err(format!("Number `{text}` in variable formula is out of the range of a double"));
    }
    Ok(v)
}

/// C `atof`: the number at the start of `s` after blanks and an optional sign, 0 if none.
pub fn atof(s: &str) -> f64 {
    let t = s.trim_start_matches(|c: char| c.is_ascii_whitespace());
    let (neg, t) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t),
    };
    let v = strtod_prefix(t).unwrap_or(0.0);
    if neg {
        -v
    } else {
        v
    }
}
