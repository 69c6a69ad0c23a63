//! A fix argument that is a constant, a variable (`v_name`), or NULL, and its value at a step.

use dmhs_parser::args::word_f64;
use dmhs_parser::{Args, DResult, Word};

#[derive(Clone, Debug, PartialEq)]
pub enum FixValue {
    Const(f64),
    Variable(String),
    Null,
}

impl FixValue {
    /// Parse a word; `allow_null` accepts `NULL`.
    pub fn parse(w: &Word, what: &str, allow_null: bool) -> DResult<FixValue> {
        if allow_null && w.text == "NULL" {
            return Ok(FixValue::Null);
        }
        if let Some(name) = w.text.strip_prefix("v_") {
            return Ok(FixValue::Variable(name.to_string()));
        }
        Ok(FixValue::Const(word_f64(w, what)?))
    }
    /// Current value (None for NULL); `equal` evaluates an equal-style variable by name.
    pub fn eval(&self, equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<Option<f64>, String> {
        match self {
            FixValue::Const(x) => Ok(Some(*x)),
            FixValue::Null => Ok(None),
            FixValue::Variable(name) => equal(name).map(Some).map_err(|e| format!("variable `{name}`: {e}")),
        }
    }
}

/// A fix argument's value at a step: NULL, one value for every atom, or (an atom-style
/// variable) one per local atom.
pub enum Evaluated {
    Null,
    One(f64),
    PerAtom(Vec<f64>),
}

impl Evaluated {
    /// The value for local atom `i` (None for NULL).
    pub fn at(&self, i: usize) -> Option<f64> {
        match self {
            Evaluated::Null => None,
            Evaluated::One(x) => Some(*x),
            Evaluated::PerAtom(v) => Some(v[i]),
        }
    }
}

/// `NAME` or `NAME[I]` (an input of fix ave/time, ave/histo or vector without its `c_`/`f_`/`v_`
/// prefix, or with it): the name and the 1-based index I, a located error at `w` for a bad one.
pub fn split_index<'t>(text: &'t str, w: &Word, a: &Args) -> DResult<(&'t str, Option<usize>)> {
    match text.find('[') {
        None => Ok((text, None)),
        Some(k) if text.ends_with(']') => {
            let i = text[k + 1..text.len() - 1].parse::<usize>().ok().filter(|&i| i >= 1);
            Ok((&text[..k], Some(i.ok_or_else(|| a.error_at(w, format!("`{}`: the index must be a positive integer", w.text), "bad index"))?)))
        }
        Some(_) => Err(a.error_at(w, format!("`{}`: missing `]`", w.text), "bad index")),
    }
}
