//! fix ave/histo: the files of tests/ave_histo/in.ave_histo (per-atom velocities, the kinetic
//! energy per atom with a running total and extra bins, two global values with a window and end
//! bins) against LAMMPS' files of the same deck, stored in tests/ave_histo/expected and made now
//! (live); the thermo table of lammps-refs/decks/in.thermo_ave_histo (the same fixes, their
//! counts and extremes); and located errors.
//!
//! Measured: every count and bin line is identical to LAMMPS'; the smallest and largest values
//! differ in the last digit where the velocities do (round-off of the trajectory).

use dmhs::deck::run_text;

mod common;
mod thermo_tables;

thermo_tables::thermo_table_tests!(["thermo_ave_histo"]);

const FILES: [&str; 3] = ["h1.txt", "h2.txt", "h3.txt"];

fn deck_dir() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/ave_histo")
}

#[test]
fn files_match_stored_lammps_output() {
    let tmp = common::run_dmhs(&deck_dir(), "in.ave_histo");
    let bad = common::compare_dirs(&FILES, &deck_dir().join("expected"), tmp.path());
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    // the counts and bins are exactly LAMMPS' (only the extremes may differ in the last digit)
    for f in FILES {
        let want = std::fs::read_to_string(deck_dir().join("expected").join(f)).unwrap();
        let got = std::fs::read_to_string(tmp.path().join(f)).unwrap();
        let bins = |s: &str| s.lines().filter(|l| l.split_whitespace().count() == 4).map(String::from).collect::<Vec<_>>();
        assert_eq!(bins(&got), bins(&want), "{f}");
        assert!(bins(&want).len() >= 40, "{f}: the stored file has its bin lines");
    }
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn files_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.ave_histo", &FILES, 1e-12);
}

#[test]
fn bad_histograms_are_located() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\ncompute ke all ke/atom\n";
    common::assert_located_errors(
        base,
        &[
            ("fix h all ave/histo 3 2 10 0 1 5 vx mode vector\n", "inconsistent fix ave/histo Nevery/Nrepeat/Nfreq 3 2 10"),
            ("fix h all ave/histo 1 1 10 1 0 5 vx mode vector\n", "must be below hi"),
            ("fix h all ave/histo 1 1 10 0 1 0 vx mode vector\n", "Nbin"),
            ("fix h all ave/histo 1 1 10 0 1 5 vx\n", "cannot process per-atom values in scalar mode"),
            ("fix h all ave/histo 1 1 10 0 1 5 vx c_thermo_temp mode vector\n", "not all global, peratom, or local"),
            ("fix h all ave/histo 1 1 10 0 1 5 c_nope\n", "Compute ID nope for fix ave/histo does not exist"),
            ("fix h all ave/histo 1 1 10 0 1 5 c_thermo_temp beyond far\n", "beyond"),
            ("fix h all ave/histo 1 1 10 0 1 5 c_thermo_temp overwrite\n", "ave running"),
            ("fix h all ave/histo 1 1 10 0 1 5 c_thermo_temp weights v_w\n", "weights"),
            ("fix h all ave/histo 1 1 10 0 1 5\n", "a value"),
        ],
    );
    // an atom-style variable in scalar mode is refused when the run starts (its style is known then)
    let deck = format!("{base}variable a atom vx\nfix h all ave/histo 1 1 10 0 1 5 v_a\nrun 0\n");
    let f = run_text("bad.deck", &deck, &Default::default()).err().expect("refused");
    assert!(f.rendered.contains("cannot process per-atom values in scalar mode"), "{}", f.rendered);
}
