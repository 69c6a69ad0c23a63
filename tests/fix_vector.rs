//! fix vector: the thermo table of lammps-refs/decks/in.thermo_fix_vector (a growing vector
//! and array over two runs, nmax, trap() and slope() of them) against LAMMPS' (stored, and
//! LAMMPS run now); the rows it keeps; located errors.

use dmhs::deck::{run_text, DeckOptions};
use dmhs_parser::EvalContext;

mod common;
mod thermo_tables;

thermo_tables::thermo_table_tests!(["thermo_fix_vector"]);

const GAS: &str = "units lj\natom_style atomic\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 random 20 4321 NULL\n\
    mass 1 1.0\npair_style zero 1.0\npair_coeff * *\nvelocity all create 1.0 87287\nfix 1 all nve\n";

/// A row at every multiple of Nevery from the step the fix is defined, each step once over
/// several runs (the setup of the second run repeats no row); nmax keeps the last N.
#[test]
fn rows_are_the_steps_of_nevery() {
    let deck = format!("{GAS}run 3\nvariable s equal step\nfix v all vector 4 v_s\nfix w all vector 4 v_s c_thermo_temp nmax 3\nrun 9\nrun 8\n");
    let opts = DeckOptions { screen: false, ..Default::default() };
    let mut run = run_text("rows", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let sim = &mut run.sim;
    let steps: Vec<f64> = (1..=5).map(|i| sim.fix_value("v", Some(i)).unwrap()).collect();
    assert_eq!(steps, [4.0, 8.0, 12.0, 16.0, 20.0]);
    assert!(sim.fix_value("v", Some(6)).is_err());
    let kept: Vec<f64> = (1..=3).map(|i| sim.fix_array_value("w", i, 1).unwrap()).collect();
    assert_eq!(kept, [12.0, 16.0, 20.0]);
    assert!(sim.fix_array_value("w", 4, 1).is_err() && sim.fix_array_value("w", 1, 3).is_err());
}

#[test]
fn bad_fix_vectors_are_located() {
    common::assert_located_errors(
        GAS,
        &[
            ("fix v all vector 0 c_thermo_temp\n", "Nevery"),
            ("fix v all vector 10\n", "a value"),
            ("fix v all vector 10 c_nope\n", "Compute ID for fix vector does not exist"),
            ("fix v all vector 10 f_nope\n", "Fix ID for fix vector does not exist"),
            ("fix v all vector 10 c_thermo_temp c_thermo_pe\n", "Fix vector cannot set output array intensive/extensive from these inputs"),
            ("fix v all vector 10 c_thermo_temp nmax 0\n", "nmax"),
            ("fix v all vector 10 c_thermo_temp every 2\n", "every"),
            ("fix a all ave/time 4 1 4 c_thermo_temp\nfix v all vector 10 f_a\n", "Fix for fix vector not computed at compatible time"),
            ("fix v all vector 10 v_none\n", "Variable name none for fix vector does not exist"),
            ("variable a atom x\nfix v all vector 10 v_a\n", "Fix vector variable a is not equal-style variable"),
        ],
    );
}
