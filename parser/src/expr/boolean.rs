//! The condition of the `if` command (LAMMPS `Variable::evaluate_boolean()`): numbers and
//! bare words, comparisons and logic, no arithmetic. Its tokens are read with nom; they are
//! computed with LAMMPS' own scheme, an operand stack and an operator stack reduced as
//! operators arrive, not with a precedence grammar: on a malformed condition such as
//! `1 == 2 ! 3` that scheme pairs values with operators in its own way, and which error
//! LAMMPS reports depends on it.

use nom::branch::alt;
use nom::bytes::complete::tag;
use nom::character::complete::char;
use nom::combinator::{consumed, eof, map, value};
use nom::{Finish, Offset};

use super::eval::{binary, bool_value};
use super::lex::{self, parenthesized, space, strtod_prefix, Fail, PResult};
use super::{BinOp, ExprError};
use crate::context::EvalContext;

const BOOL_SYNTAX: &str = "Invalid Boolean syntax in if command";

/// The condition of an `if` command: numbers (a leading `-` belongs to the number), bare
/// words compared with `==`/`!=`, parentheses, `! == != < <= > >= && || |^`. True when the
/// value is not 0. The context is not consulted (the text was substituted before).
pub fn evaluate_boolean(text: &str, _ctx: &mut dyn EvalContext) -> Result<bool, ExprError> {
    match (Condition { text }).run(text).finish() {
        Ok((_, v)) => Ok(v != 0.0),
        Err(Fail::Located(e)) => Err(*e),
        Err(Fail::NoMatch(at)) => Err(syntax(text.offset(at), 0)),
    }
}

/// An operand: a number or a bare word, with the byte range of its text.
#[derive(Clone, Debug, PartialEq)]
enum Value {
    Num(f64),
    Word(String),
}

type Operand = (Value, usize, usize);

/// An operator on the stack: a binary operator or `!`.
#[derive(Clone, Copy, PartialEq)]
enum Op {
    Bin(BinOp),
    Not,
}

impl Op {
    fn precedence(self) -> u8 {
        match self {
            Op::Bin(b) => b.precedence(),
            Op::Not => 8,
        }
    }
}

fn syntax(at: usize, len: usize) -> ExprError {
    ExprError::new(BOOL_SYNTAX, at, len)
}

/// Reads a condition; knows the whole text, to give byte offsets.
#[derive(Clone, Copy)]
struct Condition<'t> {
    text: &'t str,
}

impl<'t> Condition<'t> {
    fn at(self, i: &str) -> usize {
        self.text.offset(i)
    }

    /// The value of `whole` (the condition, or the inside of parentheses).
    fn run(self, whole: &'t str) -> PResult<'t, f64> {
        let mut args: Vec<Operand> = vec![];
        let mut ops: Vec<(Op, usize)> = vec![];
        let mut expect_operand = true;
        let mut i = whole;
        loop {
            (i, _) = space(i)?;
            if i.starts_with(|c: char| c == '(' || c == '-' || c == '.' || c.is_ascii_alphanumeric()) {
                if !expect_operand {
                    return Err(syntax(self.at(i), 1).into());
                }
                expect_operand = false;
                let (rest, operand) = self.operand(i)?;
                args.push(operand);
                i = rest;
                continue;
            }
            let (rest, op) = self.operator(i)?;
            let (at, n) = (self.at(i), i.len() - rest.len());
            i = rest;
            if op == Some(Op::Not) && expect_operand {
                ops.push((Op::Not, at));
                continue;
            }
            if expect_operand {
                return Err(syntax(at, n).into());
            }
            expect_operand = true;
            // finish the operations that bind at least as tightly as this one
            let prec = op.map(|o| o.precedence()).unwrap_or(0);
            while let Some(&(top, top_at)) = ops.last() {
                if top.precedence() < prec {
                    break;
                }
                ops.pop();
                reduce(top, top_at, &mut args)?;
            }
            match op {
                None => break,
                Some(o) => ops.push((o, at)),
            }
        }
        let (lo, len) = (self.at(whole), whole.len());
        if !ops.is_empty() || args.len() != 1 {
            return Err(syntax(lo, len).into());
        }
        match args.pop() {
            Some((Value::Num(v), _, _)) => Ok((i, v)),
            Some((Value::Word(w), at, len)) => Err(ExprError::new("If command boolean cannot be single string", at, len)
                .with_help(format!("compare the word with == or !=, e.g. \"{w} == ...\""))
                .into()),
            None => Err(syntax(lo, len).into()),
        }
    }

    /// The operand at the start of `i` (which starts with `(`, `-`, `.`, a digit or a letter),
    /// with its byte range.
    fn operand(self, i: &'t str) -> PResult<'t, Operand> {
        let (rest, (text, v)) = consumed(alt((
            |i| self.group(i),
            map(lex::word, |w: &str| Value::Word(w.to_string())),
            |i| self.number(i),
        )))(i)?;
        Ok((rest, (v, self.at(text), text.len())))
    }

    /// Parentheses: the value of the condition inside.
    fn group(self, i: &'t str) -> PResult<'t, Value> {
        let (rest, inside) = parenthesized(i, || syntax(self.at(i), 1).with_help("this `(` is never closed"))?;
        let (_, v) = self.run(inside)?;
        Ok((rest, Value::Num(v)))
    }

    /// A number; a leading `-` belongs to it.
    fn number(self, i: &'t str) -> PResult<'t, Value> {
        let (rest, token) = alt((lex::number, lex::negative_number))(i)?;
        let (neg, digits) = match token.strip_prefix('-') {
            Some(digits) => (true, digits),
            None => (false, token),
        };
        let v = strtod_prefix(digits)
            .map_err(|m| ExprError::new(m.replace("in variable formula", "in if command"), self.at(i), token.len()))?;
        Ok((rest, Value::Num(if neg { -v } else { v })))
    }

    /// The operator at the start of `i`, `None` at the end.
    fn operator(self, i: &'t str) -> PResult<'t, Option<Op>> {
        alt((value(None, eof), map(condition_op, Some), |i| Err(self.bad_operator(i).into())))(i)
    }

    fn bad_operator(self, i: &str) -> ExprError {
        let at = self.at(i);
        match i.as_bytes()[0] {
            b'=' => syntax(at, 1).with_help("use `==` to compare"),
            b'&' => syntax(at, 1).with_help("use `&&` for a logical and"),
            b'|' => syntax(at, 1).with_help("use `||` or `|^`"),
            b'+' | b'*' | b'/' | b'^' | b'%' => {
                syntax(at, 1).with_help("an `if` condition has no arithmetic; compute it with $(...)")
            }
            _ => syntax(at, i.chars().next().map_or(1, char::len_utf8)),
        }
    }
}

/// The operators of a condition (`<` and `>` after `<=` and `>=`).
fn condition_op(i: &str) -> PResult<'_, Op> {
    alt((
        value(Op::Bin(BinOp::Eq), tag("==")),
        value(Op::Bin(BinOp::Ne), tag("!=")),
        value(Op::Not, char('!')),
        value(Op::Bin(BinOp::Le), tag("<=")),
        value(Op::Bin(BinOp::Lt), char('<')),
        value(Op::Bin(BinOp::Ge), tag(">=")),
        value(Op::Bin(BinOp::Gt), char('>')),
        value(Op::Bin(BinOp::And), tag("&&")),
        value(Op::Bin(BinOp::Or), tag("||")),
        value(Op::Bin(BinOp::Xor), tag("|^")),
    ))(i)
}

/// Apply the operator on top of the stack to its operands.
fn reduce(op: Op, at: usize, args: &mut Vec<Operand>) -> Result<(), ExprError> {
    let (b, bat, blen) = args.pop().ok_or_else(|| syntax(at, 1))?;
    let end = bat + blen;
    let Op::Bin(bin) = op else {
        return match b {
            Value::Num(v) => {
                args.push((Value::Num(bool_value(v == 0.0)), at, end - at));
                Ok(())
            }
            Value::Word(_) => Err(ExprError::new("If command boolean not cannot operate on string", at, end - at)),
        };
    };
    let (a, aat, _) = args.pop().ok_or_else(|| syntax(at, 1))?;
    let (lo, len) = (aat, end - aat);
    let equality = matches!(bin, BinOp::Eq | BinOp::Ne);
    let value = match (&a, &b) {
        (Value::Num(x), Value::Num(y)) => binary(bin, *x, *y).unwrap_or(0.0),
        (Value::Word(x), Value::Word(y)) if equality => bool_value((x == y) == (bin == BinOp::Eq)),
        _ if equality => return Err(ExprError::new("If command boolean is comparing string to number", lo, len)),
        _ => {
            return Err(ExprError::new("If command boolean can only operate on numbers", lo, len)
                .with_help("words can only be compared with == and !="))
        }
    };
    args.push((Value::Num(value), lo, len));
    Ok(())
}
