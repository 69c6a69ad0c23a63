//! Vector-style variables (LAMMPS' Variable::compute_vector): the thermo table of
//! lammps-refs/decks/in.thermo_vector_variables (global vectors of computes, an array column,
//! vector variables of vector variables, elements in thermo and in equal-style formulas with a
//! number or a variable as index, sum() and ave()) against LAMMPS' (stored, and LAMMPS run
//! now); and LAMMPS' errors.

use dmhs::deck::{run_text, DeckOptions};

mod thermo_tables;

thermo_tables::thermo_table_tests!(["thermo_vector_variables"]);

const LIQUID: &str = "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\n\
    create_atoms 1 box\nmass 1 1.0\nvelocity all create 1.5 87287 loop geom\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\n\
    compute com all com\ncompute red all reduce sum vx vy vz\nvariable c vector c_com*2\nvariable k equal 1\n";

/// Each formula stops the run at step 0 with (part of) LAMMPS' message.
#[test]
fn bad_vector_variables_stop_the_run() {
    let opts = DeckOptions { screen: false, ..Default::default() };
    for (lines, want) in [
        ("variable t vector c_thermo_temp*c_red\nthermo_style custom step v_t[1]\n", "Inconsistent lengths in vector-style variable"),
        ("variable t vector x*2\nthermo_style custom step v_t[1]\n", "Atom vector in vector-style variable formula"),
        ("thermo_style custom step v_c[4]\n", "the vector has 3 values"),
        ("thermo_style custom step v_k[1]\n", "Thermo custom variable k is not vector-style"),
        ("variable e equal v_c[0]+1\nthermo_style custom step v_e\n", "Index between variable brackets must be positive"),
        ("variable e equal v_c[5]\nthermo_style custom step v_e\n", "vector-style variable c is accessed out-of-range"),
        ("variable e equal v_c\nthermo_style custom step v_e\n", "Vector-style variable in equal-style variable formula"),
    ] {
        let deck = format!("{LIQUID}{lines}run 0\n");
        let f = run_text("vv.deck", &deck, &opts).err().unwrap_or_else(|| panic!("ran: {lines}"));
        assert!(f.rendered.contains(want), "{lines}: expected `{want}`:\n{}", f.rendered);
    }
}

/// An element, the sum and the average of a vector variable agree with the compute it reads.
#[test]
fn elements_sum_and_average_follow_the_compute() {
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let deck = format!("{LIQUID}variable s equal sum(v_c)\nvariable a equal ave(v_c)\nvariable i equal v_c[v_k]\nthermo_style custom step c_com[2] v_c[2] v_i c_com[1] v_s v_a\nthermo_modify format float %.17g\nrun 0\n");
    let run = run_text("vv.deck", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let (_, rows) = thermo_tables::table(run.sim.out.captured.as_deref().unwrap());
    let r = &rows[0];
    assert_eq!(r[2], r[1] * 2.0);
    assert_eq!(r[3], r[4] * 2.0);
    assert!(r[5] > 0.0 && (r[6] - r[5] / 3.0).abs() < 1e-15 * r[5], "{r:?}");
}

/// A constant vector `[v1,v2,...]` and `${name}` of a vector-style variable, printed as
/// LAMMPS 22 Jul 2025 prints them (`print "D ${d}"` gave `D [1,2.5,-3e-07]`).
#[test]
fn constant_vectors_and_their_text() {
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let deck = format!("{LIQUID}variable d vector [1,2.5,-3e-7]\nvariable e equal v_d[2]*2\nprint \"D ${{d}} E ${{e}}\"\n");
    let run = run_text("vv.deck", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.as_deref().unwrap();
    assert!(text.lines().any(|l| l == "D [1,2.5,-3e-07] E 5"), "{text}");
}
