//! compute coord/atom: the thermo table of lammps-refs/decks/in.thermo_coord_atom against
//! LAMMPS' (stored, and LAMMPS run now), counts on a hand-made row of atoms, and located errors.

use dmhs::deck::{run_text, DeckOptions};

mod common;
mod thermo_tables;

thermo_tables::thermo_table_tests!(["thermo_coord_atom"]);

/// Four atoms on a periodic x row at 0.5, 1.5, 2.6 and 4.5 of a 5-long box (types 1 1 2 2):
/// within 1.05 atom 1 sees 2 and 4 (across the face), atom 2 sees 1, atom 3 none, atom 4 sees 1;
/// by type (1, 2) and from group {1, 3} towards group {2, 4}: atom 1 (1, 1), atom 3 (0, 0).
#[test]
fn counts_of_a_row() {
    let deck = "units lj\natom_style atomic\nregion box block 0 5 -2 2 -2 2\ncreate_box 2 box\n\
        create_atoms 1 single 0.5 0 0\ncreate_atoms 1 single 1.5 0 0\ncreate_atoms 2 single 2.6 0 0\ncreate_atoms 2 single 4.5 0 0\n\
        mass * 1.0\npair_style lj/cut 1.2\npair_coeff * * 1.0 1.0\ngroup odd id 1 3\ngroup even id 2 4\n\
        compute c all coord/atom cutoff 1.05\ncompute t odd coord/atom cutoff 1.05 group even 1 2\nrun 0\n";
    let opts = DeckOptions { screen: false, ..Default::default() };
    let run = run_text("row", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let sim = &run.sim;
    let per = |id: &str| sim.computes[sim.find_compute(id).unwrap()].peratom(&sim.world()).unwrap();
    let (c, t) = (per("c"), per("t"));
    let a = &sim.state.atoms;
    for i in 0..a.nlocal {
        let want = [2.0, 1.0, 0.0, 1.0][a.tag[i] as usize - 1];
        assert_eq!(c.get(i, 0), want, "atom {}", a.tag[i]);
        let want_t = [[1.0, 1.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]][a.tag[i] as usize - 1];
        assert_eq!([t.get(i, 0), t.get(i, 1)], want_t, "atom {}", a.tag[i]);
    }
}

#[test]
fn bad_coords_are_located() {
    let base = "units lj\nregion box block 0 5 0 5 0 5\ncreate_box 2 box\nmass * 1.0\npair_style lj/cut 2.5\npair_coeff * * 1.0 1.0\n";
    common::assert_located_errors(
        base,
        &[
            ("compute c all coord/atom 1.5\n", "Invalid cstyle 1.5"),
            ("compute c all coord/atom orientorder 1.5\n", "orientorder"),
            ("compute c all coord/atom cutoff -1\n", "Rc"),
            ("compute c all coord/atom cutoff 1.5 group nobody\n", "Could not find compute coord/atom group2 ID nobody"),
            ("compute c all coord/atom cutoff 1.5 3\n", "type"),
        ],
    );
    let deck = format!("{base}create_atoms 1 single 1 1 1\ncompute c all coord/atom cutoff 3.0\nthermo_style custom step c_c\ncompute s all reduce sum c_c\nthermo_style custom step c_s\nrun 0\n");
    let f = run_text("bad.deck", &deck, &Default::default()).err().expect("refused");
    assert!(f.rendered.contains("cutoff is longer than pairwise cutoff"), "{}", f.rendered);
}
