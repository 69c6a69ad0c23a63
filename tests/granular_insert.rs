//! fix pour and what insertion decks use with it (compute_modify, erotate/sphere). The parity
//! of the inserted particles and of the run with LAMMPS is in tests/lammps_parity.rs (decks
//! lammps-refs/decks/in.gran_pour*); these tests check the messages, the degrees of freedom of
//! the thermo temperature and the refused forms.

use std::path::PathBuf;
use std::process::Command;

fn deck() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks/pour/in.pour_base")
}

/// Runs the base deck with `extra` (one or two commands, split at a newline) before the run
/// (and `vars`); returns (exit code, output).
fn run(extra: &str, vars: &[(&str, &str)]) -> (i32, String) {
    let (extra, extra2) = extra.split_once('\n').unwrap_or((extra, "print none"));
    let tmp = tempfile::tempdir().unwrap();
    let mut c = Command::new(env!("CARGO_BIN_EXE_dmhs"));
    c.arg("-in").arg(deck()).args(["-log", "none", "-threads", "1", "-var", "extra", extra, "-var", "extra2", extra2]).current_dir(tmp.path());
    for (k, v) in vars {
        c.args(["-var", k, v]);
    }
    let o = c.output().unwrap();
    (o.status.code().unwrap_or(-1), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

/// The thermo rows (step, atoms, ke) of the run.
fn rows(out: &str) -> Vec<(i64, i64, String)> {
    out.lines()
        .skip_while(|l| !l.trim_start().starts_with("Step"))
        .skip(1)
        .take_while(|l| !l.starts_with("Loop"))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w[0].parse().unwrap(), w[1].parse().unwrap(), w[2].to_string())
        })
        .collect()
}

#[test]
fn pour_reports_lammps_schedule_and_inserts_a_batch() {
    let (code, out) = run("print none", &[]);
    assert_eq!(code, 0, "{out}");
    // LAMMPS 22 Jul 2025 prints the same line for this deck
    assert!(out.contains("Particle insertion: 402 every 3162 steps, 3000 by step 22135"), "{out}");
    let r = rows(&out);
    assert_eq!((r[0].0, r[0].1), (0, 0));
    assert_eq!((r[1].0, r[1].1), (100, 402));
}

#[test]
fn thermo_temperature_counts_degrees_of_freedom_once_per_run_unless_dynamic() {
    // LAMMPS counts the dof when the run starts (0 atoms: dof <= 0, so ke prints -0)...
    let (code, out) = run("print none", &[]);
    assert_eq!(code, 0, "{out}");
    assert!(rows(&out).iter().all(|r| r.2 == "-0"), "{out}");
    // ...and at every evaluation with dynamic/dof yes (`dynamic` is the old spelling)
    for kw in ["dynamic/dof", "dynamic"] {
        let (code, out) = run(&format!("compute_modify thermo_temp {kw} yes"), &[]);
        assert_eq!(code, 0, "{out}");
        let ke: f64 = rows(&out)[1].2.parse().unwrap();
        assert!(ke > 0.0, "{out}");
    }
    // extra/dof 0 leaves the centre-of-mass dof in: temp = 2 ke/(3N) instead of 2 ke/(3N - 3)
    let temp = |extra: &str| -> f64 {
        let (_, out) = run(&format!("compute_modify thermo_temp dynamic/dof yes {extra}\nthermo_style custom step atoms temp"), &[]);
        rows(&out)[3].2.parse().unwrap()
    };
    let (t3, t0) = (temp(""), temp("extra/dof 0"));
    let want = t3 * (3.0 * 402.0 - 3.0) / (3.0 * 402.0);
    assert!((t0 - want).abs() < 1e-6 * want, "{t3} {t0}");
}

#[test]
fn erotate_sphere_is_zero_without_spin() {
    let (code, out) = run("compute rot all erotate/sphere\nthermo_style custom step atoms c_rot", &[("nsteps", "100")]);
    assert_eq!(code, 0, "{out}");
    assert_eq!(rows(&out)[1], (100, 402, "0".to_string()), "{out}");
}

#[test]
fn refused_pour_forms_are_located_errors() {
    let cases: &[(&str, &str)] = &[
        ("fix p2 all pour 10 1 5 region slab mol m", "molecule template `m` for fix pour does not exist"),
        ("fix p2 all pour 10 1 5 region slab shake s", "`shake` is not supported"),
        ("region c cylinder x 0 0 1 11 14 units box\nfix p2 all pour 10 1 5 region c", "z-axis cylinder"),
        ("region big block -11 9 -9 9 10 15 units box\nfix p2 all pour 10 1 5 region big", "outside the simulation box"),
        ("fix p2 all pour 10 1 0 region slab", "seed"),
        ("fix p2 all pour 10 2 5 region slab", "atom type"),
        ("fix p2 all pour 10 1 5", "region"),
        ("fix p2 all pour 10 1 5 region slab diam poly 2 1.0 0.5 0.5 0.4", "sum to"),
        ("unfix 2\nfix p2 all pour 10 1 5 region slab", "fix gravity"),
    ];
    for (extra, want) in cases {
        let (code, out) = run(extra, &[]);
        assert_eq!(code, 2, "{extra}: {out}");
        assert!(out.contains(want) && out.contains("in.pour_base:"), "{extra}: expected `{want}` located:\n{out}");
    }
}

#[test]
fn gravity_turned_after_pour_stops_the_run() {
    let (code, out) = run("fix 2 all gravity 1.0 vector 1 0 0", &[]);
    assert_eq!(code, 2, "{out}");
    assert!(out.contains("gravity"), "{out}");
}

/// The run summary's "Neighs" of granular decks is LAMMPS' size-list count: the pairs within
/// their current radii sum + skin, a pair with a periodic image counted once per side under
/// `newton off` (gran_pour) and once under `newton on` (adapt_diameter, whose spheres grow).
/// The counts are LAMMPS 22 Jul 2025's (`lmp -in in.NAME` in lammps-refs/decks).
#[test]
fn granular_neighbour_counts_are_lammps_size_list_counts() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks");
    for (name, lammps) in [("gran_pour", vec![140]), ("adapt_diameter", vec![1311, 1878])] {
        let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).args(["-in", &format!("in.{name}"), "-log", "none", "-threads", "1"]).current_dir(&dir).output().unwrap();
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{name}: {out}{}", String::from_utf8_lossy(&o.stderr));
        let neighs: Vec<i64> = out.lines().filter_map(|l| l.strip_prefix("Neighs:")).map(|l| l.split_whitespace().next().unwrap().parse().unwrap()).collect();
        assert_eq!(neighs, lammps, "{name}");
    }
}
