//! dmhs: the Discrete Multi-Hybrid System engine (SPH + CGMD + DEM), a LAMMPS companion.

pub mod atoms;
pub mod bonded;
pub mod bonded_forces;
pub mod boundary;
pub mod compute;
pub mod create_atoms;
pub mod domain;
pub mod dump;
pub mod fix;
pub mod format;
pub mod groups;
pub mod lattice;
pub mod memory;
pub mod neighbor;
pub mod output;
pub mod pair;
pub mod progress;
pub mod random_park;
pub mod region;
pub mod run;
pub mod sim;
pub mod special;
pub mod styles;
pub mod thermo;
pub mod timing;
pub mod topology;
pub mod units;
pub mod velocity;
pub mod velocity_create;
pub mod commands;
pub mod data;

pub use dmhs_parser as parser;
