//! Scene: cubic particles in Poiseuille flow (the DMHS paper's Fig 7), examples/scenes/cubes.
//! Each test runs the fast variant of one case (`-var case X -var fast 1`) in a scratch copy of
//! the scene folder and checks: A, neutrally buoyant cubes stay clear of both walls; B, light
//! cubes rise to the free surface; C, heavy brittle cubes sink to the bottom and lose bonds.

use dmhs::deck::{run_file, DeckOptions};
use dmhs::sim::Simulation;
use std::path::PathBuf;

/// Water spacing sqrt(m / rho) and cube lattice spacing (gen_cubes.py).
const DL: f64 = 0.0023874672772626646;
const R0: f64 = 2.3e-3;
/// Channel height between the walls (40 water rows) and half the side of a cube (3.5 r0).
const H: f64 = 40.0 * DL;
const HALF: f64 = 3.5 * R0;

fn run_case(case: &str) -> Simulation {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/cubes");
    let tmp = tempfile::tempdir().unwrap();
    for name in ["in.cubes".to_string(), format!("cubes_{case}_fast.data")] {
        std::fs::copy(dir.join(&name), tmp.path().join(&name)).unwrap();
    }
    let opts = DeckOptions {
        vars: vec![("case".into(), vec![case.into()]), ("fast".into(), vec!["1".into()])],
        base_dir: Some(tmp.path().to_path_buf()),
        ..Default::default()
    };
    run_file(&tmp.path().join("in.cubes"), &opts).unwrap_or_else(|f| panic!("{}", f.rendered)).sim
}

/// Centre-of-mass height of each cube (by molecule ID), sorted.
fn cube_heights(sim: &Simulation) -> Vec<f64> {
    let a = &sim.atoms;
    let mut sums: std::collections::BTreeMap<i64, (f64, f64)> = Default::default();
    for i in 0..a.nlocal {
        if a.typ[i] == 2 {
            let e = sums.entry(a.molecule[i]).or_insert((0.0, 0.0));
            e.0 += a.x[i][1];
            e.1 += 1.0;
        }
    }
    let mut ys: Vec<f64> = sums.values().map(|(s, n)| s / n).collect();
    ys.sort_by(f64::total_cmp);
    ys
}

fn max_y(sim: &Simulation, typ: usize) -> f64 {
    let a = &sim.atoms;
    (0..a.nlocal).filter(|&i| a.typ[i] == typ).map(|i| a.x[i][1]).fold(f64::NEG_INFINITY, f64::max)
}

#[test]
fn a_neutrally_buoyant_cubes_stay_suspended() {
    let sim = run_case("A");
    let ys = cube_heights(&sim);
    println!("A: cube heights {ys:?} (channel 0..{H}), bonds {}", sim.topo.bonds.len());
    assert_eq!(ys.len(), 3);
    // started at 0.2, 0.5 and 0.8 H; none has reached a wall (a cube touching a wall has its
    // centre HALF + r0/2 from the wall particles' row)
    for y in &ys {
        assert!(*y > HALF + 2.0 * R0 && *y < H - HALF - 2.0 * R0, "cube at {y} touches a wall");
    }
    assert_eq!(sim.topo.bonds.len(), 3 * 84);
}

#[test]
fn b_light_cubes_float_to_the_free_surface() {
    let sim = run_case("B");
    let ys = cube_heights(&sim);
    // the free surface: the highest water particle (water filled 24 rows, up to 24 dL)
    let surface = max_y(&sim, 1);
    let top = max_y(&sim, 2);
    let start = 0.45 * H;
    println!("B: cube height {ys:?} (start {start}), cube top {top}, water surface {surface}");
    assert!(ys[0] > start + 2.0 * R0, "the cube rose from {start} to {} only", ys[0]);
    assert!(top > surface - R0, "the cube's top {top} is not at the surface {surface}");
}

#[test]
fn c_heavy_brittle_cubes_deposit_and_fracture() {
    let sim = run_case("C");
    let a = &sim.atoms;
    let cy: Vec<f64> = (0..a.nlocal).filter(|&i| a.typ[i] == 2).map(|i| a.x[i][1]).collect();
    let mean = cy.iter().sum::<f64>() / cy.len() as f64;
    let bonds = sim.topo.bonds.len();
    println!("C: mean height of the cube particles {mean} (started at 0.45 H and 0.75 H: {}), bonds {bonds} of 168", 0.6 * H);
    assert!(mean < 0.2 * H, "the cube material is not on the bottom: mean height {mean}");
    assert!(bonds < 168 * 9 / 10, "only {} bonds broke", 168 - bonds);
}
