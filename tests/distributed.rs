//! A deck run over several ranks (spatial decomposition; ranks as threads of this process,
//! connected as MPI ranks are) gives the serial run's numbers: the thermo table and the final
//! positions and velocities, within round-off of the different order of the force sums.

use dmhs::deck::{run_text_on, DeckOptions};
use dmhs::engine::comm::{Comm, Threads};
use std::sync::Arc;

/// The screen text, and (ID, x, v) of every atom sorted by ID, of rank 0 after the deck.
type Outcome = (String, Vec<(i64, [f64; 3], [f64; 3])>);

fn outcome(run: &dmhs::deck::DeckRun) -> Outcome {
    let a = &run.sim.state.atoms;
    let mut atoms: Vec<_> = (0..a.nlocal).map(|i| (a.tag[i], a.x[i], a.v[i])).collect();
    atoms.sort_by_key(|t| t.0);
    (run.sim.out.captured.clone().unwrap_or_default(), atoms)
}

fn options() -> DeckOptions {
    DeckOptions { screen: false, capture_text: true, ..Default::default() }
}

/// Run `deck` on `n` ranks; every rank's outcome (or its error), by rank.
fn on_ranks(deck: &str, n: usize) -> Vec<Result<Outcome, String>> {
    on_ranks_with(deck, n, &options())
}

/// [`on_ranks`] with the deck options `opts` (a folder for its relative paths, variables).
fn on_ranks_with(deck: &str, n: usize, opts: &DeckOptions) -> Vec<Result<Outcome, String>> {
    let world = Threads::world(n);
    let handles: Vec<_> = world
        .into_iter()
        .map(|c| {
            let (deck, opts) = (deck.to_string(), opts.clone());
            std::thread::spawn(move || {
                let comm: Arc<dyn Comm> = Arc::new(c);
                match run_text_on("deck", &deck, &opts, Some(comm)) {
                    Ok(run) => Ok(outcome(&run)),
                    Err(f) => Err(f.rendered),
                }
            })
        })
        .collect();
    handles.into_iter().map(|h| h.join().unwrap_or_else(|_| Err("rank panicked".into()))).collect()
}

fn serial(deck: &str) -> Outcome {
    serial_with(deck, &options())
}

fn serial_with(deck: &str, opts: &DeckOptions) -> Outcome {
    outcome(&dmhs::deck::run_text("deck", deck, opts).unwrap_or_else(|f| panic!("{}", f.rendered)))
}

/// The numbers of the thermo rows (lines that start with a step number).
fn thermo_rows(text: &str) -> Vec<Vec<f64>> {
    let mut rows = Vec::new();
    let mut in_table = false;
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() == Some(&"Step") {
            in_table = true;
            continue;
        }
        if line.starts_with("Loop time") {
            in_table = false;
        }
        if in_table {
            if let Ok(v) = words.iter().map(|w| w.parse::<f64>()).collect::<Result<Vec<_>, _>>() {
                rows.push(v);
            }
        }
    }
    rows
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

const MELT: &str = "
units        lj
atom_style   atomic
lattice      fcc 0.8442
region       box block 0 6 0 6 0 6
create_box   1 box
create_atoms 1 box
mass         1 1.0
velocity     all create 3.0 87287 loop geom
pair_style   lj/cut 2.5
pair_coeff   1 1 1.0 1.0 2.5
neighbor     0.3 bin
neigh_modify every 20 delay 0 check no
fix          1 all nve
thermo_style custom step temp epair emol etotal press atoms
thermo       50
run          150
run          100
";

/// The melt with `text` in place of its fix nve and thermo_style lines, its neighbour lists
/// rebuilt when atoms moved far enough.
fn melt_with(text: &str) -> String {
    MELT.replace("fix          1 all nve\nthermo_style custom step temp epair emol etotal press atoms\n", text).replace("check no\n", "check yes\n")
}

fn compare(deck: &str, ranks: usize) {
    compare_decks(deck, deck, ranks, 1e-9);
}

/// [`compare`] of `serial_deck` run serially with `ranks_deck` run on ranks (decks that differ
/// only in where they write), the atoms' positions and velocities within `atom_tol`.
fn compare_decks(serial_deck: &str, ranks_deck: &str, ranks: usize, atom_tol: f64) {
    compare_decks_with(serial_deck, ranks_deck, ranks, atom_tol, &options());
}

/// [`compare_decks`] with the deck options `opts`.
fn compare_decks_with(serial_deck: &str, ranks_deck: &str, ranks: usize, atom_tol: f64, opts: &DeckOptions) {
    let (text0, atoms0) = serial_with(serial_deck, opts);
    let rows0 = thermo_rows(&text0);
    assert!(rows0.len() >= 7, "serial thermo rows: {text0}");
    let results = on_ranks_with(ranks_deck, ranks, opts);
    let errors: Vec<String> = results.iter().enumerate().filter_map(|(k, r)| r.as_ref().err().map(|e| format!("rank {k}: {e}"))).collect();
    assert!(errors.is_empty(), "{ranks} ranks:\n{}", errors.join("\n"));
    for (rank, r) in results.into_iter().enumerate() {
        let (text, atoms) = r.unwrap();
        assert_eq!(atoms.len(), atoms0.len(), "rank {rank} of {ranks} holds every atom after the runs");
        for (a, b) in atoms.iter().zip(&atoms0) {
            assert_eq!(a.0, b.0);
            for d in 0..3 {
                assert!(close(a.1[d], b.1[d], atom_tol) && close(a.2[d], b.2[d], atom_tol), "{ranks} ranks, atom {}: x {:?} v {:?} against serial {:?} {:?}", a.0, a.1, a.2, b.1, b.2);
            }
        }
        if rank == 0 {
            let rows = thermo_rows(&text);
            assert_eq!(rows.len(), rows0.len(), "{text}");
            for (r, r0) in rows.iter().zip(&rows0) {
                for (x, y) in r.iter().zip(r0) {
                    assert!(close(*x, *y, 1e-9), "{ranks} ranks: thermo row {r:?} against serial {r0:?}");
                }
            }
            assert!(text.contains(&format!("on {ranks} procs for")) && text.contains(&format!("steps with {} atoms", atoms0.len())), "{text}");
            assert!(text.contains("MPI processor grid"), "{text}");
        } else {
            assert!(text.is_empty(), "rank {rank} writes nothing: {text}");
        }
    }
}

/// The errors of a deck each of `n` thread-ranks must refuse (a rank that runs it fails the test).
fn refusals(deck: &str, n: usize) -> Vec<String> {
    refusals_with(deck, n, &options())
}

/// [`refusals`] with the deck options `opts`.
fn refusals_with(deck: &str, n: usize, opts: &DeckOptions) -> Vec<String> {
    on_ranks_with(deck, n, opts).into_iter().map(|r| r.err().expect("refused")).collect()
}

/// The `--features mpi` build (DMHS_MPI_BIN) and the launcher (DMHS_MPIEXEC, default `mpiexec`)
/// of the live MPI tests.
fn mpi_launcher() -> (String, String) {
    let bin = std::env::var("DMHS_MPI_BIN").expect("DMHS_MPI_BIN: a dmhs built with `cargo build --release --features mpi`");
    assert!(std::path::Path::new(&bin).is_file(), "DMHS_MPI_BIN={bin} is not a file");
    (bin, std::env::var("DMHS_MPIEXEC").unwrap_or_else(|_| "mpiexec".into()))
}

#[test]
fn lj_melt_on_two_ranks_is_the_serial_run() {
    compare(MELT, 2);
}

#[test]
fn lj_melt_on_three_and_four_ranks_is_the_serial_run() {
    compare(MELT, 3);
    compare(MELT, 4);
}

/// A data file of `n` x `n` zigzag bead-spring chains of 10 beads along x in a periodic cube
/// of side 12 (chains cross the periodic face), with bonds, angles and dihedrals.
fn chains_data(n: usize) -> String {
    let (beads, side) = (10usize, 12.0);
    let nchains = n * n;
    let natoms = nchains * beads;
    let mut atoms = String::new();
    let (mut bonds, mut angles, mut dihedrals) = (String::new(), String::new(), String::new());
    let (mut nb, mut na, mut nd) = (0, 0, 0);
    for c in 0..nchains {
        let (y0, z0) = (0.3 + side / n as f64 * (c % n) as f64, 0.3 + side / n as f64 * (c / n) as f64);
        let x0 = 1.7 * c as f64 % side;
        for k in 0..beads {
            let id = c * beads + k + 1;
            let x = (x0 + 0.9 * k as f64) % side;
            let (y, z) = (y0 + 0.35 * (k % 2) as f64, z0 + 0.35 * ((k / 2) % 2) as f64);
            atoms += &format!("{id} {} 1 {x} {y} {z}\n", c + 1);
            if k >= 1 {
                nb += 1;
                bonds += &format!("{nb} 1 {} {id}\n", id - 1);
            }
            if k >= 2 {
                na += 1;
                angles += &format!("{na} 1 {} {} {id}\n", id - 2, id - 1);
            }
            if k >= 3 {
                nd += 1;
                dihedrals += &format!("{nd} 1 {} {} {} {id}\n", id - 3, id - 2, id - 1);
            }
        }
    }
    format!(
        "chains\n\n{natoms} atoms\n{nb} bonds\n{na} angles\n{nd} dihedrals\n1 atom types\n1 bond types\n1 angle types\n1 dihedral types\n\n0 {side} xlo xhi\n0 {side} ylo yhi\n0 {side} zlo zhi\n\nMasses\n\n1 1.0\n\nAtoms # molecular\n\n{atoms}\nBonds\n\n{bonds}\nAngles\n\n{angles}\nDihedrals\n\n{dihedrals}"
    )
}

/// Bead-spring chains whose bonds, angles and dihedrals cross rank boundaries and periodic
/// faces (the bonded partners within the ghost cutoff: comm_modify cutoff for the dihedrals).
fn chains_deck(dir: &std::path::Path, bond: &str) -> String {
    std::fs::write(dir.join("chains.data"), chains_data(6)).unwrap();
    format!(
        "
units        lj
atom_style   molecular
processors   * 1 1
read_data    {}/chains.data
{bond}
angle_style  harmonic
angle_coeff  1 3.0 150.0
dihedral_style harmonic
dihedral_coeff 1 0.5 1 2
pair_style   lj/cut 1.122462048309373
pair_coeff   1 1 1.0 1.0
pair_modify  shift yes
special_bonds lj 0.0 1.0 1.0
comm_modify  cutoff 2.5
neighbor     0.4 bin
neigh_modify every 1 delay 0 check yes
velocity     all create 1.0 4928459 loop geom
fix          1 all nve
thermo_style custom step temp epair ebond eangle edihed etotal press atoms
thermo       50
timestep     0.004
run          150
run          100
",
        dir.display()
    )
}

#[test]
fn bonded_chains_across_ranks_are_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    compare(&chains_deck(dir.path(), "bond_style   harmonic\nbond_coeff   1 100.0 0.97"), 2);
    let fene = chains_deck(dir.path(), "bond_style   fene\nbond_coeff   1 30.0 1.5 1.0 1.0").replace("special_bonds lj 0.0 1.0 1.0", "special_bonds fene");
    compare(&fene, 4);
}

#[test]
fn a_bond_longer_than_the_ghost_cutoff_stops_every_rank() {
    let dir = tempfile::tempdir().unwrap();
    let deck = chains_deck(dir.path(), "bond_style   harmonic\nbond_coeff   1 100.0 0.97").replace("comm_modify  cutoff 2.5\n", "");
    for e in refusals(&deck, 4) {
        assert!(e.contains("is missing on this rank") && e.contains("beyond the ghost cutoff"), "{e}");
    }
}

/// Spheres falling onto a granular wall and settling: contacts with tangential, rolling and
/// twisting history cross rank boundaries and move between ranks with their atoms.
fn granular_deck(pair: &str, wall: &str) -> String {
    format!(
        "
units        lj
atom_style   sphere
boundary     p p f
comm_modify  vel yes
region       box block 0 8 0 8 0 24
create_box   1 box
lattice      sc 0.6
region       fill block 0 8 0 8 2 12 units box
create_atoms 1 region fill
set          type 1 diameter 1.0
set          type 1 density 1.0
velocity     all create 0.5 87287 loop geom
{pair}
pair_coeff   * *
fix          1 all nve/sphere
fix          2 all gravity 1.0 vector 0 0 -1
fix          3 all wall/gran {wall} zplane 0.0 NULL
compute      erot all erotate/sphere
compute      ts all temp/sphere
thermo_style custom step ke c_erot c_ts press f_2 atoms
thermo       100
timestep     0.002
run          800
run          400
"
    )
}

#[test]
fn granular_spheres_settling_across_ranks_are_the_serial_run() {
    compare(&granular_deck("pair_style   gran/hertz/history 2000.0 NULL 50.0 NULL 0.5 1", "hertz/history 2000.0 NULL 50.0 NULL 0.5 1"), 2);
    let granular = "pair_style   granular\npair_coeff   * * hertz/material 1e4 0.3 0.3 tangential mindlin NULL 1.0 0.5 rolling sds 500 50 0.1 twisting marshall damping tsuji";
    // a shorter horizon: this pile amplifies round-off faster (LAMMPS' own runs on 1 and 4
    // ranks differ by 1e-4 in kinetic energy by step 1200)
    let deck = granular_deck(granular, "granular hertz/material 1e4 0.3 0.3 tangential mindlin NULL 1.0 0.5 damping tsuji").replace("pair_coeff   * *\n", "");
    compare(&deck.replace("run          800\nrun          400\n", "run          300\nrun          200\n"), 4);
}

#[test]
fn an_error_on_one_rank_stops_every_rank_without_hanging() {
    // the bond is stored on atom 1 (rank 0), whose partner lies beyond rank 0's ghosts; rank 1
    // owns the partner and has nothing to fail on
    let dir = tempfile::tempdir().unwrap();
    let data = "one bond\n\n3 atoms\n1 bonds\n1 atom types\n1 bond types\n\n0 12 xlo xhi\n0 12 ylo yhi\n0 12 zlo zhi\n\nMasses\n\n1 1.0\n\nAtoms # bond\n\n1 1 1 5.5 6 6\n2 1 1 8.5 6 6\n3 2 1 1.0 1.0 1.0\n\nBonds\n\n1 1 1 2\n";
    std::fs::write(dir.path().join("bond.data"), data).unwrap();
    let deck = format!(
        "units lj\natom_style bond\nprocessors 2 1 1\nread_data {}/bond.data\nbond_style harmonic\nbond_coeff 1 10.0 3.0\npair_style lj/cut 1.12\npair_coeff 1 1 1.0 1.0\nfix 1 all nve\nrun 10\n",
        dir.path().display()
    );
    let results = on_ranks(&deck, 2);
    for r in &results {
        let e = r.as_ref().err().expect("refused");
        assert!(e.contains("on rank 0 of 2") && e.contains("bond atom 2 is missing"), "{e}");
    }
}

/// A fix's error in the setup of a run on one rank only (fix wall/lj93 finds an atom of that
/// rank on its surface) stops every rank with that error instead of leaving the others
/// waiting (they hung before 2026-12-05).
#[test]
fn a_setup_error_on_one_rank_stops_every_rank() {
    let deck = MELT.replace("lattice      fcc 0.8442\n", "boundary     p p f\nlattice      fcc 0.8442\n")
        .replace("region       box block 0 6 0 6 0 6", "processors   1 1 2\nregion       box block 0 6 0 6 0 6.25")
        .replace("fix          1 all nve\n", "fix          1 all nve\nfix          w all wall/lj93 zlo EDGE 1.0 1.0 2.5\n");
    for (rank, r) in on_ranks(&deck, 2).iter().enumerate() {
        let e = r.as_ref().err().unwrap_or_else(|| panic!("rank {rank} ran"));
        assert!(e.contains("on rank 0 of 2") && e.contains("on or inside the wall surface"), "rank {rank}: {e}");
    }
}

#[test]
fn a_settled_pile_is_balanced_over_the_ranks() {
    // the spheres settle into the lowest sixth of the box, which a uniform cut along z would
    // leave to one rank
    for r in on_ranks(&granular_deck("pair_style   gran/hertz/history 2000.0 NULL 50.0 NULL 0.5 1", "hertz/history 2000.0 NULL 50.0 NULL 0.5 1"), 2) {
        let (text, _) = r.unwrap();
        if let Some(line) = text.lines().filter(|l| l.starts_with("Nlocal:")).last() {
            let w: Vec<f64> = line.split_whitespace().filter_map(|x| x.parse().ok()).collect();
            let (ave, max, min) = (w[0], w[1], w[2]);
            assert!(max <= 1.25 * ave && min >= 0.75 * ave, "atoms per rank: {line}");
        }
    }
}

#[test]
fn a_2d_deck_with_fixed_walls_on_four_ranks() {
    let deck = "
units        lj
dimension    2
atom_style   atomic
boundary     p f p
lattice      sq2 0.8
region       box block 0 16 0 10 -0.5 0.5
create_box   1 box
region       gas block 0 16 1 9 -0.5 0.5
create_atoms 1 region gas
mass         1 1.0
velocity     all create 0.2 4928 loop geom
pair_style   lj/cut 2.5
pair_coeff   1 1 1.0 1.0 2.5
fix          1 all nve
fix          2 all enforce2d
thermo_style custom step temp epair etotal press
thermo       100
run          200
";
    let (text0, atoms0) = serial(deck);
    for r in on_ranks(deck, 4) {
        let (_, atoms) = r.unwrap();
        assert_eq!(atoms.len(), atoms0.len(), "{text0}");
        for (a, b) in atoms.iter().zip(&atoms0) {
            for d in 0..2 {
                assert!(close(a.1[d], b.1[d], 1e-9), "atom {}: {:?} against serial {:?}", a.0, a.1, b.1);
            }
        }
    }
}

/// An SPH fluid (density summation, Tait pressure, fix sph) with a sorted dump (positions,
/// velocities, compute sph/rho/atom, sph/e/atom and displace/atom, evaluated by rank 0 on the
/// gathered atoms). At the first
/// setup of fix sph a ghost keeps the velocity estimate it had when it was made (LAMMPS' own
/// order), so in LAMMPS step 0 of a first run depends on which neighbours are ghosts (measured:
/// LAMMPS' press at step 0 is 0.16084 on one rank and 0.15994 on two for this fluid without
/// `run 0`). dmhs on ranks gives the serial run's step 0 (src/sim/stale_vest.rs).
const SPH: &str = "
units        lj
dimension    2
atom_style   sph
boundary     p p p
lattice      sq 1.0
region       box block 0 20 0 12 -0.1 0.1 units box
create_box   1 box
create_atoms 1 box
mass         1 1.0
set          type 1 sph/rho 1.0
velocity     all create 0.05 2837 loop geom
pair_style   hybrid/overlay sph/rhosum 1 sph/taitwater
pair_coeff   * * sph/rhosum 2.4
pair_coeff   * * sph/taitwater 1.0 10.0 0.1 2.4
fix          1 all sph
fix          2 all enforce2d
fix          3 all addforce 0.002 0.0 0.0
region       wall block INF INF 0 1.5 INF INF units box
fix          4 all setforce NULL 0.0 NULL region wall
timestep     0.005
compute      rho all sph/rho/atom
compute      e all sph/e/atom
compute      dx all displace/atom
dump         d all custom 100 dump.sph id x y vx vy c_rho c_e c_dx[1] c_dx[4]
dump_modify  d sort id
thermo_style custom step ke pe f_3[1] f_4[2]
thermo       50
run          0 post no
run          200
";

/// The numbers of a text file, in order.
fn numbers(text: &str) -> Vec<f64> {
    text.split_whitespace().filter_map(|w| w.parse::<f64>().ok()).collect()
}

#[test]
fn an_sph_fluid_and_its_dump_on_four_ranks() {
    let run_in = |ranks: usize| {
        let dir = tempfile::tempdir().unwrap();
        let opts = DeckOptions { base_dir: Some(dir.path().to_path_buf()), ..options() };
        let results: Vec<Result<Outcome, String>> = if ranks == 1 {
            vec![dmhs::deck::run_text("deck", SPH, &opts).map(|r| outcome(&r)).map_err(|f| f.rendered)]
        } else {
            let handles: Vec<_> = Threads::world(ranks)
                .into_iter()
                .map(|c| {
                    let opts = opts.clone();
                    std::thread::spawn(move || run_text_on("deck", SPH, &opts, Some(Arc::new(c) as Arc<dyn Comm>)).map(|r| outcome(&r)).map_err(|f| f.rendered))
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap_or_else(|_| Err("rank panicked".into()))).collect()
        };
        let dump = std::fs::read_to_string(dir.path().join("dump.sph")).unwrap();
        (results.into_iter().next().unwrap().unwrap(), dump)
    };
    let ((text1, atoms1), dump1) = run_in(1);
    let ((text4, atoms4), dump4) = run_in(4);
    assert_eq!(atoms4.len(), atoms1.len());
    for (a, b) in atoms4.iter().zip(&atoms1) {
        for d in 0..2 {
            assert!(close(a.1[d], b.1[d], 1e-9) && close(a.2[d], b.2[d], 1e-9), "atom {}: {:?} {:?} against serial {:?} {:?}", a.0, a.1, a.2, b.1, b.2);
        }
    }
    let (rows4, rows1) = (thermo_rows(&text4), thermo_rows(&text1));
    assert_eq!(rows4.len(), rows1.len(), "{text4}");
    assert!(rows4.iter().flatten().zip(rows1.iter().flatten()).all(|(x, y)| close(*x, *y, 1e-9)), "{text4}\n{text1}");
    let (n4, n1) = (numbers(&dump4), numbers(&dump1));
    assert_eq!(n4.len(), n1.len(), "the dumps have the same snapshots");
    assert!(n4.iter().zip(&n1).all(|(x, y)| close(*x, *y, 1e-6)), "the dump written on 4 ranks differs from the serial one");
}

/// The first setup of fix sph, with ghosts holding the velocity estimates they were made with,
/// gives the serial run's forces and pressure on 2 and 3 ranks: ghosts from another rank stand
/// for owned atoms of the serial run, periodic images for its ghosts.
#[test]
fn an_sph_setup_with_stale_ghost_estimates_on_ranks_is_the_serial_setup() {
    let deck = SPH.replace("run          0 post no\n", "").replace("dump         d all custom 100 dump.sph id x y vx vy c_rho c_e c_dx[1] c_dx[4]\ndump_modify  d sort id\n", "").replace("thermo_style custom step ke pe", "thermo_style custom step ke pe press pxy").replace("thermo       50", "thermo       1").replace("run          200", "run          3");
    let (text0, atoms0) = serial(&deck);
    let rows0 = thermo_rows(&text0);
    assert_eq!(rows0.len(), 4, "{text0}");
    for ranks in [2, 3] {
        for (rank, r) in on_ranks(&deck, ranks).into_iter().enumerate() {
            let (text, atoms) = r.unwrap_or_else(|e| panic!("{ranks} ranks, rank {rank}: {e}"));
            for (a, b) in atoms.iter().zip(&atoms0) {
                assert!((0..2).all(|d| close(a.1[d], b.1[d], 1e-12) && close(a.2[d], b.2[d], 1e-12)), "{ranks} ranks, atom {}: {:?} {:?} against serial {:?} {:?}", a.0, a.1, a.2, b.1, b.2);
            }
            if rank == 0 {
                let rows = thermo_rows(&text);
                assert_eq!(rows.len(), rows0.len(), "{text}");
                for (r, r0) in rows.iter().zip(&rows0) {
                    assert!(r.iter().zip(r0).all(|(x, y)| close(*x, *y, 1e-12)), "{ranks} ranks: thermo row {r:?} against serial {r0:?}");
                }
            }
        }
    }
}

/// The paper's cleaning scene (SPH water, water uptake by the soil, swelling, wet adhesion) on 2
/// ranks, its fast variant over 300 steps: the serial run's thermo table and atoms. (Over 1,500
/// steps the two part at 4e-6 relative, as the serial run does from a 1-ulp change of the wall
/// speed: 1e-6; the deck's own round-off growth, measured in docs/architecture.md.)
#[test]
fn the_cleaning_scene_on_two_ranks_is_the_serial_run() {
    let deck = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/diffusion/in.cleaning")).unwrap();
    let deck: String = deck.lines().filter(|l| !l.starts_with("dump")).map(|l| format!("{l}\n")).collect();
    let deck = format!("variable fast index 1\nvariable nsteps index 300\n{}", deck.replace("thermo       500", "thermo       50\nthermo_modify format float %.17g"));
    compare(&deck, 2);
}

/// The paper's casting scene, its fast case cut to four 100-step runs (the stopper, the gate
/// and the ladle removed between them), the melt started at 25.3 C so the surface freezes
/// within them (dmhs/phase: types, bonds to solid neighbours across ranks; dmhs/cooling,
/// dmhs/heatconduction, wall/reflect, dmhs/bond/break): the serial run's thermo and atoms.
#[test]
fn the_casting_scene_on_two_ranks_is_the_serial_run() {
    let deck = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenes/casting/in.casting")).unwrap();
    let deck = deck.replace("1.0*(100-25)", "1.0*(25.3-25)").replace("thermo       $(round(0.1/v_dt))", "thermo       10\nthermo_modify format float %.17g");
    let deck = format!("variable case index fast\nvariable img index 0\nvariable topen index 0.02\nvariable tgate index 0.04\nvariable tpour index 0.02\nvariable tend index 0.08\n{deck}");
    let (text, _) = serial(&deck);
    let last = thermo_rows(&text).last().cloned().unwrap_or_default();
    // f_phase[3]: bonds created
    assert!(last.get(7).is_some_and(|&b| b > 10.0), "bonds made in the serial run: {last:?}\n{text}");
    compare(&deck, 2);
}

/// The paper's lava scene at 540 C, cut to 200 heat steps of the crust (the surface freezes and bonds)
/// and 100 steps of the flow (dmhs/blend with its contact history, bond/break): the serial
/// run's thermo and atoms.
#[test]
fn the_lava_scene_on_two_ranks_is_the_serial_run() {
    let deck = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenes/lava/in.lava")).unwrap();
    let deck = deck.replace("sph/e $(1000.0*", "sph/e $(540.0*").replace("thermo       $(round(v_tcrust/6/v_dth))", "thermo       10\nthermo_modify format float %.17g").replace("thermo       $(round(0.05/v_dt))", "thermo       10");
    let deck = format!("variable quick index 1\nvariable img index 0\nvariable tcrust index 10.0\nvariable tflow index 0.02\n{deck}");
    let (text, _) = serial(&deck);
    let last = thermo_rows(&text).last().cloned().unwrap_or_default();
    // f_phase[3]: bonds created
    assert!(last.get(3).is_some_and(|&b| b > 10.0), "bonds made in the serial run: {last:?}\n{text}");
    compare(&deck, 2);
}

#[test]
fn what_is_not_distributed_yet_is_refused_on_every_rank() {
    let deck = MELT.replace("fix          1 all nve\n", "fix          1 all nve\ncompute      cn all coord/atom cutoff 1.5\ndump         r all custom 50 dump.cn id c_cn\n");
    for e in refusals(&deck, 2) {
        assert!(e.contains("dump r (it writes values of computes or fixes) cannot run on 2 ranks yet"), "{e}");
    }
}

/// Sub-domains thinner than the ghost cutoff take their ghosts from ranks two and more
/// sub-domains away (LAMMPS' multiple swaps): a melt cut into slabs of 1.68 and 1.12 (the
/// cutoff with its skin is 2.8), the slabs 2 and 3 hops deep, and a tilted box likewise.
#[test]
fn sub_domains_thinner_than_the_cutoff_are_the_serial_run() {
    // the serial deck, and the same on ranks with the grid `grid`
    let on = |deck: &str, grid: &str, n: usize| compare_decks(deck, &deck.replace("create_box", &format!("processors {grid}\ncreate_box")), n, 1e-9);
    let thin = |x: &str, z: &str| MELT.replace("block 0 6 0 6 0 6", &format!("block 0 {x} 0 6 0 {z}"));
    // 2 ranks along a 3.36 box: each slab thinner than the cutoff, its one neighbour on both sides
    on(&thin("6", "2"), "1 1 2", 2);
    // 3 and 4 slabs of 1.12 and 1.68: ghosts from two and three sub-domains away
    on(&thin("6", "2"), "1 1 3", 3);
    on(&melt_with("fix          1 all nve\nthermo_style custom step temp epair emol etotal press atoms\n").replace("block 0 6 0 6 0 6", "block 0 6 0 6 0 4"), "1 1 4", 4);
    // 2 by 2 in x and z of a thin 2 x 6 x 2 slab
    on(&thin("2", "2"), "2 1 2", 4);
    // a sheared prism in 5 slabs along x: the faces across the tilt come closer than the
    // cutoff as the tilt grows
    let sheared = tilted_melt("fix          1 all nvt temp 3.0 3.0 0.5\nfix          2 all deform 1 xy erate 0.05\nthermo_style custom step temp epair etotal press pxy xy atoms\nthermo_modify format float %.15g\n");
    on(&sheared, "5 1 1", 5);
}

/// `mpiexec -np 2|4 dmhs -in DECK` (the `--features mpi` build named by DMHS_MPI_BIN, started by
/// DMHS_MPIEXEC, default `mpiexec`) writes the serial run's thermo table and final data file.
#[test]
#[cfg_attr(not(live_mpi), ignore = "live MPI comparison: DMHS_MPI_BIN (a dmhs built with --features mpi) not set")]
fn mpiexec_ranks_give_the_serial_run() {
    let (bin, mpiexec) = mpi_launcher();
    let dir = tempfile::tempdir().unwrap();
    let deck = format!("{MELT}write_data final.data\n");
    std::fs::write(dir.path().join("in.melt"), &deck).unwrap();
    let run = |np: usize| {
        let mut cmd = if np == 1 { std::process::Command::new(&bin) } else { std::process::Command::new(&mpiexec) };
        if np > 1 {
            cmd.args(["-np", &np.to_string(), &bin]);
        }
        let out = cmd.args(["-threads", "1", "-in", "in.melt", "-log", "none"]).current_dir(dir.path()).output().unwrap_or_else(|e| panic!("{mpiexec}: {e}"));
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(out.status.success(), "{np} ranks: {text}\n{}", String::from_utf8_lossy(&out.stderr));
        let data = std::fs::read_to_string(dir.path().join("final.data")).unwrap();
        (text, data)
    };
    let (text1, data1) = run(1);
    for np in [2, 4] {
        let (text, data) = run(np);
        assert!(text.contains(&format!("on {np} procs for 100 steps with 864 atoms")), "{text}");
        let (rows, rows1) = (thermo_rows(&text), thermo_rows(&text1));
        assert_eq!(rows.len(), rows1.len(), "{text}");
        for (r, r1) in rows.iter().zip(&rows1) {
            assert!(r.iter().zip(r1).all(|(x, y)| close(*x, *y, 1e-9)), "{np} ranks: {r:?} against serial {r1:?}");
        }
        // past the header line
        let body = |d: &str| numbers(d.split_once('\n').map_or("", |(_, rest)| rest));
        let (n, n1) = (body(&data), body(&data1));
        assert_eq!(n.len(), n1.len());
        assert!(n.iter().zip(&n1).all(|(x, y)| close(*x, *y, 1e-9)), "{np} ranks: the data file differs from the serial one");
    }
    // bonded chains, a granular pile and a pour under real MPI too
    std::fs::write(dir.path().join("in.melt"), chains_deck(dir.path(), "bond_style   harmonic\nbond_coeff   1 100.0 0.97") + "write_data final.data\n").unwrap();
    let rows1 = thermo_rows(&run(1).0);
    let rows2 = thermo_rows(&run(2).0);
    assert!(rows1.len() >= 7 && rows1.len() == rows2.len() && rows1.iter().flatten().zip(rows2.iter().flatten()).all(|(x, y)| close(*x, *y, 1e-9)), "chains: {rows2:?} against serial {rows1:?}");
    std::fs::write(dir.path().join("in.melt"), granular_deck("pair_style   gran/hertz/history 2000.0 NULL 50.0 NULL 0.5 1", "hertz/history 2000.0 NULL 50.0 NULL 0.5 1") + "write_data final.data\n").unwrap();
    let rows1 = thermo_rows(&run(1).0);
    let rows2 = thermo_rows(&run(2).0);
    assert!(rows1.len() >= 7 && rows1.len() == rows2.len() && rows1.iter().flatten().zip(rows2.iter().flatten()).all(|(x, y)| close(*x, *y, 1e-9)), "granular: {rows2:?} against serial {rows1:?}");
    std::fs::write(dir.path().join("in.melt"), POUR).unwrap();
    let rows1 = thermo_rows(&run(1).0);
    let rows2 = thermo_rows(&run(2).0);
    assert!(rows1.len() >= 7 && rows1.len() == rows2.len() && rows1.iter().flatten().zip(rows2.iter().flatten()).all(|(x, y)| close(*x, *y, 1e-9)), "pour: {rows2:?} against serial {rows1:?}");
    // a tilted box sheared by fix deform, cut in box fractions
    let tilted = tilted_melt("fix          1 all nvt temp 3.0 3.0 0.5\nfix          2 all deform 1 xy erate 0.05\nthermo_style custom step temp epair etotal press pxy xy atoms\n");
    std::fs::write(dir.path().join("in.melt"), tilted + "write_data final.data\n").unwrap();
    let rows1 = thermo_rows(&run(1).0);
    for np in [2, 4] {
        let rows = thermo_rows(&run(np).0);
        assert!(rows1.len() >= 7 && rows1.len() == rows.len() && rows1.iter().flatten().zip(rows.iter().flatten()).all(|(x, y)| close(*x, *y, 1e-9)), "triclinic on {np} ranks: {rows:?} against serial {rows1:?}");
    }
    std::fs::write(dir.path().join("in.melt"), &deck).unwrap();
    // the benchmark times the ranks too
    let out = std::process::Command::new(&bin).args(["bench", "--threads-list", "1", "--ranks", "2", "in.melt"]).env("DMHS_MPIEXEC", &mpiexec).current_dir(dir.path()).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && text.contains("dmhs 2r") && text.contains("dmhs 1t"), "{text}\n{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn check_prints_the_grid_and_the_atoms_of_each_rank() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("in.melt"), MELT).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dmhs")).args(["check", "in.melt", "--ranks", "4"]).current_dir(dir.path()).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    // 864 fcc atoms in a cube on a 1 x 2 x 2 grid: 216 each
    assert!(text.contains("on 4 ranks: 1 by 2 by 2 processor grid; atoms per rank 216 to 216 (216, 216, 216, 216)"), "{text}");
    let check2 = |deck: String| {
        std::fs::write(dir.path().join("in.two"), deck).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_dmhs")).args(["check", "in.two", "--ranks", "2"]).current_dir(dir.path()).output().unwrap();
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let text = check2(MELT.replace("fix          1 all nve\n", "fix          1 all nve\ncompute      cn all coord/atom cutoff 1.5\ndump         r all custom 50 dump.cn id c_cn\n"));
    assert!(text.contains("on 2 ranks: dump r (it writes values of computes or fixes) cannot run on 2 ranks yet"), "{text}");
    // the fixes that run on ranks since issue 19's second part: no refusal line
    let text = check2(MELT.replace(
        "fix          1 all nve\n",
        "fix          1 all move linear 0.1 NULL NULL units box\nfix          2 all print 10 \"$(step)\"\nfix          3 all ave/time 1 1 10 c_thermo_temp\n\
         fix          4 all dt/reset 10 NULL 0.006 0.02\nfix          5 all spring tether 10.0 5.0 5.0 5.0 0.0\n",
    ));
    assert!(text.contains("on 2 ranks: 1 by 1 by 2 processor grid") && !text.contains("cannot run"), "{text}");
}

#[test]
fn a_langevin_fluid_on_two_ranks_keeps_its_temperature() {
    // each rank draws its own stream (seed + rank, as LAMMPS): not the serial numbers, but
    // the same statistics
    let deck = MELT.replace("fix          1 all nve\n", "fix          1 all nve\nfix          2 all langevin 1.0 1.0 0.5 48279 zero yes tally yes\n")
        .replace("thermo_style custom step temp epair emol etotal press atoms", "thermo_style custom step temp epair f_2")
        .replace("run          150\nrun          100\n", "run          2000\n");
    for r in on_ranks(&deck, 2) {
        let (text, atoms) = r.unwrap();
        assert_eq!(atoms.len(), 864);
        if !text.is_empty() {
            let rows = thermo_rows(&text);
            let late: Vec<f64> = rows.iter().filter(|r| r[0] >= 1000.0).map(|r| r[1]).collect();
            let mean = late.iter().sum::<f64>() / late.len() as f64;
            assert!((mean - 1.0).abs() < 0.1, "mean temperature {mean} over steps 1000-2000:\n{text}");
            assert!(rows.last().unwrap()[3] != 0.0, "the tallied energy is reduced over ranks: {text}");
        }
    }
}

/// The thermo values that sum or pick over the group's atoms: compute com, reduce (sum, ave,
/// min, max of attributes and of property/atom), and the group functions; the melt's atoms
/// cross the periodic faces and change rank, so com unwraps with image flags on every rank.
/// Walls, an indenter and the thermostats on ranks: each rank acts on its own atoms and the
/// fixes' energies and forces (f_ID, f_ID[n]) are sums over the ranks.
#[test]
fn walls_indenters_and_thermostats_on_ranks_are_the_serial_run() {
    let slab = MELT
        .replace("region       box block 0 6 0 6 0 6\n", "boundary     p p f\nregion       box block 0 6 0 6 -0.25 6.25\n")
        .replace("check no\n", "check yes\n");
    let fixes = |text: &str| slab.replace("fix          1 all nve\nthermo_style custom step temp epair emol etotal press atoms\n", text);
    let walls = fixes(
        "fix          1 all nve\n\
         fix          2 all wall/lj93 zlo EDGE 1.0 0.2 1.0 zhi EDGE 1.0 0.2 1.0\n\
         fix          3 all indent 10.0 sphere 5.0 5.0 5.0 1.0 units box\n\
         fix          4 all temp/berendsen 2.0 2.0 0.5\n\
         thermo_style custom step temp epair etotal press f_2 f_2[1] f_2[2] f_3 f_3[1] f_3[2] f_3[3] f_4\n\
         thermo_modify format float %.15g\n",
    );
    compare(&walls, 2);
    compare(&walls, 4);
    let region = fixes(
        "fix          1 all nvt temp 2.0 2.0 0.5\n\
         region       slab block INF INF INF INF -0.2 6.2 units lattice\n\
         fix          2 all wall/region slab harmonic 50.0 1.0 1.0\n\
         fix          3 all wall/harmonic zlo -0.22 50.0 1.0 1.0 units lattice\n\
         fix          4 all temp/rescale 10 2.0 2.0 0.05 1.0\n\
         thermo_style custom step temp epair etotal press f_1 f_2 f_2[1] f_2[2] f_2[3] f_3 f_3[1] f_4\n\
         thermo_modify format float %.15g\n",
    );
    compare(&region, 2);
}

/// Heat exchange on ranks (fix heat with a constant and an atom-style flux, fix ehex, fix
/// thermal/conductivity and fix viscosity, whose swaps pair atoms of different ranks as LAMMPS' global ranking
/// does) and fix ave/correlate of their values: the serial run's thermo and atoms.
#[test]
fn heat_exchange_on_ranks_is_the_serial_run() {
    let deck = melt_with(
        "fix          1 all nve\n\
         region       hot block 0 1 INF INF INF INF units lattice\n\
         region       cold block 3 4 INF INF INF INF units lattice\n\
         variable     flux atom -0.5-0.1*y\n\
         fix          hot all heat 1 2.0 region hot\n\
         fix          cold all heat 3 v_flux region cold\n\
         fix          eh all ehex 2 1.0 region hot\n\
         fix          mp all thermal/conductivity 10 z 6 swap 2\n\
         fix          vs all viscosity 10 x z 6 swap 3\n\
         fix          cor all ave/correlate 10 4 50 c_thermo_temp f_mp type auto/upper\n\
         thermo_style custom step temp epair etotal press f_hot f_cold f_eh f_mp f_vs f_cor[3][3] f_cor[2][5]\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deck, 2);
    compare(&deck, 4);
}

#[test]
fn centres_of_mass_reductions_and_group_functions_on_ranks_are_the_serial_ones() {
    let deck = melt_with(
        "fix          1 all nve\n\
         region       half block 0 3 INF INF INF INF units lattice\n\
         group        half region half\n\
         compute      cm half com\n\
         compute      xu all property/atom xu vy\n\
         compute      lo all reduce min c_xu[1] y\n\
         compute      hi half reduce max c_xu[1] vz\n\
         compute      av all reduce ave vx c_xu[2]\n\
         compute      sq half reduce sumsq vx\n\
         variable     bx equal bound(all,xmax)-bound(half,ymin)\n\
         variable     g equal xcm(half,x)+vcm(half,y)+count(half)+mass(half)+fcm(all,z)+gyration(half)+ke(half)\n\
         thermo_style custom step temp c_cm[1] c_cm[2] c_cm[3] c_lo[1] c_lo[2] c_hi[1] c_hi[2] c_av[1] c_av[2] c_sq v_bx v_g\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deck, 2);
    compare(&deck, 4);
}

/// Bonds breaking across rank boundaries (fix bond/break, its angles and dihedrals taken along):
/// every rank removes the same bonds at the same steps, so the special lists, the bonded
/// lists and the thermo stay the serial run's.
#[test]
fn bonds_breaking_across_ranks_break_as_in_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    let deck = chains_deck(dir.path(), "bond_style   harmonic\nbond_coeff   1 100.0 0.97")
        .replace("velocity     all create 1.0", "velocity     all create 2.5")
        .replace("fix          1 all nve\n", "fix          1 all nve\nfix          brk all bond/break 5 1 1.1\n")
        .replace("thermo_style custom step temp epair ebond eangle edihed etotal press atoms", "thermo_style custom step temp epair ebond eangle edihed etotal press f_brk[1] f_brk[2] bonds angles dihedrals");
    let (text, _) = serial(&deck);
    let broken = thermo_rows(&text).last().map(|r| r[9]).unwrap_or(0.0);
    assert!((20.0..300.0).contains(&broken), "bonds broken in the serial run: {broken}\n{text}");
    compare(&deck, 2);
    compare(&deck, 4);
}

/// An LJ liquid of two types whose unlike neighbours bond (fix bond/create with limits, angles
/// and, in `extra`, more keywords) as it runs.
fn bonding_liquid(extra: &str) -> String {
    MELT.replace("atom_style   atomic", "atom_style   angle")
        .replace(
            "create_box   1 box\ncreate_atoms 1 box\nmass         1 1.0",
            "create_box   3 box bond/types 1 angle/types 1 extra/bond/per/atom 6 extra/angle/per/atom 20 extra/special/per/atom 30\ncreate_atoms 1 box\nset          group all type/fraction 2 0.5 12345\nmass         * 1.0",
        )
        .replace("pair_coeff   1 1 1.0 1.0 2.5", "pair_coeff   * * 1.0 1.0 2.5\nbond_style   harmonic\nbond_coeff   1 50.0 1.1\nangle_style  harmonic\nangle_coeff  1 5.0 109.0\nspecial_bonds lj 0.0 1.0 1.0")
        .replace("check no", "check yes")
        .replace("fix          1 all nve\n", &format!("fix          1 all nve\nfix          bc all bond/create 10 1 2 1.05 1 jparam 2 2 atype 1{extra}\n"))
        .replace("thermo_style custom step temp epair emol etotal press atoms", "thermo_style custom step temp epair ebond eangle etotal press f_bc[1] f_bc[2] bonds angles")
}

/// Bonds forming across rank boundaries and periodic faces (fix bond/create): each pair is
/// checked by the owners of its two atoms, every rank makes the same choices, so the same
/// bonds, angles and type changes appear at the same steps as in the serial run (which prints
/// LAMMPS' table: 770 bonds and 705 angles at step 250 without `prob`).
#[test]
fn bonds_forming_across_ranks_form_as_in_the_serial_run() {
    let deck = bonding_liquid(" iparam 2 1");
    let (text, _) = serial(&deck);
    let last = thermo_rows(&text).last().cloned().unwrap_or_default();
    assert_eq!(last.get(9).copied(), Some(770.0), "bonds made in the serial run: {last:?}\n{text}");
    compare(&deck, 2);
    // types that change at their limit, random acceptance
    let deck = bonding_liquid(" iparam 2 3 prob 0.7 4321");
    let (text, _) = serial(&deck);
    let last = thermo_rows(&text).last().cloned().unwrap_or_default();
    assert!(last.get(9).is_some_and(|&b| (300.0..770.0).contains(&b)), "bonds made in the serial run: {last:?}\n{text}");
    compare(&deck, 4);
}

/// A dump of forces written on ranks: the gathered atoms carry the forces of the last
/// evaluation (migration does not), so fx fy fz are the serial run's, not zeros.
#[test]
fn a_dump_of_forces_on_ranks_is_the_serial_one() {
    let deck = MELT.replace("fix          1 all nve\n", "fix          1 all nve\ndump         d all custom 50 dump.f id fx fy fz\ndump_modify  d sort id format float %.15g\n");
    let run_in = |ranks: usize| {
        let dir = tempfile::tempdir().unwrap();
        let opts = DeckOptions { base_dir: Some(dir.path().to_path_buf()), ..options() };
        let results: Vec<Result<Outcome, String>> = Threads::world(ranks)
            .into_iter()
            .map(|c| {
                let (opts, deck) = (opts.clone(), deck.clone());
                std::thread::spawn(move || run_text_on("deck", &deck, &opts, Some(Arc::new(c) as Arc<dyn Comm>)).map(|r| outcome(&r)).map_err(|f| f.rendered))
            })
            .collect::<Vec<_>>()
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|_| Err("rank panicked".into())))
            .collect();
        assert!(results.iter().all(|r| r.is_ok()), "{ranks} ranks: {:?}", results.iter().find_map(|r| r.as_ref().err()));
        numbers(&std::fs::read_to_string(dir.path().join("dump.f")).unwrap())
    };
    let (n1, n2) = (run_in(1), run_in(2));
    assert_eq!(n1.len(), n2.len(), "the dumps have the same snapshots");
    assert!(n1.iter().filter(|x| x.abs() > 1e-3).count() > 1000, "the serial dump has forces");
    assert!(n2.iter().zip(&n1).all(|(x, y)| close(*x, *y, 1e-9)), "the dump of forces written on 2 ranks differs from the serial one");
}

/// A small bonded BPM solid (a ball of bpm/sphere atoms, bonds made by create_bonds many) hits
/// a bonded plate and both fracture: bpm/rotational with fix nve/bpm/sphere and gran/hooke/history
/// contacts, or bpm/spring with pair bpm/spring and fix nve. Broken bonds go to the style's
/// store/local and a dump local (file `brk`).
fn bpm_impact(rotational: bool, brk: &std::path::Path) -> String {
    let (style, pair, fix, bonds, dt) = if rotational {
        (
            "bpm/sphere",
            "pair_style gran/hooke/history 1.0 NULL 0.5 NULL 0.1 1\npair_coeff 1 1",
            "nve/bpm/sphere",
            "bond_style bpm/rotational store/local brk 10 time id1 id2 x y z x/ref y/ref z/ref\n\
             bond_coeff 1 1.0 0.2 0.02 0.02 0.05 0.01 0.01 0.01 0.1 0.2 0.002 0.002\n\
             bond_coeff 2 1.0 0.2 0.02 0.02 0.20 0.04 0.04 0.04 0.1 0.2 0.002 0.002",
            0.05,
        )
    } else {
        (
            "bond",
            "mass 1 1.0\npair_style bpm/spring\npair_coeff 1 1 1.0 1.0 1.0",
            "nve",
            "bond_style bpm/spring store/local brk 10 time id1 id2 x y z x/ref y/ref z/ref\nbond_coeff 1 1.0 0.04 1.0\nbond_coeff 2 1.0 0.20 1.0",
            0.05,
        )
    };
    format!(
        "units lj
boundary f f f
atom_style {style}
special_bonds lj 0.0 1.0 1.0 coul 0.0 1.0 1.0
newton on off
comm_modify vel yes cutoff 2.6
lattice fcc 1.0
region box block -6 6 -5 5 -5 5
create_box 1 box bond/types 2 extra/bond/per/atom 20 extra/special/per/atom 50
region disk cylinder x 0.0 0.0 4.0 -0.5 0.5
create_atoms 1 region disk
group plate region disk
region ball sphere 3.0 0.0 0.0 2.0
create_atoms 1 region ball
group projectile region ball
displace_atoms all random 0.1 0.1 0.1 134598738
neighbor 1.0 bin
{pair}
fix 1 all {fix}
create_bonds many plate plate 1 0.0 1.5
create_bonds many projectile projectile 2 0.0 1.5
neighbor 0.3 bin
special_bonds lj 0.0 1.0 1.0 coul 1.0 1.0 1.0
{bonds}
velocity projectile set -0.3 0.0 0.0
compute nbond all nbond/atom
compute tbond all reduce sum c_nbond
timestep {dt}
thermo_style custom step ke pe ebond pxx pyy pzz c_tbond
thermo_modify format float %.15g
thermo 20
dump brk all local 10 {} f_brk[1] f_brk[2] f_brk[3] f_brk[4] f_brk[5] f_brk[6] f_brk[7] f_brk[8] f_brk[9]
dump_modify brk header no format float %.15g
run 250
run 50
",
        brk.display()
    )
}

/// The rows of a dump local of broken bonds, sorted by (time, id1, id2) (the ranks write the
/// same rows, in rank order).
fn broken_rows(path: &std::path::Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut rows: Vec<Vec<f64>> = text.lines().map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect()).collect();
    rows.sort_by(|a, b| a.partial_cmp(b).unwrap());
    rows
}

/// BPM solids fracturing across rank boundaries (issue 19): each rank computes the bonds of
/// its atoms (a bond across ranks on both, with the same bits), the bonds' reference states
/// are the same in every rank's topology, and a broken bond leaves every rank's topology,
/// special lists and neighbour lists: the serial run's thermo (bond count included), atoms and
/// broken bonds, the same bonds at the same steps, on 2 and 3 ranks.
///
/// The atoms of bpm/rotational are compared within 1e-8: its shear angle is the acos of a
/// cosine near 1 for an unsheared bond, so a last-bit difference of a force sum (the ranks add
/// a bond's and a contact's forces in another order) becomes 1e-8 in that angle and about 1e-9
/// in positions and velocities within 20 steps, where it stays (measured: 2e-9 at step 300 on
/// 2 ranks, 6e-9 on 3; serial dmhs and serial LAMMPS part by 2e-11 the same way; bpm/spring's
/// ranks stay within 6e-14). The thermo rows and broken bonds are within 1e-9.
#[test]
fn bpm_solids_fracturing_on_ranks_are_the_serial_run() {
    for (rotational, atom_tol) in [(true, 1e-8), (false, 1e-9)] {
        let dir = tempfile::tempdir().unwrap();
        let (one, many) = (dir.path().join("serial.local"), dir.path().join("ranks.local"));
        let serial_deck = bpm_impact(rotational, &one);
        let (text, _) = serial(&serial_deck);
        let rows = thermo_rows(&text);
        let (first, last) = (rows[0][7], rows.last().unwrap()[7]);
        assert!(last < 0.75 * first, "the solids fracture: bonds per atom {first} -> {last}\n{text}");
        let broken1 = broken_rows(&one);
        assert!(broken1.len() > 300, "broken bonds: {}", broken1.len());
        for ranks in [2, 3] {
            compare_decks(&serial_deck, &bpm_impact(rotational, &many), ranks, atom_tol);
            let broken = broken_rows(&many);
            assert_eq!(broken.len(), broken1.len(), "{ranks} ranks: broken bonds");
            for (r, r1) in broken.iter().zip(&broken1) {
                assert_eq!(r[..3], r1[..3], "{ranks} ranks: the same bonds break at the same steps");
                assert!(r.iter().zip(r1).all(|(x, y)| close(*x, *y, atom_tol)), "{ranks} ranks: broken bond {r:?} against serial {r1:?}");
            }
        }
    }
}

/// What the BPM styles cannot do on ranks yet is refused with the reason.
#[test]
fn bpm_volume_factor_is_refused_on_ranks() {
    let dir = tempfile::tempdir().unwrap();
    let deck = bpm_impact(false, &dir.path().join("b.local")).replace("bond_style bpm/spring store/local", "bond_style bpm/spring volume/factor yes store/local").replace("bond_coeff 1 1.0 0.04 1.0\nbond_coeff 2 1.0 0.20 1.0", "bond_coeff 1 1.0 0.04 1.0 0.5\nbond_coeff 2 1.0 0.20 1.0 0.5");
    for e in refusals(&deck, 2) {
        assert!(e.contains("bond_style bpm/spring volume/factor yes cannot run on 2 ranks yet"), "{e}");
    }
}

/// `mpiexec -np 2|3` of the fracturing BPM solids (DMHS_MPI_BIN, DMHS_MPIEXEC): the serial run's
/// thermo table and broken bonds.
#[test]
#[cfg_attr(not(live_mpi), ignore = "live MPI comparison: DMHS_MPI_BIN (a dmhs built with --features mpi) not set")]
fn mpiexec_bpm_solids_fracture_as_the_serial_run() {
    let (bin, mpiexec) = mpi_launcher();
    let dir = tempfile::tempdir().unwrap();
    for rotational in [true, false] {
        let brk = dir.path().join("brk.local");
        std::fs::write(dir.path().join("in.bpm"), bpm_impact(rotational, &brk)).unwrap();
        let run = |np: usize| {
            let mut cmd = std::process::Command::new(if np == 1 { &bin } else { &mpiexec });
            if np > 1 {
                cmd.args(["-np", &np.to_string(), &bin]);
            }
            let out = cmd.args(["-threads", "1", "-in", "in.bpm", "-log", "none"]).current_dir(dir.path()).output().unwrap_or_else(|e| panic!("{mpiexec}: {e}"));
            let text = String::from_utf8_lossy(&out.stdout).into_owned();
            assert!(out.status.success(), "{np} ranks: {text}\n{}", String::from_utf8_lossy(&out.stderr));
            (thermo_rows(&text), broken_rows(&brk))
        };
        let (rows1, broken1) = run(1);
        assert!(rows1.len() >= 15 && broken1.len() > 300, "serial: {} rows, {} broken bonds", rows1.len(), broken1.len());
        for np in [2, 3] {
            let (rows, broken) = run(np);
            assert_eq!(rows.len(), rows1.len());
            assert!(rows.iter().flatten().zip(rows1.iter().flatten()).all(|(x, y)| close(*x, *y, 1e-9)), "{np} ranks: {rows:?} against serial {rows1:?}");
            assert_eq!(broken.len(), broken1.len(), "{np} ranks: broken bonds");
            // (bpm/rotational's positions: see bpm_solids_fracturing_on_ranks_are_the_serial_run)
            assert!(broken.iter().zip(&broken1).all(|(r, r1)| r[..3] == r1[..3] && r.iter().zip(r1).all(|(x, y)| close(*x, *y, 1e-8))), "{np} ranks: the broken bonds differ from the serial run's");
        }
    }
}

/// Atoms lost through a fixed face with `thermo_modify lost ignore` leave every rank's topology
/// (their bonds with them), so the ranks keep one topology: fragments of the fracturing
/// bpm/spring solids fly out of the box (a longer time step), as in the serial run.
#[test]
fn bpm_fragments_lost_on_ranks_leave_every_ranks_topology() {
    let dir = tempfile::tempdir().unwrap();
    let deck = |f: &str| {
        bpm_impact(false, &dir.path().join(f))
            .replace("timestep 0.05", "timestep 0.1")
            .replace("thermo_modify format float %.15g", "thermo_modify format float %.15g lost ignore")
            .replace("thermo_style custom step ke pe ebond pxx pyy pzz c_tbond", "thermo_style custom step ke pe ebond pxx pyy pzz c_tbond atoms bonds")
    };
    let (text, _) = serial(&deck("a.local"));
    let last = thermo_rows(&text).last().cloned().unwrap_or_default();
    assert!(last.get(8).is_some_and(|&n| n < 434.0), "atoms are lost in the serial run: {last:?}\n{text}");
    compare_decks(&deck("a.local"), &deck("b.local"), 2, 1e-9);
}

/// bpm/spring/plastic on ranks: a bond's plastic strain, changed where the bond is computed,
/// reaches every rank's topology (lammps-refs/decks/in.bond_bpm_spring_plastic: a ball yields a
/// plate's bonds).
#[test]
fn bpm_plastic_springs_on_ranks_are_the_serial_run() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks/in.bond_bpm_spring_plastic");
    let deck = std::fs::read_to_string(path).unwrap().replace("thermo       10\n", "thermo       30\nthermo_modify format float %.15g\n");
    compare(&deck, 2);
    compare(&deck, 3);
}

/// Compute rdf on ranks (a pair across ranks counted by each owner for its own atom, the
/// histograms and type counts summed over the ranks), averaged by fix ave/time into a file:
/// the serial run's file. Two types, all pairs and one cross pair, a cutoff of its own.
#[test]
fn radial_distribution_functions_on_ranks_are_the_serial_ones() {
    let dir = tempfile::tempdir().unwrap();
    let deck = |tag: &str| {
        let path = dir.path().join(format!("{tag}.rdf")).display().to_string();
        MELT.replace("create_box   1 box\ncreate_atoms 1 box\nmass         1 1.0", "create_box   2 box\ncreate_atoms 1 box\nset          group all type/fraction 2 0.3 4321\nmass         * 1.0")
            .replace("pair_coeff   1 1 1.0 1.0 2.5", "pair_coeff   * * 1.0 1.0 2.5")
            .replace("neighbor     0.3 bin", "neighbor     0.5 bin")
            .replace("fix          1 all nve\n", &format!("fix          1 all nve\ncompute      r all rdf 40 * * 1 2 cutoff 2.4\nfix          av all ave/time 25 2 50 c_r[*] file {path} mode vector\n"))
    };
    let file = |tag: &str| dir.path().join(format!("{tag}.rdf"));
    for ranks in [2, 4] {
        let (tag0, tag) = (format!("s{ranks}"), format!("r{ranks}"));
        compare_decks(&deck(&tag0), &deck(&tag), ranks, 1e-9);
        let (x, y) = (file_numbers(&file(&tag0)).expect("serial file"), file_numbers(&file(&tag)).expect("file written on ranks"));
        // 5 blocks of 40 rows of 5 columns, and their headers
        assert!(x.len() > 5 * 40 * 5 && x.len() == y.len(), "{} values against serial {}", y.len(), x.len());
        assert!(x.iter().zip(&y).all(|(x, y)| close(*x, *y, 1e-9)), "the rdf file on {ranks} ranks differs from the serial one");
        assert!(x.iter().any(|&v| v > 2.0), "a first peak of g(r) above 2");
    }
}

/// Per-atom energies and stresses on ranks (compute pe/atom, stress/atom, their sums by
/// compute reduce and a dump of them): bonds, angles and dihedrals computed once with ghosts
/// send the ghosts' shares back to the owners, pairs across ranks give each owner its half;
/// the sums equal the serial run's and the thermo pressure and energies, the dump is the
/// serial one (rank 0 writes it with the tallies gathered with the atoms).
#[test]
fn per_atom_energies_and_stresses_on_ranks_are_the_serial_ones() {
    let dir = tempfile::tempdir().unwrap();
    let dump = |tag: &str| dir.path().join(format!("{tag}.dump"));
    let deck = |tag: &str| chains_deck(dir.path(), "bond_style   harmonic\nbond_coeff   1 100.0 0.97").replace(
        "run          150",
        &format!("dump         d all custom 50 {} id c_s[1] c_s[4] c_sb[2] c_pe c_peb\ndump_modify  d sort id format float %.15g\nrun          150", dump(tag).display()),
    ).replace(
        "thermo_style custom step temp epair ebond eangle edihed etotal press atoms",
        "compute      s all stress/atom NULL\n\
         compute      sb all stress/atom NULL bond angle dihedral\n\
         compute      pe all pe/atom\n\
         compute      peb all pe/atom bond angle dihedral\n\
         compute      sum all reduce sum c_s[1] c_s[2] c_s[3] c_sb[4] c_pe c_peb\n\
         variable     p equal -(c_sum[1]+c_sum[2]+c_sum[3])/(3*vol)\n\
         thermo_style custom step temp epair ebond eangle edihed pe press v_p c_sum[4] c_sum[5] c_sum[6]\n\
         thermo_modify format float %.15g",
    );
    let (text, _) = serial(&deck("check"));
    for r in thermo_rows(&text) {
        // the stresses' pressure is the thermo pressure; the per-atom energies sum to pe and to
        // the bonded energies
        assert!(close(r[7], r[8], 1e-12) && close(r[6], r[10], 1e-12) && close(r[3] + r[4] + r[5], r[11], 1e-12), "{r:?}");
    }
    for ranks in [2, 4] {
        let (tag0, tag) = (format!("s{ranks}"), format!("r{ranks}"));
        compare_decks(&deck(&tag0), &deck(&tag), ranks, 1e-9);
        let (x, y) = (file_numbers(&dump(&tag0)).expect("serial dump"), file_numbers(&dump(&tag)).expect("dump written on ranks"));
        assert!(x.len() > 6 * 360 * 5 && x.len() == y.len(), "{} values against serial {}", y.len(), x.len());
        assert!(x.iter().zip(&y).all(|(x, y)| close(*x, *y, 1e-9)), "the dump on {ranks} ranks differs from the serial one");
    }
}

/// The temperatures with a bias on ranks (temp/com, temp/partial, temp/region, temp/ramp,
/// temp/profile: their sums, centre-of-mass velocity and bin averages over the ranks), one of
/// them thermostatting the run (fix nvt with fix_modify temp) and one in the stress/atom's
/// kinetic term: the serial run's thermo.
#[test]
fn biased_temperatures_on_ranks_are_the_serial_ones() {
    let deck = melt_with(
        "velocity     all set 0.5 NULL NULL sum yes\n\
         region       mid block INF INF 2.0 8.0 INF INF units box\n\
         compute      tc all temp/com\n\
         compute      tp all temp/partial 1 1 0\n\
         compute      tr all temp/region mid\n\
         compute      tm all temp/ramp vx 0 0.4 y 0 10.0 units box\n\
         compute      tf all temp/profile 1 0 0 y 4\n\
         compute      s all stress/atom tc ke\n\
         compute      ks all reduce sum c_s[1]\n\
         fix          1 all nvt temp 1.2 1.2 0.5\n\
         fix_modify   1 temp tc\n\
         thermo_style custom step temp c_tc c_tp c_tr c_tm c_tf c_ks etotal\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deck, 2);
    compare(&deck, 3);
}

/// Fix energies and virials in the thermo on ranks (`fix_modify energy yes virial yes` of wall
/// fixes and addforce): each fix's scalar is already global, its virial is summed over the
/// ranks, so pe, etotal and press are the serial run's.
#[test]
fn fix_energies_and_virials_on_ranks_are_the_serial_ones() {
    let deck = MELT.replace("lattice      fcc 0.8442\n", "boundary     p p f\nlattice      fcc 0.8442\n")
        .replace("region       box block 0 6 0 6 0 6", "region       box block 0 6 0 6 -0.45 6.45")
        .replace("fix          1 all nve\n", "fix          1 all nve\n\
             fix          w all wall/lj93 zlo EDGE 1.0 1.0 2.5 zhi EDGE 1.0 1.0 2.5\n\
             fix_modify   w energy yes virial yes\n\
             fix          push all addforce 0.02 0.0 -0.01\n\
             fix_modify   push energy yes virial yes\n")
        .replace("thermo_style custom step temp epair emol etotal press atoms", "thermo_style custom step temp epair pe etotal press pxy pzz f_w f_push\nthermo_modify format float %.15g")
        .replace("check no", "check yes");
    let (text, _) = serial(&deck);
    let rows = thermo_rows(&text);
    // the fixes count in pe: pe = epair + f_w + f_push
    assert!(rows.iter().all(|r| close(r[3], r[2] + r[8] + r[9], 1e-12)), "{text}");
    compare(&deck, 2);
    compare(&deck, 4);
}

/// Fix move of every style on ranks: four groups moved (a cylinder rotated about z, a slab
/// moved linearly across the periodic faces, one wiggled, one by variables) among nve atoms;
/// the original positions travel with the atoms at migration and are gathered between runs.
#[test]
fn fix_move_on_ranks_is_the_serial_run() {
    let deck = melt_with(
        "region       cyl cylinder z 5.04 5.04 2.5 0.0 2.6 units box\n\
         region       s2 block INF INF INF INF 3.3 4.6 units box\n\
         region       s3 block INF INF INF INF 5.6 6.7 units box\n\
         region       s4 block INF INF INF INF 7.5 8.6 units box\n\
         group        rot region cyl\n\
         group        lin region s2\n\
         group        wig region s3\n\
         group        var region s4\n\
         group        rest subtract all rot lin wig var\n\
         variable     dx equal 0.4*sin(2.0*time)\n\
         variable     vx equal 0.8*cos(2.0*time)\n\
         variable     vz equal 0.05\n\
         fix          1 rest nve\n\
         fix          2 rot move rotate 5.04 5.04 0.0 0 0 1 20.0 units box\n\
         fix          3 lin move linear 1.5 -0.7 NULL units box\n\
         fix          4 wig move wiggle 0.3 NULL 0.0 0.5 units box\n\
         fix          5 var move variable v_dx NULL NULL v_vx NULL v_vz units box\n\
         compute      cw wig com\n\
         compute      cl lin com\n\
         thermo_style custom step temp epair etotal press c_cw[1] c_cl[1] c_cl[2] c_cl[3]\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deck, 2);
    compare(&deck, 3);
}

/// The numbers of a file written by a deck (None: it was not written).
fn file_numbers(path: &std::path::Path) -> Option<Vec<f64>> {
    std::fs::read_to_string(path).ok().map(|t| numbers(&t))
}

/// Fix print (screen and an appended file) and fix ave/time (of computes, a variable and a
/// fix) on ranks: rank 0 alone writes, the values are global; fix dt/reset takes the least
/// timestep over the ranks.
#[test]
fn print_ave_time_and_dt_reset_on_ranks_are_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    let deck = |tag: &str| {
        let p = |name: &str| dir.path().join(format!("{tag}.{name}")).display().to_string();
        melt_with(&format!(
            "fix          1 all nve\n\
             fix          dt all dt/reset 10 NULL 0.006 0.02 units box\n\
             variable     e equal etotal\n\
             compute      cm all com\n\
             fix          av all ave/time 5 4 50 c_thermo_temp c_thermo_pe v_e f_dt c_cm[1] file {}\n\
             fix          pr all print 25 \"$(step) $(dt:%.15g) $(temp:%.15g) $(pe:%.15g) $(c_cm[2]:%.15g)\" append {} screen yes\n\
             thermo_style custom step dt time temp epair etotal f_av[1] f_av[2] f_av[3] f_av[4] f_dt\n\
             thermo_modify format float %.15g\n",
            p("ave"),
            p("print")
        ))
    };
    let files = |tag: &str| ["ave", "print"].map(|f| dir.path().join(format!("{tag}.{f}")));
    for ranks in [2, 3] {
        // each serial run its own files (the print file is appended to)
        let (tag0, tag) = (format!("s{ranks}"), format!("r{ranks}"));
        compare_decks(&deck(&tag0), &deck(&tag), ranks, 1e-9);
        for (a, b) in files(&tag0).iter().zip(files(&tag)) {
            let (x, y) = (file_numbers(a).expect("serial file"), file_numbers(&b).expect("file written on ranks"));
            assert!(x.len() >= 25 && x.len() == y.len(), "{}: {} values against serial {}", b.display(), y.len(), x.len());
            assert!(x.iter().zip(&y).all(|(x, y)| close(*x, *y, 1e-9)), "{} differs from the serial file", b.display());
        }
    }
    // dt/reset changed the timestep
    let (text, _) = serial(&deck("check"));
    assert!(thermo_rows(&text).iter().any(|r| r[1] != 0.005), "{text}");
}

/// Fix spring tether and couple on ranks: the groups' centres of mass are sums over the ranks;
/// fix spring/self: the anchors travel with the atoms, f_ID is a sum over the ranks.
#[test]
fn springs_on_ranks_are_the_serial_run() {
    let deck = melt_with(
        "region       half block 0 3 INF INF INF INF units lattice\n\
         group        half region half\n\
         group        other subtract all half\n\
         fix          1 all nve\n\
         fix          2 half spring tether 5.0 2.0 NULL 4.0 0.0\n\
         fix          3 other spring couple half 20.0 -4.0 NULL NULL 0.5\n\
         fix          4 half spring/self 2.0 xy\n\
         fix          5 other spring/self 0.5\n\
         thermo_style custom step temp epair etotal press f_2 f_2[1] f_2[3] f_2[4] f_3 f_3[1] f_3[4] f_4 f_5\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deck, 2);
    compare(&deck, 3);
}

/// fix momentum (linear and angular with rescale) and the group functions angmom(), omega(),
/// inertia() and torque() on ranks: every sum over the ranks, as LAMMPS' Group.
#[test]
fn momentum_and_group_rotation_on_ranks_are_the_serial_run() {
    let deck = melt_with(
        "region       half block 0 3 INF INF INF INF units lattice\n\
         group        half region half\n\
         fix          1 all nve\n\
         fix          2 half addforce 0.2 -0.1 0.05\n\
         fix          3 all momentum 5 linear 1 1 0\n\
         fix          4 half momentum 7 angular rescale\n\
         variable     lz equal angmom(half,z)\n\
         variable     wx equal omega(half,x)\n\
         variable     ixy equal inertia(half,xy)\n\
         variable     tz equal torque(half,z)\n\
         variable     vz equal vcm(all,z)\n\
         thermo_style custom step temp epair etotal press v_lz v_wx v_ixy v_tz v_vz\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deck, 2);
    compare(&deck, 3);
}

/// A granular pile with heat on ranks: a region floor (fix wall/gran/region with a heat model
/// and a wall temperature) and a sphere pressed into the pile (a moving region wall with
/// tangential history); the per-atom wall histories travel with the atoms, fix heat/flow
/// integrates the temperatures of fix property/atom.
#[test]
fn region_walls_and_heat_flow_on_ranks_are_the_serial_run() {
    let deck = "
units        lj
atom_style   sphere
boundary     p p f
comm_modify  vel yes
lattice      sc $(1.0/0.99^3) origin 0.5 0.5 0.5
region       box block 0 6 0 6 0 12
create_box   1 box
region       fill block 0 6 0 6 0 8
create_atoms 1 region fill
set          type 1 diameter 1.0 density 1.0
velocity     all create 0.02 87287 loop geom
fix          props all property/atom temperature heatflow
region       l1 block INF INF INF INF 1.98 3.96
region       l2 block INF INF INF INF 3.96 INF
set          type 1 temperature 0.0
set          region l1 temperature 1.0
set          region l2 temperature 2.0
pair_style   granular
pair_coeff   * * hooke 2000.0 20.0 tangential linear_history 571.42857142857 0.5 0.5 heat area 100.0
variable     twall equal 4.0+0.01*step
region       floor block INF INF INF INF 0.0 30.0 side in units box
fix          wall all wall/gran/region granular hooke 2000.0 20.0 tangential linear_history 571.42857142857 0.5 0.5 heat area 50.0 region floor temperature v_twall
variable     dz equal -0.5*time
region       ball sphere 3.0 2.5 9.5 1.5 side out move NULL NULL v_dz units box
fix          press all wall/gran/region hertz/history 2000.0 NULL 50.0 NULL 0.5 1 region ball
fix          grav all gravity 1.0 vector 0 0 -1
neighbor     0.2 bin
neigh_modify every 1 delay 0 check yes
fix          1 all nve/sphere
fix          heat all heat/flow constant 1.0
compute      tprop all property/atom temperature
compute      tsum all reduce sum c_tprop
compute      erot all erotate/sphere
timestep     0.001
thermo_style custom step ke pe c_erot c_tsum press
thermo_modify format float %.15g
thermo       50
run          250
run          150
";
    compare(deck, 2);
    compare(deck, 3);
}

/// Under mpiexec: fix move, spring and dt/reset with fix print (appending), ave/time and
/// ave/chunk files, which rank 0 alone writes; thermo and files as the serial run's.
#[test]
#[cfg_attr(not(live_mpi), ignore = "live MPI comparison: DMHS_MPI_BIN (a dmhs built with --features mpi) not set")]
fn mpiexec_moving_groups_print_and_average_as_the_serial_run() {
    let (bin, mpiexec) = mpi_launcher();
    let dir = tempfile::tempdir().unwrap();
    let deck = melt_with(
        "region       s2 block INF INF INF INF 3.3 4.6 units box\n\
         group        lin region s2\n\
         group        rest subtract all lin\n\
         fix          1 rest nve\n\
         fix          2 lin move linear 1.5 -0.7 NULL units box\n\
         fix          3 rest spring tether 5.0 2.0 NULL 4.0 0.0\n\
         fix          dt all dt/reset 10 NULL 0.006 0.02 units box\n\
         fix          av all ave/time 5 4 50 c_thermo_temp c_thermo_pe f_3 file ave.txt\n\
         fix          pr all print 25 \"$(step) $(dt:%.15g) $(temp:%.15g) $(pe:%.15g)\" append print.txt\n\
         compute      cz all chunk/atom bin/1d z lower 0.25 units reduced\n\
         fix          ch all ave/chunk 10 5 50 cz vx density/number temp file chunk.txt\n\
         thermo_style custom step dt temp epair etotal f_3 f_av[1] f_av[2] f_ch[2][3]\n\
         thermo_modify format float %.15g\n",
    );
    std::fs::write(dir.path().join("in.fixes"), &deck).unwrap();
    let run = |np: usize| {
        for f in ["ave.txt", "print.txt", "chunk.txt"] {
            let _ = std::fs::remove_file(dir.path().join(f));
        }
        let mut cmd = std::process::Command::new(&mpiexec);
        cmd.args(["-np", &np.to_string(), &bin]);
        let out = cmd.args(["-threads", "1", "-in", "in.fixes", "-log", "none"]).current_dir(dir.path()).output().unwrap_or_else(|e| panic!("{mpiexec}: {e}"));
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(out.status.success(), "{np} ranks: {text}\n{}", String::from_utf8_lossy(&out.stderr));
        let files = ["ave.txt", "print.txt", "chunk.txt"].map(|f| file_numbers(&dir.path().join(f)).expect("written"));
        (thermo_rows(&text), files)
    };
    let (rows1, files1) = run(1);
    for np in [2, 3] {
        let (rows, files) = run(np);
        assert!(rows1.len() >= 7 && rows.len() == rows1.len(), "{np} ranks: {rows:?}");
        assert!(rows.iter().flatten().zip(rows1.iter().flatten()).all(|(x, y)| close(*x, *y, 1e-9)), "{np} ranks: {rows:?} against serial {rows1:?}");
        for (f, f1) in files.iter().zip(&files1) {
            assert!(f.len() >= 20 && f.len() == f1.len() && f.iter().zip(f1).all(|(x, y)| close(*x, *y, 1e-9)), "{np} ranks: a fix's file differs from the serial one: {} values against {}, first {:?} against {:?}", f.len(), f1.len(), &f[..f.len().min(12)], &f1[..f1.len().min(12)]);
        }
    }
}

/// Run control, restraints, a stochastic thermostat and analysis on ranks: fix recenter,
/// spring/rg, temp/csvr (the same draws on every rank), ave/histo of per-atom values and its
/// array, fix vector, compute gyration, vacf, msd and coord/atom (pairs across a rank boundary
/// counted by each owner), and fix halt stopping every rank at the same step.
#[test]
fn analysis_restraints_and_halt_on_ranks_are_the_serial_run() {
    let deck = melt_with(
        "fix          1 all nve\n\
         region       half block 0 3 INF INF INF INF units lattice\n\
         group        half region half\n\
         fix          2 all recenter INIT INIT INIT\n\
         fix          3 half spring/rg 2.0 NULL\n\
         fix          4 all temp/csvr 2.5 2.5 0.5 4321\n\
         compute      ke all ke/atom\n\
         fix          5 all ave/histo 10 2 50 0.0 6.0 12 c_ke mode vector\n\
         compute      g half gyration\n\
         compute      vf all vacf\n\
         compute      m half msd\n\
         compute      co all coord/atom cutoff 1.3\n\
         compute      cs all reduce sum c_co\n\
         fix          6 all vector 10 c_g c_thermo_temp\n\
         variable     h equal f_5[4][2]+max(f_5[3])+trap(f_6[2])+f_6[1][1]\n\
         thermo_style custom step temp epair etotal press f_2 f_3 f_4 f_5[1] f_5[3] v_h c_g c_g[1] c_vf[4] c_m[4] c_cs\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deck, 2);
    compare(&deck, 3);
    let halt = melt_with(
        "fix          1 all nve\n\
         variable     t equal temp\n\
         fix          2 all halt 10 v_t < 1.62 error continue\n\
         thermo_style custom step temp epair etotal press\n\
         thermo_modify format float %.15g\n",
    )
    .replace("thermo       50\n", "thermo       10\n");
    let (text, _) = serial(&halt);
    assert!(text.contains("Fix halt condition for fix-id 2 met on step"), "{text}");
    compare(&halt, 2);
}

/// Spheres poured into a z-cylinder (fix pour: polydisperse, a density range, lateral
/// velocities, a region moving down) land on a frictional floor and on each other, the first
/// batches among spheres that were in the region when the run began. Every rank sees the
/// spheres of all ranks near the region and draws the same stream, so each places the serial
/// run's spheres and keeps those in its sub-domain: the serial run's count, thermo and atoms on
/// 2 and 4 ranks.
const POUR: &str = "
units        lj
atom_style   sphere
boundary     p p f
comm_modify  vel yes
region       box block -4 4 -4 4 0 10 units box
create_box   2 box
neighbor     0.3 bin
neigh_modify delay 0
pair_style   gran/hooke/history 2000.0 NULL 50.0 NULL 0.5 1
pair_coeff   * *
timestep     0.001
fix          grav all gravity 1.0 vector 0 0 -1
fix          1 all nve/sphere
fix          floor all wall/gran granular hooke 2000.0 50.0 tangential linear_history 571.43 0.5 0.5 damping mass_velocity zplane 0.0 NULL
region       feed cylinder z 0 0 3.5 4 7 units box
lattice      sc 0.2
region       seed block -3 3 -3 3 4.2 6.9 units box
create_atoms 2 region seed
fix          ins all pour 150 2 4767548 region feed diam poly 3 0.6 0.3 0.8 0.5 1.0 0.2 dens 1.0 1.5 vol 0.3 20 vel -0.2 0.2 -0.1 0.3 -0.5 rate -0.1
compute      rot all erotate/sphere
compute_modify thermo_temp dynamic/dof yes
thermo_style custom step atoms ke c_rot
thermo_modify norm no format float %.15g
thermo       200
run          1400
";

#[test]
fn poured_spheres_on_ranks_are_the_serial_run() {
    let (text, atoms) = serial(POUR);
    // the spheres in the region leave room for 44 of the batch's 127
    assert!(text.contains("Fewer insertions than requested") && atoms.len() == 18 + 44, "{text}");
    compare(POUR, 2);
    compare(POUR, 4);
}

/// Atoms deposited one every 25 steps (fix deposit: `local` height above the highest atom
/// nearby, `near`, a velocity range) onto an LJ substrate, and one every 60 steps at a `global`
/// height: the highest atom and the crowding test are over every rank's atoms, so each rank
/// makes the serial run's attempts and the owner of the new atom takes it. (The serial thermo
/// is LAMMPS' to 13 digits, the failed deposition included.)
#[test]
fn deposited_atoms_on_ranks_are_the_serial_run() {
    let deck = "
units        lj
atom_style   atomic
boundary     p p f
lattice      fcc 1.0
region       box block 0 5 0 5 0 16
create_box   2 box
region       substrate block INF INF INF INF INF 3
create_atoms 1 region substrate
pair_style   lj/cut 2.5
pair_coeff   * * 1.0 1.0
mass         * 1.0
neigh_modify delay 0
group        addatoms type 2
region       mobile block 0 5 0 5 2 INF
group        mobile region mobile
velocity     mobile create 0.1 4928459 loop geom
region       slab block 0 5 0 5 8 9
fix          1 addatoms nve
fix          2 mobile nve
fix          3 addatoms deposit 10 2 25 12345 region slab near 1.2 local 0.6 1.0 2.0 vz -3.0 -2.0 vx -0.1 0.1 attempt 20
fix          4 addatoms deposit 4 2 60 54321 region slab near 1.0 global 1.0 1.5 vz -2.0 -2.0 units box
fix          5 addatoms wall/reflect zhi EDGE
thermo_style custom step atoms temp pe f_3 f_4
thermo_modify format float %.15g
thermo       30
run          300
";
    let (text, atoms) = serial(deck);
    // one of fix 3's depositions finds no uncrowded place in its 20 attempts
    assert!(atoms.len() == 350 + 14 && text.contains("depositions were unsuccessful"), "10 + 4 deposited on the 350: {} atoms\n{text}", atoms.len());
    compare(deck, 2);
    compare(deck, 3);
}

/// Bonded dimers deposited on ranks (fix deposit mol with a template that has a bond): the
/// rank that owns a dimer's centre takes its atoms, every rank adds its bond to the topology it
/// keeps whole, and the special lists and bonded lists follow at the rebuild: the serial run's
/// bond energy, atoms and thermo on 2 and 3 ranks.
#[test]
fn deposited_bonded_molecules_on_ranks_are_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("dimer.mol"), "dimer\n\n2 atoms\n1 bonds\n\nCoords\n\n1 -0.5 0 0\n2 0.5 0 0\n\nTypes\n\n1 1\n2 1\n\nBonds\n\n1 1 1 2\n").unwrap();
    let deck = format!(
        "units lj\natom_style bond\nboundary p p f\nprocessors * * 1\nregion box block 0 10 0 10 0 8\ncreate_box 1 box bond/types 1 extra/bond/per/atom 1 extra/special/per/atom 1\n\
         mass * 1.0\npair_style lj/cut 2.5\npair_coeff * * 1.0 1.0\nbond_style harmonic\nbond_coeff 1 50.0 1.1\nmolecule dimer {}/dimer.mol\n\
         region slab block 0 10 0 10 5 6\nfix 1 all nve\nfix 2 all deposit 10 0 15 12345 region slab near 1.3 mol dimer vz -1.0 -0.5 vx -0.3 0.3 units box\n\
         fix 3 all wall/reflect zlo EDGE zhi EDGE\nthermo_style custom step atoms temp epair ebond etotal f_2\nthermo_modify format float %.15g\nthermo 20\nrun 200\n",
        dir.path().display()
    );
    let (text, atoms) = serial(&deck);
    let rows = thermo_rows(&text);
    assert!(atoms.len() == 20 && rows.last().is_some_and(|r| r[4] > 0.0), "10 dimers, stretched bonds: {text}");
    compare(&deck, 2);
    compare(&deck, 3);
}

/// Shrink-wrapped faces (boundary s and m) follow the atoms of every rank: each rebuild takes
/// the extent over the ranks, so every rank cuts the same box and the volume column is the
/// serial one. A pour into a box whose top is `m` (as LAMMPS' examples/pour), and an LJ
/// cluster evaporating into a box shrink-wrapped in x and y, on 2 and 4 ranks.
#[test]
fn shrink_wrapped_boxes_on_ranks_are_the_serial_run() {
    let pour = POUR.replace("boundary     p p f\n", "boundary     p p fm\n").replace("thermo_style custom step atoms ke c_rot", "thermo_style custom step atoms ke c_rot vol");
    let melt = MELT.replace("lattice      fcc 0.8442\n", "boundary     s s p\nlattice      fcc 0.8442\n").replace("press atoms", "press atoms vol").replace("check no\n", "check yes\n");
    let (text, _) = serial(&melt);
    let vols: Vec<f64> = thermo_rows(&text).iter().map(|r| r[7]).collect();
    assert!(vols.windows(2).any(|w| w[1] != w[0]), "the box follows the atoms: {vols:?}");
    for ranks in [2, 4] {
        compare(&pour, ranks);
        compare(&melt, ranks);
    }
}

/// Fix ave/chunk on ranks: each rank bins its own atoms (compute chunk/atom bin/1d, bin/2d,
/// type, and molecule with compress in a region on one rank's side, whose IDs are gathered
/// from every rank) and the counts and sums are summed over the ranks before the averages;
/// `ids nfreq` and `ids once` keep each atom's chunk by ID wherever it migrates. Rank 0 alone writes the files,
/// which hold the serial run's numbers; the f_ID array in the thermo too.
#[test]
fn chunk_averages_on_ranks_are_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    let melt = |tag: &str| {
        let p = |name: &str| dir.path().join(format!("{tag}.{name}")).display().to_string();
        melt_with(&format!(
            "fix          1 all nve\n\
             compute      z all chunk/atom bin/1d z lower 0.25 units reduced ids nfreq\n\
             compute      xy all chunk/atom bin/2d x lower 0.5 y 0.0 2.0 units lattice ids once\n\
             compute      ke all ke/atom\n\
             fix          a all ave/chunk 10 5 50 z vx density/number temp c_ke norm sample file {}\n\
             fix          b all ave/chunk 5 2 50 xy vz density/mass ave running file {}\n\
             thermo_style custom step temp epair etotal f_a[2][3] f_a[3][6] f_b[4][5] c_z c_xy\n\
             thermo_modify format float %.15g\n",
            p("z"),
            p("xy")
        ))
    };
    for ranks in [2, 3] {
        let (tag0, tag) = (format!("s{ranks}"), format!("r{ranks}"));
        compare_decks(&melt(&tag0), &melt(&tag), ranks, 1e-9);
        for f in ["z", "xy"] {
            let (a, b) = (dir.path().join(format!("{tag0}.{f}")), dir.path().join(format!("{tag}.{f}")));
            let (x, y) = (file_numbers(&a).expect("serial file"), file_numbers(&b).expect("file written on ranks"));
            assert!(x.len() >= 100 && x.len() == y.len(), "{}: {} values against serial {}", b.display(), y.len(), x.len());
            assert!(x.iter().zip(&y).all(|(x, y)| close(*x, *y, 1e-9)), "{} differs from the serial file", b.display());
        }
    }
    // molecules (bonded chains) and types, compressed molecule IDs
    let chains = |tag: &str| {
        let p = dir.path().join(format!("{tag}.mol")).display().to_string();
        chains_deck(dir.path(), "bond_style   harmonic\nbond_coeff   1 100.0 0.97").replace(
            "fix          1 all nve\n",
            &format!(
                "fix          1 all nve\n\
                 group        odd molecule 1:36:2\n\
                 region       left block 0 4 INF INF INF INF units box\n\
                 compute      m odd chunk/atom molecule compress yes region left\n\
                 compute      t all chunk/atom type\n\
                 fix          m all ave/chunk 10 5 50 m vx vy temp file {p}\n\
                 fix          t all ave/chunk 25 2 50 t vz\n\
                 variable     nm equal c_m\n"
            ),
        ).replace("thermo_style custom step temp epair ebond eangle edihed etotal press atoms", "thermo_style custom step temp epair ebond etotal press v_nm f_m[3][4] f_t[1][2]\nthermo_modify format float %.15g")
    };
    let (text, _) = serial(&chains("c1"));
    let nm: Vec<f64> = thermo_rows(&text).iter().map(|r| r[6]).collect();
    assert!(nm.iter().all(|&n| n > 0.0 && n <= 18.0) && nm.iter().any(|&n| n < 18.0), "the odd molecules with atoms in the left region: {nm:?}");
    compare_decks(&chains("c1"), &chains("c2"), 2, 1e-9);
    let (x, y) = (file_numbers(&dir.path().join("c1.mol")).unwrap(), file_numbers(&dir.path().join("c2.mol")).unwrap());
    assert!(x.len() >= 100 && x.len() == y.len() && x.iter().zip(&y).all(|(x, y)| close(*x, *y, 1e-9)), "the molecule chunk file on 2 ranks differs from the serial one");
}

/// Fix ave/atom on ranks: each atom's sums live in an array that travels with it, so the
/// averages of atoms that change rank go on; compute reduce of them sums over the ranks, and a
/// sorted dump of them, which rank 0 writes from the gathered atoms, is the serial one.
#[test]
fn per_atom_averages_on_ranks_are_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    let deck = |tag: &str| {
        let p = dir.path().join(format!("{tag}.dump")).display().to_string();
        melt_with(&format!(
            "fix          1 all nve\n\
             compute      ke all ke/atom\n\
             fix          aa all ave/atom 5 4 50 x vx c_ke\n\
             compute      s all reduce sum f_aa[2] f_aa[3]\n\
             compute      m all reduce max f_aa[1]\n\
             dump         d all custom 50 {p} id f_aa[1] f_aa[2] f_aa[3]\n\
             dump_modify  d sort id format float %.15g\n\
             thermo_style custom step temp epair etotal c_s[1] c_s[2] c_m\n\
             thermo_modify format float %.15g\n"
        ))
    };
    for ranks in [2, 3] {
        let (tag0, tag) = (format!("s{ranks}"), format!("r{ranks}"));
        compare_decks(&deck(&tag0), &deck(&tag), ranks, 1e-9);
        let (a, b) = (dir.path().join(format!("{tag0}.dump")), dir.path().join(format!("{tag}.dump")));
        let (x, y) = (file_numbers(&a).expect("serial dump"), file_numbers(&b).expect("dump written on ranks"));
        assert!(x.len() > 864 * 4 * 5 && x.len() == y.len(), "{}: {} values against serial {}", b.display(), y.len(), x.len());
        assert!(x.iter().zip(&y).all(|(x, y)| close(*x, *y, 1e-9)), "{} differs from the serial dump", b.display());
    }
}

/// Fix aveforce (the group's force summed over the ranks, then shared out), fix adapt (pair soft's
/// prefactor from a ramp, the same on every rank) and fix balance (a no-op: ranks balance by
/// default) on ranks: the serial run's thermo and atoms.
#[test]
fn aveforce_adapt_and_balance_on_ranks_are_the_serial_run() {
    let aveforce = melt_with(
        "region       top block INF INF INF INF 4 INF units lattice\n\
         group        top region top\n\
         fix          1 all nve\n\
         fix          2 top aveforce NULL 0.1 NULL\n\
         fix          3 all balance 100 1.1 shift xyz 10 1.05\n\
         thermo_style custom step temp epair etotal press f_2[1] f_2[2] f_2[3]\n\
         thermo_modify format float %.15g\n",
    )
    // the group's own repulsions along y are replaced by their mean: a short run
    .replace("thermo       50\nrun          150\nrun          100\n", "thermo       5\nrun          20\nrun          15\n");
    compare(&aveforce, 2);
    compare(&aveforce, 3);
    let adapt = melt_with(
        "fix          1 all nve\n\
         variable     a equal ramp(0.0,40.0)\n\
         fix          2 all adapt 1 pair soft a * * v_a\n\
         thermo_style custom step temp epair etotal press v_a\n\
         thermo_modify format float %.15g\n",
    )
    .replace("pair_style   lj/cut 2.5\npair_coeff   1 1 1.0 1.0 2.5\n", "pair_style   soft 1.12\npair_coeff   * * 0.0\n");
    let (text, _) = serial(&adapt);
    assert!(thermo_rows(&text).iter().any(|r| r[2] > 0.0), "the soft energy grows with the prefactor: {text}");
    compare(&adapt, 2);
    compare(&adapt, 3);
}

/// `processors` with `map` and `grid twolevel|custom` (the layouts LAMMPS 22 Jul 2025 makes: the
/// grid file of each matches LAMMPS' on 1 to 16 ranks, see src/engine/procmap.rs): other ranks
/// own the sub-domains, the run is the serial one, and `file` lists each rank's place as LAMMPS
/// writes it (rank 1's line is LAMMPS' for this box).
#[test]
fn processor_maps_and_grids_give_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.txt"), "# 4 ranks\n2 2 1\n0 2 2 1\n1 1 1 1\n2 2 1 1\n3 1 2 1\n").unwrap();
    for (procs, ranks, place1) in [
        ("processors * * * map xyz", 4, "1 1 1: 1 2 1"),
        ("processors * * * grid twolevel 2 * * * map yzx", 4, "1 1 1: 1 2 1"),
        ("processors * * 1 grid custom grid.txt", 4, "1 1 1: 1 1 1"),
        ("processors * * * map cart", 2, "1 1 1: 1 1 2"),
    ] {
        let file = dir.path().join("procs.out");
        let line = format!("{procs} file {}\n", file.display()).replace("grid.txt", &dir.path().join("grid.txt").display().to_string());
        let deck = MELT.replace("create_box", &format!("{line}create_box"));
        compare_decks(MELT, &deck, ranks, 1e-9);
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(text.starts_with("LAMMPS mapping of processors to 3d grid\npartition = 1\n"), "{procs}: {text}");
        assert!(text.lines().any(|l| l.starts_with(place1)), "{procs}: rank 1 at {place1}:\n{text}");
        assert_eq!(text.lines().filter(|l| l.contains(": ")).count(), ranks + 1, "{procs}: {text}");
    }
}

/// What the `processors` command refuses, located in the deck: unknown keywords and styles,
/// LAMMPS' NUMA grid and multi-partition links, core counts that do not multiply to Nc, and
/// custom grid files that do not hold together (the file's line named).
#[test]
fn processors_errors_are_located() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.txt"), "1 1 1\n3 1 1 1\n").unwrap();
    let bad = dir.path().join("bad.txt").display().to_string();
    for (line, want) in [
        ("processors * * * mapp xyz".to_string(), "unknown keyword `mapp`"),
        ("processors * * * map xxy".to_string(), "unknown map style `xxy`"),
        ("processors * * * grid numa".to_string(), "grid numa is not supported"),
        ("processors * * * grid threelevel".to_string(), "unknown grid style"),
        ("processors * * * part 1 2 multiple".to_string(), "several partitions"),
        ("processors * * * grid twolevel 4 2 1 1".to_string(), "multiply to Nc = 4"),
        ("processors * * * grid custom nothere.txt".to_string(), "cannot open processors custom file"),
        (format!("processors * * * grid custom {bad}"), "bad.txt:2: processor ID 3"),
        ("processors 2 1 1".to_string(), "cannot be arranged for 1 ranks"),
    ] {
        let deck = MELT.replace("create_box", &format!("{line}\ncreate_box"));
        let err = dmhs::deck::run_text("deck", &deck, &options()).err().unwrap_or_else(|| panic!("{line}: accepted")).rendered;
        assert!(err.contains(want) && err.contains("deck:6:"), "{line}: expected `{want}`:\n{err}");
    }
    // LAMMPS 22 Jul 2025: "Processors command after simulation box is defined"
    let deck = MELT.replace("mass         1 1.0\n", "mass         1 1.0\nprocessors   * * *\n");
    let err = dmhs::deck::run_text("deck", &deck, &options()).err().expect("processors after the box is refused").rendered;
    assert!(err.contains("processors must be used before the simulation box is defined") && err.contains("deck:9:"), "{err}");
}

/// Barostats and fix deform on ranks: the box changes identically on every rank (the pressure,
/// temperature and virial are sums over the ranks), the sub-domains follow it as fractions of
/// the box, and the runs are the serial run's.
#[test]
fn barostats_and_deform_on_ranks_are_the_serial_run() {
    let npt = melt_with(
        "fix          1 all npt temp 2.0 2.0 0.5 iso 1.0 3.0 1.0\n\
         thermo_style custom step temp epair etotal press vol f_1 f_1[7]\n\
         thermo_modify format float %.15g\n",
    );
    compare(&npt, 2);
    compare(&npt, 4);
    let nph = melt_with(
        "fix          1 all nph x 2.0 2.0 1.0 y 1.0 1.0 1.0 z 3.0 3.0 1.0 ptemp 2.0 fixedpoint 0 0 0\n\
         thermo_style custom step temp epair etotal press pxx pyy pzz lx ly lz f_1\n\
         thermo_modify format float %.15g\n",
    );
    compare(&nph, 2);
    let deform = melt_with(
        "fix          1 all nve\n\
         fix          2 all deform 1 x erate 0.05 y volume remap x\n\
         thermo_style custom step temp epair etotal press lx ly lz\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deform, 2);
    compare(&deform, 4);
}

/// The LJ melt in a prism (every tilt non-zero): the ranks cut the box in box fractions, as
/// LAMMPS cuts a triclinic box, and the ghosts across the tilted faces are the serial run's.
fn tilted_melt(fixes: &str) -> String {
    MELT.replace("region       box block 0 6 0 6 0 6\n", "region       box prism 0 6 0 6 0 6 1.5 -1.0 0.8\n")
        .replace("check no\n", "check yes\n")
        .replace("fix          1 all nve\nthermo_style custom step temp epair emol etotal press atoms\n", fixes)
}

#[test]
fn a_triclinic_box_on_ranks_is_the_serial_run() {
    let nve = tilted_melt("fix          1 all nve\nthermo_style custom step temp epair etotal press pxy pxz pyz xy xz yz atoms\nthermo_modify format float %.15g\n");
    compare(&nve, 2);
    compare(&nve, 3);
    compare(&nve, 4);
    // the box tilting as the atoms move (fix deform remaps them in box fractions), and a
    // barostat on every degree of freedom of the box
    let deform = tilted_melt(
        "fix          1 all nvt temp 3.0 3.0 0.5\n\
         fix          2 all deform 1 xy erate 0.05 yz erate -0.03\n\
         thermo_style custom step temp epair etotal press pxy xy yz atoms\n\
         thermo_modify format float %.15g\n",
    );
    compare(&deform, 4);
    let npt = tilted_melt(
        "fix          1 all npt temp 3.0 3.0 0.5 tri 4.0 4.0 2.0\n\
         thermo_style custom step temp epair etotal press vol xy xz yz atoms\n\
         thermo_modify format float %.15g\n",
    );
    compare(&npt, 2);
}

/// Bonded chains in a box made triclinic and sheared (bonds, angles and dihedrals across the
/// tilted periodic faces and the ranks' boundaries).
#[test]
fn bonded_chains_in_a_triclinic_box_on_ranks_are_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    let deck = chains_deck(dir.path(), "bond_style   harmonic\nbond_coeff   1 100.0 0.97")
        .replace("angle_style  harmonic\n", "change_box   all triclinic\nchange_box   all xy final 3.0 xz final -2.0 yz final 1.5 remap units box\nangle_style  harmonic\n")
        .replace("processors   * 1 1\n", "");
    compare(&deck, 2);
    compare(&deck, 4);
}

/// A 2D liquid slab in a tilted box with shrink-wrapped faces along y: the faces follow the
/// atoms of every rank (in box fractions), and the processor grid is the one LAMMPS 22 Jul 2025
/// chooses for this deck (`mpiexec -np 4 lmp` prints "2 by 2 by 1": from the box as
/// create_box made it, not the shrink-wrapped box of the run, which would be cut 4 by 1).
#[test]
fn a_shrink_wrapped_triclinic_slab_on_ranks_is_the_serial_run() {
    let deck = "
units        lj
dimension    2
atom_style   atomic
boundary     p s p
lattice      sq2 0.8442
region       box prism 0 20 0 12 -0.5 0.5 4.0 0 0
create_box   1 box
region       blob block 0 20 2 10 INF INF
create_atoms 1 region blob
mass         1 1.0
velocity     all create 1.0 87287 loop geom
pair_style   lj/cut 2.5
pair_coeff   1 1 1.0 1.0 2.5
neighbor     0.3 bin
neigh_modify every 2 delay 0 check yes
fix          1 all nve
fix          2 all enforce2d
thermo_style custom step temp epair etotal press pxy xy ylo yhi atoms
thermo_modify format float %.15g
thermo       50
run          300
";
    compare(deck, 2);
    compare(deck, 4);
    let text = on_ranks(deck, 4).swap_remove(0).unwrap().0;
    assert!(text.contains("2 by 2 by 1 MPI processor grid"), "{text}");
}

/// NEMD on ranks: SLLOD shear of the tilted melt (fix deform xy erate remap v, fix nvt/sllod
/// with its temp/deform), and a dense granular packing sheared the same way with `comm_modify
/// vel yes`, whose contact damping reads the ghosts' velocities: an image across a periodic
/// face carries the box's streaming velocity (LAMMPS' deform_vremap), on every rank as in the
/// serial run.
#[test]
fn sllod_shear_on_ranks_is_the_serial_run() {
    let sllod = tilted_melt(
        "fix          1 all nvt/sllod temp 3.0 3.0 0.5\n\
         fix          2 all deform 1 xy erate 0.2 remap v\n\
         compute      tdef all temp/deform\n\
         thermo_style custom step temp c_tdef epair etotal press pxy xy atoms\n\
         thermo_modify format float %.15g\n",
    );
    compare(&sllod, 2);
    compare(&sllod, 4);
    let granular = "
units        lj
atom_style   sphere
comm_modify  vel yes
lattice      sc 0.9
region       box prism 0 7 0 7 0 7 0 0 0
create_box   1 box
create_atoms 1 box
set          type 1 diameter 1.05
set          type 1 density 1.0
velocity     all create 0.1 87287 loop geom
pair_style   gran/hooke/history 2000.0 NULL 50.0 NULL 0.5 1
pair_coeff   * *
fix          1 all nve/sphere
fix          2 all deform 1 xy erate 0.5 remap v
compute      erot all erotate/sphere
thermo_style custom step ke c_erot press pxy xy atoms
thermo_modify format float %.15g
thermo       100
timestep     0.002
run          800
";
    compare(granular, 2);
    compare(granular, 4);
}

/// A deck of lammps-refs/decks with thermo every `every` steps, and the options that run it
/// there (its files read from that folder) with `nsteps` steps per run.
fn refs_deck(name: &str, nsteps: usize, every: usize) -> (String, DeckOptions) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks");
    let text = std::fs::read_to_string(dir.join(format!("in.{name}"))).unwrap();
    let text: String = text.lines().map(|l| if l.split_whitespace().next() == Some("thermo") && l.split_whitespace().count() == 2 { format!("thermo {every}\n") } else { format!("{l}\n") }).collect();
    let opts = DeckOptions { base_dir: Some(dir), vars: vec![("nsteps".into(), vec![nsteps.to_string()])], ..options() };
    (text, opts)
}

/// Rigid bodies on ranks (fix rigid and rigid/small with their nve, nvt, npt and nph steps,
/// Langevin, enforce2d): every rank knows every body (set up from all atoms, gathered on
/// ranks), each sums the forces and torques of its own atoms, and the sums are added over
/// the ranks; the bodies then move as in a serial run.
#[test]
fn rigid_bodies_on_ranks_are_the_serial_run() {
    for (name, ranks) in [
        ("rigid_small_clumps", 2),
        ("rigid_small_clumps", 4),
        ("rigid_nvt_npt_clumps", 3),
        ("rigid_group_langevin", 2),
        ("rigid_small_langevin", 3),
        ("rigid_nve_small_clumps", 2),
        ("rigid_npt_small_clumps", 2),
        ("rigid_nph_small_2d", 4),
        ("rigid_single_2d", 2),
        ("rigid_clumps_flags", 2),
        ("rigid_small_reinit", 2),
    ] {
        eprintln!("{name} on {ranks} ranks");
        let (deck, opts) = refs_deck(name, 150, 25);
        compare_decks_with(&deck, &deck, ranks, 1e-9, &opts);
    }
}

/// A rigid fix that inserts bodies from a molecule template stays refused on ranks.
#[test]
fn rigid_bodies_from_a_template_are_refused_on_ranks() {
    let (deck, opts) = refs_deck("rigid_deposit", 100, 25);
    for e in refusals_with(&deck, 2, &opts) {
        assert!(e.contains("with a molecule template (mol) cannot run on 2 ranks yet"), "{e}");
    }
}

/// delta-SPH density diffusion (dmhs/sph/delta, both forms, under hybrid/overlay) on ranks: the
/// diffusion reads the ghosts' densities, forwarded as sph/taitwater's are.
#[test]
fn delta_sph_on_ranks_is_the_serial_run() {
    for (form, ranks) in [("molteni", 2), ("fourtakas g 0.0 -0.002 0.0", 4)] {
        let deck = SPH
            .replace("run          0 post no\n", "")
            .replace("dump         d all custom 100 dump.sph id x y vx vy c_rho c_e c_dx[1] c_dx[4]\ndump_modify  d sort id\n", "")
            .replace("thermo       50", "thermo       25")
            .replace("pair_style   hybrid/overlay sph/rhosum 1 sph/taitwater\npair_coeff   * * sph/rhosum 2.4\n", &format!("pair_style   hybrid/overlay sph/taitwater dmhs/sph/delta {form}\npair_coeff   * * dmhs/sph/delta 1.0 10.0 0.1 2.4\n"))
            .replace("velocity     all create 0.05", "velocity     all create 0.3");
        compare_decks(&deck, &deck, ranks, 1e-9);
    }
}

/// pair_style zero and bond_style zero on ranks (a deck that lists pairs and bonds without
/// forces, as LAMMPS decks do to keep a neighbour list or a topology).
#[test]
fn zero_styles_on_ranks_are_the_serial_run() {
    let dir = tempfile::tempdir().unwrap();
    // the chains' bonds as bond_style zero (short runs: the chains come apart), pairs listed to
    // 2.0 by pair_style zero beside the WCA
    let deck = chains_deck(dir.path(), "bond_style   zero\nbond_coeff   1")
        .replace("pair_style   lj/cut 1.122462048309373\npair_coeff   1 1 1.0 1.0\n", "pair_style   hybrid/overlay lj/cut 1.122462048309373 zero 2.0\npair_coeff   1 1 lj/cut 1.0 1.0\npair_coeff   * * zero\n")
        .replace("thermo       50\n", "thermo       5\n")
        .replace("run          150\nrun          100\n", "run          30\nrun          20\n");
    compare(&deck, 2);
    // run on, the unbonded chains come apart: a dihedral reaches past the ghosts, and the
    // message names the rank it came from once
    for e in refusals(&deck.replace("run          30\nrun          20\n", "run          150\n"), 2) {
        assert!(e.contains("is missing on this rank") && e.matches("on rank ").count() == 1, "{e}");
    }
}

/// compute heat/flux (from ke/atom, pe/atom and stress/atom), centro/atom (reduced) and
/// msd/chunk (per molecule) on ranks: each rank sums its own atoms, the sums are added over
/// the ranks.
#[test]
fn heat_flux_centro_and_msd_chunk_on_ranks_are_the_serial_ones() {
    let flux = melt_with(
        "fix          1 all nve\n\
         compute      ke all ke/atom\n\
         compute      pe all pe/atom\n\
         compute      st all stress/atom NULL virial\n\
         compute      flux all heat/flux ke pe st\n\
         thermo_style custom step temp epair c_flux[1] c_flux[2] c_flux[3] c_flux[4] c_flux[6]\n\
         thermo_modify format float %.15g\n",
    );
    compare(&flux, 2);
    compare(&flux, 3);
    // centro/atom, like coord/atom, from each owned atom's pairs with owned atoms and ghosts
    let centro = melt_with(
        "fix          1 all nve\n\
         compute      cs all centro/atom fcc\n\
         compute      sum all reduce sum c_cs\n\
         compute      max all reduce max c_cs\n\
         thermo_style custom step temp epair c_sum c_max\n\
         thermo_modify format float %.15g\n",
    );
    compare(&centro, 2);
    compare(&centro, 4);
    let dir = tempfile::tempdir().unwrap();
    let chains = chains_deck(dir.path(), "bond_style   harmonic\nbond_coeff   1 100.0 0.97").replace(
        "thermo_style custom step temp epair ebond eangle edihed etotal press atoms\n",
        "compute      mol all chunk/atom molecule\ncompute      msd all msd/chunk mol\nvariable     m1 equal c_msd[1][4]\nvariable     m3 equal c_msd[3][1]\nthermo_style custom step temp epair v_m1 v_m3\nthermo_modify format float %.15g\n",
    );
    compare(&chains, 2);
}
