//! Commands that edit a whole system: replicate, read_data ... add, delete_bonds. Their
//! trajectories are compared with LAMMPS by the reference decks (lammps-refs/decks/in.replicate_*,
//! in.read_data_add*, in.delete_bonds*, tests/lammps_parity.rs); here: what they print and the
//! located errors for what LAMMPS refuses.

use std::path::PathBuf;
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn deck(name: &str) -> String {
    std::fs::read_to_string(root().join("lammps-refs/decks").join(name)).unwrap()
}

/// `dmhs` on `text` (written as in.t beside the reference data files, with `nsteps` 0): exit
/// code and output.
fn run(text: &str) -> (i32, String) {
    let tmp = tempfile::tempdir().unwrap();
    for e in std::fs::read_dir(root().join("lammps-refs/decks")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "data") {
            std::fs::copy(&p, tmp.path().join(p.file_name().unwrap())).unwrap();
        }
    }
    let path = tmp.path().join("in.t");
    std::fs::write(&path, text).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).args(["-in", "in.t", "-var", "nsteps", "0", "-log", "none"]).current_dir(tmp.path()).output().unwrap();
    (o.status.code().unwrap_or(-1), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

fn expect_error(text: &str, want: &str) {
    let (code, out) = run(text);
    assert_eq!(code, 2, "expected a deck error `{want}`:\n{out}");
    assert!(out.contains(want) && out.contains("in.t:"), "expected `{want}` with its location:\n{out}");
}

#[test]
fn replicate_prints_what_lammps_prints() {
    // LAMMPS 22 Jul 2025 on this deck: 640 atoms, 600 bonds, 560 angles, 520 dihedrals, box
    // (0 0 0) to (24 12 24)
    let (code, out) = run(&deck("in.replicate_chains"));
    assert_eq!(code, 0, "{out}");
    for line in ["Replication is creating a 2x1x2 = 4 times larger system...", "  orthogonal box = (0 0 0) to (24 12 24)", "  640 atoms", "  600 bonds", "  560 angles", "  520 dihedrals"] {
        assert!(out.lines().any(|l| l == line), "missing `{line}`:\n{out}");
    }
}

#[test]
fn replicate_errors_are_located() {
    let lj = deck("in.replicate_lj");
    let chains = deck("in.replicate_chains");
    expect_error(&lj.replace("replicate    1 3 2", "replicate    1 0 2"), "ny must be in 1..=");
    expect_error(&lj.replace("replicate    1 3 2", "replicate    1 3 2 bondlist"), "bondlist is not in LAMMPS 22 Jul 2025");
    expect_error(&lj.replace("replicate    1 3 2", "replicate    1 3 2 fast"), "unknown keyword `fast`");
    expect_error(&lj.replace("replicate    1 3 2", "replicate    1 3"), "nz");
    expect_error(&format!("dimension 2\n{}", lj.replace("fcc 0.8442", "sq 0.8442").replace("0 3 0 3", "0 3 -0.5 0.5").replace("0.05 0.05 0.05", "0.05 0.05 0.0").replace("replicate    1 3 2", "replicate    1 3 2")), "cannot be replicated in z");
    // fix move keeps the original positions per atom: LAMMPS refuses ("Cannot replicate with
    // fixes that store atom quantities")
    expect_error(&lj.replace("replicate    1 3 2", "fix m all move linear 0 0 0\nrun 0\nreplicate    1 3 2"), "cannot replicate with fixes that store per-atom values");
    expect_error(&chains.replace("units        lj", "replicate 2 2 2\nunits        lj"), "replicate used before the simulation box is defined");
}
