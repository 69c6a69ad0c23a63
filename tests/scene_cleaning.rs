//! Scene 4 of the paper (Fig 11, examples/scenes/cleaning): a protein soil deposit on a wall
//! absorbs water, swells, loses its adhesion at c = 0.5 and is washed off by the shear flow.
//! The fast variant of the deck runs here; the check reads the deck's own thermo columns:
//!
//! * v_nwall: soil particles on the wall (inside the deposit's footprint, one soil spacing of
//!   margin, up to twice the initial height; washed-off particles leave it downstream);
//! * c_cmax: the largest soil water concentration; c_rmax: the largest soil radius.

use dmhs::deck::{run_text, DeckOptions};
use dmhs::tools::plot_cmd::read_table;

#[test]
fn soil_stays_on_the_wall_until_it_is_wet_then_is_washed_off() {
    let dir = tempfile::tempdir().unwrap();
    let opts = DeckOptions {
        vars: vec![("fast".into(), vec!["1".into()])],
        capture_text: true,
        base_dir: Some(dir.path().to_path_buf()),
        ..Default::default()
    };
    let deck = include_str!("../examples/scenes/cleaning/in.cleaning");
    let run = run_text("in.cleaning", deck, &opts).map_err(|f| f.rendered).unwrap();
    let t = read_table(run.sim.out.captured.as_deref().unwrap()).unwrap();
    let col = |name: &str| -> Vec<f64> {
        let k = t.find(name).unwrap();
        t.rows.iter().map(|r| r[k]).collect()
    };
    let (time, cmax, rmax, nwall, mwall) = (col("Time"), col("c_cmax"), col("c_rmax"), col("v_nwall"), col("v_mwall"));
    assert_eq!(time.len(), 41, "thermo every nsteps/40");
    let n0 = nwall[0];
    assert!(n0 >= 40.0, "the deposit: {n0} particles");
    assert_eq!(mwall[0], 1.0);

    // while no soil particle has reached the threshold, every one stays on the wall
    let dry: Vec<usize> = (0..time.len()).filter(|&k| cmax[k] < 0.5).collect();
    assert!(dry.len() >= 5, "several samples before the threshold: {}", dry.len());
    for &k in &dry {
        assert_eq!(nwall[k], n0, "t = {}: c_max = {} < 0.5 but the soil on the wall fell to {}", time[k], cmax[k], nwall[k]);
    }
    // the first loss comes after the threshold is passed, and the soil keeps going
    let first_loss = (0..time.len()).find(|&k| nwall[k] < n0).expect("soil is washed off");
    assert!(cmax[first_loss] >= 0.5);
    let t_wet = time[dry.last().unwrap() + 1];
    println!("threshold passed at t = {t_wet} s, first loss at t = {} s, soil on the wall {} -> {} ({:.3} of the mass)", time[first_loss], n0, nwall.last().unwrap(), mwall.last().unwrap());
    assert!(*mwall.last().unwrap() < 0.9, "at least a tenth of the soil is washed off: {}", mwall.last().unwrap());
    // the soil swelled: the largest radius grew by more than a quarter from the dry 2.35e-5 m
    assert_eq!(rmax[0], 2.35e-5);
    assert!(*rmax.last().unwrap() > 1.25 * 2.35e-5, "{}", rmax.last().unwrap());
    assert!(dir.path().join("scene_cleaning.0.png").exists(), "the deck draws its pictures");

    // Fig 11 in numbers (README, "Measured against the paper"): the lag before the first loss
    // and the soil left on the wall against time. Measured at dt = 5e-6 s and 4e-6 s: first loss
    // at 0.015 s in both; left 43/43 at 0.015 s, 42/42 at 0.03 s, 39/40 at 0.045 s, 36/39 at
    // 0.06 s. Tolerance: that spread plus one particle (a washed-off particle can come round the
    // periodic channel and cross the footprint again).
    let at = |t: f64| (0..time.len()).find(|&k| (time[k] - t).abs() < 1e-9).unwrap_or_else(|| panic!("no sample at t = {t}"));
    assert!((time[first_loss] - 0.015).abs() < 0.0015 + 1e-9, "first loss at t = {} s, measured 0.015 s", time[first_loss]);
    for (t, lo, hi) in [(0.015, 42.0, 44.0), (0.03, 41.0, 43.0), (0.045, 38.0, 41.0), (0.06, 35.0, 40.0)] {
        let n = nwall[at(t)];
        println!("t = {t} s: {n} of {n0} soil particles on the wall");
        assert!(n >= lo && n <= hi, "t = {t} s: {n} soil particles on the wall, measured {lo}..{hi}");
    }
}

#[test]
fn count_and_mass_take_a_region() {
    // LAMMPS' count(group,region) and mass(group,region): the deck's measure of soil on the wall
    let deck = "units si\natom_style atomic\nregion box block 0 4 0 1 0 1 units box\ncreate_box 2 box\n\
        create_atoms 1 single 0.5 0.5 0.5 units box\ncreate_atoms 1 single 1.5 0.5 0.5 units box\n\
        create_atoms 2 single 2.5 0.5 0.5 units box\ncreate_atoms 1 single 3.5 0.5 0.5 units box\n\
        mass 1 2.0\nmass 2 5.0\nregion left block 0 2.6 INF INF INF INF units box\n\
        variable n equal count(all,left)\nvariable m equal mass(all,left)\nvariable n1 equal count(all)\n\
        print \"${n} ${m} ${n1}\"\n";
    let opts = DeckOptions { capture_text: true, ..Default::default() };
    let run = run_text("count", deck, &opts).map_err(|f| f.rendered).unwrap();
    let out = run.sim.out.captured.as_deref().unwrap();
    assert!(out.lines().any(|l| l == "3 9 4"), "{out}");
    let bad = "units si\natom_style atomic\nregion box block 0 1 0 1 0 1 units box\ncreate_box 1 box\nvariable n equal count(all,nowhere)\nprint \"${n}\"\n";
    let err = run_text("count", bad, &DeckOptions::default()).err().expect("unknown region").rendered;
    assert!(err.contains("region `nowhere` does not exist"), "{err}");
}
