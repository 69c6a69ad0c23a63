//! `dmhs crosscheck DECK [--against lammps|liggghts]`: the deck in dmhs and in a reference
//! engine (LAMMPS by default; LIGGGHTS for granular decks, see [`crate::tools::liggghts`]), per-atom
//! differences, a verdict.

use crate::tools::cli::deck_dir;
use crate::tools::crosscheck::{capture_state, compare_runs, report, AtomTable, Difference};
use crate::deck::{run_file, DeckOptions};
use std::path::Path;

pub const DEFAULT_FORCE_TOL: f64 = 1e-12;
pub const DEFAULT_POS_TOL: f64 = 1e-9;
pub const DEFAULT_VEL_TOL: f64 = 1e-8;

/// dmhs' step-0 forces and final state for a deck (relative paths resolve in the deck's folder).
pub fn dmhs_capture(deck: &Path, vars: &[(String, Vec<String>)]) -> Result<(AtomTable, AtomTable, f64), String> {
    dmhs_capture_logged(deck, vars, None)
}

/// [`dmhs_capture`], writing the log to `log`.
pub fn dmhs_capture_logged(deck: &Path, vars: &[(String, Vec<String>)], log: Option<std::path::PathBuf>) -> Result<(AtomTable, AtomTable, f64), String> {
    let opts = DeckOptions { vars: vars.to_vec(), screen: false, log, base_dir: Some(deck_dir(deck)), capture: true, ..Default::default() };
    let run = run_file(deck, &opts).map_err(|f| f.rendered)?;
    let sim = run.sim;
    let f0 = sim.capture_setup.clone().ok_or("the deck has no run command: nothing to compare")?;
    let fin = capture_state(&sim);
    let d = sim.state.domain.as_ref().ok_or("the deck defines no box")?;
    let prd = d.prd();
    let box_len = prd[..d.dimension].iter().cloned().fold(0.0, f64::max);
    Ok((f0, fin, box_len))
}

/// `dmhs capture DECK --out DIR`: forces0.txt and final.txt of dmhs, in the format of
/// lammps_driver.py (two engines, or two builds of dmhs, compare with `diff`).
pub fn capture_cmd(decks: &[std::path::PathBuf], opts: &DeckOptions, out: Option<&Path>) -> i32 {
    let ([deck], Some(out)) = (decks, out) else {
        eprintln!("dmhs capture: give one deck and --out DIR");
        return 2;
    };
    let deck_abs = std::fs::canonicalize(deck).unwrap_or(deck.clone());
    let (forces0, fin, _) = match dmhs_capture_logged(&deck_abs, &opts.vars, opts.log.clone()) {
        Ok(x) => x,
        Err(e) => {
            eprint!("{e}");
            return 1;
        }
    };
    let write = |name: &str, t: &AtomTable| crate::output::log::write_atomic(&out.join(name), t.to_text().as_bytes());
    match std::fs::create_dir_all(out).and_then(|_| write("forces0.txt", &forces0)).and_then(|_| write("final.txt", &fin)) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("dmhs capture: cannot write into {}: {e}", out.display());
            1
        }
    }
}

/// Whether every difference is within its tolerance.
pub fn within(diffs: &[Difference], tols: [f64; 3]) -> Vec<String> {
    let mut bad = vec![];
    for d in diffs {
        let tol = match d.quantity.as_str() {
            "position" => tols[1],
            "velocity" | "rho" | "esph" | "omega" => tols[2],
            _ => tols[0],
        };
        if !(d.max_rel <= tol) {
            bad.push(format!("{}: max rel {:.3e} > tolerance {:.1e} (atom {})", d.quantity, d.max_rel, tol, d.worst_id));
        }
    }
    bad
}

pub fn crosscheck_cmd(decks: &[std::path::PathBuf], opts: &DeckOptions, against: &[String], tols: [Option<f64>; 3]) -> i32 {
    let tols = [tols[0].unwrap_or(DEFAULT_FORCE_TOL), tols[1].unwrap_or(DEFAULT_POS_TOL), tols[2].unwrap_or(DEFAULT_VEL_TOL)];
    if decks.is_empty() {
        eprintln!("dmhs crosscheck: give a deck");
        return 2;
    }
    let engines: Vec<String> = if against.is_empty() { vec!["lammps".to_string()] } else { against.to_vec() };
    for engine in &engines {
        if engine != "lammps" && engine != "liggghts" {
            eprintln!("dmhs crosscheck: --against {engine} is not supported (lammps and liggghts are)");
            return 2;
        }
    }
    let mut status = 0;
    for deck in decks {
        let deck_abs = std::fs::canonicalize(deck).unwrap_or(deck.clone());
        let (ours0, ours, box_len) = match dmhs_capture(&deck_abs, &opts.vars) {
            Ok(x) => x,
            Err(e) => {
                eprint!("{e}");
                return 2;
            }
        };
        for engine in &engines {
            let tmp = match tempfile::tempdir() {
                Ok(t) => t,
                Err(e) => {
                    eprintln!("dmhs crosscheck: cannot make a temporary directory: {e}");
                    return 1;
                }
            };
            let ran = if engine == "lammps" {
                crate::tools::lammps::run_driver(&deck_abs, &opts.vars, tmp.path())
            } else {
                crate::tools::liggghts::run_driver(&deck_abs, &opts.vars, tmp.path())
            };
            if let Err(e) = ran {
                eprintln!("dmhs crosscheck: {e}");
                return 1;
            }
            let theirs0 = AtomTable::read(&tmp.path().join("forces0.txt"));
            let theirs = AtomTable::read(&tmp.path().join("final.txt"));
            let (theirs0, theirs) = match (theirs0, theirs) {
                (Ok(a), Ok(b)) => (a, b),
                (Err(e), _) | (_, Err(e)) => {
                    eprintln!("dmhs crosscheck: {e}");
                    return 1;
                }
            };
            let label = if engine == "lammps" { "LAMMPS" } else { "LIGGGHTS" };
            match compare_runs(&ours0, &theirs0, &ours, &theirs, box_len) {
                Ok(diffs) => {
                    println!("crosscheck {} against {label} ({} atoms)", deck.display(), theirs.rows.len());
                    print!("{}", report(&diffs));
                    let bad = within(&diffs, tols);
                    if bad.is_empty() {
                        println!("PASS (force tol {:.0e}, position tol {:.0e}, velocity tol {:.0e})", tols[0], tols[1], tols[2]);
                    } else {
                        for b in bad {
                            println!("FAIL {b}");
                        }
                        status = 1;
                    }
                }
                Err(e) => {
                    println!("FAIL {e}");
                    status = 1;
                }
            }
        }
    }
    status
}
