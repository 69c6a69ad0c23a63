//! SPH validation against analytic and experimental references (`dmhs validate`, src/validate.rs).
//!
//! The `--quick` variants run here (a few seconds in all, release build). Expected values were
//! measured with real LAMMPS (22 Jul 2025) on the same decks: dmhs reproduces LAMMPS' Lucy-kernel
//! SPH, so its errors must be LAMMPS' errors.
//!
//! Long runs are `#[ignore]`d: `cargo test --release --test validation -- --ignored` runs the full
//! cases (a few minutes) and the quick speed-accuracy sweep (needs LAMMPS).
//! The live LAMMPS comparison is skipped when LAMMPS is missing, unless DMHS_REQUIRE_LAMMPS=1.

use dmhs::tools::validate::{run_case, run_dmhs, run_lammps, CaseReport, Engine, Options};

fn quick() -> Options {
    Options { quick: true, engine: Engine::Dmhs }
}

fn assert_passed(rep: &CaseReport) {
    assert!(rep.passed(), "{}", rep.render());
}

fn assert_close(what: &str, got: f64, expected: f64, rel: f64) {
    assert!((got - expected).abs() <= rel * expected.abs(), "{what}: {got:e}, expected {expected:e} (within {rel:e} relative)");
}

#[test]
fn poiseuille_converges_and_is_within_one_percent_at_40() {
    let rep = run_case("poiseuille", &quick()).unwrap();
    assert_passed(&rep);
    // L2 velocity error at t = 1 s (steady to 5e-5); LAMMPS gives the same numbers
    assert_close("N=10", rep.summary_value("l2_N10").unwrap(), 4.37609e-2, 1e-4);
    assert_close("N=20", rep.summary_value("l2_N20").unwrap(), 1.91360e-2, 1e-4);
    assert_close("N=40", rep.summary_value("l2_N40").unwrap(), 7.49053e-3, 1e-4);
    assert!(rep.summary_value("l2_N40").unwrap() < 0.01);
    assert!(rep.summary_value("order_20_40").unwrap() > 1.3);
}

#[test]
fn couette_startup() {
    let rep = run_case("couette", &quick()).unwrap();
    assert_passed(&rep);
    assert_close("N=40", rep.summary_value("l2_N40").unwrap(), 2.0774e-3, 1e-3);
    // during the start-up (t = 0.1125 s, third sample) the error is below 0.5 % at N = 40
    let run = &rep.runs[2];
    assert_eq!(run["N"], 40);
    let e = run["samples"][2]["l2_rel"].as_f64().unwrap();
    assert!(e < 5e-3, "{e}");
}

#[test]
fn heat_conduction_follows_erf() {
    let rep = run_case("heat", &quick()).unwrap();
    assert_passed(&rep);
    // max |T - T_exact| for a unit jump; N = 200 is not better than N = 100: the Brookshaw
    // Laplacian with h/dx fixed has a lattice bias (effective D 0.5 % high)
    assert_close("N=50", rep.summary_value("max_N50").unwrap(), 2.5852e-3, 1e-3);
    assert_close("N=100", rep.summary_value("max_N100").unwrap(), 3.6071e-4, 1e-3);
    assert_close("N=200", rep.summary_value("max_N200").unwrap(), 5.6081e-4, 1e-3);
}

#[test]
fn hydrostatic_pressure_profile() {
    let rep = run_case("hydrostatic", &quick()).unwrap();
    assert_passed(&rep);
    assert_close("N=20", rep.summary_value("l2_N20").unwrap(), 5.2462e-2, 1e-3);
    assert_close("N=40", rep.summary_value("l2_N40").unwrap(), 3.7748e-2, 1e-3);
}

#[test]
fn dam_break_front_against_martin_moyce() {
    let rep = run_case("dambreak", &quick()).unwrap();
    assert_passed(&rep);
    // the SPH front runs ahead of the experiment (no gate, no floor friction): by 6.8 % on
    // average over the 10 data points up to Z = 4.5, by 12.5 % at most (same as LAMMPS)
    let rms = rep.summary_value("rms_dx0.02").unwrap();
    assert_close("RMS", rms, 7.5526e-2, 1e-3);
    let run = &rep.runs[0];
    assert_close("mean", run["mean_rel"].as_f64().unwrap(), 6.7894e-2, 1e-3);
    let points = run["points"].as_array().unwrap();
    assert_eq!(points.len(), 10);
    for p in points {
        let rel = p["rel"].as_f64().unwrap();
        assert!(rel > -0.01 && rel < 0.13, "{p}");
    }
}

#[test]
fn sod_shock_tube_against_exact_riemann() {
    let rep = run_case("sod", &quick()).unwrap();
    assert_passed(&rep);
    // L1 (mean absolute per particle within 60 of the diaphragm) at t = 20, 2008 particles
    assert_close("rho", rep.summary_value("l1_rho").unwrap(), 9.6575e-3, 1e-3);
    assert_close("u", rep.summary_value("l1_u").unwrap(), 2.7709e-2, 1e-3);
    assert_close("p", rep.summary_value("l1_p").unwrap(), 1.1040e-2, 1e-3);
    // the exact star state of Sod's problem (Toro: p* 0.30313, u* 0.92745)
    assert_close("p*", rep.runs[0]["p_star"].as_f64().unwrap(), 0.30313, 1e-4);
}

/// dmhs and LAMMPS on the same validation deck: the same state, hence the same error.
#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn validation_deck_matches_lammps() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let vars = vec![("N".to_string(), "20".to_string())];
    let ours = run_dmhs("poiseuille", &vars, &[0.1]).unwrap();
    let theirs = run_lammps("poiseuille", &vars, &[0.1]).unwrap();
    assert_eq!(ours.last().step, theirs.last().step);
    let d = dmhs::tools::crosscheck::compare(&ours.last().state, &theirs.last().state, "velocity", &["vx", "vy", "vz"], dmhs::tools::crosscheck::Scale::MaxMagnitude).unwrap();
    assert!(d.max_rel < 1e-10, "{d:?}");
}

#[test]
fn cli_writes_json_and_charts() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("heat.json");
    let img = dir.path().join("img");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dmhs"))
        .args(["validate", "heat", "--quick", "--json"])
        .arg(&json)
        .arg("--img")
        .arg(&img)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("PASS max |T - T_exact|, N = 100"), "{stdout}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["case"], "heat");
    assert_eq!(v["passed"], true);
    assert_eq!(v["runs"].as_array().unwrap().len(), 3);
    assert!(img.join("heat_profile.png").exists() && img.join("heat_profile.svg").exists());
    // an unknown case is a usage error
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dmhs")).args(["validate", "nope"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown case `nope`"));
}

/// The full cases (the numbers of docs/validation.md): several minutes.
#[test]
#[ignore]
fn full_cases() {
    let opts = Options { quick: false, engine: Engine::Dmhs };
    for case in dmhs::tools::validate::CASES {
        let rep = run_case(case, &opts).unwrap();
        println!("{}", rep.render());
        assert_passed(&rep);
    }
}

/// The quick speed-accuracy sweep (dmhs and LAMMPS).
#[test]
#[ignore]
fn speed_sweep_quick() {
    let points = dmhs::tools::validate::speed_sweep(true, &mut |_| {}).unwrap();
    for p in &points {
        assert!(p.error.is_some() && p.seconds > 0.0, "{p:?}");
    }
    // LAMMPS and dmhs (Lucy) have the same error on each configuration
    for p in points.iter().filter(|p| p.engine == Engine::Lammps) {
        let q = points.iter().find(|q| q.engine == Engine::Dmhs && q.kernel == p.kernel && q.n == p.n && q.cdt == p.cdt).unwrap();
        assert!((p.error.unwrap() - q.error.unwrap()).abs() < 1e-9, "{p:?} {q:?}");
    }
}
