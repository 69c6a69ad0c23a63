//! `group ID dynamic|static`, fix pour's insertion interval set at init, and `write_dump`.
//! Trajectories are compared with LAMMPS by lammps-refs/decks/in.group_dynamic and
//! in.pour_timestep (tests/lammps_parity.rs); here: what LAMMPS 22 Jul 2025 refuses (located
//! errors), what it prints, and that write_dump writes what a dump of the same step writes.
//! in.group_dynamic_property (`property`, and `set ... i_NAME|d_NAME`): its thermo table against
//! LAMMPS', every column. in.region_varshape (regions whose shape words are variables, and a
//! moving region, read by fix addforce/setforce and count(all,region) in thermo): its thermo
//! table against LAMMPS', and the located errors of variable shapes.

use std::path::{Path, PathBuf};
use std::process::Command;

mod thermo_tables;

thermo_tables::thermo_table_tests!(["group_dynamic_property", "region_varshape"]);

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn deck(name: &str) -> String {
    std::fs::read_to_string(root().join("lammps-refs/decks").join(name)).unwrap()
}

/// `dmhs` on `text` in `dir` (as in.t): exit code and output.
fn run_in(dir: &Path, text: &str, nsteps: &str) -> (i32, String) {
    std::fs::write(dir.join("in.t"), text).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).args(["-in", "in.t", "-var", "nsteps", nsteps, "-log", "none"]).current_dir(dir).output().unwrap();
    (o.status.code().unwrap_or(-1), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

fn run(text: &str) -> (i32, String) {
    let tmp = tempfile::tempdir().unwrap();
    run_in(tmp.path(), text, "0")
}

fn expect_error(text: &str, want: &str) {
    let (code, out) = run(text);
    assert_ne!(code, 0, "expected an error `{want}`:\n{out}");
    assert!(out.contains(want) && out.contains("in.t:"), "expected `{want}` with its location:\n{out}");
}

const GROUP_LINE: &str = "group        pushed dynamic all region band every 5";

#[test]
fn dynamic_group_prints_and_counts_at_setup() {
    // LAMMPS: "dynamic group pushed defined"; the members are set at the run's setup
    let (code, out) = run(&deck("in.group_dynamic"));
    assert_eq!(code, 0, "{out}");
    assert!(out.lines().any(|l| l == "dynamic group pushed defined"), "{out}");
    // step 0 of LAMMPS' thermo: count(pushed) 160, count(damped) 140
    let row = out.lines().skip_while(|l| !l.trim_start().starts_with("Step")).nth(1).expect("thermo row of step 0");
    let v: Vec<&str> = row.split_whitespace().collect();
    assert_eq!((v[4], v[5]), ("160", "140"), "{row}");
}

#[test]
fn dynamic_group_refusals_are_lammps() {
    let d = deck("in.group_dynamic");
    let with = |extra: &str| d.replace(GROUP_LINE, &format!("{GROUP_LINE}\n{extra}"));
    expect_error(&with("group g2 union all pushed"), "Cannot union groups using a dynamic group");
    expect_error(&with("group g2 subtract all pushed"), "Cannot subtract groups using a dynamic group");
    expect_error(&with("group g2 intersect all pushed"), "Cannot intersect groups using a dynamic group");
    expect_error(&with("fix p pushed property/atom i_flag"), "Fix property/atom does not allow use with a dynamic group");
    expect_error(&with("compute m pushed msd"), "Compute msd is not compatible with dynamic groups");
    expect_error(&d.replace(GROUP_LINE, "group        pushed dynamic all"), "LAMMPS needs at least one");
    expect_error(&d.replace(GROUP_LINE, "group        pushed dynamic pushed region band"), "Group dynamic cannot reference itself");
    expect_error(&d.replace(GROUP_LINE, "group        pushed dynamic nope region band"), "parent group `nope` does not exist");
    expect_error(&d.replace(GROUP_LINE, "group        all dynamic left region band"), "Group all cannot be made dynamic");
    expect_error(&d.replace(GROUP_LINE, "group        pushed dynamic all region nope"), "Region nope for dynamic group pushed does not exist");
    expect_error(&d.replace(GROUP_LINE, "group        pushed dynamic all var nope"), "Variable 'nope' for dynamic group pushed does not exist");
    expect_error(&d.replace(GROUP_LINE, "group        pushed dynamic all region band every 0"), "Illegal every value 0");
    expect_error(&d.replace(GROUP_LINE, "group        pushed dynamic all foo 1"), "unknown keyword `foo`");
    // property: a custom per-atom vector that exists when the group is defined (LAMMPS' check)
    expect_error(&d.replace(GROUP_LINE, "group        pushed dynamic all property flag"), "Custom per-atom vector flag for group dynamic does not exist");
    expect_error(&d.replace(GROUP_LINE, "set          group all i_flag 1"), "Set keyword or custom property i_flag does not exist");
    expect_error(&d.replace(GROUP_LINE, "fix p all property/atom i_flag\nset group all i_flag 1.5"), "integer");
    // the parent of a dynamic group cannot be dynamic (LAMMPS checks at init)
    let (code, out) = run(&with("group sub dynamic pushed region lhalf"));
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("Dynamic group parent group pushed cannot be dynamic"), "{out}");
}

#[test]
fn group_static_and_delete_drop_the_internal_fix() {
    let d = deck("in.group_dynamic");
    // after `static`, union is allowed again; after delete, the name can be reused as a plain group
    let d = d.replace(GROUP_LINE, &format!("{GROUP_LINE}\ngroup pushed static\ngroup g2 union all pushed"));
    let d = d.replace("group        damped dynamic left var fast", "group        damped dynamic left var fast\ngroup damped delete\ngroup damped region band");
    let (code, out) = run(&d.replace("fix          3 damped viscous 0.5\n", ""));
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("0 atoms in group pushed"), "{out}");
    // a static group is no longer recomputed: still empty at the run's setup, so c_tp is 0
    let row = out.lines().skip_while(|l| !l.trim_start().starts_with("Step")).nth(1).expect("thermo row of step 0");
    assert_eq!(row.split_whitespace().nth(4), Some("0"), "{row}");
    assert!(out.contains("atoms in group damped"), "{out}");
}

#[test]
fn pour_interval_uses_the_run_timestep_and_refuses_a_later_change() {
    // LAMMPS 22 Jul 2025 on in.pour_timestep: "Particle insertion: 37 every 1105 steps, 300 by
    // step 8841" (dt 0.002, set after the fix), printed once although the deck has two runs
    let (code, out) = run(&deck("in.pour_timestep"));
    assert_eq!(code, 0, "{out}");
    let lines: Vec<&str> = out.lines().filter(|l| l.starts_with("Particle insertion:")).collect();
    assert_eq!(lines, ["Particle insertion: 37 every 1105 steps, 300 by step 8841"], "{out}");
    let d = deck("in.pour_timestep");
    expect_error(&d.replace("run          300", "timestep 0.001\nrun          300"), "Cannot change timestep with fix pour");
}

#[test]
fn write_dump_equals_a_dump_of_the_same_step() {
    let tmp = tempfile::tempdir().unwrap();
    let d = deck("in.group_dynamic").replace("run          100", "run          10\nwrite_dump   left custom wd.txt id type x y z vx modify sort id format float %20.15g");
    let d = d.replace("thermo       50", "thermo       50\ndump         1 left custom 10 ref.txt id type x y z vx\ndump_modify  1 sort id format float %20.15g");
    let (code, out) = run_in(tmp.path(), &d, "20");
    assert_eq!(code, 0, "{out}");
    let reference = std::fs::read_to_string(tmp.path().join("ref.txt")).unwrap();
    let last = &reference[reference.rfind("ITEM: TIMESTEP").unwrap()..];
    assert!(last.starts_with("ITEM: TIMESTEP\n30\n"), "{last}");
    assert_eq!(std::fs::read_to_string(tmp.path().join("wd.txt")).unwrap(), last);
}

#[test]
fn write_dump_errors_are_located() {
    let d = deck("in.group_dynamic");
    let with = |line: &str| d.replace("run          100", line);
    expect_error(&with("write_dump nope custom x.txt id"), "group `nope` does not exist");
    expect_error(&with("write_dump all bogus x.txt id"), "unknown dump style `bogus`");
    expect_error(&with("write_dump all custom x.txt id zork"), "unknown dump field `zork`");
    expect_error(&with("write_dump all custom x.txt id modify"), "a dump_modify keyword after `modify`");
    expect_error(&with("write_dump all custom x.txt id modify sort foo"), "sorts dumps only by");
    expect_error(&with("write_dump all"), "group-ID, dump style and file name");
    expect_error(&with("write_dump all movie x.mp4 type type"), "movie cannot be used with write_dump");
}

const VARSHAPE: &str = "units lj\natom_style atomic\nregion box block 0 4 0 4 0 4 units box\ncreate_box 1 box\n\
create_atoms 1 single 1 1 1 units box\nmass 1 1.0\npair_style zero 1.0\npair_coeff * *\nfix 1 all nve\n";

/// Shape words that may be variables take them (evaluated at definition); those LAMMPS 22 Jul
/// 2025 reads as numbers refuse them; a value that breaks the shape at a later step stops the
/// run with LAMMPS' message.
#[test]
fn variable_shapes_are_checked_where_lammps_checks_them() {
    expect_error(&format!("{VARSHAPE}variable r equal 1\nregion c cylinder z 1 1 1 v_r 2 units box\n"), "region cylinder takes a number for lo, not a variable");
    expect_error(&format!("{VARSHAPE}region s sphere 1 1 1 v_nope units box\n"), "Variable nope for region sphere");
    expect_error(&format!("{VARSHAPE}variable n equal 1\nregion p plane 0 0 0 v_n 0 1 units box\n"), "normal vector must be all variables or all constants");
    let (code, out) = run(&format!("{VARSHAPE}variable r equal 1-0.1*step\nregion s sphere 1 1 1 v_r units box\nfix 2 all addforce 1 0 0 region s\nrun 20\n"));
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("Variable evaluation in region gave bad value") && out.contains("step 11"), "{out}");
    // fix pour refuses a region that changes (LAMMPS: its bounding box is fixed)
    expect_error(
        "units lj\natom_style sphere\nregion box block 0 10 0 10 0 10\ncreate_box 1 box\nvariable h equal 8+step*0.01\nregion slab block 1 9 1 9 5 v_h units box\nfix g all gravity 1.0 vector 0 0 -1\nfix ins all pour 10 1 4767548 region slab\n",
        "fix pour region cannot be dynamic",
    );
    // an ellipsoid has inside tests only (LAMMPS' surface code for it gives no displacement)
    expect_error(&format!("{VARSHAPE}region e ellipsoid 2 2 2 1 1 1 units box\nfix w all wall/region e lj93 1 1 2.5\n"), "does not support region style ellipsoid");
    // a group command places the region at its step (a variable of the step)
    let (code, out) = run(&format!("{VARSHAPE}variable x equal 2-0.5*step\nregion b block 0 v_x 0 4 0 4 units box\nrun 3\ngroup g region b\nprint \"N ${{n}}\"\n").replace("print", "variable n equal count(g)\nprint"));
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("0 atoms in group g") && out.contains("N 0"), "{out}");
}
