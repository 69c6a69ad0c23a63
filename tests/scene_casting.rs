//! The paper's casting scene (Figs 9 and 10), examples/scenes/casting/in.casting: liquid poured
//! from a ladle into a cold mould, solidifying with latent heat (slow) or without it under strong
//! surface cooling (fast).
//!
//! Quick variants run here (`-var quick 1`: 4 s slow, 8 s fast); the full slow run (45 s, to
//! complete solidification) is `#[ignore]`d: `cargo test --release --test scene_casting -- --ignored`.

use dmhs::deck::{run_file, DeckOptions, DeckRun};
use dmhs::tools::validate::{parse_thermo, Thermo};
use std::path::Path;

mod scene_common;

fn run_deck(vars: &[(&str, &str)]) -> DeckRun {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/casting/in.casting");
    let mut all = vec![("img", "0")];
    all.extend_from_slice(vars);
    let opts = DeckOptions { capture_text: true, vars: all.iter().map(|(k, v)| (k.to_string(), vec![v.to_string()])).collect(), ..Default::default() };
    run_file(&deck, &opts).unwrap_or_else(|e| panic!("{}", e.rendered))
}

fn thermo(r: &DeckRun) -> Thermo {
    parse_thermo(r.sim.out.captured.as_ref().unwrap())
}

fn run_casting(vars: &[(&str, &str)]) -> Thermo {
    thermo(&run_deck(vars))
}

/// The solid fraction (`f_phase`) at whole seconds `times`, against the values measured with the
/// deck's dt = 2e-4 s. Tolerance 0.05: the largest difference between dt = 2e-4 s and 1e-4 s
/// (`-var dt 1.0e-4`) at these times is 0.043 (fast, 4 s: 0.550 against 0.593), plus one particle
/// of 140 (0.007) for the last digit.
fn check_solid_fraction(t: &Thermo, label: &str, want: &[(f64, f64)]) {
    let (time, fs) = (col(t, "Time"), col(t, "f_phase"));
    for &(at, f) in want {
        let k = time.iter().position(|&x| (x - at).abs() < 1e-9).unwrap_or_else(|| panic!("no sample at {at} s"));
        println!("{label}: solid fraction {} at {at} s (measured {f})", fs[k]);
        assert!((fs[k] - f).abs() <= 0.05, "{label}: solid fraction {} at {at} s, measured {f}", fs[k]);
    }
}

/// Fig 9D's three zones in the mould (0 < x < 0.3, y < 0.5) by enthalpy, as the deck's state
/// picture colours them: solid e < e_sol, transition e_sol <= e <= e_liq, liquid e > e_liq
/// (e = esph/m; the slow case's e_sol = 50, e_liq = 100 J/kg). Returns each zone's count and mean
/// distance from the nearest mould face (x = 0, x = 0.3, y = 0), as zones.py does.
fn zones(r: &DeckRun, esol: f64, eliq: f64) -> [(usize, f64); 3] {
    let a = &r.sim.state.atoms;
    let mut z = [(0usize, 0.0f64); 3];
    for i in (0..a.nlocal).filter(|&i| a.typ[i] <= 2) {
        let (x, y, e) = (a.x[i][0], a.x[i][1], a.esph[i] / r.sim.state.mass(i));
        if !(x > 0.0 && x < 0.3 && y < 0.5) {
            continue;
        }
        let k = if e <= esol { 0 } else if e > eliq { 2 } else { 1 };
        z[k].0 += 1;
        z[k].1 += x.min(0.3 - x).min(y);
    }
    z.map(|(n, d)| (n, if n > 0 { d / n as f64 } else { f64::NAN }))
}

fn col(t: &Thermo, name: &str) -> Vec<f64> {
    t.column(name).unwrap_or_else(|| panic!("no column {name} in {:?}", t.columns))
}

/// The liquid charge: 140 particles (two compartments of 7 x 10 in the ladle).
const N: f64 = 140.0;

/// The solid fraction never falls except by counted re-melting: between two samples it drops by
/// at most (melting events in between)/N. Returns the largest drop.
fn check_drops_are_remelts(t: &Thermo) -> f64 {
    let (fs, melted) = (col(t, "f_phase"), col(t, "f_phase[8]"));
    let mut worst: f64 = 0.0;
    for k in 1..fs.len() {
        let drop = fs[k - 1] - fs[k];
        let remelts = melted[k] - melted[k - 1];
        // thermo prints 8 significant digits: a drop of 1/140 can read 0.00714286
        assert!(drop <= remelts / N + 1e-7, "solid fraction fell by {drop} at sample {k} with only {remelts} melting events");
        worst = worst.max(drop);
    }
    worst
}

#[test]
fn slow_casting_solidifies_from_the_mould_with_three_zones() {
    slow_quick_checks(&[]);
}

/// The quick slow checks at half the time step (the spread behind the tolerances):
/// `cargo test --release --test scene_casting -- --ignored half_time_step`.
#[test]
#[ignore]
fn slow_casting_at_half_the_time_step() {
    slow_quick_checks(&[("dt", "1.0e-4")]);
}

fn slow_quick_checks(extra: &[(&str, &str)]) {
    let mut vars = vec![("quick", "1")];
    vars.extend_from_slice(extra);
    let r = run_deck(&vars);
    let t = thermo(&r);
    // solid fraction against time: measured 0.293, 0.329, 0.393 (dt 1e-4 s: 0.257, 0.329, 0.379)
    check_solid_fraction(&t, "slow quick", &[(2.0, 0.293), (3.0, 0.329), (4.0, 0.393)]);
    // Fig 9D: a solid crust at the mould faces, the transition inside it, a liquid core. Measured
    // at 4 s: mean distance from the nearest face 0.018 / 0.041 / 0.092 m (51 / 14 / 75
    // particles; dt 1e-4 s: 0.019 / 0.033 / 0.091 m); the bounds leave 0.01 m (0.4 dx) beyond
    // that spread
    let [(ns, ds), (nt, dt), (nl, dl)] = zones(&r, 50.0, 100.0);
    println!("zones at 4 s: solid {ns} at {ds:.4} m, transition {nt} at {dt:.4} m, liquid {nl} at {dl:.4} m from the mould");
    assert!(ns >= 40 && nt >= 5 && nl >= 40, "zones {ns} / {nt} / {nl}");
    assert!(ds < 0.03 && (0.02..0.055).contains(&dt) && dl > 0.08, "zone distances {ds} / {dt} / {dl}");
    assert!(ds < dt && dt < dl);
    let (time, fs) = (col(&t, "Time"), col(&t, "f_phase"));
    let (liq, plateau, solid) = (col(&t, "v_nliq"), col(&t, "f_phase[6]"), col(&t, "f_phase[2]"));
    let melted = col(&t, "f_phase[8]");
    let last = fs.len() - 1;
    assert!((time[last] - 4.0).abs() < 1e-9);
    // every liquid particle is accounted for (none left the box)
    for k in 0..fs.len() {
        assert_eq!(liq[k] + plateau[k] + solid[k], N, "sample {k}");
    }
    let worst = check_drops_are_remelts(&t);
    println!("slow quick: solid fraction {} at t = {}, largest drop {worst}, melting events {}", fs[last], time[last], melted[last]);
    // measured 0.393 (55 of 140)
    assert!(fs[last] > 0.3, "solid fraction at 4 s: {}", fs[last]);
    // re-melting is rare: at most 5 % of the charge (7 measured)
    assert!(melted[last] <= 0.05 * N, "melting events {}", melted[last]);
    // the three zones of Fig 9D coexist: liquid above e_liq, transition on the plateau, solid
    let both: Vec<usize> = (0..fs.len()).filter(|&k| liq[k] >= 10.0 && plateau[k] >= 5.0 && solid[k] >= 10.0).collect();
    println!("three zones (>= 10 liquid, >= 5 transition, >= 10 solid) at {} of {} samples, e.g. t = {}: {} / {} / {}", both.len(), fs.len(), time[both[0]], liq[both[0]], plateau[both[0]], solid[both[0]]);
    // measured: 28 of 41 samples, from t = 1.3 s (120 / 9 / 11) to the end (71 / 14 / 55)
    assert!(both.len() >= 20);
    // solid particles are bonded to their solid neighbours
    assert!(col(&t, "Bonds")[last] >= 0.8 * solid[last]);
}

/// Fast solidification (Fig 10): the crust of the first half is broken mechanically (bonds
/// stretched beyond r_max = 1.09 r0 by the incoming metal break) and partly re-melted.
#[test]
fn fast_casting_crust_breaks_and_partly_remelts() {
    fast_quick_checks(&[]);
}

/// The quick fast checks at half the time step: `cargo test --release --test scene_casting --
/// --ignored half_time_step`.
#[test]
#[ignore]
fn fast_casting_at_half_the_time_step() {
    fast_quick_checks(&[("dt", "1.0e-4")]);
}

fn fast_quick_checks(extra: &[(&str, &str)]) {
    let mut vars = vec![("quick", "1"), ("case", "fast")];
    vars.extend_from_slice(extra);
    let r = run_deck(&vars);
    let t = thermo(&r);
    // solid fraction against time: measured 0.279, 0.443, 0.550, 0.743, 0.893, 0.993 at 2 to 7 s
    // (dt 1e-4 s: 0.307, 0.443, 0.593, 0.707, 0.864, 0.971)
    check_solid_fraction(&t, "fast quick", &[(2.0, 0.279), (3.0, 0.443), (4.0, 0.550), (5.0, 0.743), (6.0, 0.893), (7.0, 0.993)]);
    // Fig 10's end: "a unique block ... formed from half-solidified fragments", with small
    // fragments "with no links with the rest". Here: bonded fragments of the solid (type 2)
    let pieces = scene_common::fragments(&r, 2, 1);
    println!("fast quick: bonded fragments at 8 s (>= 1 particle): {} pieces, largest {:?}", pieces.len(), &pieces[..pieces.len().min(8)]);
    // measured: 74 pieces, the largest 14 particles of 140 (dt 1e-4 s: 87, 15): no unique block,
    // the gap of the README's "Measured against the paper"; bounds: the largest within 4 of that
    assert!((10..=19).contains(&pieces[0]) && pieces.len() >= 60, "fragments: {} pieces, largest {}", pieces.len(), pieces[0]);
    let (time, fs, plateau) = (col(&t, "Time"), col(&t, "f_phase"), col(&t, "f_phase[6]"));
    let (frozen, melted) = (col(&t, "f_phase[7]"), col(&t, "f_phase[8]"));
    let (created, deleted, broken, longest) = (col(&t, "f_phase[3]"), col(&t, "f_phase[4]"), col(&t, "f_brk[2]"), col(&t, "f_brk[4]"));
    let last = fs.len() - 1;
    // the pour ends when the ladle is lifted away (5 s) and what was left in it has landed
    let k_poured = time.iter().position(|&x| x >= 6.0 - 1e-9).unwrap();
    println!(
        "fast quick: solid fraction {}, solidification events {}, melting events {}, bonds created {}, deleted by melting {}, broken by stretching {} ({} by t = {}), longest bond {} m, bonds left {}",
        fs[last], frozen[last], melted[last], created[last], deleted[last], broken[last], broken[k_poured], time[k_poured], longest[last], col(&t, "Bonds")[last]
    );
    // no latent heat: no transition zone
    assert!(plateau.iter().all(|&p| p == 0.0));
    assert!(fs[last] > 0.8, "solid fraction at 8 s: {}", fs[last]);
    // mechanical breakage: bonds made by solidification are pulled beyond r_max and break
    // (30 measured with K = k_b; 27 to 36 when alpha, c0 or dt is changed by 5 to 10 %), while
    // metal is poured (all but at most a quarter of them before 6 s; measured 30 of 30)
    assert!(broken[last] >= 20.0, "bonds broken by stretching {}", broken[last]);
    assert!(broken[k_poured] >= 0.75 * broken[last], "{} of {} breaks before t = 6 s", broken[k_poured], broken[last]);
    // the paper's literal r_max = 0.04 m is never reached (see README)
    assert!(longest[last] < 0.04, "longest bond {}", longest[last]);
    // the hot second pour re-melts part of the crust of the first: solid particles melt again
    // and lose their bonds (measured 155 melting events, 63 bonds deleted; 133 to 153 and 58 to
    // 69 with the changes above)
    assert!(melted[last] >= 100.0, "melting events {}", melted[last]);
    assert!(deleted[last] >= 40.0, "bonds deleted by melting {}", deleted[last]);
    // what is left is bonded fragments, not sand (measured 70 bonds; 51 to 58 with the changes)
    assert!(col(&t, "Bonds")[last] >= 40.0, "bonds left {}", col(&t, "Bonds")[last]);
    // more solidification events than particles: re-melted particles solidify again
    assert!(frozen[last] > fs[last] * N + 20.0);
    assert_eq!(frozen[last] - melted[last], (fs[last] * N).round());
}

#[test]
#[ignore]
fn slow_casting_solidifies_completely() {
    let t = run_casting(&[]);
    let (time, fs) = (col(&t, "Time"), col(&t, "f_phase"));
    let worst = check_drops_are_remelts(&t);
    let k1 = fs.iter().position(|&f| f == 1.0).expect("never fully solid");
    println!("slow full: fully solid at t = {}, largest drop {worst}, melting events {}", time[k1], col(&t, "f_phase[8]")[fs.len() - 1]);
    assert!(fs[k1..].iter().all(|&f| f == 1.0));
    // measured: fully solid from 32.0 s (K = k_b)
    assert!(time[k1] < 40.0, "fully solid only at {}", time[k1]);
}
