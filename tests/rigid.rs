//! fix rigid/small and its nve, nvt, npt and nph forms against LAMMPS beyond the trajectories
//! (those are in tests/lammps_parity.rs): the thermo tables of rigid_small_clumps (3d),
//! rigid_small_2d (enforce2d), rigid_small_gran (clumps of spheres on a granular floor: the body
//! mass in the granular damping, compute temp/sphere), rigid_small_langevin, rigid_nve_small_clumps
//! and rigid_nvt_small_clumps (the NO_SQUISH step and its Nose-Hoover chains, f_1 the extended
//! system's energy, ecouple), rigid_nvt_small_2d, rigid_npt_small_clumps and rigid_nph_small_2d
//! (the barostat), and rigid_deposit (fix deposit rigid), whose
//! pressure and its tensor carry the bodies' constraint virial (LAMMPS' set_xv/set_v tally, on
//! by default), every printed step, against lammps-refs/refs/NAME/thermo.txt (and LAMMPS run
//! now, when present). And the located refusals of what the fixes do not support.

use dmhs::deck::{run_text, DeckOptions};

mod thermo_tables;
use thermo_tables::table;

const DECKS: [&str; 24] = ["rigid_small_tri", "rigid_clumps_flags", "rigid_small_custom", "rigid_read_data_fix", "rigid_small_infile", "rigid_small_reinit", "rigid_gravity_bodies", "rigid_pour_gravity", "rigid_clumps_infile", "rigid_custom_gmask", "rigid_nve_nvt_flags", "rigid_group_langevin", "rigid_nvt_npt_clumps", "rigid_single_2d", "rigid_small_clumps", "rigid_small_2d", "rigid_small_gran", "rigid_small_langevin", "rigid_nve_small_clumps", "rigid_nvt_small_clumps", "rigid_nvt_small_2d", "rigid_npt_small_clumps", "rigid_nph_small_2d", "rigid_deposit"];

thermo_tables::thermo_table_tests!(DECKS);

/// Two rigid dimers in a periodic box, meeting head on.
const BASE: &str = "units lj\natom_style bond\nboundary p p p\nregion box block 0 10 0 10 0 10 units box\ncreate_box 1 box\n\
create_atoms 1 single 2 5 5 units box\ncreate_atoms 1 single 3 5 5 units box\ncreate_atoms 1 single 4.1 5.2 5 units box\ncreate_atoms 1 single 5.1 5.2 5 units box\n\
set atom 1*2 mol 1\nset atom 3*4 mol 2\nmass 1 1.0\nvelocity all set 0.5 0 0\nvelocity all set -0.5 0 0 units box\n\
pair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nneigh_modify exclude molecule/intra all\n\
fix 1 all rigid/small molecule\n";

fn thermo(extra: &str) -> Vec<Vec<f64>> {
    let deck = format!("{BASE}{extra}thermo_style custom step press pxx pxy\nthermo_modify format float %.17g\nthermo 5\nrun 10\n");
    let run = run_text("ok.deck", &deck, &DeckOptions { screen: false, capture_text: true, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
    table(run.sim.out.captured.as_deref().unwrap()).1
}

/// `fix_modify virial no` takes the constraint virial out of the pressure, `yes` puts it back.
#[test]
fn fix_modify_virial_switches_the_constraint_virial() {
    let on = thermo("");
    let off = thermo("fix_modify 1 virial no\n");
    let again = thermo("fix_modify 1 virial no\nfix_modify 1 virial yes\n");
    assert_eq!(on, again);
    assert!(on.iter().zip(&off).all(|(a, b)| a[1] != b[1]), "the virial changes the pressure:\n{on:?}\n{off:?}");
}

#[test]
fn unsupported_uses_are_located_errors() {
    for (cmd, want) in [
        ("fix_modify 1 energy yes", "does not support fix_modify energy"),
        ("fix 2 all rigid group 1 nogroup", "could not find fix rigid group ID `nogroup`"),
        ("fix 2 all rigid custom i_body", "requires previously defined property/atom `body`"),
        ("fix 2 all rigid custom v_nobody", "Variable name for fix rigid custom does not exist"),
        ("variable e equal 1\nfix 2 all rigid custom v_e", "is no atom-style variable"),
        ("fix 2 all rigid custom d_x", "unsupported fix rigid custom property `d_x`"),
        ("fix 2 all rigid sphere", "illegal fix rigid body style `sphere`"),
        ("fix 2 all rigid molecule force 3 on on on", "body range"),
        ("fix 2 all rigid molecule torque 1 on maybe on", "maybe"),
        ("fix 2 all rigid molecule infile no_such_bodies.txt", "cannot open fix rigid infile"),
        ("fix 2 all rigid/small molecule infile no_such_bodies.txt", "cannot open fix rigid/small infile"),
        ("fix 2 all rigid/small molecule gravity", "fix gravity ID"),
        ("fix 2 all rigid/nve molecule langevin 1 1 1 5", "belongs to rigid and rigid/small"),
        ("fix 2 all rigid/nvt molecule", "did not set temp for fix rigid/nvt"),
        ("fix 2 all rigid molecule mol t", "molecule template `t` does not exist"),
        ("fix_modify 1 bodyforces sometimes", "sometimes"),
        ("fix 2 all rigid/nve/small molecule langevin 1 1 1 5", "belongs to rigid and rigid/small"),
        ("fix 2 all rigid/small molecule langevin 1 1 0 5", "langevin period must be > 0.0"),
        ("fix 2 all rigid/nve/small molecule temp 1 1 1", "illegal fix rigid/nve/small keyword `temp`"),
        ("fix 2 all rigid/nvt/small molecule", "did not set temp for fix rigid/nvt/small"),
        ("fix 2 all rigid/nvt/small molecule temp 1 0 1", "target temperature for fix rigid/nvt/small cannot be 0.0"),
        ("fix 2 all rigid/nvt/small molecule temp 1 1 0", "period must be > 0.0"),
        ("fix 2 all rigid/nvt/small molecule temp 1 1 1 tparam 4 1 4", "t_order must be 3 or 5"),
        ("fix 2 all rigid/nvt/small molecule temp 1 1 1 iso 1 1 1", "rigid/npt, rigid/nph and their /small forms"),
        ("fix 2 all rigid/nph/small molecule temp 1 1 1 iso 1 1 1", "illegal fix rigid/nph/small keyword `temp`"),
        ("fix 2 all rigid/nph/small molecule", "pressure control must be used with fix rigid/nph/small"),
        ("fix 2 all rigid/npt/small molecule iso 1 1 1", "did not set temp for fix rigid/npt/small"),
        ("fix 2 all rigid/npt/small molecule temp 0 1 1 iso 1 1 1", "target temperature for fix rigid/npt/small cannot be 0.0"),
        ("fix 2 all rigid/nph/small molecule x 1 1 1 couple xyz", "pressure settings"),
        ("fix 2 all rigid/nph/small molecule x 1 1 1 y 2 2 1 couple xy", "pressure settings"),
        ("fix 2 all rigid/nph/small molecule iso -1 1 1", "cannot be < 0.0"),
        ("fix 2 all rigid/nph/small molecule iso 1 1 0", "damping parameters must be > 0.0"),
        ("fix 2 all rigid/nph/small molecule iso 1 1 1 dilate nogroup", "dilate group ID `nogroup` does not exist"),
        ("compute k all ke/rigid", "rigid fix ID"),
        ("compute k all erotate/rigid 1 extra", "extra"),
    ] {
        let deck = format!("{BASE}{cmd}\nrun 0\n");
        let f = run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {cmd}"));
        let line = BASE.lines().count() + 1 + cmd.matches('\n').count();
        assert!(f.rendered.contains(&format!("bad.deck:{line}:")) && f.rendered.contains(want), "{cmd}: expected `{want}`:\n{}", f.rendered);
    }
}

/// `gravity FIXID` names a fix gravity: none, or a fix of another style, stops the run (LAMMPS'
/// init); a rigid/small infile names molecules of the group by ID (1 to the largest), located at
/// the file's line.
#[test]
fn rigid_gravity_and_infile_refusals() {
    for (cmd, want) in [("fix 2 all rigid/small molecule gravity g", "fix rigid/small cannot find fix gravity ID g"), ("fix g all nve\nfix 2 all rigid molecule gravity g", "fix rigid gravity fix ID g is not a gravity fix style")] {
        let deck = format!("{BASE}{cmd}\nrun 0\n");
        let f = run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {cmd}"));
        assert!(f.rendered.contains(want), "{cmd}: expected `{want}`:\n{}", f.rendered);
    }
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bodies.txt");
    std::fs::write(&file, "# two bodies\n2\n1 2.0 2.5 5 5 1 1 1 0 0 0 0 0 0 0 0 0 0 0 0\n3 2.0 4.6 5.2 5 1 1 1 0 0 0 0 0 0 0 0 0 0 0 0\n").unwrap();
    let deck = format!("{BASE}fix 2 all rigid/small molecule infile {}\nrun 0\n", file.display());
    let f = run_text("bad.deck", &deck, &Default::default()).err().expect("molecule 3 does not exist");
    assert!(f.rendered.contains("bodies.txt:4: invalid rigid body molecule ID 3 in fix rigid/small infile") && f.rendered.contains(&format!("bad.deck:{}:", BASE.lines().count() + 1)), "{}", f.rendered);
}

/// rigid/small `custom`: LAMMPS' refusals of a missing property and of a variable of another
/// style, dmhs' of a molecule template beside custom bodies, and LAMMPS' check at the run's
/// setup that the ghost cutoff reaches every body atom from its owner (bodies {1,4} and {2,3}:
/// 3.107 from atom 1 to atom 4 against 2.8, unless comm_modify cutoff reaches it).
#[test]
fn rigid_small_custom_refusals() {
    let base = BASE.replace("fix 1 all rigid/small molecule\n", "fix p all property/atom i_b\nset atom 1 i_b 1\nset atom 4 i_b 1\nset atom 2*3 i_b 2\n");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("pair.mol"), "# two atoms\n2 atoms\n\nCoords\n\n1 0 0 0\n2 1 0 0\n\nTypes\n\n1 1\n2 1\n").unwrap();
    let opts = DeckOptions { screen: false, base_dir: Some(dir.path().to_path_buf()), ..Default::default() };
    for (cmd, want) in [
        ("fix 2 all rigid/small custom i_nope", "fix rigid/small custom requires previously defined property/atom `nope`"),
        ("variable v equal 1\nfix 2 all rigid/small custom v_v", "Fix rigid/small custom variable is no atom-style variable"),
        ("molecule two pair.mol\nfix 2 all rigid/small custom i_b mol two", "fix rigid/small custom with a molecule template (`mol`) is not supported"),
        ("fix 2 all rigid/small custom i_b", "Rigid body extent 3.106444913401813 > ghost atom cutoff - use comm_modify cutoff"),
    ] {
        let deck = format!("{base}{cmd}\nrun 0\n");
        let f = run_text("bad.deck", &deck, &opts).err().unwrap_or_else(|| panic!("accepted: {cmd}"));
        assert!(f.rendered.contains(want), "{cmd}: expected `{want}`:\n{}", f.rendered);
    }
    let deck = format!("{base}comm_modify cutoff 3.2\nfix 2 all rigid/small custom i_b\nrun 0\n");
    run_text("ok.deck", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
}

/// fix deposit `rigid`: LAMMPS' three refusals (no molecule template, no such fix, another
/// template than the rigid fix's).
#[test]
fn deposit_rigid_refusals() {
    let base = "units lj\natom_style bond\nboundary p p f\nregion box block 0 5 0 5 0 10\ncreate_box 3 box\nmass * 1.0\n\
molecule tri rigid_tri.mol\nmolecule other rigid_tri.mol\nregion slab block 0 5 0 5 5 6\npair_style lj/cut 2.5\npair_coeff * * 1.0 1.0\n";
    let opts = DeckOptions { screen: false, base_dir: Some(thermo_tables::root().join("lammps-refs/decks")), ..Default::default() };
    for (fixes, want) in [
        ("fix 1 all rigid/nve/small molecule mol tri\nfix 3 all deposit 1 1 10 1 region slab rigid 1\n", "cannot use fix deposit rigid and not molecule"),
        ("fix 1 all rigid/nve/small molecule mol tri\nfix 3 all deposit 1 0 10 1 region slab mol tri rigid 9\n", "fix deposit rigid fix ID 9 does not exist"),
        ("fix 1 all rigid/nve/small molecule mol other\nfix 3 all deposit 1 0 10 1 region slab mol tri rigid 1\n", "not using same molecule template ID"),
        ("fix 1 all nve\nfix 3 all deposit 1 0 10 1 region slab mol tri rigid 1\n", "is not a rigid/small fix"),
    ] {
        let deck = format!("{base}{fixes}run 10\n");
        let f = run_text("bad.deck", &deck, &opts).err().unwrap_or_else(|| panic!("accepted: {fixes}"));
        assert!(f.rendered.contains(want), "{fixes}: expected `{want}`:\n{}", f.rendered);
    }
}

/// compute ke/rigid and erotate/rigid name a rigid fix: another fix or none stops the run with
/// LAMMPS' reasons.
#[test]
fn rigid_energy_computes_need_a_rigid_fix() {
    for (cmd, want) in [("compute k all ke/rigid 9", "fix ID 9 for compute ke/rigid does not exist"), ("fix 3 all nve\ncompute k all erotate/rigid 3", "compute erotate/rigid with non-rigid fix-ID 3")] {
        let deck = format!("{BASE}{cmd}\nthermo_style custom step c_k\nrun 0\n");
        let f = run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {cmd}"));
        assert!(f.rendered.contains(want), "{cmd}: expected `{want}`:\n{}", f.rendered);
    }
}

/// rigid/npt/small's chains and box state travel through write_restart/read_restart: the
/// continued run prints LAMMPS 22 Jul 2025's rows for this deck (its log, 8 digits).
#[test]
fn rigid_barostat_restart_is_lammps() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("rnpt.restart");
    let fix = "fix 1 all rigid/npt/small molecule temp 1.5 1.5 0.05 x 0.2 0.2 0.5 y 0.2 0.2 0.5 z 0.1 0.1 0.5 couple xy tparam 4 1 3 pchain 3\n";
    let pair = "pair_style lj/cut 1.122462048309373\npair_coeff * * 1.0 0.9\nneigh_modify every 1 delay 0 check yes exclude molecule/intra all\n";
    let deck = format!(
        "units lj\natom_style angle\nboundary p p p\nread_data rigid_clumps.data\n{pair}neighbor 0.3 bin\n{fix}timestep 0.0005\nrun 200\nwrite_restart {f}\nclear\nread_restart {f}\n{pair}{fix}thermo_style custom step temp press vol f_1\nthermo 50\nrun 100\n",
        f = file.display()
    );
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(thermo_tables::root().join("lammps-refs/decks")), ..Default::default() };
    let run = run_text("in.restart", &deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let rows = table(run.sim.out.captured.as_deref().unwrap()).1;
    let lammps = [[200.0, 1.6843836, 0.074194793, 1320.6079, 6.753716], [250.0, 1.6832797, 0.044436864, 1320.4623, 6.6880978], [300.0, 1.6182764, 0.047026311, 1315.596, 6.6239891]];
    assert_eq!(rows.len(), lammps.len(), "{rows:?}");
    for (ours, theirs) in rows.iter().zip(&lammps) {
        for (a, b) in ours.iter().zip(theirs) {
            assert!((a - b).abs() <= 5e-8 * b.abs().max(1e-300), "{ours:?} against LAMMPS {theirs:?}");
        }
    }
}

/// A `velocity create` after fix rigid/small and before the first run counts no rigid degrees
/// of freedom (LAMMPS' FixRigidSmall::dof before its bodies are set up), so the velocities are
/// LAMMPS': the step-0 temperature, with the bodies' dof removed, is LAMMPS 22 Jul 2025's
/// 1.0179873874876 (its log of this deck, %.15g) and the kinetic energy 0.742282470043043.
#[test]
fn velocity_before_the_first_run_counts_no_rigid_dof() {
    let deck = "units lj\natom_style angle\nboundary p p p\nread_data rigid_clumps.data\npair_style lj/cut 1.122462048309373\npair_coeff * * 1.0 0.9\n\
                neighbor 0.3 bin\nneigh_modify every 1 delay 0 check yes exclude molecule/intra all\nfix 1 all rigid/small molecule\nvelocity all create 1.0 12345\n\
                timestep 0.0005\nthermo_style custom step temp ke\nthermo_modify format float %.15g\nrun 0\n";
    let opts = DeckOptions { screen: false, capture_text: true, base_dir: Some(thermo_tables::root().join("lammps-refs/decks")), ..Default::default() };
    let run = run_text("in.vel", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let rows = table(run.sim.out.captured.as_deref().unwrap()).1;
    assert_eq!(rows[0][1..], [1.0179873874876, 0.742282470043043], "{rows:?}");
}

/// `reinit no` keeps the first run's bodies: a `velocity` command between runs is undone by the
/// bodies' velocities at the next setup, where `reinit yes` (the default) takes the atoms' new
/// velocities into new bodies (LAMMPS' FixRigid::init).
#[test]
fn fix_rigid_reinit_no_keeps_the_bodies() {
    let ke = |reinit: &str| -> Vec<Vec<f64>> {
        let deck = BASE.replace("fix 1 all rigid/small molecule\n", &format!("fix 1 all rigid molecule{reinit}\n"));
        let deck = format!("{deck}thermo_style custom step ke\nthermo_modify format float %.17g\nthermo 10\nrun 10\nvelocity all set 0 0 0\nrun 10\n");
        let run = run_text("ok.deck", &deck, &DeckOptions { screen: false, capture_text: true, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
        table(run.sim.out.captured.as_deref().unwrap()).1
    };
    // the last table: the second run's steps 10 and 20 (the dimers move at 0.5 before it)
    let (yes, no) = (ke(""), ke(" reinit no"));
    assert_eq!(yes[0][1], 0.0, "reinit yes: the bodies take the atoms' zero velocities: {yes:?}");
    assert!(no[0][1] > 0.1, "reinit no: the bodies keep moving: {no:?}");
}

/// A fix rigid `infile` with a bad line is a located error naming the file's line.
#[test]
fn fix_rigid_infile_errors_name_the_line() {
    let dir = tempfile::tempdir().unwrap();
    for (text, want) in [
        ("# bodies\n\n1\n1 2.0 5 5 5 1 1 1 0 0 0 0 0 0 0 0\n", "bodies.txt:4: incorrect rigid body format"),
        ("2\n1 2.0 5 5 5 1 1 1 0 0 0 0 0 0 0 0 0 0 0 0\n", "unexpected end of fix rigid infile"),
        ("1\n7 2.0 5 5 5 1 1 1 0 0 0 0 0 0 0 0 0 0 0 0\n", "bodies.txt:2: invalid rigid body ID 7"),
        ("1\n1 2.0 5 5 five 1 1 1 0 0 0 0 0 0 0 0 0 0 0 0\n", "bodies.txt:2: expected a number, found `five`"),
        ("one\n", "bodies.txt:1: fix rigid infile has incorrect format"),
    ] {
        std::fs::write(dir.path().join("bodies.txt"), text).unwrap();
        let deck = format!("{BASE}fix 2 all rigid molecule infile bodies.txt\nrun 0\n");
        let opts = DeckOptions { base_dir: Some(dir.path().to_path_buf()), ..Default::default() };
        let f = run_text("bad.deck", &deck, &opts).err().unwrap_or_else(|| panic!("accepted: {text}"));
        let line = BASE.lines().count() + 1;
        assert!(f.rendered.contains(&format!("bad.deck:{line}:")) && f.rendered.contains(want), "expected `{want}`:\n{}", f.rendered);
    }
}

/// gmask(), rmask() and grmask() in atom-style variables (LAMMPS' special functions): the
/// dimers' atoms at x = 2, 3, 4.1, 5.1; the region holds the first two, the group the last two.
#[test]
fn mask_functions_pick_group_and_region_atoms() {
    let deck = format!(
        "{BASE}region left block 0 3.5 0 10 0 10 units box\ngroup right id 3 4\nvariable g atom gmask(right)\nvariable r atom rmask(left)\nvariable gr atom grmask(right,left)+grmask(all,left)\n\
group G variable g\ngroup R variable r\ngroup GR variable gr\nvariable n equal count(G)+10*count(R)+100*count(GR)\nthermo_style custom step v_n\nrun 0\n"
    );
    let run = run_text("ok.deck", &deck, &DeckOptions { screen: false, capture_text: true, ..Default::default() }).unwrap_or_else(|f| panic!("{}", f.rendered));
    let rows = table(run.sim.out.captured.as_deref().unwrap()).1;
    assert_eq!(rows[0][1], 222.0);
    let bad = format!("{BASE}variable g atom gmask(nogroup)\ngroup G variable g\n");
    let f = run_text("bad.deck", &bad, &Default::default()).err().expect("an unknown group is an error");
    assert!(f.rendered.contains("Group ID nogroup in variable formula does not exist"), "{}", f.rendered);
}
