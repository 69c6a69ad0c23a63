//! fix wall/gran/region and the region keywords it brought (cone, open, move, rotate, delete):
//! the errors of bad input, located and named; LAMMPS' behaviour when a region a fix uses is
//! deleted. Their numbers are compared with LAMMPS in tests/lammps_parity.rs (lammps-refs decks
//! gran_region_box, gran_region_funnel, gran_region_rotate, gran_region_move, gran_region_mixer,
//! gran_region_plane, gran_region_prism, gran_region_boolean, gran_region_contacts). The
//! `contacts` arrays of gran_region_contacts and gran_jkr_walls (JKR against a flat and a region
//! wall), reduced in thermo, and gran_region_varshape (a turning cylinder whose radius shrinks,
//! a plane lid that moves down: walls of variable shape) are compared here column by column
//! with LAMMPS' thermo table.

use std::process::Command;

mod thermo_tables;

thermo_tables::thermo_table_tests!(["gran_region_contacts", "gran_jkr_walls", "gran_region_varshape", "gran_contact_atom"]);

fn run(mode: &str, deck: &str) -> (i32, String) {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("in.region");
    std::fs::write(&path, deck).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).arg(mode).arg(&path).current_dir(tmp.path()).output().unwrap();
    (o.status.code().unwrap_or(-1), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

const BASE: &str = "units lj
atom_style sphere
boundary f f f
comm_modify vel yes
region box block -10 10 -10 10 -10 10 units box
create_box 1 box
create_atoms 1 single 0 0 -5.6 units box
set type 1 diameter 1.0 density 1.0
pair_style gran/hooke 4000.0 NULL 100.0 NULL 0.5 1
pair_coeff * *
fix 2 all nve/sphere
region container block -6 6 -6 6 -6 6 units box
";

fn deck(rest: &str) -> String {
    format!("{BASE}{rest}")
}

#[test]
fn wall_region_runs_and_pushes_a_sphere_off_the_floor() {
    let (code, out) = run("-in", &deck("fix w all wall/gran/region hooke/history 4000.0 NULL 100.0 NULL 0.5 1 region container\nvariable vz equal vz[1]\nthermo_style custom step v_vz\nthermo 10\nrun 10\n"));
    assert_eq!(code, 0, "{out}");
    // the sphere starts 0.1 inside the floor's reach: the wall pushes it up
    let last = out.lines().filter(|l| l.trim_start().starts_with("10 ")).next_back().unwrap();
    let vz: f64 = last.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!(vz > 0.0, "{out}");
}

#[test]
fn bad_input_is_located() {
    let cases = [
        ("fix w all wall/gran/region hooke 4000.0 NULL 100.0 NULL 0.5 1 region nowhere\n", "region nowhere for fix wall/gran/region does not exist"),
        ("fix w all wall/gran/region hooke 4000.0 NULL 100.0 NULL 0.5 1 container\n", "expected `region region-ID`"),
        ("fix w all wall/gran/region hooke 4000.0 NULL 100.0 NULL 0.5 1 region container contacts temperature 300\n", "`temperature` needs a heat model"),
        ("fix w all wall/gran/region hooke 4000.0 NULL 100.0 NULL 0.5 1 region container\ncompute r all reduce sum f_w[1]\n", "fix `w` does not compute per-atom values"),
        ("fix w all wall/gran xplane -1 1 region container\n", "unknown"),
        ("region r block 0 1 0 1 0 1 move x NULL NULL\n", "v_name or NULL"),
        ("region c cone z 0 0 1 2 0 1 open 5\n", "no open face 5"),
        ("region nowhere delete\n", "region `nowhere` to delete does not exist"),
        ("comm_modify mode multi\n", "cannot use comm mode `multi` without `multi` style neighbor lists"),
    ];
    for (rest, want) in cases {
        let (code, out) = run("check", &deck(rest));
        assert_ne!(code, 0, "{rest}: {out}");
        assert!(out.contains(want) && out.contains("in.region:"), "{rest}: want `{want}`\n{out}");
    }
}

#[test]
fn deleted_region_stops_the_next_run_as_in_lammps() {
    // LAMMPS: "Region container for fix wall/gran/region does not exist" when the run starts
    let (code, out) = run("-in", &deck("fix w all wall/gran/region hooke 4000.0 NULL 100.0 NULL 0.5 1 region container\nrun 5\nregion container delete\nrun 5\n"));
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("region container for fix wall/gran/region does not exist"), "{out}");
    // defined again: the fix takes the new region, with LAMMPS' warning
    let (code, out) = run(
        "-in",
        &deck("fix w all wall/gran/region hooke 4000.0 NULL 100.0 NULL 0.5 1 region container\nrun 5\nregion container delete\nregion container block -7 7 -7 7 -7 7 units box\nrun 5\n"),
    );
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("WARNING: Region properties for region container changed between runs, resetting its motion"), "{out}");
}

#[test]
fn balance_and_comm_style_are_accepted_with_a_note() {
    let (code, out) = run("check", &deck("neighbor 0.3 multi\ncomm_style brick\ncomm_modify mode multi group all vel yes\nbalance 1.1 shift xyz 20 1.1\nfix bal all balance 10000 1.1 shift xyz 20 1.01\n"));
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("note: balance does nothing") && out.contains("note: fix bal balance does nothing"), "{out}");
}
