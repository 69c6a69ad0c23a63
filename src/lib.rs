//! dmhs: the Discrete Multi-Hybrid System engine (SPH + CGMD + DEM), a LAMMPS companion.
//!
//! The crate is in layers; each imports only the layers above it in this list
//! (docs/architecture.md):
//! - [`engine`]: the state the stages borrow (atoms, box, topology, units) and the machinery
//!   every model shares (neighbour lists, threading, contact history, timing);
//! - [`models`]: the physics (pair and bonded styles, fixes, computes, regions), one file per
//!   style and one registry per kind;
//! - [`output`]: what a run writes (log, thermo, dumps, pictures, charts);
//! - [`sim`]: the simulation a deck builds and the time step that drives it;
//! - [`deck`]: LAMMPS commands, data and restart files turned into a simulation;
//! - [`tools`]: the command line and what it offers besides running a deck (crosscheck, bench,
//!   validate, plot).

pub mod engine;
pub mod models;
pub mod output;
pub mod sim;
pub mod deck;
pub mod tools;

pub use dmhs_parser as parser;
