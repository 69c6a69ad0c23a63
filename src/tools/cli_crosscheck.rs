//! `dmhs crosscheck DECK [--against lammps|liggghts]`: the deck in dmhs and in a reference
//! engine (LAMMPS by default; LIGGGHTS for granular decks, see [`crate::tools::liggghts`]), per-atom
//! differences, a verdict.

use crate::tools::cli::deck_dir;
use crate::tools::crosscheck::{capture_state, compare_runs, curve_table, curves, report, AtomTable, Capture, Curve, Difference, CHAOS_MARGIN};
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
    dmhs_capture_full(deck, vars, log).map(|(c, box_len)| (c.forces0, c.fin, box_len))
}

/// dmhs' step-0 forces, checkpoints (steps 1, 2, 4, ... after the first run's start and the
/// end of every run) and final state, and the longest box edge.
pub fn dmhs_capture_full(deck: &Path, vars: &[(String, Vec<String>)], log: Option<std::path::PathBuf>) -> Result<(Capture, f64), String> {
    let opts = DeckOptions { vars: vars.to_vec(), screen: false, log, base_dir: Some(deck_dir(deck)), capture: true, ..Default::default() };
    let run = run_file(deck, &opts).map_err(|f| f.rendered)?;
    let mut sim = run.sim;
    let forces0 = sim.capture_setup.take().ok_or("the deck has no run command: nothing to compare")?;
    let fin = capture_state(&sim);
    let d = sim.state.domain.as_ref().ok_or("the deck defines no box")?;
    let prd = d.prd();
    let box_len = prd[..d.dimension].iter().cloned().fold(0.0, f64::max);
    Ok((Capture { forces0, checkpoints: std::mem::take(&mut sim.capture_checkpoints), fin }, box_len))
}

/// What lammps_driver.py wrote into `dir`: forces0.txt, checkpoint.STEP.txt, final.txt.
pub fn read_capture(dir: &Path, steps: &[i64]) -> Result<Capture, String> {
    let mut checkpoints = vec![];
    for &s in steps {
        let p = dir.join(format!("checkpoint.{s}.txt"));
        if p.exists() {
            checkpoints.push((s, AtomTable::read(&p)?));
        }
    }
    Ok(Capture { forces0: AtomTable::read(&dir.join("forces0.txt"))?, checkpoints, fin: AtomTable::read(&dir.join("final.txt"))? })
}

/// LAMMPS twice on a deck, as written and with every coordinate nudged by one ulp before the
/// first run (its own round-off sensitivity), both writing the checkpoints `steps`; the two
/// runs go in parallel.
pub fn lammps_pair(deck: &Path, vars: &[(String, Vec<String>)], steps: &[i64]) -> Result<(Capture, Capture), String> {
    let (a, b) = (tempfile::tempdir().map_err(|e| e.to_string())?, tempfile::tempdir().map_err(|e| e.to_string())?);
    let list: Vec<String> = steps.iter().map(|s| s.to_string()).collect();
    let ck = vec!["--checkpoints".to_string(), list.join(",")];
    let mut nudged = ck.clone();
    nudged.extend(["--perturb".to_string(), "ulp".to_string()]);
    let (ra, rb) = std::thread::scope(|sc| {
        let h = sc.spawn(|| crate::tools::lammps::run_driver_with(deck, vars, b.path(), &nudged));
        let ra = crate::tools::lammps::run_driver_with(deck, vars, a.path(), &ck);
        (ra, h.join().unwrap_or_else(|_| Err("the LAMMPS thread failed".to_string())))
    });
    ra?;
    rb.map_err(|e| format!("(the run nudged by one ulp) {e}"))?;
    Ok((read_capture(a.path(), steps)?, read_capture(b.path(), steps)?))
}

/// The verdict of the curves: whether they pass, and one line per quantity.
pub fn verdict(curves: &[Curve]) -> (bool, String) {
    let mut s = String::new();
    let mut pass = true;
    for c in curves {
        let fails = c.failures();
        let upto = c.agrees_up_to().unwrap_or("no point");
        let all = c.rows.iter().all(|r| r.1 <= c.tol);
        let line = if !fails.is_empty() {
            pass = false;
            let more = if fails.len() > 1 { format!(" (and at {} later points)", fails.len() - 1) } else { String::new() };
            format!("FAIL {}{more}\n", fails[0])
        } else if all {
            format!("  {:<9} agrees within {:.0e} at every point\n", c.quantity, c.tol)
        } else {
            let worst = c.rows.iter().filter(|r| r.1 > c.tol).map(|r| r.1 / r.2.max(f64::MIN_POSITIVE)).fold(0.0, f64::max);
            format!("  {:<9} agrees within {:.0e} up to {upto}, then diverges no faster than LAMMPS from itself (at most {worst:.2} x its own divergence; allowed {CHAOS_MARGIN})\n", c.quantity, c.tol)
        };
        s += &line;
    }
    (pass, s)
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
            "velocity" | "rho" | "esph" | "omega" | "temperature" => tols[2],
            _ => tols[0],
        };
        if !(d.max_rel <= tol) {
            bad.push(format!("{}: max rel {:.3e} > tolerance {:.1e} (atom {})", d.quantity, d.max_rel, tol, d.worst_id));
        }
    }
    bad
}

pub fn crosscheck_cmd(decks: &[std::path::PathBuf], opts: &DeckOptions, against: &[String], tols: [Option<f64>; 3], curve_file: Option<&Path>) -> i32 {
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
        let (ours, box_len) = match dmhs_capture_full(&deck_abs, &opts.vars, None) {
            Ok(x) => x,
            Err(e) => {
                eprint!("{e}");
                return 2;
            }
        };
        for engine in &engines {
            let code = if engine == "lammps" { against_lammps(deck, &deck_abs, &opts.vars, &ours, box_len, tols, curve_file) } else { against_liggghts(deck, &deck_abs, &opts.vars, &ours, box_len, tols) };
            match code {
                Ok(true) => {}
                Ok(false) => status = 1,
                Err(e) => {
                    eprintln!("dmhs crosscheck: {e}");
                    return 1;
                }
            }
        }
    }
    status
}

/// The checkpoint comparison with LAMMPS (and LAMMPS against itself); prints, returns the verdict.
fn against_lammps(deck: &Path, deck_abs: &Path, vars: &[(String, Vec<String>)], ours: &Capture, box_len: f64, tols: [f64; 3], curve_file: Option<&Path>) -> Result<bool, String> {
    let steps: Vec<i64> = ours.checkpoints.iter().map(|c| c.0).collect();
    let (base, nudged) = lammps_pair(deck_abs, vars, &steps)?;
    let cs = match curves(ours, &base, &nudged, box_len, tols) {
        Ok(c) => c,
        Err(e) => {
            println!("FAIL {e}");
            return Ok(false);
        }
    };
    println!("crosscheck {} against LAMMPS ({} atoms; step 0, {} checkpoints, the end)", deck.display(), base.fin.rows.len(), steps.len());
    println!("LAMMPS' own divergence: LAMMPS run again with every coordinate moved by one ulp before the first run");
    println!("scales (each difference below is divided by its quantity's scale):");
    for c in &cs {
        println!("  {:<9} {:>12.6e}  {}", c.quantity, c.scale, c.scale_why);
    }
    let table = curve_table(&cs);
    println!("divergence: max |dmhs - LAMMPS| / scale per quantity, then (LAMMPS) max |LAMMPS nudged - LAMMPS| / scale");
    print!("{table}");
    if let Some(f) = curve_file {
        crate::output::log::write_atomic(f, table.as_bytes()).map_err(|e| format!("cannot write {}: {e}", f.display()))?;
    }
    let (pass, text) = verdict(&cs);
    print!("{text}");
    if pass {
        println!("PASS (force tol {:.0e}, position tol {:.0e}, velocity tol {:.0e}; or within {CHAOS_MARGIN} x LAMMPS' own divergence where that is larger)", tols[0], tols[1], tols[2]);
    }
    Ok(pass)
}

/// LIGGGHTS writes step-0 forces and the final state only: those are compared with the strict
/// tolerances.
fn against_liggghts(deck: &Path, deck_abs: &Path, vars: &[(String, Vec<String>)], ours: &Capture, box_len: f64, tols: [f64; 3]) -> Result<bool, String> {
    let tmp = tempfile::tempdir().map_err(|e| format!("cannot make a temporary directory: {e}"))?;
    crate::tools::liggghts::run_driver(deck_abs, vars, tmp.path())?;
    let theirs0 = AtomTable::read(&tmp.path().join("forces0.txt"))?;
    let theirs = AtomTable::read(&tmp.path().join("final.txt"))?;
    match compare_runs(&ours.forces0, &theirs0, &ours.fin, &theirs, box_len) {
        Ok(diffs) => {
            println!("crosscheck {} against LIGGGHTS ({} atoms)", deck.display(), theirs.rows.len());
            print!("{}", report(&diffs));
            let bad = within(&diffs, tols);
            if bad.is_empty() {
                println!("PASS (force tol {:.0e}, position tol {:.0e}, velocity tol {:.0e})", tols[0], tols[1], tols[2]);
            }
            for b in &bad {
                println!("FAIL {b}");
            }
            Ok(bad.is_empty())
        }
        Err(e) => {
            println!("FAIL {e}");
            Ok(false)
        }
    }
}
