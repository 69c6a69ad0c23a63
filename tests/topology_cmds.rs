//! create_bonds beside its LAMMPS parity deck (lammps-refs/decks/in.create_bonds, compared in
//! tests/lammps_parity.rs): the bond count LAMMPS prints for it, and located errors for what
//! LAMMPS refuses.

use std::path::PathBuf;
use std::process::Command;

fn base() -> String {
    std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lammps-refs/decks/in.create_bonds")).unwrap()
}

/// `dmhs check` on `deck` (written as in.cb): exit code and output.
fn check(deck: &str) -> (i32, String) {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("in.cb");
    std::fs::write(&path, deck).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).arg("check").arg(&path).current_dir(tmp.path()).output().unwrap();
    (o.status.code().unwrap_or(-1), format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr)))
}

#[test]
fn many_adds_the_bonds_lammps_adds() {
    // LAMMPS 22 Jul 2025 prints "Added 40 bonds, new total = 40" for this deck's create_bonds many
    // (a 5 x 5 patch: 2 x 5 x 4 nearest-neighbour pairs)
    let (code, out) = check(&base());
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("Added 40 bonds, new total = 40"), "{out}");
}

#[test]
fn many_can_be_repeated_without_doubling_bonds() {
    // bonded pairs are not in the neighbour list (1-2 weight 0), so a second many adds none
    let deck = base().replace("create_bonds many patch patch 1 0.0 1.2\n", "create_bonds many patch patch 1 0.0 1.2\ncreate_bonds many patch patch 1 0.0 1.2\n");
    let (code, out) = check(&deck);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("Added 0 bonds, new total = 40"), "{out}");
}

#[test]
fn create_bonds_errors_are_located() {
    let many = "create_bonds many patch patch 1 0.0 1.2";
    for (from, to, want) in [
        (many, "create_bonds many patch nogroup 1 0.0 1.2", "group `nogroup` does not exist"),
        (many, "create_bonds many patch patch 3 0.0 1.2", "bond type must be in 1..=2"),
        (many, "create_bonds many patch patch 1 1.2 1.0", "rmin 1.2 is larger than rmax 1"),
        (many, "create_bonds many patch patch 1 0.0 3.5", "larger than the neighbour cutoff 2.8"),
        (many, "create_bonds many patch patch 1 0.0 1.2 special no", "special yes"),
        (many, "create_bonds lots patch patch 1 0.0 1.2", "unknown keyword `lots`"),
        ("special_bonds lj 0.0 1.0 1.0", "special_bonds lj 0.5 1.0 1.0", "1-2 weights of 0.0"),
        ("create_bonds single/bond 2 1 2", "create_bonds single/bond 2 1 1000", "atom 1000 does not exist"),
        ("create_bonds single/angle 1 1 2 3", "create_bonds single/angle 1 1 2 2", "atom 2 appears twice"),
        ("create_bonds single/angle 1 1 2 3", "create_bonds single/dihedral 1 1 2 3 4", "no dihedral types are defined"),
    ] {
        let deck = base().replace(from, to);
        assert_ne!(deck, base(), "{from}");
        let (code, out) = check(&deck);
        assert_eq!(code, 2, "{to}: {out}");
        assert!(out.contains(want) && out.contains("in.cb:"), "{to}: expected `{want}`:\n{out}");
    }
}

/// bond_style zero as LAMMPS 22 Jul 2025: bonds without force or energy, r0 reported by
/// write_data (`1 1.5`, `2 0` for this deck), extra coefficient words refused unless `nocoeff`;
/// write_data with a type left without coefficients is LAMMPS' error.
#[test]
fn bond_style_zero_is_lammps() {
    let deck = "units lj\natom_style bond\nregion box block 0 5 0 5 0 5\ncreate_box 1 box bond/types 2 extra/bond/per/atom 2\n\
                create_atoms 1 single 1 1 1\ncreate_atoms 1 single 2 1 1\ncreate_atoms 1 single 3 1.2 1\nmass 1 1.0\n\
                bond_style zero\nbond_coeff 1 1.5\nbond_coeff 2\ncreate_bonds single/bond 1 1 2\ncreate_bonds single/bond 2 2 3\n\
                pair_style zero 2.5\npair_coeff * *\nvelocity all create 1.0 1234\nfix 1 all nve\n\
                thermo_style custom step ebond\nrun 10\nwrite_data out.data\n";
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("in.bz"), deck).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_dmhs")).args(["-in", "in.bz", "-log", "none"]).current_dir(tmp.path()).output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.lines().any(|l| l.split_whitespace().collect::<Vec<_>>() == ["10", "0"]), "{out}");
    let data = std::fs::read_to_string(tmp.path().join("out.data")).unwrap();
    assert!(data.contains("Bond Coeffs # zero\n\n1 1.5\n2 0\n"), "{data}");
    for (from, to, code, want) in [
        ("bond_coeff 1 1.5\n", "bond_coeff 1 1.5 2\n", 2, "unexpected argument `2`"),
        ("bond_style zero\n", "bond_style zero wobble\n", 2, "wobble"),
        // write_data checks the coefficients as LAMMPS' init does (it panicked on the unset type)
        ("bond_coeff 2\n", "", 2, "All bond coeffs are not set (missing for type 2)"),
        ("bond_style zero\nbond_coeff 1 1.5\n", "bond_style zero nocoeff\nbond_coeff 1 1.5 2 3\n", 0, ""),
    ] {
        let (c, text) = check(&deck.replace(from, to));
        assert_eq!(c, code, "{to}: {text}");
        assert!(text.contains(want) && (code == 0 || text.contains("in.cb:")), "{to}: {text}");
    }
}
