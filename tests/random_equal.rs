//! Equal-style `random()` and `normal()`: the thermo table of
//! lammps-refs/decks/in.thermo_random_equal (draws read by thermo, by fix addforce every step and
//! by an immediate `${}` substitution, all from one generator) against LAMMPS' (stored, and LAMMPS
//! run now). The generator's rules and errors are tested in the parser crate.

mod common;
mod thermo_tables;

thermo_tables::thermo_table_tests!(["thermo_random_equal"]);
