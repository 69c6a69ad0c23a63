//! compute contact/atom: counts on a hand-made arrangement (touching, just apart, across a
//! periodic face, group2, a pair excluded by neigh_modify), and its located errors. Its counts
//! in a settling bed are compared with LAMMPS' in tests/granular_region.rs (deck
//! gran_contact_atom).

use dmhs::deck::{run_text, DeckOptions};

mod common;

/// Five spheres of diameter 1 along x in a periodic 6-long box: 1 at x=0.5, 2 at 1.5 (touching
/// 1 exactly), 3 at 2.4 (overlapping 2), 4 at 3.6 (0.2 apart from 3), 5 at 5.5 (touching 1
/// across the periodic face). LAMMPS 22 Jul 2025 on the same lines (read through atom-style
/// variables `v_a[I]` with `atom_modify map array`) gives all: 2 2 1 0 1; against group2 {1, 3}:
/// 0 2 . . 1; the compute over group {1, 3}: atom 2 0, atom 3 1; after `neigh_modify exclude
/// type 1 2` all: 1 2 1 0 0.
#[test]
fn contacts_of_a_row_of_spheres() {
    let deck = "units lj\natom_style sphere\nboundary p p p\ncomm_modify vel yes\nregion box block 0 6 -3 3 -3 3\ncreate_box 2 box\n\
        create_atoms 1 single 0.5 0 0\ncreate_atoms 1 single 1.5 0 0\ncreate_atoms 1 single 2.4 0 0\n\
        create_atoms 1 single 3.6 0 0\ncreate_atoms 2 single 5.5 0 0\nset type * diameter 1.0\n\
        pair_style granular\npair_coeff * * hooke 1000 0.0 tangential linear_nohistory 0 0.0\n\
        group odd id 1 3\ncompute c all contact/atom\ncompute c2 all contact/atom odd\ncompute ce odd contact/atom\nrun 0\n";
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let counts = |deck: &str| -> Vec<[f64; 3]> {
        let run = run_text("contacts", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
        let sim = &run.sim;
        let per = |id: &str| sim.computes[sim.find_compute(id).unwrap()].peratom(&sim.world()).unwrap().data;
        let (c, c2, ce) = (per("c"), per("c2"), per("ce"));
        let tag = &sim.state.atoms.tag;
        (1..=5).map(|id| {
            let k = tag.iter().position(|&t| t == id).unwrap();
            [c[k], c2[k], ce[k]]
        }).collect()
    };
    let got = counts(deck);
    assert_eq!(got.iter().map(|r| r[0]).collect::<Vec<_>>(), [2.0, 2.0, 1.0, 0.0, 1.0]);
    assert_eq!([got[0][1], got[1][1], got[4][1]], [0.0, 2.0, 1.0]);
    assert_eq!([got[1][2], got[2][2]], [0.0, 1.0]);
    let excluded = counts(&deck.replace("run 0\n", "neigh_modify exclude type 1 2\nrun 0\n"));
    assert_eq!(excluded.iter().map(|r| r[0]).collect::<Vec<_>>(), [1.0, 2.0, 1.0, 0.0, 0.0]);
}

#[test]
fn contact_atom_errors_are_located() {
    let sphere = "units lj\natom_style sphere\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 single 1 1 1\n";
    let atomic = "units lj\natom_style atomic\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 single 1 1 1\nmass 1 1.0\n";
    common::assert_located_errors(atomic, &[("compute c all contact/atom\n", "requires atom style sphere")]);
    common::assert_located_errors(
        sphere,
        &[
            ("compute c all contact/atom nogroup\n", "group2 ID nogroup does not exist"),
            ("compute c all contact/atom all extra\n", "extra"),
            ("compute c all contact/atom\ncompute s all reduce sum c_c\nthermo_style custom step c_s\n", "requires a pair style"),
        ],
    );
}
