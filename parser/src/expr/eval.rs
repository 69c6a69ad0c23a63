//! Computing formulas: the builder that computes while the parser reads (used by
//! [`super::evaluate`]), the walk over a parsed tree ([`eval`]), and every operation and
//! function exactly as LAMMPS computes it.

use super::lex::atof;
use super::parser::{Args, Build};
use super::{BinOp, Expr, ExprError, Index, MathFn, Node, UnOp, ATOM_VECTORS, CONSTANTS, GROUP_FUNCTIONS, MATH_FUNCTIONS, UNSUPPORTED_FUNCTIONS};
use crate::context::EvalContext;
use crate::variables;

/// Computes each piece as the parser reads it (LAMMPS' order of evaluation and errors).
pub(crate) struct Evaluator<'c> {
    pub ctx: &'c mut dyn EvalContext,
}

impl Build for Evaluator<'_> {
    type Out = f64;
    fn leaf(&mut self, e: Expr) -> Result<f64, ExprError> {
        eval(&e, self.ctx)
    }
    fn unary(&mut self, op: UnOp, arg: f64, _offset: usize, _len: usize) -> Result<f64, ExprError> {
        Ok(unary(op, arg))
    }
    fn binary(&mut self, op: BinOp, a: f64, b: f64, offset: usize, len: usize) -> Result<f64, ExprError> {
        binary(op, a, b).map_err(|m| ExprError::new(m, offset, len))
    }
    fn math(&mut self, f: MathFn, args: &Args<'_>, offset: usize, len: usize) -> Result<f64, ExprError> {
        // ternary() with three arguments reads only the branch it returns
        if f == MathFn::Ternary && args.len() == 3 {
            let c = args.read(self, 0)?;
            return args.read(self, if c != 0.0 { 1 } else { 2 });
        }
        // LAMMPS computes every argument before it checks their number
        let mut v = Vec::with_capacity(args.len());
        for k in 0..args.len() {
            v.push(args.read(self, k)?);
        }
        math(self.ctx, f, &v, offset, len)
    }
}

/// LAMMPS `MAXBIGINT` as a double (the "never" step of `stride()`).
const MAXBIGINT: f64 = i64::MAX as f64;

/// Evaluate a tree as an equal-style formula (no flushing of the result; see
/// [`super::evaluate`]).
pub fn eval(e: &Expr, ctx: &mut dyn EvalContext) -> Result<f64, ExprError> {
    match &e.node {
        Node::Number(v) => Ok(*v),
        Node::Unary(op, a) => Ok(unary(*op, eval(a, ctx)?)),
        Node::Binary(op, a, b) => {
            let x = eval(a, ctx)?;
            let y = eval(b, ctx)?;
            binary(*op, x, y).map_err(|m| e.err(m))
        }
        Node::Math(f, args) => {
            if *f == MathFn::Ternary && args.len() == 3 {
                let c = eval(&args[0], ctx)?;
                return eval(if c != 0.0 { &args[1] } else { &args[2] }, ctx);
            }
            let mut v = Vec::with_capacity(args.len());
            for a in args {
                v.push(eval(a, ctx)?);
            }
            math(ctx, *f, &v, e.offset, e.len)
        }
        Node::Function { name, args } => function(e, name, args, ctx),
        Node::Variable { name, index } => {
            if let Some(index) = index {
                return match variables::style_of(ctx, name) {
                    None => Err(e.err(format!("Invalid variable reference v_{name} in variable formula")).bare()),
                    Some("atom" | "atomfile") => {
                        let atom = index_value(e, index, ctx)?;
                        ctx.atom_variable_element(name, atom).map_err(|m| e.err(m))
                    }
                    Some("vector") => {
                        // LAMMPS: an index out of range is an error, the index an integer >= 1
                        let i = index_value(e, index, ctx)?;
                        let v = ctx.vector_variable(name).map_err(|m| e.err(m).bare())?;
                        if i < 1 || i as usize > v.len() {
                            return Err(e.err(format!("Variable formula vector-style variable {name} is accessed out-of-range (index {i} of {})", v.len())).bare());
                        }
                        Ok(v[i as usize - 1])
                    }
                    Some(_) => Err(e.err(format!("Variable {name}: Mismatched variable in variable formula"))
                        .bare()
                        .with_help(format!("v_{name} is a single value; remove the brackets"))),
                };
            }
            variables::formula_value(ctx, name).map_err(|m| e.err(m).bare())
        }
        Node::Compute { id, indices } => match global_index(e, indices, ctx)? {
            (i, None) => ctx.compute_value(id, i),
            (Some(i), Some(j)) => ctx.compute_array_value(id, i, j),
            (None, Some(_)) => unreachable!("a second index comes with a first"),
        }
        .map_err(|m| e.err(m)),
        Node::Fix { id, indices } => match global_index(e, indices, ctx)? {
            (i, None) => ctx.fix_value(id, i),
            (Some(i), Some(j)) => ctx.fix_array_value(id, i, j),
            (None, Some(_)) => unreachable!("a second index comes with a first"),
        }
        .map_err(|m| e.err(m)),
        Node::AtomElement { compute, id, indices } => {
            let atom = index_value(e, &indices[0], ctx)?;
            let column = indices.get(1).map(|j| index_value(e, j, ctx)).transpose()?;
            ctx.peratom_element(*compute, id, column.map(|j| j as usize), atom).map_err(|m| e.err(m))
        }
        Node::UpperCase(word) => {
            let lower = word.to_ascii_lowercase();
            Err(e.err(format!("{word}: upper-case C_/F_ reads a global vector, which an equal-style formula cannot hold"))
                .with_help(format!("use {}{} for a scalar or ...[i] for one element", &lower[..2], &word[2..])))
        }
        Node::AtomValue { keyword, id } => {
            let id = index_value(e, id, ctx)?;
            match ctx.atom_value(keyword, id) {
                Some(r) => r.map_err(|m| e.err(m)),
                None => Err(e.err("Invalid atom vector in variable formula")
                    .with_help(format!("per-atom values by ID are {}", ATOM_VECTORS.join(", ")))),
            }
        }
        Node::AtomVector(_) => Err(e
            .err("Atom vector in equal-style variable formula")
            .bare()
            .with_help("one atom's value is written with its atom ID, e.g. x[12]")),
        Node::Thermo(word) => match ctx.thermo_keyword(word) {
            Some(r) => r.map_err(|m| e.err(m)),
            None => {
                let mut err = e.err(format!("Invalid thermo keyword '{word}' in variable formula"));
                let names = CONSTANTS.iter().map(|c| c.0).chain(ATOM_VECTORS.iter().copied());
                if let Some(h) = crate::suggest::did_you_mean_help(word, names) {
                    err = err.with_help(h);
                }
                Err(err)
            }
        },
    }
}

fn unary(op: UnOp, v: f64) -> f64 {
    match op {
        UnOp::Neg => -v,
        UnOp::Not => bool_value(v == 0.0),
    }
}

pub(crate) fn bool_value(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}

/// One binary operation, exactly as LAMMPS computes it.
pub(crate) fn binary(op: BinOp, x: f64, y: f64) -> Result<f64, String> {
    use BinOp::*;
    Ok(match op {
        Add => x + y,
        Sub => x - y,
        Mul => x * y,
        Div => {
            if y == 0.0 {
                return Err("Divide by 0 in variable formula".into());
            }
            x / y
        }
        Mod => {
            if y == 0.0 {
                return Err("Modulo 0 in variable formula".into());
            }
            x % y
        }
        Pow => {
            if y == 0.0 {
                1.0
            } else if x == 0.0 && y < 0.0 {
                return Err("Invalid power expression in variable formula".into());
            } else {
                x.powf(y)
            }
        }
        Eq => bool_value(x == y),
        Ne => bool_value(x != y),
        Lt => bool_value(x < y),
        Le => bool_value(x <= y),
        Gt => bool_value(x > y),
        Ge => bool_value(x >= y),
        And => bool_value(x != 0.0 && y != 0.0),
        Or => bool_value(x != 0.0 || y != 0.0),
        Xor => bool_value((x == 0.0) != (y == 0.0)),
    })
}

/// The value of a bracket index (`v_name` is looked up as LAMMPS does: its text, converted).
fn index_value(e: &Expr, idx: &Index, ctx: &mut dyn EvalContext) -> Result<i64, ExprError> {
    match idx {
        Index::Number(n) => Ok(*n),
        Index::Variable(name) => {
            if variables::style_of(ctx, name).is_none() {
                return Err(e.err(format!("Invalid variable name {name} in variable formula")).bare());
            }
            let text = match variables::retrieve(ctx, name) {
                Ok(Some(t)) => t,
                Ok(None) => return Err(e.err("Invalid variable evaluation in variable formula").bare()),
                Err(m) => return Err(e.err(m).bare()),
            };
            let n = atof(&text) as i64;
            if n <= 0 {
                return Err(e.err("Index between variable brackets must be positive").bare());
            }
            Ok(n)
        }
    }
}

/// The indices of `c_ID`, `c_ID[i]` or `c_ID[i][j]` (the parser allows at most two).
fn global_index(e: &Expr, indices: &[Index], ctx: &mut dyn EvalContext) -> Result<(Option<usize>, Option<usize>), ExprError> {
    let mut at = |k: usize| -> Result<Option<usize>, ExprError> {
        indices.get(k).map(|i| index_value(e, i, ctx).map(|n| n as usize)).transpose()
    };
    Ok((at(0)?, at(1)?))
}

/// The byte range errors of a function call point at.
struct Site {
    offset: usize,
    len: usize,
}

impl Site {
    fn err(&self, m: impl Into<String>) -> ExprError {
        ExprError::new(m, self.offset, self.len)
    }
}

/// The current step and run window for the step-dependent functions.
struct StepInfo {
    step: i64,
    begin: i64,
    end: i64,
}

fn thermo_number(e: &Site, ctx: &mut dyn EvalContext, key: &str, func: &str) -> Result<f64, ExprError> {
    match ctx.thermo_keyword(key) {
        Some(r) => r.map_err(|m| e.err(m)),
        None => Err(e.err(format!("{func}() needs the current {key}, which is not available here"))),
    }
}

fn step_info(e: &Site, ctx: &mut dyn EvalContext, func: &str) -> Result<StepInfo, ExprError> {
    let step = thermo_number(e, ctx, "step", func)? as i64;
    // between runs LAMMPS has beginstep = endstep = 0
    let (begin, end) = ctx.run_window().unwrap_or((0, 0));
    Ok(StepInfo { step, begin, end })
}

/// A math function of already computed arguments (ternary() with three arguments is
/// handled by the callers, which compute only one branch).
fn math(ctx: &mut dyn EvalContext, f: MathFn, v: &[f64], offset: usize, len: usize) -> Result<f64, ExprError> {
    let e = &Site { offset, len };
    let (name, _, nargs) = MATH_FUNCTIONS.iter().find(|m| m.1 == f).copied().unwrap_or(("?", f, 0));
    let bad = || {
        e.err("Invalid math function in variable formula")
            .with_help(format!("{name}() takes {nargs} argument{}", if nargs == 1 { "" } else { "s" }))
    };
    if v.len() != nargs {
        return Err(bad());
    }
    let invalid = |m: &str| Err(e.err(m));
    let x = v[0];
    Ok(match f {
        MathFn::Sqrt => {
            if x < 0.0 {
                return invalid("Sqrt of negative value in variable formula");
            }
            x.sqrt()
        }
        MathFn::Exp => x.exp(),
        MathFn::Ln | MathFn::Log => {
            if x <= 0.0 {
                return invalid("Log of zero/negative value in variable formula");
            }
            if f == MathFn::Ln {
                x.ln()
            } else {
                x.log10()
            }
        }
        MathFn::Abs => x.abs(),
        MathFn::Sign => {
            if x >= 0.0 {
                1.0
            } else {
                -1.0
            }
        }
        MathFn::Sin => x.sin(),
        MathFn::Cos => x.cos(),
        MathFn::Tan => x.tan(),
        MathFn::Asin => {
            if !(-1.0..=1.0).contains(&x) && !x.is_nan() {
                return invalid("Arcsin of invalid value in variable formula");
            }
            x.asin()
        }
        MathFn::Acos => {
            if !(-1.0..=1.0).contains(&x) && !x.is_nan() {
                return invalid("Arccos of invalid value in variable formula");
            }
            x.acos()
        }
        MathFn::Atan => x.atan(),
        MathFn::Atan2 => x.atan2(v[1]),
        MathFn::Ceil => x.ceil(),
        MathFn::Floor => x.floor(),
        MathFn::Round => {
            // LAMMPS MYROUND: halves go up
            if x - x.floor() >= 0.5 {
                x.ceil()
            } else {
                x.floor()
            }
        }
        MathFn::Ternary => {
            if x != 0.0 {
                v[1]
            } else {
                v[2]
            }
        }
        MathFn::Random | MathFn::Normal => {
            if f == MathFn::Normal && v[1] < 0.0 {
                return invalid("Invalid math function in variable formula");
            }
            let rng = ctx.variables().random_equal(v[2]).map_err(|m| e.err(m))?;
            if f == MathFn::Normal {
                x + v[1] * rng.gaussian()
            } else {
                rng.uniform() * (v[1] - x) + x
            }
        }
        MathFn::Ramp => {
            let s = step_info(e, ctx, name)?;
            if s.end == s.begin {
                x
            } else {
                let mut delta = (s.step - s.begin) as f64;
                if delta != 0.0 {
                    delta /= (s.end - s.begin) as f64;
                }
                x + delta * (v[1] - x)
            }
        }
        MathFn::Vdisplace => {
            let s = step_info(e, ctx, name)?;
            let dt = thermo_number(e, ctx, "dt", name)?;
            let delta = (s.step - s.begin) as f64;
            x + v[1] * delta * dt
        }
        MathFn::Swiggle | MathFn::Cwiggle => {
            if v[2] == 0.0 {
                return Err(bad().with_help("the period (third argument) must not be 0"));
            }
            let s = step_info(e, ctx, name)?;
            let dt = thermo_number(e, ctx, "dt", name)?;
            let delta = (s.step - s.begin) as f64;
            let omega = 2.0 * std::f64::consts::PI / v[2];
            if f == MathFn::Swiggle {
                x + v[1] * (omega * delta * dt).sin()
            } else {
                x + v[1] * (1.0 - (omega * delta * dt).cos())
            }
        }
        MathFn::Stagger | MathFn::Logfreq | MathFn::Logfreq2 | MathFn::Logfreq3 | MathFn::Stride | MathFn::Stride2 => {
            let step = thermo_number(e, ctx, "step", name)? as i64;
            let iv: Vec<i64> = v.iter().map(|&a| a as i32 as i64).collect();
            match step_function(f, step, &iv) {
                Ok(r) => r,
                Err(StepFnError::Invalid) => return Err(bad()),
                Err(StepFnError::Exceeded) => return invalid("Calls to variable exceeded limit"),
            }
        }
    })
}

enum StepFnError {
    Invalid,
    Exceeded,
}

/// stagger(), logfreq(), logfreq2(), logfreq3(), stride(), stride2(): the next output step
/// after `step`, with LAMMPS' integer arithmetic (its arguments are truncated to `int`).
fn step_function(f: MathFn, step: i64, a: &[i64]) -> Result<f64, StepFnError> {
    use StepFnError::*;
    let (v1, v2) = (a[0], a[1]);
    Ok(match f {
        MathFn::Stagger => {
            if v1 <= 0 || v2 <= 0 || v1 <= v2 {
                return Err(Invalid);
            }
            let lower = step / v1 * v1;
            if step - lower < v2 {
                (lower + v2) as f64
            } else {
                (lower + v1) as f64
            }
        }
        MathFn::Logfreq => {
            let v3 = a[2];
            if v1 <= 0 || v2 <= 0 || v3 <= 0 || v2 >= v3 {
                return Err(Invalid);
            }
            if step < v1 {
                v1 as f64
            } else {
                let mut lower = v1;
                while step >= v3 * lower {
                    lower *= v3;
                }
                let multiple = step / lower;
                if multiple < v2 {
                    ((multiple + 1) * lower) as f64
                } else {
                    (lower * v3) as f64
                }
            }
        }
        MathFn::Logfreq2 => {
            let v3 = a[2];
            if v1 <= 0 || v2 <= 0 || v3 <= 0 {
                return Err(Invalid);
            }
            if step < v1 {
                v1 as f64
            } else {
                let mut value = v1 as f64;
                let mut delta = v1 as f64 * (v3 as f64 - 1.0) / v2 as f64;
                let mut count = 0;
                while step as f64 >= value {
                    value += delta;
                    count += 1;
                    if count % v2 == 0 {
                        delta *= v3 as f64;
                    }
                }
                value.ceil()
            }
        }
        MathFn::Logfreq3 => {
            let v3 = a[2];
            if v1 <= 0 || v2 <= 1 || v3 <= 0 || v3 - v1 + 1 < v2 {
                return Err(Invalid);
            }
            let mut value = v1 as f64;
            if step >= v1 {
                let mut logsp = v1 as f64;
                let factor = (v3 as f64 / v1 as f64).powf(1.0 / (v2 - 1) as f64);
                let mut linsp = v1;
                while step as f64 >= value {
                    logsp *= factor;
                    linsp += 1;
                    if linsp as f64 > logsp {
                        value = linsp as f64;
                    } else {
                        let c = logsp.ceil();
                        value = c - (((c as i64) - 1) / v3) as f64;
                    }
                }
            }
            if step > v3 {
                return Err(Exceeded);
            }
            value
        }
        MathFn::Stride => {
            let v3 = a[2];
            if v1 < 0 || v2 < 0 || v3 <= 0 || v1 > v2 {
                return Err(Invalid);
            }
            if step < v1 {
                v1 as f64
            } else if step < v2 {
                let next = v1 + (step - v1) / v3 * v3 + v3;
                if next > v2 {
                    MAXBIGINT
                } else {
                    next as f64
                }
            } else {
                MAXBIGINT
            }
        }
        MathFn::Stride2 => {
            let (v3, v4, v5, v6) = (a[2], a[3], a[4], a[5]);
            if v1 < 0 || v2 < 0 || v3 <= 0 || v1 > v2 {
                return Err(Invalid);
            }
            if v4 < 0 || v5 < 0 || v6 <= 0 || v4 > v5 {
                return Err(Invalid);
            }
            if v4 < v1 || v5 > v2 {
                return Err(Invalid);
            }
            if step < v1 {
                v1 as f64
            } else if step < v2 {
                if step < v4 || step > v5 {
                    let mut next = v1 + (step - v1) / v3 * v3 + v3;
                    if step < v4 && next > v4 {
                        next = v4;
                    }
                    next as f64
                } else {
                    let mut next = v4 + (step - v4) / v6 * v6 + v6;
                    if next > v5 {
                        next = v1 + (v5 - v1) / v3 * v3 + v3;
                        if next > v2 {
                            return Ok(MAXBIGINT);
                        }
                    }
                    next as f64
                }
            } else {
                MAXBIGINT
            }
        }
        _ => 0.0,
    })
}

/// Group, special, feature and unknown functions.
fn function(e: &Expr, name: &str, args: &[String], ctx: &mut dyn EvalContext) -> Result<f64, ExprError> {
    if let Some(r) = ctx.group_function(name, args) {
        return r.map_err(|m| e.err(m));
    }
    if GROUP_FUNCTIONS.contains(&name) {
        return Err(e.err(format!("group function {name}() is not available here")));
    }
    if name == "is_file" {
        if args.len() != 1 {
            return Err(e.err("Invalid is_file() function in variable formula").with_help("is_file(name) takes 1 argument"));
        }
        return Ok(bool_value(std::path::Path::new(&args[0]).is_file()));
    }
    if let Some(r) = special_function(name, args, ctx) {
        return r.map_err(|m| e.err(m));
    }
    if UNSUPPORTED_FUNCTIONS.contains(&name) {
        return Err(e.err(format!("{name}() is a LAMMPS function that dmhs does not support")));
    }
    let mut err = e.err(format!("Invalid math/group/special/feature function '{name}()' in variable formula"));
    let known = MATH_FUNCTIONS.iter().map(|m| m.0).chain(GROUP_FUNCTIONS.iter().copied());
    if let Some(h) = crate::suggest::did_you_mean_help(name, known) {
        err = err.with_help(h);
    }
    Err(err)
}

/// `sum()`, `min()`, `max()`, `ave()`, `trap()` and `slope()` of a global vector or array
/// column, with LAMMPS' order of operations and messages (Variable::special_function).
/// `None`: not one of them.
fn special_function(name: &str, args: &[String], ctx: &mut dyn EvalContext) -> Option<Result<f64, String>> {
    const BIG: f64 = 1.0e20;
    if !["sum", "min", "max", "ave", "trap", "slope"].contains(&name) {
        return None;
    }
    Some((|| {
        let [arg] = args else {
            return Err(format!("Invalid special function {name}() in variable formula"));
        };
        let (body, column) = match arg.find('[') {
            None => (arg.as_str(), None),
            Some(k) => {
                let inside = arg[k + 1..].strip_suffix(']').ok_or("Mismatched brackets in variable")?;
                if inside.is_empty() {
                    return Err("Empty brackets in variable".into());
                }
                if !inside.bytes().all(|b| b.is_ascii_digit()) {
                    return Err("Non digit character between brackets in variable".into());
                }
                match inside.parse::<usize>() {
                    Ok(n) if n > 0 => (&arg[..k], Some(n)),
                    _ => return Err("Index between variable brackets must be positive".into()),
                }
            }
        };
        let vec = if let Some(id) = body.strip_prefix("c_") {
            ctx.global_values(true, id, column)?
        } else if let Some(id) = body.strip_prefix("f_") {
            ctx.global_values(false, id, column)?
        } else if let Some(v) = body.strip_prefix("v_") {
            if column.is_some() || variables::style_of(ctx, v).is_none() {
                return Err("Invalid special function in variable formula".into());
            }
            if variables::style_of(ctx, v) != Some("vector") {
                return Err("Mis-matched special function variable in variable formula".into());
            }
            ctx.vector_variable(v)?
        } else {
            return Err("Invalid special function in variable formula".into());
        };
        let n = vec.len();
        let mut value = match name {
            "min" => BIG,
            "max" => -BIG,
            _ => 0.0,
        };
        let (mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0);
        for (i, &one) in vec.iter().enumerate() {
            match name {
                "min" => value = if value < one { value } else { one },
                "max" => value = if value > one { value } else { one },
                "slope" => {
                    let x = i as f64;
                    sx += x;
                    sy += one;
                    sxx += x * x;
                    sxy += x * one;
                }
                _ => value += one,
            }
        }
        match name {
            "trap" if n > 0 => value -= 0.5 * vec[0] + 0.5 * vec[n - 1],
            "ave" => value /= n as f64,
            "slope" => {
                let numerator = n as f64 * sxy - sx * sy;
                let denominator = n as f64 * sxx - sx * sx;
                value = if denominator != 0.0 { numerator / denominator } else { BIG };
            }
            _ => {}
        }
        Ok(value)
    })())
}
