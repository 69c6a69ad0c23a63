//! The physics: pair styles, bonded styles, fixes, computes and regions. One style is one file;
//! each kind has one registry list that maps LAMMPS style names to constructors.

pub mod atom_formula;
pub mod bonded;
pub mod compute;
pub mod fix;
pub mod pair;
pub mod styles;
pub mod vector_formula;
pub mod world;

/// One time-step limit of a model (shown by `dmhs check` and warned about at the start of a run).
#[derive(Clone, Debug, PartialEq)]
pub struct Limit {
    pub model: String,
    pub rule: String,
    pub dt_max: f64,
}
