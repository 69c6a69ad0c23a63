//! fix ave/correlate writes the files LAMMPS writes: tests/ave_correlate/in.ave_correlate (a
//! 256-atom LJ liquid: the heat flux autocorrelation of LAMMPS' KAPPA example, and each pair
//! `type` on three global values with ave one and running, start, prefactor, overwrite, its
//! array read by trap() and fix print) is run by dmhs and its files compared with LAMMPS' files
//! of the same deck, stored in tests/ave_correlate/expected (always) and made now (live).
//!
//! Tolerance: see tests/common/mod.rs. Measured: every correlation file is byte-identical to
//! LAMMPS 22 Jul 2025's after 600 steps; print.txt's last line differs in the 10th digit of one
//! value (the liquid's round-off growth).

mod common;

use std::path::PathBuf;

const FILES: [&str; 8] = ["flux.txt", "auto.txt", "upper.txt", "lower.txt", "auto_upper.txt", "auto_lower.txt", "full.txt", "print.txt"];

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/ave_correlate")
}

#[test]
fn files_match_stored_lammps_output() {
    let tmp = common::run_dmhs(&deck_dir(), "in.ave_correlate");
    let bad = common::compare_dirs(&FILES, &deck_dir().join("expected"), tmp.path());
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    let read = |f: &str| std::fs::read_to_string(tmp.path().join(f)).unwrap();
    // ave running with overwrite keeps one block; ave one writes one per Nfreq step
    assert_eq!(read("auto_upper.txt").lines().count(), 3 + 7);
    assert_eq!(read("auto.txt").matches(" 6\n").count(), 31);
    // start 50: the first block at step 60, its first lag counted from step 50 on
    assert!(read("lower.txt").lines().nth(3) == Some("60 6"), "{}", read("lower.txt"));
    // the Green-Kubo integral is there and not zero
    assert!(read("print.txt").lines().nth(4).unwrap().contains("count 119 k11 2.0915"), "{}", read("print.txt"));
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn files_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.ave_correlate", &FILES, 1e-5);
}

/// Bad input is a located error (deck:line:col and what was expected), never a panic.
#[test]
fn bad_input_is_a_located_error() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\nvariable v vector [1,2]\n";
    let cases: &[(&str, &str)] = &[
        ("fix a all ave/correlate 0 2 10 c_thermo_temp\n", "Illegal fix ave/correlate command: Nevery, Nrepeat and Nfreq must be positive"),
        ("fix a all ave/correlate 3 2 10 c_thermo_temp\n", "Nfreq must be a multiple of Nevery"),
        ("fix a all ave/correlate 2 10 10 c_thermo_temp\n", "with ave one, Nfreq must be at least (Nrepeat-1)*Nevery"),
        ("fix a all ave/correlate 2 5 10 c_thermo_temp overwrite\n", "overwrite needs ave running"),
        ("fix a all ave/correlate 2 5 10\n", "a value"),
        ("fix a all ave/correlate 2 5 10 c_nope\n", "Compute ID nope for fix ave/correlate does not exist"),
        ("fix a all ave/correlate 2 5 10 f_nope\n", "Fix ID nope for fix ave/correlate does not exist"),
        ("compute g all gyration\nfix a all ave/correlate 2 5 10 c_g[7]\n", "vector is accessed out-of-range"),
        ("fix a all ave/correlate 2 5 10 c_thermo_temp type sideways\n", "sideways"),
        ("fix a all ave/correlate 2 5 10 c_thermo_temp bogus\n", "bogus"),
        ("fix a all ave/correlate 2 5 10 v_v[1]\n", "vector-style variables are not supported"),
        ("fix b all ave/time 1 1 10 c_thermo_temp\nfix a all ave/correlate 5 2 10 f_b\n", "not computed at compatible time"),
    ];
    common::assert_located_errors(base, cases);
}
