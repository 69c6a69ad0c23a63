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

fn reliability_deck(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks/reliability").join(name).to_str().unwrap().to_string()
}

/// Run the LJ deck at time step `dt` in a fresh folder: exit code, screen, log, dump.
fn lj_at(dt: &str, extra: &[&str]) -> (Option<i32>, String, String, String) {
    let tmp = tempfile::tempdir().unwrap();
    let mut args = vec!["run", "DECK", "-var", "dt", dt, "-log", "run.log"];
    let deck = reliability_deck("in.unstable_lj");
    args[1] = &deck;
    args.extend_from_slice(extra);
    let (code, text) = dmhs(&args, tmp.path());
    let log = std::fs::read_to_string(tmp.path().join("run.log")).unwrap_or_default();
    let dump = std::fs::read_to_string(tmp.path().join("dump.lj")).unwrap_or_default();
    (code, text, log, dump)
}

/// LJ at 20x and 100x LAMMPS' time step (issue 15, item 6): the first step moves atoms farther
/// than the skin; the run stops with exit 1, naming step, particle, the distance and its bound and
/// the stable time-step estimate, on screen and at the end of the log, and the dump is whole.
#[test]
fn lj_far_above_its_time_step_stops_at_the_first_step() {
    for (dt, ratio) in [("0.1", "3.40x"), ("0.5", "17.01x")] {
        let (code, text, log, dump) = lj_at(dt, &[]);
        assert_eq!(code, Some(1), "dt {dt}: {text}");
        assert!(text.contains(&format!("WARNING: the time step {} is {ratio} the T/20 of the well", if dt == "0.1" { "1.0000e-1" } else { "5.0000e-1" })), "{text}");
        let err = text.lines().find(|l| l.contains("run stopped at step 1: particle ")).unwrap_or_else(|| panic!("dt {dt}: {text}"));
        assert!(err.contains(" in one step (speed ") && err.contains("more than the neighbour skin 0.3"), "{err}");
        assert!(err.contains(&format!("is {ratio} the T/20 of the well, T = 2 pi sqrt(m/(2k)) limit 2.9386e-2")), "{err}");
        assert!(log.trim_end().ends_with(err.trim_start_matches("error: ").trim_end()) || log.contains(err.trim()), "the log ends with the error:\n{log}");
        assert!(dump_is_whole(&dump) >= 1, "{dump}");
    }
}

/// At LAMMPS' time step (0.005, 0.17x the well limit) the same deck runs to the end, quietly.
#[test]
fn lj_at_its_time_step_runs() {
    let (code, text, _, dump) = lj_at("0.005", &[]);
    assert_eq!(code, Some(0), "{text}");
    assert!(!text.contains("WARNING"), "{text}");
    assert_eq!(dump_is_whole(&dump), 51);
}

/// `dmhs/stability off` turns the new checks off too; the run then goes on to the end, and the
/// neighbour build copes with the atoms flung far outside the box (it once panicked there).
#[test]
fn the_guard_can_be_turned_off() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = std::fs::read_to_string(reliability_deck("in.unstable_lj")).unwrap().replace("fix          1 all nve", "fix          1 all nve\ndmhs/stability off");
    std::fs::write(tmp.path().join("in.off"), deck).unwrap();
    let (code, text) = dmhs(&["run", "in.off", "-var", "dt", "0.5", "-var", "nsteps", "8", "-log", "none"], tmp.path());
    assert_eq!(code, Some(0), "{text}");
    assert!(text.contains("Loop time of") && !text.contains("run stopped"), "{text}");
}

fn granular_at(dt: &str) -> (Option<i32>, String, String) {
    let tmp = tempfile::tempdir().unwrap();
    let data = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks/gran_bed.data");
    let (code, text) = dmhs(&["run", &reliability_deck("in.unstable_granular"), "-var", "dt", dt, "-var", "data", data.to_str().unwrap(), "-log", "none"], tmp.path());
    let dump = std::fs::read_to_string(tmp.path().join("dump.gran")).unwrap_or_default();
    (code, text, dump)
}

/// A periodic granular gas at 100x its time step (issue 15, item 7) stops within a few steps,
/// naming the DEM contact limit; at its own time step it runs to the end.
#[test]
fn granular_at_a_hundred_times_its_time_step_stops() {
    let (code, text, dump) = granular_at("0.01");
    assert_eq!(code, Some(1), "{text}");
    let err = text.lines().find(|l| l.contains("run stopped at step ")).unwrap_or_else(|| panic!("{text}"));
    let step: i64 = err.split("run stopped at step ").nth(1).unwrap().split(':').next().unwrap().parse().unwrap();
    assert!((2..=10).contains(&step), "{err}");
    assert!(err.contains("in one step") && err.contains("more than the neighbour skin 0.2"), "{err}");
    assert!(err.contains("is 32.58x the t_c/10, t_c = pi sqrt(m_eff/k_n) limit 3.0689e-4"), "{err}");
    assert_eq!(dump_is_whole(&dump) as i64, step);
    let (code, text, dump) = granular_at("0.0001");
    assert_eq!(code, Some(0), "{text}");
    assert_eq!(dump_is_whole(&dump), 101);
}
