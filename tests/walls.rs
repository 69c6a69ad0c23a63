//! Wall fixes with potentials against LAMMPS, beyond the per-atom state tests/lammps_parity.rs
//! compares: every column of the thermo table (temperature, energies, the walls' energies f_ID
//! and forces f_ID[k]) of the decks walls_family (fix wall/lj93, lj126, lj1043, harmonic, morse),
//! walls_region (fix wall/region lj93, lj126, lj1043, harmonic, morse; inside and `side out`)
//! and walls_colloid (fix wall/region colloid) at every printed step, against
//! lammps-refs/refs/NAME/thermo.txt (and LAMMPS run now, when present). And the errors: located
//! for bad commands, a run error for a particle outside its region or behind its wall.

use dmhs::deck::{run_text, DeckOptions};

mod thermo_tables;
use thermo_tables::{root, table};

const DECKS: [&str; 3] = ["walls_family", "walls_region", "walls_colloid"];

fn opts() -> DeckOptions {
    DeckOptions { screen: false, capture_text: true, base_dir: Some(root().join("lammps-refs/decks")), ..Default::default() }
}

thermo_tables::thermo_table_tests!(DECKS);

/// A small closed box of atoms for the error cases.
const BASE: &str = "units lj\natom_style atomic\nboundary f f f\nregion box block 0 10 0 10 0 10 units box\ncreate_box 1 box\n\
create_atoms 1 single 5 5 5 units box\ncreate_atoms 1 single 5 5 6.5 units box\nmass 1 1.0\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\n\
region ball sphere 5 5 5 3 units box\nregion slab plane 0 0 5 0 0 1 units box\nfix 1 all nve\n";

#[test]
fn bad_wall_commands_are_located_errors() {
    for (cmd, want) in [
        ("fix w all wall/lj126 xlo EDGE 1.0 1.0", "cutoff"),
        ("fix w all wall/morse xlo EDGE 1.0 1.0 1.0", "cutoff"),
        ("fix w all wall/harmonic xlo EDGE 1.0 1.0 0.0", "> 0"),
        ("fix w all wall/lj1043 xlo EDGE 1.0 1.0 2.5 xlo EDGE 1.0 1.0 2.5", "defined twice"),
        ("fix w all wall/lj93 xlo EDGE 1.0 1.0 2.5 fld yes", "fld yes"),
        ("fix w all wall/lj126 xlo EDGE 1.0 1.0 2.5 wobble 1", "unknown keyword `wobble`"),
        ("fix w all wall/lj126 units box", "a wall face"),
        ("fix w all wall/lj9 xlo EDGE 1.0 1.0 2.5", "wall/lj93"),
        ("fix w all wall/region nothere lj93 1.0 1.0 2.5", "region nothere for fix wall/region does not exist"),
        ("fix w all wall/region ball lj99 1.0 1.0 2.5", "unknown fix wall/region style `lj99`"),
        ("fix w all wall/region ball lj93 1.0 1.0", "cutoff"),
        ("fix w all wall/region ball morse 1.0 2.0 1.0", "cutoff"),
        ("fix w all wall/region ball lj93 1.0 1.0 -1", "> 0"),
        ("fix w all wall/region ball harmonic 1.0 1.0 1.0 extra", "extra"),
        ("fix w all wall/region ball colloid 1.0 1.0 2.0", "atom_style sphere"),
        ("fix w all wall/region", "region ID"),
    ] {
        let deck = format!("{BASE}{cmd}\nrun 0\n");
        let f = run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {cmd}"));
        assert!(f.rendered.contains("bad.deck:14:") && f.rendered.contains(want), "{cmd}: expected `{want}`:\n{}", f.rendered);
    }
}

#[test]
fn particles_on_the_wrong_side_stop_the_run() {
    for (cmd, want) in [
        // the second atom sits outside a sphere of radius 1
        ("region small sphere 5 5 5 1 units box\nfix w all wall/region small lj93 1.0 1.0 2.5", "outside the surface of region small"),
        // the first atom is inside the hole of a side-out sphere
        ("region hole sphere 5 5 5 1 side out units box\nfix w all wall/region hole harmonic 1.0 1.0 2.5", "outside the surface of region hole"),
        ("fix w all wall/lj126 zhi 6.0 1.0 1.0 2.5", "particle 2 is on or inside the wall surface"),
    ] {
        let deck = format!("{BASE}{cmd}\nrun 10\n");
        let f = run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {cmd}"));
        assert!(f.rendered.contains(want) && f.rendered.contains("step 0"), "{cmd}: expected `{want}`:\n{}", f.rendered);
    }
    // fix wall/lj1043 ignores particles behind its wall, as LAMMPS
    let deck = format!("{BASE}fix w all wall/lj1043 zhi 6.0 1.0 1.0 2.5\nthermo_style custom step f_w f_w[1]\nrun 0\n");
    run_text("ok.deck", &deck, &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
}

/// Flat walls on the six faces of a block and fix wall/region on that block are the same
/// formula along the same normals: equal energies and forces, and the per-wall forces of the
/// flat walls add up to the region's.
#[test]
fn flat_and_region_walls_agree() {
    for (flat, region) in [("lj93 1.0 1.0 4.0", "lj93 1.0 1.0 4.0"), ("lj126 1.0 1.1 4.0", "lj126 1.0 1.1 4.0"), ("lj1043 1.0 1.0 4.0", "lj1043 1.0 1.0 4.0"), ("harmonic 2.0 1.0 4.0", "harmonic 2.0 1.0 4.0"), ("morse 1.0 1.5 2.0 4.0", "morse 1.0 1.5 2.0 4.0")] {
        let (style, args) = flat.split_once(' ').unwrap();
        let faces: String = ["xlo 2", "xhi 8", "ylo 2", "yhi 8", "zlo 2", "zhi 8"].iter().map(|f| format!(" {f} {args}")).collect();
        let deck = format!(
            "{BASE}region inner block 2 8 2 8 2 8 units box\nfix a all wall/{style}{faces} units box\nfix b all wall/region inner {region}\n\
thermo_style custom step f_a f_b f_a[1] f_a[2] f_a[3] f_a[4] f_a[5] f_a[6] f_b[1] f_b[2] f_b[3]\nthermo_modify format float %.17g\nrun 0\n"
        );
        let run = run_text("agree.deck", &deck, &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
        let (_, rows) = table(run.sim.out.captured.as_deref().unwrap());
        let r = &rows[0];
        assert!(r[1] != 0.0 && (r[1] - r[2]).abs() <= 1e-14 * r[1].abs(), "{style}: energies {} {}", r[1], r[2]);
        for d in 0..3 {
            let sum = r[3 + 2 * d] + r[4 + 2 * d];
            assert!((sum - r[9 + d]).abs() <= 1e-12 * r[9 + d].abs().max(1.0), "{style}: axis {d}: flat {sum} region {}", r[9 + d]);
        }
        assert!(r[9..12].iter().any(|f| *f != 0.0), "{style}: no force");
    }
}

/// The walls act while minimizing, as LAMMPS' min_post_force (their energy not in pe): the CG
/// relaxation of lammps-refs' min_cluster_cg deck inside a fix wall/region sphere and above a
/// fix wall/lj93 floor stops as LAMMPS 22 Jul 2025 does (same criterion, 10 iterations, 61
/// force evaluations, final pe -4.37811033299797 and wall energy -0.384589004876596).
#[test]
fn walls_act_while_minimizing() {
    let base = std::fs::read_to_string(root().join("lammps-refs/decks/in.min_cluster_cg")).unwrap();
    let deck = base
        .replace("min_modify   norm inf", "region       cage sphere 0 0 0 3.0 units box\nfix          w all wall/region cage lj126 1.0 1.0 1.5\nfix          z all wall/lj93 zlo -3.0 1.0 1.0 2.5 units box\nmin_modify   norm inf")
        .replace("thermo_style custom step pe fnorm fmax", "thermo_style custom step pe fnorm fmax f_w f_z");
    let run = run_text("min_walls", &deck, &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.as_deref().unwrap();
    assert!(text.contains("Stopping criterion = linesearch alpha is zero") && text.contains("Iterations, force evaluations = 10 61"), "{text}");
    // the minimization's table: the last row of the table before the summary
    let min_table = &text[..text.find("Minimization stats").unwrap()];
    let (names, rows) = table(min_table);
    let last = rows.last().unwrap();
    let col = |n: &str| last[names.iter().position(|c| c == n).unwrap()];
    assert_eq!(col("Step"), 10.0);
    assert!((col("PotEng") - -4.37811033299797).abs() < 1e-13, "{}", col("PotEng"));
    assert!((col("f_w") - -0.384589004876596).abs() < 1e-14, "{}", col("f_w"));
    assert!((col("f_z") - -0.0394712739038538).abs() < 1e-14, "{}", col("f_z"));
}
