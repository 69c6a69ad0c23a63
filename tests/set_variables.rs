//! `set ... v_name` (issue 16): an atom-style variable gives each selected atom its own value,
//! evaluated over every atom with the values the earlier keywords set; random() and normal()
//! draw one number per atom in local order from one generator kept across evaluations;
//! missing variables, other styles and refused values are located errors with LAMMPS' words.
//! The LAMMPS parity deck is lammps-refs/decks/in.set_variables (tests/lammps_parity.rs).

use dmhs::deck::{run_text, DeckOptions};
use dmhs::engine::random_mars::RanMars;
use dmhs::sim::Simulation;

const BOX: &str = "units lj\natom_style sphere\nboundary p p f\nlattice sc 1.0\nregion box block 0 3 0 3 0 3\ncreate_box 2 box\ncreate_atoms 1 box\n";

fn run(extra: &str) -> Result<Simulation, String> {
    let deck = format!("{BOX}{extra}");
    run_text("set-test", &deck, &DeckOptions::default()).map(|r| r.sim).map_err(|f| f.rendered)
}

fn error(extra: &str) -> String {
    match run(extra) {
        Ok(_) => panic!("no error for {extra}"),
        Err(e) => e,
    }
}

fn by_tag(sim: &Simulation) -> Vec<usize> {
    let a = &sim.state.atoms;
    let mut idx: Vec<usize> = (0..a.nlocal).collect();
    idx.sort_by_key(|&i| a.tag[i]);
    idx
}

#[test]
fn each_atom_gets_its_own_value() {
    let sim = run("variable d atom 0.5+0.01*id\nset group all diameter v_d\n\
                   variable rho atom 2.0+x\nset type 1 density v_rho\n\
                   variable t atom 1+(id%2)\nset group all type v_t\n\
                   variable zero atom 0*id\nset type 2 diameter v_zero density v_rho\n\
                   variable w atom y-z\nset group all omega 0.5 v_w 0.0 vx v_w\n\
                   variable ix atom id%3\nset group all image v_ix NULL NULL\n")
    .unwrap();
    let a = &sim.state.atoms;
    for i in by_tag(&sim) {
        let id = a.tag[i] as f64;
        let t = 1 + (a.tag[i] % 2) as usize;
        assert_eq!(a.typ[i], t);
        // the density saw the radius the first set gave; type 2 became point particles
        // afterwards, whose mass is the density itself (LAMMPS)
        let rho = 2.0 + a.x[i][0];
        if t == 1 {
            let r = 0.5 * (0.5 + 0.01 * id);
            assert_eq!(a.radius[i], r);
            assert_eq!(a.rmass[i], 4.0 * std::f64::consts::PI / 3.0 * r * r * r * rho);
        } else {
            assert_eq!(a.radius[i], 0.0);
            assert_eq!(a.rmass[i], rho);
        }
        let w = a.x[i][1] - a.x[i][2];
        assert_eq!(a.omega[i], [0.5, w, 0.0]);
        assert_eq!(a.v[i][0], w);
        assert_eq!(a.image[i][0], (a.tag[i] % 3) as i32);
    }
}

#[test]
fn normal_draws_per_atom_and_the_stream_goes_on() {
    let sim = run("variable d atom normal(1.0,0.1,4321)\nset group all diameter v_d\nvariable u atom random(2.0,3.0,99)\nset group all vz v_u\n").unwrap();
    let a = &sim.state.atoms;
    // one generator, seeded by the first call (4321; the second seed is not used), drawing
    // in local order: create_atoms made the atoms in ID order
    let mut r = RanMars::new(4321);
    for i in 0..a.nlocal {
        assert_eq!(a.radius[i], 0.5 * (1.0 + 0.1 * r.gaussian()), "atom {}", a.tag[i]);
    }
    for i in 0..a.nlocal {
        assert_eq!(a.v[i][2], r.uniform() * (3.0 - 2.0) + 2.0, "atom {}", a.tag[i]);
    }
}

#[test]
fn errors_are_located_with_lammps_words() {
    let line = BOX.lines().count() + 2;
    let e = error("variable d equal 1.0\nset group all diameter v_nope\n");
    assert!(e.contains("Variable name v_nope for set command does not exist") && e.contains(&format!("set-test:{line}:24")), "{e}");
    let e = error("variable d equal 1.0\nset group all diameter v_d\n");
    assert!(e.contains("Variable v_d for set command is invalid style") && e.contains("equal-style"), "{e}");
    let e = error("variable d atom 1.0-0.1*id\nset group all diameter v_d\n");
    assert!(e.contains("Invalid diameter in set command") && e.contains("for atom 11"), "{e}");
    let e = error("variable t atom id\nset group all type v_t\n");
    assert!(e.contains("Invalid atom type in set command") && e.contains("for atom 3"), "{e}");
    let e = error("variable iz atom 1\nset group all image NULL NULL v_iz\n");
    assert!(e.contains("Cannot set variable image flag for non-periodic dimension"), "{e}");
    let e = error("set group all density 0.0\n");
    assert!(e.contains("Invalid density in set command"), "{e}");
    let e = error("variable d atom normal(1.0,0.1,-3)\nset group all diameter v_d\n");
    assert!(e.contains("Invalid math function in variable formula"), "{e}");
}

/// `fix wall/gran ... contacts` (LAMMPS' per-atom array: flag, force, contact point, radius;
/// zero away from the wall) and `group ID variable V` selecting the atoms where V is not zero,
/// as in.chute uses them (bit-identical to LAMMPS there: docs/validation.md).
#[test]
fn wall_contacts_feed_a_group_variable() {
    let deck = "units lj\natom_style sphere\nboundary p f p\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\n\
                create_atoms 1 single 1 0.45 1\ncreate_atoms 1 single 2 2 2\nset group all diameter 1.0\n\
                fix wall all wall/gran granular hooke 10.0 0.5 tangential linear_history 1.0 0.5 0.1 yplane 0.0 NULL contacts\n\
                run 0\nvariable touch atom f_wall[1]>0\ngroup floor variable touch\n";
    let sim = run_text("contacts-test", deck, &DeckOptions::default()).map_err(|f| f.rendered).unwrap().sim;
    let fix = sim.fixes.iter().find(|f| f.id() == "wall").unwrap();
    assert_eq!(fix.peratom_cols(), Some(8));
    let p = fix.peratom(&sim.state).unwrap();
    let a = &sim.state.atoms;
    let floor = sim.state.groups.bit("floor").unwrap();
    for i in 0..a.nlocal {
        let row: Vec<f64> = (0..8).map(|c| p.get(i, c)).collect();
        if a.tag[i] == 1 {
            // Hooke: k * overlap along +y, at the foot of the sphere on the plane
            assert!((row[2] - 10.0 * (0.5 - 0.45)).abs() < 1e-12, "{row:?}");
            assert_eq!([row[0], row[1], row[3], row[4], row[5], row[6], row[7]], [1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.5]);
            assert!(a.mask[i] & floor != 0);
        } else {
            assert_eq!(row, vec![0.0; 8]);
            assert!(a.mask[i] & floor == 0);
        }
    }
    let e = error("variable t equal 1\ngroup g variable t\n");
    assert!(e.contains("Variable t for group is invalid style"), "{e}");
}
