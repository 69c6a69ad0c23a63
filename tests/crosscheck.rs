//! `dmhs crosscheck` verdicts against live LAMMPS (skipped without LAMMPS unless
//! DMHS_REQUIRE_LAMMPS=1): decks that agree to round-off, or diverge no faster than LAMMPS from
//! itself, pass; the same decks with one coefficient changed by 1e-6 in dmhs fail.

use dmhs::tools::cli_crosscheck::{dmhs_capture_full, lammps_pair, verdict, DEFAULT_FORCE_TOL, DEFAULT_POS_TOL, DEFAULT_VEL_TOL};
use dmhs::tools::crosscheck::{curve_table, curves};
use std::path::{Path, PathBuf};
use std::process::Command;

const TOLS: [f64; 3] = [DEFAULT_FORCE_TOL, DEFAULT_POS_TOL, DEFAULT_VEL_TOL];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn vars(v: &[(&str, &str)]) -> Vec<(String, Vec<String>)> {
    v.iter().map(|(k, x)| (k.to_string(), vec![x.to_string()])).collect()
}

/// `dmhs crosscheck DECK -var ...`: (exit code, stdout).
fn crosscheck_cli(deck: &Path, v: &[(&str, &str)]) -> (i32, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_dmhs"));
    cmd.arg("crosscheck").arg(deck);
    for (k, x) in v {
        cmd.args(["-var", k, x]);
    }
    let o = cmd.output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout).to_string();
    println!("{out}{}", String::from_utf8_lossy(&o.stderr));
    (o.status.code().unwrap_or(-1), out)
}

/// dmhs on `ours` against LAMMPS on `theirs`: (pass, table and verdict).
fn verdict_of(ours: &Path, ours_vars: &[(&str, &str)], theirs: &Path, theirs_vars: &[(&str, &str)]) -> (bool, String) {
    let (capture, box_len) = dmhs_capture_full(ours, &vars(ours_vars), None).unwrap();
    let steps: Vec<i64> = capture.checkpoints.iter().map(|c| c.0).collect();
    let (base, nudged) = lammps_pair(theirs, &vars(theirs_vars), &steps).unwrap();
    let cs = curves(&capture, &base, &nudged, box_len, TOLS).unwrap();
    let (pass, text) = verdict(&cs);
    let text = format!("{}{text}", curve_table(&cs));
    println!("{text}");
    (pass, text)
}

/// in.settle copied into a temporary folder (it writes a restart file beside itself), and a
/// copy whose normal stiffness kn differs by 1e-6.
fn settle_decks() -> (tempfile::TempDir, PathBuf, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(root().join("examples/dem/in.settle")).unwrap();
    let (plain, kn) = (tmp.path().join("in.settle"), tmp.path().join("in.settle_kn"));
    std::fs::write(&plain, &text).unwrap();
    let changed = text.replace("gran/hooke/history 200000.0 NULL", "gran/hooke/history 200000.2 NULL");
    assert_ne!(changed, text);
    std::fs::write(&kn, changed).unwrap();
    (tmp, plain, kn)
}

#[test]
fn lattice_passes_with_the_force_scale_of_the_run() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let (code, out) = crosscheck_cli(&root().join("tests/decks/crosscheck/in.lattice"), &[]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("PASS") && out.contains("at step 0 it is only"), "{out}");
}

#[test]
fn lattice_with_epsilon_off_by_1e_6_fails() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let deck = root().join("tests/decks/crosscheck/in.lattice");
    let (pass, text) = verdict_of(&deck, &[("eps", "1.000001")], &deck, &[]);
    assert!(!pass, "{text}");
    assert!(text.contains("FAIL force at step 1:"), "{text}");
}

#[test]
fn chaotic_settle_passes_where_it_diverges() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    // 5,000 steps: LAMMPS' own velocity divergence passes the 1e-8 tolerance near step 4,000
    // (10,000 steps, the deck's length, checked by hand: PASS, docs/validation.md)
    let (_tmp, plain, _) = settle_decks();
    let (code, out) = crosscheck_cli(&plain, &[("nsteps", "5000")]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("velocity  agrees within 1e-8 up to step") && out.contains("diverges no faster than LAMMPS from itself"), "{out}");
}

#[test]
fn settle_with_kn_off_by_1e_6_fails() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let (_tmp, plain, kn) = settle_decks();
    let (pass, text) = verdict_of(&kn, &[("nsteps", "2000")], &plain, &[("nsteps", "2000")]);
    assert!(!pass, "{text}");
}

#[test]
fn sph_with_newton_off_and_map_yes_passes() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let (code, out) = crosscheck_cli(&root().join("tests/decks/crosscheck/in.sph_newton_off"), &[]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("desph") && out.contains("PASS"), "{out}");
}
