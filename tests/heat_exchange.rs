//! Heat and momentum exchange for thermal conductivity and viscosity (LAMMPS' examples/KAPPA and
//! examples/VISCOSITY): fix heat (constant, equal- and atom-style flux), fix ehex (eHEX/a, and
//! plain HEX with `hex`), fix thermal/conductivity and fix viscosity (Muller-Plathe swaps, with
//! `swap` and `vtarget`), and fix ave/chunk and fix ave/atom of an atom-style variable (the
//! examples' temperature profile).
//!
//! tests/heat_exchange/in.heat_exchange runs them on a gas of dimers (bonds only, pair zero, so
//! each atom's force is its one bond's): the values, the profile and the final atoms are
//! byte-identical to LAMMPS 22 Jul 2025's (%.17g), stored in tests/heat_exchange/expected and
//! made now (live). Besides, the heat each fix adds is checked against its definition on an
//! ideal gas, and bad input is a located error.

mod common;

use std::path::PathBuf;

const FILES: [&str; 3] = ["values.txt", "profile.txt", "final.txt"];

fn deck_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/heat_exchange")
}

/// Byte equality of each file in the two folders.
fn identical(want: &std::path::Path, got: &std::path::Path) -> Vec<String> {
    FILES
        .iter()
        .filter(|f| std::fs::read(want.join(f)).unwrap_or_default() != std::fs::read(got.join(f)).unwrap_or_else(|e| panic!("{f}: {e}")))
        .map(|f| format!("{f} differs from LAMMPS' ({})", want.join(f).display()))
        .collect()
}

#[test]
fn files_are_the_stored_lammps_files() {
    let tmp = common::run_dmhs(&deck_dir(), "in.heat_exchange");
    let bad = identical(&deck_dir().join("expected"), tmp.path());
    assert!(bad.is_empty(), "{}", bad.join("\n"));
    // the fixes act: heat in (scale > 1), heat out (< 1), and energy swapped
    let last = std::fs::read_to_string(tmp.path().join("values.txt")).unwrap().lines().last().unwrap().to_string();
    let v: Vec<f64> = last.split_whitespace().map(|w| w.parse().unwrap()).collect();
    assert_eq!(v[0], 400.0, "{last}");
    assert!(v[3] > 1.0 && v[4] < 1.0 && v[5] > 1.0 && v[6] > 1.0 && v[7] < 1.0 && v[8] > 100.0 && v[9] < -100.0 && v[10] < -10.0, "{last}");
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn files_are_the_files_lammps_writes_now() {
    let Some(python) = dmhs::tools::lammps::python_for_live_test() else {
        return;
    };
    let lmp = common::run_lammps(&python, &deck_dir(), "in.heat_exchange");
    let ours = common::run_dmhs(&deck_dir(), "in.heat_exchange");
    let bad = identical(lmp.path(), ours.path());
    assert!(bad.is_empty(), "{}", bad.join("\n"));
    let stale = identical(lmp.path(), &deck_dir().join("expected"));
    assert!(stale.is_empty(), "tests/heat_exchange/expected is not what LAMMPS writes now:\n{}", stale.join("\n"));
}

/// The kinetic energy of an ideal gas (no forces) after each of 20 steps with one fix.
fn kinetic_energies(fix: &str) -> Vec<f64> {
    let deck = format!(
        "units lj\nlattice sc 0.5\nregion box block 0 6 0 6 0 6\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 2.0\n\
         pair_style zero 1.0\npair_coeff * *\nvelocity all create 1.5 87287 loop geom\nvelocity all set 0.3 NULL NULL sum yes\n\
         timestep 0.01\nfix 1 all nve\n{fix}\nthermo_style custom step ke\nthermo_modify format float %.17g\nthermo 1\nrun 20\n"
    );
    let opts = dmhs::deck::DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = dmhs::deck::run_text("ideal.deck", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.clone().unwrap();
    let (names, rows) = table(&text);
    let k = names.iter().position(|n| n == "KinEng").unwrap();
    rows.iter().map(|r| r[k] * 216.0).collect()
}

/// Column names and rows of the thermo table in `text`.
fn table(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().position(|l| l.trim_start().starts_with("Step")).unwrap();
    let names = lines[start].split_whitespace().map(String::from).collect();
    let rows = lines[start + 1..].iter().map_while(|l| l.split_whitespace().map(|w| w.parse::<f64>().ok()).collect::<Option<Vec<f64>>>().filter(|r| !r.is_empty())).collect();
    (names, rows)
}

/// fix heat and fix ehex on the whole of an ideal gas add exactly eflux * N * dt every N steps
/// (the velocities scale about the centre of mass, whose drift keeps its energy); fix
/// thermal/conductivity and fix viscosity move energy or momentum but keep the total energy.
#[test]
fn the_heat_added_is_the_flux_times_the_time() {
    let base = kinetic_energies("");
    assert!(base.windows(2).all(|w| w[0] == w[1]), "no forces: constant energy {base:?}");
    for (fix, n, flux) in [("fix h all heat 1 0.7", 1, 0.7), ("fix h all heat 4 -0.5", 4, -0.5), ("fix h all ehex 2 0.3", 2, 0.3), ("fix h all ehex 1 -0.2 hex", 1, -0.2)] {
        let ke = kinetic_energies(fix);
        for (step, e) in ke.iter().enumerate() {
            let applied = (step as i64 / n) as f64;
            let want = base[0] + applied * flux * n as f64 * 0.01;
            assert!((e - want).abs() < 1e-11 * base[0], "{fix}: step {step}: ke {e}, want {want}");
        }
    }
    for fix in ["fix h all thermal/conductivity 2 y 6 swap 4", "fix h all viscosity 2 x z 6 swap 3"] {
        for e in &kinetic_energies(fix) {
            assert!((e - base[0]).abs() < 1e-12 * base[0], "{fix}: swaps keep the energy: {e} against {}", base[0]);
        }
    }
}

/// Bad input is a located error (deck:line:col and what was expected), never a panic.
#[test]
fn bad_input_is_a_located_error() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\nvariable e equal 1.0\ncompute ke all ke/atom\n\
                compute layers all chunk/atom bin/1d z lower 0.5 units reduced\n";
    let cases: &[(&str, &str)] = &[
        ("fix h all heat 0 1.0\n", "N (steps between heat additions)"),
        ("fix h all heat 1\n", "eflux"),
        ("fix h all heat 1 abc\n", "eflux"),
        ("fix h all heat 1 1.0 region nowhere\n", "region `nowhere` does not exist"),
        ("fix h all heat 1 1.0 bogus\n", "bogus"),
        ("fix h all ehex 1 1.0 constrain\n", "fix shake or fix rattle"),
        ("fix h all ehex 1 1.0 com\n", "fix shake or fix rattle"),
        ("fix h all ehex 1 v_e\n", "F"),
        ("fix m all thermal/conductivity 10 w 20\n", "edim"),
        ("fix m all thermal/conductivity 10 z 7\n", "Nbin must be even"),
        ("fix m all thermal/conductivity 10 z 2\n", "Nbin (number of slabs)"),
        ("fix m all thermal/conductivity 10 z 20 swap 0\n", "Nswap"),
        ("fix m all thermal/conductivity 10 z 20 exchange 3\n", "exchange"),
        ("fix m all viscosity 10 x w 20\n", "pdim"),
        ("fix m all viscosity 10 x y 9\n", "Nbin must be even"),
        ("fix m all viscosity 10 x y 20 vtarget -1\n", "Fix viscosity vtarget value must be positive"),
        ("fix m all viscosity 10 x y 20 vtarget\n", "vtarget (a positive velocity or INF)"),
        ("fix m all viscosity 10 x y 20 swap 2 bogus\n", "bogus"),
        ("fix a all ave/chunk 10 1 10 layers v_e\n", "Fix ave/chunk variable e is not atom-style variable"),
        ("fix a all ave/chunk 10 1 10 layers v_nope\n", "Variable name nope for fix ave/chunk does not exist"),
        ("fix a all ave/atom 10 1 10 v_e\n", "Fix ave/atom variable e is not atom-style variable"),
        ("fix s all ave/spatial 20 50 1000 y center 0.05 vx units reduced\n", "was removed from LAMMPS"),
    ];
    common::assert_located_errors(base, cases);
}
