//! The command line and what it offers besides running a deck: crosscheck and capture against
//! LAMMPS/LIGGGHTS, benchmarks, validation against analytic references, charts. Nothing in the
//! time step imports this layer.

pub mod analytic;
pub mod bench;
pub mod cli;
pub mod cli_crosscheck;
pub mod crosscheck;
pub mod lammps;
pub mod liggghts;
pub mod measure;
pub mod plot_cmd;
pub mod validate;
pub mod validate_convergence;
