//! pair granular's `mdr` normal model (with `damping mdr` and the per-atom bookkeeping of
//! LAMMPS' fix GRANULAR/MDR): parity with the stored LAMMPS 22 Jul 2025 reference of
//! lammps-refs deck gran_mdr_squeeze (step-0 forces within 1e-12 of the force scale, positions
//! after 400 steps of yielding, adhesive, penalised contacts within 1e-9 of the box), and
//! LAMMPS' refusals as located errors.

use dmhs::tools::cli_crosscheck::{dmhs_capture, within, DEFAULT_FORCE_TOL, DEFAULT_POS_TOL, DEFAULT_VEL_TOL};
use dmhs::tools::crosscheck::{compare_runs, report, AtomTable};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn squeezed_spheres_match_the_stored_lammps_reference() {
    matches_stored_reference("gran_mdr_squeeze");
}

/// Region walls with mdr: a moving spherical indenter presses spheres into a box floor
/// (plastic, bulk response, adhesion), a sphere slides down a corner.
#[test]
fn region_walls_match_the_stored_lammps_reference() {
    matches_stored_reference("gran_mdr_wall");
}

fn matches_stored_reference(name: &str) {
    let deck = root().join(format!("lammps-refs/decks/in.{name}"));
    let refdir = root().join(format!("lammps-refs/refs/{name}"));
    let (ours0, ours, box_len) = dmhs_capture(&deck, &[]).unwrap_or_else(|e| panic!("dmhs failed: {e}"));
    let theirs0 = AtomTable::read(&refdir.join("forces0.txt")).unwrap();
    let theirs = AtomTable::read(&refdir.join("final.txt")).unwrap();
    let diffs = compare_runs(&ours0, &theirs0, &ours, &theirs, box_len).unwrap();
    println!("{}", report(&diffs));
    let bad = within(&diffs, [DEFAULT_FORCE_TOL, DEFAULT_POS_TOL, DEFAULT_VEL_TOL]);
    assert!(bad.is_empty(), "{}", bad.join("; "));
}

/// The reference deck, edited: each edit fails with a located error containing the text.
#[test]
fn lammps_refusals_are_located_errors() {
    let base = std::fs::read_to_string(root().join("lammps-refs/decks/in.gran_mdr_squeeze")).unwrap();
    let base = base.replace("run          ${nsteps}", "run 0");
    let coeff = "pair_coeff   * * mdr 5e6 0.4 1.9e5 2.0 0.96 0.2 damping mdr 1 tangential linear_history 1428.57 1.0 0.7 rolling sds 1.0 0.0 0.6";
    assert!(base.contains(coeff));
    let with_coeff = |c: &str| base.replace(coeff, c);
    let cases: Vec<(String, &str)> = vec![
        (base.replace("newton       off", "newton       on"), "requires `newton off`"),
        (base.replace("comm_modify  vel yes\n", ""), "comm_modify vel yes"),
        (with_coeff("pair_coeff * * mdr 5e6 0.4 1.9e5 2.0 0.96 0.2 damping velocity tangential linear_history 1 1 1"), "only damping mdr may be used with the mdr normal model"),
        (with_coeff("pair_coeff * * mdr 5e6 0.4 1.9e5 2.0 0.96 0.2 tangential linear_history 1 1 1"), "needs `damping mdr 1|2`"),
        (with_coeff("pair_coeff * * hooke 1 1 damping mdr 1 tangential linear_history 1 1 1"), "damping mdr can only be used with the mdr normal model"),
        (with_coeff("pair_coeff * * mdr 5e6 0.4 1.9e5 2.0 0.96 0.2 damping mdr 3 tangential linear_history 1 1 1"), "must be 1 or 2"),
        (with_coeff("pair_coeff * * mdr 0 0.4 1.9e5 2.0 0.96 0.2 damping mdr 1 tangential linear_history 1 1 1"), "E (Young's modulus) must be > 0"),
        (with_coeff("pair_coeff * * mdr 5e6 0.6 1.9e5 2.0 0.96 0.2 damping mdr 1 tangential linear_history 1 1 1"), "nu (Poisson's ratio) must be in [0, 0.5]"),
        (with_coeff("pair_coeff * * mdr 5e6 0.4 1.9e5 2.0 1.5 0.2 damping mdr 1 tangential linear_history 1 1 1"), "psi_b"),
        (with_coeff("pair_coeff * * mdr 5e6 0.4 1.9e5 -2.0 0.96 0.2 damping mdr 1 tangential linear_history 1 1 1"), "gamma (effective surface energy) must be >= 0"),
        (base.replace(coeff, &format!("{coeff}\n{coeff}")), "takes one pair_coeff"),
        (base.replace("fix          1 all nve/sphere", "fix          1 all nve/sphere\nfix          w all wall/gran granular mdr 5e6 0.4 1.9e5 2.0 0.96 0.2 damping mdr 1 tangential linear_history 1 1 1 zplane -0.01 NULL"), "LAMMPS' mdr supports only region walls"),
    ];
    for (deck, want) in cases {
        let f = dmhs::deck::run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted, expected `{want}`"));
        assert!(f.rendered.contains("bad.deck:") && f.rendered.contains(want), "expected `{want}`:\n{}", f.rendered);
    }
}

/// The region-wall deck, edited: LAMMPS' checks that the walls' mdr agrees with the pair's.
#[test]
fn region_walls_disagreeing_with_the_pair_are_refused() {
    let base = std::fs::read_to_string(root().join("lammps-refs/decks/in.gran_mdr_wall")).unwrap().replace("run          ${nsteps}", "run 0");
    let wall = "fix          press all wall/gran/region granular mdr 5e6 0.4 1.9e5 0.0 0.96 0.2 damping mdr 1";
    let pair = "pair_coeff   * * mdr 5e6 0.4 1.9e5 2.0 0.96 0.2 damping mdr 1 tangential linear_history 1428.57 1.0 0.7 rolling sds 1.0 0.0 0.6";
    assert!(base.contains(wall) && base.contains(pair));
    let cases: Vec<(String, &str)> = vec![
        (base.replace(wall, &wall.replace("5e6 0.4", "6e6 0.4")), "Young's modulus in pair style, 5000000, does not agree with value 6000000"),
        (base.replace(wall, &wall.replace("0.4 1.9e5", "0.3 1.9e5")), "Poisson's ratio in pair style"),
        (base.replace(wall, &wall.replace("1.9e5", "2e5")), "Yield stress in pair style"),
        (base.replace(wall, &wall.replace("0.96 0.2", "0.9 0.2")), "Bulk response trigger in pair style"),
        (base.replace(wall, &wall.replace("0.96 0.2", "0.96 0.3")), "Damping in pair style"),
        (base.replace(pair, "pair_coeff   * * hertz/material 5e6 0.2 0.4 tangential linear_history 1428.57 1.0 0.7"), "needs pair_style granular with the mdr model"),
    ];
    for (deck, want) in cases {
        let f = dmhs::deck::run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted, expected `{want}`"));
        assert!(f.rendered.contains("bad.deck:") && f.rendered.contains(want), "expected `{want}`:\n{}", f.rendered);
    }
}
