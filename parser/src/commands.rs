//! (temporary stub until the command tables land)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StyleKind { Pair, Bond, Angle, Dihedral, Improper, Fix, Compute, AtomStyle, Region, Dump }
pub fn is_lammps_style(_k: StyleKind, _name: &str) -> bool { false }
