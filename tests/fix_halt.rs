//! fix halt: the deck lammps-refs/decks/in.fix_halt stops its runs at LAMMPS' steps with LAMMPS'
//! messages (refs/fix_halt/messages.txt, from LAMMPS' log; tests/lammps_parity.rs compares the
//! atoms at the end), the comparisons and `error hard`, and located errors.

use dmhs::deck::{run_file, run_text, DeckOptions};

mod common;

fn root() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn screen(deck: &str) -> String {
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = run_text("halt.deck", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    run.sim.out.captured.clone().unwrap()
}

/// The halt lines and the `print` lines after each run, as LAMMPS 22 Jul 2025 writes them: the
/// first run ends at step 14 (temperature below 2.2 at a check every 7 steps, `error
/// continue`), the second at 21 (the longest bond past 1.7, checked every 3 steps, no message),
/// the third does nothing (`error soft`).
#[test]
fn deck_stops_where_lammps_stops() {
    let deck = root().join("lammps-refs/decks/in.fix_halt");
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(deck.parent().unwrap().to_path_buf()), ..Default::default() };
    let run = run_file(&deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.clone().unwrap();
    let got: Vec<&str> = text.lines().filter(|l| l.starts_with("Fix halt") || l.starts_with("after ")).collect();
    let want = std::fs::read_to_string(root().join("lammps-refs/refs/fix_halt/messages.txt")).unwrap();
    assert_eq!(got, want.lines().collect::<Vec<_>>());
    assert_eq!(run.sim.state.step, 21);
}

const LJ: &str = "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
    pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\nthermo 100\n";

/// Each operator on the step counter (checked every 2 steps): the run ends at the first check at
/// which the comparison holds; `|^` holds when exactly one side is zero.
#[test]
fn operators_compare_as_lammps() {
    for (op, value, stop) in [("<", "3", 2), ("<=", "4", 2), (">", "5", 6), (">=", "6", 6), ("==", "8", 8), ("!=", "2", 4), ("|^", "0", 2)] {
        let deck = format!("{LJ}variable s equal step\nfix h all halt 2 v_s {op} {value}\nrun 20\nprint \"stopped at $(step)\"\n");
        let text = screen(&deck);
        assert!(text.contains(&format!("stopped at {stop}\n")), "{op} {value}: {text}");
        assert!(text.contains(&format!("Fix halt condition for fix-id h met on step {stop} with value {stop}\n")), "{op} {value}: {text}");
    }
}

/// `error hard` stops the deck with the message; `error continue` lets the next run go on.
#[test]
fn hard_errors_and_continue_runs_again() {
    let deck = format!("{LJ}variable s equal step\nfix h all halt 5 v_s >= 5 error hard\nrun 20\n");
    let f = run_text("halt.deck", &deck, &Default::default()).err().expect("hard halt is an error");
    assert!(f.rendered.contains("Fix halt condition for fix-id h met on step 5 with value 5"), "{}", f.rendered);
    let text = screen(&format!("{LJ}variable s equal step\nfix h all halt 5 v_s >= 5 error continue message no\nrun 20\nrun 20\nprint \"at $(step)\"\n"));
    assert!(text.contains("at 10\n") && !text.contains("Fix halt condition"), "{text}");
}

#[test]
fn bad_halts_are_located() {
    common::assert_located_errors(
        LJ,
        &[
            ("fix h all halt 0 v_s < 1\n", "N"),
            ("fix h all halt 1 temp < 1\n", "Invalid fix halt attribute temp"),
            ("fix h all halt 1 v_s => 1\n", "operator"),
            ("fix h all halt 1 v_s < 1 error maybe\n", "error"),
            ("fix h all halt 1 v_s < 1 universe yes\n", "partitions"),
            ("fix h all halt 1 diskfree < 1\n", "diskfree"),
            ("fix h all halt 1 v_s < 1 colour red\n", "colour"),
        ],
    );
    // an unknown or atom-style variable is refused when the run starts, as LAMMPS' init
    for (extra, want) in [("", "Could not find fix halt variable name s"), ("variable s atom x\n", "is not equal-style")] {
        let deck = format!("{LJ}{extra}fix h all halt 1 v_s < 1\nrun 1\n");
        let f = run_text("halt.deck", &deck, &Default::default()).err().expect("refused");
        assert!(f.rendered.contains(want), "{}", f.rendered);
    }
}
