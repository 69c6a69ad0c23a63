//! dmhs: the Discrete Multi-Hybrid System engine (SPH + CGMD + DEM), a LAMMPS companion.

pub mod create_atoms;
pub mod domain;
pub mod lattice;
pub mod random_park;
pub mod region;
pub mod units;
pub mod velocity_create;

pub use dmhs_parser as parser;
