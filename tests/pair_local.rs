//! compute pair/local against LAMMPS: the dump local files of the lammps-refs decks
//! pair_local_chains (lj/cut + soft under hybrid/overlay, special weights, a group),
//! pair_local_gran (pair granular hertz/material, mindlin, rolling, twisting: p1..p12, `cutoff
//! radius` and the type cutoff) and pair_local_hertz (gran/hertz/history: p1..p10, every 100
//! steps), from lammps-refs/refs/NAME/local.* or LAMMPS run now. Each row carries the pair's atom
//! IDs (compute property/local in the same dump); rows are matched by pair, a row LAMMPS lists
//! from the other atom turned round (the columns that change sign with the pair negated), and
//! every column compared relative to its largest value. And the located errors.

mod common;
use dmhs::deck::{run_file, DeckOptions};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn deck(name: &str) -> PathBuf {
    root().join("lammps-refs/decks").join(format!("in.{name}"))
}

/// A dump file of a deck and the value columns (from 1, after index and the two IDs) that
/// change sign when the pair is turned round: dx dy dz, fx fy fz, the tangential force and
/// x_i - x_j of pair granular, the tangential force and relative velocities of the classic
/// styles.
const FILES: [(&str, &str, &[usize]); 4] = [
    ("pair_local_chains", "pairs", &[2, 3, 4, 7, 8, 9]),
    ("pair_local_gran", "pairs", &[2, 3, 4, 5, 6, 7, 14, 15, 16]),
    ("pair_local_gran", "cut", &[]),
    ("pair_local_hertz", "pairs", &[2, 3, 4, 6, 7, 8, 10, 11, 12, 13, 14, 15]),
];

/// Largest column difference relative to the column's largest |value| (the LAMMPS run's
/// round-off growth over 100-300 steps: at most 3.4e-11 measured).
const TOLERANCE: f64 = 1e-10;

type Rows = BTreeMap<(i64, i64), Vec<f64>>;

/// The snapshots of a dump local file (`index c_ids[1] c_ids[2] values...`): step -> rows by
/// pair (lower ID first).
fn snapshots(text: &str, turned: &[usize]) -> BTreeMap<i64, Rows> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = BTreeMap::new();
    let mut k = 0;
    while k < lines.len() {
        if !lines[k].starts_with("ITEM: TIMESTEP") {
            k += 1;
            continue;
        }
        let step: i64 = lines[k + 1].trim().parse().unwrap();
        let n: usize = lines[k + 3].trim().parse().unwrap();
        let mut rows = Rows::new();
        for l in &lines[k + 9..k + 9 + n] {
            let w: Vec<&str> = l.split_whitespace().collect();
            let (i, j): (i64, i64) = (w[1].parse().unwrap(), w[2].parse().unwrap());
            let mut v: Vec<f64> = w[3..].iter().map(|x| x.parse().unwrap()).collect();
            if i > j {
                for &c in turned {
                    v[c - 1] = -v[c - 1];
                }
            }
            assert!(rows.insert((i.min(j), i.max(j)), v).is_none(), "pair {i} {j} listed twice");
        }
        out.insert(step, rows);
        k += 9 + n;
    }
    out
}

/// The dump files deck `name` writes (the suffixes of its `SUFFIXfile` variables).
fn suffixes(name: &str) -> Vec<&'static str> {
    FILES.iter().filter(|f| f.0 == name).map(|f| f.1).collect()
}

/// dmhs on deck `name` with its dump files under `dir/local.*`.
fn dmhs_run(name: &str, dir: &Path) {
    common::run_with_local_files(&deck(name), &suffixes(name), dir);
}

/// Every file: the same steps, the same pairs, every column within [`TOLERANCE`]; the step-0
/// snapshots (the same positions in both) equal to the last bit.
fn check(reference: impl Fn(&str) -> PathBuf) {
    let mut bad = vec![];
    for name in ["pair_local_chains", "pair_local_gran", "pair_local_hertz"] {
        let tmp = tempfile::tempdir().unwrap();
        dmhs_run(name, tmp.path());
        for (_, suffix, turned) in FILES.iter().filter(|f| f.0 == name) {
            let theirs = snapshots(&std::fs::read_to_string(reference(name).join(format!("local.{suffix}"))).unwrap(), turned);
            let ours = snapshots(&std::fs::read_to_string(tmp.path().join(format!("local.{suffix}"))).unwrap(), turned);
            assert_eq!(ours.keys().collect::<Vec<_>>(), theirs.keys().collect::<Vec<_>>(), "{name}.{suffix}: steps");
            for (step, t) in &theirs {
                let o = &ours[step];
                assert!(t.len() >= 50, "{name}.{suffix}: too few rows to test anything");
                if t.keys().ne(o.keys()) {
                    bad.push(format!("{name}.{suffix} step {step}: {} pairs against LAMMPS' {}", o.len(), t.len()));
                    continue;
                }
                let ncol = t.values().next().unwrap().len();
                let worst: Vec<f64> = (0..ncol)
                    .map(|c| {
                        let scale = t.values().map(|v| v[c].abs()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
                        t.iter().map(|(k, v)| (v[c] - o[k][c]).abs()).fold(0.0, f64::max) / scale
                    })
                    .collect();
                println!("{name}.{suffix} step {step}: {} pairs, largest difference per column {}", t.len(), worst.iter().map(|w| format!("{w:.1e}")).collect::<Vec<_>>().join(" "));
                let limit = if *step == 0 { 0.0 } else { TOLERANCE };
                if let Some(c) = worst.iter().position(|&w| w > limit) {
                    bad.push(format!("{name}.{suffix} step {step}: column {} differs by {:.1e} of its largest value", c + 1, worst[c]));
                }
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn stored_pair_rows() {
    check(|name| root().join("lammps-refs/refs").join(name));
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn live_pair_rows() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    for name in ["pair_local_chains", "pair_local_gran", "pair_local_hertz"] {
        let out = tmp.path().join(name);
        std::fs::create_dir_all(&out).unwrap();
        dmhs::tools::lammps::run_driver(&deck(name), &common::local_file_vars(&suffixes(name), &out), &out).unwrap();
    }
    check(|name| tmp.path().join(name));
}

/// `deck` with `line` replaced by `to`, in a scratch folder beside the data file it reads.
fn edited(name: &str, edits: &[(&str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let mut text = std::fs::read_to_string(deck(name)).unwrap();
    for (line, to) in edits {
        let was = text.clone();
        text = text.replacen(line, to, 1);
        assert_ne!(text, was, "{line}");
    }
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("in.pl");
    std::fs::write(&path, &text).unwrap();
    std::fs::copy(root().join("lammps-refs/decks/chains_periodic_full.data"), tmp.path().join("chains_periodic_full.data")).unwrap();
    (tmp, path)
}

/// Bad compute pair/local commands are located errors (`dmhs check`).
#[test]
fn pair_local_errors_are_located() {
    let line = "compute      pl rest pair/local dist dx dy dz eng force fx fy fz";
    for (to, want) in [
        ("compute pl rest pair/local", "a value"),
        ("compute pl rest pair/local energy", "Invalid keyword `energy`"),
        ("compute pl rest pair/local p0", "pN needs N >= 1"),
        ("compute pl rest pair/local dist sphere", "sphere"),
        ("compute pl rest pair/local dist cutoff sphere", "cutoff"),
        ("compute pl rest pair/local dist cutoff radius", "requires atom attribute radius"),
    ] {
        let (tmp, path) = edited("pair_local_chains", &[(line, to)]);
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_dmhs")).arg("check").arg(&path).current_dir(tmp.path()).output().unwrap();
        let out = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
        assert_eq!(o.status.code(), Some(2), "{to}: {out}");
        assert!(out.contains(want) && out.contains("in.pl:"), "{to}: expected `{want}`:\n{out}");
    }
}

/// What the pair style cannot give stops the run with LAMMPS' reason: an extra value it does not
/// have, a style without single.
#[test]
fn pair_local_refusals_at_run_time() {
    let hertz = "pair_style   gran/hertz/history 2e4 NULL 50.0 NULL 0.4 1";
    for (name, edits, want) in [
        ("pair_local_hertz", vec![("p9 p10 cutoff radius", "p9 p10 p11 cutoff radius")], "does not have extra field requested by compute pair/local (p11; pair style gran/hertz/history has 10)"),
        (
            "pair_local_chains",
            vec![("compute      pl rest pair/local dist dx dy dz eng force fx fy fz", "compute pl rest pair/local dist p1"), ("c_pl[5]", "c_pl[2]")],
            "(p1; pair style hybrid/overlay has 0)",
        ),
        ("pair_local_hertz", vec![(hertz, "pair_style gran/hooke 2e4 NULL 50.0 NULL 0.4 1")], "Pair style gran/hooke does not support compute pair/local"),
    ] {
        let (tmp, path) = edited(name, &edits);
        let opts = DeckOptions { screen: false, base_dir: Some(tmp.path().to_path_buf()), ..Default::default() };
        let err = match run_file(&path, &opts) {
            Ok(_) => panic!("{name}: {edits:?} ran"),
            Err(f) => f.rendered,
        };
        assert!(err.contains(want), "{name}: expected `{want}`:\n{err}");
    }
}

/// compute pair/local read inside a fix's hook (fix ave/histo `kind local`, every 10 steps) and
/// by compute reduce in thermo: LAMMPS 22 Jul 2025's numbers on the same deck (the smallest pair
/// distance and the histogram's counts and extremes, `thermo_modify format float %.15g`).
#[test]
fn pair_local_in_fix_hooks_and_reduce() {
    let deck = "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 box\n\
        mass 1 1.0\nvelocity all create 1.5 87287 loop geom\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n\
        compute dist all pair/local dist eng\ncompute mind all reduce min c_dist[1] inputs local\n\
        fix h all ave/histo 10 1 10 0.8 2.5 4 c_dist[1] mode vector kind local\n\
        thermo_style custom step c_mind f_h[1] f_h[2] f_h[3] f_h[4]\nthermo 50\nthermo_modify format float %.15g\nrun 100\n";
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = dmhs::deck::run_text("histo.deck", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.clone().unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("Step"))
        .skip(1)
        .take_while(|l| !l.starts_with("Loop"))
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect();
    let lammps = [
        [0.0, 1.18765385658167, 6912.0, 0.0, 1.18765385658167, 2.37530771316334],
        [50.0, 0.904086757727591, 7025.0, 0.0, 0.904086757727591, 2.49999018306676],
        [100.0, 0.932292441058103, 7040.0, 0.0, 0.932292441058103, 2.49997093545024],
    ];
    assert_eq!(rows.len(), 3, "{text}");
    for (ours, theirs) in rows.iter().zip(lammps) {
        for (a, b) in ours.iter().zip(theirs) {
            assert!((a - b).abs() <= 2e-15 * b.abs(), "{ours:?} against LAMMPS' {theirs:?}");
        }
    }
}
