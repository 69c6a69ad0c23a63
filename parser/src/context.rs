//! The two traits that connect the script layer to the engine.
//!
//! * [`EvalContext`]: what an equal-style expression can ask of the simulation
//!   (thermo keywords, computes, fixes, group functions, per-atom values) and the variable store.
//! * [`Host`]: the engine as seen by the interpreter: it executes every command that is not
//!   flow control (variable, next, jump, label, include, if, print, echo, quit are handled by
//!   the interpreter itself).

use crate::ast::Command;
use crate::diag::{DResult, Diagnostic};
use crate::span::SourceMap;
use crate::variables::Variables;

/// Values an expression may reference. Every method has a default that says "not available",
/// so a test context only implements `variables`.
pub trait EvalContext {
    /// The variable store (for `v_name` and `${name}`).
    fn variables(&mut self) -> &mut Variables;

    /// A thermo keyword used as a bare word in an expression (`step`, `atoms`, `time`, `dt`,
    /// `temp`, `pe`, `ke`, `etotal`, `press`, `vol`, `lx`, `xlo`, ...). `None`: not a keyword.
    fn thermo_keyword(&mut self, _name: &str) -> Option<Result<f64, String>> {
        None
    }
    /// `c_ID` (index `None`) or `c_ID[i]` (1-based) as a global value.
    fn compute_value(&mut self, id: &str, _index: Option<usize>) -> Result<f64, String> {
        Err(format!("compute `{id}` does not exist"))
    }
    /// `f_ID` or `f_ID[i]` as a global value.
    fn fix_value(&mut self, id: &str, _index: Option<usize>) -> Result<f64, String> {
        Err(format!("fix `{id}` does not exist"))
    }
    /// `c_ID[i][j]` (1-based) of a global array.
    fn compute_array_value(&mut self, id: &str, _i: usize, _j: usize) -> Result<f64, String> {
        Err(format!("compute `{id}` does not exist"))
    }
    /// `f_ID[i][j]` (1-based) of a global array.
    fn fix_array_value(&mut self, id: &str, _i: usize, _j: usize) -> Result<f64, String> {
        Err(format!("fix `{id}` does not exist"))
    }
    /// What the special functions `sum()`, `min()`, `max()`, `ave()`, `trap()` and `slope()` run
    /// over: `c_ID`/`f_ID` (`column` None) a global vector, `c_ID[k]`/`f_ID[k]` column k (1-based)
    /// of a global array, in row order. `compute` tells `c_` from `f_`.
    fn global_values(&mut self, compute: bool, id: &str, _column: Option<usize>) -> Result<Vec<f64>, String> {
        Err(format!("{} `{id}` does not exist", if compute { "compute" } else { "fix" }))
    }
    /// `C_ID[I]` (`column` None) or `C_ID[I][J]` (`compute` true; `F_` alike): atom I's value of
    /// a per-atom vector or array column J.
    fn peratom_element(&mut self, compute: bool, id: &str, _column: Option<usize>, _atom: i64) -> Result<f64, String> {
        Err(format!("{} `{id}` does not exist", if compute { "compute" } else { "fix" }))
    }
    /// `v_name[I]` of atom-style variable `name`: its value for atom I.
    fn atom_variable_element(&mut self, name: &str, _atom: i64) -> Result<f64, String> {
        Err(format!("Variable {name}: per-atom values are not available here"))
    }
    /// The values of vector-style variable `name` (LAMMPS' Variable::compute_vector).
    fn vector_variable(&mut self, name: &str) -> Result<Vec<f64>, String> {
        Err(format!("Variable {name}: vector-style variables are not available here"))
    }
    /// Group and region functions: `count(group)`, `mass(group)`, `xcm(group,x)`, `bound(group,xmin)`, ...
    /// `None`: not a group function.
    fn group_function(&mut self, _name: &str, _args: &[String]) -> Option<Result<f64, String>> {
        None
    }
    /// A per-atom value referenced by atom ID: `x[12]`, `vx[3]`, `mass[5]`, `type[7]`, ...
    /// `None`: not a per-atom keyword.
    fn atom_value(&mut self, _keyword: &str, _id: i64) -> Option<Result<f64, String>> {
        None
    }
    /// First and last step of the current (or last) `run` (for `ramp()`, `vdisplace()`, ...).
    /// `None` before any run.
    fn run_window(&mut self) -> Option<(i64, i64)> {
        None
    }
}

/// The engine as the interpreter drives it.
pub trait Host: EvalContext {
    /// Execute one command (already substituted and split into words).
    fn execute(&mut self, cmd: &Command, sources: &mut SourceMap) -> DResult<()>;
    /// Write text to the screen and the log file (both as configured by the host).
    fn print(&mut self, text: &str);
    /// Echo a command line (the `echo` command chooses screen and/or log).
    fn echo(&mut self, text: &str, screen: bool, log: bool) {
        if screen || log {
            self.print(text);
        }
    }
    /// Whether the engine implements a command (the interpreter reports all unknown and
    /// unsupported command names of a file before running it).
    fn supports_command(&self, name: &str) -> bool;
    /// The IDs of the atoms that exist now (this rank's) and the largest atom ID of all ranks
    /// (for atomfile variables).
    fn atom_ids(&mut self) -> (Vec<i64>, i64) {
        (Vec::new(), 0)
    }
    /// A fix halt ended the runs (LAMMPS' expired timer): `run ... every` stops its segments.
    fn run_halted(&self) -> bool {
        false
    }
    /// Report a warning (the host decides where it goes).
    fn warn(&mut self, warning: Diagnostic, sources: &SourceMap) {
        self.print(&warning.render(sources));
    }
}
