//! The BPM bond styles (bpm/spring, bpm/rotational) against LAMMPS beyond what lammps_parity.rs
//! compares (forces at step 0, the state after the run of lammps-refs/decks/in.bond_bpm_*): the
//! bonds that break, and when, and the thermo table. The breaking decks write the broken bonds
//! with `bond_style ... store/local brk 10 time id1 id2 x y z x/ref y/ref z/ref` and `dump local`
//! (`header no`) to the file of their variable `brkfile`. Also the located errors of bad input.
//!
//! * `stored_broken_bonds`: against lammps-refs/refs/NAME/broken.txt and thermo.txt.
//! * `live_broken_bonds`: against LAMMPS run now (skipped without LAMMPS unless
//!   DMHS_REQUIRE_LAMMPS=1).

use dmhs::deck::{run_file, run_text, DeckOptions};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The decks whose bonds break (with a `brkfile` variable).
const BREAKING: [&str; 2] = ["bond_bpm_spring", "bond_bpm_rotational"];
/// Every BPM deck, for the thermo tables.
const DECKS: [&str; 3] = ["bond_bpm_spring", "bond_bpm_rotational", "bond_bpm_rotational_nobreak"];

fn deck(name: &str) -> PathBuf {
    root().join("lammps-refs/decks").join(format!("in.{name}"))
}

/// The rows of a dump local file: (step, id1, id2) and the other columns, sorted (the rows of
/// one step come in each engine's own bond order).
fn read_rows(text: &str) -> Vec<((i64, i64, i64), Vec<f64>)> {
    let mut rows: Vec<((i64, i64, i64), Vec<f64>)> = text
        .lines()
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            ((v[0] as i64, v[1] as i64, v[2] as i64), v[3..].to_vec())
        })
        .collect();
    rows.sort_by_key(|r| r.0);
    rows
}

/// dmhs on deck `name`: the broken-bond rows (with a `brkfile`, else "") and the screen text.
fn dmhs_run(name: &str, dir: &Path) -> (String, String) {
    let file = dir.join("broken.txt");
    let opts = DeckOptions {
        screen: false,
        capture_text: true,
        base_dir: Some(deck(name).parent().unwrap().to_path_buf()),
        vars: vec![("brkfile".into(), vec![file.to_string_lossy().into_owned()])],
        ..Default::default()
    };
    let run = run_file(&deck(name), &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    (std::fs::read_to_string(file).unwrap_or_default(), run.sim.out.captured.clone().expect("captured screen text"))
}

/// Same bonds at the same steps; midpoints (printed with %g, 6 digits) within 1e-5.
fn compare(name: &str, theirs: &str, ours: &str) {
    let (theirs, ours) = (read_rows(theirs), read_rows(ours));
    let steps: std::collections::BTreeSet<i64> = theirs.iter().map(|r| r.0 .0).collect();
    println!("{name}: LAMMPS: {} bonds broke at {} distinct steps ({:?}..{:?})", theirs.len(), steps.len(), steps.first(), steps.last());
    assert!(theirs.len() >= 20, "{name}: the reference breaks too few bonds to test anything");
    let keys = |r: &[((i64, i64, i64), Vec<f64>)]| r.iter().map(|x| x.0).collect::<Vec<_>>();
    assert_eq!(keys(&ours), keys(&theirs), "{name}: broken bonds (step, id1, id2) differ");
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(a.1.len(), 6);
        for (p, q) in a.1.iter().zip(&b.1) {
            assert!((p - q).abs() <= 1e-5 * q.abs().max(1.0), "{name}: bond {:?}: {:?} vs LAMMPS {:?}", a.0, a.1, b.1);
        }
    }
}

/// Column names and rows of the thermo table in `text` (a log, or thermo.txt: `# Step ...`).
fn thermo(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let t = dmhs::tools::validate::parse_thermo(&text.replace("# Step", "Step"));
    (t.columns, t.rows)
}

/// The same thermo columns and rows; every value within 1e-7 of its column's largest magnitude
/// (thermo prints 8 digits), the bond counts equal.
fn compare_thermo(name: &str, theirs: &str, ours: &str) {
    let ((their_names, theirs), (our_names, ours)) = (thermo(theirs), thermo(ours));
    assert_eq!(our_names, their_names, "{name}: thermo columns");
    assert_eq!(ours.len(), theirs.len(), "{name}: thermo rows");
    for (c, col) in their_names.iter().enumerate() {
        let scale = theirs.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
        let worst = ours.iter().zip(&theirs).map(|(a, b)| (a[c] - b[c]).abs()).fold(0.0, f64::max);
        println!("{name}: {col}: max |dmhs - LAMMPS| {worst:.3e} (scale {scale:.3e})");
        let tol = if col.starts_with("c_t") || col == "Step" { 0.0 } else { 1e-7 * scale };
        assert!(worst <= tol, "{name}: thermo column {col} differs by {worst:e} (scale {scale:e})");
    }
}

#[test]
fn stored_broken_bonds() {
    for name in DECKS {
        let tmp = tempfile::tempdir().unwrap();
        let refs = root().join("lammps-refs/refs").join(name);
        let (rows, screen) = dmhs_run(name, tmp.path());
        if BREAKING.contains(&name) {
            compare(name, &std::fs::read_to_string(refs.join("broken.txt")).unwrap(), &rows);
        }
        compare_thermo(name, &std::fs::read_to_string(refs.join("thermo.txt")).unwrap(), &screen);
    }
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn live_broken_bonds() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    for name in DECKS {
        let tmp = tempfile::tempdir().unwrap();
        let file = tmp.path().join("lammps_broken.txt");
        dmhs::tools::lammps::run_driver(&deck(name), &[("brkfile".into(), vec![file.to_string_lossy().into_owned()])], tmp.path()).unwrap();
        let (rows, screen) = dmhs_run(name, tmp.path());
        if BREAKING.contains(&name) {
            compare(name, &std::fs::read_to_string(file).unwrap(), &rows);
        }
        compare_thermo(name, &std::fs::read_to_string(tmp.path().join("log.lammps")).unwrap(), &screen);
    }
}

fn error_of(deck: &str) -> String {
    match run_text("in.test", deck, &DeckOptions { screen: false, ..Default::default() }) {
        Ok(_) => panic!("deck ran without error:\n{deck}"),
        Err(f) => f.rendered,
    }
}

/// Two bonded atoms, BPM's settings; `{}` is replaced by the bond_style line and what follows.
const TWO: &str = "units lj\natom_style bond\nnewton on off\ncomm_modify vel yes\nspecial_bonds lj 0 1 1 coul 1 1 1\nregion b block -4 4 -4 4 -4 4\ncreate_box 1 b bond/types 1 extra/bond/per/atom 4 extra/special/per/atom 4\ncreate_atoms 1 single 0 0 0\ncreate_atoms 1 single 1 0 0\nmass 1 1.0\ncreate_bonds single/bond 1 1 2\n";

#[test]
fn bad_input_is_located() {
    let at = |line: usize| format!("in.test:{line}:");
    let e = error_of(&format!("{TWO}bond_style bpm/spring break no\n"));
    assert!(e.contains("must turn off smoothing with break no") && e.contains(&at(12)), "{e}");
    let e = error_of(&format!("{TWO}bond_style bpm/spring store/local brk 10 bogus\n"));
    assert!(e.contains("at least one value") && e.contains(&at(12)), "{e}");
    // volume/factor yes takes a fifth coefficient, av
    let e = error_of(&format!("{TWO}bond_style bpm/spring volume/factor yes\nbond_coeff 1 1.0 0.1 0.0\n"));
    assert!(e.contains("av") && e.contains(&at(13)), "{e}");
    let e = error_of(&format!("{TWO}bond_style bpm/spring volume/factor maybe\n"));
    assert!(e.contains("maybe") && e.contains(&at(12)), "{e}");
    let e = error_of(&format!("{TWO}bond_style bpm/spring normalize maybe\n"));
    assert!(e.contains("maybe") && e.contains(&at(12)), "{e}");
    let e = error_of(&format!("{TWO}bond_style bpm/spring\nbond_coeff 1 1.0 0.1\n"));
    assert!(e.contains("gamma") && e.contains(&at(13)), "{e}");
    // LAMMPS' init checks, at the run
    let e = error_of(&format!("{}bond_style bpm/spring\nbond_coeff 1 1.0 0.1 0.0\nrun 0\n", TWO.replace("newton on off", "newton on")));
    assert!(e.contains("require Newton bond off"), "{e}");
    let e = error_of(&format!("{}bond_style bpm/spring\nbond_coeff 1 1.0 0.1 0.0\nrun 0\n", TWO.replace("lj 0 1 1 coul 1 1 1", "lj 0 0 1 coul 1 1 1")));
    assert!(e.contains("special LJ weights = 0,1,1"), "{e}");
    let e = error_of(&format!("{}bond_style bpm/spring\nbond_coeff 1 1.0 0.1 0.0\nrun 0\n", TWO.replace("comm_modify vel yes\n", "")));
    assert!(e.contains("ghost atoms store velocity"), "{e}");
    let e = error_of(&format!("{TWO}bond_style bpm/spring overlay/pair yes\nbond_coeff 1 1.0 0.1 0.0\nrun 0\n"));
    assert!(e.contains("overlay/pair yes") && e.contains("1.0 for all special_bonds weights"), "{e}");
    // dump local: the fix must have local data at compatible times
    let e = error_of(&format!("{TWO}bond_style bpm/spring store/local brk 10 id1 id2\ndump d all local 15 /dev/null f_brk[1]\n"));
    assert!(e.contains("compatible times") && e.contains(&at(13)), "{e}");
    let e = error_of(&format!("{TWO}bond_style bpm/spring store/local brk 10 id1 id2\ndump d all local 10 /dev/null f_brk\n"));
    assert!(e.contains("local vector") && e.contains(&at(13)), "{e}");
}

#[test]
fn a_stretched_bond_breaks_once_and_the_pair_turns_on() {
    // atom 2 leaves at speed 1: the bond (r0 = 1, ecrit 0.1) breaks when r > 1.1, its record has
    // the step and the lower ID first, and nbond drops to 0
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("b.txt");
    let deck = format!(
        "{TWO}pair_style zero 1.0\npair_coeff * *\nbond_style bpm/spring store/local brk 1 id1 id2 time\nbond_coeff 1 1.0 0.1 0.0\nset atom 2 vx 1.0\nfix 1 all nve\ntimestep 0.01\ncompute nb all nbond/atom\ncompute t all reduce sum c_nb\nthermo_style custom step c_t\ndump d all local 1 {} f_brk[3] f_brk[1] f_brk[2]\ndump_modify d header no\nrun 20\n",
        file.display()
    );
    let run = run_text("in.test", &deck, &DeckOptions { screen: false, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
    assert!(run.sim.state.topo.bonds.is_empty());
    // LAMMPS 22 Jul 2025 wrote `11 1 2 ` for this deck
    let text = std::fs::read_to_string(&file).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows.len(), 1, "{text}");
    assert_eq!(rows[0], "11 1 2 ");
}

#[test]
fn rotational_bad_input_is_located() {
    let sphere = TWO.replace("atom_style bond", "atom_style bpm/sphere").replace("mass 1 1.0\n", "");
    let coeff = "bond_coeff 1 1 1 1 1 1 1 1 1 1 1 1 1\n";
    // (deck, what the message says, the line it points at; 0: an error of the run, unlocated)
    let cases = [
        (format!("{sphere}bond_style bpm/rotational smooth maybe\n"), "maybe", 11),
        (format!("{sphere}bond_style bpm/rotational volume/factor no\n"), "volume/factor", 11),
        (format!("{sphere}bond_style bpm/rotational store/local brk 10\n"), "at least one value", 11),
        (format!("{sphere}bond_style bpm/rotational break no\n"), "must turn off smoothing with break no", 11),
        (format!("{sphere}bond_style bpm/rotational\nbond_coeff 1 1 1 1 1 1 1 1 1 1 1 1\n"), "gtwist", 12),
        // LAMMPS' init checks, at the run
        (format!("{TWO}bond_style bpm/rotational\n{coeff}run 0\n"), "requires atom style bpm/sphere", 0),
        (format!("{}bond_style bpm/rotational\n{coeff}run 0\n", sphere.replace("comm_modify vel yes\n", "")), "ghost atoms store velocity", 0),
        (format!("{}bond_style bpm/rotational\n{coeff}run 0\n", sphere.replace("newton on off", "newton on")), "require Newton bond off", 0),
    ];
    for (deck, says, line) in cases {
        let e = error_of(&deck);
        assert!(e.contains(says) && (line == 0 || e.contains(&format!("in.test:{line}:"))), "{e}");
    }
}

#[test]
fn rotational_bond_breaks_only_with_break_yes() {
    // atom 2 leaves at speed 1 (time step 0.005): B = Kr (r - r0) / Fcr reaches 1 at r - r0 =
    // 0.01. LAMMPS 22 Jul 2025 breaks the bond at step 3 with `break yes`, and keeps it (nbond 1
    // at step 20, no error) with `break no smooth no`
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("b.txt");
    let sphere = TWO.replace("atom_style bond", "atom_style bpm/sphere").replace("mass 1 1.0\n", "");
    for (settings, nbonds) in [("break no smooth no", 1), ("store/local brk 1 time id1 id2", 0)] {
        let dump = if nbonds == 0 { format!("dump d all local 1 {} f_brk[1] f_brk[2] f_brk[3]\ndump_modify d header no\n", file.display()) } else { String::new() };
        let deck = format!("{sphere}pair_style zero 1.0\npair_coeff * *\nbond_style bpm/rotational {settings}\nbond_coeff 1 1 1 1 1 0.01 1 1 1 0 0 0 0\nset atom 2 vx 1.0\nfix 1 all nve/bpm/sphere\n{dump}run 20\n");
        let run = run_text("in.test", &deck, &DeckOptions { screen: false, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
        assert_eq!(run.sim.state.topo.bonds.len(), nbonds, "{settings}");
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap().trim_end(), "3 1 2");
}
