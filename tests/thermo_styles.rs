//! thermo_style multi and yaml, thermo_modify line, colname and format ranges, laid out as LAMMPS 22 Jul 2025 lays them
//! out: the text below is LAMMPS' output for lammps-refs/decks/in.thermo_nvt with the style
//! changed and `run 200` (the CPU seconds of the multi header lines left out), and LAMMPS run
//! now when present.

use dmhs::deck::{run_text, DeckOptions};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

const MULTI: &str = "\
------------ Step              0 ----- CPU =            0 (sec) -------------
TotEng   =        -6.6092 KinEng   =         0.1206 Temp     =         0.0806 
PotEng   =        -6.7298 E_bond   =         0.0000 E_angle  =         0.0000 
E_dihed  =         0.0000 E_impro  =         0.0000 E_vdwl   =        -6.7298 
E_coul   =         0.0000 E_long   =         0.0000 Press    =        -6.0765
------------ Step            100 ----- CPU = 
TotEng   =        -6.5850 KinEng   =         0.0854 Temp     =         0.0571 
PotEng   =        -6.6704 E_bond   =         0.0000 E_angle  =         0.0000 
E_dihed  =         0.0000 E_impro  =         0.0000 E_vdwl   =        -6.6704 
E_coul   =         0.0000 E_long   =         0.0000 Press    =        -5.5123
------------ Step            200 ----- CPU = 
TotEng   =        -6.5414 KinEng   =         0.1168 Temp     =         0.0780 
PotEng   =        -6.6582 E_bond   =         0.0000 E_angle  =         0.0000 
E_dihed  =         0.0000 E_impro  =         0.0000 E_vdwl   =        -6.6582 
E_coul   =         0.0000 E_long   =         0.0000 Press    =        -5.0131
";

const YAML: &str = "\
---
keywords: ['Step', 'Temp', 'PotEng', 'f_1', ]
data:
  - [0, 0.08057207363, -6.729842225, 0, ]
  - [100, 0.05705935057, -6.67041613, -0.01338371796, ]
  - [200, 0.07802305302, -6.658166102, -0.04388276743, ]
...
";

/// The nvt deck with `style` lines in place of its thermo_style line, 200 steps.
fn deck(style: &str) -> String {
    let base = std::fs::read_to_string(root().join("lammps-refs/decks/in.thermo_nvt")).unwrap();
    let out = base.replace("thermo_style custom step temp pe ke etotal f_1 f_2\n", &format!("{style}\n")).replace("run          ${nsteps}", "run 200");
    assert_ne!(out, base);
    out
}

/// The thermo output of a run: from the first line of `start` to the line before "Loop time",
/// the CPU seconds of multi headers cut off.
fn block(text: &str, start: &str) -> String {
    let lines: Vec<&str> = text.lines().skip_while(|l| !l.starts_with(start)).take_while(|l| !l.starts_with("Loop time")).collect();
    lines.iter().map(|l| if l.starts_with("------------ Step") && !l.contains("CPU =            0 ") { format!("{}\n", &l[..l.find("CPU = ").unwrap() + 6]) } else { format!("{l}\n") }).collect()
}

fn dmhs(style: &str) -> String {
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = run_text("in.styles", &deck(style), &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    run.sim.out.captured.clone().unwrap()
}

#[test]
fn multi_is_lammps_layout() {
    assert_eq!(block(&dmhs("thermo_style multi"), "------------ Step"), MULTI);
}

#[test]
fn yaml_is_lammps_layout() {
    assert_eq!(block(&dmhs("thermo_style custom step temp pe f_1\nthermo_modify line yaml format float %.10g"), "---"), YAML);
}

/// `thermo_modify line multi` on a custom style: the labels padded to 8, three to a line.
#[test]
fn custom_columns_in_multi_lines() {
    let text = block(&dmhs("thermo_style custom step temp f_1 f_2\nthermo_modify line multi"), "------------ Step");
    let first: Vec<&str> = text.lines().take(3).collect();
    assert_eq!(first[0], "------------ Step              0 ----- CPU =            0 (sec) -------------");
    assert_eq!(first[1], "Step     =              0 Temp     =         0.0806 f_1      =         0.0000 ");
    assert_eq!(first[2], "f_2      =         0.0000");
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn live_styles_are_lammps() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    for (style, start, want) in [
        ("thermo_style multi", "------------ Step", MULTI),
        ("thermo_style custom step temp pe f_1\nthermo_modify line yaml format float %.10g", "---", YAML),
        ("thermo_style custom step temp pe f_1 f_2\nthermo_modify colname f_1 E_lower colname -1 E_upper format 2*3 %9.5f colname 2 T", "   Step", COLNAME),
    ] {
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("in.styles");
        std::fs::write(&path, deck(style)).unwrap();
        dmhs::tools::lammps::run_driver(&path, &[], tmp.path()).unwrap();
        let log = std::fs::read_to_string(tmp.path().join("log.lammps")).unwrap();
        assert_eq!(block(&log, start), want, "{style}");
    }
}

/// `thermo_modify colname` (by keyword, by number from either end) and `format N*M`: LAMMPS'
/// header and rows for the nvt deck.
const COLNAME: &str = "   Step           T            PotEng        E_lower        E_upper    
         0    0.08057  -6.72984  0              0            
       100    0.05706  -6.67042 -0.013383718   -0.021605047  
       200    0.07802  -6.65817 -0.043882767   -0.066577866  
";

#[test]
fn colname_and_format_ranges_are_lammps() {
    let text = dmhs("thermo_style custom step temp pe f_1 f_2\nthermo_modify colname f_1 E_lower colname -1 E_upper format 2*3 %9.5f colname 2 T");
    assert_eq!(block(&text, "   Step"), COLNAME);
}

/// A colname or format that names no column is a located error.
#[test]
fn bad_colname_is_located() {
    for (line, want) in [("thermo_modify colname c_nothere X", "Invalid thermo_modify colname argument: c_nothere"), ("thermo_modify colname 9 X", "Invalid thermo_modify colname argument: 9"), ("thermo_modify format 3*9 %g", "Invalid thermo_modify format argument: 3*9")] {
        let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
        let err = run_text("in.bad", &deck(&format!("thermo_style custom step temp pe f_1 f_2\n{line}")), &opts).err().expect("an error");
        assert!(err.rendered.contains(want) && err.rendered.contains("in.bad:"), "{line}: {}", err.rendered);
    }
}
