//! Analytic validation of the granular contact laws (formulas in docs/validation.md, DEM):
//!
//! * head-on restitution and contact time of the linear spring-dashpot, with the error
//!   shrinking in proportion to dt/t_c (pair gran/hooke/history and pair granular);
//! * a sphere sliding on a frictional floor without rotation stops after v0^2 / (2 mu g);
//! * with rotation (fix nve/sphere) slip ends at t = 2 v0 / (7 mu g) with v = 5/7 v0;
//! * on an incline below the friction angle the sphere sticks, held by the tangential spring
//!   stretched m g sin(theta) / k_t; above it, it slides with a = g (sin - mu cos);
//! * in a static column the overlap below the k-th sphere is k m g / k_n.

use dmhs::deck::{run_text, DeckOptions};
use dmhs::sim::Simulation;
use std::f64::consts::PI;

/// Build the simulation of a deck (without a run), then set it up for stepping.
fn start(deck: &str) -> Simulation {
    let r = run_text("analytic", deck, &DeckOptions::default()).map_err(|f| f.rendered).unwrap();
    let mut sim = r.sim;
    sim.init_run().unwrap();
    sim.setup(true).unwrap();
    sim
}

fn step(sim: &mut Simulation) {
    sim.step_once(false).unwrap();
}

/// Position, velocity and angular velocity of the atom with ID `tag`.
fn atom(sim: &Simulation, tag: i64) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let a = &sim.state.atoms;
    let i = (0..a.nlocal).find(|&i| a.tag[i] == tag).unwrap();
    let img = a.image[i];
    let prd = sim.state.domain.as_ref().unwrap().prd();
    let x = [a.x[i][0] + img[0] as f64 * prd[0], a.x[i][1] + img[1] as f64 * prd[1], a.x[i][2] + img[2] as f64 * prd[2]];
    (x, a.v[i], a.omega[i])
}

/// Sphere mass for diameter 1, density 1 (as `create_atoms` makes it).
const M: f64 = PI / 6.0;

/// Spring-dashpot theory for effective mass `meff`: (contact time, restitution).
fn theory(kn: f64, gamma_n: f64, meff: f64) -> (f64, f64) {
    let w0sq = kn / meff;
    let beta = 0.5 * gamma_n;
    let w = (w0sq - beta * beta).sqrt();
    let tc = PI / w;
    (tc, (-beta * tc).exp())
}

/// Head-on collision of two unit spheres that touch at t = 0 (so the contact starts with the
/// first step at every dt): measured (contact time, restitution).
fn head_on(pair: &str, dt: f64) -> (f64, f64) {
    let deck = format!(
        "units lj\natom_style sphere\nboundary f f f\ncomm_modify vel yes\n\
         region box block -4 4 -4 4 -4 4 units box\ncreate_box 1 box\n\
         create_atoms 1 single -0.5 0 0 units box\ncreate_atoms 1 single 0.5 0 0 units box\n\
         set atom 1 vx 1.0\nset atom 2 vx -1.0\n{pair}\nneighbor 0.3 bin\nfix 1 all nve/sphere\ntimestep {dt:e}\n"
    );
    let mut sim = start(&deck);
    let mut in_contact = 0usize;
    let mut was = false;
    for _ in 0..2_000_000 {
        step(&mut sim);
        let (x1, _, _) = atom(&sim, 1);
        let (x2, _, _) = atom(&sim, 2);
        let touching = x2[0] - x1[0] < 1.0;
        if touching {
            in_contact += 1;
        } else if was {
            break;
        }
        was = touching;
    }
    let (_, v1, _) = atom(&sim, 1);
    let (_, v2, _) = atom(&sim, 2);
    (in_contact as f64 * dt, (v2[0] - v1[0]) / 2.0)
}

#[test]
fn restitution_and_contact_time_converge_with_dt() {
    let kn = 2.0e5;
    let meff = 0.5 * M;
    // gamma_n for e = 0.35 (the inverse formula)
    let e_target: f64 = 0.35;
    let w0 = (kn / meff).sqrt();
    let gamma_n = 2.0 * w0 * (-e_target.ln()) / (PI * PI + e_target.ln().powi(2)).sqrt();
    let (tc, e_th) = theory(kn, gamma_n, meff);
    assert!((e_th - e_target).abs() < 1e-12);
    let styles = [
        format!("pair_style gran/hooke/history {kn} NULL {gamma_n} NULL 0.5 1\npair_coeff * *"),
        format!("pair_style granular\npair_coeff * * hooke {kn} {gamma_n} tangential linear_history {} 0.5 0.5 damping mass_velocity", kn * 2.0 / 7.0),
    ];
    for pair in &styles {
        let mut last_err = f64::INFINITY;
        let mut scaled = vec![];
        for n in [50.0, 100.0, 1000.0] {
            let dt = tc / n;
            let (tc_meas, e) = head_on(pair, dt);
            let err = (e - e_th).abs();
            println!("{}: dt = t_c/{n}: e = {e:.6} (theory {e_th:.6}), t_c = {tc_meas:.6e} (theory {tc:.6e})", pair.split_whitespace().nth(1).unwrap());
            // first-order convergence: the error is a fraction of dt/t_c and shrinks with dt
            assert!(err < 0.25 / n, "restitution error {err} at dt = t_c/{n}");
            scaled.push(err * n);
            assert!(err < last_err, "restitution error does not shrink with dt");
            assert!((tc_meas - tc).abs() <= 2.0 * dt, "contact time {tc_meas} vs {tc}");
            last_err = err;
        }
        // error / (dt/t_c) about constant (measured 0.18, 0.18, 0.18)
        let (lo, hi) = scaled.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(hi < 2.0 * lo, "error not proportional to dt/t_c: {scaled:?}");
    }
}

/// A sphere resting on a frictional floor (fix wall/gran granular) under gravity `g`, with
/// the floor overlap at its static value; `extra` adds commands (velocities, tilt).
fn on_floor(integrator: &str, g: f64, tilt_deg: f64, mu: f64, extra: &str) -> Simulation {
    let (kn, kt) = (2.0e5, 2.0e5 * 2.0 / 7.0);
    let theta = tilt_deg.to_radians();
    let z0 = 0.5 - M * g * theta.cos() / kn;
    let deck = format!(
        "units lj\natom_style sphere\nboundary p p f\ncomm_modify vel yes\n\
         region box block -50 50 -5 5 0 5 units box\ncreate_box 1 box\n\
         create_atoms 1 single 0 0 {z0:e} units box\n\
         pair_style granular\npair_coeff * * hooke {kn} 200 tangential linear_history {kt} 0.5 {mu} damping mass_velocity\n\
         fix wall all wall/gran granular hooke {kn} 200 tangential linear_history {kt} 0.5 {mu} damping mass_velocity zplane 0.0 NULL\n\
         fix grav all gravity {g} vector {} 0 {}\n{extra}\nneighbor 0.3 bin\nfix 1 all {integrator}\ntimestep 1e-4\n",
        theta.sin(),
        -theta.cos()
    );
    start(&deck)
}

#[test]
fn sliding_without_rotation_stops_after_v0_squared_over_2_mu_g() {
    let (g, mu, v0) = (10.0, 0.3, 2.0);
    let mut sim = on_floor("nve", g, 0.0, mu, &format!("velocity all set {v0} 0 0 units box"));
    let x0 = atom(&sim, 1).0[0];
    let t_stop = v0 / (mu * g);
    let n = (1.5 * t_stop / 1e-4) as usize;
    let mut stopped_at = None;
    for k in 0..n {
        step(&mut sim);
        if stopped_at.is_none() && atom(&sim, 1).1[0] <= 0.0 {
            stopped_at = Some((k + 1) as f64 * 1e-4);
        }
    }
    let d = atom(&sim, 1).0[0] - x0;
    let d_th = v0 * v0 / (2.0 * mu * g);
    println!("stop distance {d:.6} (theory {d_th:.6}), stop time {stopped_at:?} (theory {t_stop:.6})");
    assert!((d - d_th).abs() < 2e-3 * d_th, "stop distance {d} vs {d_th}");
    assert!((stopped_at.unwrap() - t_stop).abs() < 2e-3 * t_stop);
}

#[test]
fn sliding_sphere_starts_rolling_at_five_sevenths_v0() {
    let (g, mu, v0) = (10.0, 0.3, 2.0);
    let mut sim = on_floor("nve/sphere", g, 0.0, mu, &format!("velocity all set {v0} 0 0 units box"));
    let t_roll = 2.0 * v0 / (7.0 * mu * g);
    // slip ends when the contact point stops sliding: v_x - r omega_y = 0
    let mut slip_end = None;
    for k in 0..(2.0 * t_roll / 1e-4) as usize {
        step(&mut sim);
        let (_, v, w) = atom(&sim, 1);
        if slip_end.is_none() && v[0] - 0.5 * w[1] <= 0.0 {
            slip_end = Some((k + 1) as f64 * 1e-4);
        }
    }
    let (_, v, w) = atom(&sim, 1);
    println!("v = {:.6} (theory {:.6}), omega_y = {:.6}, slip ended at {slip_end:?} (theory {t_roll:.6})", v[0], 5.0 / 7.0 * v0, w[1]);
    assert!((v[0] - 5.0 / 7.0 * v0).abs() < 2e-3 * v0, "rolling velocity {}", v[0]);
    // rolling without slip: v = omega_y r
    assert!((v[0] - 0.5 * w[1]).abs() < 2e-3 * v0);
    assert!((slip_end.unwrap() - t_roll).abs() < 0.02 * t_roll);
}

#[test]
fn incline_stick_stretches_the_spring_by_m_g_sin_over_kt() {
    // tan(theta) = 0.12 < mu = 0.3: sticks; even the dynamic overshoot of the load as the
    // spring takes it up (at most twice the static value) stays below mu, so there is no slip
    let (g, mu) = (10.0, 0.3);
    let theta = 0.12f64.atan();
    let mut sim = on_floor("nve", g, theta.to_degrees(), mu, "");
    let x0 = atom(&sim, 1).0[0];
    for _ in 0..20_000 {
        step(&mut sim);
    }
    let creep = atom(&sim, 1).0[0] - x0;
    let kt = 2.0e5 * 2.0 / 7.0;
    let creep_th = M * g * theta.sin() / kt;
    println!("creep {creep:.6e} (theory {creep_th:.6e})");
    assert!((creep - creep_th).abs() < 1e-3 * creep_th, "creep {creep} vs {creep_th}");
    assert!(atom(&sim, 1).1[0].abs() < 1e-6);
}

#[test]
fn incline_slide_accelerates_at_g_sin_minus_mu_cos() {
    // tan(26.6 deg) = 0.5 > mu = 0.3: slides
    let (g, mu) = (10.0, 0.3);
    let theta = 0.5f64.atan();
    let mut sim = on_floor("nve", g, theta.to_degrees(), mu, "");
    for _ in 0..2_000 {
        step(&mut sim);
    }
    let v1 = atom(&sim, 1).1[0];
    let n = 10_000;
    for _ in 0..n {
        step(&mut sim);
    }
    let v2 = atom(&sim, 1).1[0];
    let a = (v2 - v1) / (n as f64 * 1e-4);
    let a_th = g * (theta.sin() - mu * theta.cos());
    println!("acceleration {a:.6} (theory {a_th:.6})");
    assert!((a - a_th).abs() < 1e-3 * a_th, "acceleration {a} vs {a_th}");
}

#[test]
fn static_column_overlaps_are_k_m_g_over_kn() {
    let (kn, g, n) = (2.0e5, 10.0, 10usize);
    let mut deck = String::from(
        "units lj\natom_style sphere\nboundary p p f\ncomm_modify vel yes\n\
         region box block -3 3 -3 3 0 20 units box\ncreate_box 1 box\n",
    );
    for k in 0..n {
        deck += &format!("create_atoms 1 single 0 0 {} units box\n", 0.5 + k as f64);
    }
    deck += &format!(
        "pair_style gran/hooke/history {kn} NULL 1500 NULL 0.5 1\npair_coeff * *\n\
         fix wall all wall/gran granular hooke {kn} 1500 tangential linear_history {} 0.5 0.5 damping mass_velocity zplane 0.0 NULL\n\
         fix grav all gravity {g} vector 0 0 -1\nneighbor 0.3 bin\nfix 1 all nve/sphere\ntimestep 1e-4\n",
        kn * 2.0 / 7.0
    );
    let mut sim = start(&deck);
    // near-critical damping: settled to round-off after about 20,000 steps
    for _ in 0..25_000 {
        step(&mut sim);
    }
    let z: Vec<f64> = (1..=n as i64).map(|t| atom(&sim, t).0[2]).collect();
    let unit = M * g / kn;
    // floor: the whole column; between spheres k and k+1 (from the top): k m g / kn
    let floor = 0.5 - z[0];
    println!("floor overlap {floor:.6e} (theory {:.6e})", n as f64 * unit);
    assert!((floor - n as f64 * unit).abs() < 1e-6 * n as f64 * unit);
    for k in 1..n {
        let overlap = 1.0 - (z[k] - z[k - 1]);
        let from_top = (n - k) as f64;
        assert!((overlap - from_top * unit).abs() < 1e-6 * from_top * unit, "overlap {k}: {overlap} vs {}", from_top * unit);
    }
}
