//! fix rigid/small against LAMMPS beyond the trajectories (those are in tests/lammps_parity.rs):
//! the thermo tables of rigid_small_clumps (3d), rigid_small_2d (enforce2d) and
//! rigid_small_gran (clumps of spheres on a granular floor: the body mass in the granular
//! damping, compute temp/sphere), whose pressure and its tensor carry the bodies' constraint
//! virial (LAMMPS' set_xv/set_v tally, on by default), every printed step, against
//! lammps-refs/refs/NAME/thermo.txt (and LAMMPS run now, when present). And the located
//! refusals of what the fix does not support.

use dmhs::deck::{run_text, DeckOptions};

mod thermo_tables;
use thermo_tables::table;

const DECKS: [&str; 3] = ["rigid_small_clumps", "rigid_small_2d", "rigid_small_gran"];

thermo_tables::thermo_table_tests!(DECKS);

/// Two rigid dimers in a periodic box, meeting head on.
const BASE: &str = "units lj\natom_style bond\nboundary p p p\nregion box block 0 10 0 10 0 10 units box\ncreate_box 1 box\n\
create_atoms 1 single 2 5 5 units box\ncreate_atoms 1 single 3 5 5 units box\ncreate_atoms 1 single 4.1 5.2 5 units box\ncreate_atoms 1 single 5.1 5.2 5 units box\n\
set atom 1*2 mol 1\nset atom 3*4 mol 2\nmass 1 1.0\nvelocity all set 0.5 0 0\nvelocity all set -0.5 0 0 units box\n\
pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nneigh_modify exclude molecule/intra all\n\
fix 1 all rigid/small molecule\n";

fn thermo(extra: &str) -> Vec<Vec<f64>> {
    let deck = format!("{BASE}{extra}thermo_style custom step press pxx pxy\nthermo_modify format float %.17g\nthermo 5\nrun 10\n");
    let run = run_text("ok.deck", &deck, &DeckOptions { screen: false, capture_text: true, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
    table(run.sim.out.captured.as_deref().unwrap()).1
}

/// `fix_modify virial no` takes the constraint virial out of the pressure, `yes` puts it back.
#[test]
fn fix_modify_virial_switches_the_constraint_virial() {
    let on = thermo("");
    let off = thermo("fix_modify 1 virial no\n");
    let again = thermo("fix_modify 1 virial no\nfix_modify 1 virial yes\n");
    assert_eq!(on, again);
    assert!(on.iter().zip(&off).all(|(a, b)| a[1] != b[1]), "the virial changes the pressure:\n{on:?}\n{off:?}");
}

#[test]
fn unsupported_uses_are_located_errors() {
    for (cmd, want) in [("fix_modify 1 energy yes", "does not support fix_modify energy"), ("fix 2 all rigid molecule", "fix rigid is not supported"), ("fix 2 all rigid/small molecule langevin 1 1 1 5", "langevin")] {
        let deck = format!("{BASE}{cmd}\nrun 0\n");
        let f = run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {cmd}"));
        let line = BASE.lines().count() + 1;
        assert!(f.rendered.contains(&format!("bad.deck:{line}:")) && f.rendered.contains(want), "{cmd}: expected `{want}`:\n{}", f.rendered);
    }
}
