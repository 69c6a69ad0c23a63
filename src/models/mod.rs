//! The physics: pair styles, bonded styles, fixes, computes and regions. One style is one file;
//! each kind has one registry list that maps LAMMPS style names to constructors.

pub mod bonded;
pub mod compute;
pub mod fix;
pub mod pair;
pub mod styles;
pub mod world;
