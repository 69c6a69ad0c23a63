//! compute property/local against LAMMPS: the dump local files of the lammps-refs decks
//! property_local_gran (granular contacts, `cutoff radius` and `type`, periodic boundaries) and
//! property_local_topo (bonds, angles, dihedrals with delete_bonds' negative types, a group,
//! pairs with special bonds), from lammps-refs/refs/NAME/local.* or LAMMPS run now. Bonds,
//! angles and dihedrals row for row (LAMMPS' order); pairs as sets per step, each pair with its
//! atoms' types (LAMMPS' row order and orientation come from its own binning). And the
//! located errors, and the run summary's "Neighs" count against LAMMPS' (the same pairs, counted
//! as LAMMPS' half list does).


#[allow(unused)]
mod thermo_tables;
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

/// How a file's rows compare: in order, or as pairs with the columns of (atom 1, atom 2, type 1,
/// type 2) after the row index.
#[derive(Clone, Copy)]
enum Rows {
    Ordered,
    Pairs([usize; 4]),
}

const FILES: [(&str, &str, Rows); 6] = [
    ("property_local_gran", "pairs", Rows::Pairs([1, 2, 3, 4])),
    ("property_local_gran", "cut", Rows::Pairs([0, 1, 3, 2])),
    ("property_local_topo", "bonds", Rows::Ordered),
    ("property_local_topo", "angles", Rows::Ordered),
    ("property_local_topo", "dihedrals", Rows::Ordered),
    ("property_local_topo", "pairs", Rows::Pairs([1, 2, 3, 4])),
];

/// The snapshots of a dump local file: step -> rows of words.
fn snapshots(text: &str) -> BTreeMap<i64, Vec<Vec<String>>> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = BTreeMap::new();
    let mut k = 0;
    while k < lines.len() {
        if lines[k].starts_with("ITEM: TIMESTEP") {
            let step: i64 = lines[k + 1].trim().parse().unwrap();
            let n: usize = lines[k + 3].trim().parse().unwrap();
            let rows = lines[k + 9..k + 9 + n].iter().map(|l| l.split_whitespace().map(String::from).collect()).collect();
            out.insert(step, rows);
            k += 9 + n;
        } else {
            k += 1;
        }
    }
    out
}

/// The rows as compared: ordered rows as they are; pairs as (lower ID, higher ID, its type,
/// the other's type), sorted.
fn normalized(rows: &[Vec<String>], how: Rows) -> Vec<Vec<String>> {
    match how {
        Rows::Ordered => rows.to_vec(),
        Rows::Pairs([a, b, ta, tb]) => {
            let mut v: Vec<Vec<String>> = rows
                .iter()
                .map(|r| {
                    let (ia, ib): (i64, i64) = (r[a].parse().unwrap(), r[b].parse().unwrap());
                    if ia <= ib {
                        vec![r[a].clone(), r[b].clone(), r[ta].clone(), r[tb].clone()]
                    } else {
                        vec![r[b].clone(), r[a].clone(), r[tb].clone(), r[ta].clone()]
                    }
                })
                .collect();
            v.sort_by_key(|r| (r[0].parse::<i64>().unwrap(), r[1].parse::<i64>().unwrap()));
            v
        }
    }
}

/// The dump files deck `name` writes (the suffixes of its `SUFFIXfile` variables).
fn suffixes(name: &str) -> Vec<&'static str> {
    FILES.iter().filter(|f| f.0 == name).map(|f| f.1).collect()
}

/// dmhs on deck `name` with its dump files under `dir/local.*`.
fn dmhs_run(name: &str, dir: &Path) {
    common::run_with_local_files(&deck(name), &suffixes(name), dir);
}

/// Every file of every deck: the same steps, the same rows.
fn check(reference: impl Fn(&str) -> PathBuf) {
    let mut bad = vec![];
    for name in ["property_local_gran", "property_local_topo"] {
        let tmp = tempfile::tempdir().unwrap();
        dmhs_run(name, tmp.path());
        for (deck_name, suffix, how) in FILES.iter().filter(|f| f.0 == name) {
            let theirs = snapshots(&std::fs::read_to_string(reference(deck_name).join(format!("local.{suffix}"))).unwrap());
            let ours = snapshots(&std::fs::read_to_string(tmp.path().join(format!("local.{suffix}"))).unwrap());
            assert!(theirs.len() >= 3, "{name}.{suffix}: too few snapshots");
            assert_eq!(ours.keys().collect::<Vec<_>>(), theirs.keys().collect::<Vec<_>>(), "{name}.{suffix}: steps");
            for (step, rows) in &theirs {
                let (t, o) = (normalized(rows, *how), normalized(&ours[step], *how));
                println!("{name}.{suffix} step {step}: LAMMPS {} rows, dmhs {}", t.len(), o.len());
                assert!(t.len() >= 10, "{name}.{suffix}: too few rows to test anything");
                if t != o {
                    let first = t.iter().zip(&o).position(|(a, b)| a != b).unwrap_or(t.len().min(o.len()));
                    bad.push(format!("{name}.{suffix} step {step}: {} rows against LAMMPS' {}; first difference at row {first}: {:?} / {:?}", o.len(), t.len(), o.get(first), t.get(first)));
                }
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn stored_local_rows() {
    check(|name| root().join("lammps-refs/refs").join(name));
}

/// compute reduce over the contacts' type columns (the sum of both types of every contact, which
/// does not depend on the pairs' orientation) at every printed step, equal to LAMMPS'.
#[test]
fn reduce_of_local_columns() {
    let (names, theirs) = thermo_tables::table(&std::fs::read_to_string(root().join("lammps-refs/refs/property_local_gran/thermo.txt")).unwrap());
    let (_, ours) = thermo_tables::dmhs_table("property_local_gran");
    let c = names.iter().position(|n| n == "v_tsum").unwrap();
    let (t, o): (Vec<f64>, Vec<f64>) = (theirs.iter().map(|r| r[c]).collect(), ours.iter().map(|r| r[c]).collect());
    println!("type sums over the contacts: LAMMPS {t:?}, dmhs {o:?}");
    assert!(t.iter().all(|&x| x > 100.0));
    assert_eq!(o, t);
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn live_local_rows() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    for name in ["property_local_gran", "property_local_topo"] {
        let out = tmp.path().join(name);
        std::fs::create_dir_all(&out).unwrap();
        dmhs::tools::lammps::run_driver(&deck(name), &common::local_file_vars(&suffixes(name), &out), &out).unwrap();
    }
    check(|name| tmp.path().join(name));
}

/// Bad compute property/local commands are located errors (`dmhs check`).
#[test]
fn property_local_errors_are_located() {
    let base = std::fs::read_to_string(deck("property_local_topo")).unwrap();
    let line = "compute      b all property/local batom1 batom2 btype";
    for (to, want) in [
        ("compute b all property/local batom1 patom2", "cannot use these inputs together"),
        ("compute b all property/local natom1 natom2", "neighbour-list pairs"),
        ("compute b all property/local iatom1", "impropers"),
        ("compute b all property/local batom3", "Invalid keyword `batom3`"),
        ("compute b all property/local", "attribute"),
        ("compute b all property/local patom1 cutoff radius", "requires atom attribute radius"),
        ("compute b all property/local patom1 cutoff sphere", "cutoff"),
    ] {
        let deck_text = base.replacen(line, to, 1);
        assert_ne!(deck_text, base);
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("in.pl");
        std::fs::write(&path, &deck_text).unwrap();
        std::fs::copy(root().join("lammps-refs/decks/chains_periodic_full.data"), tmp.path().join("chains_periodic_full.data")).unwrap();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_dmhs")).arg("check").arg(&path).current_dir(tmp.path()).output().unwrap();
        let out = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
        assert_eq!(o.status.code(), Some(2), "{to}: {out}");
        assert!(out.contains(want) && out.contains("in.pl:"), "{to}: expected `{want}`:\n{out}");
    }
}

/// The last "Neighs:" count LAMMPS 22 Jul 2025 prints for three decks (lammps-refs/regenerate.sh
/// leaves its logs in refs/NAME/log.lammps): bead-spring chains under a barostat, a granular bed,
/// chains with excluded special pairs.
const NEIGHS: [(&str, &str); 3] = [("npt_chains_com", "709"), ("property_local_gran", "1301"), ("property_local_topo", "677")];

fn last_neighs(text: &str) -> Option<String> {
    text.lines().filter(|l| l.starts_with("Neighs:")).last().and_then(|l| l.split_whitespace().nth(1)).map(String::from)
}

/// The run summary's neighbour count is LAMMPS' (its half list with `newton on`: special pairs of
/// weight 0 left out, a pair across a periodic boundary once).
#[test]
fn summary_neighbour_count_is_lammps() {
    for (name, theirs) in NEIGHS {
        let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(deck(name).parent().unwrap().to_path_buf()), ..Default::default() };
        let run = run_file(&deck(name), &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
        let ours = last_neighs(run.sim.out.captured.as_deref().unwrap());
        println!("{name}: Neighs dmhs {ours:?}, LAMMPS {theirs}");
        assert_eq!(ours.as_deref(), Some(theirs), "{name}");
    }
}

/// The counts of [`NEIGHS`] are what LAMMPS prints now.
#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn live_neighbour_counts() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    for (name, count) in NEIGHS {
        let tmp = tempfile::tempdir().unwrap();
        dmhs::tools::lammps::run_driver(&deck(name), &[], tmp.path()).unwrap();
        assert_eq!(last_neighs(&std::fs::read_to_string(tmp.path().join("log.lammps")).unwrap()).as_deref(), Some(count), "{name}");
    }
}
