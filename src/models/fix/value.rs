//! A fix argument that is a constant, a variable (`v_name`), or NULL, and its value at a step.

use dmhs_parser::args::word_f64;
use dmhs_parser::{DResult, Word};

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
