//! The `dmhs` command line: exit codes (0 ok, 2 deck error, 1 other failure), located errors,
//! LAMMPS-style options, check, the built-in example.

use std::path::PathBuf;
use std::process::{Command, Output};

fn dmhs(args: &[&str], dir: &std::path::Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dmhs")).args(args).current_dir(dir).output().unwrap()
}

fn text(o: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

fn decks() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks")
}

#[test]
fn runs_a_deck_with_lammps_options() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = decks().join("in.small_lj");
    let o = dmhs(&["-in", deck.to_str().unwrap(), "-var", "nsteps", "20", "-log", "run.log", "-echo", "screen"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("Loop time of") && t.contains("for 20 steps with 256 atoms"), "{t}");
    assert!(t.contains("final temperature "), "{t}");
    assert!(t.contains("run          20"), "echo screen shows substituted commands:\n{t}");
    let log = std::fs::read_to_string(tmp.path().join("run.log")).unwrap();
    assert!(log.contains("Per MPI rank memory allocation") && log.contains("Loop time of"));
}

#[test]
fn screen_none_is_quiet() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = decks().join("in.small_lj");
    let o = dmhs(&["run", deck.to_str().unwrap(), "-screen", "none", "-log", "none"], tmp.path());
    assert_eq!(o.status.code(), Some(0));
    assert!(o.stdout.is_empty(), "{}", text(&o));
    assert!(!tmp.path().join("log.dmhs").exists());
}

#[test]
fn deck_errors_are_located_and_exit_2() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = decks().join("in.errors");
    let o = dmhs(&["run", deck.to_str().unwrap(), "-log", "none"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains("error: expected a number for sigma, found `abc`"), "{t}");
    assert!(t.contains("in.errors:9:22"), "{t}");
    assert!(t.contains("^^^"), "{t}");
    assert!(t.contains("help: syntax: pair_coeff I J epsilon sigma [Rc]"), "{t}");
}

#[test]
fn a_failed_run_exits_1_and_names_the_atom() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = decks().join("in.lost_atoms");
    let o = dmhs(&["run", deck.to_str().unwrap(), "-log", "out.log"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(1), "{t}");
    assert!(t.contains("lost atoms") && t.contains("left the box through a fixed boundary"), "{t}");
    // what was written before the failure is kept
    let log = std::fs::read_to_string(tmp.path().join("out.log")).unwrap();
    assert!(log.contains("Step"), "{log}");
}

#[test]
fn check_prints_the_setup_without_running() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = decks().join("in.small_lj");
    let o = dmhs(&["check", deck.to_str().unwrap()], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("atoms: 256 of 1 types") && t.contains("pair lj/cut 2.5") && t.contains("fix 1 nve"), "{t}");
    assert!(!t.contains("Loop time"), "{t}");
}

/// `dmhs check` opens no output file: fix print, the fix ave/* files, print, log, write_data,
/// write_restart and write_dump are checked but write nothing.
#[test]
fn check_writes_no_files() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = "units lj\nlattice fcc 0.8442\nregion b block 0 3 0 3 0 3\ncreate_box 1 b\ncreate_atoms 1 box\nmass 1 1\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1 1\nfix 1 all nve\ncompute t all temp\n\
                fix a all ave/time 10 1 10 c_t file avet.txt\nfix h all ave/histo 10 1 10 0 1 10 c_t file hist.txt\n\
                fix pr all print 10 \"hi\" file pr.txt\nprint \"x\" file p.txt\nprint \"y\" append pa.txt\nlog lg.txt\n\
                write_data w.data\nwrite_restart r.rst\nwrite_dump all atom wd.dump\ndump d all atom 10 d.dump\nrun 20\n";
    std::fs::write(tmp.path().join("in.deck"), deck).unwrap();
    let o = dmhs(&["check", "in.deck"], tmp.path());
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let files: Vec<String> = std::fs::read_dir(tmp.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    assert_eq!(files, ["in.deck"], "dmhs check wrote files");
}

#[test]
fn check_reports_several_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = tmp.path().join("in.bad");
    std::fs::write(&deck, "units lj\natom_style atomic\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\nmass 1 -1.0\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0\nfix 1 all shake 0.0001 20 0 b 1\n").unwrap();
    let o = dmhs(&["check", "in.bad"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains("in.bad:5:8") && t.contains("mass must be > 0"), "{t}");
    assert!(t.contains("in.bad:8:11") && t.contains("fix style `shake` is a LAMMPS style that dmhs does not support"), "{t}");
}

/// The built-in example (examples/capsules/in.capsules), shortened: it says what it is, runs
/// the three models, prints its summary and leaves its pictures.
#[test]
fn builtin_example_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let o = dmhs(&["-var", "nsteps", "20"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("DMHS example: 1496 SPH fluid particles, 512 wall/post particles"), "{t}");
    assert!(t.contains("three bonded capsules (72 particles, 195 bonds)"), "{t}");
    assert!(t.contains("for 20 steps with 2080 atoms"), "{t}");
    for model in ["pair sph/taitwater/morris (1-1 1-2)", "pair lj/cut (1-3)", "pair granular (2-3 3-3)", "bond harmonic"] {
        assert!(t.contains(model), "{model}: {t}");
    }
    assert!(t.contains("Summary after 0.02 time units"), "{t}");
    for f in ["log.dmhs", "dmhs-example.0.png", "dmhs-example.20.png"] {
        assert!(tmp.path().join(f).exists(), "{f}");
    }
}

#[test]
fn unknown_option_is_a_usage_error() {
    let tmp = tempfile::tempdir().unwrap();
    let o = dmhs(&["-sf", "omp"], tmp.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("LAMMPS option -sf is not supported"));
}

/// `dmhs check` names each active model with its type pairs and its time-step limit; a run
/// prints each model's share of the loop time after the stage breakdown.
#[test]
fn check_and_run_report_the_active_models() {
    let tmp = tempfile::tempdir().unwrap();
    let refs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks");
    // decks read their data files from the working directory, as in LAMMPS
    for f in ["in.sph_overlay_2d", "sph_island_2d.data", "in.gran_clumps_history", "gran_clumps.data"] {
        std::fs::copy(refs.join(f), tmp.path().join(f)).unwrap();
    }
    let overlay = tmp.path().join("in.sph_overlay_2d");
    let o = dmhs(&["check", overlay.to_str().unwrap()], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("sph/taitwater/morris (kernel lucy) [type pairs 1-1 1-2 2-2]"), "{t}");
    assert!(t.contains("lj/cut 0.5 [type pairs 1-2]"), "{t}");
    assert!(t.contains("SPH            acoustic CFL"), "{t}");

    let o = dmhs(&["run", overlay.to_str().unwrap(), "-log", "none"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    let table = t.split("Model timing breakdown:").nth(1).expect("model table");
    for row in ["pair sph/taitwater/morris (1-1 1-2 2-2)", "pair sph/heatconduction (1-1 1-2 2-2)", "pair lj/cut (1-2)", "fix 1 sph", "fix 2 enforce2d"] {
        assert!(table.contains(row), "missing `{row}` in\n{table}");
    }

    let clumps = tmp.path().join("in.gran_clumps_history");
    let o = dmhs(&["check", clumps.to_str().unwrap()], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    // k_n 20000 and the lightest particle: t_c/10 = pi sqrt(m/2 / k_n)/10
    assert!(t.contains("DEM contact    t_c/10") && t.contains("dt <= 9.7047e-4"), "{t}");
    assert!(t.contains("bond harmonic  T/20"), "{t}");
}

/// `dmhs bench --repeat 2 --threads-list 1,2` against LAMMPS: one row per engine (LAMMPS serial,
/// `mpiexec -np 2`, `-sf omp -pk omp 2`, dmhs on 1 and 2 threads) with the median of two
/// interleaved rounds, a ratio to the fastest LAMMPS on as many cores, the peak memory, and the
/// range of the per-round ratios.
#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn bench_repeats_rounds_and_reports_medians() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let deck = decks().join("in.small_lj");
    let o = dmhs(&["bench", "--against", "lammps", "--repeat", "2", "--threads-list", "1,2", deck.to_str().unwrap(), "-var", "nsteps", "200"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    let rows: Vec<Vec<&str>> = t.lines().filter(|l| l.contains("in.small_lj")).map(|l| l.split_whitespace().collect()).collect();
    // deck, engine (2 words), atoms, steps, seconds, particle-st/s, ratio, peak MiB, bytes/part, round ratios
    let engines: Vec<String> = rows.iter().map(|r| r[1..3].join(" ")).collect();
    assert_eq!(engines, ["lammps 1t", "lammps np2", "lammps omp2", "dmhs 1t", "dmhs 2t"], "{t}");
    for r in &rows {
        assert_eq!(r[3], "256", "{t}");
        assert_eq!(r[4], "200", "{t}");
        assert!(r[5].parse::<f64>().unwrap() > 0.0, "{t}");
        // a process of a few MiB at least, and per particle that over 256 atoms (MiB printed
        // to 0.1)
        let mib: f64 = r[8].parse().unwrap();
        // (a 20 ms process was once sampled at 0.7 MiB on a loaded machine, when the sampling
        // was every 50 ms; now every 2 ms in a run's first second: dmhs alone is 7 MiB)
        assert!(mib > 2.0 && mib < 4096.0, "{t}");
        assert!((r[9].parse::<f64>().unwrap() - mib * 1048576.0 / 256.0).abs() <= 0.05 * 1048576.0 / 256.0 + 1.0, "{t}");
    }
    assert_eq!(rows[0][7], "1.00", "the only 1-core reference:\n{t}");
    assert_eq!(rows[0][10], "1.00-1.00", "{t}");
    // of the two 2-core LAMMPS runs, the faster is the reference
    let two: Vec<f64> = rows[1..3].iter().map(|r| r[7].parse().unwrap()).collect();
    assert!(two.iter().any(|&x| x == 1.0) && two.iter().all(|&x| x <= 1.0), "{t}");
    for r in &rows[3..] {
        let ratio: f64 = r[7].parse().unwrap();
        let (lo, hi) = r[10].split_once('-').map(|(a, b)| (a.parse::<f64>().unwrap(), b.parse::<f64>().unwrap())).unwrap();
        // the ratio of medians lies near the per-round ratios (to the printed digits; the
        // reference of a round may be another LAMMPS configuration than that of the medians,
        // and on a loaded machine two rounds can differ by tens of percent; the test failed once
        // with the bounds 0.8-1.25, right after a build)
        assert!(lo > 0.0 && lo * 0.5 - 0.01 <= ratio && ratio <= hi * 2.0 + 0.01, "{t}");
    }
}

/// `dmhs bench --sizes NAME=V1,V2`: the deck once per value of its index variable (a `-var` of
/// the same name gives way), a row per engine and size, and the chart of particle-steps/s
/// against particles in --img.
#[test]
fn bench_runs_a_deck_at_each_size_and_draws_the_chart() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = tmp.path().join("in.sized");
    let lj = std::fs::read_to_string(decks().join("in.small_lj")).unwrap();
    std::fs::write(&deck, format!("variable n index 4\n{}", lj.replace("block 0 4 0 4 0 4", "block 0 ${n} 0 ${n} 0 ${n}"))).unwrap();
    let img = tmp.path().join("img");
    let o = dmhs(&["bench", "--threads-list", "1,2", "--sizes", "n=2,3", "-var", "n", "9", "-var", "nsteps", "20", "--img", img.to_str().unwrap(), deck.to_str().unwrap()], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    let rows: Vec<Vec<&str>> = t.lines().filter(|l| l.contains("in.sized n=")).map(|l| l.split_whitespace().collect()).collect();
    // deck, size, engine (2 words), atoms, steps, ...: fcc has 4 atoms per cell
    let got: Vec<String> = rows.iter().map(|r| format!("{} {} {} {}", r[1], r[2], r[3], r[4])).collect();
    assert_eq!(got, ["n=2 dmhs 1t 32", "n=2 dmhs 2t 32", "n=3 dmhs 1t 108", "n=3 dmhs 2t 108"], "{t}");
    for ext in ["png", "svg"] {
        assert!(img.join(format!("bench_sizes_in_sized.{ext}")).is_file(), "{t}");
    }
    let o = dmhs(&["bench", "--sizes", "n", deck.to_str().unwrap()], tmp.path());
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--sizes: `n` is not NAME=V1,V2,..."), "{}", text(&o));
}

/// `dmhs bench --baseline PATH`: another dmhs build on the same thread counts, interleaved, and
/// the ratios taken against it (here the same executable: the baseline's own ratio is 1).
#[test]
fn bench_compares_against_a_baseline_build() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = decks().join("in.small_lj");
    let o = dmhs(&["bench", "--baseline", env!("CARGO_BIN_EXE_dmhs"), "--threads-list", "1", "--repeat", "2", deck.to_str().unwrap(), "-var", "nsteps", "20"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    let rows: Vec<Vec<&str>> = t.lines().filter(|l| l.contains("in.small_lj")).map(|l| l.split_whitespace().collect()).collect();
    let engines: Vec<String> = rows.iter().map(|r| r[1..3].join(" ")).collect();
    assert_eq!(engines, ["base 1t", "dmhs 1t"], "{t}");
    assert_eq!((rows[0][7], rows[0][10]), ("1.00", "1.00-1.00"), "{t}");
    assert!(rows[1][7].parse::<f64>().unwrap() > 0.0, "{t}");
    assert!(t.contains("ratio: particle-steps/s over the baseline build"), "{t}");
    let o = dmhs(&["bench", "--baseline", "no/such/dmhs", deck.to_str().unwrap()], tmp.path());
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--baseline no/such/dmhs: no such file"), "{}", text(&o));
}

#[test]
fn bench_rejects_a_bad_repeat_count() {
    let o = dmhs(&["bench", "--against", "lammps", "--repeat", "0", "x"], &decks());
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--repeat: `0` is not a count of 1 or more"), "{}", text(&o));
}

/// The stage breakdown covers the loop only (LAMMPS starts its timers after setup), so its
/// shares add up to at most 100%: a one-step run spends as long in setup as in its loop.
#[test]
fn timing_breakdown_adds_up_to_the_loop() {
    let tmp = tempfile::tempdir().unwrap();
    let deck = decks().join("in.small_lj");
    let o = dmhs(&["-in", deck.to_str().unwrap(), "-var", "nsteps", "1", "-log", "none"], tmp.path());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    let table = t.split("MPI task timing breakdown:").nth(1).expect("a breakdown");
    let mut sum = 0.0;
    for name in ["Pair", "Bond", "Neigh", "Comm", "Output", "Modify", "Other"] {
        let line = table.lines().find(|l| l.starts_with(name)).unwrap_or_else(|| panic!("no {name} row:\n{table}"));
        sum += line.rsplit('|').next().unwrap().trim().parse::<f64>().unwrap();
    }
    // each share is printed to 0.01
    assert!(sum <= 100.1, "stage shares add up to {sum}%:\n{table}");
}
