//! The state the stages borrow and the machinery every model shares.

pub mod atoms;
pub mod bonded_lists;
pub mod boundary;
pub mod comm;
pub mod contact_history;
pub mod decomp;
pub mod domain;
pub mod fields;
pub mod groups;
pub mod lammps_order;
pub mod lattice;
pub mod molecule;
pub mod neighbor;
pub mod par;
pub mod quat;
pub mod random_mars;
pub mod random_park;
pub mod region;
pub mod special;
pub mod state;
pub mod tally;
pub mod timing;
pub mod topology;
pub mod units;
pub mod water;
