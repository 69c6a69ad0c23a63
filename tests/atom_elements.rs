//! One atom's value by atom ID in equal-style formulas: `x[ID]`, `v_name[ID]` of an atom-style
//! variable, `C_ID[ID]`, `C_ID[ID][J]`, `F_ID[ID]`. The thermo table of
//! lammps-refs/decks/in.thermo_atom_elements against LAMMPS' (stored, and LAMMPS run now);
//! LAMMPS' rule for IDs no atom has; located errors.

use dmhs::deck::{run_text, DeckOptions};
use dmhs_parser::variables::compute_equal;

mod common;
mod thermo_tables;

thermo_tables::thermo_table_tests!(["thermo_atom_elements"]);

const ROW: &str = "units lj\natom_style atomic\natom_modify map yes\nregion box block 0 10 -2 2 -2 2\ncreate_box 1 box\n\
    create_atoms 1 single 1 0 0\ncreate_atoms 1 single 2 0 0\ncreate_atoms 1 single 4 0 0 \nmass 1 1.0\n\
    pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0\ncompute st all stress/atom NULL\ncompute ke all ke/atom\n";

/// As LAMMPS' peratom2global: an ID below the largest that no atom has reads 0.
#[test]
fn a_missing_id_reads_zero() {
    let deck = format!("{ROW}group two id 2\ndelete_atoms group two compress no\nvariable r atom 10*x\nvariable a equal x[3]+v_r[1]\nvariable b equal x[2]+v_r[2]+C_ke[2]\nrun 0\n");
    let opts = DeckOptions { screen: false, ..Default::default() };
    let mut run = run_text("ids", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    assert_eq!(compute_equal(&mut run.sim, "a").unwrap(), 14.0);
    assert_eq!(compute_equal(&mut run.sim, "b").unwrap(), 0.0);
}

#[test]
fn bad_elements_are_errors() {
    common::assert_located_errors(
        ROW,
        &[
            ("variable a equal x[4]\nthermo_style custom step v_a\n", "Variable atom ID is out of range"),
            ("variable r atom x\nvariable a equal v_r[9]\nthermo_style custom step v_a\n", "Variable atom ID is out of range"),
            ("variable a equal C_ke[1][1]\nthermo_style custom step v_a\n", "does not compute the requested property"),
            ("variable a equal C_st[1]\nthermo_style custom step v_a\n", "does not compute the requested property"),
            ("variable a equal C_st[1][7]\nthermo_style custom step v_a\n", "compute array is accessed out-of-range"),
            ("variable a equal C_no[1]\nthermo_style custom step v_a\n", "Invalid compute ID 'no' in variable formula"),
            ("variable a equal F_no[1]\nthermo_style custom step v_a\n", "Invalid fix ID 'no' in variable formula"),
            ("variable a equal C_ke\nthermo_style custom step v_a\n", "upper-case C_/F_"),
            ("variable v vector 1\nvariable a equal v_v[2]\nthermo_style custom step v_a\n", "vector-style variable v is accessed out-of-range"),
        ],
    );
}
