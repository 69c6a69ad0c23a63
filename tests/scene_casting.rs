//! The paper's casting scene (Figs 9 and 10), examples/scenes/casting/in.casting: liquid poured
//! from a ladle into a cold mould, solidifying with latent heat (slow) or without it under strong
//! surface cooling (fast).
//!
//! Quick variants run here (`-var quick 1`: 4 s slow, 8 s fast); the full slow run (45 s, to
//! complete solidification) is `#[ignore]`d: `cargo test --release --test scene_casting -- --ignored`.

use dmhs::deck::{run_file, DeckOptions};
use dmhs::tools::validate::{parse_thermo, Thermo};
use std::path::Path;

fn run_casting(vars: &[(&str, &str)]) -> Thermo {
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/casting/in.casting");
    let mut all = vec![("img", "0")];
    all.extend_from_slice(vars);
    let opts = DeckOptions { capture_text: true, vars: all.iter().map(|(k, v)| (k.to_string(), vec![v.to_string()])).collect(), ..Default::default() };
    let r = run_file(&deck, &opts).unwrap_or_else(|e| panic!("{}", e.rendered));
    parse_thermo(r.sim.out.captured.as_ref().unwrap())
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
    let t = run_casting(&[("quick", "1")]);
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
    let t = run_casting(&[("quick", "1"), ("case", "fast")]);
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
