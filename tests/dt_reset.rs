//! fix dt/reset against LAMMPS: every column of the thermo table (dt, time summed over the
//! changing dt, temperature, energies, pressure and its components, the fix's scalar) of the
//! lammps-refs decks thermo_dt_reset (LJ heated by fix langevin), thermo_dt_reset_sph (2D
//! sph/taitwater/morris, whose pressure is LAMMPS' F dot r virial) and thermo_dt_reset_sph3d
//! (3D morris), against lammps-refs/refs/NAME/thermo.txt (and LAMMPS run now, when present).
//! And the errors for bad arguments, located.

mod common;
mod thermo_tables;

const DECKS: [&str; 3] = ["thermo_dt_reset", "thermo_dt_reset_sph", "thermo_dt_reset_sph3d"];

thermo_tables::thermo_table_tests!(DECKS);

/// Bad arguments are located errors.
#[test]
fn bad_dt_reset_commands_are_located_errors() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n";
    let cases: &[(&str, &str)] = &[
        ("fix 3 all dt/reset 0 0.001 NULL 0.004\n", "N (steps between resets)"),
        ("fix 3 all dt/reset 10 -1 NULL 0.004\n", "Tmin must be >= 0"),
        ("fix 3 all dt/reset 10 0.01 0.001 0.004\n", "must be larger than Tmin"),
        ("fix 3 all dt/reset 10 NULL NULL 0.0\n", "Xmax must be > 0"),
        ("fix 3 all dt/reset 10 NULL NULL\n", "missing Xmax"),
        ("fix 3 all dt/reset 10 NULL NULL 0.1 units metal\n", "unknown units"),
        ("fix 3 all dt/reset 10 NULL NULL 0.1 emax 0\n", "emax must be > 0"),
        ("fix 3 all dt/reset 10 NULL NULL 0.1 emin 1\n", "unknown keyword `emin`"),
    ];
    common::assert_located_errors(base, cases);
}
