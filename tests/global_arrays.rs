//! Global arrays and the special functions over global vectors: `c_ID[i][j]` and `f_ID[i][j]`
//! in thermo and variables, `sum()`, `min()`, `max()`, `ave()`, `trap()`, `slope()` of
//! `c_ID`, `c_ID[j]`, `f_ID` and `f_ID[j]`, and fix ave/histo's `kind`. The thermo table of
//! lammps-refs/decks/in.thermo_global_arrays (compute rdf, fix ave/time in vector mode, fix
//! ave/histo, fix ave/chunk) against LAMMPS' (stored, and LAMMPS run now); trap() of a
//! compute's array column; located errors.

use dmhs::deck::{run_text, DeckOptions};
use dmhs_parser::EvalContext;

mod common;
mod thermo_tables;

thermo_tables::thermo_table_tests!(["thermo_global_arrays"]);

const LIQUID: &str = "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\n\
    create_atoms 1 box\ndisplace_atoms all random 0.05 0.05 0.05 7717\nmass 1 1.0\nvelocity all create 1.5 87287 loop geom\n\
    pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\ncompute rdf all rdf 10\n";

/// trap() of a compute's array column is the trapezoid rule over that column: the sum less half
/// of its first and last elements. (LAMMPS 22 Jul 2025 subtracts, instead of the last element,
/// the one nvec-1 places after the first in the row-major array: docs/commands.md.)
#[test]
fn trap_of_a_compute_column_uses_its_last_row() {
    let deck = format!("{LIQUID}variable t equal trap(c_rdf[3])\nvariable s equal sum(c_rdf[3])\nvariable sl equal slope(c_rdf[2])\nrun 0\n");
    let opts = DeckOptions { screen: false, ..Default::default() };
    let mut run = run_text("trap", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let sim = &mut run.sim;
    let a = sim.computes[sim.find_compute("rdf").unwrap()].array(&sim.world()).unwrap();
    let col: Vec<f64> = a.iter().map(|r| r[2]).collect();
    let sum = col.iter().fold(0.0, |s, x| s + x);
    let value = |sim: &mut dmhs::sim::Simulation, name: &str| dmhs_parser::variables::compute_equal(sim, name).unwrap();
    assert_eq!(value(sim, "s"), sum);
    assert_eq!(value(sim, "t"), sum - (0.5 * col[0] + 0.5 * col[col.len() - 1]));
    assert!(col[col.len() - 1] > 0.0);
    // least squares of g(r) against the row number
    let g: Vec<f64> = a.iter().map(|r| r[1]).collect();
    let n = g.len() as f64;
    let (mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0);
    for (i, y) in g.iter().enumerate() {
        let x = i as f64;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    assert_eq!(value(sim, "sl"), (n * sxy - sx * sy) / (n * sxx - sx * sx));
}

#[test]
fn bad_references_are_errors() {
    let cases: &[(&str, &str)] = &[
        ("thermo_style custom step c_rdf[1][4]\n", "compute array is accessed out-of-range"),
        ("thermo_style custom step c_rdf[11][1]\n", "compute array is accessed out-of-range"),
        ("variable a equal c_rdf[1][0]\nthermo_style custom step v_a\n", "Index between variable brackets must be positive"),
        ("variable a equal sum(c_rdf)\nthermo_style custom step v_a\n", "does not compute the requested property"),
        ("variable a equal sum(c_rdf[2],1)\nthermo_style custom step v_a\n", "Invalid special function sum() in variable formula"),
        ("variable a equal max(c_rdf[4])\nthermo_style custom step v_a\n", "compute array is accessed out-of-range"),
        ("variable a equal ave(c_nothere)\nthermo_style custom step v_a\n", "Invalid compute ID 'nothere' in variable formula"),
        ("variable b equal 1\nvariable a equal ave(v_b)\nthermo_style custom step v_a\n", "Mis-matched special function variable in variable formula"),
        ("variable a equal ave(x)\nthermo_style custom step v_a\n", "Invalid special function in variable formula"),
        ("fix h all ave/histo 1 1 1 0 1 4 c_rdf[2] mode vector\nthermo_style custom step f_h[5][1]\n", "fix array is accessed out-of-range"),
        ("fix h all ave/histo 1 1 1 0 1 4 c_rdf[2] mode vector\nthermo_style custom step f_h[1][4]\n", "fix array is accessed out-of-range"),
        ("fix v all ave/time 1 1 1 c_rdf[2] c_rdf[3] mode vector\nthermo_style custom step f_v[3]\n", "has no global vector element"),
        ("fix v all ave/time 1 1 1 c_rdf[2] mode vector\nthermo_style custom step f_v[3][1]\n", "has no global array"),
    ];
    common::assert_located_errors(LIQUID, cases);
    common::assert_located_errors(
        &format!("{LIQUID}compute ke all ke/atom\n"),
        &[
            ("thermo_style custom step c_rdf[1][2][3]\n", "bad index"),
            ("fix h all ave/histo 1 1 1 0 1 4 c_ke kind global\n", "Fix ave/histo input is invalid compute"),
            ("fix h all ave/histo 1 1 1 0 1 4 vx kind local\n", "is a per-atom value"),
            ("fix h all ave/histo 1 1 1 0 1 4 c_rdf[2] kind peratom mode vector\n", "Fix ave/histo input is invalid compute"),
            ("fix h all ave/histo 1 1 1 0 1 4 c_ke kind atom\n", "kind"),
        ],
    );
}

/// `kind` picks what an input gives: an atom-style variable read as per-atom values.
#[test]
fn kind_peratom_reads_an_atom_variable() {
    let deck = format!("{LIQUID}variable u atom vx*vx\nfix h all ave/histo 1 1 1 0 4 8 v_u mode vector kind peratom\nthermo_style custom step f_h[1]\nrun 0\n");
    let opts = DeckOptions { screen: false, ..Default::default() };
    let mut run = run_text("kind", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    // counted and missed (beyond 4) values: one per atom
    assert_eq!(run.sim.fix_value("h", Some(1)).unwrap() + run.sim.fix_value("h", Some(2)).unwrap(), 256.0);
    let deck = format!("{LIQUID}variable u equal 1\nfix h all ave/histo 1 1 1 0 4 8 v_u mode vector kind peratom\nrun 0\n");
    let f = run_text("kind.deck", &deck, &Default::default()).err().expect("an equal-style variable is not per-atom");
    assert!(f.rendered.contains("not all global, peratom, or local"), "{}", f.rendered);
}
