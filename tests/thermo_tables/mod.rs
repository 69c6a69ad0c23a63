//! The thermo tables of lammps-refs decks against LAMMPS' (tests/thermostats.rs, tests/walls.rs,
//! tests/granular_region.rs):
//! every column at every printed step, from the stored refs/NAME/thermo.txt or LAMMPS run now.
#![allow(dead_code)]

use dmhs::deck::{run_file, DeckOptions};
use std::path::{Path, PathBuf};

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Column names and rows of the last thermo table in `text`.
pub fn table(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().rposition(|l| l.trim_start().trim_start_matches("# ").starts_with("Step")).expect("a thermo header");
    let names = lines[start].trim_start().trim_start_matches("# ").split_whitespace().map(String::from).collect();
    let rows = lines[start + 1..].iter().map_while(|l| l.split_whitespace().map(|w| w.parse::<f64>().ok()).collect::<Option<Vec<f64>>>().filter(|r| !r.is_empty())).collect();
    (names, rows)
}

/// The last thermo table of lammps-refs/decks/in.NAME as dmhs prints it.
pub fn dmhs_table(name: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let deck = root().join("lammps-refs/decks").join(format!("in.{name}"));
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(deck.parent().unwrap().to_path_buf()), ..Default::default() };
    let run = run_file(&deck, &opts).unwrap_or_else(|f| panic!("{name}: {}", f.rendered));
    table(run.sim.out.captured.as_deref().expect("captured screen text"))
}

/// Every column at every printed step within 1e-7 of the column's largest magnitude (thermo
/// prints 8 digits; equal bits print equal text).
fn compare(name: &str, reference: &Path) -> Option<String> {
    let (their_names, theirs) = table(&std::fs::read_to_string(reference).unwrap());
    let (our_names, ours) = dmhs_table(name);
    assert_eq!(our_names, their_names, "{name}: thermo columns");
    assert!(their_names.iter().any(|c| c.starts_with("f_") || c.starts_with("c_") || c == "Press"), "{name}: the deck prints no fix or compute value and not the pressure");
    if ours.len() != theirs.len() {
        return Some(format!("{name}: {} thermo rows, LAMMPS {}", ours.len(), theirs.len()));
    }
    let mut bad = vec![];
    for (c, col) in their_names.iter().enumerate() {
        let scale = theirs.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
        assert!(col == "Step" || scale > 0.0, "{name}: column {col} is zero throughout; it tests nothing");
        let worst = ours.iter().zip(&theirs).map(|(a, b)| (a[c] - b[c]).abs()).fold(0.0, f64::max);
        println!("{name}: {col}: max |dmhs - LAMMPS| {worst:.3e} (scale {scale:.3e})");
        if worst > 1e-7 * scale {
            bad.push(format!("{name}: {col} differs by {worst:e} (scale {scale:e})"));
        }
    }
    (!bad.is_empty()).then(|| bad.join("\n"))
}

/// Every deck against LAMMPS' thermo table: the stored one, or (`live`) LAMMPS run now.
pub fn check_all(decks: &[&str], live: bool) {
    let mut bad = vec![];
    for name in decks {
        let tmp = tempfile::tempdir().unwrap();
        let reference = if live {
            let deck = root().join("lammps-refs/decks").join(format!("in.{name}"));
            dmhs::tools::lammps::run_driver(&deck, &[], tmp.path()).unwrap();
            tmp.path().join("log.lammps")
        } else {
            root().join("lammps-refs/refs").join(name).join("thermo.txt")
        };
        bad.extend(compare(name, &reference));
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The two tests of a file's decks: against the stored tables, and against LAMMPS run now.
macro_rules! thermo_table_tests {
    ($decks:expr) => {
        #[test]
        fn stored_thermo_tables() {
            thermo_tables::check_all(&$decks, false);
        }

        #[test]
        #[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
        fn live_thermo_tables() {
            if dmhs::tools::lammps::python_for_live_test().is_none() {
                return;
            }
            thermo_tables::check_all(&$decks, true);
        }
    };
}
pub(crate) use thermo_table_tests;
