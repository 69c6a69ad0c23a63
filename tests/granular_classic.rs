//! LAMMPS' classic `fix wall/gran` forms. Their numbers are compared with LAMMPS in
//! tests/lammps_parity.rs (lammps-refs deck gran_wall_classic); here: the creep warning that
//! `dmhs check` gives for `hooke/history`, and the forms' argument errors.

use std::path::PathBuf;
use std::process::Command;

fn check(deck: &str) -> (i32, String) {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("in.wall");
    std::fs::write(&path, deck).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).arg("check").arg(&path).current_dir(tmp.path()).output().unwrap();
    (o.status.code().unwrap_or(-1), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

fn deck(wall: &str) -> String {
    let base = std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks/in.gran_wall_classic")).unwrap();
    let line = base.lines().find(|l| l.starts_with("fix          floor")).unwrap().to_string();
    base.replace(&line, &format!("fix          floor all wall/gran {wall}"))
}

#[test]
fn hooke_history_wall_runs_with_a_creep_warning() {
    let (code, out) = check(&deck("hooke/history 20000.0 NULL 50.0 NULL 0.4 1 zplane 0.0 NULL"));
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("WARNING: fix wall/gran hooke/history") && out.contains("creep"), "{out}");
    // the granular form and the no-history classic form give no such warning
    let (code, out) = check(&deck("hooke 20000.0 NULL 50.0 NULL 0.4 1 zplane 0.0 NULL"));
    assert_eq!(code, 0, "{out}");
    assert!(!out.contains("creep"), "{out}");
}

#[test]
fn classic_wall_argument_errors_are_located() {
    for (wall, want) in [
        ("hooke/history 20000.0 NULL 50.0 NULL 0.4 2 zplane 0.0 NULL", "dampflag"),
        ("hooke/history -1 NULL 50.0 NULL 0.4 1 zplane 0.0 NULL", "Kn"),
        ("hooke/history 20000.0 NULL 50.0 NULL 0.4 1 zplane", "lo"),
        ("hook 20000.0 NULL 50.0 NULL 0.4 1 zplane 0.0 NULL", "hooke"),
    ] {
        let (code, out) = check(&deck(wall));
        assert_eq!(code, 2, "{wall}: {out}");
        assert!(out.contains(want) && out.contains("in.wall:"), "{wall}: expected `{want}`:\n{out}");
    }
}
