//! An [`EvalContext`] for unit tests: a variable store plus tables of thermo keywords,
//! compute and fix values, group function results and per-atom values.

use crate::context::EvalContext;
use crate::expr::{ATOM_VECTORS, GROUP_FUNCTIONS};
use crate::variables::Variables;
use std::collections::HashMap;

#[derive(Default)]
pub struct TestContext {
    pub vars: Variables,
    /// Thermo keywords (`step`, `dt`, `time`, `vol`, ...).
    pub thermo: HashMap<String, f64>,
    /// `c_ID` (index `None`) and `c_ID[i]`.
    pub computes: HashMap<(String, Option<usize>), f64>,
    /// `f_ID` and `f_ID[i]`.
    pub fixes: HashMap<(String, Option<usize>), f64>,
    /// Group functions by their call text without spaces, e.g. `"xcm(all,x)"`.
    pub groups: HashMap<String, f64>,
    /// Per-atom values by keyword and atom ID.
    pub atoms: HashMap<(String, i64), f64>,
    pub window: Option<(i64, i64)>,
}

impl TestContext {
    pub fn new() -> TestContext {
        TestContext::default()
    }
    /// A context with `step` 0 and `dt` 0.005 (LAMMPS lj defaults).
    pub fn with_step() -> TestContext {
        let mut c = TestContext::new();
        c.thermo.insert("step".into(), 0.0);
        c.thermo.insert("dt".into(), 0.005);
        c
    }
    pub fn thermo(mut self, name: &str, v: f64) -> TestContext {
        self.thermo.insert(name.into(), v);
        self
    }
}

impl EvalContext for TestContext {
    fn variables(&mut self) -> &mut Variables {
        &mut self.vars
    }
    fn thermo_keyword(&mut self, name: &str) -> Option<Result<f64, String>> {
        self.thermo.get(name).map(|&v| Ok(v))
    }
    fn compute_value(&mut self, id: &str, index: Option<usize>) -> Result<f64, String> {
        if !self.computes.keys().any(|(c, _)| c == id) {
            return Err(format!("Invalid compute ID '{id}' in variable formula"));
        }
        self.computes.get(&(id.to_string(), index)).copied().ok_or_else(|| "Mismatched compute in variable formula".to_string())
    }
    fn fix_value(&mut self, id: &str, index: Option<usize>) -> Result<f64, String> {
        if !self.fixes.keys().any(|(c, _)| c == id) {
            return Err(format!("Invalid fix ID '{id}' in variable formula"));
        }
        self.fixes.get(&(id.to_string(), index)).copied().ok_or_else(|| "Mismatched fix in variable formula".to_string())
    }
    fn group_function(&mut self, name: &str, args: &[String]) -> Option<Result<f64, String>> {
        if !GROUP_FUNCTIONS.contains(&name) {
            return None;
        }
        let key = format!("{name}({})", args.join(","));
        Some(self.groups.get(&key).copied().ok_or_else(|| format!("Group {} in variable formula does not exist", args[0])))
    }
    fn atom_value(&mut self, keyword: &str, id: i64) -> Option<Result<f64, String>> {
        if !ATOM_VECTORS.contains(&keyword) {
            return None;
        }
        Some(self.atoms.get(&(keyword.to_string(), id)).copied().ok_or_else(|| "Variable atom ID is too large".to_string()))
    }
    fn run_window(&mut self) -> Option<(i64, i64)> {
        self.window
    }
}
