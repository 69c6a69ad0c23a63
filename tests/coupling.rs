//! The DMHS coupling: no-slip at a wall of bonded elemental particles. Couette start-up flow
//! (examples/coupling/in.couette_bonded_wall) against the analytic series solution, at an early
//! time (the start-up profile) and near the steady state (the linear profile).

use dmhs::deck::{run_file, DeckOptions};
use std::path::PathBuf;

const U: f64 = 0.02;
/// Distance between the inner rows of the two walls, and the kinematic viscosity mu/rho0.
const H: f64 = 1.1;
const NU: f64 = 0.1;
const DT: f64 = 0.005;

/// u(y, t) for a plate at y = H set moving at U at t = 0 above one at rest at y = 0.
pub fn couette_startup(y: f64, t: f64) -> f64 {
    let mut u = U * y / H;
    for n in 1..2000 {
        let nf = n as f64;
        let sign = if n % 2 == 1 { 1.0 } else { -1.0 };
        u -= 2.0 * U / std::f64::consts::PI * sign / nf * (nf * std::f64::consts::PI * y / H).sin() * (-nf * nf * std::f64::consts::PI.powi(2) * NU * t / (H * H)).exp();
    }
    u
}

/// Mean fluid vx per row (y = 0.1 .. 1.0) after `nsteps`, and the largest |u - analytic| / U.
fn run(nsteps: usize) -> (Vec<(f64, f64, f64)>, f64) {
    let deck = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/coupling/in.couette_bonded_wall");
    let opts = DeckOptions { vars: vec![("nsteps".into(), vec![nsteps.to_string()])], base_dir: Some(deck.parent().unwrap().to_path_buf()), ..Default::default() };
    let sim = run_file(&deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered)).sim;
    let a = &sim.state.atoms;
    let t = nsteps as f64 * DT;
    let mut rows = vec![];
    for r in 1..=10 {
        let y0 = r as f64 * 0.1;
        let (mut s, mut ys, mut n) = (0.0, 0.0, 0.0);
        for i in 0..a.nlocal {
            if a.typ[i] == 1 && (a.x[i][1] - y0).abs() < 0.05 {
                s += a.v[i][0];
                ys += a.x[i][1];
                n += 1.0;
            }
        }
        assert!(n > 0.0, "no fluid in row {r}");
        let y = ys / n;
        rows.push((y, s / n, couette_startup(y, t)));
    }
    let err = rows.iter().map(|(_, u, ua)| (u - ua).abs() / U).fold(0.0, f64::max);
    (rows, err)
}

#[test]
fn couette_past_bonded_walls_matches_the_analytic_profile() {
    for (nsteps, tol) in [(400, 0.03), (4000, 0.02)] {
        let (rows, err) = run(nsteps);
        println!("t = {}: max |u - u_exact| / U = {err:.4}", nsteps as f64 * DT);
        for (y, u, ua) in &rows {
            println!("  y {y:.4}  u/U {:.5}  exact {:.5}", u / U, ua / U);
        }
        assert!(err < tol, "t = {}: error {err} > {tol}", nsteps as f64 * DT);
    }
}

/// A bonded chain 1-2-3-4 (atom_style hybrid sph bond, periodic 10 x 10 box) at x positions
/// `x` with energies `esph` (cv = 1), written as `chain.data` into `dir`.
fn write_chain(dir: &std::path::Path, x: [f64; 4], esph: [f64; 4]) {
    let atoms: String = (0..4).map(|k| format!("{} 1 {} 5 0 1.0 {} 1.0 1\n", k + 1, x[k], esph[k])).collect();
    let data = format!(
        "chain\n\n4 atoms\n1 atom types\n3 bonds\n1 bond types\n\n0 10 xlo xhi\n0 10 ylo yhi\n-0.5 0.5 zlo zhi\n\nMasses\n\n1 1.0\n\n\
Atoms # hybrid sph bond\n\n{atoms}\nBonds\n\n1 1 1 2\n2 1 2 3\n3 1 3 4\n"
    );
    std::fs::write(dir.join("chain.data"), data).unwrap();
}

/// A chain 1-2-3-4 (atom_style hybrid sph bond) whose atom 2 is hot (esph/cv = 5 > Tmax = 2):
/// dmhs/bond/break with the temperature criterion breaks both bonds of atom 2 on the first
/// check and keeps 3-4; Rmax is too long for the distance rule to act.
#[test]
fn temperature_criterion_breaks_every_bond_of_a_hot_atom() {
    let dir = tempfile::tempdir().unwrap();
    write_chain(dir.path(), [1.0, 2.0, 3.0, 4.0], [1.0, 5.0, 1.0, 1.9]);
    let deck = "units lj\ndimension 2\natom_style hybrid sph bond\nboundary p p p\nread_data chain.data\nbond_style harmonic\nbond_coeff 1 10.0 1.0\n\
pair_style zero 1.0\npair_coeff * *\nfix hot all dmhs/bond/break 1 1 5.0 temp 2.0\nthermo_style custom step f_hot[1] f_hot[2]\nrun 3\n";
    let path = dir.path().join("in.hot");
    std::fs::write(&path, deck).unwrap();
    let opts = DeckOptions { base_dir: Some(dir.path().to_path_buf()), ..Default::default() };
    let mut sim = run_file(&path, &opts).unwrap_or_else(|f| panic!("{}", f.rendered)).sim;
    let bonds: Vec<[i64; 2]> = sim.state.topo.bonds.iter().map(|b| b.atoms).collect();
    assert_eq!(bonds, vec![[3, 4]]);
    use dmhs::parser::EvalContext;
    assert_eq!(sim.fix_value("hot", Some(2)).unwrap(), 2.0);
    // broken on step 1; nothing more on steps 2 and 3
    assert_eq!(sim.fix_value("hot", Some(1)).unwrap(), 0.0);
}

/// dmhs/bond/break's f_ID[3] / f_ID[4]: the longest checked bond at the last check and since the
/// fix was defined. A static chain with bonds 1.0, 1.5 and 2.5 long and Rmax 2.0: step 1 sees
/// 2.5 and breaks 3-4; step 2 sees 1.5 as the longest, the running maximum stays 2.5.
#[test]
fn dmhs_bond_break_reports_the_longest_bond() {
    let dir = tempfile::tempdir().unwrap();
    write_chain(dir.path(), [1.0, 2.0, 3.5, 6.0], [1.0; 4]);
    let deck = |fix: &str, steps: u32| {
        format!("units lj\ndimension 2\natom_style hybrid sph bond\nboundary p p p\nread_data chain.data\nbond_style harmonic\nbond_coeff 1 10.0 1.0\n\
pair_style zero 3.0\npair_coeff * *\n{fix}\nrun {steps}\n")
    };
    let path = dir.path().join("in.long");
    let opts = DeckOptions { base_dir: Some(dir.path().to_path_buf()), ..Default::default() };
    use dmhs::parser::EvalContext;
    let expect = [(1, 2.5, 2.5, 1.0), (2, 1.5, 2.5, 0.0)];
    for (steps, last, ever, broken_last) in expect {
        std::fs::write(&path, deck("fix b all dmhs/bond/break 1 1 2.0", steps)).unwrap();
        let mut sim = run_file(&path, &opts).unwrap_or_else(|f| panic!("{}", f.rendered)).sim;
        assert!((sim.fix_value("b", Some(3)).unwrap() - last).abs() < 1e-12, "step {steps}");
        assert!((sim.fix_value("b", Some(4)).unwrap() - ever).abs() < 1e-12, "step {steps}");
        assert_eq!(sim.fix_value("b", Some(1)).unwrap(), broken_last);
        assert_eq!(sim.fix_value("b", Some(2)).unwrap(), 1.0);
    }
    // LAMMPS' bond/break has two values only
    std::fs::write(&path, deck("fix b all bond/break 1 1 2.0", 1)).unwrap();
    let mut sim = run_file(&path, &opts).unwrap_or_else(|f| panic!("{}", f.rendered)).sim;
    assert!(sim.fix_value("b", Some(3)).is_err());
}

#[test]
fn bond_fix_errors_name_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let data = "chain\n\n2 atoms\n1 atom types\n1 bonds\n1 bond types\n\n0 10 xlo xhi\n0 10 ylo yhi\n-0.5 0.5 zlo zhi\n\nMasses\n\n1 1.0\n\n\
Atoms # bond\n\n1 1 1 1.0 5 0\n2 1 1 2.0 5 0\n\nBonds\n\n1 1 1 2\n";
    std::fs::write(dir.path().join("d.data"), data).unwrap();
    for (fix, expect) in [
        ("fix b all bond/break 1 2 1.5", "bond type"),
        ("fix b all bond/break 0 1 1.5", "Nevery"),
        ("fix b all dmhs/bond/break 1 1 1.5 temp 2.0", "sph"),
        ("fix b all bond/break 1 1 1.5 temp 2.0", "temp"),
        ("fix b all bond/create 1 1 1 1.5 1 iparam 1 1 jparam 2 1", "Inconsistent"),
    ] {
        let deck = format!("units lj\ndimension 2\natom_style bond\nread_data d.data\nbond_style harmonic\nbond_coeff 1 1 1\n{fix}\n");
        let path = dir.path().join("in.bad");
        std::fs::write(&path, deck).unwrap();
        let opts = DeckOptions { base_dir: Some(dir.path().to_path_buf()), ..Default::default() };
        let err = run_file(&path, &opts).err().unwrap_or_else(|| panic!("`{fix}` was accepted")).rendered;
        assert!(err.contains(expect) && err.contains("in.bad:7"), "`{fix}`: {err}");
    }
}
