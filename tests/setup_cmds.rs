//! Set-up commands beside their LAMMPS parity deck (lammps-refs/decks/in.setup_cmds, compared
//! in tests/lammps_parity.rs): the boxes LAMMPS prints for its change_box lines, and located
//! errors for what LAMMPS (or dmhs) refuses in displace_atoms, change_box, run_style, fix freeze
//! and the per-atom energy computes.

use std::path::PathBuf;
use std::process::Command;

fn base() -> String {
    std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks/in.setup_cmds")).unwrap()
}

/// `dmhs check` on `deck` (written as in.sc): exit code and output.
fn check(deck: &str) -> (i32, String) {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("in.sc");
    std::fs::write(&path, deck).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).arg("check").arg(&path).current_dir(tmp.path()).output().unwrap();
    (o.status.code().unwrap_or(-1), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

#[test]
fn change_box_prints_the_boxes_lammps_prints() {
    // LAMMPS 22 Jul 2025 prints these four boxes for the deck's two change_box commands
    let (code, out) = check(&base());
    assert_eq!(code, 0, "{out}");
    for line in [
        "  orthogonal box = (-0.5 0 0) to (3.9943219 3.4943219 3.4943219)",
        "  orthogonal box = (-0.5 -0.17471609 0) to (3.9943219 3.669038 3.4943219)",
        "  orthogonal box = (0 -0.17471609 0) to (5.678273 3.669038 3.4943219)",
        "  orthogonal box = (0 -0.17471609 -0.43679023) to (5.678273 3.669038 5.4161989)",
    ] {
        assert!(out.contains(line), "missing `{line}`:\n{out}");
    }
}

#[test]
fn setup_command_errors_are_located() {
    let rot = "displace_atoms top rotate 3 3 3 1 1 0.5 33 units box";
    let cb = "change_box all x delta -0.5 0.5 y scale 1.1 remap units box";
    for (from, to, want) in [
        ("run_style verlet", "run_style respa 2 2", "dmhs has one integrator"),
        ("run_style verlet", "run_style verlet 2", "unexpected argument `2`"),
        (rot, "displace_atoms top rotate 3 3 3 0 0 0 33 units box", "zero length rotation vector"),
        (rot, "displace_atoms top spin 3 3 3 1 1 0.5 33", "displacement style"),
        (rot, "displace_atoms top rotate 3 3 3 1 1", "needs 7 arguments"),
        (rot, "displace_atoms top rotate 3 3 3 1 1 0.5 33 units cubits", "units"),
        ("displace_atoms all random 0.1 0.1 0.1 12345", "displace_atoms all random 0.1 0.1 0.1 0", "seed"),
        ("variable mx equal 0.03", "variable mx string 0.03", "Variable for displace_atoms is invalid style"),
        ("move v_mx v_my", "move v_nope v_my", "Variable name for displace_atoms does not exist: v_nope"),
        ("move v_mx v_my 0.01", "move v_mx v_my dz", "expected a number for dz"),
        (cb, "change_box all xy final 1", "Cannot change box tilt factors for orthogonal box"),
        (cb, "change_box all x volume", "volume is not supported"),
        (cb, "change_box all x delta -0.5 0.5 remap wobble", "unknown keyword `wobble`"),
        (cb, "change_box all x final 2 1", "empty or inverted"),
        (cb, "change_box nogroup x final 0 1", "group `nogroup` does not exist"),
        (cb, "change_box all boundary p p pf", "both faces must be periodic or neither"),
        ("fix fr low freeze", "fix fr low freeze now", "unexpected argument `now`"),
        ("compute ke all ke/atom", "compute ke all ke/atom 2", "ke/atom"),
        ("atom_style sphere", "atom_style atomic\nmass * 1.0", "requires atom style sphere"),
        ("compute ke all ke/atom", "compute ke all ke/atom\nmass 1 1.0", "Cannot set per-type atom mass for atom style sphere"),
    ] {
        let deck = base().replacen(from, to, 1);
        assert_ne!(deck, base(), "{from}");
        let (code, out) = check(&deck);
        assert_eq!(code, 2, "{to}: {out}");
        assert!(out.contains(want) && out.contains("in.sc:"), "{to}: expected `{want}`:\n{out}");
    }
}

#[test]
fn two_freeze_fixes_are_refused_at_run() {
    let deck = base().replace("fix fr low freeze", "fix fr low freeze\nfix fr2 top freeze");
    let (code, out) = check(&deck);
    assert_ne!(code, 0, "{out}");
    assert!(out.contains("more than one fix freeze"), "{out}");
}

#[test]
fn displace_atoms_move_in_2d_ignores_the_z_word() {
    // LAMMPS 22 Jul 2025 neither reads nor applies move's dz in 2d (x stays in the plane at z = 0)
    let deck = "dimension 2\nboundary p p p\nregion box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 single 1 1 0\nmass 1 1\n\
                variable a atom x\ndisplace_atoms all move 2 v_a v_nope units box\ndisplace_atoms all move 0 0 3 units box\n\
                write_dump all custom out.dump id x y z modify format float %g\n";
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("in.2d"), deck).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).args(["-in", "in.2d", "-log", "none"]).current_dir(tmp.path()).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let dump = std::fs::read_to_string(tmp.path().join("out.dump")).unwrap();
    // y moved by the x that x's move left (3), as LAMMPS
    assert_eq!(dump.lines().last().unwrap(), "1 3 4 0", "{dump}");
}

/// `clear` starts a new simulation inside the deck, as LAMMPS': the variables stay, the units,
/// box, atoms, groups and fixes are gone (the same IDs can be defined again). The printed lines
/// are LAMMPS 22 Jul 2025's for this deck.
#[test]
fn clear_keeps_only_the_variables() {
    let deck = "variable a equal 2.5\nunits si\nregion b block 0 4 0 4 0 4\ncreate_box 1 b\ncreate_atoms 1 single 1 1 1\nmass 1 1.0\ngroup g id 1\nfix 1 all nve\n\
                clear\nprint \"a=${a}\"\nregion b block 0 2 0 2 0 2\ncreate_box 1 b\nprint \"atoms=$(atoms) dt=$(dt)\"\nfix 1 all nve\ngroup g id 1\nprint \"count=$(count(g))\"\n";
    let opts = dmhs::deck::DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = dmhs::deck::run_text("in.clear", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    let text = run.sim.out.captured.clone().unwrap();
    let printed: Vec<&str> = text.lines().filter(|l| l.starts_with("a=") || l.starts_with("atoms=") || l.starts_with("count=")).collect();
    assert_eq!(printed, ["a=2.5", "atoms=0 dt=0.0050000000000000001041", "count=0"], "{text}");
    let bad = dmhs::deck::run_text("in.bad", "clear now\n", &Default::default()).err().expect("an error");
    assert!(bad.rendered.contains("in.bad:1"), "{}", bad.rendered);
}
