//! `dmhs bench --against lammps [--against liggghts] DECK...`: particle-steps per second of dmhs
//! (at several thread counts) and of the reference engines (serial: LAMMPS' `lmp`, LIGGGHTS for
//! granular decks) on the same decks, measured in the same invocation. The ratio column is
//! relative to LAMMPS (to LIGGGHTS when only it is given).

use crate::cli::deck_dir;
use crate::deck::{run_file, DeckOptions};
use std::path::PathBuf;

/// One measurement.
#[derive(Clone, Debug)]
pub struct Timing {
    pub engine: String,
    pub seconds: f64,
    pub steps: u64,
    pub atoms: u64,
    pub bytes_per_particle: Option<f64>,
}

impl Timing {
    pub fn particle_steps_per_second(&self) -> f64 {
        if self.seconds > 0.0 { self.steps as f64 * self.atoms as f64 / self.seconds } else { 0.0 }
    }
}

/// Time a deck in dmhs with `threads` worker threads.
pub fn time_dmhs(deck: &std::path::Path, vars: &[(String, Vec<String>)], threads: usize) -> Result<Timing, String> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| e.to_string())?;
    let opts = DeckOptions { vars: vars.to_vec(), screen: false, log: None, base_dir: Some(deck_dir(deck)), ..Default::default() };
    let run = pool.install(|| run_file(deck, &opts)).map_err(|f| f.rendered)?;
    let s = &run.sim;
    Ok(Timing {
        engine: format!("dmhs {threads}t"),
        seconds: s.last_loop_seconds,
        steps: s.last_loop_steps as u64,
        atoms: s.atoms.nlocal as u64,
        bytes_per_particle: Some(crate::memory::bytes_per_particle(s)),
    })
}

pub fn bench_cmd(decks: &[PathBuf], opts: &DeckOptions, against: &[String], threads: Vec<usize>) -> i32 {
    if decks.is_empty() {
        eprintln!("dmhs bench: give at least one deck");
        return 2;
    }
    for a in against {
        if a != "lammps" && a != "liggghts" {
            eprintln!("dmhs bench: --against {a} is not supported (lammps and liggghts are)");
            return 2;
        }
    }
    // LAMMPS first: it is the reference of the ratio column
    let mut engines: Vec<&str> = vec![];
    if against.iter().any(|a| a == "lammps") {
        engines.push("lammps");
    }
    if against.iter().any(|a| a == "liggghts") {
        engines.push("liggghts");
    }
    println!("{:<40} {:<12} {:>10} {:>8} {:>9} {:>14} {:>8} {:>10}", "deck", "engine", "atoms", "steps", "seconds", "particle-st/s", "ratio", "bytes/part");
    let mut status = 0;
    for deck in decks {
        let name = deck.display().to_string();
        let mut reference: Option<f64> = None;
        for engine in &engines {
            let timed = if *engine == "lammps" { crate::lammps::time_lmp(deck, &opts.vars) } else { crate::liggghts::time_liggghts(deck, &opts.vars) };
            match timed {
                Ok((sec, steps, atoms)) => {
                    let t = Timing { engine: format!("{engine} 1t"), seconds: sec, steps, atoms, bytes_per_particle: None };
                    let pss = t.particle_steps_per_second();
                    let ratio = match reference {
                        Some(r) => format!("{:.2}", pss / r),
                        None => {
                            reference = Some(pss);
                            "1.00".to_string()
                        }
                    };
                    println!("{:<40} {:<12} {:>10} {:>8} {:>9.3} {:>14.4e} {:>8} {:>10}", name, t.engine, atoms, steps, sec, pss, ratio, "-");
                }
                Err(e) => {
                    eprintln!("dmhs bench: {e}");
                    status = 1;
                }
            }
        }
        for &n in &threads {
            match time_dmhs(deck, &opts.vars, n) {
                Ok(t) => {
                    let pss = t.particle_steps_per_second();
                    let ratio = reference.map(|r| format!("{:.2}", pss / r)).unwrap_or("-".into());
                    println!(
                        "{:<40} {:<12} {:>10} {:>8} {:>9.3} {:>14.4e} {:>8} {:>10.0}",
                        name, t.engine, t.atoms, t.steps, t.seconds, pss, ratio, t.bytes_per_particle.unwrap_or(0.0)
                    );
                }
                Err(e) => {
                    eprint!("{e}");
                    status = 1;
                }
            }
        }
    }
    status
}
