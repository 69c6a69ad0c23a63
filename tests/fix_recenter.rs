//! fix recenter: the thermo table of lammps-refs/decks/in.thermo_recenter against LAMMPS'
//! (stored, and LAMMPS run now), the centre it holds, and located errors.

use dmhs::deck::{run_file, DeckOptions};

mod common;
mod thermo_tables;
use thermo_tables::{root, table};

thermo_tables::thermo_table_tests!(["thermo_recenter"]);

/// After each step the lower half's centre is at its x at the start of the run (INIT) and at
/// the middle of the box in y (fraction 0.5), while z drifts (NULL); f_rc[2] (the y shift,
/// divided by the 500 atoms by thermo's normalisation) moves everything against the drift.
#[test]
fn the_centre_stays_at_its_target() {
    let deck = root().join("lammps-refs/decks/in.thermo_recenter");
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(deck.parent().unwrap().to_path_buf()), ..Default::default() };
    let run = run_file(&deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let (names, rows) = table(run.sim.out.captured.as_deref().unwrap());
    let col = |n: &str| names.iter().position(|c| c == n).unwrap_or_else(|| panic!("no column {n}"));
    let middle = run.sim.state.domain.as_ref().unwrap().hi[1] / 2.0;
    for r in &rows[1..] {
        assert!((r[col("v_lx")] - rows[0][col("v_lx")]).abs() < 1e-13, "step {}", r[0]);
        assert!((r[col("v_ly")] - middle).abs() < 1e-13, "step {}", r[0]);
        assert!(r[col("f_rc[2]")] < 0.0, "step {}", r[0]);
    }
    assert!(rows.last().unwrap()[col("v_lz")] > rows[0][col("v_lz")] + 0.05);
}

#[test]
fn bad_recenters_are_located() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 2 0 2 0 2\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\ngroup none empty\n";
    common::assert_located_errors(
        base,
        &[
            ("fix r all recenter 0 0\n", "z"),
            ("fix r all recenter INIT NULL abc\n", "z"),
            ("fix r all recenter INIT INIT INIT shift nogroup\n", "Could not find fix recenter group ID nogroup"),
            ("fix r all recenter INIT INIT INIT units reduced\n", "units"),
            ("fix r all recenter INIT INIT INIT bias yes\n", "bias"),
            ("fix r none recenter INIT INIT INIT\n", "Fix recenter group has no atoms"),
        ],
    );
}
