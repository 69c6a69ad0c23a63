//! fix momentum and the group functions angmom(), omega(), inertia() and torque(): the thermo
//! table of lammps-refs/decks/in.fix_momentum_rigid against LAMMPS' (stored, and LAMMPS run now),
//! the same table against the rigid-body algebra, the LJ deck in.fix_momentum zeroing the x and
//! z momentum, and located errors (of velocity set with variables too, which the rigid deck uses). (tests/lammps_parity.rs compares both decks' atoms.)

use dmhs::deck::{run_file, run_text, DeckOptions};

mod common;
mod thermo_tables;
use thermo_tables::{root, table};

thermo_tables::thermo_table_tests!(["fix_momentum_rigid"]);

fn deck_table(name: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let deck = root().join("lammps-refs/decks").join(format!("in.{name}"));
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(deck.parent().unwrap().to_path_buf()), ..Default::default() };
    let run = run_file(&deck, &opts).unwrap_or_else(|f| panic!("{name}: {}", f.rendered));
    table(run.sim.out.captured.as_deref().unwrap())
}

/// Four atoms (masses 1-4) moving as a rigid body with omega (0.1, 0.2, 0.3) and a drift: at
/// step 0 omega() returns the rotation and angmom() = inertia() omega; after fix momentum
/// `angular rescale` (steps 2 and 4) the angular momentum is gone, the kinetic energy is the one
/// before, and the drift keeps its direction, scaled to carry all of it.
#[test]
fn rigid_rotation_is_removed_and_energy_kept() {
    let (names, rows) = deck_table("fix_momentum_rigid");
    let col = |n: &str| names.iter().position(|c| c == n).unwrap_or_else(|| panic!("no column {n}"));
    let r0 = &rows[0];
    let get = |r: &[f64], n: &str| r[col(n)];
    let w = [0.1, 0.2, 0.3];
    for (k, n) in ["v_wx", "v_wy", "v_wz"].iter().enumerate() {
        assert!((get(r0, n) - w[k]).abs() < 1e-14, "{n} = {}", get(r0, n));
    }
    // inertia() holds the off-diagonal entries with LAMMPS' sign: I = sum m (r.r 1 - r r^T)
    let i = [
        [get(r0, "v_ixx"), get(r0, "v_ixy"), get(r0, "v_ixz")],
        [get(r0, "v_ixy"), get(r0, "v_iyy"), get(r0, "v_iyz")],
        [get(r0, "v_ixz"), get(r0, "v_iyz"), get(r0, "v_izz")],
    ];
    for (k, n) in ["v_lx", "v_ly", "v_lz"].iter().enumerate() {
        let l = i[k][0] * w[0] + i[k][1] * w[1] + i[k][2] * w[2];
        assert!((get(r0, n) - l).abs() < 1e-12, "{n} = {} but I w = {l}", get(r0, n));
    }
    // fix nve moves the atoms along their constant velocities, so by step 2 the motion is no
    // longer rigid; what the removal leaves must still be free of angular momentum, carry the
    // energy before and keep the centre of mass moving along the drift (v -= omega x r moves no
    // momentum; rescale scales it)
    let ke0 = get(r0, "v_kk");
    let drift0 = [get(r0, "v_ux"), get(r0, "v_uy"), get(r0, "v_uz")];
    for r in &rows[2..] {
        for n in ["v_lx", "v_ly", "v_lz"] {
            assert!(get(r, n).abs() < 1e-12, "step {}: {n} = {}", r[0], get(r, n));
        }
        assert!((get(r, "v_kk") - ke0).abs() < 1e-13, "step {}: ke {} before {ke0}", r[0], get(r, "v_kk"));
        let u = [get(r, "v_ux"), get(r, "v_uy"), get(r, "v_uz")];
        let scale = u[0] / drift0[0];
        assert!(scale > 1.0, "step {}: rescale put the removed rotation's energy into the drift", r[0]);
        for d in 0..3 {
            assert!((u[d] - scale * drift0[d]).abs() < 1e-14, "step {}: drift turned", r[0]);
        }
    }
}

/// The LJ deck zeroes the x and z momentum of all atoms every 10 steps and the angular
/// momentum of the upper half (with rescale) every 25: at printed steps that only the first
/// touches (20, 40, 60, 80, 120, ...) vcm x and z are round-off while the y drift the forces
/// build is kept; at steps both touch (100, 200, ...) the upper half has no angular momentum.
#[test]
fn linear_flags_zero_only_their_components() {
    let (names, rows) = deck_table("fix_momentum");
    let col = |n: &str| names.iter().position(|c| c == n).unwrap();
    let (mut alone, mut both) = (0, 0);
    for r in &rows[1..] {
        if r[0] as i64 % 25 != 0 {
            alone += 1;
            assert!(r[col("v_vx")].abs() < 1e-13 && r[col("v_vz")].abs() < 1e-13, "step {}: vcm x {} z {}", r[0], r[col("v_vx")], r[col("v_vz")]);
        } else {
            both += 1;
            for n in ["v_lx", "v_ly", "v_lz"] {
                assert!(r[col(n)].abs() < 1e-11, "step {}: angmom(upper) {n} {}", r[0], r[col(n)]);
            }
        }
    }
    assert_eq!((alone, both), (16, 4));
    let last = rows.last().unwrap();
    assert!(last[col("v_vy")].abs() > 1e-3, "the y momentum the forces build is kept: {}", last[col("v_vy")]);
}

/// torque(g,dim): the sum of (r - xcm) x f; two atoms at x = -1 and 1 pushed along -y and +y.
#[test]
fn torque_of_a_couple() {
    let deck = "units lj\natom_style atomic\nboundary f f f\nregion box block -5 5 -5 5 -5 5\ncreate_box 1 box\n\
        create_atoms 1 single -1 0 0\ncreate_atoms 1 single 1 0 0\nmass 1 1.0\nvariable fy atom 0.5*x\n\
        fix push all addforce 0.0 v_fy 0.0\nvariable tz equal torque(all,z)\nvariable tx equal torque(all,x)\n\
        thermo_style custom step v_tz v_tx\nthermo 1\nrun 1\n";
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = run_text("torque", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let (_, rows) = table(run.sim.out.captured.as_deref().unwrap());
    // r x f: (-1)(-0.5) + (1)(0.5) = 1 about z, nothing about x
    assert!((rows[1][1] - 1.0).abs() < 1e-15 && rows[1][2] == 0.0, "{:?}", rows[1]);
}

#[test]
fn errors_are_located() {
    let base = "units lj\natom_style atomic\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 single 1 1 1\nmass 1 1.0\n";
    common::assert_located_errors(
        base,
        &[
            ("fix m all momentum 0 linear 1 1 1\n", "N (steps between removals)"),
            ("fix m all momentum 10\n", "requires `linear` or `angular`"),
            ("fix m all momentum 10 rescale\n", "requires `linear` or `angular`"),
            ("fix m all momentum 10 linear 2 0 0\n", "xflag"),
            ("fix m all momentum 10 linear 1 1\n", "zflag"),
            ("fix m all momentum 10 angular spin\n", "unknown keyword `spin`"),
            ("group none empty\nfix m none momentum 10 angular\n", "the group has no atoms"),
            ("variable w equal inertia(all,xw)\nprint ${w}\n", "inertia() needs xx, yy, zz, xy, yz or xz"),
            ("variable w equal angmom(all,q)\nprint ${w}\n", "angmom() needs a dimension x, y or z"),
            ("velocity all set v_nothere 0 0\n", "Variable name for velocity set does not exist"),
            ("variable s string hello\nvelocity all set v_s 0 0\n", "Variable for velocity set is invalid style"),
            ("variable s atom 1/0\nvelocity all set 0 v_s 0\n", "Divide by 0"),
        ],
    );
}
