//! Sets the cfg `live_lammps` where the live LAMMPS test (tests/data_file_lammps.rs) can run or
//! must run (DMHS_REQUIRE_LAMMPS=1); without it the test is ignored with the reason, and
//! cargo's summary counts it. The same rule as the dmhs crate's build.rs.

use std::path::Path;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(live_lammps)");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=DMHS_LAMMPS_PYTHON");
    println!("cargo::rerun-if-env-changed=DMHS_REQUIRE_LAMMPS");
    let required = std::env::var("DMHS_REQUIRE_LAMMPS").is_ok_and(|x| x == "1");
    let python = std::env::var_os("DMHS_LAMMPS_PYTHON").is_some_and(|p| Path::new(&p).is_file());
    if required || python || Path::new("../.venv-lammps/bin/python").exists() {
        println!("cargo::rustc-cfg=live_lammps");
    }
}
