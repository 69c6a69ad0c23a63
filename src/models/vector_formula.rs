//! Vector-style variables (LAMMPS' Variable::compute_vector): a formula whose global vectors
//! (`c_ID`, `f_ID` of a compute or fix with a global vector, even one that also has a scalar,
//! `c_ID[I]` and `f_ID[I]` of one with a global array and no vector: its column I, `v_name` of
//! another vector-style variable) are taken
//! element by element, all of one length, with single values (numbers, thermo keywords,
//! equal-style variables, vector elements) the same for every element. Each element gets the
//! operations of an equal-style formula on its numbers (the scalar evaluator), so the same bits.

use crate::models::world::World;
use dmhs_parser::expr::{self, Expr, Index, Node};
use dmhs_parser::EvalContext;

use super::atom_formula::{per_atom, V};

/// The values of vector-style variable `name`.
pub fn vector_variable(name: &str, w: &World, ctx: &mut dyn EvalContext) -> Result<Vec<f64>, String> {
    vector_of(name, w, ctx, 0)
}

fn vector_of(name: &str, w: &World, ctx: &mut dyn EvalContext, depth: usize) -> Result<Vec<f64>, String> {
    if depth > 32 {
        return Err(format!("variable {name}: variables refer to each other in a loop"));
    }
    let vars = ctx.variables();
    if vars.style(name) != Some("vector") {
        return Err(format!("Variable {name} is not vector-style"));
    }
    let text = vars.formula(name).unwrap_or_default().trim().to_string();
    // a constant vector `[v1,v2,...]`
    if let Some(inner) = text.strip_prefix('[').and_then(|t| t.strip_suffix(']')) {
        return inner
            .split(',')
            .map(|w| w.trim().parse::<f64>().map_err(|_| format!("Variable {name}: invalid constant vector `{text}` (numbers separated by commas)")))
            .collect();
    }
    let tree = expr::parse(&text).map_err(|e| format!("variable {name}: {}", e.message))?;
    // LAMMPS: a formula of single values only gives a vector of length 1
    Ok(match eval_tree(&tree, w, ctx, depth + 1).map_err(|e| format!("variable {name}: {e}"))? {
        V::Scalar(x) => vec![x],
        V::Many(v) => v,
    })
}

/// `op` of the children's values, element by element where any of them is a vector (all of
/// one length).
fn elementwise(e: &Expr, kids: Vec<V>, ctx: &mut dyn EvalContext, rebuild: impl Fn(Vec<Expr>) -> Node) -> Result<V, String> {
    let mut len = None;
    for k in &kids {
        if let V::Many(v) = k {
            match len {
                None => len = Some(v.len()),
                Some(n) if n != v.len() => return Err(format!("Inconsistent lengths in vector-style variable ({n} and {})", v.len())),
                _ => {}
            }
        }
    }
    per_atom(e, kids, len.unwrap_or(1), ctx, rebuild)
}

/// A global vector (no index) or an array's column (one index) of compute or fix `id`; None:
/// the reference is a single value (a scalar, a vector's element), for the scalar evaluator.
fn global(compute: bool, id: &str, indices: &[Index], w: &World, ctx: &mut dyn EvalContext) -> Option<Result<V, String>> {
    let column = match indices {
        [] => None,
        [Index::Number(k)] if *k > 0 => Some(*k as usize),
        _ => return None,
    };
    // as LAMMPS 22 Jul 2025 reads them here: c_ID is the global vector where there is one
    // (compute temp's six components, not its scalar), c_ID[I] the vector's element where
    // there is one, else the array's column
    let (vector, array) = if compute {
        let c = w.compute(id)?;
        (c.vector(w).is_ok(), c.array_cols().is_some())
    } else {
        let f = w.fix(id)?;
        (f.size_vector() > 0, f.size_array().is_some())
    };
    let has = match column {
        None => vector,
        Some(_) => !vector && array,
    };
    has.then(|| ctx.global_values(compute, id, column).map(V::Many))
}

fn eval_tree(e: &Expr, w: &World, ctx: &mut dyn EvalContext, depth: usize) -> Result<V, String> {
    let scalar = |ctx: &mut dyn EvalContext| expr::eval(e, ctx).map(V::Scalar).map_err(|e| e.message);
    match &e.node {
        Node::Unary(op, a) => {
            let k = vec![eval_tree(a, w, ctx, depth)?];
            elementwise(e, k, ctx, |mut c| Node::Unary(*op, Box::new(c.remove(0))))
        }
        Node::Binary(op, a, b) => {
            let k = vec![eval_tree(a, w, ctx, depth)?, eval_tree(b, w, ctx, depth)?];
            elementwise(e, k, ctx, |mut c| {
                let y = c.pop().expect("two");
                Node::Binary(*op, Box::new(c.pop().expect("two")), Box::new(y))
            })
        }
        Node::Math(f, args) => {
            let mut k = Vec::with_capacity(args.len());
            for a in args {
                k.push(eval_tree(a, w, ctx, depth)?);
            }
            elementwise(e, k, ctx, |c| Node::Math(*f, c))
        }
        Node::Variable { name, index: None } if ctx.variables().style(name) == Some("vector") => vector_of(name, w, ctx, depth).map(V::Many),
        Node::Compute { id, indices } => global(true, id, indices, w, ctx).unwrap_or_else(|| scalar(ctx)),
        Node::Fix { id, indices } => global(false, id, indices, w, ctx).unwrap_or_else(|| scalar(ctx)),
        Node::AtomVector(_) => Err("Atom vector in vector-style variable formula".into()),
        _ => scalar(ctx),
    }
}
