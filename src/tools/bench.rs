//! `dmhs bench --against lammps [--against liggghts] DECK...`: particle-steps per second of dmhs
//! (at several thread counts) and of the reference engines (serial: LAMMPS' `lmp`, LIGGGHTS for
//! granular decks) on the same decks, measured in the same invocation. The ratio column is
//! relative to LAMMPS (to LIGGGHTS when only it is given).

use crate::tools::cli::deck_dir;
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
        atoms: s.state.atoms.nlocal as u64,
        bytes_per_particle: Some(crate::sim::memory::bytes_per_particle(s)),
    })
}

/// One engine of a bench: a reference engine (serial) or dmhs at a thread count.
#[derive(Clone, Copy)]
enum Engine<'a> {
    Reference(&'a str),
    Dmhs(usize),
}

impl Engine<'_> {
    fn time(&self, deck: &std::path::Path, vars: &[(String, Vec<String>)]) -> Result<Timing, String> {
        match *self {
            Engine::Reference(name) => {
                let (seconds, steps, atoms) = if name == "lammps" { crate::tools::lammps::time_lmp(deck, vars)? } else { crate::tools::liggghts::time_liggghts(deck, vars)? };
                Ok(Timing { engine: format!("{name} 1t"), seconds, steps, atoms, bytes_per_particle: None })
            }
            Engine::Dmhs(n) => time_dmhs(deck, vars, n),
        }
    }
}

/// The median of `v` (not empty; the mean of the middle two for an even count).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}

/// `repeat` rounds, each timing every engine once in turn (so that a slow spell of a shared
/// machine hits all engines of a round alike); each engine's row gives its median time, and with
/// more than one round the lowest and highest of the per-round ratios.
pub fn bench_cmd(decks: &[PathBuf], opts: &DeckOptions, against: &[String], threads: Vec<usize>, repeat: usize) -> i32 {
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
    let mut engines: Vec<Engine> = vec![];
    for name in ["lammps", "liggghts"] {
        if against.iter().any(|a| a == name) {
            engines.push(Engine::Reference(name));
        }
    }
    engines.extend(threads.iter().map(|&n| Engine::Dmhs(n)));
    let rounds_col = if repeat > 1 { format!(" {:>13}", "round ratios") } else { String::new() };
    println!("{:<40} {:<12} {:>10} {:>8} {:>9} {:>14} {:>8} {:>10}{}", "deck", "engine", "atoms", "steps", "seconds", "particle-st/s", "ratio", "bytes/part", rounds_col);
    let mut status = 0;
    for deck in decks {
        let name = deck.display().to_string();
        // times[e][r]: engine e in round r (None where it failed)
        let mut times: Vec<Vec<Option<Timing>>> = vec![vec![]; engines.len()];
        for _ in 0..repeat {
            for (e, engine) in engines.iter().enumerate() {
                let t = engine.time(deck, &opts.vars);
                if let Err(msg) = &t {
                    eprintln!("dmhs bench: {}", msg.trim_end());
                    status = 1;
                }
                times[e].push(t.ok());
            }
        }
        let pss = |t: &Option<Timing>| t.as_ref().map(|t| t.particle_steps_per_second());
        // the reference: the first engine, if it is a reference engine and ran
        let reference_rounds: Option<&Vec<Option<Timing>>> = match engines.first() {
            Some(Engine::Reference(_)) => times.first(),
            _ => None,
        };
        let reference = reference_rounds.and_then(|r| {
            let ok: Vec<f64> = r.iter().filter_map(pss).collect();
            if ok.is_empty() { None } else { Some(median(ok)) }
        });
        for rounds in &times {
            let ok: Vec<&Timing> = rounds.iter().flatten().collect();
            let Some(first) = ok.first() else { continue };
            let seconds = median(ok.iter().map(|t| t.seconds).collect());
            let p = median(ok.iter().map(|t| t.particle_steps_per_second()).collect());
            let ratio = reference.map(|r| format!("{:.2}", p / r)).unwrap_or("-".into());
            let bytes = first.bytes_per_particle.map(|b| format!("{b:.0}")).unwrap_or("-".into());
            let mut line = format!("{:<40} {:<12} {:>10} {:>8} {:>9.3} {:>14.4e} {:>8} {:>10}", name, first.engine, first.atoms, first.steps, seconds, p, ratio, bytes);
            if repeat > 1 {
                let per_round: Vec<f64> = match reference_rounds {
                    Some(r) => rounds.iter().zip(r).filter_map(|(t, rt)| Some(pss(t)? / pss(rt)?)).collect(),
                    None => vec![],
                };
                let range = if per_round.is_empty() { "-".to_string() } else { format!("{:.2}-{:.2}", per_round.iter().copied().fold(f64::INFINITY, f64::min), per_round.iter().copied().fold(0.0, f64::max)) };
                line += &format!(" {range:>13}");
            }
            println!("{line}");
        }
    }
    status
}
