//! (temporary stub) The variable store.
use crate::context::EvalContext;
#[derive(Debug, Default)]
pub struct Variables {}
pub fn compute_equal(_ctx: &mut dyn EvalContext, name: &str) -> Result<f64, String> { Err(format!("no variable {name}")) }
