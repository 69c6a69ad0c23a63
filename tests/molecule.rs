//! Molecule templates and `create_atoms ... mol`, beside their LAMMPS parity deck
//! (lammps-refs/decks/in.molecule_create with trimer.mol, compared in tests/lammps_parity.rs:
//! positions of the randomly turned copies, bonds and angles through the forces): the atom and
//! molecule IDs and the topology of each copy as LAMMPS 22 Jul 2025 writes them (write_data of
//! the same deck), the summary LAMMPS prints, and located errors for bad templates.

use dmhs::deck::{run_file, run_text, DeckOptions};
use std::path::PathBuf;

fn decks() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks")
}

fn opts(dir: PathBuf) -> DeckOptions {
    DeckOptions { screen: false, capture_text: true, base_dir: Some(dir), vars: vec![("nsteps".into(), vec!["0".into()])], ..Default::default() }
}

#[test]
fn copies_get_consecutive_ids_molecules_and_the_template_topology() {
    let run = run_file(&decks().join("in.molecule_create"), &opts(decks())).unwrap_or_else(|f| panic!("{}", f.rendered));
    let st = &run.sim.state;
    let a = &st.atoms;
    assert_eq!(a.nlocal, 192, "64 lattice sites, 3 atoms each");
    // LAMMPS: copy c (0-based) holds atoms 3c+1..3c+3, molecule c+1, types 1 2 1
    for i in 0..a.nlocal {
        let c = (a.tag[i] - 1) / 3;
        assert_eq!(a.molecule[i], c + 1, "atom {}", a.tag[i]);
        assert_eq!(a.typ[i], if (a.tag[i] - 1) % 3 == 1 { 2 } else { 1 }, "atom {}", a.tag[i]);
    }
    let bonds: Vec<[i64; 2]> = st.topo.bonds.iter().map(|b| b.atoms).collect();
    let want: Vec<[i64; 2]> = (0..64).flat_map(|c| [[3 * c + 1, 3 * c + 2], [3 * c + 2, 3 * c + 3]]).collect();
    assert_eq!(bonds, want);
    let angles: Vec<[i64; 3]> = st.topo.angles.iter().map(|b| b.atoms).collect();
    assert_eq!(angles, (0..64).map(|c| [3 * c + 1, 3 * c + 2, 3 * c + 3]).collect::<Vec<_>>());
    // the copies keep the template's shape: bond lengths 1 (closest image)
    let map = a.tag_map();
    let prd = st.domain.as_ref().unwrap().prd();
    for b in &bonds {
        let (i, j) = (map.get(b[0]).unwrap(), map.get(b[1]).unwrap());
        let d: f64 = (0..3)
            .map(|k| {
                let mut x = a.x[i][k] - a.x[j][k];
                x -= prd[k] * (x / prd[k]).round();
                x * x
            })
            .sum::<f64>()
            .sqrt();
        assert!((d - 1.0).abs() < 1e-12, "bond {b:?}: {d}");
    }
    let out = run.sim.out.captured.clone().unwrap_or_default();
    for line in ["Read molecule template tri:", "  1 molecules", "  3 atoms with max type 2", "  2 bonds with max type 1", "  1 angles with max type 1", "Created 192 atoms"] {
        assert!(out.contains(line), "missing `{line}` in:\n{out}");
    }
}

/// The first error of `deck` (with `mol` written as t.mol beside it), rendered.
fn error_of(deck: &str, mol: &str) -> String {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("t.mol"), mol).unwrap();
    let mut o = opts(tmp.path().to_path_buf());
    o.capture_text = false;
    match run_text("in.test", deck, &o) {
        Ok(_) => panic!("deck ran without error:\n{deck}"),
        Err(f) => f.rendered,
    }
}

const BOX: &str = "units lj\natom_style bond\nregion b block 0 4 0 4 0 4\ncreate_box 2 b bond/types 1 extra/bond/per/atom 2 extra/special/per/atom 4\n";
const DIMER: &str = "dimer\n2 atoms\n1 bonds\n\nCoords\n\n1 0 0 0\n2 1 0 0\n\nTypes\n\n1 1\n2 2\n\nBonds\n\n1 1 1 2\n";

#[test]
fn bad_templates_and_uses_are_located() {
    let ok = format!("{BOX}molecule m t.mol\ncreate_atoms 0 single 2 2 2 mol m 1234\n");
    // the good case runs
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("t.mol"), DIMER).unwrap();
    run_text("in.test", &ok, &opts(tmp.path().to_path_buf())).unwrap_or_else(|f| panic!("{}", f.rendered));
    let cases: &[(&str, &str, &str)] = &[
        // (deck, molecule file, expected message and location)
        (&ok, &DIMER.replace("2 2\n", "2 3\n"), "invalid atom type 3 in molecule file|t.mol:13:"),
        (&ok, &DIMER.replace("1 1 1 2\n", "1 2 1 2\n"), "invalid bond type 2|t.mol:17:"),
        (&ok, &DIMER.replace("2 1 0 0\n", "1 1 0 0\n"), "atom 1 appears twice|t.mol:8:"),
        (&ok, &DIMER.replace("Types", "Typos"), "unknown section `Typos`|t.mol:10:"),
        (&ok.replace("mol m 1234", "mol q 1234"), DIMER, "molecule template `q` for create_atoms does not exist|in.test:6:"),
        (&ok.replace("mol m 1234", "mol m 0"), DIMER, "molecule random seed|in.test:6:"),
        (&ok.replace("create_atoms 0", "create_atoms 1"), DIMER, "exceeds the 2 atom types|in.test:6:"),
        (&ok.replace("molecule m t.mol", "molecule m t.mol\nmolecule m t.mol"), DIMER, "reuse of molecule template ID `m`|in.test:6:"),
        (&ok.replace("molecule m t.mol", "molecule m-1 t.mol"), DIMER, "alphanumeric|in.test:5:"),
        (&ok.replace("molecule m t.mol", "molecule m nofile.mol"), DIMER, "cannot open molecule file|in.test:5:"),
        (&ok.replace("molecule m t.mol", "molecule m t.mol scale -1"), DIMER, "scale factor|in.test:5:"),
        (&ok.replace("atom_style bond", "atom_style atomic").replace(" bond/types 1 extra/bond/per/atom 2 extra/special/per/atom 4", ""), DIMER, "has no bonds|in.test:5:"),
        (&ok.replace("single 2 2 2", "random 3 99 NULL"), DIMER, "overlap and maxtry|ok"),
        (&ok.replace("single 2 2 2", "random 3 99 NULL").replace("mol m 1234", "mol m 1234 overlap -1"), DIMER, "overlap distance|in.test:6:"),
        (&ok.replace("single 2 2 2", "random 3 99 nowhere"), DIMER, "nowhere|in.test:6:"),
    ];
    for (deck, mol, want) in cases {
        if want.ends_with("|ok") {
            // accepted: create_atoms random with mol
            let tmp = tempfile::tempdir().unwrap();
            std::fs::write(tmp.path().join("t.mol"), mol).unwrap();
            run_text("in.test", deck, &opts(tmp.path().to_path_buf())).unwrap_or_else(|f| panic!("{}", f.rendered));
            continue;
        }
        let e = error_of(deck, mol);
        for part in want.split('|') {
            assert!(e.contains(part), "expected `{part}`:\n{e}");
        }
    }
}

/// create_atoms random with mol (lammps-refs/decks/in.molecule_random, positions compared in
/// tests/lammps_parity.rs): 12 trimers without an overlap test, then 28 of 30 with `overlap
/// 1.2` (LAMMPS' count), each of those with every atom at least 1.2 from the atoms made before.
#[test]
fn random_molecules_keep_their_overlap_distance() {
    let run = run_file(&decks().join("in.molecule_random"), &opts(decks())).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.as_deref().unwrap();
    assert!(text.contains("only inserted 28 particles out of 30"), "{text}");
    let st = &run.sim.state;
    let a = &st.atoms;
    assert_eq!(a.nlocal, 120);
    let prd = st.domain.as_ref().unwrap().prd();
    let mut by_tag: Vec<usize> = (0..a.nlocal).collect();
    by_tag.sort_by_key(|&i| a.tag[i]);
    for (k, &i) in by_tag.iter().enumerate() {
        assert_eq!(a.molecule[i], k as i64 / 3 + 1);
        if k < 36 {
            continue;
        }
        for &j in &by_tag[..k - k % 3] {
            let d2: f64 = (0..3).map(|c| {
                let mut d = a.x[i][c] - a.x[j][c];
                d -= prd[c] * (d / prd[c]).round();
                d * d
            }).sum();
            assert!(d2 >= 1.2 * 1.2 * (1.0 - 1e-12), "atoms {} and {}: {}", a.tag[i], a.tag[j], d2.sqrt());
        }
    }
}

#[test]
fn fix_deposit_bad_input_is_located() {
    let base = format!("{BOX}molecule m t.mol\nregion slab block 0 4 0 4 3 4\nfix 1 all deposit 5 0 10 1234 region slab mol m\n");
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("t.mol"), DIMER).unwrap();
    run_text("in.test", &base, &opts(tmp.path().to_path_buf())).unwrap_or_else(|f| panic!("{}", f.rendered));
    let cases: &[(&str, &str, &str)] = &[
        ("region slab mol m", "mol m", "region ID (fix deposit needs `region ID`)"),
        ("region slab mol", "region nope mol", "region ID `nope` for fix deposit does not exist"),
        ("mol m", "mol q", "molecule template ID `q` for fix deposit does not exist"),
        ("deposit 5 0", "deposit 5 1", "offset 1 plus the template's largest type 2"),
        ("mol m", "mol m shake s1", "`shake` is not supported"),
        ("region slab mol m", "region slab rigid r1", "cannot use fix deposit rigid and not molecule"),
        ("mol m", "mol m molfrac 0.5", "must add up to 1"),
        ("mol m", "molfrac 1.0", "needs `mol` before it"),
        ("10 1234", "10 0", "random seed"),
        ("block 0 4 0 4 3 4", "block 0 4 0 4 3 9", "deposition region extends outside simulation box"),
        ("mol m", "mol m orient 0 0 0", "orient"),
    ];
    for (from, to, want) in cases {
        let deck = base.replace(from, to);
        assert_ne!(deck, base, "{from}");
        let e = error_of(&deck, DIMER);
        assert!(e.contains(want) && e.contains("in.test:"), "{to}: expected `{want}`:\n{e}");
    }
}

#[test]
fn rotate_turns_every_copy_as_lammps_does() {
    // LAMMPS 22 Jul 2025 wrote these positions (write_data) for the same deck
    let mol = "dimer\n2 atoms\n\nCoords\n\n1 0 0 0\n2 1 0 0\n\nTypes\n\n1 1\n2 1\n";
    let deck = "units lj\natom_style atomic\nregion box block -5 5 -5 5 -5 5\ncreate_box 1 box\nmolecule m t.mol\ncreate_atoms 0 single 0 0 0 mol m 4567 rotate 90 0 0 1\ncreate_atoms 0 single 1 1 1 mol m 4567 rotate 30 1 1 0\n";
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("t.mol"), mol).unwrap();
    let run = run_text("in.test", deck, &opts(tmp.path().to_path_buf())).unwrap_or_else(|f| panic!("{}", f.rendered));
    let a = &run.sim.state.atoms;
    let want = [
        [-1.1102230246251565e-16, -0.5, 0.0],
        [1.1102230246251565e-16, 0.5, 0.0],
        [0.5334936490538903, 0.9665063509461097, 1.176776695296637],
        [1.4665063509461098, 1.0334936490538904, 0.8232233047033631],
    ];
    for (i, w) in want.iter().enumerate() {
        assert_eq!(a.x[a.tag_map().get(i as i64 + 1).unwrap()], *w, "atom {}", i + 1);
    }
}

#[test]
fn thermo_modify_temp_and_press_errors_are_located() {
    let base = "units lj\nregion b block 0 4 0 4 0 4\ncreate_box 1 b\ncompute t all temp\ncompute ke all ke\nthermo_modify temp t\n";
    let opts = DeckOptions { screen: false, ..Default::default() };
    run_text("in.test", base, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    for (from, to, want) in [
        ("temp t", "temp nope", "could not find thermo_modify temperature compute `nope`"),
        ("temp t", "temp ke", "`ke` does not compute temperature"),
        ("temp t", "press ke", "`ke` does not compute pressure"),
        ("temp t", "press thermo_temp", "does not compute pressure"),
    ] {
        let e = match run_text("in.test", &base.replace(from, to), &opts) {
            Ok(_) => panic!("{to}: no error"),
            Err(f) => f.rendered,
        };
        assert!(e.contains(want) && e.contains("in.test:6:"), "{to}: expected `{want}`:\n{e}");
    }
}
