//! State a restart file must carry besides atoms and contacts (issue 17): a run continued with
//! read_restart and the same fix definitions ends in exactly the state (every bit) of the run
//! that went on after write_restart, for
//! * BPM bonds: each bond's reference state (r0, and the reference directions of
//!   bpm/rotational), the style's stored flag, each atom's bond-list order after bonds broke,
//!   and LAMMPS' atom order (the order of the bond sums);
//! * thermostats: fix nvt's chain (eta, eta_dot), the energy of temp/berendsen and
//!   temp/rescale; fix nph's barostat.
//!
//! Each case also drops the state from the file and checks that the continuation then differs,
//! so the test sees what it claims to.

use dmhs::deck::{run_file, DeckOptions};
use dmhs::tools::crosscheck::capture_state;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Run a deck file; the final state as text and the thermo log.
fn run(deck: &Path) -> (String, String) {
    let opts = DeckOptions { base_dir: Some(deck.parent().unwrap().to_path_buf()), screen: false, ..Default::default() };
    let mut r = run_file(deck, &opts).map_err(|f| f.rendered).unwrap();
    (capture_state(&r.sim).to_text(), r.sim.thermo_values().map(|v| format!("{v:?}")).unwrap_or_default())
}

/// The reference deck's lines before its `run`, with `${nsteps}`-style index variables kept.
fn setup_part(name: &str) -> String {
    let text = std::fs::read_to_string(root().join("lammps-refs/decks").join(name)).unwrap();
    text.lines().take_while(|l| !l.starts_with("run")).filter(|l| !l.starts_with("dump")).collect::<Vec<_>>().join("\n") + "\n"
}

/// The lines of the reference deck a continuation repeats: those starting with one of `keys`.
fn redefinitions(name: &str, keys: &[&str]) -> String {
    let text = std::fs::read_to_string(root().join("lammps-refs/decks").join(name)).unwrap();
    text.lines().filter(|l| keys.iter().any(|k| l.starts_with(k))).collect::<Vec<_>>().join("\n") + "\n"
}

/// Uninterrupted (run n; write_restart; run m) against restarted (read_restart; the
/// redefinitions; run m): equal to the bit. Then `drop` takes the state under test out of the
/// file, and the continuation must differ.
fn check(deck: &str, data: Option<&str>, n: u32, m: u32, keys: &[&str], drop: impl Fn(&mut Value)) {
    let dir = tempfile::tempdir().unwrap();
    if let Some(d) = data {
        std::fs::copy(root().join("lammps-refs/decks").join(d), dir.path().join(d)).unwrap();
    }
    let a = dir.path().join("in.a");
    std::fs::write(&a, format!("{}run {n}\nwrite_restart state.restart\nrun {m}\n", setup_part(deck))).unwrap();
    let whole = run(&a);
    let c = dir.path().join("in.c");
    std::fs::write(&c, format!("read_restart state.restart\n{}run {m}\n", redefinitions(deck, keys))).unwrap();
    let restarted = run(&c);
    assert!(whole.0 == restarted.0, "{deck}: the restarted run's atoms differ from the uninterrupted run's");
    assert_eq!(whole.1, restarted.1, "{deck}: the thermo values differ");

    let path = dir.path().join("state.restart");
    let mut file: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    drop(&mut file);
    std::fs::write(&path, serde_json::to_string(&file).unwrap()).unwrap();
    assert!(run(&c) != whole, "{deck}: without the state under test the continuation should differ");
}

const FIXES: &[&str] = &["variable", "fix", "compute", "neighbor", "neigh_modify", "comm_modify", "thermo"];

#[test]
fn bpm_rotational_bonds_continue_bit_for_bit() {
    // bonds break between steps 0 and 1200 (slots reordered); r0 and reference directions kept
    check("in.bond_bpm_rotational", Some("bpm_ball_plate.data"), 600, 600, FIXES, |f| {
        let t = f["topology"].as_object_mut().unwrap();
        t.remove("bond_history");
        t.remove("bond_history_stored");
    });
}

#[test]
fn bpm_bond_order_after_breaking_is_kept() {
    // the reference states kept, but each atom's bond list in record order: the sums change
    check("in.bond_bpm_rotational", Some("bpm_ball_plate.data"), 600, 300, FIXES, |f| {
        f["topology"].as_object_mut().unwrap().remove("bond_slots");
        f["atoms"].as_object_mut().unwrap().remove("lammps_order");
    });
}

#[test]
fn bpm_spring_bonds_continue_bit_for_bit() {
    check("in.bond_bpm_spring", None, 500, 500, FIXES, |f| {
        f["topology"].as_object_mut().unwrap().remove("bond_history");
    });
}

fn drop_fixes(f: &mut Value) {
    f["fixes"] = Value::Array(vec![]);
}

#[test]
fn nose_hoover_chains_continue_bit_for_bit() {
    check("in.thermo_nvt", None, 300, 300, FIXES, drop_fixes);
}

#[test]
fn berendsen_energy_continues() {
    check("in.thermo_berendsen", None, 300, 300, FIXES, drop_fixes);
}

#[test]
fn rescale_energy_continues() {
    check("in.thermo_rescale", None, 300, 300, FIXES, drop_fixes);
}

/// fix nph's barostat (box velocities, their chain, the reference box and temperature) and the
/// box itself; the deck scales about a fixed point of its own (the default, the box centre when
/// the fix is defined, moves with the restarted box, in LAMMPS too).
#[test]
fn barostat_continues_bit_for_bit() {
    check("in.nph_deviatoric", None, 150, 150, FIXES, drop_fixes);
}

/// `pair_style granular` named again after read_restart keeps the style's contact histories
/// (LAMMPS keeps the style when the same one is named, changing only its settings): a settling
/// bed with mindlin, rolling and twisting springs continues bit for bit; without the histories
/// in the file it does not. (Before, the new style started without contacts.)
#[test]
fn granular_contacts_survive_a_repeated_pair_style() {
    let dir = tempfile::tempdir().unwrap();
    let setup = setup_part("in.pair_local_gran");
    let a = dir.path().join("in.a");
    std::fs::write(&a, format!("{setup}run 60\nwrite_restart state.restart\nrun 60\n")).unwrap();
    let whole = run(&a);
    let again: Vec<&str> = setup.lines().filter(|l| ["variable", "fix", "comm_modify", "pair_style", "pair_coeff", "timestep", "thermo"].iter().any(|k| l.starts_with(k))).collect();
    let c = dir.path().join("in.c");
    std::fs::write(&c, format!("read_restart state.restart\n{}\nrun 60\n", again.join("\n"))).unwrap();
    assert!(again.iter().any(|l| l.starts_with("pair_style")));
    assert_eq!(run(&c), whole, "the restarted run differs from the uninterrupted one");
    let path = dir.path().join("state.restart");
    let mut file: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    for h in file["contact_histories"].as_array_mut().unwrap() {
        h["contacts"] = Value::Array(vec![]);
    }
    std::fs::write(&path, serde_json::to_string(&file).unwrap()).unwrap();
    assert!(run(&c) != whole, "without the contacts the continuation should differ");
}

/// `atom_modify first GROUP` travels in the restart file (LAMMPS keeps the group's name in its
/// header): the restarted system keeps the group's atoms first and does not sort.
#[test]
fn atom_modify_first_is_restored() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("first.restart");
    let deck = format!(
        "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
         group mid id 20:40\natom_modify first mid\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nrun 0\nwrite_restart {f}\nclear\nread_restart {f}\n",
        f = file.display()
    );
    let run = dmhs::deck::run_text("in.first", &deck, &DeckOptions { screen: false, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
    let order = &run.sim.state.lammps_order;
    assert_eq!(order.first.as_deref(), Some("mid"));
    assert_eq!(order.sortfreq, 0);
    // the group's 21 atoms lead LAMMPS' order
    assert!(order.ids()[..21].iter().all(|t| (20..=40).contains(t)), "{:?}", &order.ids()[..21]);
}
