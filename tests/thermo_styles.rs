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

/// An LJ melt whose thermo interval comes from variables: logfreq, then stride, then a
/// variable beyond the run's end (two runs of 20).
const VARIABLE_THERMO: &str = "\
units lj
atom_style atomic
lattice fcc 0.8442
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass 1 1.0
velocity all create 1.44 87287 loop geom
pair_style lj/cut 2.5
pair_coeff 1 1 1.0 1.0 2.5
fix 1 all nve
variable s equal logfreq(10,3,10)
thermo v_s
thermo_style custom step pe
run 250
variable t equal stride(300,400,30)
thermo v_t
run 150
variable u equal 1000
thermo v_u
run 20
run 20
";

/// The steps of the thermo lines of every run (`Step` headers split the runs).
fn thermo_steps(text: &str) -> Vec<Vec<i64>> {
    let mut runs: Vec<Vec<i64>> = vec![];
    let mut on = false;
    for l in text.lines() {
        if l.trim_start().starts_with("Step") {
            runs.push(vec![]);
            on = true;
        } else if l.starts_with("Loop time") {
            on = false;
        } else if on {
            runs.last_mut().unwrap().push(l.split_whitespace().next().unwrap().parse().unwrap());
        }
    }
    runs
}

/// `thermo v_name`: a line at the setup of every run, then at the steps the equal-style
/// variable gives after each line, capped at the run's last step except the first (so a first
/// step beyond the run prints no last line): LAMMPS 22 Jul 2025's steps for the same deck, and
/// LAMMPS run now when present.
#[test]
fn variable_thermo_intervals_are_lammps() {
    let lammps: Vec<Vec<i64>> = vec![vec![0, 10, 20, 30, 100, 200, 250], vec![250, 300, 330, 360, 390, 400], vec![400], vec![420]];
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = run_text("in.vthermo", VARIABLE_THERMO, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    assert_eq!(thermo_steps(run.sim.out.captured.as_deref().unwrap()), lammps);
    if dmhs::tools::lammps::python_for_live_test().is_some() {
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("in.vthermo");
        std::fs::write(&path, VARIABLE_THERMO).unwrap();
        dmhs::tools::lammps::run_driver(&path, &[], tmp.path()).unwrap();
        assert_eq!(thermo_steps(&std::fs::read_to_string(tmp.path().join("log.lammps")).unwrap()), lammps);
    }
    // LAMMPS' errors: a missing variable, another style, a step not after the current one
    for (lines, want) in [
        ("thermo v_nope", "Variable name nope for thermo every does not exist"),
        ("variable a atom x\nthermo v_a", "Variable a for thermo every is invalid style"),
        ("variable b equal step\nthermo v_b", "Thermo every variable b returned a bad timestep"),
    ] {
        let text = VARIABLE_THERMO.replacen("thermo v_s\n", &format!("{lines}\n"), 1);
        let err = run_text("in.bad", &text, &opts).err().expect("an error");
        assert!(err.rendered.contains(want) && err.rendered.contains("in.bad:"), "{lines}: {}", err.rendered);
    }
}

/// Warnings past `thermo_modify warn N` are not printed, as LAMMPS 22 Jul 2025's Error::warning:
/// its log of this deck prints the replicate warning after `always`, none after `warn 1` (the
/// count is already 1), the notice at the next thermo output, one after `default` (count reset),
/// none after a negative limit. LAMMPS' notice reads "8 vs 1": besides the replicate warnings,
/// thermo_style's (previous thermo_modify settings lost) and Verlet's (no fix with time
/// integration), all counted here, it counts two run-setup warnings of a deck without a pair
/// style that dmhs does not issue (atom sorting disabled, no ghost atoms).
#[test]
fn warning_limit_is_lammps() {
    let deck = "units lj\nboundary p p f\natom_style atomic\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\nmass 1 1.0\n\
                thermo_modify warn always\nreplicate 1 1 2\nthermo_modify warn 1\nreplicate 1 1 2\nreplicate 1 1 2\nreplicate 1 1 2\n\
                thermo_style custom step atoms\nrun 0\nreplicate 1 1 2\nrun 0\nthermo_modify warn default\nreplicate 1 1 2\n\
                thermo_modify warn -3\nreplicate 1 1 2\nrun 0\n";
    let opts = DeckOptions { screen: false, capture_text: true, echo: Some((true, true)), ..Default::default() };
    let run = run_text("in.warn", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.clone().unwrap();
    let seen: Vec<&str> = text.lines().filter(|l| l.starts_with("WARNING") || l.starts_with("replicate") || l.starts_with("thermo_modify") || l.starts_with("run")).collect();
    let warn = "WARNING: Replicating in a non-periodic dimension";
    #[rustfmt::skip]
    let want = [
        "thermo_modify warn always", "replicate 1 1 2", warn, "thermo_modify warn 1", "replicate 1 1 2", "replicate 1 1 2", "replicate 1 1 2",
        "run 0", "WARNING: Too many warnings: 6 vs 1. All future warnings will be suppressed", "replicate 1 1 2", "run 0",
        "thermo_modify warn default", "replicate 1 1 2", warn, "thermo_modify warn -3", "replicate 1 1 2", "run 0",
    ];
    assert_eq!(seen, want, "{text}");
    let bad = run_text("in.bad", "thermo_modify warn lots\n", &DeckOptions { screen: false, ..Default::default() }).err().expect("an error");
    assert!(bad.rendered.contains("in.bad:1") && bad.rendered.contains("warn"), "{}", bad.rendered);
}

/// A new thermo_style drops every thermo_modify setting (norm, temp, flush, lost, ...), with
/// LAMMPS' warning; the pressure compute keeps the temperature `thermo_modify temp` gave it.
/// The rows are LAMMPS 22 Jul 2025's for this deck.
#[test]
fn a_new_thermo_style_drops_thermo_modify_settings() {
    let deck = "units lj\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                velocity all create 1.0 87287\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n\
                compute t2 all temp/partial 1 1 0\nthermo_modify norm no temp t2 flush yes lost warn\n\
                thermo_style custom step temp pe ke press\nrun 0\nthermo_modify norm no temp t2\nrun 0\n";
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = run_text("deck", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.clone().unwrap();
    assert_eq!(text.matches("WARNING: New thermo_style command, previous thermo_modify settings will be lost").count(), 1, "{text}");
    let rows: Vec<&str> = text.lines().filter(|l| l.trim_start().starts_with("0 ")).map(|l| l.trim()).collect();
    let want = ["0   1             -6.7733681      1.4861111     -5.6573178", "0   1.0366051     -731.52375      110.91675     -5.6573178"];
    assert_eq!(rows, want, "{text}");
}

/// A run without a fix that moves atoms warns, as LAMMPS' Verlet::init; `run ... pre no`
/// (no init) and minimize do not.
#[test]
fn a_run_without_time_integration_warns() {
    let base = "units lj\nlattice fcc 0.8442\nregion b block 0 2 0 2 0 2\ncreate_box 1 b\ncreate_atoms 1 box\nmass 1 1\npair_style lj/cut 2.5\npair_coeff 1 1 1 1\n";
    let warn = "WARNING: No fixes with time integration, atoms won't move";
    for (rest, count) in [("run 1\n", 1), ("run 1\nrun 1 pre no\n", 1), ("fix 1 all nve\nrun 1\n", 0), ("minimize 0 0 10 10\n", 0), ("run 1\nrun 1\n", 2)] {
        let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
        let run = run_text("in.warn", &format!("{base}{rest}"), &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
        let text = run.sim.out.captured.clone().unwrap();
        assert_eq!(text.matches(warn).count(), count, "{rest}:\n{text}");
    }
}
