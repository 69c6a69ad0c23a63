//! Granular commands beside the contact models. LAMMPS' classic `fix wall/gran` forms (their
//! numbers are compared with LAMMPS in tests/lammps_parity.rs, lammps-refs deck
//! gran_wall_classic): the creep warning `dmhs check` gives for `hooke/history`, and argument
//! errors. compute temp/sphere against the values LAMMPS prints for the same deck.

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

/// Heat conduction input (lammps-refs deck gran_heat_area edited): every error located at the
/// command (file:line) with what was expected.
#[test]
fn heat_input_errors_are_located() {
    let base = std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks/in.gran_heat_area")).unwrap();
    let without = |prefixes: &[&str]| base.lines().filter(|l| !prefixes.iter().any(|p| l.starts_with(p))).collect::<Vec<_>>().join("\n");
    let cases: Vec<(String, &str)> = vec![
        // a heat model without per-atom temperatures
        (without(&["fix          props", "set          region", "set          type 1 temperature", "fix          heat", "compute      t", "thermo_style"]), "pair granular: a heat model needs per-atom temperature and heatflow"),
        (without(&["fix          props"]), "set temperature needs per-atom temperatures"),
        (base.replace("heat/flow constant 1.0", "heat/flow constant"), "missing cp (specific heat)"),
        (base.replace("heat/flow constant 1.0", "heat/flow constant -1.0"), "cp (specific heat) must be >= 0"),
        (base.replace("heat/flow constant 1.0", "heat/flow type 1.0 2.0"), "unexpected"),
        (base.replace("heat/flow constant 1.0", "heat/flow linear 1.0"), "constant"),
        (base.replace("heat area 100.0", "heat area -100.0"), "h (heat transfer coefficient) must be >= 0"),
        (base.replace("heat area 100.0", "heat conduction 100.0"), "heat model `conduction` is not supported"),
        (base.replace(" temperature v_twall", ""), "with a heat model needs the wall temperature"),
        (base.replace("heat area 50.0 ", ""), "`temperature` needs a heat model"),
        (base.replace("property/atom temperature heatflow", "property/atom temperature heatflow rmass"), "fix property/atom rmass is not supported"),
        (base.replace("property/atom temperature heatflow", "property/atom temperature heatflow temperature"), "already exists"),
    ];
    for (deck, want) in cases {
        let (code, out) = check(&deck);
        assert_eq!(code, 2, "expected `{want}`:\n{out}");
        assert!(out.contains(want) && out.contains("in.wall:"), "expected `{want}`:\n{out}");
    }
    // without a heat model nothing needs temperatures; d_/i_ values are accepted
    let (code, out) = check(&base.replace("property/atom temperature heatflow", "property/atom temperature heatflow d_flag i_count ghost yes"));
    assert_eq!(code, 0, "{out}");
}

/// LAMMPS lets fix property/atom (only it) come before the box, as examples/pour's
/// in.pour.2d.molecule does; other fixes there stay a located error.
#[test]
fn property_atom_may_precede_the_box() {
    let base = std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks/in.gran_heat_area")).unwrap();
    let props = base.lines().find(|l| l.starts_with("fix          props")).unwrap().to_string();
    let early = base.replace(&format!("{props}\n"), "").replace("create_box   1 box", &format!("{props}\ncreate_box   1 box"));
    let (code, out) = check(&early);
    assert_eq!(code, 0, "{out}");
    let (code, out) = check(&early.replace(&props, "fix          early all nve/sphere"));
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("fix used before the simulation box is defined") && out.contains("in.wall:16:"), "{out}");
}

/// Step-0 thermo of tests/decks/granular/in.temp_sphere: c_ts c_tr c_te c_ts[1] c_ts[4] c_tr[3]
/// as LAMMPS 22 Jul 2025 prints them (`thermo_modify format float %.15g`), in 2D and 3D.
#[test]
fn temp_sphere_matches_lammps() {
    let deck = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks/granular/in.temp_sphere");
    let lammps = [
        ("2", "0.5", "0  0.995961596540736 0.0298879899104784 0.981933968420444 1.69237744939981 0.438741599786922 0.0269884087997604"),
        ("3", "5.5", "0  0.742353896594996 0.00996266330349282 0.734059439649801 1.53250982760794 0.153891814731438 0.0269884087997604"),
    ];
    for (dim, zhi, want) in lammps {
        let tmp = tempfile::tempdir().unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).arg("-in").arg(&deck).args(["-log", "none", "-var", "dim", dim, "-var", "zhi", zhi]).current_dir(tmp.path()).output().unwrap();
        let out = String::from_utf8_lossy(&o.stdout).to_string();
        let row = out.lines().skip_while(|l| !l.trim_start().starts_with("Step")).nth(1).unwrap_or_default().to_string();
        let words = |s: &str| s.split_whitespace().map(str::to_string).collect::<Vec<_>>();
        assert_eq!(words(&row), words(want), "dimension {dim}:\n{out}");
    }
}
