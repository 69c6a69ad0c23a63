//! Runs that go unstable stop with a message naming the step, the particle, the quantity and the
//! violated bound; everything written before stays intact. The time-step limits are reported by
//! `dmhs check` and warned about at the start of a run.

use std::path::PathBuf;
use std::process::Command;

fn deck() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks/in.dambreak_dt")
}

fn dmhs(args: &[&str], dir: &std::path::Path) -> (Option<i32>, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).args(args).current_dir(dir).output().unwrap();
    (o.status.code(), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

/// Every snapshot of a dump file is complete: its atom count matches its lines.
fn dump_is_whole(text: &str) -> usize {
    let lines: Vec<&str> = text.lines().collect();
    let mut k = 0;
    let mut snapshots = 0;
    while k < lines.len() {
        assert_eq!(lines[k], "ITEM: TIMESTEP");
        let n: usize = lines[k + 3].parse().unwrap();
        assert!(lines[k + 8].starts_with("ITEM: ATOMS"));
        assert!(k + 9 + n <= lines.len(), "truncated snapshot");
        k += 9 + n;
        snapshots += 1;
    }
    snapshots
}

#[test]
fn four_times_the_acoustic_limit_stops_cleanly() {
    let tmp = tempfile::tempdir().unwrap();
    // cfl 2 = 4x the acoustic limit 0.25 hs/c
    let (code, text) = dmhs(&["run", deck().to_str().unwrap(), "-var", "cfl", "2", "-log", "run.log"], tmp.path());
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("WARNING: the time step 1.5000e-3 is 4.00x the acoustic CFL 0.25 hs/c limit"), "{text}");
    assert!(text.contains("run stopped at step"), "{text}");
    assert!(text.contains("atom ") || text.contains("particle "), "{text}");
    assert!(text.contains("the time step 1.5000e-3 is 4.00x the acoustic CFL 0.25 hs/c limit 3.7500e-4"), "{text}");
    let log = std::fs::read_to_string(tmp.path().join("run.log")).unwrap();
    assert!(log.contains("Loop time of"), "the log is closed properly:\n{log}");
    let dump = std::fs::read_to_string(tmp.path().join("dump.dambreak")).unwrap();
    assert!(dump_is_whole(&dump) >= 1);
}

#[test]
fn within_the_limit_it_runs() {
    let tmp = tempfile::tempdir().unwrap();
    // cfl is the time step in units of 0.25 h/c = 2x the acoustic limit 0.25 hs/c
    let (code, text) = dmhs(&["run", deck().to_str().unwrap(), "-var", "cfl", "0.4", "-var", "nsteps", "400", "-log", "none"], tmp.path());
    assert_eq!(code, Some(0), "{text}");
    assert!(!text.contains("WARNING"), "{text}");
    let dump = std::fs::read_to_string(tmp.path().join("dump.dambreak")).unwrap();
    assert_eq!(dump_is_whole(&dump), 9);
}

#[test]
fn check_reports_the_limits() {
    let tmp = tempfile::tempdir().unwrap();
    let (code, text) = dmhs(&["check", deck().to_str().unwrap(), "-var", "cfl", "4"], tmp.path());
    assert_eq!(code, Some(0), "{text}");
    assert!(text.contains("stable time step estimates:"), "{text}");
    assert!(text.contains("acoustic CFL 0.25 hs/c (hs = h/2 = 0.03, c = 20)") && text.contains("dt <= 3.7500e-4"), "{text}");
    assert!(text.contains("force 0.25 sqrt(hs/|a|max)"), "{text}");
    assert!(text.contains("WARNING: the time step 3.0000e-3 is 8.00x"), "{text}");
}

#[test]
fn density_guard_names_particle_and_bound() {
    // a heavy compression: the density guard must fire before anything else
    let tmp = tempfile::tempdir().unwrap();
    let deck = tmp.path().join("in.squeeze");
    std::fs::write(
        &deck,
        "dimension 2\nunits lj\natom_style sph\nboundary p p p\nregion box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\n\
         lattice sq 1.0\ncreate_atoms 1 box\nmass 1 1.0\nset group all sph/rho 1.0\nset atom 50 sph/rho 2.5\n\
         pair_style sph/taitwater\npair_coeff * * 1.0 10.0 0.1 1.3\nfix 1 all sph\nfix 2 all enforce2d\ntimestep 0.001\nrun 10\n",
    )
    .unwrap();
    let (code, text) = dmhs(&["run", "in.squeeze", "-log", "none"], tmp.path());
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("run stopped at step 1: particle 50 (type 1) has density 2.49"), "{text}");
    assert!(text.contains("outside the sane range (0.0000e0, 2.0000e0] (0 to 2 x rho0 = 1)"), "{text}");
}
