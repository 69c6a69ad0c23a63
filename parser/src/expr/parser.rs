//! The formula grammar, written once with nom and used two ways through [`Build`]: to make a
//! tree ([`TreeBuilder`]) and to compute a value while reading ([`super::eval::Evaluator`]).
//!
//! LAMMPS computes while it parses, so the first error it meets (a syntax error, a division
//! by zero, an unknown keyword) is the one it reports, and the unused branch of `ternary()`
//! is never read. Computing through the parser reproduces that order exactly; the tree keeps
//! the same structure for later walks.
//!
//! Two layers: [`Lexer`] reads operands and operators (it needs only the whole text, for byte
//! offsets), and [`Grammar`] applies LAMMPS' precedence and hands every piece to the builder
//! as soon as it is read.

use nom::branch::alt;
use nom::bytes::complete::{tag, take_till1, take_while};
use nom::character::complete::{anychar, char};
use nom::combinator::{consumed, eof, map, map_opt, not, opt, recognize, value};
use nom::multi::{many0_count, many_m_n, separated_list1};
use nom::sequence::terminated;
use nom::{Finish, Offset};

use super::lex::{self, is_word_char, nested, parenthesized, space, strtod_prefix, Fail, PResult};
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
    /// A math function; its arguments are read with [`Args::read`] in the order (and as far)
    /// the builder wants.
    fn math(&mut self, f: MathFn, args: &Args<'_>, offset: usize, len: usize) -> Result<Self::Out, ExprError>
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
    fn math(&mut self, f: MathFn, args: &Args<'_>, offset: usize, len: usize) -> Result<Expr, ExprError> {
        let parsed = (0..args.len()).map(|k| args.read(self, k)).collect::<Result<_, _>>()?;
        Ok(Expr { node: Node::Math(f, parsed), offset, len })
    }
}

/// Read `text` as one formula.
pub(crate) fn read<B: Build>(text: &str, bld: &mut B) -> Result<B::Out, ExprError> {
    Grammar { lex: Lexer { text }, bld }.whole(text)
}

/// The arguments of a math function: the text of each, read as a formula of its own (as
/// LAMMPS does) when the builder asks.
pub(crate) struct Args<'t> {
    lex: Lexer<'t>,
    items: Vec<&'t str>,
}

impl Args<'_> {
    pub(crate) fn len(&self) -> usize {
        self.items.len()
    }
    /// Read argument `k`.
    pub(crate) fn read<B: Build>(&self, bld: &mut B, k: usize) -> Result<B::Out, ExprError> {
        Grammar { lex: self.lex, bld }.whole(self.items[k])
    }
}

/// A value with the byte range of its text.
type Spanned<T> = (T, usize, usize);

/// The binary operator after an operand and the text after that operator.
type Lookahead<'t> = Option<(BinOp, &'t str)>;

/// Precedence and the builder.
struct Grammar<'t, 'b, B> {
    lex: Lexer<'t>,
    bld: &'b mut B,
}

impl<'t, B: Build> Grammar<'t, '_, B> {
    /// `i` as one formula: the whole text, the inside of parentheses or one function argument.
    fn whole(&mut self, i: &'t str) -> Result<B::Out, ExprError> {
        let lex = self.lex;
        // at precedence 1 every operator is taken, so the formula is read to its end
        let (_, ((v, _, _), next)) = self.binary(i, 1).finish().map_err(|e| lex.report(e))?;
        debug_assert!(next.is_none(), "formula left unread");
        Ok(v)
    }

    /// Operations of precedence `min` and above, each grouped left to right (precedence
    /// climbing), and the operator after them, read once and handed to the caller (`None` at
    /// the end). A loop rather than nom's `fold_many0`: each operation is built as soon as its
    /// right operand is read, and building may fail (a division by zero stops LAMMPS there).
    fn binary(&mut self, i: &'t str, min: u8) -> PResult<'t, (Spanned<B::Out>, Lookahead<'t>)> {
        let (i, (mut lhs, lo, mut hi)) = self.unary(i)?;
        let (mut i, mut next) = self.lex.lookahead(i)?;
        while let Some((op, after)) = next {
            if op.precedence() < min {
                break;
            }
            let (rest, ((rhs, _, rhi), after_rhs)) = self.binary(after, op.precedence() + 1)?;
            hi = rhi;
            lhs = self.bld.binary(op, lhs, rhs, lo, hi - lo)?;
            (i, next) = (rest, after_rhs);
        }
        Ok((i, ((lhs, lo, hi), next)))
    }

    /// Unary `-` and `!` apply to the operand right after them (they bind tighter than `^`).
    fn unary(&mut self, i: &'t str) -> PResult<'t, Spanned<B::Out>> {
        let (i, _) = space(i)?;
        let (rest, op) = opt(unary_op)(i)?;
        let Some(op) = op else { return self.primary(i) };
        let (rest, (arg, _, hi)) = self.unary(rest)?;
        let lo = self.lex.at(i);
        Ok((rest, (self.bld.unary(op, arg, lo, hi - lo)?, lo, hi)))
    }

    /// An operand, handed to the builder (the inside of parentheses is a formula of its own).
    fn primary(&mut self, i: &'t str) -> PResult<'t, Spanned<B::Out>> {
        let (rest, operand) = self.lex.operand(i)?;
        let (lo, hi) = (self.lex.at(i), self.lex.at(rest));
        let out = match operand {
            Operand::Group(inside) => self.whole(inside)?,
            Operand::Leaf(node) => self.bld.leaf(Expr { node, offset: lo, len: hi - lo })?,
            Operand::Math(f, items) => self.bld.math(f, &Args { lex: self.lex, items }, lo, hi - lo)?,
        };
        Ok((rest, (out, lo, hi)))
    }
}

/// An operand as read, before the builder sees it. `repr(u8)` keeps the node at an aligned
/// offset: with the default layout the tag shares the node's first byte, and moving an operand
/// copied the node from an odd offset, which stalled the CPU (evaluation was ~10% slower).
#[repr(u8)]
enum Operand<'t> {
    /// `( ... )`: the text inside.
    Group(&'t str),
    /// Anything the builder takes whole: a number, `v_name`, `c_ID[i]`, a thermo keyword, a
    /// group or other non-math function, ...
    Leaf(Node),
    /// A math function and the text of its arguments.
    Math(MathFn, Vec<&'t str>),
}

/// Reads the tokens of a formula; knows the whole text, to give byte offsets.
#[derive(Clone, Copy)]
struct Lexer<'t> {
    text: &'t str,
}

impl<'t> Lexer<'t> {
    /// Byte offset of `i` (a slice of the text).
    fn at(self, i: &str) -> usize {
        self.text.offset(i)
    }

    /// The error to report for a failed read.
    fn report(self, e: Fail<'_>) -> ExprError {
        match e {
            Fail::Located(e) => *e,
            Fail::NoMatch(at) => self.syntax_here(at),
        }
    }

    /// A syntax error at the first character of `i` (or at the end).
    fn syntax_here(self, i: &str) -> ExprError {
        let at = self.at(i);
        let Some(c) = i.chars().next() else {
            return ExprError::new(SYNTAX, at, 0).with_help("the formula ends where an operand is expected");
        };
        let e = ExprError::new(SYNTAX, at, c.len_utf8());
        match c {
            '+' => e.with_help("LAMMPS formulas have no unary `+`"),
            ',' => e.with_help("a comma separates the arguments of a function only"),
            ')' => e.with_help("this `)` has no matching `(`"),
            '"' | '\'' => e.with_help("quotes are not part of a formula"),
            _ => e,
        }
    }

    /// Where an operator was expected but `i` starts with something else.
    fn operator_error(self, i: &str) -> ExprError {
        let e = self.syntax_here(i);
        match i.chars().next() {
            Some(c) if c.is_ascii_alphanumeric() || c == '.' || c == '(' => {
                e.with_help("an operator is missing between two operands")
            }
            _ => e,
        }
    }

    /// The operator after an operand (blanks skipped), with the text after it. LAMMPS reports
    /// a bad operator as soon as it reads it, before the operations on its left.
    fn lookahead(self, i: &'t str) -> PResult<'t, Lookahead<'t>> {
        let (i, _) = space(i)?;
        let (after, op) = self.operator(i)?;
        Ok((i, op.map(|op| (op, after))))
    }

    /// The binary operator at the start of `i`, `None` at the end of the text; anything else
    /// is an error.
    fn operator(self, i: &'t str) -> PResult<'t, Option<BinOp>> {
        alt((value(None, eof), map(binary_op, Some), |i| Err(self.bad_operator(i).into())))(i)
    }

    fn bad_operator(self, i: &str) -> ExprError {
        let e = ExprError::new(SYNTAX, self.at(i), 1);
        match i.as_bytes()[0] {
            b'=' => e.with_help("use `==` to compare two values"),
            b'!' => e.with_help("`!` negates the operand that follows it"),
            b'&' => e.with_help("use `&&` for a logical and"),
            b'|' => e.with_help("use `||` for a logical or, `|^` for exclusive or"),
            _ => self.operator_error(i),
        }
    }

    /// A number, a word with what follows it, or parentheses.
    fn operand(self, i: &'t str) -> PResult<'t, Operand<'t>> {
        alt((
            map(|i| self.number(i), Operand::Leaf),
            |i| self.word(i),
            map(|i| self.group(i), Operand::Group),
            |i| Err(self.syntax_here(i).into()),
        ))(i)
    }

    /// `( ... )`: the text inside.
    fn group(self, i: &'t str) -> PResult<'t, &'t str> {
        parenthesized(i, || self.unclosed(i))
    }

    /// `i` starts with a `(` that has no matching `)`.
    fn unclosed(self, i: &str) -> ExprError {
        ExprError::new(SYNTAX, self.at(i), 1).with_help("this `(` is never closed")
    }

    /// A number, converted as `strtod` converts it.
    fn number(self, i: &'t str) -> PResult<'t, Node> {
        let (rest, token) = lex::number(i)?;
        let value = strtod_prefix(token).map_err(|m| ExprError::new(m, self.at(i), token.len()))?;
        Ok((rest, Node::Number(value)))
    }

    /// A word and what follows it: `c_ID[..]`, `f_ID[..]`, `v_name[..]`, `func(...)`, `x[ID]`,
    /// an atom vector, a constant or a thermo keyword.
    fn word(self, i: &'t str) -> PResult<'t, Operand<'t>> {
        let (rest, word) = lex::word(i)?;
        let (rest, node) = if let Some(id) = word.strip_prefix("c_") {
            let (rest, indices) = self.brackets(rest, 2)?;
            (rest, Node::Compute { id: id.to_string(), indices })
        } else if let Some(id) = word.strip_prefix("f_") {
            let (rest, indices) = self.brackets(rest, 2)?;
            (rest, Node::Fix { id: id.to_string(), indices })
        } else if word.starts_with("C_") || word.starts_with("F_") {
            let (rest, indices) = self.brackets(rest, 2)?;
            if indices.is_empty() {
                (rest, Node::UpperCase(word.to_string()))
            } else {
                (rest, Node::AtomElement { compute: word.starts_with('C'), id: word[2..].to_string(), indices })
            }
        } else if let Some(name) = word.strip_prefix("v_") {
            let (rest, index) = opt(|i| self.bracket(i))(rest)?;
            (rest, Node::Variable { name: name.to_string(), index })
        } else if rest.starts_with('(') {
            return self.call(word, rest);
        } else if let (rest, Some(id)) = opt(|i| self.bracket(i))(rest)? {
            (rest, Node::AtomValue { keyword: word.to_string(), id })
        } else {
            (rest, bare_word(word))
        };
        Ok((rest, Operand::Leaf(node)))
    }

    /// `name(args)` (`rest` starts at the `(`): a math function (its arguments are formulas)
    /// or any other function (its arguments are kept as trimmed text).
    fn call(self, name: &str, rest: &'t str) -> PResult<'t, Operand<'t>> {
        let (rest, items) = self.args(rest)?;
        if let Some(&(_, f, _)) = MATH_FUNCTIONS.iter().find(|(n, _, _)| *n == name) {
            return Ok((rest, Operand::Math(f, items)));
        }
        let args = items.iter().map(|a| a.trim().to_string()).collect();
        Ok((rest, Operand::Leaf(Node::Function { name: name.to_string(), args })))
    }

    /// `(` and the comma-separated arguments up to its matching `)` (commas inside nested
    /// parentheses do not split), in one pass.
    fn args(self, i: &'t str) -> PResult<'t, Vec<&'t str>> {
        let arg = recognize(many0_count(alt((take_till1(|c| matches!(c, '(' | ')' | ',')), nested))));
        let (inside, _) = char('(')(i)?;
        let mut list = terminated(consumed(separated_list1(char(','), arg)), char(')'));
        let Ok((rest, (inside, items))) = list(inside) else { return Err(self.unclosed(i).into()) };
        if items.len() > MAX_FUNC_ARGS {
            let e = ExprError::new("Too many args in variable function", self.at(inside), inside.len());
            return Err(e.bare().with_help(format!("a function takes at most {MAX_FUNC_ARGS} arguments")).into());
        }
        Ok((rest, items))
    }

    /// Up to `max` bracket pairs.
    fn brackets(self, i: &'t str, max: usize) -> PResult<'t, Vec<Index>> {
        many_m_n(0, max, |i| self.bracket(i))(i)
    }

    /// `[digits]` or `[v_name]` (LAMMPS `int_between_brackets`); not a match without `[`.
    /// LAMMPS reports these errors without the variable's name.
    fn bracket(self, i: &'t str) -> PResult<'t, Index> {
        let (start, _) = char('[')(i)?;
        let open = self.at(i);
        let is_var = start.starts_with("v_");
        let allowed: fn(char) -> bool = if is_var { is_word_char } else { |c| c.is_ascii_digit() };
        let (rest, inside) = take_while(allowed)(start)?;
        let Ok((rest, _)) = char::<_, Fail>(']')(rest) else {
            return Err(self.unclosed_bracket(open, rest, is_var).into());
        };
        if inside.is_empty() {
            return Err(ExprError::new("Empty brackets in variable", open, 2).bare().into());
        }
        if is_var {
            return Ok((rest, Index::Variable(inside[2..].to_string())));
        }
        match inside.parse::<i64>() {
            Ok(0) => {
                let e = ExprError::new("Index between variable brackets must be positive", open, self.at(rest) - open);
                Err(e.bare().into())
            }
            Ok(n) => Ok((rest, Index::Number(n))),
            Err(_) => {
                let msg = format!("Index {inside} between brackets is too large");
                Err(ExprError::new(msg, self.at(start), inside.len()).bare().into())
            }
        }
    }

    /// The index that opens at `open` stops at `rest`, which is not `]`.
    fn unclosed_bracket(self, open: usize, rest: &str, is_var: bool) -> ExprError {
        let at = self.at(rest);
        if rest.is_empty() {
            let e = ExprError::new("Mismatched brackets in variable", open, at - open);
            return e.bare().with_help("`]` is missing");
        }
        let msg = if is_var {
            "Variable name between brackets must be alphanumeric or underscore characters"
        } else {
            "Non digit character between brackets in variable"
        };
        ExprError::new(msg, at, 1).bare().with_help("the index is a positive integer or v_name")
    }
}

/// A word with nothing after it: an atom vector, a constant or a thermo keyword.
fn bare_word(word: &str) -> Node {
    if ATOM_VECTORS.contains(&word) {
        Node::AtomVector(word.to_string())
    } else if let Some(&(_, v)) = CONSTANTS.iter().find(|(n, _)| *n == word) {
        Node::Number(v)
    } else {
        Node::Thermo(word.to_string())
    }
}

/// LAMMPS' binary operators. The arithmetic ones are single characters that start no other
/// operator, so one look at the character settles them (the commonest case, read first).
fn binary_op(i: &str) -> PResult<'_, BinOp> {
    let arithmetic = |c| match c {
        '+' => Some(BinOp::Add),
        '-' => Some(BinOp::Sub),
        '*' => Some(BinOp::Mul),
        '/' => Some(BinOp::Div),
        '%' => Some(BinOp::Mod),
        '^' => Some(BinOp::Pow),
        _ => None,
    };
    alt((
        map_opt(anychar, arithmetic),
        value(BinOp::Eq, tag("==")),
        value(BinOp::Ne, tag("!=")),
        value(BinOp::Le, tag("<=")),
        value(BinOp::Lt, char('<')),
        value(BinOp::Ge, tag(">=")),
        value(BinOp::Gt, char('>')),
        value(BinOp::And, tag("&&")),
        value(BinOp::Or, tag("||")),
        value(BinOp::Xor, tag("|^")),
    ))(i)
}

/// Unary minus, and a `!` that does not start `!=`.
fn unary_op(i: &str) -> PResult<'_, UnOp> {
    alt((value(UnOp::Neg, char('-')), value(UnOp::Not, terminated(char('!'), not(char('='))))))(i)
}
