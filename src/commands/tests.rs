use super::run_plain;
use crate::sim::Simulation;

#[test]
fn lj_melt_runs() {
    let mut sim = Simulation::new();
    sim.out.captured = Some(String::new());
    run_plain(&mut sim, &std::fs::read_to_string("/tmp/t1/in.lj").unwrap()).unwrap();
    println!("{}", sim.out.captured.as_ref().unwrap());
    let mut ids: Vec<usize> = (0..sim.atoms.nlocal).collect();
    ids.sort_by_key(|&i| sim.atoms.tag[i]);
    for &i in ids.iter().take(3) {
        println!("{} {:?} {:?}", sim.atoms.tag[i], sim.atoms.x[i], sim.atoms.v[i]);
    }
}
