//! `dmhs bench --against lammps [--against liggghts] DECK...`: particle-steps per second of dmhs
//! and of the reference engines on the same decks, measured in the same invocation, each engine a
//! child process whose peak memory is read from /proc. For every core count N of
//! `--threads-list`, LAMMPS runs as a user with N cores would run it: serial for N = 1,
//! `mpiexec -np N` and `-sf omp -pk omp N` above; LIGGGHTS runs serial. The ratio column compares
//! each engine with the fastest reference engine on the same number of cores.

use crate::output::plot::{Chart, Legend, Series};
use crate::tools::lammps::{LmpConfig, RunTiming};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// One measurement.
#[derive(Clone, Debug)]
pub struct Timing {
    pub engine: String,
    pub seconds: f64,
    pub steps: u64,
    pub atoms: u64,
    pub peak_bytes: Option<u64>,
}

impl Timing {
    pub fn particle_steps_per_second(&self) -> f64 {
        if self.seconds > 0.0 { self.steps as f64 * self.atoms as f64 / self.seconds } else { 0.0 }
    }
}

/// Time a deck in dmhs with `threads` worker threads, as a child process (this executable).
pub fn time_dmhs(deck: &Path, vars: &[(String, Vec<String>)], threads: usize) -> Result<RunTiming, String> {
    time_dmhs_on(deck, vars, threads, 1)
}

/// [`time_dmhs`] on `ranks` ranks of `mpiexec` (DMHS_MPIEXEC, default `mpiexec`) when more than
/// one: this executable must be the `mpi` build.
pub fn time_dmhs_on(deck: &Path, vars: &[(String, Vec<String>)], threads: usize, ranks: usize) -> Result<RunTiming, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot find the dmhs executable: {e}"))?;
    time_exe(&exe, deck, vars, threads, ranks)
}

/// [`time_dmhs_on`] with the dmhs executable `exe` (another build, for `--baseline`).
fn time_exe(exe: &Path, deck: &Path, vars: &[(String, Vec<String>)], threads: usize, ranks: usize) -> Result<RunTiming, String> {
    let dir = deck.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut cmd = if ranks > 1 {
        if !cfg!(feature = "mpi") {
            return Err("--ranks needs the MPI build of dmhs (cargo build --release --features mpi)".into());
        }
        let mpiexec = std::env::var("DMHS_MPIEXEC").unwrap_or_else(|_| "mpiexec".into());
        let mut c = std::process::Command::new(mpiexec);
        c.arg("-np").arg(ranks.to_string()).arg(exe);
        c
    } else {
        std::process::Command::new(exe)
    };
    cmd.current_dir(dir).arg("-in").arg(deck.file_name().unwrap_or_default()).arg("-log").arg("none").arg("-threads").arg(threads.to_string());
    for (name, values) in vars {
        cmd.arg("-var").arg(name).args(values);
    }
    let name = exe.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let m = crate::tools::measure::run_measured(&mut cmd, &name, Duration::from_millis(50)).map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    if !m.status.success() {
        return Err(format!("dmhs failed on {}:\n{}{}", deck.display(), m.stdout, m.stderr));
    }
    let (seconds, steps, atoms) = crate::tools::lammps::parse_loop_time(&m.stdout).ok_or_else(|| format!("no `Loop time` line in the output of dmhs for {}", deck.display()))?;
    Ok(RunTiming { seconds, steps, atoms, peak_bytes: m.peak_bytes })
}

/// One engine of a bench.
#[derive(Clone, Copy)]
enum Engine {
    Lammps(LmpConfig),
    Liggghts,
    Dmhs(usize),
    /// dmhs on N ranks of one thread each
    DmhsRanks(usize),
    /// another dmhs build (`--baseline PATH`) on N threads
    Baseline(usize),
}

impl Engine {
    fn cores(self) -> usize {
        match self {
            Engine::Lammps(c) => c.cores(),
            Engine::Liggghts => 1,
            Engine::Dmhs(n) | Engine::DmhsRanks(n) | Engine::Baseline(n) => n,
        }
    }

    /// Whether the ratios are taken against this engine: the baseline build when there is one,
    /// else the reference engines (LAMMPS, LIGGGHTS).
    fn is_reference(self, with_baseline: bool) -> bool {
        match self {
            Engine::Baseline(_) => true,
            Engine::Lammps(_) | Engine::Liggghts => !with_baseline,
            Engine::Dmhs(_) | Engine::DmhsRanks(_) => false,
        }
    }

    fn label(self) -> String {
        match self {
            Engine::Lammps(c) => format!("lammps {}", c.label()),
            Engine::Liggghts => "liggghts 1t".into(),
            Engine::Dmhs(n) => format!("dmhs {n}t"),
            Engine::DmhsRanks(n) => format!("dmhs {n}r"),
            Engine::Baseline(n) => format!("base {n}t"),
        }
    }

    fn time(self, deck: &Path, vars: &[(String, Vec<String>)], baseline: Option<&Path>) -> Result<Timing, String> {
        let t = match self {
            Engine::Lammps(config) => crate::tools::lammps::time_lmp(deck, vars, config)?,
            Engine::Liggghts => crate::tools::liggghts::time_liggghts(deck, vars)?,
            Engine::Dmhs(n) => time_dmhs(deck, vars, n)?,
            Engine::DmhsRanks(n) => time_dmhs_on(deck, vars, 1, n)?,
            Engine::Baseline(n) => time_exe(baseline.expect("a baseline build"), deck, vars, n, 1)?,
        };
        Ok(Timing { engine: self.label(), seconds: t.seconds, steps: t.steps, atoms: t.atoms, peak_bytes: t.peak_bytes })
    }
}

/// The median of `v` (not empty; the mean of the middle two for an even count).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}

/// One deck measured: `times[e][r]`, engine e in round r (None where it failed).
type Rounds = Vec<Vec<Option<Timing>>>;

/// What `dmhs bench` runs besides the decks.
#[derive(Clone, Copy)]
pub struct BenchOptions<'a> {
    /// reference engines: "lammps", "liggghts"
    pub against: &'a [String],
    /// core counts: dmhs threads, and the reference engines' configurations on as many cores
    pub threads: &'a [usize],
    /// interleaved rounds of all engines
    pub repeat: usize,
    /// also dmhs on that many ranks of one thread (the `mpi` build)
    pub ranks: Option<usize>,
    /// an index variable of the decks and its values (`--sizes NAME=V1,V2`)
    pub sizes: Option<&'a (String, Vec<String>)>,
    /// where the chart of `sizes` goes (default out/bench)
    pub img: Option<&'a Path>,
    /// another dmhs build, run on the same thread counts, against which the ratios are taken
    pub baseline: Option<&'a Path>,
}

/// `repeat` rounds, each timing every engine once in turn (so that a slow spell of a shared
/// machine hits all engines of a round alike); each engine's row gives its median time, its ratio
/// to the fastest reference engine on as many cores (medians; the baseline build where given),
/// and with more than one round the lowest and highest of the per-round ratios.
/// `ranks`: also dmhs on that many ranks of one thread (the `mpi` build), against the reference
/// engines on as many cores.
/// `sizes`: an index variable of the decks and its values: every deck runs once per value, and
/// a chart of particle-steps/s against particles, one line per engine, goes to `img` (default
/// out/bench) as bench_sizes_DECK.png and .svg.
pub fn bench_cmd(decks: &[PathBuf], vars: &[(String, Vec<String>)], o: &BenchOptions) -> i32 {
    let BenchOptions { against, threads, repeat, ranks, sizes, img, baseline } = *o;
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
    let cores_of_ranks = ranks.filter(|r| !threads.contains(r));
    let mut engines: Vec<Engine> = vec![];
    // the reference engines run on every core count dmhs runs on
    let mut reference_cores = threads.to_vec();
    reference_cores.extend(cores_of_ranks);
    if against.iter().any(|a| a == "lammps") {
        for &n in &reference_cores {
            if n == 1 {
                engines.push(Engine::Lammps(LmpConfig::Serial));
            } else {
                engines.push(Engine::Lammps(LmpConfig::Mpi(n)));
                engines.push(Engine::Lammps(LmpConfig::Omp(n)));
            }
        }
    }
    if against.iter().any(|a| a == "liggghts") {
        engines.push(Engine::Liggghts);
    }
    if let Some(b) = baseline {
        if !b.is_file() {
            eprintln!("dmhs bench: --baseline {}: no such file (give another dmhs executable)", b.display());
            return 2;
        }
        engines.extend(threads.iter().map(|&n| Engine::Baseline(n)));
    }
    engines.extend(threads.iter().map(|&n| Engine::Dmhs(n)));
    engines.extend(ranks.map(Engine::DmhsRanks));
    let rounds_col = if repeat > 1 { format!(" {:>13}", "round ratios") } else { String::new() };
    println!("{:<40} {:<12} {:>10} {:>8} {:>9} {:>14} {:>8} {:>9} {:>10}{}", "deck", "engine", "atoms", "steps", "seconds", "particle-st/s", "ratio", "peak MiB", "bytes/part", rounds_col);
    let mut status = 0;
    for deck in decks {
        let name = deck.display().to_string();
        let Some((var, values)) = sizes else {
            let times = measure(deck, vars, &engines, repeat, baseline, &mut status);
            print_rows(&name, &engines, &times, repeat, baseline.is_some());
            continue;
        };
        // per engine: (particles, median particle-steps/s) at each size
        let mut curves: Vec<Vec<(f64, f64)>> = vec![vec![]; engines.len()];
        for value in values {
            let mut with_size: Vec<(String, Vec<String>)> = vars.iter().filter(|(n, _)| n != var).cloned().collect();
            with_size.push((var.clone(), vec![value.clone()]));
            let times = measure(deck, &with_size, &engines, repeat, baseline, &mut status);
            print_rows(&format!("{name} {var}={value}"), &engines, &times, repeat, baseline.is_some());
            for (curve, rounds) in curves.iter_mut().zip(&times) {
                let ok: Vec<&Timing> = rounds.iter().flatten().collect();
                if let Some(first) = ok.first() {
                    curve.push((first.atoms as f64, median(ok.iter().map(|t| t.particle_steps_per_second()).collect())));
                }
            }
        }
        let stem = deck.file_name().map(|f| f.to_string_lossy().replace('.', "_")).unwrap_or_else(|| "deck".into());
        let dir = img.map(Path::to_path_buf).unwrap_or_else(|| PathBuf::from("out/bench"));
        let mut chart = Chart::new(&format!("{} at {} = {}", deck.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default(), var, values.join(", ")))
            .x_label("particles")
            .y_label("particle-steps per second")
            .log_x()
            .log_y()
            .legend(Legend::LowerLeft);
        for (k, (engine, curve)) in engines.iter().zip(curves).enumerate() {
            if !curve.is_empty() {
                let series = if engine.is_reference(baseline.is_some()) { Series::dashed(&engine.label(), curve) } else { Series::line_points(&engine.label(), curve) };
                chart = chart.series(series.color(k));
            }
        }
        match std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display())).and_then(|_| chart.save(&dir.join(format!("bench_sizes_{stem}")))) {
            Ok(files) => println!("chart: {}", files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>().join(", ")),
            Err(e) => {
                eprintln!("dmhs bench: {e}");
                status = 1;
            }
        }
    }
    if baseline.is_some() {
        println!("ratio: particle-steps/s over the baseline build (base: --baseline) on as many cores");
    } else if !against.is_empty() {
        println!("ratio: particle-steps/s over the fastest reference engine on as many cores (LAMMPS: serial on 1; mpiexec -np N and -sf omp -pk omp N on N)");
        println!("peak MiB: the summed high-water resident memory of the engine's processes; bytes/part: that over the atoms");
    }
    status
}

/// Every engine on `deck`, `repeat` interleaved rounds; a failure is reported and sets `status`.
fn measure(deck: &Path, vars: &[(String, Vec<String>)], engines: &[Engine], repeat: usize, baseline: Option<&Path>, status: &mut i32) -> Rounds {
    let mut times: Rounds = vec![vec![]; engines.len()];
    for _ in 0..repeat {
        for (e, engine) in engines.iter().enumerate() {
            let t = engine.time(deck, vars, baseline);
            if let Err(msg) = &t {
                eprintln!("dmhs bench: {}", msg.trim_end());
                *status = 1;
            }
            times[e].push(t.ok());
        }
    }
    times
}

/// The table rows of one measured deck (`name` in the deck column).
fn print_rows(name: &str, engines: &[Engine], times: &Rounds, repeat: usize, with_baseline: bool) {
    let pss = |t: &Option<Timing>| t.as_ref().map(|t| t.particle_steps_per_second());
    // the fastest reference engine on `cores` cores: by medians, and in round r
    let best_median = |cores: usize| -> Option<f64> {
        engines.iter().zip(times).filter(|(e, _)| e.is_reference(with_baseline) && e.cores() == cores).filter_map(|(_, r)| {
            let ok: Vec<f64> = r.iter().filter_map(pss).collect();
            (!ok.is_empty()).then(|| median(ok))
        }).reduce(f64::max)
    };
    let best_in_round = |cores: usize, r: usize| -> Option<f64> {
        engines.iter().zip(times).filter(|(e, _)| e.is_reference(with_baseline) && e.cores() == cores).filter_map(|(_, t)| pss(&t[r])).reduce(f64::max)
    };
    for (engine, rounds) in engines.iter().zip(times) {
        let ok: Vec<&Timing> = rounds.iter().flatten().collect();
        let Some(first) = ok.first() else { continue };
        let seconds = median(ok.iter().map(|t| t.seconds).collect());
        let p = median(ok.iter().map(|t| t.particle_steps_per_second()).collect());
        let ratio = best_median(engine.cores()).map(|r| format!("{:.2}", p / r)).unwrap_or("-".into());
        let peak = ok.iter().filter_map(|t| t.peak_bytes).max();
        let mib = peak.map(|b| format!("{:.1}", b as f64 / 1048576.0)).unwrap_or("-".into());
        let per_particle = peak.map(|b| format!("{:.0}", b as f64 / first.atoms.max(1) as f64)).unwrap_or("-".into());
        let mut line = format!("{:<40} {:<12} {:>10} {:>8} {:>9.3} {:>14.4e} {:>8} {:>9} {:>10}", name, first.engine, first.atoms, first.steps, seconds, p, ratio, mib, per_particle);
        if repeat > 1 {
            let per_round: Vec<f64> = rounds.iter().enumerate().filter_map(|(r, t)| Some(pss(t)? / best_in_round(engine.cores(), r)?)).collect();
            let range = if per_round.is_empty() { "-".to_string() } else { format!("{:.2}-{:.2}", per_round.iter().copied().fold(f64::INFINITY, f64::min), per_round.iter().copied().fold(0.0, f64::max)) };
            line += &format!(" {range:>13}");
        }
        println!("{line}");
    }
}
