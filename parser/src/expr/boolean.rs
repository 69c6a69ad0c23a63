//! The condition of the `if` command (LAMMPS `Variable::evaluate_boolean()`): numbers and
//! bare words, comparisons and logic, no arithmetic. It is computed with LAMMPS' own scheme,
//! an operand stack and an operator stack reduced as operators arrive, so that errors come
//! in the same order as in LAMMPS.

use super::eval::{binary, bool_value};
use super::parser::{is_space, is_word_char, matching_paren, number_end, strtod_prefix};
use super::{BinOp, ExprError};
use crate::context::EvalContext;

const BOOL_SYNTAX: &str = "Invalid Boolean syntax in if command";

/// The condition of an `if` command: numbers (a leading `-` belongs to the number), bare
/// words compared with `==`/`!=`, parentheses, `! == != < <= > >= && || |^`. True when the
/// value is not 0. The context is not consulted (the text was substituted before).
pub fn evaluate_boolean(text: &str, _ctx: &mut dyn EvalContext) -> Result<bool, ExprError> {
    Ok(Stacks::new(text).run(0, text.len())? != 0.0)
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

struct Stacks<'a> {
    text: &'a str,
    b: &'a [u8],
}

impl<'a> Stacks<'a> {
    fn new(text: &'a str) -> Stacks<'a> {
        Stacks { text, b: text.as_bytes() }
    }

    /// Evaluate `text[lo..hi]` (parentheses are evaluated on their own).
    fn run(&self, lo: usize, hi: usize) -> Result<f64, ExprError> {
        let mut args: Vec<Operand> = vec![];
        let mut ops: Vec<(Op, usize)> = vec![];
        let mut expect_operand = true;
        let mut i = lo;
        loop {
            while i < hi && is_space(self.b[i]) {
                i += 1;
            }
            if i < hi && self.starts_operand(self.b[i]) {
                if !expect_operand {
                    return Err(syntax(i, 1));
                }
                expect_operand = false;
                let (operand, next) = self.operand(i, hi)?;
                args.push(operand);
                i = next;
                continue;
            }
            let (op, n) = self.operator(i, hi)?;
            let at = i;
            i += n;
            if op == Some(Op::Not) && expect_operand {
                ops.push((Op::Not, at));
                continue;
            }
            if expect_operand {
                return Err(syntax(at, n));
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
        if !ops.is_empty() || args.len() != 1 {
            return Err(syntax(lo, hi - lo));
        }
        match args.pop() {
            Some((Value::Num(v), _, _)) => Ok(v),
            Some((Value::Word(w), at, len)) => Err(ExprError::new("If command boolean cannot be single string", at, len)
                .with_help(format!("compare the word with == or !=, e.g. \"{w} == ...\""))),
            None => Err(syntax(lo, hi - lo)),
        }
    }

    fn starts_operand(&self, c: u8) -> bool {
        c == b'(' || c.is_ascii_digit() || c == b'.' || c == b'-' || c.is_ascii_alphabetic()
    }

    /// The operand at `i` and the byte after it.
    fn operand(&self, i: usize, hi: usize) -> Result<(Operand, usize), ExprError> {
        let c = self.b[i];
        if c == b'(' {
            let close = matching_paren(self.b, i, hi).ok_or_else(|| syntax(i, 1).with_help("this `(` is never closed"))?;
            let v = self.run(i + 1, close)?;
            return Ok(((Value::Num(v), i, close + 1 - i), close + 1));
        }
        if c.is_ascii_alphabetic() {
            let mut j = i;
            while j < hi && is_word_char(self.b[j]) {
                j += 1;
            }
            return Ok(((Value::Word(self.text[i..j].to_string()), i, j - i), j));
        }
        // a number; its first character (a digit, a point or a minus sign) is always taken
        let j = number_end(self.b, i + 1, hi);
        let token = &self.text[i..j];
        let (neg, digits) = match token.strip_prefix('-') {
            Some(rest) => (true, rest),
            None => (false, token),
        };
        let v = strtod_prefix(digits)
            .map_err(|m| ExprError::new(m.replace("in variable formula", "in if command"), i, j - i))?;
        Ok(((Value::Num(if neg { -v } else { v }), i, j - i), j))
    }

    /// The operator at `i` (`None` at the end) and its length.
    fn operator(&self, i: usize, hi: usize) -> Result<(Option<Op>, usize), ExprError> {
        if i >= hi {
            return Ok((None, 0));
        }
        let next = (i + 1 < hi).then(|| self.b[i + 1]);
        let bin = |op| Ok((Some(Op::Bin(op)), 2));
        match (self.b[i], next) {
            (b'=', Some(b'=')) => bin(BinOp::Eq),
            (b'!', Some(b'=')) => bin(BinOp::Ne),
            (b'!', _) => Ok((Some(Op::Not), 1)),
            (b'<', Some(b'=')) => bin(BinOp::Le),
            (b'<', _) => Ok((Some(Op::Bin(BinOp::Lt)), 1)),
            (b'>', Some(b'=')) => bin(BinOp::Ge),
            (b'>', _) => Ok((Some(Op::Bin(BinOp::Gt)), 1)),
            (b'&', Some(b'&')) => bin(BinOp::And),
            (b'|', Some(b'|')) => bin(BinOp::Or),
            (b'|', Some(b'^')) => bin(BinOp::Xor),
            (b'=', _) => Err(syntax(i, 1).with_help("use `==` to compare")),
            (b'&', _) => Err(syntax(i, 1).with_help("use `&&` for a logical and")),
            (b'|', _) => Err(syntax(i, 1).with_help("use `||` or `|^`")),
            (b'+' | b'*' | b'/' | b'^' | b'%', _) => {
                Err(syntax(i, 1).with_help("an `if` condition has no arithmetic; compute it with $(...)"))
            }
            _ => {
                let len = self.text[i..].chars().next().map(|c| c.len_utf8()).unwrap_or(1);
                Err(syntax(i, len))
            }
        }
    }
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
