//! `fix_modify energy` and `virial` against LAMMPS: every column of the thermo tables (pe,
//! etotal, pressure and its tensor, compute pe with and without `fix`, the fixes' f_ID) of the
//! decks fix_modify_walls (fix wall/lj93 and wall/region: energy and virial) and
//! fix_modify_forces (fix addforce: energy and virial; spring, indent, gravity: energy) and
//! fix_modify_spring_self (spring/self: energy) at every
//! printed step, against lammps-refs/refs/NAME/thermo.txt (and LAMMPS run now, when present).
//! The minimization with wall energies is min_cluster_walls in tests/minimize.rs. And the
//! located errors for what a fix does not tally.

use dmhs::deck::run_text;

mod thermo_tables;
use thermo_tables::table;

const DECKS: [&str; 3] = ["fix_modify_walls", "fix_modify_forces", "fix_modify_spring_self"];

thermo_tables::thermo_table_tests!(DECKS);

const BASE: &str = "units lj\natom_style atomic\nboundary p p f\nregion box block 0 10 0 10 0 10 units box\ncreate_box 1 box\n\
create_atoms 1 single 5 5 5 units box\ncreate_atoms 1 single 5 5 6.5 units box\nmass 1 1.0\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\n\
fix 1 all nve\nfix w all wall/lj93 zlo EDGE 1.0 1.0 8.0\nfix s all setforce 0 NULL NULL\n";

fn thermo(extra: &str) -> Vec<f64> {
    let deck = format!("{BASE}{extra}thermo_style custom step pe press c_p f_w\nthermo_modify format float %.17g\nrun 0\n");
    let run = run_text("ok.deck", &deck, &dmhs::deck::DeckOptions { screen: false, capture_text: true, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
    table(run.sim.out.captured.as_deref().unwrap()).1.remove(0)
}

/// energy yes adds f_ID to pe (and to compute pe unless its keyword list lacks `fix`), virial
/// yes changes the pressure, and `no` takes them out again.
#[test]
fn energy_and_virial_switch_on_and_off() {
    let plain = thermo("compute p all pe\n");
    let on = thermo("compute p all pe\nfix_modify w energy yes virial yes\n");
    let pair_only = thermo("compute p all pe pair\nfix_modify w energy yes\n");
    let off = thermo("compute p all pe\nfix_modify w energy yes virial yes dynamic/dof no\nfix_modify w energy no virial no\n");
    assert!(plain[4] != 0.0);
    assert_eq!(on[1], plain[1] + plain[4]);
    assert_eq!(on[3], on[1]);
    assert!(on[2] != plain[2]);
    assert_eq!(pair_only[3], plain[1]);
    assert_eq!(pair_only[1], on[1]);
    assert_eq!(off, plain);
}

#[test]
fn bad_fix_modify_is_a_located_error() {
    for (cmd, want) in [
        ("fix_modify s energy yes", "fix s (setforce) does not support fix_modify energy"),
        ("fix_modify 1 virial yes", "fix 1 (nve) does not support fix_modify virial"),
        ("fix g all gravity 1.0 vector 0 0 -1\nfix_modify g virial yes", "does not support fix_modify virial"),
        ("fix_modify w energy maybe", "maybe"),
        ("fix_modify w respa 1", "rRESPA"),
        ("fix_modify w bodyforces early", "bodyforces"),
        ("fix_modify w wobble yes", "unknown keyword `wobble`"),
        ("fix_modify w", "a keyword"),
        ("fix_modify nothere energy yes", "fix `nothere` does not exist"),
    ] {
        let deck = format!("{BASE}{cmd}\nrun 0\n");
        let f = run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {cmd}"));
        let line = 14 + cmd.matches('\n').count();
        assert!(f.rendered.contains(&format!("bad.deck:{line}:")) && f.rendered.contains(want), "{cmd}: expected `{want}`:\n{}", f.rendered);
    }
    // `no` is accepted for any fix, as LAMMPS checks only when the tally is switched on
    run_text("ok.deck", &format!("{BASE}fix_modify s energy no virial no\nrun 0\n"), &Default::default()).unwrap_or_else(|f| panic!("{}", f.rendered));
}

/// `pair_modify pair M [k] ...` (lammps-refs/decks/in.pair_modify_hybrid compares it with LAMMPS)
/// and its located errors: not a hybrid style, an unknown sub-style, a missing instance number,
/// `pair` after another keyword.
#[test]
fn pair_modify_pair_errors_are_located() {
    let base = "units lj\natom_style atomic\nregion box block 0 5 0 5 0 5 units box\ncreate_box 2 box\nmass * 1.0\n";
    let err = |text: &str| match run_text("bad.deck", &format!("{base}{text}"), &dmhs::deck::DeckOptions { screen: false, ..Default::default() }) {
        Ok(_) => panic!("accepted: {text}"),
        Err(f) => f.rendered,
    };
    let e = err("pair_style lj/cut 2.5\npair_modify pair lj/cut shift yes\n");
    assert!(e.contains("pair_modify pair can only be used with pair_style hybrid") && e.contains("bad.deck:7:18"), "{e}");
    let e = err("pair_style hybrid lj/cut 2.5 soft 1.0\npair_modify pair lj/cut/coul/long shift yes\n");
    assert!(e.contains("names `lj/cut/coul/long`, which is not a sub-style") && e.contains("sub-styles: lj/cut, soft"), "{e}");
    let e = err("pair_style hybrid lj/cut 2.5 lj/cut 2.0\npair_modify pair lj/cut shift yes\n");
    assert!(e.contains("sub-style index"), "{e}");
    let e = err("pair_style hybrid lj/cut 2.5 soft 1.0\npair_modify shift yes pair soft\n");
    assert!(e.contains("pair_modify pair must be the first keyword"), "{e}");
}
