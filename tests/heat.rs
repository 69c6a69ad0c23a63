//! Heat conduction, phase change and cooling (paper Eqs 22-25): pair dmhs/heatconduction,
//! fix dmhs/phase, fix dmhs/cooling, compute dmhs/phase/atom.
//!
//! Quick cases run here (about a second in all, release build). The Stefan problem at double
//! resolution is `#[ignore]`d: `cargo test --release --test heat -- --ignored`.

use dmhs::deck::{run_file, run_text, DeckOptions, DeckRun};
use std::path::Path;

fn opts(vars: &[(&str, &str)]) -> DeckOptions {
    DeckOptions { capture_text: true, vars: vars.iter().map(|(k, v)| (k.to_string(), vec![v.to_string()])).collect(), ..Default::default() }
}

fn run(name: &str, deck: &str) -> DeckRun {
    run_text(name, deck, &opts(&[])).unwrap_or_else(|e| panic!("{}", e.rendered))
}

/// The thermo rows of every run: (header words, rows).
fn thermo(r: &DeckRun) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = r.sim.out.captured.as_ref().unwrap();
    let mut header = vec![];
    let mut rows = vec![];
    let mut inside = false;
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        if w.first() == Some(&"Step") {
            header = w.iter().map(|s| s.to_string()).collect();
            inside = true;
        } else if line.starts_with("Loop time") {
            inside = false;
        } else if inside && w.len() == header.len() {
            if let Ok(v) = w.iter().map(|s| s.parse::<f64>()).collect::<Result<Vec<_>, _>>() {
                rows.push(v);
            }
        }
    }
    (header, rows)
}

fn col(h: &[String], name: &str) -> usize {
    h.iter().position(|s| s == name).unwrap_or_else(|| panic!("no column {name} in {h:?}"))
}

/// Sum of esph (the particles' energies m e) over all atoms.
fn total_energy(r: &DeckRun) -> f64 {
    let s = &r.sim;
    s.state.atoms.esph[..s.state.atoms.nlocal].iter().sum()
}

/// Solidified length X(t) of examples/heat/in.stefan at every thermo sample (t > 0): the solid
/// fraction by enthalpy times the liquid length 1 m, measured from the wall surface (the plane of
/// the outermost wall particles, x = -dx/2).
fn stefan_front(n: usize) -> Vec<(f64, f64)> {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/heat/in.stefan");
    let ns = n.to_string();
    let r = run_file(&deck, &opts(&[("N", &ns)])).unwrap_or_else(|e| panic!("{}", e.rendered));
    let (h, rows) = thermo(&r);
    let (ct, cf) = (col(&h, "Time"), col(&h, "f_phase[5]"));
    let dx = 1.0 / n as f64;
    rows.iter().filter(|row| row[ct] > 0.0).map(|row| (row[ct], row[cf] * 1.0 + 0.5 * dx)).collect()
}

/// Neumann's front for the deck's values.
fn stefan_exact(t: f64) -> f64 {
    let lambda = dmhs::tools::analytic::stefan_lambda(1000.0, 1.0, 2.0, 1.0, 1.0, 50.0, 0.0, 25.0, 100.0);
    2.0 * lambda * (t / 2000.0).sqrt()
}

/// (t, X, relative error) at every sample with t >= 20 s (front >= 5 spacings at N = 100).
fn stefan_errors(n: usize) -> Vec<(f64, f64, f64)> {
    stefan_errors_of(&stefan_front(n))
}

fn stefan_errors_of(front: &[(f64, f64)]) -> Vec<(f64, f64, f64)> {
    front.iter().filter(|p| p.0 >= 20.0 - 1e-9).map(|&(t, x)| (t, x, (x - stefan_exact(t)) / stefan_exact(t))).collect()
}

/// Least-squares lambda of X = 2 lambda sqrt(alpha_s t) through the samples, relative to Neumann's.
fn fitted_lambda_error(errs: &[(f64, f64, f64)]) -> f64 {
    let alpha_s: f64 = 1.0 / 2000.0;
    let (mut xs, mut ss) = (0.0, 0.0);
    for (t, x, _) in errs {
        let s = 2.0 * (alpha_s * t).sqrt();
        xs += x * s;
        ss += s * s;
    }
    let lambda = dmhs::tools::analytic::stefan_lambda(1000.0, 1.0, 2.0, 1.0, 1.0, 50.0, 0.0, 25.0, 100.0);
    xs / ss / lambda - 1.0
}

#[test]
fn stefan_front_within_5_percent_at_100_per_metre() {
    let errs = stefan_errors(100);
    assert_eq!(errs.len(), 11);
    // the front advances column by column (steps of dx = 1 cm), so single samples scatter by
    // up to about dx/2 around the solution: -5.1 % at worst (t = 24 s), -2.9 % at t = 40 s
    for (t, x, e) in &errs {
        assert!(e.abs() < 0.055, "t = {t}: front {x}, error {e:+.4}");
    }
    let last = errs.last().unwrap();
    assert!((last.2 + 0.0286).abs() < 0.002, "{last:?}");
    // the front trajectory X(t) (least-squares lambda over t = 20..40 s) is within 5 %
    let fit = fitted_lambda_error(&errs);
    println!("lambda fit error {fit:+.4}");
    assert!(fit.abs() < 0.05, "lambda fit error {fit:+.4}");
}

/// The full variant: 200 particles per metre, and the chart docs/img/stefan_front.png (with the
/// 100 per metre run) drawn with src/plot.rs.
#[test]
#[ignore]
fn stefan_front_at_200_per_metre() {
    let f200 = stefan_front(200);
    let errs = stefan_errors_of(&f200);
    for (t, x, e) in &errs {
        println!("N = 200  t = {t:5.1}  X = {x:.5}  error {e:+.4}");
        assert!(e.abs() < 0.05, "t = {t}: front {x}, error {e:+.4}");
    }
    assert!(errs.last().unwrap().2.abs() < 0.005);
    println!("lambda fit error {:+.4}", fitted_lambda_error(&errs));
    let f100 = stefan_front(100);
    for (t, x, e) in stefan_errors_of(&f100) {
        println!("N = 100  t = {t:5.1}  X = {x:.5}  error {e:+.4}");
    }
    use dmhs::output::plot::{Chart, Series};
    let exact: Vec<(f64, f64)> = (0..=200).map(|k| 40.0 * k as f64 / 200.0).map(|t| (t, stefan_exact(t))).collect();
    let chart = Chart::new("Stefan problem: solidification front vs Neumann's solution")
        .x_label("t (s)")
        .y_label("front X (m)")
        .series(Series::line("Neumann (analytic)", exact).color(6))
        .series(Series::points("dmhs, 100 particles/m", f100).color(0))
        .series(Series::points("dmhs, 200 particles/m", f200).color(1));
    chart.save(&Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/img/stefan_front")).unwrap();
}

const CLOSED: &str = "
dimension 2
units si
atom_style sph
boundary f f p
atom_modify map array
region box block 0 12 0 6 -0.5 0.5 units box
create_box 3 box
lattice sq 1.0 origin 0.5 0.5 0.0
region hot block 4 12 0 6 EDGE EDGE units box
region cold block 0 4 0 6 EDGE EDGE units box
create_atoms 1 region hot
create_atoms 3 region cold
group melt type 1 2
group wall type 3
mass 1*2 1000.0
mass 3 3700.0
set group all sph/rho 1000.0
set group melt sph/e 175000.0
set group wall sph/e 0.0
set group wall sph/cv 11100.0
pair_style dmhs/heatconduction
pair_coeff 1*2 1*2 1.0 2.6
pair_coeff 3 3 100.0 2.6
fix integ all sph/stationary
fix phase melt dmhs/phase Tstar 25 cvs 2 cvl 1 latent 50 liquid 1 solid 2
compute st all dmhs/phase/atom
compute Tmax all reduce max c_st[1]
thermo_style custom step f_phase f_phase[5] c_Tmax
timestep 0.05
";

#[test]
fn closed_system_conserves_energy_to_round_off() {
    // a hot liquid against a conducting wall with its own kappa, cv and mass, all integrated
    let r0 = run("closed0", &format!("{CLOSED}\nrun 0\n"));
    let e0 = total_energy(&r0);
    let r = run("closed", &format!("{CLOSED}\nthermo 500\nrun 4000\n"));
    let e1 = total_energy(&r);
    let (h, rows) = thermo(&r);
    let fs = rows.last().unwrap()[col(&h, "f_phase")];
    assert!(fs > 0.1 && fs < 1.0, "part of the liquid solidified: {fs}");
    let rel = (e1 - e0).abs() / e0.abs();
    println!("sum of esph: {e0} -> {e1}, relative change {rel:e}, solid fraction {fs}");
    assert!(rel < 1e-13, "sum of esph: {e0} -> {e1} ({rel:e})");
    // the wall warmed: heat went from the liquid to the wall
    let s = &r.sim;
    let ew: f64 = (0..s.state.atoms.nlocal).filter(|&i| s.state.atoms.typ[i] == 3).map(|i| s.state.atoms.esph[i]).sum();
    assert!(ew > 0.0);
}

const ONE: &str = "
dimension 2
units si
atom_style sph
boundary f f p
atom_modify map array
region box block 0 2 0 2 -0.5 0.5 units box
create_box 2 box
create_atoms 1 single 1.0 1.0 0.0 units box
mass * 2.0
set group all sph/rho 1000.0
set group all sph/e 350.0
pair_style dmhs/heatconduction
pair_coeff * * 1.0 0.5
fix integ all sph/stationary
fix phase all dmhs/phase Tstar 25 cvs 2 cvl 1 latent 50 liquid 1 solid 2
fix cool all dmhs/cooling 1.0 0.0
compute st all dmhs/phase/atom
compute T all reduce max c_st[1]
thermo_style custom step time c_T f_phase f_cool[2]
thermo_modify format float %.15g
thermo 10
timestep 0.001
run 5000
";

#[test]
fn cooling_shows_the_plateau_at_tstar() {
    // one particle, dT/dt = -(T - 0) from T = 100: liquid exponential to T* = 25 at t1 = ln 4,
    // plateau while the latent heat L = 50 leaves at the rate cvl kT T* = 25 (2 s), then solid
    let r = run("plateau", ONE);
    let (h, rows) = thermo(&r);
    let (ct, c_t, cs, cr) = (col(&h, "Time"), col(&h, "c_T"), col(&h, "f_phase"), col(&h, "f_cool[2]"));
    let t1 = 4f64.ln();
    let t2 = t1 + 2.0;
    let (mut first, mut last) = (f64::NAN, f64::NAN);
    for row in &rows {
        let (t, temp) = (row[ct], row[c_t]);
        if temp == 25.0 {
            if first.is_nan() {
                first = t;
            }
            last = t;
        }
        if t < t1 - 0.01 {
            let exact = 100.0 * (-t).exp();
            assert!((temp - exact).abs() < 2e-3 * exact, "liquid t = {t}: {temp} vs {exact}");
            assert_eq!(row[cs], 0.0);
        } else if t > t1 + 0.01 && t < t2 - 0.01 {
            assert_eq!(temp, 25.0, "plateau at T* (t = {t})");
        } else if t > t2 + 0.01 {
            let exact = 25.0 * (-(t - t2)).exp();
            assert!((temp - exact).abs() < 2e-3 * exact, "solid t = {t}: {temp} vs {exact}");
            assert_eq!(row[cs], 1.0);
        }
    }
    println!("plateau from t = {first} to {last} (exact {t1:.4} to {t2:.4}); removed {}", rows.last().unwrap()[cr]);
    assert!((first - t1).abs() < 0.011, "plateau starts at {first}, expected {t1}");
    assert!((last - t2).abs() < 0.011, "plateau ends at {last}, expected {t2}");
    // the energy removed by cooling is what the particle lost
    let removed = rows.last().unwrap()[cr];
    let lost = 350.0 - total_energy(&r);
    assert!((removed - lost).abs() < 1e-12 * lost, "removed {removed}, lost {lost}");
}

#[test]
fn surface_particles_found_by_coordination() {
    // a 6 x 6 square block, spacing 1, coordination within 1.5: interior 8, edges 5, corners 3;
    // below 5.5 -> the 20 boundary atoms cool
    let deck = "
dimension 2
units si
atom_style sph
boundary f f p
region box block -2 8 -2 8 -0.5 0.5 units box
create_box 1 box
lattice sq 1.0 origin 0.5 0.5 0.0
region blk block 0 6 0 6 EDGE EDGE units box
create_atoms 1 region blk
mass 1 1.0
set group all sph/rho 1.0
set group all sph/e 10.0
pair_style dmhs/heatconduction
pair_coeff 1 1 0.0 1.6
fix integ all sph/stationary
fix cool all dmhs/cooling 0.5 0.0 surface 1.5 5.5
thermo_style custom step f_cool
run 1
";
    let r = run("surface", deck);
    let (h, rows) = thermo(&r);
    assert_eq!(rows.last().unwrap()[col(&h, "f_cool")], 20.0);
    // cv = 1: each boundary atom lost about dt kT T = 0.005 * 10 ... per unit of e
    let s = &r.sim;
    let cooled = (0..s.state.atoms.nlocal).filter(|&i| s.state.atoms.esph[i] < 10.0).count();
    assert_eq!(cooled, 20);
}

const BONDING: &str = "
dimension 2
units si
atom_style hybrid sph bond
boundary f f p
atom_modify map array
region box block -1 6 -1 1 -0.5 0.5 units box
create_box 2 box bond/types 1 extra/bond/per/atom 4
create_atoms 2 single 0.0 0.0 0.0 units box
create_atoms 2 single 1.0 0.0 0.0 units box
create_atoms 1 single 2.0 0.0 0.0 units box
create_atoms 1 single 3.0 0.0 0.0 units box
create_atoms 1 single 4.0 0.0 0.0 units box
mass * 1.0
set group all sph/rho 1.0
set group all sph/e 20.0
set atom 5 sph/e 200.0
pair_style dmhs/heatconduction
pair_coeff * * 0.0 1.2
bond_style harmonic
bond_coeff 1 100.0 1.0
special_bonds lj 1 1 1
fix integ all sph/stationary
fix phase all dmhs/phase Tstar 25 cvs 2 cvl 1 latent 50 liquid 1 solid 2 bond 1 cutoff 1.1
thermo_style custom step f_phase f_phase[2] f_phase[3] f_phase[4] bonds
run 1
";

#[test]
fn solidifying_atoms_bond_to_solid_neighbours_and_melting_breaks_bonds() {
    let r = run("bonding", BONDING);
    let s = &r.sim;
    let mut bonds: Vec<[i64; 2]> = s.state.topo.bonds.iter().map(|b| b.atoms).collect();
    bonds.sort();
    // atoms 1, 2 were solid from the start (within the cut-off but not bonded: an already solid
    // atom creates no bonds); 3 then 4 solidify in ID order: 3-2, then 4-3; 5 stays liquid
    assert_eq!(bonds, vec![[3, 2], [4, 3]]);
    let map = s.state.atoms.tag_map();
    let ty = |t: i64| s.state.atoms.typ[map.get(t).unwrap()];
    assert_eq!((ty(3), ty(4), ty(5)), (2, 2, 1));
    // heat atom 3 above e_liq: it melts, loses both bonds and becomes liquid
    let r = run("melting", &format!("{BONDING}\nset atom 3 sph/e 150.0\nrun 1\n"));
    let s = &r.sim;
    assert!(s.state.topo.bonds.is_empty(), "{:?}", s.state.topo.bonds);
    let map = s.state.atoms.tag_map();
    assert_eq!(s.state.atoms.typ[map.get(3).unwrap()], 1);
    let (h, rows) = thermo(&r);
    let last = rows.last().unwrap();
    assert_eq!((last[col(&h, "f_phase[2]")], last[col(&h, "f_phase[3]")], last[col(&h, "f_phase[4]")]), (3.0, 2.0, 2.0));
}

/// Two spheres of type `$ty` (diameter 1, mass 20), at the origin and at `$second` (x y).
macro_rules! two_spheres {
    ($ty:literal, $second:literal) => {
        concat!(
            "
dimension 2
units si
atom_style hybrid sph sphere
boundary f f p
comm_modify vel yes
atom_modify map array
region box block -3 4 -3 4 -0.5 0.5 units box
create_box 2 box
create_atoms ", $ty, " single 0.0 0.0 0.0 units box
create_atoms ", $ty, " single ", $second, " 0.0 units box
set group all diameter 1.0
set group all mass 20.0
mass * 20.0
"
        )
    };
}

/// Two overlapping spheres inside the SPH support, moving; `PAIR` is replaced per case.
const TWO: &str = concat!(
    two_spheres!("1", "0.9 0.2"),
    "set group all sph/rho 1010.0
set atom 2 sph/rho 990.0
set atom 1 vx 0.3
set atom 1 vy -0.1
set atom 2 vx -0.2
set atom 1 sph/e 20000.0
set atom 2 sph/e 10000.0
PAIR
fix integ all sph
run 0
"
);

fn forces(pair: &str) -> Vec<[f64; 3]> {
    let r = run("two", &TWO.replace("PAIR", pair));
    let s = &r.sim;
    let map = s.state.atoms.tag_map();
    (1..=2).map(|t| s.state.atoms.f[map.get(t).unwrap()]).collect()
}

#[test]
fn blend_is_the_weighted_sum_of_sph_and_dem() {
    let sph = forces("pair_style sph/taitwater/morris\npair_coeff * * 1000.0 100.0 1.0 1.5");
    let dem = forces("pair_style gran/hooke 1000.0 NULL 0.3 NULL 0.5 0\npair_coeff * *");
    let blend = "pair_style dmhs/blend 1000.0 NULL 0.3 NULL 0.5 0\npair_coeff * * 1000.0 100.0 1.0 1.5";
    // no phase fix: phi = 1, pure SPH
    let pure = forces(blend);
    // m = 20, L = 0, T* = 500, cvs = cvl = 1: atom 1 at T = 1000 has phi = 1, atom 2 at T = 500
    // phi = 0 -> pair weight 1/2
    let half = forces(&format!("{blend}\nfix phase all dmhs/phase Tstar 500 cvs 1 cvl 1 latent 0 liquid 1 solid 2 mix 500 1000"));
    for i in 0..2 {
        for k in 0..2 {
            assert!(sph[i][k].abs() > 1e-3 && dem[i][k].abs() > 1e-3, "both parts act: {sph:?} {dem:?}");
            assert!((pure[i][k] - sph[i][k]).abs() <= 1e-13 * sph[i][k].abs(), "{pure:?} vs {sph:?}");
            let exact = 0.5 * sph[i][k] + 0.5 * dem[i][k];
            assert!((half[i][k] - exact).abs() <= 1e-13 * exact.abs().max(1.0), "{half:?} vs {exact}");
        }
        // Newton's third law
        assert!((half[0][i] + half[1][i]).abs() < 1e-12);
    }
}

/// Two solid spheres (T = 400 C below `mix 500 1000`: phi = 0, so the pair is all DEM) held in
/// place with an overlap of 0.1 (diameters 1, centres 0.9 apart along y) while atom 2 slides
/// along x at 0.2 m/s. No integrator moves them, so the contact's tangential displacement after
/// n steps is exactly n dt v (the spring integrates v_tr dt, as gran/hooke/history) and the
/// normal force stays Kn delta = 100 N. With `history` the tangential force on atom 2 is
/// -Kt n dt v until it reaches the Coulomb cap xmu Kn delta = 50 N, then stays at the cap.
const SLIDING: &str = concat!(
    two_spheres!("2", "0.0 0.9"),
    "set group all sph/rho 1000.0
set group all sph/e 8000.0
set atom 2 vx 0.2
PAIR
fix phase all dmhs/phase Tstar 500 cvs 1 cvl 1 latent 0 liquid 1 solid 2 mix 500 1000
neighbor 1.0 bin
timestep 0.01
"
);

fn sliding_force(pair: &str, runs: &[usize]) -> Vec<[f64; 3]> {
    let runs: String = runs.iter().map(|n| format!("run {n}\n")).collect();
    let r = run("sliding", &format!("{}{runs}", SLIDING.replace("PAIR", pair)));
    let s = &r.sim;
    let map = s.state.atoms.tag_map();
    (1..=2).map(|t| s.state.atoms.f[map.get(t).unwrap()]).collect()
}

#[test]
fn blend_history_tangential_spring_until_the_coulomb_cap() {
    // Kn 1000, Kt 100, gamma_n 0.3 (no normal velocity: no damping), xmu 0.5, dampflag 0
    let (kn, kt, xmu, delta, v, dt) = (1000.0, 100.0, 0.5, 0.1, 0.2, 0.01);
    let with = "pair_style dmhs/blend 1000.0 100.0 0.3 0.0 0.5 0 history\npair_coeff * * 1000.0 10.0 1.0 1.5";
    let cap = xmu * kn * delta;
    // 100 steps: below the cap (20 N); 100 + 140 steps in two runs (the contact is carried over
    // the second run's setup): 48 N, still below; 100 + 300 steps: capped at 50 N
    for (runs, expect_t) in [(vec![100], kt * 100.0 * dt * v), (vec![100, 140], kt * 240.0 * dt * v), (vec![100, 300], cap)] {
        let f = sliding_force(with, &runs);
        println!("runs {runs:?}: f1 {:?}, f2 {:?}", f[0], f[1]);
        assert!((f[1][0] + expect_t).abs() <= 1e-9 * expect_t, "runs {runs:?}: tangential force on 2 {} against -{expect_t}", f[1][0]);
        assert!((f[1][1] - kn * delta).abs() <= 1e-9 * kn * delta, "normal force {}", f[1][1]);
        for k in 0..2 {
            assert!((f[0][k] + f[1][k]).abs() <= 1e-12 * kn, "Newton's third law: {f:?}");
        }
    }
    assert!(kt * 240.0 * dt * v < cap && kt * 400.0 * dt * v > cap);
    // the DEM part is gran/hooke/history's contact, bit for bit
    for runs in [vec![100], vec![100, 300]] {
        assert_eq!(sliding_force(with, &runs), sliding_force("pair_style gran/hooke/history 1000.0 100.0 0.3 0.0 0.5 0\npair_coeff * *", &runs));
    }
    // without `history` (gran/hooke) the tangential force is damping only, 0 with dampflag 0
    let f = sliding_force("pair_style dmhs/blend 1000.0 100.0 0.3 0.0 0.5 0\npair_coeff * * 1000.0 10.0 1.0 1.5", &[100]);
    assert_eq!(f[1][0], 0.0);
}

#[test]
fn bad_blend_history_is_a_located_error() {
    let cases = [
        ("pair_style dmhs/blend 1000.0 0.0 0.3 0.0 0.5 0 history", "Kt must be > 0"),
        ("pair_style dmhs/blend 0.0 NULL 0.3 0.0 0.5 0 history", "Kt must be > 0"),
        ("pair_style dmhs/blend 1000.0 100.0 0.3 0.0 0.5 0 history history", "given twice"),
        ("pair_style dmhs/blend 1000.0 100.0 0.3 0.0 0.5 0 histroy", "unknown keyword `histroy`"),
        ("pair_style dmhs/blend 1000.0 -100.0 0.3 0.0 0.5 0 history", "Kt"),
    ];
    for (line, expect) in cases {
        let deck = SLIDING.replace("PAIR", &format!("{line}\npair_coeff * * 1000.0 10.0 1.0 1.5"));
        let err = run_text("bad", &deck, &opts(&[])).err().unwrap_or_else(|| panic!("`{line}` was accepted"));
        assert!(err.rendered.contains("bad:18:"), "{line}: no location in {}", err.rendered);
        assert!(err.rendered.contains(expect), "{line}: expected `{expect}` in {}", err.rendered);
    }
}

/// Stock LAMMPS heat exchange between a fluid (fix sph), moving solid spheres (nve/sphere +
/// sph/stationary) and a held wall in `atom_style hybrid sph sphere`: dmhs matches LAMMPS
/// (measured: esph to 2.2e-16 relative after 500 steps). Skipped without LAMMPS unless
/// DMHS_REQUIRE_LAMMPS=1.
#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn hybrid_heat_exchange_matches_lammps() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/heat/in.conduct_hybrid");
    let (ours0, ours, box_len) = dmhs::tools::cli_crosscheck::dmhs_capture(&deck, &[]).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    dmhs::tools::lammps::run_driver(&deck, &[], tmp.path()).unwrap();
    let theirs0 = dmhs::tools::crosscheck::AtomTable::read(&tmp.path().join("forces0.txt")).unwrap();
    let theirs = dmhs::tools::crosscheck::AtomTable::read(&tmp.path().join("final.txt")).unwrap();
    let diffs = dmhs::tools::crosscheck::compare_runs(&ours0, &theirs0, &ours, &theirs, box_len).unwrap();
    let bad = dmhs::tools::cli_crosscheck::within(&diffs, [1e-12, 1e-12, 1e-12]);
    assert!(bad.is_empty(), "{}\n{}", dmhs::tools::crosscheck::report(&diffs), bad.join("\n"));
    // the wall (no integrator) kept esph = 0; the solids warmed
    let e = ours.column("esph").unwrap();
    let warm = ours.rows.values().filter(|r| r.1[e] > 1.0).count();
    assert!(warm > 0);
}

#[test]
fn bad_phase_and_cooling_commands_are_located_errors() {
    let base = "
dimension 2
units si
atom_style sph
region box block 0 2 0 2 -0.5 0.5 units box
create_box 2 box
";
    let cases = [
        ("fix p all dmhs/phase Tstar 25 cvs 2 cvl 1 latent 50 liquid 1", "needs the keyword `solid`"),
        ("fix p all dmhs/phase Tstar 25 cvs 2 cvl 1 latent 50 liquid 1 solid 1", "must differ"),
        ("fix p all dmhs/phase Tstar 25 cvs -2 cvl 1 latent 50 liquid 1 solid 2", "cvs"),
        ("fix p all dmhs/phase Tstar 25 cvs 2 cvl 1 latent 50 liquid 1 solid 2 bond 1", "bond"),
        ("fix p all dmhs/phase Tstar 25 cvs 2 cvl 1 latent 50 liquid 1 solid 2 mix 900 500", "Thigh"),
        ("fix p all dmhs/phase Tstar 25 cvs 2 cvl 1 latent 50 liquid 1 solid 2 colour red", "colour"),
        ("fix c all dmhs/cooling 0.1", "Tair"),
        ("fix c all dmhs/cooling 0.1 0.0 surface 1.0", "NC"),
    ];
    for (line, expect) in cases {
        let err = run_text("bad", &format!("{base}{line}\n"), &opts(&[])).err().unwrap_or_else(|| panic!("`{line}` was accepted"));
        assert!(err.rendered.contains("bad:7:"), "{line}: no location in {}", err.rendered);
        assert!(err.rendered.contains(expect), "{line}: expected `{expect}` in {}", err.rendered);
    }
}
