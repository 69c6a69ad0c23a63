//! Thermostat fixes (langevin, temp/rescale, temp/berendsen, temp/csvr, nvt) against LAMMPS, beyond the
//! per-atom state that tests/lammps_parity.rs compares: every column of the thermo table of the
//! lammps-refs decks thermo_* (temperature, energies and the fixes' own f_ID scalars) at every
//! printed step, against lammps-refs/refs/NAME/thermo.txt (and LAMMPS run now, when present).
//! And validations: long Langevin and CSVR runs hold the target temperature with the canonical
//! spread.

use dmhs::deck::{run_text, DeckOptions};

/// The thermostat decks (thermo_bias*: with the bias computes temp/partial, temp/com and
/// temp/region), and deposit_mol (langevin on a substrate, atoms inserted during the run,
/// `thermo_modify temp` of the inserted atoms).
const DECKS: [&str; 11] = ["thermo_rescale", "thermo_berendsen", "thermo_nvt", "thermo_langevin", "thermo_langevin_omega", "thermo_bias", "thermo_bias_nvt", "thermo_bias_region", "thermo_temp_ramp", "thermo_temp_profile", "deposit_mol"];

mod thermo_tables;
use thermo_tables::{root, table};

thermo_tables::thermo_table_tests!(DECKS);

/// An LJ liquid (500 atoms, density 0.8442) started at T 0.5 under fix langevin at T 1.2,
/// damp 0.5: after 1000 steps of equilibration the mean of 4000 steps (sampled every 20) must
/// be within 4 standard errors of 1.2. The canonical spread of T is T sqrt(2/(3N)) = 0.044
/// per sample; with the damping time of 100 steps about 40 samples are independent, so one
/// standard error is 0.007.
#[test]
fn langevin_holds_the_target_temperature() {
    let deck = "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 5 0 5 0 5\ncreate_box 1 box\n\
        create_atoms 1 box\nmass 1 1.0\nvelocity all create 0.5 4928459 loop geom\npair_style lj/cut 2.5\n\
        pair_coeff 1 1 1.0 1.0 2.5\nneighbor 0.3 bin\nfix 1 all nve\nfix 2 all langevin 1.2 1.2 0.5 699483 zero yes\n\
        timestep 0.005\nthermo 20\nrun 1000\nrun 4000\n";
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = run_text("langevin_liquid", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let (names, rows) = table(run.sim.out.captured.as_deref().unwrap());
    let t = names.iter().position(|c| c == "Temp").unwrap();
    let temps: Vec<f64> = rows[1..].iter().map(|r| r[t]).collect();
    assert_eq!(temps.len(), 200);
    let mean = temps.iter().sum::<f64>() / temps.len() as f64;
    let sd = (temps.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (temps.len() - 1) as f64).sqrt();
    println!("langevin liquid: mean T {mean:.4} (target 1.2), sample spread {sd:.4} (canonical {:.4})", 1.2 * (2.0f64 / 1500.0).sqrt());
    assert!((mean - 1.2).abs() < 4.0 * 0.007, "mean temperature {mean} is not the target 1.2");
    // the spread is the canonical one within 30 % (Langevin samples the canonical ensemble)
    assert!((sd / (1.2 * (2.0f64 / 1500.0).sqrt()) - 1.0).abs() < 0.3, "spread {sd}");
}

/// An ideal gas of 20 atoms (no pair forces: T moves only through the thermostat) under fix
/// temp/csvr at T 1.5, damp 0.1 (20 steps): over 40000 steps sampled every 50, the mean and the
/// spread of T are the canonical ones, 1.5 and 1.5 sqrt(2/57) (57 degrees of freedom), within 4
/// standard errors for the mean (800 nearly independent samples: 0.01) and 20% for the spread.
#[test]
fn csvr_samples_the_canonical_temperature() {
    let deck = "units lj\natom_style atomic\nregion box block 0 10 0 10 0 10\ncreate_box 1 box\n\
        create_atoms 1 random 20 4821 NULL\nmass 1 1.0\nvelocity all create 0.3 7731 loop geom\npair_style zero 1.0\n\
        pair_coeff * *\nfix 1 all nve\nfix 2 all temp/csvr 1.5 1.5 0.1 55117\nthermo 50\nrun 40000\n";
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = run_text("csvr_gas", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let (names, rows) = table(run.sim.out.captured.as_deref().unwrap());
    let t = names.iter().position(|c| c == "Temp").unwrap();
    let temps: Vec<f64> = rows[20..].iter().map(|r| r[t]).collect();
    let mean = temps.iter().sum::<f64>() / temps.len() as f64;
    let sd = (temps.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (temps.len() - 1) as f64).sqrt();
    let canonical = 1.5 * (2.0f64 / 57.0).sqrt();
    println!("csvr gas: mean T {mean:.4} (target 1.5), spread {sd:.4} (canonical {canonical:.4})");
    assert!((mean - 1.5).abs() < 4.0 * canonical / (temps.len() as f64).sqrt(), "mean temperature {mean}");
    assert!((sd / canonical - 1.0).abs() < 0.2, "spread {sd} against {canonical}");
}

/// A run restarted from a restart file goes on with fix temp/csvr's energy and random stream
/// (LAMMPS writes both): 10 steps after read_restart give the bits of the 10 steps that followed
/// write_restart in the first deck. (After an odd number of steps the stream holds the second
/// number of a Gaussian pair, which LAMMPS' RanMars state leaves out: there LAMMPS' restarted run
/// differs from its continued one, and dmhs' does the same.)
#[test]
fn csvr_restarts_its_random_stream() {
    let tmp = tempfile::tempdir().unwrap();
    let rs = tmp.path().join("rs.bin").display().to_string();
    let setup = "pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\nfix t all temp/csvr 1.0 1.0 0.1 4321\nthermo_style custom step temp f_t\nthermo_modify format float %.17g\nthermo 10\n";
    let first = format!("units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
        velocity all create 1.5 87287 loop geom\n{setup}run 100\nwrite_restart {rs}\nrun 10\n");
    let second = format!("read_restart {rs}\n{setup}run 10\n");
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let last_row = |name: &str, deck: &str| {
        let run = run_text(name, deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
        table(run.sim.out.captured.as_deref().unwrap()).1.last().unwrap().clone()
    };
    let a = last_row("csvr_first", &first);
    let b = last_row("csvr_second", &second);
    assert_eq!(a[0], 110.0);
    assert_eq!(a, b);
}

/// Bad thermostat commands give located errors (`dmhs check` on the langevin deck, edited).
#[test]
fn thermostat_errors_are_located() {
    let base = std::fs::read_to_string(root().join("lammps-refs/decks/in.thermo_langevin")).unwrap();
    let lang = "fix          2 all langevin v_tl 0.15 1.0 48279 scale 2 1.5 tally yes zero yes";
    for (to, want) in [
        ("fix 2 all langevin 0.1 0.1 1.0 0", "seed"),
        ("fix 2 all langevin 0.1 0.1 1.0 900000001", "seed"),
        ("fix 2 all langevin 0.1 0.1 0.0 5", "damp"),
        ("fix 2 all langevin 0.1 0.1 1.0 5 gjf vhalf", "gjf"),
        ("fix 2 all langevin 0.1 0.1 1.0 5 angmom 3.0", "angmom"),
        ("fix 2 all langevin 0.1 0.1 1.0 5 scale 3 1.0", "atom type"),
        ("fix 2 all langevin 0.1 0.1 1.0 5 wobble yes", "unknown keyword `wobble`"),
        ("fix 2 all temp/rescale 0 0.1 0.1 0.01 1.0", "N (steps between rescales)"),
        ("fix 2 all temp/berendsen 0.1 0.1", "damp"),
        ("fix 2 all temp/csvr 0.1 0.1 0.0 5", "Tdamp"),
        ("fix 2 all temp/csvr 0.1 0.1 1.0 0", "seed"),
        ("fix 2 all temp/csvr 0.1 0.1 1.0 5 extra", "unexpected"),
        ("fix 2 all nvt temp 0.1 0.1 0.0", "Tdamp"),
        ("fix 2 all nvt temp 0.0 0.1 1.0", "must be > 0.0"),
        ("fix 2 all nvt tchain 3", "needs temperature control"),
        ("fix 2 all nvt temp 0.1 0.1 1.0 iso 1.0 1.0 1.0", "pressure control"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\nfix_modify 2 temp nothere", "compute `nothere` does not exist"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute ke all ke\nfix_modify 2 temp ke", "is not a temperature fix_modify temp takes"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tp all temp/partial 0 1 2", "zflag"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tp all temp/partial 0 1", "zflag"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tr all temp/region nowhere", "Region nowhere for compute temp/region does not exist"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tc all temp/com extra", "compute ID group temp/com"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tr all temp/ramp vw 0 1 y 0 1", "vdim"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tr all temp/ramp vx 0 1 q 0 1", "dim"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tr all temp/ramp vx 0 1 y 0 1 units reduced", "units"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tr all temp/ramp vx 0 1 y 0", "chi"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tp all temp/profile 1 0 0 w 5", "bin style"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tp all temp/profile 1 0 0 xy 5", "Ny"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tp all temp/profile 1 0 0 x 0", "Nx"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tp all temp/profile 1 0 2 x 3", "zflag"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute tp all temp/profile 1 0 0 x 3 out bin", "out bin"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\nvelocity all scale 0.1 bias yes", "without temp keyword"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute t all temp\nvelocity all scale 0.1 temp t bias yes", "does not calculate a velocity bias"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute ke all ke\nvelocity all scale 0.1 temp ke", "is not a temperature dmhs' velocity takes"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\nfix_modify 2 energy yes", "fix_modify energy"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\ncompute t all temp\nfix_modify 1 temp t", "has no temperature"),
        ("fix 2 all langevin 0.1 0.1 1.0 5\nfix_modify 9 temp t", "fix `9` does not exist"),
    ] {
        let deck = base.replacen(lang, to, 1);
        assert_ne!(deck, base);
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("in.th");
        std::fs::write(&path, &deck).unwrap();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_dmhs")).arg("check").arg(&path).current_dir(tmp.path()).output().unwrap();
        let out = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
        assert_eq!(o.status.code(), Some(2), "{to}: {out}");
        assert!(out.contains(want) && out.contains("in.th:"), "{to}: expected `{want}`:\n{out}");
    }
}

/// `fix langevin omega yes` needs finite-size particles: refused when the run starts.
#[test]
fn langevin_omega_needs_spheres() {
    let base = std::fs::read_to_string(root().join("lammps-refs/decks/in.thermo_langevin")).unwrap();
    let deck = base.replace("tally yes zero yes", "omega yes").replace("run          ${nsteps}", "run 10");
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(root().join("lammps-refs/decks")), ..Default::default() };
    let err = run_text("in.omega", &deck, &opts).err().expect("a run error");
    assert!(err.rendered.contains("omega requires atom style sphere"), "{}", err.rendered);
}
