//! delete_atoms random and variable, and mol yes / bond yes, delete LAMMPS' atoms and bonds:
//! tests/delete/in.delete is run by dmhs; the remaining atoms (write_dump, 17 digits) and the
//! lines LAMMPS prints ("Deleted N atoms", "Deleted N bonds", the count warning) are compared with
//! LAMMPS' for the same deck, stored in tests/delete/expected (always) and made now (live).

mod common;

use std::path::PathBuf;

const FILES: [&str; 2] = ["atomic.dump", "mol.dump"];

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/delete")
}

/// The deck's lines about deletions, as LAMMPS prints them (without its source locations).
fn messages(text: &str) -> String {
    let keep = |l: &&str| l.starts_with("Deleted") || l.starts_with("Added") || l.starts_with("WARNING: Delete_atoms");
    text.lines().filter(keep).map(|l| l.split(" (src").next().unwrap().to_string() + "\n").collect()
}

#[test]
fn deletions_match_stored_lammps_output() {
    let tmp = tempfile::tempdir().unwrap();
    let opts = dmhs::deck::DeckOptions {
        vars: vec![("out".into(), vec![tmp.path().display().to_string()])],
        base_dir: Some(deck_dir()),
        capture_text: true,
        ..Default::default()
    };
    let run = dmhs::deck::run_file(&deck_dir().join("in.delete"), &opts).map_err(|f| f.rendered).unwrap();
    for f in FILES {
        let (want, got) = (std::fs::read(deck_dir().join("expected").join(f)).unwrap(), std::fs::read(tmp.path().join(f)).unwrap());
        assert!(want == got, "{f} is not byte-identical to LAMMPS'");
    }
    let want = std::fs::read_to_string(deck_dir().join("expected/messages.txt")).unwrap();
    assert_eq!(messages(run.sim.out.captured.as_deref().unwrap()), want);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn deletions_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.delete", &FILES, 0.0);
}

/// Bad input is a located error.
#[test]
fn bad_delete_atoms_input_is_an_error() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 2 0 2 0 2\ncreate_box 1 box\ncreate_atoms 1 box\nmass * 1.0\n";
    let cases: &[(&str, &str)] = &[
        ("delete_atoms random fraction 1.5 no all NULL 1\n", "fraction"),
        ("delete_atoms random count 40 yes all NULL 1\n", "Delete_atoms count of 40 exceeds number of eligible atoms 32"),
        ("delete_atoms random count 4 no all nowhere 1\n", "Could not find delete_atoms random region ID nowhere"),
        ("delete_atoms random count 4 no all NULL 0\n", "random number seed"),
        ("delete_atoms random half 4 no all NULL 1\n", "random style"),
        ("variable e equal 1\ndelete_atoms variable e\n", "Variable e for delete_atoms is invalid style"),
        ("delete_atoms group all bond yes\n", "Cannot use delete_atoms bond yes for non-molecular systems"),
        ("delete_atoms group all mol yes\n", "Delete_atoms mol yes requires atom attribute molecule"),
    ];
    common::assert_located_errors(base, cases);
}
