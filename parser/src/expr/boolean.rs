//! The condition of the `if` command (LAMMPS `Variable::evaluate_boolean()`): numbers and
//! bare words, comparisons and logic, no arithmetic. It is computed with LAMMPS' own scheme
//! (operator and operand stacks, reducing as operators arrive) so that errors come in the
//! same order.

use super::eval::{binary, bool_value};
use super::parser::{is_space, is_word_char, strtod_prefix};
use super::{BinOp, ExprError};
use crate::context::EvalContext;

/// An operand of a Boolean expression: a number or a bare word.
#[derive(Clone, Debug, PartialEq)]
enum BoolArg {
    Num(f64),
    Str(String),
}

/// The condition of an `if` command, as LAMMPS `Variable::evaluate_boolean()`: numbers
/// (a leading `-` is part of the number), bare words compared with `==`/`!=`, parentheses,
/// `! == != < <= > >= && || |^`; no arithmetic. True when the value is not 0.
/// The context is not consulted (the text is substituted before).
pub fn evaluate_boolean(text: &str, _ctx: &mut dyn EvalContext) -> Result<bool, ExprError> {
    Ok(boolean(text, 0, text.len())? != 0.0)
}

const BOOL_SYNTAX: &str = "Invalid Boolean syntax in if command";

/// An operator on the stack: a binary operator or `!`.
#[derive(Clone, Copy, PartialEq)]
enum BoolOp {
    Bin(BinOp),
    Not,
}

impl BoolOp {
    fn precedence(self) -> u8 {
        match self {
            BoolOp::Bin(b) => b.precedence(),
            BoolOp::Not => 8,
        }
    }
}

/// Evaluate `text[lo..hi]` with LAMMPS' operator-precedence stacks, reducing as operators
/// arrive, so errors come in the same order as in LAMMPS.
fn boolean(text: &str, lo: usize, hi: usize) -> Result<f64, ExprError> {
    let b = text.as_bytes();
    let mut args: Vec<(BoolArg, usize, usize)> = vec![];
    let mut ops: Vec<(BoolOp, usize)> = vec![];
    let mut expect_arg = true;
    let mut i = lo;
    let syntax = |at: usize, len: usize| ExprError::new(BOOL_SYNTAX, at, len);
    loop {
        let c = if i < hi { Some(b[i]) } else { None };
        match c {
            Some(c) if is_space(c) => {
                i += 1;
                continue;
            }
            Some(b'(') => {
                if !expect_arg {
                    return Err(syntax(i, 1));
                }
                expect_arg = false;
                let mut level = 0;
                let mut close = None;
                for j in i + 1..hi {
                    match b[j] {
                        b'(' => level += 1,
                        b')' if level > 0 => level -= 1,
                        b')' => {
                            close = Some(j);
                            break;
                        }
                        _ => {}
                    }
                }
                let Some(close) = close else {
                    return Err(syntax(i, 1).with_help("this `(` is never closed"));
                };
                let v = boolean(text, i + 1, close)?;
                args.push((BoolArg::Num(v), i, close + 1 - i));
                i = close + 1;
                continue;
            }
            Some(c) if c.is_ascii_digit() || c == b'.' || c == b'-' => {
                if !expect_arg {
                    return Err(syntax(i, 1));
                }
                expect_arg = false;
                let start = i;
                i += 1;
                while i < hi && (b[i].is_ascii_digit() || b[i] == b'.') {
                    i += 1;
                }
                if i < hi && (b[i] == b'e' || b[i] == b'E') {
                    i += 1;
                    if i < hi && (b[i] == b'+' || b[i] == b'-') {
                        i += 1;
                    }
                    while i < hi && b[i].is_ascii_digit() {
                        i += 1;
                    }
                }
                let token = &text[start..i];
                let (neg, digits) = match token.strip_prefix('-') {
                    Some(rest) => (true, rest),
                    None => (false, token),
                };
                let v = strtod_prefix(digits).map_err(|m| {
                    ExprError::new(m.replace("in variable formula", "in if command"), start, i - start)
                })?;
                args.push((BoolArg::Num(if neg { -v } else { v }), start, i - start));
                continue;
            }
            Some(c) if c.is_ascii_alphabetic() => {
                if !expect_arg {
                    return Err(syntax(i, 1));
                }
                expect_arg = false;
                let start = i;
                while i < hi && is_word_char(b[i]) {
                    i += 1;
                }
                args.push((BoolArg::Str(text[start..i].to_string()), start, i - start));
                continue;
            }
            _ => {}
        }
        // an operator or the end
        let at = i;
        let next = if i + 1 < hi { Some(b[i + 1]) } else { None };
        let (op, n): (Option<BoolOp>, usize) = match c {
            None => (None, 0),
            Some(b'=') if next == Some(b'=') => (Some(BoolOp::Bin(BinOp::Eq)), 2),
            Some(b'!') if next == Some(b'=') => (Some(BoolOp::Bin(BinOp::Ne)), 2),
            Some(b'!') => (Some(BoolOp::Not), 1),
            Some(b'<') if next == Some(b'=') => (Some(BoolOp::Bin(BinOp::Le)), 2),
            Some(b'<') => (Some(BoolOp::Bin(BinOp::Lt)), 1),
            Some(b'>') if next == Some(b'=') => (Some(BoolOp::Bin(BinOp::Ge)), 2),
            Some(b'>') => (Some(BoolOp::Bin(BinOp::Gt)), 1),
            Some(b'&') if next == Some(b'&') => (Some(BoolOp::Bin(BinOp::And)), 2),
            Some(b'|') if next == Some(b'|') => (Some(BoolOp::Bin(BinOp::Or)), 2),
            Some(b'|') if next == Some(b'^') => (Some(BoolOp::Bin(BinOp::Xor)), 2),
            Some(b'=') => return Err(syntax(at, 1).with_help("use `==` to compare")),
            Some(b'&') => return Err(syntax(at, 1).with_help("use `&&` for a logical and")),
            Some(b'|') => return Err(syntax(at, 1).with_help("use `||` or `|^`")),
            Some(b'+' | b'*' | b'/' | b'^' | b'%') => {
                return Err(syntax(at, 1).with_help("an `if` condition has no arithmetic; compute it with $(...)"));
            }
            Some(_) => {
                let len = text[at..].chars().next().map(|c| c.len_utf8()).unwrap_or(1);
                return Err(syntax(at, len));
            }
        };
        i += n;
        if op == Some(BoolOp::Not) && expect_arg {
            ops.push((BoolOp::Not, at));
            continue;
        }
        if expect_arg {
            return Err(syntax(at, n));
        }
        expect_arg = true;
        let prec = op.map(|o| o.precedence()).unwrap_or(0);
        while let Some(&(top, top_at)) = ops.last() {
            if top.precedence() < prec {
                break;
            }
            ops.pop();
            reduce_boolean(top, top_at, &mut args)?;
        }
        match op {
            None => break,
            Some(o) => ops.push((o, at)),
        }
    }
    if !ops.is_empty() || args.len() != 1 {
        return Err(syntax(lo, hi - lo));
    }
    match args.pop() {
        Some((BoolArg::Num(v), _, _)) => Ok(v),
        Some((BoolArg::Str(s), at, len)) => Err(ExprError::new("If command boolean cannot be single string", at, len)
            .with_help(format!("compare the word with == or !=, e.g. \"{s} == ...\""))),
        None => Err(syntax(lo, hi - lo)),
    }
}

fn reduce_boolean(op: BoolOp, at: usize, args: &mut Vec<(BoolArg, usize, usize)>) -> Result<(), ExprError> {
    let syntax = || ExprError::new(BOOL_SYNTAX, at, 1);
    let (b, bat, blen) = args.pop().ok_or_else(syntax)?;
    let result = match op {
        BoolOp::Not => match b {
            BoolArg::Num(v) => {
                args.push((BoolArg::Num(bool_value(v == 0.0)), at, bat + blen - at));
                return Ok(());
            }
            BoolArg::Str(_) => return Err(ExprError::new("If command boolean not cannot operate on string", at, bat + blen - at)),
        },
        BoolOp::Bin(bin) => {
            let (a, aat, _) = args.pop().ok_or_else(syntax)?;
            let range = (aat, bat + blen - aat);
            let value = match (bin, &a, &b) {
                (BinOp::Eq | BinOp::Ne, BoolArg::Str(x), BoolArg::Str(y)) => bool_value((x == y) == (bin == BinOp::Eq)),
                (BinOp::Eq | BinOp::Ne, BoolArg::Num(_), BoolArg::Str(_))
                | (BinOp::Eq | BinOp::Ne, BoolArg::Str(_), BoolArg::Num(_)) => {
                    return Err(ExprError::new("If command boolean is comparing string to number", range.0, range.1));
                }
                (_, BoolArg::Num(x), BoolArg::Num(y)) => binary(bin, *x, *y).unwrap_or(0.0),
                _ => {
                    return Err(ExprError::new("If command boolean can only operate on numbers", range.0, range.1)
                        .with_help("words can only be compared with == and !="));
                }
            };
            (BoolArg::Num(value), range)
        }
    };
    args.push((result.0, result.1 .0, result.1 .1));
    Ok(())
}
