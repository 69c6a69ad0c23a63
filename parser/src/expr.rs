//! Equal-style formulas (`variable a equal ...`, `$(...)`) and `if` conditions as LAMMPS
//! 22 Jul 2025 reads and computes them (src/variable.cpp `Variable::evaluate()` and
//! `evaluate_boolean()`).
//!
//! [`evaluate`] computes while it reads, as LAMMPS does, so the first error LAMMPS would meet
//! is the one reported. [`parse`] reads the same grammar into a tree whose nodes keep their
//! byte ranges, and [`eval`] computes a tree (for formulas parsed once and computed often, and
//! for a later per-atom evaluator).
//!
//! LAMMPS rules reproduced here (each checked with the real `lmp`, see the tests):
//! * precedence, low to high: `|| |^`, `&&`, `== !=`, `< <= > >=`, `+ -`, `* / %`, `^`, and the
//!   unary `-` and `!` bind tightest of all; every binary operator groups left to right, so
//!   `-2^2` is 4 and `2^3^2` is 64; there is no unary `+`;
//! * operands are computed left to right and each operation is one IEEE operation in that
//!   order, so results are bit-identical to LAMMPS;
//! * a number is digits and points with an optional exponent, converted by `strtod` (so `1.2.3`
//!   is 1.2); `x^0` is 1 for any x; `&&`/`||` evaluate both sides; `ternary()` reads only the
//!   branch it returns;
//! * the value of a whole formula is flushed to zero when its magnitude is below the smallest
//!   normal double (LAMMPS prints `0` for `0*-1` and for `1e-300*1e-10`), but values inside it
//!   are not (`atan2(0*-1,-1)` is -PI).
//!
//! Where dmhs differs: numbers LAMMPS cannot convert (`.e5`, `1e400`, `1e-310`) make LAMMPS
//! abort and are errors here; a stray `!` after an operand is a syntax error at once (LAMMPS
//! reads on and reports a syntax error at the end); the special functions `sum()`, `min()`,
//! `max()`, `ave()`, `trap()` and `slope()` take computes' and fixes' global vectors and array
//! columns, not vector-style variables; `sort()`, `rsort()` and the mask functions are not
//! supported. `random()` and `normal()` draw from the generator `Variables` keeps (LAMMPS'
//! randomequal).

use crate::context::EvalContext;

mod boolean;
mod eval;
mod lex;
mod parser;

pub use boolean::evaluate_boolean;
pub use eval::eval;
pub use lex::{atof, strtod_prefix};

/// An error in a formula: the LAMMPS message and the byte range of the offending text.
#[derive(Clone, Debug, PartialEq)]
pub struct ExprError {
    pub message: String,
    /// Byte offset of the offending text in the formula.
    pub offset: usize,
    /// Its length in bytes (0 at the end of the formula).
    pub len: usize,
    /// A hint for the user (shown as a `help:` line), if any.
    pub help: Option<String>,
    /// LAMMPS writes this message without the `Variable NAME:` prefix of the variable being
    /// evaluated (it already names its variable, or LAMMPS reports it bare).
    pub bare: bool,
}

impl ExprError {
    pub fn new(message: impl Into<String>, offset: usize, len: usize) -> ExprError {
        ExprError { message: message.into(), offset, len, help: None, bare: false }
    }
    pub(crate) fn with_help(mut self, help: impl Into<String>) -> ExprError {
        self.help = Some(help.into());
        self
    }
    pub(crate) fn bare(mut self) -> ExprError {
        self.bare = true;
        self
    }
}

impl std::fmt::Display for ExprError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// Binary operators, in LAMMPS' precedence classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Or,
    Xor,
    And,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Pow,
}

impl BinOp {
    /// LAMMPS' precedence levels (1 lowest); unary operators are level 8.
    pub fn precedence(self) -> u8 {
        use BinOp::*;
        match self {
            Or | Xor => 1,
            And => 2,
            Eq | Ne => 3,
            Lt | Le | Gt | Ge => 4,
            Add | Sub => 5,
            Mul | Div | Mod => 6,
            Pow => 7,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Not,
}

/// The math functions of LAMMPS equal-style formulas.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MathFn {
    Sqrt,
    Exp,
    Ln,
    Log,
    Abs,
    Sign,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Random,
    Normal,
    Ceil,
    Floor,
    Round,
    Ternary,
    Ramp,
    Stagger,
    Logfreq,
    Logfreq2,
    Logfreq3,
    Stride,
    Stride2,
    Vdisplace,
    Swiggle,
    Cwiggle,
}

pub(crate) const MATH_FUNCTIONS: &[(&str, MathFn, usize)] = &[
    ("sqrt", MathFn::Sqrt, 1),
    ("exp", MathFn::Exp, 1),
    ("ln", MathFn::Ln, 1),
    ("log", MathFn::Log, 1),
    ("abs", MathFn::Abs, 1),
    ("sign", MathFn::Sign, 1),
    ("sin", MathFn::Sin, 1),
    ("cos", MathFn::Cos, 1),
    ("tan", MathFn::Tan, 1),
    ("asin", MathFn::Asin, 1),
    ("acos", MathFn::Acos, 1),
    ("atan", MathFn::Atan, 1),
    ("atan2", MathFn::Atan2, 2),
    ("random", MathFn::Random, 3),
    ("normal", MathFn::Normal, 3),
    ("ceil", MathFn::Ceil, 1),
    ("floor", MathFn::Floor, 1),
    ("round", MathFn::Round, 1),
    ("ternary", MathFn::Ternary, 3),
    ("ramp", MathFn::Ramp, 2),
    ("stagger", MathFn::Stagger, 2),
    ("logfreq", MathFn::Logfreq, 3),
    ("logfreq2", MathFn::Logfreq2, 3),
    ("logfreq3", MathFn::Logfreq3, 3),
    ("stride", MathFn::Stride, 3),
    ("stride2", MathFn::Stride2, 6),
    ("vdisplace", MathFn::Vdisplace, 2),
    ("swiggle", MathFn::Swiggle, 3),
    ("cwiggle", MathFn::Cwiggle, 3),
];

/// Group functions; their arguments are names, handed to [`EvalContext::group_function`].
pub const GROUP_FUNCTIONS: &[&str] =
    &["count", "mass", "charge", "xcm", "vcm", "fcm", "bound", "gyration", "ke", "angmom", "torque", "inertia", "omega"];

/// LAMMPS special and feature functions that dmhs does not implement (a clear error, not the
/// "invalid function" of a misspelling).
pub(crate) const UNSUPPORTED_FUNCTIONS: &[&str] = &[
    "sort", "rsort", "next", "is_active",
    "is_available", "is_defined", "is_os", "extract_setting", "label2type", "is_typelabel", "is_timeout",
];

/// Per-atom vectors: a bare name is an error in an equal-style formula, `name[ID]` is one atom's value.
pub const ATOM_VECTORS: &[&str] =
    &["id", "mass", "type", "mol", "radius", "q", "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"];

/// Named constants.
pub(crate) const CONSTANTS: &[(&str, f64)] = &[
    ("PI", std::f64::consts::PI),
    ("version", 20250722.0),
    ("yes", 1.0),
    ("no", 0.0),
    ("on", 1.0),
    ("off", 0.0),
    ("true", 1.0),
    ("false", 0.0),
];

/// An index between brackets: a positive integer or `v_name`.
#[derive(Clone, Debug, PartialEq)]
pub enum Index {
    Number(i64),
    Variable(String),
}

/// One node of a formula tree.
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    Number(f64),
    Unary(UnOp, Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// A math function; its arguments are formulas.
    Math(MathFn, Vec<Expr>),
    /// Any other `name(args)`: group, special, feature or unknown functions; the arguments
    /// are kept as trimmed text.
    Function { name: String, args: Vec<String> },
    /// `v_name` or `v_name[i]`.
    Variable { name: String, index: Option<Index> },
    /// `c_ID`, `c_ID[i]`, `c_ID[i][j]`.
    Compute { id: String, indices: Vec<Index> },
    /// `f_ID`, `f_ID[i]`, `f_ID[i][j]`.
    Fix { id: String, indices: Vec<Index> },
    /// `C_ID`/`F_ID`: LAMMPS' forced access to a global vector (never a scalar).
    UpperCase(String),
    /// `C_ID[I]`, `C_ID[I][J]` (`F_` alike): one atom's value of a per-atom vector or array
    /// column J, by atom ID I.
    AtomElement { compute: bool, id: String, indices: Vec<Index> },
    /// `x[12]`: one atom's value by atom ID.
    AtomValue { keyword: String, id: Index },
    /// A bare per-atom vector such as `x` (per-atom formulas only).
    AtomVector(String),
    /// Any other word: a thermo keyword.
    Thermo(String),
}

/// A formula tree node with the byte range of its text.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub node: Node,
    pub offset: usize,
    pub len: usize,
}

impl Expr {
    pub(crate) fn err(&self, message: impl Into<String>) -> ExprError {
        ExprError::new(message, self.offset, self.len)
    }
}

/// Evaluate a whole formula: parse, evaluate, and flush a result below the smallest normal
/// double to zero, as LAMMPS does for the value of a variable or `$(...)`.
pub fn evaluate(text: &str, ctx: &mut dyn EvalContext) -> Result<f64, ExprError> {
    let v = parser::read(text, &mut eval::Evaluator { ctx })?;
    Ok(flush_tiny(v))
}

/// Parse a formula into a tree (every function argument included, also the branch of
/// `ternary()` that [`evaluate`] would not read).
pub fn parse(text: &str) -> Result<Expr, ExprError> {
    parser::read(text, &mut parser::TreeBuilder)
}

/// LAMMPS returns exactly 0 for a formula whose magnitude is below `DBL_MIN` (this also turns
/// `-0` into `0`).
pub fn flush_tiny(v: f64) -> f64 {
    if v.abs() < f64::MIN_POSITIVE {
        0.0
    } else {
        v
    }
}

#[cfg(test)]
mod grammar_tests;
#[cfg(test)]
mod tests;
