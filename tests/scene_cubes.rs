//! Scene: cubic particles in Poiseuille flow (the DMHS paper's Fig 7), examples/scenes/cubes.
//! Each test runs the fast variant of one case (`-var case X -var fast 1`) in a scratch copy of
//! the scene folder and checks: A, neutrally buoyant cubes stay clear of both walls; B, a light
//! cube floats at the free surface; C, heavy brittle cubes sink intact and break where one lands
//! on another.

use dmhs::deck::{run_file, DeckOptions};
use dmhs::sim::Simulation;
use std::path::PathBuf;

/// Water spacing sqrt(m / rho), also the cube lattice spacing (gen_cubes.py).
const DL: f64 = 0.0023874672772626646;
const R0: f64 = DL;
/// Channel height between the walls (40 water rows) and half the side of a cube (3.5 r0).
const H: f64 = 40.0 * DL;
const HALF: f64 = 3.5 * R0;

fn run_case(case: &str) -> Simulation {
    run_deck(case, &[])
}

/// The fast variant of `case` with further `-var NAME VALUE` settings.
fn run_deck(case: &str, extra: &[(&str, &str)]) -> Simulation {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/cubes");
    let tmp = tempfile::tempdir().unwrap();
    for name in ["in.cubes".to_string(), format!("cubes_{case}_fast.data"), "cubes_C_land.data".to_string()] {
        std::fs::copy(dir.join(&name), tmp.path().join(&name)).unwrap();
    }
    let mut vars = vec![("case".to_string(), vec![case.to_string()]), ("fast".to_string(), vec!["1".to_string()])];
    vars.extend(extra.iter().map(|(k, v)| (k.to_string(), vec![v.to_string()])));
    let opts = DeckOptions { vars, base_dir: Some(tmp.path().to_path_buf()), ..Default::default() };
    run_file(&tmp.path().join("in.cubes"), &opts).unwrap_or_else(|f| panic!("{}", f.rendered)).sim
}

/// Centre-of-mass height of each cube, sorted.
fn cube_heights(sim: &Simulation) -> Vec<f64> {
    let mut ys = heights_by_molecule(sim);
    ys.sort_by(f64::total_cmp);
    ys
}

fn max_y(sim: &Simulation, typ: usize) -> f64 {
    let a = &sim.state.atoms;
    (0..a.nlocal).filter(|&i| a.typ[i] == typ).map(|i| a.x[i][1]).fold(f64::NEG_INFINITY, f64::max)
}

#[test]
fn a_neutrally_buoyant_cubes_stay_suspended() {
    let sim = run_case("A");
    let ys = cube_heights(&sim);
    println!("A: cube heights {ys:?} (channel 0..{H}), bonds {}", sim.state.topo.bonds.len());
    assert_eq!(ys.len(), 3);
    // started at 0.2, 0.5 and 0.8 H; none has come near a wall (a cube resting on the bottom
    // wall has its centre at HALF)
    for y in &ys {
        assert!(*y > HALF + 2.0 * R0 && *y < H - HALF - 2.0 * R0, "cube at {y} touches a wall");
    }
    assert_eq!(sim.state.topo.bonds.len(), 3 * 84);
    assert_eq!(deposited(&ys), 0, "7A: no neutrally buoyant cube deposits");
}

#[test]
fn b_light_cube_floats_at_the_free_surface() {
    // the cube starts with its centre 1 dL above the top water row (3 of its 7 rows in the
    // water): it settles to its floating depth and stays there, top at the surface; a cube as
    // dense as the water (or denser) would go on sinking
    let sim = run_case("B");
    let ys = cube_heights(&sim);
    let surface = max_y(&sim, 1);
    let top = max_y(&sim, 2);
    let start = 24.5 * DL;
    println!("B: cube centre {:?} (start {start}), cube top {top}, highest water particle {surface}", ys);
    assert!(top > surface - R0, "the cube's top {top} is below the surface {surface}");
    assert!(top < surface + 2.0 * R0, "the cube's top {top} sits too high above the surface {surface}");
    assert!(ys[0] < start, "the cube did not settle into the water");
}

/// Bonds left in each cube (by molecule ID), in molecule order.
fn bonds_per_cube(sim: &Simulation) -> Vec<usize> {
    let a = &sim.state.atoms;
    let mol: std::collections::HashMap<i64, i64> = (0..a.nlocal).map(|i| (a.tag[i], a.molecule[i])).collect();
    let mut n: std::collections::BTreeMap<i64, usize> = Default::default();
    for b in &sim.state.topo.bonds {
        *n.entry(mol[&b.atoms[0]]).or_insert(0) += 1;
    }
    n.values().copied().collect()
}

/// Fig 7C's numbers (README, "Measured against the paper"): cubes deposited (centre below
/// HALF + 1.5 dL: on the bottom, with at most the one water layer that stays under a cube; the
/// same height as strain.py's) and cubes fractured (at least one bond lost of 84).
fn deposited(ys: &[f64]) -> usize {
    ys.iter().filter(|&&y| y < HALF + 1.5 * DL).count()
}

fn fractured(bonds: &[usize]) -> usize {
    bonds.iter().filter(|&&n| n < 84).count()
}

/// Centre-of-mass height of each cube, in molecule order.
fn heights_by_molecule(sim: &Simulation) -> Vec<f64> {
    let a = &sim.state.atoms;
    let mut sums: std::collections::BTreeMap<i64, (f64, f64)> = Default::default();
    for i in 0..a.nlocal {
        if a.typ[i] == 2 {
            let e = sums.entry(a.molecule[i]).or_insert((0.0, 0.0));
            e.0 += a.x[i][1];
            e.1 += 1.0;
        }
    }
    sums.values().map(|(s, n)| s / n).collect()
}

#[test]
fn c_heavy_brittle_cubes_sink_intact_and_deposit() {
    // two cubes start at 0.13 H and 0.42 H: the lower one sinks to the floor, the upper one
    // sinks after it (a water film between the two drains slowly); bonds break beyond 0.1%
    // strain, which sinking never reaches (README: at most 0.01% in the full run)
    let sim = run_case("C");
    let ys = cube_heights(&sim);
    let bonds = bonds_per_cube(&sim);
    let (start_lo, start_hi) = (5.5 * DL, 16.5 * DL);
    println!("C: cube centres {ys:?} (started at {start_lo} and {start_hi}), bonds per cube {bonds:?} of 84 each");
    // on the floor: the wall's top row is at -dL/2, so a cube touching it has its centre at
    // 3.5 r0; one layer of water stays under it (it drains slowly), so allow 1.5 dL more
    assert!(ys[0] < HALF + 1.5 * DL, "the lower cube is not on the bottom: {}", ys[0]);
    assert!(ys[1] < start_hi - DL, "the upper cube did not sink: {}", ys[1]);
    assert_eq!(bonds, vec![84, 84], "a sinking cube lost bonds");
    // Fig 7C in numbers at 0.1 s: 1 of 2 deposited, none fractured (nothing has landed yet)
    assert_eq!((deposited(&ys), fractured(&bonds)), (1, 0));
}

/// With delta-SPH (`-var delta 0.1`, dmhs/sph/delta fourtakas between water particles) the water
/// stays quiet at 8x the time step (2.5e-5 s, 4000 steps for the same 0.1 s): C sinks as at
/// 3.125e-6 s and keeps its bonds; without it, at 2.5e-5 s, the water's sound waves grow and
/// shake the brittle cubes apart (README, "delta-SPH").
#[test]
fn c_with_delta_sph_at_8x_the_time_step() {
    let sim = run_deck("C", &[("delta", "0.1"), ("dt", "2.5e-5"), ("nfast", "4000")]);
    let ys = cube_heights(&sim);
    let bonds = bonds_per_cube(&sim);
    println!("C, delta 0.1, dt 2.5e-5: cube centres {ys:?}, bonds per cube {bonds:?}");
    assert!(ys[0] < HALF + 1.5 * DL, "the lower cube is not on the bottom: {}", ys[0]);
    assert!(ys[1] < 16.5 * DL - DL, "the upper cube did not sink: {}", ys[1]);
    assert_eq!(bonds, vec![84, 84], "a sinking cube lost bonds");
    let without = bonds_per_cube(&run_deck("C", &[("dt", "2.5e-5"), ("nfast", "4000")]));
    println!("C, no delta, dt 2.5e-5: bonds per cube {without:?}");
    assert!(without.iter().sum::<usize>() < 168, "without delta-SPH the bonds held: {without:?}");
}

#[test]
fn c_landing_breaks_bonds() {
    // molecule 1 rests on the bottom wall, molecule 2 hits it at 0.1 m/s (in.cubes `vland`,
    // README); bonds break beyond 0.1% strain
    let sim = run_deck("C", &[("land", "1")]);
    let ys = heights_by_molecule(&sim);
    let bonds = bonds_per_cube(&sim);
    println!("C landing: cube centres {ys:?}, bonds per cube {bonds:?} of 84 each");
    assert!(ys[0] < HALF + 0.5 * DL, "the lower cube left the bottom: {}", ys[0]);
    assert!(ys[1] < ys[0] + 7.0 * R0 + 0.5 * DL, "the landing cube bounced off: {}", ys[1]);
    let lost = 168 - bonds.iter().sum::<usize>();
    assert!(lost >= 30, "the landing broke only {lost} bonds");
    // Fig 7C's "the cubes above hit ... those underneath and, in some cases, break them": the
    // landing fractures both cubes (48 and 51 bonds left); the lower one stays deposited
    assert_eq!(fractured(&bonds), 2, "cubes fractured: {bonds:?}");
    assert_eq!(deposited(&ys), 1);
}
