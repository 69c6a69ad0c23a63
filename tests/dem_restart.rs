//! write_restart / read_restart: a run continued from a restart file ends in exactly the same
//! state (every bit of every position, velocity and angular velocity) as the uninterrupted run,
//! contact histories included; the same continuation without the stored histories does not.
//! Also: granular runs give the same bits on 1, 2 and 3 threads.

use dmhs::tools::crosscheck::capture_state;
use dmhs::deck::{run_file, DeckOptions};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Run a deck file with the given thread count; return the final state as text.
fn run(deck: &Path, threads: usize) -> String {
    let opts = DeckOptions { base_dir: Some(deck.parent().unwrap().to_path_buf()), ..Default::default() };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let r = pool.install(|| run_file(deck, &opts)).map_err(|f| f.rendered).unwrap();
    capture_state(&r.sim).to_text()
}

/// The reference deck up to (not including) its `run` line, with `nsteps` set.
fn setup_part(name: &str) -> String {
    let text = std::fs::read_to_string(root().join("lammps-refs/decks").join(name)).unwrap();
    text.lines().take_while(|l| !l.starts_with("run")).collect::<Vec<_>>().join("\n") + "\n"
}

/// The lines of the reference deck a continuation must repeat (fixes, neighbour settings,
/// output): everything from the first line that matches one of `keys`.
fn redefinitions(name: &str, keys: &[&str]) -> String {
    let text = std::fs::read_to_string(root().join("lammps-refs/decks").join(name)).unwrap();
    text.lines().filter(|l| keys.iter().any(|k| l.starts_with(k))).collect::<Vec<_>>().join("\n") + "\n"
}

/// Uninterrupted (run N; write_restart; run M) against restarted (read_restart; run M).
fn check_continuation(deck: &str, data: Option<&str>, n: u32, m: u32, keys: &[&str], min_contacts: usize) {
    let dir = tempfile::tempdir().unwrap();
    if let Some(d) = data {
        std::fs::copy(root().join("lammps-refs/decks").join(d), dir.path().join(d)).unwrap();
    }
    let a = dir.path().join("in.a");
    std::fs::write(&a, format!("{}run {n}\nwrite_restart state.restart\nrun {m}\n", setup_part(deck))).unwrap();
    let whole = run(&a, 2);
    let c = dir.path().join("in.c");
    std::fs::write(&c, format!("read_restart state.restart\n{}run {m}\n", redefinitions(deck, keys))).unwrap();
    let restarted = run(&c, 2);
    assert!(whole == restarted, "{deck}: the restarted run differs from the uninterrupted one");

    // without its contact histories the continuation is a different trajectory
    let text = std::fs::read_to_string(dir.path().join("state.restart")).unwrap();
    let mut file: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut removed = 0usize;
    for h in file["contact_histories"].as_array_mut().unwrap() {
        let contacts = h["contacts"].as_array_mut().unwrap();
        removed += contacts.len();
        contacts.clear();
    }
    assert!(removed >= min_contacts, "{deck}: expected at least {min_contacts} contacts in the restart file, found {removed}");
    std::fs::write(dir.path().join("state.restart"), serde_json::to_string(&file).unwrap()).unwrap();
    assert!(run(&c, 2) != whole, "{deck}: dropping the contact histories should change the continuation");
}

#[test]
fn settling_box_restart_is_bit_identical() {
    // pair gran/hooke/history, fix wall/gran (per-atom wall spring), periodic x y
    check_continuation("in.gran_settle_history", None, 700, 500, &["fix", "neighbor", "neigh_modify", "thermo"], 200);
}

#[test]
fn granular_clumps_restart_is_bit_identical() {
    // pair granular between bonded clumps (bonds, angles, special_bonds, exclusions replayed)
    check_continuation("in.gran_clumps_granular", Some("gran_clumps.data"), 1000, 600, &["fix", "neighbor", "neigh_modify", "thermo"], 2);
}

#[test]
fn restart_file_round_trips() {
    // reading a restart and writing it again gives the same file (atoms in the same order)
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("in.a");
    std::fs::write(&a, format!("{}run 300\nwrite_restart one.restart\n", setup_part("in.gran_settle_granular"))).unwrap();
    run(&a, 1);
    let b = dir.path().join("in.b");
    std::fs::write(&b, "read_restart one.restart\nwrite_restart two.restart\n").unwrap();
    run(&b, 1);
    let one = std::fs::read_to_string(dir.path().join("one.restart")).unwrap();
    let two = std::fs::read_to_string(dir.path().join("two.restart")).unwrap();
    assert_eq!(one, two);
}

#[test]
fn granular_same_bits_on_1_2_and_3_threads() {
    for deck in ["in.gran_settle_history", "in.gran_clumps_granular_sphere"] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::copy(root().join("lammps-refs/decks/gran_clumps.data"), dir.path().join("gran_clumps.data")).unwrap();
        let d = dir.path().join("in.deck");
        std::fs::write(&d, format!("{}run 800\n", setup_part(deck))).unwrap();
        let one = run(&d, 1);
        assert_eq!(one, run(&d, 2), "{deck}: 1 and 2 threads differ");
        assert_eq!(one, run(&d, 3), "{deck}: 1 and 3 threads differ");
    }
}
