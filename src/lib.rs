//! dmhs: the Discrete Multi-Hybrid System engine (SPH + CGMD + DEM), a LAMMPS companion.

pub mod bonded;
pub mod domain;
pub mod special;
pub mod units;

pub use dmhs_parser as parser;
