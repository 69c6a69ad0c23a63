//! Heat sub-models of `pair_style granular` (LAMMPS gran_sub_mod_heat.cpp): conduction through
//! the contact (LAMMPS' `radius`, `area`), which needs atom temperatures. dmhs has none yet (its
//! own conduction between particles is pair dmhs/heatconduction): the table is empty, and
//! `heat NAME` is refused with a located error.

use super::Style;

/// No heat model is supported yet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Heat {}

/// The heat models dmhs supports.
pub static STYLES: &[Style<Heat>] = &[];
