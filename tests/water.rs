//! Water diffusion, swelling, wet adhesion and Stokes drag (docs/multihybrid.md, "Water diffusion
//! and swelling" and "Drag"):
//!
//! * 1D Fickian diffusion between two half-spaces against the erf solution (examples/diffusion/in.fick);
//! * the total water mass sum w_i is conserved to round-off, also while SPH densities change;
//! * swelling: the radius follows V = V0 + w/rhow in 2D and 3D;
//! * dmhs/lj/wet: the adhesion force falls linearly with c and vanishes at the threshold;
//! * fix dmhs/stokes: terminal velocity F / (6 pi mu r);
//! * restart keeps the water field; moving SPH walls (velocity set + setforce) carry their velocity.

use dmhs::tools::analytic::heat_half_spaces;
use dmhs::deck::{run_text, DeckOptions};
use dmhs::sim::Simulation;
use dmhs::engine::water::{conc, water};
use std::f64::consts::PI;

fn run(deck: &str, vars: &[(&str, &str)]) -> Simulation {
    let opts = DeckOptions { vars: vars.iter().map(|(k, v)| (k.to_string(), vec![v.to_string()])).collect(), ..Default::default() };
    run_text("water-test", deck, &opts).map_err(|f| f.rendered).unwrap().sim
}

/// Build a deck's simulation (no run) and set it up for stepping.
fn start(deck: &str) -> Simulation {
    let mut sim = run(deck, &[]);
    sim.init_run().unwrap();
    sim.setup(true).unwrap();
    sim
}

fn total_water(sim: &Simulation) -> f64 {
    water(&sim.state.atoms).unwrap()[..sim.state.atoms.nlocal].iter().sum()
}

fn index_of(sim: &Simulation, tag: i64) -> usize {
    (0..sim.state.atoms.nlocal).find(|&i| sim.state.atoms.tag[i] == tag).unwrap()
}

/// Max and RMS of c - c_exact over the strip for the Fick deck at resolution N.
fn fick_errors(n: usize) -> (f64, f64, f64) {
    let deck = include_str!("../examples/diffusion/in.fick");
    let ns = n.to_string();
    let sim = run(deck, &[("N", &ns)]);
    let t = sim.state.step as f64 * sim.state.dt;
    let a = &sim.state.atoms;
    let (mut max, mut sq) = (0.0f64, 0.0);
    for i in 0..a.nlocal {
        let e = conc(a, &sim.state.type_mass, i) - heat_half_spaces(a.x[i][0], t, 1.0e-3, 1.0, 0.0);
        max = max.max(e.abs());
        sq += e * e;
    }
    (max, (sq / a.nlocal as f64).sqrt(), t)
}

#[test]
fn fick_diffusion_matches_erf() {
    let (max50, rms50, t) = fick_errors(50);
    let (max100, rms100, _) = fick_errors(100);
    assert!((t - 2.5).abs() < 0.03, "{t}");
    // the same Brookshaw Laplacian as sph/heatconduction: the same numbers as the heat case
    assert!((max50 - 2.5852e-3).abs() < 1e-6, "{max50:e}");
    assert!((max100 - 3.6071e-4).abs() < 1e-7, "{max100:e}");
    assert!(rms100 < 2e-4 && rms100 < 0.2 * rms50, "{rms50:e} {rms100:e}");
    eprintln!("fick: N=50 max {max50:.4e} L2(rms) {rms50:.4e}; N=100 max {max100:.4e} L2(rms) {rms100:.4e}");
}

/// A periodic 2D box of two fluids with different masses and densities, random concentrations,
/// diffusing while moving under Tait pressure (densities change every step).
const MIXED: &str = "
dimension 2
units si
atom_style sph
boundary p p p
atom_modify map array
region box block 0 0.02 0 0.02 -0.0005 0.0005 units box
create_box 2 box
lattice sq 0.001
create_atoms 1 box
region heavy block 0.011 0.019 INF INF INF INF units box
set region heavy type 2
";

fn mixed_deck(moving: bool) -> String {
    let fluid = if moving {
        "pair_style hybrid/overlay sph/taitwater dmhs/sph/diffusion\n\
         pair_coeff 1 2 sph/taitwater 1000 1.0 0.1 0.0026\npair_coeff 1 1 sph/taitwater 1000 1.0 0.1 0.0026\npair_coeff 2 2 sph/taitwater 1800 1.0 0.1 0.0026\n\
         pair_coeff 1 1 dmhs/sph/diffusion 1e-6 0.0026\npair_coeff 1 2 dmhs/sph/diffusion 3e-7 0.0026\npair_coeff 2 2 dmhs/sph/diffusion 2e-6 0.0026\n\
         fix f all sph\n"
    } else {
        "pair_style dmhs/sph/diffusion\npair_coeff 1 1 1e-6 0.0026\npair_coeff 1 2 3e-7 0.0026\npair_coeff 2 2 2e-6 0.0026\n"
    };
    format!(
        "{MIXED}\nmass 1 1.0e-3\nmass 2 1.8e-3\nset type 1 sph/rho 1000\nset type 2 sph/rho 1800\n\
         velocity all create 2e15 4928 dist gaussian\n{fluid}fix w all dmhs/diffusion\n\
         set type 1 dmhs/conc 0.9\nset type 2 dmhs/conc 0.05\nset region box dmhs/conc 0.3\n\
         region blob block 0 0.008 0 0.02 INF INF units box\nset region blob dmhs/conc 1.0\n\
         neighbor 0.0005 bin\ntimestep 1e-4\n"
    )
}

#[test]
fn water_mass_is_conserved_to_round_off() {
    for moving in [false, true] {
        let mut sim = start(&mixed_deck(moving));
        let w0 = total_water(&sim);
        let rho0: Vec<f64> = sim.state.atoms.rho[..sim.state.atoms.nlocal].to_vec();
        let c0: Vec<f64> = (0..sim.state.atoms.nlocal).map(|i| conc(&sim.state.atoms, &sim.state.type_mass, i)).collect();
        for _ in 0..200 {
            sim.step_once(false).unwrap();
        }
        let w1 = total_water(&sim);
        let rel = (w1 - w0).abs() / w0;
        let moved = (0..sim.state.atoms.nlocal).map(|i| (sim.state.atoms.rho[i] - rho0[i]).abs()).fold(0.0, f64::max);
        let changed = (0..sim.state.atoms.nlocal).map(|i| (conc(&sim.state.atoms, &sim.state.type_mass, i) - c0[i]).abs()).fold(0.0, f64::max);
        eprintln!("moving={moving}: sum w {w0:e} -> {w1:e}, relative change {rel:e}; max |drho| {moved:e}, max |dc| {changed:e}");
        assert!(changed > 1e-2, "water must move: {changed}");
        if moving {
            assert!(moved > 1e-3, "densities must change: {moved}");
        }
        assert!(rel < 1e-13, "sum w drifts by {rel:e}");
    }
}

#[test]
fn swelling_radius_follows_the_absorbed_water() {
    for dim in [2usize, 3] {
        let z = if dim == 2 { "-0.5 0.5" } else { "-5 5" };
        let deck = format!(
            "dimension {dim}\nunits si\natom_style hybrid sph sphere\nboundary f f p\n\
             region box block -5 5 -5 5 {z} units box\ncreate_box 2 box\n\
             create_atoms 1 single 0 0 0 units box\ncreate_atoms 2 single 1 0 0 units box\n\
             mass * 1.0\nset group all sph/rho 1.0\nset group all diameter 1.2\n\
             pair_style dmhs/sph/diffusion\npair_coeff * * 0.05 1.5\n\
             fix w all dmhs/diffusion\nfix s all dmhs/swell 2.0\n\
             set atom 2 dmhs/conc 1.0\ntimestep 0.01\n"
        );
        let mut sim = start(&deck);
        let r0 = 0.6;
        let v0 = if dim == 3 { 4.0 / 3.0 * PI * r0 * r0 * r0 } else { PI * r0 * r0 };
        let mut grew = 0.0;
        for _ in 0..50 {
            sim.step_once(false).unwrap();
            for tag in [1, 2] {
                let i = index_of(&sim, tag);
                let w = water(&sim.state.atoms).unwrap()[i];
                let v = v0 + w / 2.0;
                let r = if dim == 3 { (3.0 * v / (4.0 * PI)).cbrt() } else { (v / PI).sqrt() };
                assert!((sim.state.atoms.radius[i] - r).abs() < 1e-15, "dim {dim} atom {tag}: {} vs {r}", sim.state.atoms.radius[i]);
                if tag == 1 {
                    grew = sim.state.atoms.radius[i] - r0;
                }
            }
        }
        assert!(grew > 1e-3, "the dry particle absorbs water and swells: {grew}");
        eprintln!("swell dim {dim}: dry particle radius {r0} -> {}", r0 + grew);
    }
}

/// Two particles at distance `r` with concentrations c1, c2: x-force on atom 1.
fn wet_force(style: &str, r: f64, c1: f64, c2: f64) -> f64 {
    let deck = format!(
        "units si\natom_style hybrid sph sphere\nboundary f f f\n\
         region box block -4e-4 4e-4 -4e-4 4e-4 -4e-4 4e-4 units box\ncreate_box 2 box\n\
         create_atoms 1 single 0 0 0 units box\ncreate_atoms 2 single {r} 0 0 units box\n\
         mass * 1e-10\nset group all sph/rho 1800\n\
         pair_style {style}\npair_coeff 1 1 7e-11 5e-5 0.5\npair_coeff 2 2 7e-11 5e-5 0.5\npair_coeff 1 2 5e-10 5e-5 0.5\n\
         fix w all dmhs/diffusion\nset atom 1 dmhs/conc {c1}\nset atom 2 dmhs/conc {c2}\nneighbor 1e-5 bin\n"
    );
    let sim = start(&deck);
    sim.state.atoms.f[index_of(&sim, 1)][0]
}

fn lj_force(eps: f64, sigma: f64, r: f64) -> f64 {
    let sr6 = (sigma / r).powi(6);
    24.0 * eps * (2.0 * sr6 * sr6 - sr6) / r
}

#[test]
fn wet_adhesion_falls_linearly_to_zero_at_the_threshold() {
    let r = 6.5e-5; // beyond the LJ minimum (5.61e-5): adhesion
    let dry = -lj_force(5e-10, 5e-5, r); // force on atom 1 (at -x of atom 2): pulled to +x
    assert!(dry > 0.0);
    let mut rows = vec![];
    for c in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6] {
        let f = wet_force("dmhs/lj/wet 1.25e-4", r, c, 0.0);
        let expected = dry * (1.0 - c / 0.5).max(0.0);
        assert!((f - expected).abs() <= 1e-12 * dry, "c = {c}: {f:e} vs {expected:e}");
        rows.push((c, f));
    }
    assert_eq!(rows[5].1, 0.0);
    eprintln!("wet adhesion (surface pair eps 5e-10, r 6.5e-5): {rows:?}");
    // conc mean: the pair's c is the mean, so c1 = 0.5 next to a dry particle halves the adhesion
    let f = wet_force("dmhs/lj/wet 1.25e-4 conc mean", r, 0.5, 0.0);
    assert!((f - 0.5 * dry).abs() <= 1e-12 * dry);
    // the repulsive core is kept whole by default, weakened with `scale all`
    let rc = 4.8e-5;
    let core = -lj_force(5e-10, 5e-5, rc);
    assert!(core < 0.0);
    assert!((wet_force("dmhs/lj/wet 1.25e-4", rc, 0.5, 0.0) - core).abs() <= 1e-12 * core.abs());
    assert_eq!(wet_force("dmhs/lj/wet 1.25e-4 scale all", rc, 0.5, 0.0), 0.0);
    assert!((wet_force("dmhs/lj/wet 1.25e-4 scale all", rc, 0.25, 0.0) - 0.5 * core).abs() <= 1e-12 * core.abs());
}

#[test]
fn wet_adhesion_follows_swelling() {
    // particle 1 holds water: it swells by g; with `swell` the LJ acts between the swollen
    // surfaces, so its force at distance r equals the dry force at r - g (and lambda from c)
    let deck = "units si\natom_style hybrid sph sphere\nboundary f f f\n\
         region box block -4e-4 4e-4 -4e-4 4e-4 -4e-4 4e-4 units box\ncreate_box 2 box\n\
         create_atoms 1 single 0 0 0 units box\ncreate_atoms 2 single 7e-5 0 0 units box\n\
         mass * 1e-10\nset group all sph/rho 1800\nset group all diameter 4.7e-5\n\
         pair_style dmhs/lj/wet 1.25e-4 swell 1e-5\npair_coeff * * 7e-11 5e-5 0.5\n\
         fix w all dmhs/diffusion\nfix s all dmhs/swell 1.0\nset atom 1 dmhs/conc 0.2\nneighbor 1e-5 bin\n";
    let sim = start(deck);
    let i = index_of(&sim, 1);
    let w = water(&sim.state.atoms).unwrap()[i];
    let r0: f64 = 2.35e-5;
    let v = 4.0 / 3.0 * PI * r0.powi(3) + w / 1.0;
    let g = (3.0 * v / (4.0 * PI)).cbrt() - r0;
    assert!(g > 1e-7 && g < 1e-5, "{g}");
    let f = sim.state.atoms.f[i][0];
    let expected = -lj_force(7e-11, 5e-5, 7e-5 - g) * (1.0 - 0.2 / 0.5);
    assert!((f - expected).abs() <= 1e-9 * expected.abs(), "{f:e} vs {expected:e} (growth {g:e})");
}

#[test]
fn stokes_drag_gives_the_terminal_velocity() {
    // a sphere of radius 1e-5 m, density 1000, in water (mu 1e-3) under a body force: the
    // velocity relaxes (time m/gamma = 2.2e-5 s) to F / (6 pi mu r)
    let (r, mu, g): (f64, f64, f64) = (1e-5, 1e-3, 9.81);
    for body in ["fix g all gravity 9.81 vector 0 -1 0", "fix g all addforce 0 -4.108908e-11 0"] {
        let deck = format!(
            "units si\natom_style sphere\nboundary f f f\nregion box block -1 1 -1 1 -1 1 units box\ncreate_box 1 box\n\
             create_atoms 1 single 0 0 0 units box\nset atom 1 diameter {}\nset atom 1 density 1000\n\
             fix 1 all nve/sphere\n{body}\nfix d all dmhs/stokes {mu}\ntimestep 1e-7\n",
            2.0 * r
        );
        let mut sim = start(&deck);
        let m = sim.state.atoms.rmass[0];
        let force = if body.contains("gravity") { m * g } else { 4.108908e-11 };
        for _ in 0..5000 {
            sim.step_once(false).unwrap();
        }
        let vt = force / (6.0 * PI * mu * r);
        let v = -sim.state.atoms.v[0][1];
        eprintln!("stokes ({body}): v {v:e}, F/(6 pi mu r) {vt:e}, relative {:e}", (v - vt).abs() / vt);
        assert!((v - vt).abs() < 1e-9 * vt, "{v:e} vs {vt:e}");
    }
}

#[test]
fn restart_keeps_the_water_field() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("w.restart");
    let deck = format!("{}\nrun 20\nwrite_restart {}\n", mixed_deck(false), file.display());
    let sim = run(&deck, &[]);
    let before: Vec<(i64, f64)> = (0..sim.state.atoms.nlocal).map(|i| (sim.state.atoms.tag[i], water(&sim.state.atoms).unwrap()[i])).collect();
    let deck2 = format!(
        "read_restart {}\npair_style dmhs/sph/diffusion\npair_coeff 1 1 1e-6 0.0026\npair_coeff 1 2 3e-7 0.0026\npair_coeff 2 2 2e-6 0.0026\nfix w all dmhs/diffusion\n",
        file.display()
    );
    let sim2 = run(&deck2, &[]);
    for (tag, w) in before {
        let i = index_of(&sim2, tag);
        assert_eq!(water(&sim2.state.atoms).unwrap()[i], w);
    }
}

#[test]
fn moving_sph_wall_carries_its_velocity() {
    // the paper's cleaning scene drives the water with a moving upper wall: wall particles get
    // `velocity set`, fix setforce 0 and fix sph, so they move at v_W and their velocity
    // estimate (what the SPH styles read) is v_W
    let deck = "dimension 2\nunits si\natom_style sph\nboundary p f p\natom_modify map array\n\
         region box block 0 0.01 0 0.006 -0.0005 0.0005 units box\ncreate_box 2 box\nlattice sq 0.0005\n\
         create_atoms 1 box\nregion top block INF INF 0.005 INF INF INF units box\ngroup wall region top\nset group wall type 2\n\
         mass * 2.5e-4\nset group all sph/rho 1000\n\
         pair_style sph/taitwater/morris\npair_coeff * * 1000 1.0 0.1 0.0013\n\
         velocity wall set 2e-4 0 0 units box\nfix f all sph\nfix s wall setforce 0 0 0\nneighbor 0.0002 bin\ntimestep 1e-5\n";
    let mut sim = start(deck);
    let bit = sim.state.groups.bit("wall").unwrap();
    let x0: Vec<f64> = (0..sim.state.atoms.nlocal).map(|i| sim.state.atoms.x[i][0]).collect();
    let tags: Vec<i64> = sim.state.atoms.tag[..sim.state.atoms.nlocal].to_vec();
    for _ in 0..100 {
        sim.step_once(false).unwrap();
    }
    let a = &sim.state.atoms;
    let mut fluid_vx = 0.0f64;
    let mut walls = 0;
    for i in 0..a.nlocal {
        let k = tags.iter().position(|&t| t == a.tag[i]).unwrap();
        if a.mask[i] & bit != 0 {
            walls += 1;
            assert_eq!(a.v[i], [2e-4, 0.0, 0.0]);
            assert_eq!(a.vest[i], [2e-4, 0.0, 0.0]);
            let dx = (a.x[i][0] - x0[k]).rem_euclid(0.01);
            assert!((dx - 2e-4 * 100.0 * 1e-5).abs() < 1e-15, "{dx}");
        } else {
            fluid_vx = fluid_vx.max(a.v[i][0]);
        }
    }
    assert!(walls > 0);
    assert!(fluid_vx > 1e-5, "the moving wall drags the fluid: {fluid_vx}");
}

#[test]
fn bad_water_decks_name_the_problem() {
    let head = "units si\natom_style sph\nregion box block 0 1 0 1 0 1 units box\ncreate_box 1 box\ncreate_atoms 1 single 0.5 0.5 0.5 units box\n";
    let cases = [
        ("set atom 1 dmhs/conc 0.5\n", "6:12", "mass of atom type 1 is not set"),
        ("mass 1 1\nset atom 1 sph/rho 1\npair_style dmhs/sph/diffusion\npair_coeff 1 1 -1 0.1\n", "9:16", "must be >= 0"),
        ("mass 1 1\nset atom 1 sph/rho 1\nfix s all dmhs/swell 1\n", "8:11", "needs an atom style with radii"),
        ("mass 1 1\nset atom 1 sph/rho 1\npair_style dmhs/sph/diffusion\npair_coeff 1 1 1 0.1\nrun 1\n", "10:1", "no particle carries water"),
        ("pair_style dmhs/lj/wet 1.0 conc median\n", "6:33", "expected one of: max, mean"),
        ("pair_style dmhs/lj/wet 1.0\npair_coeff 1 1 1 1 0\n", "7:20", "cth"),
        ("fix d all dmhs/stokes 1e-3\n", "6:11", "needs an atom style with radii"),
    ];
    for (tail, at, msg) in cases {
        let deck = format!("{head}{tail}");
        let err = match run_text("bad.in", &deck, &DeckOptions::default()) {
            Ok(_) => panic!("accepted:\n{deck}"),
            Err(f) => f.rendered,
        };
        assert!(err.contains(&format!("bad.in:{at}")) && err.contains(msg), "{tail}:\n{err}");
    }
}

#[test]
fn water_fields_reach_dumps_and_reductions() {
    let dir = tempfile::tempdir().unwrap();
    let dump = dir.path().join("w.dump");
    let deck = format!(
        "{}\ncompute c all property/atom conc water dwater\ncompute s all reduce sum c_c[2]\n\
         dump d all custom 10 {} id conc water dwater\nthermo_style custom step c_s f_w\nrun 10\n",
        mixed_deck(false),
        dump.display()
    );
    let sim = run(&deck, &[]);
    let text = std::fs::read_to_string(&dump).unwrap();
    assert!(text.contains("ITEM: ATOMS id conc water dwater"), "{}", &text[..300.min(text.len())]);
    let last = text.rsplit("ITEM: ATOMS").next().unwrap();
    let rows: Vec<Vec<f64>> = last.lines().skip(1).map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), sim.state.atoms.nlocal);
    for r in &rows {
        let i = index_of(&sim, r[0] as i64);
        // dump custom writes %g (6 significant digits)
        let w = water(&sim.state.atoms).unwrap()[i];
        assert!((r[2] - w).abs() <= 1e-5 * w.abs(), "{} vs {w}", r[2]);
        let c = conc(&sim.state.atoms, &sim.state.type_mass, i);
        assert!((r[1] - c).abs() <= 1e-5 * c.abs(), "{} vs {c}", r[1]);
    }
    assert!(rows.iter().any(|r| r[3] != 0.0), "rates are dumped");
}

#[test]
fn dry_wet_lj_is_lj_cut() {
    // without water, dmhs/lj/wet is lj/cut (checked against LAMMPS in lammps-refs): same forces,
    // energy, pressure and trajectory on a periodic LJ liquid, with pair_modify shift
    let deck = |pair: &str, coeff: &str| {
        format!(
            "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 2 box\ncreate_atoms 1 box\n\
             region half block 0 2 INF INF INF INF\nset region half type 2\nmass * 1.0\nvelocity all create 1.5 87287 loop geom\n\
             pair_style {pair}\npair_coeff 1 1 {coeff}\npair_coeff 2 2 1.2 0.9 {}\npair_modify shift yes\n\
             neighbor 0.3 bin\nfix 1 all nve\nthermo_style custom step pe press\nrun 100\n",
            if pair.starts_with("dmhs") { "0.5 2.5" } else { "2.5" }
        )
    };
    let mut a = run(&deck("lj/cut 2.5", "1.0 1.0"), &[]);
    let mut b = run(&deck("dmhs/lj/wet 2.5", "1.0 1.0 0.5"), &[]);
    let (ea, eb) = (a.thermo_values(), b.thermo_values());
    let (ea, eb) = (ea.unwrap(), eb.unwrap());
    for k in 0..ea.len() {
        assert!((ea[k] - eb[k]).abs() <= 1e-9 * ea[k].abs().max(1.0), "thermo column {k}: {} vs {}", ea[k], eb[k]);
    }
    for i in 0..a.state.atoms.nlocal {
        let j = index_of(&b, a.state.atoms.tag[i]);
        for d in 0..3 {
            assert!((a.state.atoms.x[i][d] - b.state.atoms.x[j][d]).abs() < 1e-9, "atom {}", a.state.atoms.tag[i]);
        }
    }
}

#[test]
fn pair_rate_is_eq_26() {
    // two particles of different mass and density: dw_1/dt = V1 V2 2D (c1 - c2) (1/r) dW/dr,
    // dw_2/dt = -dw_1/dt (Lucy kernel, 3D)
    let deck = "units si\natom_style sph\nregion box block -1 1 -1 1 -1 1 units box\ncreate_box 2 box\n\
         create_atoms 1 single 0 0 0 units box\ncreate_atoms 2 single 0.03 0.04 0 units box\n\
         mass 1 2.0\nmass 2 3.0\nset type 1 sph/rho 1000\nset type 2 sph/rho 1500\n\
         pair_style dmhs/sph/diffusion\npair_coeff * * 0.7 0.1\nfix w all dmhs/diffusion\n\
         set atom 1 dmhs/conc 0.8\nset atom 2 dmhs/conc 0.1\n";
    let sim = start(deck);
    let (i, j) = (index_of(&sim, 1), index_of(&sim, 2));
    let dw = sim.state.atoms.extra[sim.state.atoms.field(dmhs::engine::fields::WATER_RATE).unwrap()].data.clone();
    let wfd = dmhs::models::pair::sph::Kernel::Lucy.wfd(0.05 * 0.05, 0.1, true);
    let expected = (2.0 / 1000.0) * (3.0 / 1500.0) * 2.0 * 0.7 * (0.8 - 0.1) * wfd;
    assert!(expected < 0.0);
    assert!((dw[i] - expected).abs() <= 1e-14 * expected.abs(), "{} vs {expected}", dw[i]);
    assert_eq!(dw[j], -dw[i]);
}

#[test]
fn restart_keeps_the_dry_size_of_swollen_particles() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("s.restart");
    let setup = "dimension 2\nunits si\natom_style hybrid sph sphere\nboundary f f p\n\
         region box block -5 5 -5 5 -0.5 0.5 units box\ncreate_box 2 box\n\
         create_atoms 1 single 0 0 0 units box\ncreate_atoms 2 single 1 0 0 units box\n\
         mass * 1.0\nset group all sph/rho 1.0\nset group all diameter 1.2\n";
    let fixes = "pair_style dmhs/sph/diffusion\npair_coeff * * 0.05 1.5\nfix w all dmhs/diffusion\nfix s all dmhs/swell 2.0\ntimestep 0.01\n";
    let a = run(&format!("{setup}{fixes}set atom 2 dmhs/conc 1.0\nrun 30\nwrite_restart {}\nrun 30\n", file.display()), &[]);
    let b = run(&format!("read_restart {}\n{fixes}run 30\n", file.display()), &[]);
    for tag in [1, 2] {
        let (i, j) = (index_of(&a, tag), index_of(&b, tag));
        assert_eq!(a.state.atoms.radius[i], b.state.atoms.radius[j], "atom {tag}");
        assert_eq!(water(&a.state.atoms).unwrap()[i], water(&b.state.atoms).unwrap()[j]);
    }
    assert!(a.state.atoms.radius[index_of(&a, 1)] > 0.6);
}

#[test]
fn diffusion_reports_its_time_step_limit() {
    // D dt/dx^2 = 0.7 is stable and 0.8 unstable on the Fick deck (h = 2.6 dx): the limit
    // 0.05 h^2/D keeps a factor of about 2 below that
    let deck = include_str!("../examples/diffusion/in.fick");
    let sim = run(&deck.replace("run          ${nsteps}", ""), &[]);
    let limits = dmhs::sim::stability::limits(&sim, false);
    let l = limits.iter().find(|l| l.model == "water diffusion").expect("a diffusion limit");
    let (h, d) = (0.026, 1e-3);
    assert!((l.dt_max - 0.05 * h * h / d).abs() < 1e-15, "{l:?}");
    let stable = |cdt: &str| {
        let s = run(deck, &[("N", "50"), ("cdt", cdt), ("tend", "40")]);
        (0..s.state.atoms.nlocal).all(|i| conc(&s.state.atoms, &s.state.type_mass, i).abs() <= 1.0 + 1e-9)
    };
    assert!(stable("0.7"));
    assert!(!stable("0.8"));
}
