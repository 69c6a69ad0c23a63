//! Atom-style variables evaluated over the owned atoms (LAMMPS' Variable::compute_atom), for
//! `group ID dynamic ... var V`, `set ... v_V` and `group ID variable V`. A formula tree is
//! walked once: a node is one number for every atom or a value per atom; per-atom operations
//! are made atom by atom with the scalar evaluator on a node of numbers, so each atom gets the
//! operations (and bits) of an equal-style formula. `random()` and `normal()` draw one number
//! per atom, in LAMMPS' local order, from the simulation's [`AtomRandom`].

use crate::engine::random_mars::{RanMars, SEED_RANGE};
use crate::models::compute::{property::Field, PerAtomRef};
use crate::models::world::World;
use dmhs_parser::expr::{self, Expr, Index, MathFn, Node};
use dmhs_parser::EvalContext;

/// A formula node's value: one number for every element, or one per element (per atom here,
/// per vector element in [`super::vector_formula`]).
pub(crate) enum V {
    Scalar(f64),
    Many(Vec<f64>),
}

impl V {
    pub(crate) fn at(&self, i: usize) -> f64 {
        match self {
            V::Scalar(x) => *x,
            V::Many(v) => v[i],
        }
    }
}

/// The generator of `random()` and `normal()` in atom-style formulas (LAMMPS'
/// `Variable::randomatom`): one per simulation, made by the first such call with its seed
/// (seed + rank 0) and kept for every later evaluation.
pub type AtomRandom = Option<RanMars>;

/// The value of atom-style variable `name` for each owned atom, in local order (formulas
/// without random numbers; a fix hook has no generator to draw from).
pub fn atom_variable(name: &str, w: &World, ctx: &mut dyn EvalContext) -> Result<Vec<f64>, String> {
    atom_variable_drawing(name, w, ctx, None)
}

/// [`atom_variable`] as an input of fix `style` (ave/atom, ave/chunk), which LAMMPS requires to
/// exist and to be atom-style, with its messages.
pub fn atom_variable_input(style: &str, name: &str, w: &World, ctx: &mut dyn EvalContext) -> Result<Vec<f64>, String> {
    match ctx.variables().style(name) {
        None => Err(format!("Variable name {name} for fix {style} does not exist")),
        Some("atom" | "atomfile") => atom_variable(name, w, ctx),
        Some(_) => Err(format!("Fix {style} variable {name} is not atom-style variable")),
    }
}

/// [`atom_variable`], drawing `random()` and `normal()` from `rng` (None: refused).
pub fn atom_variable_drawing(name: &str, w: &World, ctx: &mut dyn EvalContext, rng: Option<&mut AtomRandom>) -> Result<Vec<f64>, String> {
    let n = w.state.atoms.nlocal;
    match eval_variable(name, w, ctx, 0, rng)? {
        V::Scalar(x) => Ok(vec![x; n]),
        V::Many(v) => Ok(v),
    }
}

fn eval_variable(name: &str, w: &World, ctx: &mut dyn EvalContext, depth: usize, rng: Option<&mut AtomRandom>) -> Result<V, String> {
    if depth > 32 {
        return Err(format!("variable {name}: variables refer to each other in a loop"));
    }
    let vars = ctx.variables();
    match vars.style(name) {
        None => Err(format!("variable {name} does not exist")),
        Some("atom") => {
            let text = vars.formula(name).unwrap_or_default().to_string();
            let tree = expr::parse(&text).map_err(|e| format!("variable {name}: {}", e.message))?;
            // LAMMPS draws per atom for the whole tree; dmhs walks node by node, which gives
            // the same numbers only with one draw per formula
            if count_draws(&tree) > 1 {
                return Err(format!("variable {name}: dmhs supports one random() or normal() per atom-style formula"));
            }
            eval_tree(&tree, w, ctx, depth + 1, rng)
        }
        // the file's value of each atom by ID, 0 for atoms it does not list
        Some("atomfile") => {
            let values = vars.atomfile_values(name).expect("an atomfile variable");
            let a = &w.state.atoms;
            Ok(V::Many(a.tag[..a.nlocal].iter().map(|t| values.get(t).copied().unwrap_or(0.0)).collect()))
        }
        Some(_) => {
            let tree = Expr { node: Node::Variable { name: name.to_string(), index: None }, offset: 0, len: 0 };
            scalar(&tree, ctx)
        }
    }
}

fn scalar(e: &Expr, ctx: &mut dyn EvalContext) -> Result<V, String> {
    expr::eval(e, ctx).map(V::Scalar).map_err(|e| e.message)
}

fn number(x: f64) -> Expr {
    Expr { node: Node::Number(x), offset: 0, len: 0 }
}

/// `op` of the children's values, element by element (`n` of them) where any of them has one
/// value per element: each element gets the scalar evaluator's operations on its numbers.
pub(crate) fn per_atom(e: &Expr, kids: Vec<V>, n: usize, ctx: &mut dyn EvalContext, rebuild: impl Fn(Vec<Expr>) -> Node) -> Result<V, String> {
    let any = kids.iter().any(|k| matches!(k, V::Many(_)));
    let count = if any { n } else { 1 };
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let node = rebuild(kids.iter().map(|k| number(k.at(i))).collect());
        out.push(expr::eval(&Expr { node, offset: e.offset, len: e.len }, ctx).map_err(|e| e.message)?);
    }
    Ok(if any { V::Many(out) } else { V::Scalar(out[0]) })
}

fn peratom_ref(prefix: &str, id: &str, indices: &[Index], w: &World) -> Option<Result<V, String>> {
    let cols = if prefix == "c_" { w.compute(id)?.peratom_cols()? } else { w.fix(id)?.peratom_cols()? };
    let _ = cols;
    let name = match indices {
        [] => format!("{prefix}{id}"),
        [Index::Number(k)] => format!("{prefix}{id}[{k}]"),
        _ => return Some(Err(format!("{prefix}{id}: only a number may index a per-atom value here"))),
    };
    Some((|| {
        let r = PerAtomRef::parse(&name, w).expect("c_ or f_")?;
        let p = r.values(w)?;
        Ok(V::Many((0..w.state.atoms.nlocal).map(|i| r.get(&p, i)).collect()))
    })())
}

/// How many `random()` and `normal()` calls a formula tree makes itself.
fn count_draws(e: &Expr) -> usize {
    match &e.node {
        Node::Unary(_, a) => count_draws(a),
        Node::Binary(_, a, b) => count_draws(a) + count_draws(b),
        Node::Math(f, args) => usize::from(matches!(f, MathFn::Random | MathFn::Normal)) + args.iter().map(count_draws).sum::<usize>(),
        _ => 0,
    }
}

/// `random(lo,hi,seed)` or `normal(mu,sigma,seed)` for every owned atom, drawn in LAMMPS' local
/// order as Variable::compute_atom does (its error messages).
fn draw(f: MathFn, args: &[Expr], w: &World, ctx: &mut dyn EvalContext, depth: usize, rng: Option<&mut AtomRandom>) -> Result<V, String> {
    let name = if f == MathFn::Normal { "normal" } else { "random" };
    let Some(rng) = rng else {
        return Err(format!("{name}() in an atom-style variable is supported where set or group evaluates it, not during a run"));
    };
    let n = w.state.atoms.nlocal;
    let a = eval_tree(&args[0], w, ctx, depth, Some(&mut *rng))?;
    let b = eval_tree(&args[1], w, ctx, depth, Some(&mut *rng))?;
    if rng.is_none() {
        // the seed is read once, when the generator is made
        let seed = match eval_tree(&args[2], w, ctx, depth, Some(&mut *rng))? {
            V::Scalar(s) => s as i32,
            V::Many(_) => 0,
        };
        if seed <= 0 {
            return Err("Invalid math function in variable formula".into());
        }
        if !SEED_RANGE.contains(&(seed as i64)) {
            return Err("Invalid seed for Marsaglia random # generator".into());
        }
        *rng = Some(RanMars::new(seed));
    }
    let r = rng.as_mut().expect("made above");
    let mut out = vec![0.0; n];
    for &i in w.state.lammps_order.indices(n).iter() {
        let (x, y) = (a.at(i), b.at(i));
        out[i] = if f == MathFn::Normal {
            if y < 0.0 {
                return Err("Invalid math function in variable formula".into());
            }
            x + y * r.gaussian()
        } else {
            if y < x {
                return Err("Invalid math function in variable formula".into());
            }
            r.uniform() * (y - x) + x
        };
    }
    Ok(V::Many(out))
}

fn eval_tree(e: &Expr, w: &World, ctx: &mut dyn EvalContext, depth: usize, mut rng: Option<&mut AtomRandom>) -> Result<V, String> {
    let n = w.state.atoms.nlocal;
    match &e.node {
        Node::Unary(op, a) => {
            let k = vec![eval_tree(a, w, ctx, depth, rng)?];
            per_atom(e, k, n, ctx, |mut c| Node::Unary(*op, Box::new(c.remove(0))))
        }
        Node::Binary(op, a, b) => {
            let k = vec![eval_tree(a, w, ctx, depth, rng.as_deref_mut())?, eval_tree(b, w, ctx, depth, rng)?];
            per_atom(e, k, n, ctx, |mut c| {
                let y = c.pop().expect("two");
                Node::Binary(*op, Box::new(c.pop().expect("two")), Box::new(y))
            })
        }
        Node::Math(f @ (MathFn::Random | MathFn::Normal), args) if args.len() == 3 => draw(*f, args, w, ctx, depth, rng),
        Node::Math(f, args) => {
            if *f == MathFn::Ternary && args.len() == 3 {
                let c = eval_tree(&args[0], w, ctx, depth, rng.as_deref_mut())?;
                let (t, f) = (eval_tree(&args[1], w, ctx, depth, rng.as_deref_mut())?, eval_tree(&args[2], w, ctx, depth, rng)?);
                return Ok(match c {
                    V::Scalar(c) => if c != 0.0 { t } else { f },
                    V::Many(c) => V::Many((0..n).map(|i| if c[i] != 0.0 { t.at(i) } else { f.at(i) }).collect()),
                });
            }
            let mut k = Vec::with_capacity(args.len());
            for a in args {
                k.push(eval_tree(a, w, ctx, depth, rng.as_deref_mut())?);
            }
            per_atom(e, k, n, ctx, |c| Node::Math(*f, c))
        }
        Node::Function { name, args } if matches!(name.as_str(), "gmask" | "rmask" | "grmask") => mask_function(name, args, w).map(V::Many),
        Node::Variable { name, index: None } => eval_variable(name, w, ctx, depth, rng),
        Node::Compute { id, indices } => peratom_ref("c_", id, indices, w).unwrap_or_else(|| scalar(e, ctx)),
        Node::Fix { id, indices } => peratom_ref("f_", id, indices, w).unwrap_or_else(|| scalar(e, ctx)),
        // a fix property/atom's custom values (LAMMPS' i_name and d_name in atom-style formulas)
        Node::Thermo(name) if (name.starts_with("i_") || name.starts_with("d_")) && w.state.atoms.find_extra(name).is_some() => {
            let k = w.state.atoms.find_extra(name).expect("checked");
            Ok(V::Many(w.state.atoms.extra[k].data[..n].to_vec()))
        }
        Node::AtomVector(name) => {
            let f = Field::parse(name).ok_or_else(|| format!("`{name}` is not a per-atom value dmhs knows"))?;
            f.check(w.state)?;
            Ok(V::Many((0..n).map(|i| f.value(w.state, i)).collect()))
        }
        _ => scalar(e, ctx),
    }
}

/// LAMMPS' atom-style special functions gmask(group), rmask(region), grmask(group,region): 1
/// for an atom in the group and/or the region, else 0.
fn mask_function(name: &str, args: &[String], w: &World) -> Result<Vec<f64>, String> {
    let state = w.state;
    let want = if name == "grmask" { 2 } else { 1 };
    if args.len() != want {
        return Err(format!("Invalid {name}() function in variable formula: it takes {want} argument(s)"));
    }
    let group = |g: &str| state.groups.bit(g).ok_or_else(|| format!("Group ID {g} in variable formula does not exist"));
    let region = |r: &str| state.regions.iter().find(|reg| reg.id == r).ok_or_else(|| format!("Region ID {r} in variable formula does not exist"));
    let (bit, reg) = match name {
        "gmask" => (Some(group(&args[0])?), None),
        "rmask" => (None, Some(region(&args[0])?)),
        _ => (Some(group(&args[0])?), Some(region(&args[1])?)),
    };
    let a = &state.atoms;
    Ok((0..a.nlocal).map(|i| bit.is_none_or(|b| a.mask[i] & b != 0) && reg.is_none_or(|r| r.matches(a.x[i]))).map(|on| if on { 1.0 } else { 0.0 }).collect())
}
