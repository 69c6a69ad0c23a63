//! The state the stages borrow and the machinery every model shares.

pub mod atoms;
pub mod bonded_lists;
pub mod boundary;
pub mod comm;
pub mod contact_history;
pub mod decomp;
pub mod procmap;
pub mod domain;
pub mod fields;
pub mod group_rotation;
pub mod groups;
pub mod jacobi;
pub mod lammps_order;
pub mod lattice;
pub mod memory;
pub mod molecule;
#[cfg(feature = "mpi")]
pub mod mpi_comm;
pub mod neighbor;
pub mod par;
pub mod quat;
/// LAMMPS' generators (in the parser crate: equal-style `random()` draws from RanMars too).
pub use dmhs_parser::random_mars;
pub use dmhs_parser::random_park;
pub mod region;
pub mod special;
pub mod state;
pub mod tally;
pub mod timing;
pub mod topology;
pub mod units;
pub mod water;
