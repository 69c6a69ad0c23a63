//! The formula grammar, written once and used two ways through [`Build`]: to make a tree
//! ([`TreeBuilder`]) and to compute a value while reading ([`super::eval::Evaluator`]).
//!
//! LAMMPS computes while it parses, so the first error it meets (a syntax error, a division
//! by zero, an unknown keyword) is the one it reports, and the unused branch of `ternary()`
//! is never read. Computing through the parser reproduces that order exactly; the tree keeps
//! the same structure for later walks.

use super::{BinOp, Expr, ExprError, Index, MathFn, Node, UnOp, ATOM_VECTORS, CONSTANTS, MATH_FUNCTIONS};

const SYNTAX: &str = "Invalid syntax in variable formula";

/// LAMMPS `MAXFUNCARG`: at most this many arguments in a function call.
const MAX_FUNC_ARGS: usize = 6;

/// What the parser makes of each piece. Every method gets the byte range of its text.
pub(crate) trait Build {
    type Out;
    /// An operand that is not an operation or a math function (a number, `v_name`, `c_ID`,
    /// a thermo keyword, a group function, ...).
    fn leaf(&mut self, e: Expr) -> Result<Self::Out, ExprError>;
    fn unary(&mut self, op: UnOp, arg: Self::Out, offset: usize, len: usize) -> Result<Self::Out, ExprError>;
    fn binary(&mut self, op: BinOp, a: Self::Out, b: Self::Out, offset: usize, len: usize) -> Result<Self::Out, ExprError>;
    /// A math function; `args` are the byte ranges of its arguments, read with
    /// [`Parser::arg`] in the order (and as far) the builder wants.
    fn math(&mut self, p: &Parser, f: MathFn, args: &[(usize, usize)], offset: usize, len: usize) -> Result<Self::Out, ExprError>
    where
        Self: Sized;
}

/// Builds the formula tree.
pub(crate) struct TreeBuilder;

impl Build for TreeBuilder {
    type Out = Expr;
    fn leaf(&mut self, e: Expr) -> Result<Expr, ExprError> {
        Ok(e)
    }
    fn unary(&mut self, op: UnOp, arg: Expr, offset: usize, len: usize) -> Result<Expr, ExprError> {
        Ok(Expr { node: Node::Unary(op, Box::new(arg)), offset, len })
    }
    fn binary(&mut self, op: BinOp, a: Expr, b: Expr, offset: usize, len: usize) -> Result<Expr, ExprError> {
        Ok(Expr { node: Node::Binary(op, Box::new(a), Box::new(b)), offset, len })
    }
    fn math(&mut self, p: &Parser, f: MathFn, args: &[(usize, usize)], offset: usize, len: usize) -> Result<Expr, ExprError> {
        let mut parsed = Vec::with_capacity(args.len());
        for &r in args {
            parsed.push(p.arg(self, r)?);
        }
        Ok(Expr { node: Node::Math(f, parsed), offset, len })
    }
}

/// A value with the byte range of its text.
type Spanned<T> = (T, usize, usize);

pub(crate) struct Parser<'a> {
    text: &'a str,
    b: &'a [u8],
    pos: usize,
    /// End of the part being read (the inside of parentheses and each function argument is
    /// read on its own, as in LAMMPS).
    end: usize,
}

pub(crate) fn is_space(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\n' | b'\r' | 0x0b | 0x0c)
}
pub(crate) fn is_word_char(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

impl<'a> Parser<'a> {
    pub(crate) fn new(text: &'a str) -> Parser<'a> {
        Parser { text, b: text.as_bytes(), pos: 0, end: text.len() }
    }

    /// Read the whole text as one formula.
    pub(crate) fn whole<B: Build>(&mut self, bld: &mut B) -> Result<B::Out, ExprError> {
        let (v, _, _) = self.binary(bld, 1)?;
        self.skip_space();
        if self.pos < self.end {
            return Err(self.operator_error());
        }
        Ok(v)
    }

    /// Read one function argument (a byte range of the text) as a formula.
    pub(crate) fn arg<B: Build>(&self, bld: &mut B, (lo, hi): (usize, usize)) -> Result<B::Out, ExprError> {
        let mut p = Parser { text: self.text, b: self.b, pos: lo, end: hi };
        p.whole(bld)
    }

    fn peek(&self) -> Option<u8> {
        (self.pos < self.end).then(|| self.b[self.pos])
    }
    fn peek_at(&self, k: usize) -> Option<u8> {
        (self.pos + k < self.end).then(|| self.b[self.pos + k])
    }
    fn skip_space(&mut self) {
        while matches!(self.peek(), Some(c) if is_space(c)) {
            self.pos += 1;
        }
    }
    fn syntax_at(&self, offset: usize, len: usize) -> ExprError {
        ExprError::new(SYNTAX, offset, len)
    }
    /// A syntax error at the current character (or at the end).
    fn syntax_here(&self) -> ExprError {
        let Some(c) = self.peek() else {
            return self.syntax_at(self.end, 0).with_help("the formula ends where an operand is expected");
        };
        let len = self.text[self.pos..].chars().next().map(|ch| ch.len_utf8()).unwrap_or(1);
        let e = self.syntax_at(self.pos, len);
        match c {
            b'+' => e.with_help("LAMMPS formulas have no unary `+`"),
            b',' => e.with_help("a comma separates the arguments of a function only"),
            b')' => e.with_help("this `)` has no matching `(`"),
            b'"' | b'\'' => e.with_help("quotes are not part of a formula"),
            _ => e,
        }
    }
    /// Where an operator was expected but something else was found.
    fn operator_error(&self) -> ExprError {
        let e = self.syntax_here();
        match self.peek() {
            Some(c) if c.is_ascii_alphanumeric() || c == b'.' || c == b'(' => {
                e.with_help("an operator is missing between two operands")
            }
            _ => e,
        }
    }

    /// Left-associative binary operators of precedence >= `min`.
    fn binary<B: Build>(&mut self, bld: &mut B, min: u8) -> Result<Spanned<B::Out>, ExprError> {
        let (mut lhs, lo, mut hi) = self.unary(bld)?;
        loop {
            self.skip_space();
            if self.pos >= self.end {
                break;
            }
            // LAMMPS reports a bad operator as soon as it reads it, before finishing the
            // operations to its left
            let (op, n) = self.binary_op()?;
            if op.precedence() < min {
                break;
            }
            self.pos += n;
            let (rhs, _, rhi) = self.binary(bld, op.precedence() + 1)?;
            hi = rhi;
            lhs = bld.binary(op, lhs, rhs, lo, hi - lo)?;
        }
        Ok((lhs, lo, hi))
    }

    /// The binary operator at `pos` and its length, without consuming it.
    fn binary_op(&self) -> Result<(BinOp, usize), ExprError> {
        let c = self.peek().unwrap_or(0);
        let next = self.peek_at(1);
        Ok(match c {
            b'+' => (BinOp::Add, 1),
            b'-' => (BinOp::Sub, 1),
            b'*' => (BinOp::Mul, 1),
            b'/' => (BinOp::Div, 1),
            b'%' => (BinOp::Mod, 1),
            b'^' => (BinOp::Pow, 1),
            b'=' if next == Some(b'=') => (BinOp::Eq, 2),
            b'!' if next == Some(b'=') => (BinOp::Ne, 2),
            b'<' if next == Some(b'=') => (BinOp::Le, 2),
            b'<' => (BinOp::Lt, 1),
            b'>' if next == Some(b'=') => (BinOp::Ge, 2),
            b'>' => (BinOp::Gt, 1),
            b'&' if next == Some(b'&') => (BinOp::And, 2),
            b'|' if next == Some(b'|') => (BinOp::Or, 2),
            b'|' if next == Some(b'^') => (BinOp::Xor, 2),
            b'=' => return Err(self.syntax_at(self.pos, 1).with_help("use `==` to compare two values")),
            b'!' => return Err(self.syntax_at(self.pos, 1).with_help("`!` negates the operand that follows it")),
            b'&' => return Err(self.syntax_at(self.pos, 1).with_help("use `&&` for a logical and")),
            b'|' => return Err(self.syntax_at(self.pos, 1).with_help("use `||` for a logical or, `|^` for exclusive or")),
            _ => return Err(self.operator_error()),
        })
    }

    /// Unary `-` and `!` apply to the operand right after them (they bind tighter than `^`).
    fn unary<B: Build>(&mut self, bld: &mut B) -> Result<Spanned<B::Out>, ExprError> {
        self.skip_space();
        let start = self.pos;
        let op = match (self.peek(), self.peek_at(1)) {
            (Some(b'-'), _) => UnOp::Neg,
            (Some(b'!'), n) if n != Some(b'=') => UnOp::Not,
            _ => return self.primary(bld),
        };
        self.pos += 1;
        let (arg, _, hi) = self.unary(bld)?;
        Ok((bld.unary(op, arg, start, hi - start)?, start, hi))
    }

    fn primary<B: Build>(&mut self, bld: &mut B) -> Result<Spanned<B::Out>, ExprError> {
        let start = self.pos;
        match self.peek() {
            Some(b'(') => {
                let close = self.matching_paren(start)?;
                let inner = self.arg(bld, (start + 1, close))?;
                self.pos = close + 1;
                Ok((inner, start, close + 1))
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => {
                let e = self.number()?;
                let hi = e.offset + e.len;
                Ok((bld.leaf(e)?, start, hi))
            }
            Some(c) if c.is_ascii_alphabetic() => self.word(bld),
            _ => Err(self.syntax_here()),
        }
    }

    /// The `)` matching the `(` at `open`.
    fn matching_paren(&self, open: usize) -> Result<usize, ExprError> {
        matching_paren(self.b, open, self.end)
            .ok_or_else(|| self.syntax_at(open, 1).with_help("this `(` is never closed"))
    }

    /// A number: digits and points, then an optional exponent; the value is what `strtod`
    /// reads from the start of that text (LAMMPS ignores the rest, so `1.2.3` is 1.2).
    fn number(&mut self) -> Result<Expr, ExprError> {
        let start = self.pos;
        self.pos = number_end(self.b, start, self.end);
        let token = &self.text[start..self.pos];
        let value = strtod_prefix(token).map_err(|m| ExprError::new(m, start, token.len()))?;
        Ok(Expr { node: Node::Number(value), offset: start, len: self.pos - start })
    }

    /// A word and what follows it: `c_ID[..]`, `f_ID[..]`, `v_name[..]`, `func(...)`, `x[ID]`,
    /// an atom vector, a constant or a thermo keyword.
    fn word<B: Build>(&mut self, bld: &mut B) -> Result<Spanned<B::Out>, ExprError> {
        let start = self.pos;
        while matches!(self.peek(), Some(c) if is_word_char(c)) {
            self.pos += 1;
        }
        let word = &self.text[start..self.pos];
        let node = if let Some(id) = word.strip_prefix("c_") {
            Node::Compute { id: id.to_string(), indices: self.brackets(2)? }
        } else if let Some(id) = word.strip_prefix("f_") {
            Node::Fix { id: id.to_string(), indices: self.brackets(2)? }
        } else if word.starts_with("C_") || word.starts_with("F_") {
            self.brackets(2)?;
            Node::UpperCase(word.to_string())
        } else if let Some(name) = word.strip_prefix("v_") {
            let mut idx = self.brackets(1)?;
            Node::Variable { name: name.to_string(), index: idx.pop() }
        } else if self.peek() == Some(b'(') {
            return self.call(bld, start, word);
        } else if self.peek() == Some(b'[') {
            let id = self.bracket()?;
            Node::AtomValue { keyword: word.to_string(), id }
        } else if ATOM_VECTORS.contains(&word) {
            Node::AtomVector(word.to_string())
        } else if let Some(&(_, v)) = CONSTANTS.iter().find(|(n, _)| *n == word) {
            Node::Number(v)
        } else {
            Node::Thermo(word.to_string())
        };
        let e = Expr { node, offset: start, len: self.pos - start };
        Ok((bld.leaf(e)?, start, self.pos))
    }

    /// Up to `max` bracket pairs right after a word.
    fn brackets(&mut self, max: usize) -> Result<Vec<Index>, ExprError> {
        let mut out = vec![];
        while out.len() < max && self.peek() == Some(b'[') {
            out.push(self.bracket()?);
        }
        Ok(out)
    }

    /// `[digits]` or `[v_name]` at `pos` (LAMMPS `int_between_brackets`). LAMMPS reports these
    /// errors without the variable's name.
    fn bracket(&mut self) -> Result<Index, ExprError> {
        let open = self.pos;
        let start = open + 1;
        let is_var = self.text[start..self.end].starts_with("v_");
        let mut i = start;
        while i < self.end && self.b[i] != b']' {
            let c = self.b[i];
            let ok = if is_var { is_word_char(c) } else { c.is_ascii_digit() };
            if !ok {
                let msg = if is_var {
                    "Variable name between brackets must be alphanumeric or underscore characters"
                } else {
                    "Non digit character between brackets in variable"
                };
                return Err(ExprError::new(msg, i, 1).bare().with_help("the index is a positive integer or v_name"));
            }
            i += 1;
        }
        if i >= self.end {
            return Err(ExprError::new("Mismatched brackets in variable", open, i - open).bare().with_help("`]` is missing"));
        }
        if i == start {
            return Err(ExprError::new("Empty brackets in variable", open, 2).bare());
        }
        self.pos = i + 1;
        let inside = &self.text[start..i];
        if is_var {
            return Ok(Index::Variable(inside[2..].to_string()));
        }
        match inside.parse::<i64>() {
            Ok(0) => Err(ExprError::new("Index between variable brackets must be positive", open, i + 1 - open).bare()),
            Ok(n) => Ok(Index::Number(n)),
            Err(_) => Err(ExprError::new(format!("Index {inside} between brackets is too large"), start, i - start).bare()),
        }
    }

    /// `name(args)`: a math function (arguments are formulas) or any other function
    /// (arguments are kept as trimmed text).
    fn call<B: Build>(&mut self, bld: &mut B, start: usize, name: &str) -> Result<Spanned<B::Out>, ExprError> {
        let open = self.pos;
        let close = self.matching_paren(open)?;
        self.pos = close + 1;
        let args = self.split_args(open + 1, close)?;
        let (offset, len) = (start, close + 1 - start);
        let out = if let Some(&(_, f, _)) = MATH_FUNCTIONS.iter().find(|(n, _, _)| *n == name) {
            bld.math(self, f, &args, offset, len)?
        } else {
            let args = args.iter().map(|&(lo, hi)| self.text[lo..hi].trim().to_string()).collect();
            bld.leaf(Expr { node: Node::Function { name: name.to_string(), args }, offset, len })?
        };
        Ok((out, offset, close + 1))
    }

    /// Byte ranges of the comma-separated arguments in `lo..hi` (commas inside nested
    /// parentheses do not split).
    fn split_args(&self, lo: usize, hi: usize) -> Result<Vec<(usize, usize)>, ExprError> {
        let mut out = vec![];
        let mut level = 0i32;
        let mut from = lo;
        for i in lo..hi {
            match self.b[i] {
                b'(' => level += 1,
                b')' => level -= 1,
                b',' if level == 0 => {
                    out.push((from, i));
                    from = i + 1;
                }
                _ => {}
            }
        }
        out.push((from, hi));
        if out.len() > MAX_FUNC_ARGS {
            return Err(ExprError::new("Too many args in variable function", lo, hi - lo)
                .bare()
                .with_help(format!("a function takes at most {MAX_FUNC_ARGS} arguments")));
        }
        Ok(out)
    }
}

/// The `)` matching the `(` at `open`, before `end` (LAMMPS counts parentheses only).
pub(crate) fn matching_paren(b: &[u8], open: usize, end: usize) -> Option<usize> {
    let mut level = 0;
    for (i, &c) in b.iter().enumerate().take(end).skip(open + 1) {
        match c {
            b'(' => level += 1,
            b')' if level > 0 => level -= 1,
            b')' => return Some(i),
            _ => {}
        }
    }
    None
}

/// End of the number text that starts at `i`: digits and points, then `e` or `E`, a sign
/// and digits (LAMMPS' scan; the value is read from it by [`strtod_prefix`]).
pub(crate) fn number_end(b: &[u8], mut i: usize, end: usize) -> usize {
    while i < end && (b[i].is_ascii_digit() || b[i] == b'.') {
        i += 1;
    }
    if i < end && (b[i] == b'e' || b[i] == b'E') {
        i += 1;
        if i < end && (b[i] == b'+' || b[i] == b'-') {
            i += 1;
        }
        while i < end && b[i].is_ascii_digit() {
            i += 1;
        }
    }
    i
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
