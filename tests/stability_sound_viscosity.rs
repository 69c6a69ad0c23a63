//! The sound-viscosity time-step limit of SPH with Morris viscosity and `fix sph`: dt <= 2 nu/c^2
//! (src/stability.rs). fix sph moves the density half a step behind the positions, so the pressure
//! of a sound wave lags it and feeds it; only the viscosity takes that energy out. A periodic water
//! box at rest with velocity noise (tests/decks/in.sound_viscosity, limit 9e-6 s, a quarter of the
//! acoustic CFL limit): at 2x the limit the noise grows, at 1x it dies out, in dmhs as in LAMMPS.

use std::path::{Path, PathBuf};
use std::process::Command;

fn deck() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks/in.sound_viscosity")
}

/// The value printed after `key` (the deck's `print "KEY ${ke}"` lines).
fn printed(text: &str, key: &str) -> f64 {
    let line = text.lines().find(|l| l.starts_with(key)).unwrap_or_else(|| panic!("no {key} in:\n{text}"));
    line[key.len()..].trim().parse().unwrap()
}

fn dmhs(args: &[&str], dir: &Path) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).args(args).current_dir(dir).output().unwrap();
    let text = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(o.status.success(), "{text}");
    text
}

/// (kinetic energy at the start, after 0.1 s) at dt = f x the limit.
fn run_dmhs(f: &str, dir: &Path) -> (f64, f64, String) {
    let text = dmhs(&["run", deck().to_str().unwrap(), "-var", "f", f, "-log", "none"], dir);
    (printed(&text, "START_KE"), printed(&text, "FINAL_KE"), text)
}

#[test]
fn check_reports_and_warns() {
    let tmp = tempfile::tempdir().unwrap();
    let text = dmhs(&["check", deck().to_str().unwrap(), "-var", "f", "2"], tmp.path());
    assert!(text.contains("sound-viscosity 2 nu/c^2 (type 1: nu = mu/rho0 = 0.288/1000, c = 8)") && text.contains("dt <= 9.0000e-6"), "{text}");
    assert!(text.contains("WARNING: the time step 1.8000e-5 is 2.00x the sound-viscosity 2 nu/c^2 limit"), "{text}");
    let text = dmhs(&["check", deck().to_str().unwrap(), "-var", "f", "1"], tmp.path());
    assert!(!text.contains("WARNING"), "at the limit: {text}");
}

#[test]
fn noise_grows_above_the_limit_and_dies_out_below() {
    let tmp = tempfile::tempdir().unwrap();
    let (start, grown, text) = run_dmhs("2", tmp.path());
    // measured: 3.52e-7 J -> 4.16e-5 J in 0.1 s (the same in LAMMPS)
    assert!(grown > 50.0 * start, "2x the limit: kinetic energy {start} -> {grown}\n{text}");
    let (start, damped, text) = run_dmhs("1", tmp.path());
    // measured: 3.52e-7 J -> 9.8e-10 J
    assert!(damped < 0.01 * start, "at the limit: kinetic energy {start} -> {damped}\n{text}");
}

/// The same numbers from LAMMPS (its fix sph has the lag: this is the model, not an engine bug).
#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn lammps_gives_the_same_growth_and_decay() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let (_, grown, _) = run_dmhs("2", tmp.path());
    let (_, damped, _) = run_dmhs("1", tmp.path());
    let lmp = dmhs::tools::lammps::find_lmp(&python).unwrap();
    for (f, ours) in [("2", grown), ("1", damped)] {
        let o = Command::new(&lmp)
            .args(["-in", deck().to_str().unwrap(), "-var", "f", f, "-log", "none", "-nocite"])
            .current_dir(tmp.path())
            .env("LD_LIBRARY_PATH", dmhs::tools::lammps::library_path(&python))
            .env("OMP_NUM_THREADS", "1")
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&o.stdout).to_string();
        assert!(o.status.success(), "LAMMPS failed:\n{text}{}", String::from_utf8_lossy(&o.stderr));
        let theirs = printed(&text, "FINAL_KE");
        println!("f = {f}: kinetic energy after 0.1 s: dmhs {ours:.6e}, LAMMPS {theirs:.6e}");
        assert!((ours - theirs).abs() <= 1e-6 * theirs, "f = {f}: dmhs {ours} vs LAMMPS {theirs}");
    }
}

#[test]
fn bonded_types_are_not_fluid() {
    // the cubes scene: water (type 1, limit 2 (0.1/1000)/8^2 = 3.125e-6 s, its time step) and
    // cube particles (type 2, rho0 1500: 2.08e-6 s) whose atoms are all bonded, so they carry no
    // SPH sound wave (README of the scene: a cube at 8x its own limit stays quiet)
    let tmp = tempfile::tempdir().unwrap();
    let scene = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/cubes");
    for name in ["in.cubes", "cubes_C_fast.data"] {
        std::fs::copy(scene.join(name), tmp.path().join(name)).unwrap();
    }
    let text = dmhs(&["check", "in.cubes", "-var", "case", "C", "-var", "fast", "1"], tmp.path());
    assert!(text.contains("sound-viscosity 2 nu/c^2 (type 1: nu = mu/rho0 = 0.1/1000, c = 8)") && text.contains("dt <= 3.1250e-6"), "{text}");
    assert!(!text.contains("type 2: nu"), "{text}");
    assert!(!text.contains("WARNING"), "{text}");
}
