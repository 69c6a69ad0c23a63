use super::run_plain;
use crate::sim::Simulation;

/// The LAMMPS LJ melt, run through the library: every atom stays, the total momentum (zero from
/// `velocity ... create`) stays zero, and fix nve keeps the total energy within 1% (the lattice
/// melting at T = 3 drifts it by 0.3%).
#[test]
fn lj_melt_runs() {
    let deck = "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 box\n\
                mass 1 1.0\nvelocity all create 3.0 87287 loop geom\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\n\
                neighbor 0.3 bin\nneigh_modify every 1 delay 0 check yes\nfix 1 all nve\nthermo_style custom step pe ke etotal\nthermo 100\nrun 100\n";
    let mut sim = Simulation::new();
    sim.out.captured = Some(String::new());
    run_plain(&mut sim, deck).unwrap();
    let a = &sim.state.atoms;
    assert_eq!(a.nlocal, 256);
    let p: [f64; 3] = std::array::from_fn(|k| a.v[..a.nlocal].iter().map(|v| v[k]).sum());
    assert!(p.iter().all(|c| c.abs() < 1e-10), "momentum {p:?}");
    // the thermo rows of steps 0 and 100: etotal is the last column
    let log = sim.out.captured.as_ref().unwrap();
    let etotal: Vec<f64> = log.lines().filter(|l| l.trim_start().starts_with("0 ") || l.trim_start().starts_with("100 ")).map(|l| l.split_whitespace().last().unwrap().parse().unwrap()).collect();
    assert_eq!(etotal.len(), 2, "{log}");
    assert!((etotal[1] - etotal[0]).abs() < 1e-2 * etotal[0].abs(), "{log}");
}
