//! The `dmhs` command line: LAMMPS' habits (`-in`, `-var`, `-log`, `-screen`, `-echo`) plus
//! the subcommands run, check, crosscheck and bench. Exit codes: 0 ok, 2 deck error,
//! 1 any other failure.

use crate::deck::{run_file, DeckOptions};
use std::path::{Path, PathBuf};

/// The deck `dmhs` runs when given none.
pub const BUILTIN_EXAMPLE: &str = include_str!("../../examples/capsules/in.capsules");

pub const USAGE: &str = "\
dmhs: particle engine for solid-liquid flows (SPH + CGMD + DEM), reading LAMMPS input

usage:
  dmhs                              run the built-in example: elastic capsules carried by a
                                    channel flow past a post (SPH + bonds + contact, about 10 s;
                                    writes dmhs-example.*.png here)
  dmhs run DECK [options]           run an input deck
  dmhs -in DECK [options]           the same, LAMMPS style
  dmhs check DECK [options]         parse and build the deck without running; print the set-up
                                    (--ranks N, or under mpiexec: also the processor grid and
                                    the atoms each rank would own)
  mpiexec -np N dmhs -in DECK       run on N ranks (the build with --features mpi)
  dmhs crosscheck DECK [options]    run DECK in dmhs and in LAMMPS (twice: as written and with
                                    every coordinate nudged by one ulp); compare per-atom forces,
                                    positions, velocities at step 0, at steps 1, 2, 4, 8, ...
                                    and at the end, against LAMMPS' own round-off divergence
                                    (--against liggghts: in LIGGGHTS 3.8, for granular decks)
  dmhs capture DECK --out DIR       dmhs' step-0 forces and final state of DECK as the files
                                    lammps-refs/lammps_driver.py writes for LAMMPS
                                    (forces0.txt, final.txt: %.17g-exact, sorted by atom ID)
  dmhs bench --against lammps [--against liggghts] DECK... [options]
                                    particle-steps per second of dmhs and the reference engines
  dmhs validate CASE [--quick]      run an SPH validation case against its analytic reference:
                                    poiseuille, couette, heat, hydrostatic, dambreak, all
  dmhs validate chart               Poiseuille speed-versus-accuracy chart, dmhs and LAMMPS
                                    (speed_accuracy.png and .svg in --img DIR, default
                                    out/validate; --img docs/img updates the docs)
  dmhs validate convergence         kernel convergence of Poiseuille and Couette flow: Lucy,
                                    cubic, Wendland C2 at h/dx rising with N, 2.6, 3 and 4
                                    (convergence_*.png and .svg in --img DIR, default
                                    out/validate)
  dmhs plot FILE [--x COL] [--y COL1,COL2] [-o OUT.png|OUT.svg] [--title T] [--logy]
                                    line chart of columns of a thermo log (every run), a fix
                                    ave/time file or a column file with a header line

options:
  -var NAME VALUE...   define an index variable (as lmp -var; short form -v)
  -log FILE|none       log file (default log.dmhs)
  -screen none         no screen output
  -echo screen|log|both|none
  -threads N           worker threads (default: all cores, under mpiexec one per rank;
                       results do not depend on it)
  -h, -help            this help;  -version: the version of dmhs
  crosscheck: --force-tol X (default 1e-12, relative to the largest force in the run)
              --pos-tol X   (default 1e-9, relative to the box length)
              --vel-tol X   (default 1e-8, relative to the largest speed in the run)
              --curve FILE  also write the divergence table to FILE
  bench: --threads-list 1,2 (core counts: dmhs threads; LAMMPS serial on 1 core,
                        mpiexec -np N and -sf omp -pk omp N on N; default 1,2)
         --repeat N    (N interleaved rounds of all engines; medians and the
                        range of the per-round ratios; default 1)
         --ranks N     (also dmhs on N ranks of one thread, `dmhs Nr`: the
                        build with --features mpi, run by DMHS_MPIEXEC or mpiexec)
         --sizes NAME=V1,V2,...  (each deck once per value of its index variable
                        NAME, e.g. NX=32,100,316,1000; draws particle-steps/s
                        against particles for every engine into --img DIR,
                        default out/bench)
         --baseline PATH  (also another dmhs build, `base Nt` rows on the same
                        thread counts, interleaved; the ratios are taken against it)
  validate: --quick (the fast variants the tests run), --engine dmhs|lammps,
            --json FILE (default out/validate/CASE.json), --img DIR (also draw the charts)
";

#[derive(Debug, Default)]
struct Cli {
    sub: String,
    decks: Vec<PathBuf>,
    opts: DeckOptions,
    threads: Option<usize>,
    against: Vec<String>,
    force_tol: Option<f64>,
    pos_tol: Option<f64>,
    vel_tol: Option<f64>,
    threads_list: Option<Vec<usize>>,
    repeat: Option<usize>,
    ranks: Option<usize>,
    sizes: Option<(String, Vec<String>)>,
    baseline: Option<PathBuf>,
    quick: bool,
    engine: Option<String>,
    json: Option<PathBuf>,
    img: Option<PathBuf>,
    out: Option<PathBuf>,
    curve: Option<PathBuf>,
}

fn parse(args: &[String]) -> Result<Cli, String> {
    let mut c = Cli { opts: DeckOptions { screen: true, log: Some(PathBuf::from("log.dmhs")), ..Default::default() }, ..Default::default() };
    let mut i = 0;
    if let Some(first) = args.first() {
        if ["run", "check", "crosscheck", "capture", "bench", "validate", "help"].contains(&first.as_str()) {
            c.sub = first.clone();
            i = 1;
        }
    }
    let value = |i: usize, flag: &str| -> Result<&String, String> { args.get(i + 1).ok_or_else(|| format!("{flag} needs a value")) };
    let float = |s: &String, flag: &str| -> Result<f64, String> { s.parse::<f64>().map_err(|_| format!("{flag}: `{s}` is not a number")) };
    while i < args.len() {
        let a = args[i].as_str();
        match a {
            "-h" | "-help" | "--help" => {
                c.sub = "help".into();
                i += 1;
            }
            "-version" | "--version" => {
                c.sub = "version".into();
                i += 1;
            }
            "-in" | "-i" => {
                c.decks.push(PathBuf::from(value(i, a)?));
                if c.sub.is_empty() {
                    c.sub = "run".into();
                }
                i += 2;
            }
            "-var" | "-v" => {
                let name = value(i, a)?.clone();
                // the first value is taken whatever it starts with (`-var zlo -0.1`), the
                // others up to the next word starting with `-`, as LAMMPS reads them
                let Some(first) = args.get(i + 2) else {
                    return Err(format!("-var {name} needs at least one value"));
                };
                let mut vals = vec![first.clone()];
                let mut k = i + 3;
                while k < args.len() && !args[k].starts_with('-') {
                    vals.push(args[k].clone());
                    k += 1;
                }
                c.opts.vars.push((name, vals));
                i = k;
            }
            "-log" | "-l" => {
                let v = value(i, a)?;
                c.opts.log = if v == "none" { None } else { Some(PathBuf::from(v)) };
                i += 2;
            }
            "-screen" | "-sc" => {
                let v = value(i, a)?;
                if v != "none" {
                    return Err("-screen FILE is not supported (use -screen none, or redirect)".into());
                }
                c.opts.screen = false;
                i += 2;
            }
            "-echo" | "-e" => {
                c.opts.echo = Some(match value(i, a)?.as_str() {
                    "screen" => (true, false),
                    "log" => (false, true),
                    "both" => (true, true),
                    "none" => (false, false),
                    o => return Err(format!("-echo {o}: expected screen, log, both or none")),
                });
                i += 2;
            }
            "-nocite" | "-nc" => i += 1,
            "-threads" | "--threads" => {
                let v = value(i, a)?;
                c.threads = Some(v.parse().map_err(|_| format!("-threads: `{v}` is not a count"))?);
                i += 2;
            }
            "--against" => {
                c.against.push(value(i, a)?.clone());
                i += 2;
            }
            "--force-tol" => {
                c.force_tol = Some(float(value(i, a)?, a)?);
                i += 2;
            }
            "--pos-tol" => {
                c.pos_tol = Some(float(value(i, a)?, a)?);
                i += 2;
            }
            "--curve" => {
                c.curve = Some(PathBuf::from(value(i, a)?));
                i += 2;
            }
            "--vel-tol" => {
                c.vel_tol = Some(float(value(i, a)?, a)?);
                i += 2;
            }
            "--threads-list" => {
                let v = value(i, a)?;
                let list: Result<Vec<usize>, _> = v.split(',').map(|s| s.trim().parse::<usize>()).collect();
                c.threads_list = Some(list.map_err(|_| format!("--threads-list: `{v}` is not a list like 1,2"))?);
                i += 2;
            }
            "--repeat" => {
                let v = value(i, a)?;
                c.repeat = Some(v.parse::<usize>().ok().filter(|&n| n >= 1).ok_or_else(|| format!("--repeat: `{v}` is not a count of 1 or more"))?);
                i += 2;
            }
            "--ranks" => {
                let v = value(i, a)?;
                c.ranks = Some(v.parse::<usize>().ok().filter(|&n| n >= 1).ok_or_else(|| format!("--ranks: `{v}` is not a count of 1 or more"))?);
                i += 2;
            }
            "--sizes" => {
                let v = value(i, a)?;
                let (name, values) = v.split_once('=').ok_or_else(|| format!("--sizes: `{v}` is not NAME=V1,V2,... (an index variable of the deck and its values)"))?;
                let values: Vec<String> = values.split(',').map(|s| s.trim().to_string()).filter(|s| !s.is_empty()).collect();
                if name.is_empty() || values.is_empty() {
                    return Err(format!("--sizes: `{v}` is not NAME=V1,V2,... (an index variable of the deck and its values)"));
                }
                c.sizes = Some((name.to_string(), values));
                i += 2;
            }
            "--baseline" => {
                c.baseline = Some(PathBuf::from(value(i, a)?));
                i += 2;
            }
            "--quick" => {
                c.quick = true;
                i += 1;
            }
            "--engine" => {
                c.engine = Some(value(i, a)?.clone());
                i += 2;
            }
            "--json" => {
                c.json = Some(PathBuf::from(value(i, a)?));
                i += 2;
            }
            "--out" => {
                c.out = Some(PathBuf::from(value(i, a)?));
                i += 2;
            }
            "--img" => {
                c.img = Some(PathBuf::from(value(i, a)?));
                i += 2;
            }
            "-sf" | "-suffix" | "-pk" | "-package" | "-k" | "-kokkos" | "-partition" | "-p" | "-restart2data" | "-r2data" | "-restart2dump" | "-r2dump" | "-mpicolor" | "-skiprun" | "-sr" => {
                return Err(format!("LAMMPS option {a} is not supported by dmhs"));
            }
            _ if a.starts_with('-') => return Err(format!("unknown option {a} (see dmhs --help)")),
            _ => {
                c.decks.push(PathBuf::from(a));
                i += 1;
            }
        }
    }
    Ok(c)
}

/// The deck options and thread count of an `lmp`-style argument list (-var, -log, -screen none,
/// -echo, -threads, -nocite), as the Python module's `cmdargs` gives them (no deck, no sub-command).
pub fn lmp_options(args: &[String]) -> Result<(DeckOptions, Option<usize>), String> {
    let c = parse(args)?;
    if !c.sub.is_empty() || !c.decks.is_empty() {
        return Err(format!("cmdargs {args:?}: only -var, -log, -screen none, -echo, -threads and -nocite apply here (run a deck with file())"));
    }
    Ok((c.opts, c.threads))
}

/// Run the command line; returns the process exit code.
pub fn main_with_args(args: &[String]) -> i32 {
    // `plot` has options of its own
    if args.first().map(String::as_str) == Some("plot") {
        return crate::tools::plot_cmd::plot_cmd(&args[1..]);
    }
    let cli = match parse(args) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("dmhs: {e}");
            return 2;
        }
    };
    if cli.sub == "bench" {
        // the benchmark makes its own pool per thread count
        let threads = cli.threads_list.clone().unwrap_or(vec![1, 2]);
        let o = crate::tools::bench::BenchOptions {
            against: &cli.against,
            threads: &threads,
            repeat: cli.repeat.unwrap_or(1),
            ranks: cli.ranks,
            sizes: cli.sizes.as_ref(),
            img: cli.img.as_deref(),
            baseline: cli.baseline.as_deref(),
        };
        return crate::tools::bench::bench_cmd(&cli.decks, &cli.opts.vars, &o);
    }
    // The pool says how many threads (0: rayon's default, the cores or RAYON_NUM_THREADS) and
    // runs the command on one of its workers, whose stack is as large as a main thread's (for
    // deeply nested decks); sub-commands that run several decks at once spread them over it.
    // The loops of a run use the team made below (engine::par::team), not the pool.
    let pool = match rayon::ThreadPoolBuilder::new().num_threads(cli.threads.map(|n| n.max(1)).unwrap_or(0)).stack_size(8 << 20).build() {
        Ok(p) => p,
        Err(e) => {
            eprintln!("dmhs: could not start the worker threads: {e}");
            return 1;
        }
    };
    // under mpiexec (the `mpi` build) every rank runs the command, as a rank of the others
    // (MPI is finalized when the guard drops, at the end of this function)
    #[cfg(feature = "mpi")]
    let _mpi_guard = crate::engine::mpi_comm::Mpi::start().map(|(comm, universe)| {
        use crate::engine::comm::Comm;
        if comm.size() > 1 {
            let _ = RANKS.set(std::sync::Arc::new(comm));
        }
        universe
    });
    // the deck's team of threads: -threads N, or all cores; under mpiexec one per rank unless
    // -threads says otherwise (as LAMMPS runs one thread per MPI task), so ranks sharing a
    // machine's cores do not each spin a worker per core
    let team = match (cli.threads, ranks()) {
        (None, Some(_)) => 1,
        _ => pool.current_num_threads(),
    };
    pool.install(|| crate::engine::par::with_threads(team, || dispatch(&cli)))
}

/// The ranks this process runs with (`mpiexec` of the `mpi` build); unset: alone.
static RANKS: std::sync::OnceLock<std::sync::Arc<dyn crate::engine::comm::Comm>> = std::sync::OnceLock::new();

fn ranks() -> Option<std::sync::Arc<dyn crate::engine::comm::Comm>> {
    RANKS.get().cloned()
}

/// Rank 0 of several, or a process alone: it reports errors (the others ran the same deck).
fn reports() -> bool {
    ranks().map_or(true, |c| c.rank() == 0)
}

fn dispatch(cli: &Cli) -> i32 {
    match cli.sub.as_str() {
        "help" => {
            print!("{USAGE}");
            0
        }
        "version" => {
            println!("dmhs {}", env!("CARGO_PKG_VERSION"));
            0
        }
        "" | "run" => run_cmd(cli),
        "check" => check_cmd(cli),
        "crosscheck" => crate::tools::cli_crosscheck::crosscheck_cmd(&cli.decks, &cli.opts, &cli.against, [cli.force_tol, cli.pos_tol, cli.vel_tol], cli.curve.as_deref()),
        "capture" => crate::tools::cli_crosscheck::capture_cmd(&cli.decks, &cli.opts, cli.out.as_deref()),
        "validate" => crate::tools::validate::validate_cmd(&cli.decks, cli.quick, cli.engine.as_deref(), cli.json.as_deref(), cli.img.as_deref()),
        _ => unreachable!(),
    }
}

fn run_cmd(cli: &Cli) -> i32 {
    let result = match cli.decks.as_slice() {
        [] => crate::deck::run_text_on("<built-in example: examples/capsules/in.capsules>", BUILTIN_EXAMPLE, &cli.opts, ranks()),
        [deck] => crate::deck::run_file_on(deck, &cli.opts, ranks()),
        _ => {
            eprintln!("dmhs run: give one deck");
            return 2;
        }
    };
    match result {
        Ok(r) => r.quit.unwrap_or(0),
        Err(f) => {
            if reports() {
                eprint!("{}", f.rendered);
            }
            if f.runtime { 1 } else { 2 }
        }
    }
}

fn check_cmd(cli: &Cli) -> i32 {
    let [deck] = cli.decks.as_slice() else {
        eprintln!("dmhs check: give one deck");
        return 2;
    };
    let mut opts = cli.opts.clone();
    opts.check_only = true;
    opts.log = None;
    match run_file(deck, &opts) {
        Ok(r) => {
            let sources = r.interp.sources();
            // errors that only follow from a refused definition: one line each, not counted
            let notes: Vec<String> = r
                .follow_ons
                .iter()
                .map(|(d, cause)| {
                    let at = d.primary_span().map(|s| format!("{}: ", sources.location(s))).unwrap_or_default();
                    let line = sources.get(cause.file).map(|f| f.line_col(cause.lo).0).unwrap_or(0);
                    format!("note: {at}{} (follows from the error at line {line})\n", d.message)
                })
                .collect();
            if r.check_errors.is_empty() && notes.is_empty() {
                if !reports() {
                    return 0;
                }
                println!("\n{}", r.sim.describe());
                if let Some(n) = cli.ranks.or(ranks().map(|c| c.size())) {
                    print!("{}", r.sim.decomposition_plan(n));
                }
                println!("check: {} is valid", deck.display());
                return 0;
            }
            // the half-built set-up after errors would only mislead: errors and a count
            for d in &r.check_errors {
                eprint!("{}", d.render(sources));
            }
            eprint!("{}", notes.concat());
            let n = r.check_errors.len();
            eprintln!("{n} error{}", if n == 1 { "" } else { "s" });
            2
        }
        Err(f) => {
            eprint!("{}", f.rendered);
            let n = f.diagnostics.iter().filter(|d| d.is_error()).count().max(1);
            eprintln!("{n} error{}", if n == 1 { "" } else { "s" });
            2
        }
    }
}

/// Directory of a deck (relative paths inside it resolve there, as when LAMMPS runs in it).
pub fn deck_dir(deck: &Path) -> PathBuf {
    deck.parent().filter(|p| !p.as_os_str().is_empty()).map(Path::to_path_buf).unwrap_or_else(|| PathBuf::from("."))
}

#[cfg(test)]
mod tests {
    use super::parse;

    /// `-var NAME V1 V2 ...`: the first value whatever it starts with, the rest up to the next
    /// option (LAMMPS' reading of its command line).
    #[test]
    fn var_values_as_lammps_reads_them() {
        let args: Vec<String> = ["-var", "zlo", "-0.1", "-var", "style", "x", "1.0", "-log", "none", "-v", "n", "-5", "7"].iter().map(|s| s.to_string()).collect();
        let c = parse(&args).unwrap();
        let vars: Vec<(String, Vec<String>)> = c.opts.vars.clone();
        let want: Vec<(String, Vec<String>)> = vec![("zlo".into(), vec!["-0.1".into()]), ("style".into(), vec!["x".into(), "1.0".into()]), ("n".into(), vec!["-5".into(), "7".into()])];
        assert_eq!(vars, want);
        assert!(parse(&["-var".to_string(), "x".to_string()]).is_err());
    }
}
