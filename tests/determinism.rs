//! Results are bit-identical whatever the number of threads (the slab-chunk pair loop gives
//! every atom its force contributions in a fixed order), and between repeated runs.

use dmhs::tools::cli::deck_dir;
use dmhs::tools::crosscheck::capture_state;
use dmhs::deck::{run_file, DeckOptions};
use std::path::PathBuf;

fn final_state(deck: &str, vars: &[(&str, &str)], threads: usize) -> String {
    let deck = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(deck);
    let opts = DeckOptions {
        vars: vars.iter().map(|(k, v)| (k.to_string(), vec![v.to_string()])).collect(),
        base_dir: Some(deck_dir(&deck)),
        ..Default::default()
    };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let run = pool.install(|| run_file(&deck, &opts)).map_err(|f| f.rendered).unwrap();
    capture_state(&run.sim).to_text()
}

#[test]
fn lj_3d_same_bits_on_1_2_and_4_threads() {
    let vars = [("n", "8"), ("nsteps", "300"), ("T", "1.0")];
    let one = final_state("lammps-refs/decks/in.lj3d_periodic", &vars, 1);
    assert_eq!(one, final_state("lammps-refs/decks/in.lj3d_periodic", &vars, 2));
    assert_eq!(one, final_state("lammps-refs/decks/in.lj3d_periodic", &vars, 4));
}

#[test]
fn chains_same_bits_on_1_and_3_threads() {
    let vars = [("nsteps", "300")];
    assert_eq!(final_state("lammps-refs/decks/in.chains_walls", &vars, 1), final_state("lammps-refs/decks/in.chains_walls", &vars, 3));
}
