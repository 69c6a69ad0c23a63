//! PLACEHOLDER (parser-script helper): a small equal-style expression evaluator (numbers,
//! `v_name`, thermo keywords, + - * / ^ %, comparisons, && ||, a few functions) so the
//! interpreter compiles and its tests run. The parser-expr helper's expr.rs replaces this file.

use crate::context::EvalContext;

/// An evaluation error located by a byte range in the expression text.
#[derive(Clone, Debug, PartialEq)]
pub struct ExprError {
    pub message: String,
    pub offset: usize,
    pub len: usize,
}

fn err<T>(message: impl Into<String>, offset: usize, len: usize) -> Result<T, ExprError> {
    Err(ExprError { message: message.into(), offset, len })
}

/// Evaluate an equal-style formula.
pub fn evaluate(text: &str, ctx: &mut dyn EvalContext) -> Result<f64, ExprError> {
    let mut p = P { s: text.as_bytes(), i: 0, ctx };
    let v = p.expr(0)?;
    p.ws();
    if p.i < p.s.len() {
        return err("invalid syntax in variable formula", p.i, p.s.len() - p.i);
    }
    Ok(v)
}

/// LAMMPS' `if` boolean: numbers compared numerically, other words compared as strings
/// with `==` and `!=`.
pub fn evaluate_boolean(text: &str, ctx: &mut dyn EvalContext) -> Result<bool, ExprError> {
    let _ = ctx;
    let toks = bool_tokens(text)?;
    let mut k = 0;
    let v = bool_or(&toks, &mut k)?;
    if k < toks.len() {
        return err("invalid Boolean syntax in if command", toks[k].1, toks[k].0.len());
    }
    Ok(v.num() != 0.0)
}

struct P<'a> {
    s: &'a [u8],
    i: usize,
    ctx: &'a mut dyn EvalContext,
}

fn binop(op: &str) -> Option<(u8, bool)> {
    // (precedence, right associative)
    Some(match op {
        "||" | "|^" => (1, false),
        "&&" => (2, false),
        "==" | "!=" => (3, false),
        "<" | "<=" | ">" | ">=" => (4, false),
        "+" | "-" => (5, false),
        "*" | "/" | "%" => (6, false),
        "^" => (8, true),
        _ => return None,
    })
}

impl P<'_> {
    fn ws(&mut self) {
        while self.i < self.s.len() && (self.s[self.i] as char).is_whitespace() {
            self.i += 1;
        }
    }
    fn peek_op(&mut self) -> Option<&'static str> {
        self.ws();
        let rest = &self.s[self.i..];
        ["||", "|^", "&&", "==", "!=", "<=", ">=", "<", ">", "+", "-", "*", "/", "%", "^"]
            .into_iter()
            .find(|op| rest.starts_with(op.as_bytes()))
    }
    fn expr(&mut self, min: u8) -> Result<f64, ExprError> {
        let mut lhs = self.unary()?;
        while let Some(op) = self.peek_op() {
            let (prec, right) = binop(op).unwrap();
            if prec < min {
                break;
            }
            let at = self.i;
            self.i += op.len();
            let rhs = self.expr(if right { prec } else { prec + 1 })?;
            lhs = match op {
                "+" => lhs + rhs,
                "-" => lhs - rhs,
                "*" => lhs * rhs,
                "/" => {
                    if rhs == 0.0 {
                        return err("divide by 0 in variable formula", at, 1);
                    }
                    lhs / rhs
                }
                "%" => lhs % rhs,
                "^" => lhs.powf(rhs),
                "<" => (lhs < rhs) as i32 as f64,
                "<=" => (lhs <= rhs) as i32 as f64,
                ">" => (lhs > rhs) as i32 as f64,
                ">=" => (lhs >= rhs) as i32 as f64,
                "==" => (lhs == rhs) as i32 as f64,
                "!=" => (lhs != rhs) as i32 as f64,
                "&&" => (lhs != 0.0 && rhs != 0.0) as i32 as f64,
                "||" => (lhs != 0.0 || rhs != 0.0) as i32 as f64,
                _ => ((lhs == 0.0) != (rhs == 0.0)) as i32 as f64,
            };
        }
        Ok(lhs)
    }
    fn unary(&mut self) -> Result<f64, ExprError> {
        self.ws();
        match self.s.get(self.i) {
            Some(b'-') => {
                self.i += 1;
                Ok(-self.expr(7)?)
            }
            Some(b'!') => {
                self.i += 1;
                Ok((self.expr(7)? == 0.0) as i32 as f64)
            }
            _ => self.atom(),
        }
    }
    fn atom(&mut self) -> Result<f64, ExprError> {
        self.ws();
        let start = self.i;
        let Some(&c) = self.s.get(self.i) else {
            return err("invalid syntax in variable formula", start, 0);
        };
        if c == b'(' {
            self.i += 1;
            let v = self.expr(0)?;
            self.ws();
            if self.s.get(self.i) != Some(&b')') {
                return err("missing ) in variable formula", start, 1);
            }
            self.i += 1;
            return Ok(v);
        }
        if c.is_ascii_digit() || c == b'.' {
            while self.i < self.s.len() && (self.s[self.i].is_ascii_digit() || self.s[self.i] == b'.') {
                self.i += 1;
            }
            if self.i < self.s.len() && (self.s[self.i] == b'e' || self.s[self.i] == b'E') {
                self.i += 1;
                if self.i < self.s.len() && (self.s[self.i] == b'+' || self.s[self.i] == b'-') {
                    self.i += 1;
                }
                while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                    self.i += 1;
                }
            }
            let t = std::str::from_utf8(&self.s[start..self.i]).unwrap_or("");
            return t.parse().or_else(|_| err(format!("invalid number `{t}`"), start, self.i - start));
        }
        if c.is_ascii_alphabetic() || c == b'_' {
            while self.i < self.s.len() && (self.s[self.i].is_ascii_alphanumeric() || self.s[self.i] == b'_') {
                self.i += 1;
            }
            let name = std::str::from_utf8(&self.s[start..self.i]).unwrap_or("").to_string();
            let len = self.i - start;
            self.ws();
            if self.s.get(self.i) == Some(&b'(') {
                self.i += 1;
                let a = self.expr(0)?;
                self.ws();
                if self.s.get(self.i) != Some(&b')') {
                    return err("missing ) in function", start, len);
                }
                self.i += 1;
                return Ok(match name.as_str() {
                    "sqrt" => {
                        if a < 0.0 {
                            return err("sqrt of negative value in variable formula", start, len);
                        }
                        a.sqrt()
                    }
                    "exp" => a.exp(),
                    "ln" => a.ln(),
                    "abs" => a.abs(),
                    "sin" => a.sin(),
                    "cos" => a.cos(),
                    "floor" => a.floor(),
                    "ceil" => a.ceil(),
                    _ => return err(format!("unknown function `{name}`"), start, len),
                });
            }
            if let Some(var) = name.strip_prefix("v_") {
                return match crate::variables::numeric_value(self.ctx, var) {
                    Ok(v) => Ok(v),
                    Err(m) => err(m, start, len),
                };
            }
            if name == "PI" {
                return Ok(std::f64::consts::PI);
            }
            return match self.ctx.thermo_keyword(&name) {
                Some(Ok(v)) => Ok(v),
                Some(Err(m)) => err(m, start, len),
                None => err(format!("invalid thermo keyword `{name}` in variable formula"), start, len),
            };
        }
        err("invalid syntax in variable formula", start, 1)
    }
}

#[derive(Clone, Debug)]
enum BVal {
    Num(f64),
    Str(String),
}
impl BVal {
    fn num(&self) -> f64 {
        match self {
            BVal::Num(x) => *x,
            BVal::Str(_) => 0.0,
        }
    }
}

fn bool_tokens(text: &str) -> Result<Vec<(String, usize)>, ExprError> {
    let b = text.as_bytes();
    let mut out = vec![];
    let mut i = 0;
    while i < b.len() {
        if (b[i] as char).is_whitespace() {
            i += 1;
            continue;
        }
        let two = if i + 1 < b.len() { &text[i..i + 2] } else { "" };
        if ["==", "!=", "<=", ">=", "&&", "||", "|^"].contains(&two) {
            out.push((two.to_string(), i));
            i += 2;
        } else if b"()<>!".contains(&b[i]) {
            out.push((text[i..i + 1].to_string(), i));
            i += 1;
        } else {
            let s = i;
            while i < b.len() && !(b[i] as char).is_whitespace() && !b"()<>!=&|".contains(&b[i]) {
                i += 1;
            }
            if s == i {
                return err("invalid Boolean syntax in if command", s, 1);
            }
            out.push((text[s..i].to_string(), s));
        }
    }
    Ok(out)
}

fn bool_or(t: &[(String, usize)], k: &mut usize) -> Result<BVal, ExprError> {
    let mut l = bool_and(t, k)?;
    while *k < t.len() && (t[*k].0 == "||" || t[*k].0 == "|^") {
        let op = t[*k].0.clone();
        *k += 1;
        let r = bool_and(t, k)?;
        let (a, b) = (l.num() != 0.0, r.num() != 0.0);
        l = BVal::Num(if op == "||" { (a || b) as i32 as f64 } else { (a != b) as i32 as f64 });
    }
    Ok(l)
}
fn bool_and(t: &[(String, usize)], k: &mut usize) -> Result<BVal, ExprError> {
    let mut l = bool_cmp(t, k)?;
    while *k < t.len() && t[*k].0 == "&&" {
        *k += 1;
        let r = bool_cmp(t, k)?;
        l = BVal::Num((l.num() != 0.0 && r.num() != 0.0) as i32 as f64);
    }
    Ok(l)
}
fn bool_cmp(t: &[(String, usize)], k: &mut usize) -> Result<BVal, ExprError> {
    let l = bool_atom(t, k)?;
    if *k < t.len() && ["==", "!=", "<", "<=", ">", ">="].contains(&t[*k].0.as_str()) {
        let (op, at) = t[*k].clone();
        *k += 1;
        let r = bool_atom(t, k)?;
        let v = match (&l, &r) {
            (BVal::Num(a), BVal::Num(b)) => match op.as_str() {
                "==" => a == b,
                "!=" => a != b,
                "<" => a < b,
                "<=" => a <= b,
                ">" => a > b,
                _ => a >= b,
            },
            _ => {
                let (a, b) = (bval_str(&l), bval_str(&r));
                match op.as_str() {
                    "==" => a == b,
                    "!=" => a != b,
                    _ => return err("if command: string comparison needs == or !=", at, op.len()),
                }
            }
        };
        return Ok(BVal::Num(v as i32 as f64));
    }
    Ok(l)
}
fn bval_str(v: &BVal) -> String {
    match v {
        BVal::Num(x) => x.to_string(),
        BVal::Str(s) => s.clone(),
    }
}
fn bool_atom(t: &[(String, usize)], k: &mut usize) -> Result<BVal, ExprError> {
    let Some((tok, at)) = t.get(*k).cloned() else {
        return err("invalid Boolean syntax in if command", t.last().map(|x| x.1).unwrap_or(0), 0);
    };
    *k += 1;
    match tok.as_str() {
        "(" => {
            let v = bool_or(t, k)?;
            if t.get(*k).map(|x| x.0.as_str()) != Some(")") {
                return err("missing ) in if command", at, 1);
            }
            *k += 1;
            Ok(v)
        }
        "!" => Ok(BVal::Num((bool_atom(t, k)?.num() == 0.0) as i32 as f64)),
        _ => Ok(match tok.parse::<f64>() {
            Ok(x) if crate::args::is_lammps_float(&tok) => BVal::Num(x),
            _ => BVal::Str(tok),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::variables::Variables;
    struct C(Variables);
    impl EvalContext for C {
        fn variables(&mut self) -> &mut Variables {
            &mut self.0
        }
    }
    #[test]
    fn arithmetic() {
        let mut c = C(Variables::default());
        assert_eq!(evaluate("-3.5*0.01", &mut c).unwrap(), -3.5 * 0.01);
        assert_eq!(evaluate("2^3^2", &mut c).unwrap(), 512.0);
        assert!(evaluate_boolean("abc == abc", &mut c).unwrap());
        assert!(!evaluate_boolean("1 > 2 || 0", &mut c).unwrap());
    }
}
