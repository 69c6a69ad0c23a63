//! The BPM package against LAMMPS beyond what lammps_parity.rs compares (forces at step 0 and
//! positions, velocities, spins at the end): the orientations fix nve/bpm/sphere integrates
//! (the quaternions of atom_style bpm/sphere) after the run of lammps-refs/decks/in.bpm_sphere_nve,
//! and located errors for bad BPM input (pair bpm/spring is compared in lammps_parity.rs through
//! the bpm_pair_spring deck).
//!
//! * `stored_orientations`: against lammps-refs/refs/bpm_sphere_nve/quat.txt (runs everywhere).
//! * `live_orientations`: against LAMMPS run now (`dump custom ... quatw quati quatj quatk`).

use dmhs::deck::{run_file, run_text, DeckOptions};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Largest allowed difference of a quaternion component (they are of order 1).
const QUAT_TOL: f64 = 1e-9;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn deck() -> PathBuf {
    root().join("lammps-refs/decks/in.bpm_sphere_nve")
}

/// atom ID -> (w, i, j, k) from lines `id w i j k` (`#` lines and others skipped).
fn read_quats(text: &str) -> BTreeMap<i64, [f64; 4]> {
    text.lines()
        .filter_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            if w.len() != 5 {
                return None;
            }
            let id = w[0].parse().ok()?;
            let q: Vec<f64> = w[1..].iter().map(|s| s.parse().ok()).collect::<Option<_>>()?;
            Some((id, [q[0], q[1], q[2], q[3]]))
        })
        .collect()
}

fn dmhs_quats() -> BTreeMap<i64, [f64; 4]> {
    let d = deck();
    let opts = DeckOptions { screen: false, base_dir: Some(d.parent().unwrap().to_path_buf()), ..Default::default() };
    let run = run_file(&d, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let a = &run.sim.state.atoms;
    (0..a.nlocal).map(|i| (a.tag[i], a.quat[i])).collect()
}

fn compare(theirs: &BTreeMap<i64, [f64; 4]>) {
    let ours = dmhs_quats();
    assert_eq!(ours.keys().collect::<Vec<_>>(), theirs.keys().collect::<Vec<_>>(), "atom IDs");
    let mut worst = 0.0f64;
    let mut turned = 0.0f64;
    for (id, q) in &ours {
        let r = theirs[id];
        for c in 0..4 {
            worst = worst.max((q[c] - r[c]).abs());
        }
        turned = turned.max(1.0 - r[0].abs());
    }
    println!("orientations: max |q_dmhs - q_lammps| = {worst:.3e} (largest turn in LAMMPS: 1 - |w| = {turned:.3e})");
    assert!(turned > 1e-3, "the reference spheres hardly turned: the deck tests nothing");
    assert!(worst <= QUAT_TOL, "orientations differ from LAMMPS by {worst:e}");
}

#[test]
fn stored_orientations() {
    let text = std::fs::read_to_string(root().join("lammps-refs/refs/bpm_sphere_nve/quat.txt")).unwrap();
    compare(&read_quats(&text));
}

/// LAMMPS' orientations at the end of the deck: the deck with a dump of them before its run.
pub fn lammps_quats(deck: &Path) -> Result<BTreeMap<i64, [f64; 4]>, String> {
    let python = dmhs::tools::lammps::find_python()?;
    let lmp = dmhs::tools::lammps::find_lmp(&python)?;
    let tmp = tempfile::tempdir().map_err(|e| e.to_string())?;
    let text = std::fs::read_to_string(deck).map_err(|e| e.to_string())?;
    let dump = "compute dmhs_q all property/atom quatw quati quatj quatk\n\
dump dq all custom ${nsteps} quat.dump id c_dmhs_q[1] c_dmhs_q[2] c_dmhs_q[3] c_dmhs_q[4]\n\
dump_modify dq sort id format float %.17g\nrun";
    let text = text.replacen("\nrun ", &format!("\n{dump} "), 1);
    let dir = deck.parent().unwrap();
    std::fs::write(tmp.path().join("in.deck"), text).map_err(|e| e.to_string())?;
    for e in std::fs::read_dir(dir).map_err(|e| e.to_string())? {
        let p = e.map_err(|e| e.to_string())?.path();
        if p.extension().is_some_and(|x| x == "data") {
            std::fs::copy(&p, tmp.path().join(p.file_name().unwrap())).map_err(|e| e.to_string())?;
        }
    }
    let o = std::process::Command::new(&lmp)
        .args(["-in", "in.deck", "-log", "none", "-screen", "none"])
        .current_dir(tmp.path())
        .env("LD_LIBRARY_PATH", dmhs::tools::lammps::library_path(&python))
        .output()
        .map_err(|e| e.to_string())?;
    if !o.status.success() {
        return Err(format!("LAMMPS failed: {}", String::from_utf8_lossy(&o.stdout)));
    }
    let dumped = std::fs::read_to_string(tmp.path().join("quat.dump")).map_err(|e| e.to_string())?;
    // the last snapshot: the lines after the last ITEM: ATOMS header
    let last = dumped.rsplit("ITEM: ATOMS").next().unwrap_or("");
    Ok(read_quats(last))
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn live_orientations() {
    if dmhs::tools::lammps::python_for_live_test().is_none() {
        return;
    }
    compare(&lammps_quats(&deck()).unwrap());
}

/// The first error of a deck, rendered with its location.
fn error_of(deck: &str) -> String {
    let opts = DeckOptions { screen: false, ..Default::default() };
    match run_text("in.test", deck, &opts) {
        Ok(_) => panic!("deck ran without error:\n{deck}"),
        Err(f) => f.rendered,
    }
}

const BOX: &str = "units lj\nregion b block 0 4 0 4 0 4\ncreate_box 1 b bond/types 1 extra/bond/per/atom 4\ncreate_atoms 1 single 1 1 1\n";

#[test]
fn bad_input_is_located() {
    // the integrator needs orientations
    let e = error_of(&format!("atom_style sphere\n{BOX}fix 1 all nve/bpm/sphere\n"));
    assert!(e.contains("fix nve/bpm/sphere requires atom style bpm/sphere") && e.contains("in.test:6:"), "{e}");
    // disc is 2d only; other keywords are unknown
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}fix 1 all nve/bpm/sphere disc\n"));
    assert!(e.contains("disc requires a 2d simulation") && e.contains("in.test:6:"), "{e}");
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}fix 1 all nve/bpm/sphere dilate all\n"));
    assert!(e.contains("dilate") && e.contains("in.test:6:"), "{e}");
    // compute nbond/atom: keywords, and an atom style with bonds
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}compute 1 all nbond/atom foo\n"));
    assert!(e.contains("foo") && e.contains("in.test:6:"), "{e}");
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}compute 1 all nbond/atom bond/type\n"));
    assert!(e.contains("bond type") && e.contains("in.test:6:"), "{e}");
    let e = error_of("atom_style sphere\nunits lj\nregion b block 0 4 0 4 0 4\ncreate_box 1 b\ncompute 1 all nbond/atom\n");
    assert!(e.contains("requires an atom style with bonds") && e.contains("in.test:5:"), "{e}");
    // pair bpm/spring: keywords, coefficients (ka only with anharmonic yes), ghost velocities
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}pair_style bpm/spring smooth no\n"));
    assert!(e.contains("smooth") && e.contains("in.test:6:"), "{e}");
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}pair_style bpm/spring anharmonic yes\npair_coeff 1 1 1.0 1.0 1.0\n"));
    assert!(e.contains("ka") && e.contains("in.test:7:"), "{e}");
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}pair_style bpm/spring\npair_coeff 1 1 1.0 1.0 1.0 2.0\n"));
    assert!(e.contains("in.test:7:"), "{e}");
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}pair_style bpm/spring\npair_coeff 1 1 1.0 -1.0 1.0\n"));
    assert!(e.contains("cutoff") && e.contains("in.test:7:"), "{e}");
    let e = error_of(&format!("atom_style bpm/sphere\n{BOX}pair_style bpm/spring\npair_coeff 1 1 1.0 1.0 1.0\nrun 0\n"));
    assert!(e.contains("comm_modify vel yes"), "{e}");
    // the dynamic-radius flag is 0 or 1
    let e = error_of("atom_style bpm/sphere 2\n");
    assert!(e.contains("unexpected argument `2`") && e.contains("in.test:1:"), "{e}");
}

#[test]
fn created_atoms_have_identity_orientations_and_unit_spheres() {
    let deck = format!("atom_style bpm/sphere\n{BOX}create_atoms 1 single 2 2 2\nvelocity all set 0.1 0 0\nset atom 1 omega 0 0 2\nfix 1 all nve/bpm/sphere\ntimestep 0.01\nrun 100\n");
    let run = run_text("in.test", &deck, &DeckOptions { screen: false, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
    let a = &run.sim.state.atoms;
    let m = a.tag_map();
    let (i, j) = (m.get(1).unwrap(), m.get(2).unwrap());
    // LAMMPS' create_atom_post: diameter 1, density 1
    assert_eq!(a.radius[j], 0.5);
    assert_eq!(a.rmass[j], 4.0 * std::f64::consts::PI / 3.0 * 0.5 * 0.5 * 0.5);
    assert_eq!(a.quat[j], [1.0, 0.0, 0.0, 0.0]);
    // atom 1 spun at 2 about z for t = 1: turned by 2 rad, q = (cos 1, 0, 0, sin 1), to the
    // accuracy of Richardson's scheme at 0.02 rad a step (measured 1.4e-5)
    let q = a.quat[i];
    assert!((q[0] - 1f64.cos()).abs() < 3e-5 && (q[3] - 1f64.sin()).abs() < 3e-5 && q[1] == 0.0 && q[2] == 0.0, "{q:?}");
    assert!((a.x[i][0] - 1.1).abs() < 1e-12);
}

#[test]
fn orientations_survive_a_restart() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bpm.restart");
    let deck = format!(
        "atom_style bpm/sphere\n{BOX}create_atoms 1 single 2 2 2\nset atom 1 omega 0.3 -0.7 1.1\nset atom 2 omega -0.2 0.5 0.4\n\
         fix 1 all nve/bpm/sphere\ntimestep 0.01\nrun 37\nwrite_restart {}\n",
        file.display()
    );
    let opts = DeckOptions { screen: false, ..Default::default() };
    let before = run_text("in.test", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let read = format!("read_restart {}\n", file.display());
    let after = run_text("in.read", &read, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let quats = |a: &dmhs::engine::atoms::Atoms| -> BTreeMap<i64, [u64; 4]> { (0..a.nlocal).map(|i| (a.tag[i], a.quat[i].map(f64::to_bits))).collect() };
    let (q0, q1) = (quats(&before.sim.state.atoms), quats(&after.sim.state.atoms));
    assert_ne!(q0[&1], [1f64.to_bits(), 0, 0, 0], "atom 1 did not turn");
    assert_eq!(q0, q1);
    assert!(after.sim.state.atoms.features.quat);
}
