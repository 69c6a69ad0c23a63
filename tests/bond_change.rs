//! fix bond/break and bond/create against LAMMPS: the number of bonds broken/created on every
//! step (thermo columns f_ID[1] and f_ID[2], printed every step by the decks) must be the same
//! as LAMMPS', step by step. Forces at step 0 and the final state of the same decks are
//! compared in tests/lammps_parity.rs.
//!
//! * `stored_event_counts`: against lammps-refs/refs/NAME/thermo.txt (runs everywhere).
//! * `live_event_counts`: against LAMMPS run now (skipped without LAMMPS unless
//!   DMHS_REQUIRE_LAMMPS=1).

use dmhs::deck::{run_file, DeckOptions};
use std::path::{Path, PathBuf};

const DECKS: [&str; 2] = ["bondbreak_capsule", "bondcreate_chain"];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// (step, f_ID[1], f_ID[2]) from the last thermo table in `text` (the last two columns).
fn events(text: &str) -> Vec<(i64, i64, i64)> {
    let start = text.lines().enumerate().filter(|(_, l)| l.trim_start().trim_start_matches("# ").starts_with("Step")).map(|(k, _)| k).last().expect("a thermo header");
    text.lines()
        .skip(start + 1)
        .map_while(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            let step = w.first()?.parse::<i64>().ok()?;
            let n = w.len();
            Some((step, w[n - 2].parse::<f64>().ok()? as i64, w[n - 1].parse::<f64>().ok()? as i64))
        })
        .collect()
}

fn dmhs_events(name: &str) -> Vec<(i64, i64, i64)> {
    let deck = root().join("lammps-refs/decks").join(format!("in.{name}"));
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(deck.parent().unwrap().to_path_buf()), ..Default::default() };
    let run = run_file(&deck, &opts).unwrap_or_else(|f| panic!("{name}: {}", f.rendered));
    events(run.sim.out.captured.as_deref().expect("captured screen text"))
}

fn compare(name: &str, reference: &Path) -> Option<String> {
    let theirs = events(&std::fs::read_to_string(reference).unwrap());
    let ours = dmhs_events(name);
    let changes: Vec<_> = theirs.iter().filter(|e| e.1 != 0).collect();
    println!("{name}: {} steps, LAMMPS events (step, this step, total): {changes:?}", theirs.len());
    assert!(!changes.is_empty(), "{name}: the reference has no bond events; the deck tests nothing");
    (ours != theirs).then(|| {
        let first = ours.iter().zip(&theirs).find(|(a, b)| a != b);
        format!("{name}: event counts differ (dmhs {} rows, LAMMPS {}); first difference (dmhs, LAMMPS): {first:?}", ours.len(), theirs.len())
    })
}

#[test]
fn stored_event_counts() {
    let bad: Vec<String> = DECKS.iter().filter_map(|n| compare(n, &root().join("lammps-refs/refs").join(n).join("thermo.txt"))).collect();
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn live_event_counts() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let mut bad = vec![];
    for name in DECKS {
        let tmp = tempfile::tempdir().unwrap();
        let deck = root().join("lammps-refs/decks").join(format!("in.{name}"));
        dmhs::tools::lammps::run_driver(&deck, &[], tmp.path()).unwrap();
        // the log holds the driver's `run 0` table first, then the deck's run: `events` takes the last
        bad.extend(compare(name, &tmp.path().join("log.lammps")));
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
