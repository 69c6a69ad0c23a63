//! `minimize` against LAMMPS beyond the per-atom state that tests/lammps_parity.rs compares
//! after the following run: the thermo table of the minimization at every printed iteration
//! and its summary (stopping criterion, iterations, force evaluations, energies) for the
//! lammps-refs decks min_*, against lammps-refs/refs/NAME/thermo.txt (and LAMMPS run now, when
//! present). And the rules around it: velocities kept by the line-search styles, the time step
//! restored after fire, min_style resetting min_modify, refused fixes and located errors.

use dmhs::deck::{run_file, run_text, DeckOptions};
use std::path::{Path, PathBuf};

const DECKS: [&str; 12] = [
    "min_lj_cg",
    "min_chains_sd",
    "min_fire_2d",
    "min_cluster_cg",
    "min_cluster_walls",
    "min_indent_2d",
    "min_relax_2d",
    "min_relax_iso",
    "min_relax_aniso",
    "min_relax_tri",
    "min_relax_shear",
    "min_relax_tri2d",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The minimization's thermo table (names, rows) and its summary lines, from text that starts
/// at the minimization (a LAMMPS log cut at the `minimize` command, dmhs' screen text cut at
/// its "Setting up" line, or a stored thermo.txt whose summary lines start with "## ").
struct Table {
    names: Vec<String>,
    rows: Vec<Vec<f64>>,
    stats: Vec<String>,
}

fn parse(text: &str) -> Table {
    let lines: Vec<&str> = text.lines().map(|l| l.strip_prefix("## ").unwrap_or(l)).collect();
    let start = lines.iter().position(|l| l.trim_start().trim_start_matches("# ").starts_with("Step")).expect("a thermo header");
    let names = lines[start].trim_start().trim_start_matches("# ").split_whitespace().map(String::from).collect();
    let rows = lines[start + 1..].iter().map_while(|l| l.split_whitespace().map(|w| w.parse::<f64>().ok()).collect::<Option<Vec<f64>>>().filter(|r| !r.is_empty())).collect();
    let s = lines.iter().position(|l| l.starts_with("Minimization stats:")).expect("the minimization summary");
    let stats = lines[s..].iter().take_while(|l| !l.trim().is_empty()).map(|l| l.trim().to_string()).collect();
    Table { names, rows, stats }
}

fn dmhs_table(name: &str) -> Table {
    let deck = root().join("lammps-refs/decks").join(format!("in.{name}"));
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(deck.parent().unwrap().to_path_buf()), ..Default::default() };
    let run = run_file(&deck, &opts).unwrap_or_else(|f| panic!("{name}: {}", f.rendered));
    let text = run.sim.out.captured.clone().expect("captured screen text");
    let at = text.find("style minimization ...").expect("the minimization's setup line");
    parse(&text[at..])
}

/// A summary line's numbers after its `=`.
fn numbers(stats: &[String], key: &str) -> Vec<f64> {
    let k = stats.iter().position(|l| l.starts_with(key)).unwrap_or_else(|| panic!("no `{key}` in {stats:?}"));
    // the energies are on the line after their title
    let line = if stats[k].trim_end().ends_with('=') { &stats[k + 1] } else { stats[k].split('=').nth(1).unwrap() };
    line.split_whitespace().map(|w| w.parse().unwrap()).collect()
}

/// Every column at every printed iteration within 1e-7 of the column's largest magnitude;
/// the same stopping criterion, iterations and force evaluations; energies within 1e-10.
fn compare(name: &str, theirs: &Table) -> Option<String> {
    let ours = dmhs_table(name);
    assert_eq!(ours.names, theirs.names, "{name}: thermo columns");
    let mut bad = vec![];
    if ours.rows.len() != theirs.rows.len() {
        return Some(format!("{name}: {} thermo rows, LAMMPS {}", ours.rows.len(), theirs.rows.len()));
    }
    for (c, col) in theirs.names.iter().enumerate() {
        let scale = theirs.rows.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
        let worst = ours.rows.iter().zip(&theirs.rows).map(|(a, b)| (a[c] - b[c]).abs()).fold(0.0, f64::max);
        println!("{name}: {col}: max |dmhs - LAMMPS| {worst:.3e} (scale {scale:.3e})");
        if worst > 1e-7 * scale {
            bad.push(format!("{name}: {col} differs by {worst:e} (scale {scale:e})"));
        }
    }
    for key in ["Stopping criterion", "Iterations, force evaluations"] {
        let (a, b) = (ours.stats.iter().find(|l| l.starts_with(key)), theirs.stats.iter().find(|l| l.starts_with(key)));
        if a != b || a.is_none() {
            bad.push(format!("{name}: dmhs `{a:?}`, LAMMPS `{b:?}`"));
        }
    }
    let (a, b) = (numbers(&ours.stats, "Energy initial"), numbers(&theirs.stats, "Energy initial"));
    println!("{name}: energies {a:?}, LAMMPS {b:?}");
    if a.len() != 3 || a.iter().zip(&b).any(|(x, y)| (x - y).abs() > 1e-10 * y.abs()) {
        bad.push(format!("{name}: energies initial, next-to-last, final {a:?}, LAMMPS {b:?}"));
    }
    (!bad.is_empty()).then(|| bad.join("\n"))
}

fn check_all(live: bool) {
    let mut bad = vec![];
    for name in DECKS {
        let theirs = if live {
            let deck = root().join("lammps-refs/decks").join(format!("in.{name}"));
            let tmp = tempfile::tempdir().unwrap();
            dmhs::tools::lammps::run_driver(&deck, &[], tmp.path()).unwrap();
            let log = std::fs::read_to_string(tmp.path().join("log.lammps")).unwrap();
            let at = log.lines().scan(0, |pos, l| {
                let here = *pos;
                *pos += l.len() + 1;
                Some((here, l))
            });
            let start = at.filter(|(_, l)| l.starts_with("minimize ")).map(|(p, _)| p).next().expect("the minimize command in the log");
            parse(&log[start..])
        } else {
            parse(&std::fs::read_to_string(root().join("lammps-refs/refs").join(name).join("thermo.txt")).unwrap())
        };
        bad.extend(compare(name, &theirs));
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn stored_minimization_tables() {
    check_all(false);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn live_minimization_tables() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    check_all(true);
}

const BASE: &str = "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\n\
    create_atoms 1 box\nmass 1 1.0\ndisplace_atoms all random 0.05 0.05 0.05 4871 units box\npair_style lj/cut 2.5\n\
    pair_coeff 1 1 1.0 1.0 2.5\nthermo 0\n";

fn run(deck: &str) -> dmhs::deck::DeckRun {
    run_text("in.test", deck, &DeckOptions { screen: false, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered))
}

/// cg and sd move the atoms only: velocities are as they were (LAMMPS); fire sets its own and
/// the time step it changed is restored; the step counter advances by the iterations.
#[test]
fn velocities_time_step_and_step_counter() {
    let r = run(&format!("{BASE}velocity all create 1.0 5531 loop all\nminimize 0.0 0.0 15 100\n"));
    assert_eq!(r.sim.state.step, 15);
    assert!(r.sim.state.atoms.v.iter().any(|v| v[0] != 0.0));
    let r2 = run(&format!("{BASE}velocity all create 1.0 5531 loop all\n"));
    let by_tag = |s: &dmhs::sim::Simulation| {
        let a = &s.state.atoms;
        let mut v: Vec<(i64, [f64; 3])> = (0..a.nlocal).map(|i| (a.tag[i] as i64, a.v[i])).collect();
        v.sort_by_key(|p| p.0);
        v
    };
    assert_eq!(by_tag(&r.sim), by_tag(&r2.sim), "cg changed velocities");
    let stats = r.sim.min_stats.expect("minimization stats");
    assert_eq!((stats.niter, stats.stop), (15, dmhs::sim::minimize::Stop::MaxIter));
    assert!(stats.efinal < stats.einitial);

    let r = run(&format!("{BASE}timestep 0.004\nmin_style fire\nmin_modify tmax 4.0 delaystep 1 initialdelay no\nminimize 0.0 0.0 30 100\n"));
    assert_eq!(r.sim.state.dt, 0.004, "the time step after fire");
    assert!(r.sim.state.atoms.v.iter().any(|v| v[0] != 0.0), "fire leaves its velocities");
}

/// `min_modify norm max` with fix box/relax: LAMMPS' fnorm_max reads every third extra degree
/// of freedom only (fextra[0], [3], ...). On this perfect crystal with a y target far off, LAMMPS
/// 22 Jul 2025 stops on the force tolerance after 111 iterations (its energies within 3e-14 of
/// these); reading all three box forces, dmhs took 350.
#[test]
fn norm_max_reads_every_third_extra_dof() {
    let deck = "units lj\nlattice fcc 0.8442\nregion box block 0 5 0 5 0 5\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\npair_modify shift yes\nthermo 0\n\
                fix 3 all box/relax x 0.0 y 3.0 z 0.0 vmax 1.0e-3\nmin_modify norm max\nminimize 0.0 10.0 2000 100000\n";
    let stats = run(deck).sim.min_stats.expect("minimization stats");
    assert_eq!((stats.stop, stats.niter, stats.neval), (dmhs::sim::minimize::Stop::Ftol, 111, 111));
    assert!((stats.efinal - -7.79405051988021).abs() < 1e-12, "{}", stats.efinal);
}

/// min_style makes a new minimizer: min_modify settings go back to LAMMPS' defaults.
#[test]
fn min_style_resets_min_modify() {
    let r = run(&format!("{BASE}min_modify dmax 0.01 line backtrack norm inf\nmin_style sd\n"));
    let m = &r.sim.min;
    assert_eq!((m.dmax, m.line, m.norm, m.style), (0.1, dmhs::sim::minimize::LineSearch::Quadratic, dmhs::sim::minimize::Norm::Two, dmhs::sim::minimize::MinStyle::Sd));
}

/// Bad input is a located error naming what is wrong; fixes LAMMPS would apply while
/// minimizing and dmhs does not are refused; fix box/relax's settings are checked as LAMMPS
/// checks them.
#[test]
fn bad_input_is_a_located_error() {
    let n = BASE.lines().count() + 1;
    let cases = [
        ("min_style hftn\n", "hftn"),
        ("min_style cgg\n", "cgg"),
        ("min_modify dmax\n", "dmax"),
        ("min_modify bogus 1\n", "unknown keyword `bogus`"),
        ("min_modify line forcezero\n", "forcezero"),
        ("min_modify norm three\n", "three"),
        ("min_modify integrator rk4\n", "rk4"),
        ("min_modify abcfire yes\n", "abcfire"),
        ("min_modify\n", "missing a keyword"),
        ("minimize 1e-4 1e-6 100\n", "maxeval"),
        ("minimize 1e-4 1e-6 100 1000 5\n", "unexpected argument"),
        ("minimize -1 1e-6 100 1000\n", "etol"),
        ("minimize 0 0 ten 1000\n", "maxiter"),
        ("fix a all gravity 1.0 vector 0 0 -1\nminimize 0 0 10 100\n", "gravity"),
        ("variable f equal 1.0\nfix a all addforce v_f 0.0 0.0\nminimize 0 0 10 100\n", "variable force"),
        ("fix a all setforce 1.0 0.0 0.0\nminimize 0 0 10 100\n", "non-zero forces"),
        ("min_style fire\nmin_modify dtgrow 0.9\nminimize 0 0 10 100\n", "dtgrow"),
        ("fix b all box/relax\n", "missing a pressure keyword"),
        ("fix b all box/relax iso\n", "missing iso pressure"),
        ("fix b all box/relax iso 1.0 vmax 0\n", "vmax must be > 0"),
        ("fix b all box/relax iso 1.0 nreset -1\n", "nreset"),
        ("fix b all box/relax iso 1.0 bogus 2\n", "unknown keyword `bogus`"),
        ("fix b all box/relax iso 1.0 dilate some\n", "some"),
        ("fix b all box/relax tri 1.0\n", "Pxy/Pxz/Pyz in fix box/relax with a non-triclinic box"),
        ("fix b all box/relax x 1.0 xy 0.5\n", "Pxy/Pxz/Pyz in fix box/relax with a non-triclinic box"),
        ("fix b all box/relax x 1.0 couple xyz\n", "pressure settings"),
        ("fix b all box/relax x 1.0 y 2.0 z 3.0 couple xy\n", "same target pressure"),
        ("fix b all box/relax iso 1.0\nmin_style fire\nminimize 0 0 10 100\n", "damped dynamics"),
    ];
    for (extra, want) in cases {
        let deck = format!("{BASE}{extra}");
        let f = run_text("bad.deck", &deck, &DeckOptions { screen: false, ..Default::default() }).err().unwrap_or_else(|| panic!("accepted: {extra}"));
        let last = n + extra.lines().count() - 1;
        assert!(f.rendered.contains(&format!("bad.deck:{last}:")) && f.rendered.contains(want), "{extra}: {}", f.rendered);
    }
}

/// The refs of the min_* decks exist (regenerate.sh writes thermo.txt for them).
#[test]
fn refs_exist() {
    for name in DECKS {
        assert!(Path::new(&root().join("lammps-refs/refs").join(name).join("thermo.txt")).exists(), "{name}: run lammps-refs/regenerate.sh {name}");
    }
}
