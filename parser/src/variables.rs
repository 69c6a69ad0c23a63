//! PLACEHOLDER (parser-script helper): index, loop, equal and string variables, enough for the
//! interpreter and its tests. The parser-expr helper's variables.rs replaces this file.

use crate::ast::Word;
use crate::context::EvalContext;
use crate::diag::{DResult, Diagnostic};
use std::collections::HashMap;

#[derive(Clone, Debug)]
enum Kind {
    /// index and loop: a list of values and the current position.
    List(Vec<String>, usize),
    Equal(String),
    Str(String),
}

/// All variables of a run.
#[derive(Debug, Default)]
pub struct Variables {
    vars: HashMap<String, Kind>,
}

impl Variables {
    /// The `variable` command (arguments after `variable`).
    pub fn command(&mut self, args: &[Word]) -> DResult<()> {
        let Some(name) = args.first() else {
            return Err(Diagnostic::error("missing variable name"));
        };
        let Some(style) = args.get(1) else {
            return Err(Diagnostic::at(name.span, "missing variable style", "after this name"));
        };
        let vals: Vec<String> = args[2..].iter().map(|w| w.text.clone()).collect();
        let n = name.text.clone();
        match style.text.as_str() {
            "delete" => {
                self.vars.remove(&n);
            }
            "index" => {
                self.vars.entry(n).or_insert(Kind::List(vals, 0));
            }
            "loop" => {
                let num = |s: &String| s.parse::<i64>().unwrap_or(1);
                let (lo, hi) = match vals.len() {
                    0 => (1, 0),
                    1 => (1, num(&vals[0])),
                    _ => (num(&vals[0]), num(&vals[1])),
                };
                self.vars.entry(n).or_insert_with(|| Kind::List((lo..=hi).map(|i| i.to_string()).collect(), 0));
            }
            "equal" => {
                self.vars.insert(n, Kind::Equal(vals.join(" ")));
            }
            "string" => {
                self.vars.insert(n, Kind::Str(vals.join(" ")));
            }
            s => return Err(Diagnostic::at(style.span, format!("variable style `{s}` is not supported (placeholder)"), "here")),
        }
        Ok(())
    }

    /// `next v1 v2 ...`: true if a variable was exhausted (and all named ones deleted).
    pub fn next(&mut self, args: &[Word]) -> DResult<bool> {
        let mut done = false;
        for w in args {
            match self.vars.get_mut(&w.text) {
                Some(Kind::List(v, i)) => {
                    *i += 1;
                    if *i >= v.len() {
                        done = true;
                    }
                }
                _ => return Err(Diagnostic::at(w.span, format!("invalid variable `{}` in next command", w.text), "here")),
            }
        }
        if done {
            for w in args {
                self.vars.remove(&w.text);
            }
        }
        Ok(done)
    }

    /// `-var NAME V1 V2 ...` from the command line.
    pub fn define_index(&mut self, name: &str, values: Vec<String>) {
        self.vars.insert(name.to_string(), Kind::List(values, 0));
    }

    pub fn exists(&self, name: &str) -> bool {
        self.vars.contains_key(name)
    }
}

/// Text for `$x` / `${name}`; `None` if undefined.
pub fn retrieve(ctx: &mut dyn EvalContext, name: &str) -> Result<Option<String>, String> {
    let kind = ctx.variables().vars.get(name).cloned();
    match kind {
        None => Ok(None),
        Some(Kind::List(v, i)) => Ok(v.get(i).cloned()),
        Some(Kind::Str(s)) => Ok(Some(s)),
        Some(Kind::Equal(f)) => {
            let x = crate::expr::evaluate(&f, ctx).map_err(|e| e.message)?;
            Ok(Some(crate::numfmt::format_g(x, 15)))
        }
    }
}

/// Numeric value of `v_name` (placeholder helper for the placeholder expr.rs).
pub fn numeric_value(ctx: &mut dyn EvalContext, name: &str) -> Result<f64, String> {
    let kind = ctx.variables().vars.get(name).cloned();
    match kind {
        None => Err(format!("invalid variable name `v_{name}` in variable formula")),
        // LAMMPS reads v_name back from its %.15g text (Variable::evaluate uses retrieve + atof)
        Some(Kind::Equal(f)) => {
            let x = crate::expr::evaluate(&f, ctx).map_err(|e| e.message)?;
            Ok(crate::numfmt::format_g(x, 15).parse().unwrap_or(x))
        }
        Some(Kind::List(v, i)) => v.get(i).and_then(|s| s.parse().ok()).ok_or(format!("variable `{name}` is not numeric")),
        Some(Kind::Str(s)) => s.parse().map_err(|_| format!("variable `{name}` is not numeric")),
    }
}

/// Numeric value of `v_name` (same as [`numeric_value`]).
pub fn compute_equal(ctx: &mut dyn EvalContext, name: &str) -> Result<f64, String> {
    numeric_value(ctx, name)
}
