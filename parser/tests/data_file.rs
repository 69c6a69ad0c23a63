//! Data files: column layouts, reading the files LAMMPS' own write_data wrote (tests/data/, made
//! by tests/data/generate.py with LAMMPS 22 Jul 2025), writing them back byte for byte, and
//! located errors for broken files.

use dmhs_parser::data_file::*;
use dmhs_parser::{Diagnostic, SourceMap};
use std::path::PathBuf;

fn data_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn layout(names: &str) -> AtomLayout {
    AtomLayout::from_names(&names.split_whitespace().collect::<Vec<_>>()).unwrap()
}

fn cols(cs: &[Column]) -> String {
    cs.iter().map(|c| c.name()).collect::<Vec<_>>().join(" ")
}

/// Parse a file from tests/data; panics with rendered diagnostics on error.
fn parse_file(name: &str, style: &str) -> (DataFile, String) {
    let text = std::fs::read_to_string(data_path(name)).unwrap();
    let mut sm = SourceMap::new();
    let id = sm.add(name, text.clone());
    match parse_data_file(&text, id, &layout(style)) {
        Ok(df) => (df, text),
        Err(es) => panic!("{}", es.iter().map(|e| e.render(&sm)).collect::<String>()),
    }
}

/// Parse text that must fail; returns the rendered diagnostics.
fn errors(text: &str, style: &str) -> (Vec<Diagnostic>, String) {
    let mut sm = SourceMap::new();
    let id = sm.add("bad.data", text);
    match parse_data_file(text, id, &layout(style)) {
        Ok(_) => panic!("expected errors for:\n{text}"),
        Err(es) => {
            let r = es.iter().map(|e| e.render(&sm)).collect::<String>();
            (es, r)
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Layouts (column orders observed in LAMMPS 22 Jul 2025 write_data output)
// ---------------------------------------------------------------------------------------------

#[test]
fn layouts_match_lammps_column_order() {
    let cases = [
        ("atomic", "atom-ID atom-type x y z", "atom-ID vx vy vz"),
        ("charge", "atom-ID atom-type q x y z", "atom-ID vx vy vz"),
        ("bond", "atom-ID molecule-ID atom-type x y z", "atom-ID vx vy vz"),
        ("angle", "atom-ID molecule-ID atom-type x y z", "atom-ID vx vy vz"),
        ("molecular", "atom-ID molecule-ID atom-type x y z", "atom-ID vx vy vz"),
        ("full", "atom-ID molecule-ID atom-type q x y z", "atom-ID vx vy vz"),
        ("sphere", "atom-ID atom-type diameter density x y z", "atom-ID vx vy vz wx wy wz"),
        ("sphere 1", "atom-ID atom-type diameter density x y z", "atom-ID vx vy vz wx wy wz"),
        ("bpm/sphere", "atom-ID molecule-ID atom-type diameter density x y z", "atom-ID vx vy vz wx wy wz"),
        ("sph", "atom-ID atom-type rho esph cv x y z", "atom-ID vx vy vz"),
        (
            "hybrid sph sphere angle",
            "atom-ID atom-type x y z rho esph cv diameter density molecule-ID",
            "atom-ID vx vy vz wx wy wz",
        ),
        ("hybrid full sphere", "atom-ID atom-type x y z molecule-ID q diameter density", "atom-ID vx vy vz wx wy wz"),
        ("hybrid sphere full", "atom-ID atom-type x y z diameter density molecule-ID q", "atom-ID vx vy vz wx wy wz"),
        ("hybrid charge sph", "atom-ID atom-type x y z q rho esph cv", "atom-ID vx vy vz"),
        ("hybrid bond angle", "atom-ID atom-type x y z molecule-ID", "atom-ID vx vy vz"),
        ("hybrid sphere 1 sph", "atom-ID atom-type x y z diameter density rho esph cv", "atom-ID vx vy vz wx wy wz"),
    ];
    for (style, atoms, vels) in cases {
        let l = layout(style);
        assert_eq!(cols(&l.atoms), atoms, "{style}");
        assert_eq!(cols(&l.velocities), vels, "{style}");
    }
    let full = layout("full");
    assert_eq!(
        full.atoms_help(),
        "Atoms line for atom_style full is: atom-ID molecule-ID atom-type q x y z [ix iy iz]"
    );
    assert!(full.bonds && full.angles && full.dihedrals && full.impropers && full.per_type_mass);
    let h = layout("hybrid sph sphere angle");
    assert_eq!(h.style, "hybrid");
    assert_eq!(h.style_label(), "hybrid sph sphere angle");
    assert!(h.bonds && h.angles && !h.dihedrals && h.per_type_mass && h.per_atom_mass);
    let s = layout("sphere");
    assert!(!s.per_type_mass && s.per_atom_mass && !s.bonds);
    assert!(layout("bpm/sphere").bonds && !layout("bpm/sphere").angles);
}

#[test]
fn bad_atom_styles_are_located_errors() {
    let err = |s: &str| AtomLayout::from_names(&s.split_whitespace().collect::<Vec<_>>()).unwrap_err();
    let e = err("spher");
    assert_eq!(e.message, "unknown atom style `spher`");
    assert_eq!(e.help[0], "did you mean `sphere`?");
    assert!(err("dipole").message.contains("dmhs does not support"));
    assert!(err("hybrid sphere sphere").message.contains("twice"));
    assert!(err("hybrid sph hybrid").message.contains("hybrid as a sub-style"));
    assert!(err("sphere 2").message.contains("expected 0 or 1"));
    assert!(err("atomic 1").message.contains("unexpected argument `1` for atom_style atomic"));
    assert!(err("hybrid sph 1").message.contains("unexpected argument `1` for atom_style sph"));
    assert!(err("full sphere").message.contains("unexpected argument"));
    assert!(AtomLayout::from_names(&[]).is_err());
    // plain `hybrid` is id type x y z, as in LAMMPS
    assert_eq!(cols(&layout("hybrid").atoms), "atom-ID atom-type x y z");
}

// ---------------------------------------------------------------------------------------------
// Files written by LAMMPS' write_data
// ---------------------------------------------------------------------------------------------

/// Compares parsed atoms and velocities with the bit patterns LAMMPS held in memory.
fn check_expect(df: &DataFile, name: &str) {
    let text = std::fs::read_to_string(data_path(name)).unwrap();
    let vels = df.velocities.as_ref().expect("velocities");
    let mut n = 0;
    for line in text.lines() {
        let v: Vec<u64> = line.split_whitespace().map(|w| w.parse().unwrap()).collect();
        let id = v[0] as i64;
        let a = df.atoms.iter().find(|a| a.id == id).unwrap_or_else(|| panic!("{name}: atom {id} missing"));
        assert_eq!(a.atom_type as u64, v[1], "{name}: type of atom {id}");
        for d in 0..3 {
            assert_eq!(a.x[d].to_bits(), v[2 + d], "{name}: x[{d}] of atom {id}");
        }
        let vel = vels.iter().find(|x| x.id == id).unwrap();
        for d in 0..3 {
            assert_eq!(vel.v[d].to_bits(), v[5 + d], "{name}: v[{d}] of atom {id}");
        }
        n += 1;
    }
    assert_eq!(n, df.atoms.len());
}

#[test]
fn reads_lammps_atomic_file() {
    let (df, _) = parse_file("lmp_atomic.data", "atomic");
    assert_eq!(df.title, "LAMMPS data file via write_data, version 22 Jul 2025, timestep = 37, units = lj");
    assert_eq!((df.header.atoms, df.header.atom_types), (32, 2));
    assert_eq!(df.header.boxlo, [0.0; 3]);
    assert_eq!(df.header.boxhi, [3.3591923827650145; 3]);
    assert_eq!(df.masses.iter().map(|m| (m.atom_type, m.mass)).collect::<Vec<_>>(), vec![(1, 1.0), (2, 2.5)]);
    assert_eq!(df.coeffs.len(), 1);
    let pc = &df.coeffs[0];
    assert_eq!(pc.kind, CoeffKind::Pair);
    assert_eq!(pc.style.as_ref().unwrap().text, "lj/cut");
    let args: Vec<Vec<String>> =
        pc.lines.iter().map(|l| l.command_args(pc.kind).into_iter().map(|w| w.text).collect()).collect();
    assert_eq!(args, vec![vec!["1", "1", "1", "1"], vec!["2", "2", "1.2", "1.1"]]);
    assert!(df.image_flags);
    assert!(df.atoms.iter().any(|a| a.image != [0, 0, 0]), "the run moved some atoms across the box");
    check_expect(&df, "lmp_atomic.expect");
    assert!(df.warnings.is_empty(), "{:?}", df.warnings);
}

#[test]
fn reads_lammps_triclinic_file() {
    let (df, _) = parse_file("lmp_triclinic.data", "atomic");
    assert_eq!(df.header.tilt, Some([2.025, 1.0125, -3.0374999999999996]));
    assert_eq!(df.header.boxhi, [12.149999999999999; 3]);
    assert_eq!(df.atoms.len(), 108);
    check_expect(&df, "lmp_triclinic.expect");
}

#[test]
fn reads_lammps_full_file_with_labels_and_topology() {
    let (df, _) = parse_file("lmp_full.data", "full");
    let h = &df.header;
    assert_eq!((h.atoms, h.bonds, h.angles, h.dihedrals, h.impropers), (5, 4, 1, 1, 1));
    assert_eq!((h.atom_types, h.bond_types, h.angle_types, h.dihedral_types, h.improper_types), (3, 2, 1, 1, 1));
    let labels: Vec<&str> = df.type_labels.of(TypeKind::Atom).iter().map(|w| w.text.as_str()).collect();
    assert_eq!(labels, ["C", "H", "O"]);
    assert_eq!(df.type_labels.find(TypeKind::Bond, "C-O"), Some(2));
    let a4 = df.atoms.iter().find(|a| a.id == 4).unwrap();
    assert_eq!((a4.molecule, a4.atom_type, a4.q), (1, 3, -0.34));
    let kinds: Vec<(CoeffKind, &str)> =
        df.coeffs.iter().map(|c| (c.kind, c.style.as_ref().unwrap().text.as_str())).collect();
    assert_eq!(
        kinds,
        [
            (CoeffKind::Pair, "lj/cut/coul/cut"),
            (CoeffKind::Bond, "harmonic"),
            (CoeffKind::Angle, "harmonic"),
            (CoeffKind::Dihedral, "harmonic"),
            (CoeffKind::Improper, "harmonic")
        ]
    );
    let dih = &df.coeffs[3].lines[0];
    assert_eq!(dih.types, [1]);
    assert_eq!(dih.args.iter().map(|w| w.text.as_str()).collect::<Vec<_>>(), ["0.3", "1", "3"]);
    assert_eq!(
        df.bonds.iter().map(|b| (b.topo_type, b.atoms)).collect::<Vec<_>>(),
        [(1, [1, 2]), (1, [1, 3]), (2, [1, 4]), (1, [1, 5])]
    );
    assert_eq!((df.angles[0].topo_type, df.angles[0].atoms), (1, [2, 1, 3]));
    assert_eq!(df.dihedrals[0].atoms, [2, 1, 4, 5]);
    assert_eq!(df.impropers[0].atoms, [1, 2, 3, 4]);
    assert_eq!(df.atoms_style_hint.as_ref().unwrap().text, "full");
    check_expect(&df, "lmp_full.expect");
}

#[test]
fn reads_lammps_sphere_sph_and_hybrid_files() {
    let (df, _) = parse_file("lmp_sphere.data", "sphere");
    assert!(df.masses.is_empty());
    let a2 = df.atoms.iter().find(|a| a.id == 2).unwrap();
    assert_eq!((a2.diameter, a2.density), (0.012, 1100.0));
    assert_eq!(df.velocities.as_ref().unwrap()[0].omega, [0.0, 0.0, 3.0]);
    check_expect(&df, "lmp_sphere.expect");

    let (df, _) = parse_file("lmp_sph.data", "sph");
    assert_eq!(df.atoms.len(), 100);
    assert!(df.atoms.iter().all(|a| a.esph == 4.5 && a.cv == 4186.0 && (a.rho - 1000.0).abs() < 1e-6));
    check_expect(&df, "lmp_sph.expect");

    let (df, _) = parse_file("lmp_hybrid.data", "hybrid sph sphere angle");
    let a2 = df.atoms.iter().find(|a| a.id == 2).unwrap();
    assert_eq!(
        (a2.rho, a2.esph, a2.cv, a2.diameter, a2.density, a2.molecule),
        (1001.5, 2.0, 1.0, 0.001, 999.9999999999999, 3)
    );
    assert_eq!(df.velocities.as_ref().unwrap()[1].omega, [0.0, 0.0, 1.5]);
    assert_eq!(df.bonds.len(), 2);
    assert_eq!(df.angles[0].atoms, [1, 2, 3]);
    // `Pair Coeffs # zero` lines are a type alone
    assert_eq!(
        df.coeffs[0].lines[1].command_args(CoeffKind::Pair).iter().map(|w| w.text.clone()).collect::<Vec<_>>(),
        ["2", "2"]
    );
    check_expect(&df, "lmp_hybrid.expect");
}

#[test]
fn writes_lammps_files_back_byte_for_byte() {
    for (name, style) in [
        ("lmp_atomic.data", "atomic"),
        ("lmp_triclinic.data", "atomic"),
        ("lmp_full.data", "full"),
        ("lmp_sphere.data", "sphere"),
        ("lmp_sph.data", "sph"),
        ("lmp_hybrid.data", "hybrid sph sphere angle"),
    ] {
        let (df, text) = parse_file(name, style);
        let out = df.write(&layout(style));
        // identical text, except where LAMMPS wrote a per-atom scalar with 16 digits ({:.16})
        // and the shortest round-trip form is shorter: the numbers must then be the same double
        if out != text {
            for (k, (a, b)) in out.lines().zip(text.lines()).enumerate() {
                if a == b {
                    continue;
                }
                let (wa, wb): (Vec<&str>, Vec<&str>) = (a.split(' ').collect(), b.split(' ').collect());
                assert_eq!(wa.len(), wb.len(), "{name}: line {}: {a} | {b}", k + 1);
                for (x, y) in wa.iter().zip(&wb) {
                    if x != y {
                        let (fx, fy) = (x.parse::<f64>().unwrap(), y.parse::<f64>().unwrap());
                        assert_eq!(fx.to_bits(), fy.to_bits(), "{name}: line {}: {x} vs {y}", k + 1);
                        assert!(x.len() < y.len(), "{name}: line {}: {x} vs {y}", k + 1);
                    }
                }
            }
            assert_eq!(out.lines().count(), text.lines().count(), "{name}");
        }
    }
}

#[test]
fn written_file_reads_back_to_the_same_values() {
    let l = layout("hybrid sph sphere angle");
    let mut df = DataFile { title: write_data_title("dmhs test", 42, "si"), ..Default::default() };
    df.header.atom_types = 2;
    df.header.bond_types = 1;
    df.header.angle_types = 1;
    df.header.boxlo = [-1.0 / 3.0, 0.0, -0.5];
    df.header.boxhi = [2.0 / 3.0, 1e-3, 0.5];
    df.masses = vec![MassLine::new(1, 0.1 + 0.2), MassLine::new(2, 1e-20)];
    df.coeffs.push(CoeffSection {
        kind: CoeffKind::Bond,
        style: Some(dmhs_parser::Word::new("harmonic", Default::default())),
        lines: vec![CoeffLine::new(vec![1], &["100.0", "0.001"])],
        span: Default::default(),
    });
    let mut vels = vec![];
    for i in 1..=3 {
        let mut a = AtomLine::new(i, 1 + (i as usize % 2), [0.1 * i as f64, 1e-5 / i as f64, -0.0]);
        a.rho = 1000.0 + 1.0 / i as f64;
        a.esph = 1e-7 * i as f64;
        a.cv = 4186.0;
        a.diameter = 1e-3 / 3.0;
        a.density = 2500.0;
        a.molecule = 7;
        a.image = [i as i32 - 2, 0, 1];
        df.atoms.push(a);
        vels.push(VelocityLine::new(i, [1.0 / 7.0, -2e-300, 0.0], [0.0, 0.0, 1.0 / 3.0]));
    }
    df.velocities = Some(vels);
    df.bonds = vec![BondLine::new(1, [1, 2]), BondLine::new(1, [2, 3])];
    df.angles = vec![AngleLine::new(1, [1, 2, 3])];
    df.image_flags = true;
    let text = df.write(&l);
    assert!(text.starts_with("LAMMPS data file via write_data, version dmhs test, timestep = 42, units = si\n\n3 atoms\n2 atom types\n2 bonds\n1 bond types\n1 angles\n1 angle types\n\n-0.3333333333333333 0.6666666666666666 xlo xhi\n"), "{text}");
    assert!(text.contains("\nMasses\n\n1 0.30000000000000004\n2 1e-20\n\nBond Coeffs # harmonic\n\n1 100.0 0.001\n\nAtoms # hybrid\n\n1 2 0.1 1e-05 -0 1001 1e-07 4186 0.0003333333333333333 2500 7 -1 0 1\n"), "{text}");
    assert!(text.contains("\nVelocities\n\n1 0.14285714285714285 -2e-300 0 0 0 0.3333333333333333\n"), "{text}");
    assert!(text.ends_with("\nBonds\n\n1 1 1 2\n2 1 2 3\n\nAngles\n\n1 1 1 2 3\n"), "{text}");
    let back = parse_data_file(&text, Default::default(), &l).unwrap();
    for (a, b) in back.atoms.iter().zip(&df.atoms) {
        for c in &l.atoms {
            assert_eq!(a.get(*c).unwrap().to_bits(), b.get(*c).unwrap().to_bits(), "{c:?}");
        }
        assert_eq!(a.image, b.image);
    }
    assert_eq!(
        back.velocities.as_ref().unwrap().iter().map(|v| (v.id, v.v, v.omega)).collect::<Vec<_>>(),
        df.velocities.as_ref().unwrap().iter().map(|v| (v.id, v.v, v.omega)).collect::<Vec<_>>()
    );
    assert_eq!(back.header.boxlo, df.header.boxlo);
    assert_eq!(back.masses[0].mass, 0.1 + 0.2);
}

// ---------------------------------------------------------------------------------------------
// Errors (each one is something real LAMMPS 22 Jul 2025 rejects, unless noted)
// ---------------------------------------------------------------------------------------------

const FULL: &str = "title
3 atoms
2 atom types
2 bonds
1 bond types
0 4 xlo xhi
0 4 ylo yhi
0 4 zlo zhi

Masses

1 1.0
2 2.0

Atoms # full

1 1 1 0.0 0.5 0.5 0.5
2 1 2 0.0 1.5 0.5 0.5
3 1 1 0.0 2.5 0.5 0.5

Bonds

1 1 1 2
2 1 2 3
";

#[test]
fn the_base_file_is_valid() {
    let df = parse_data_file(FULL, Default::default(), &layout("full")).unwrap();
    assert_eq!(df.atoms.len(), 3);
    assert!(!df.image_flags);
    assert_eq!(df.bonds[1].atoms, [2, 3]);
}

#[test]
fn several_line_errors_are_reported_at_once() {
    let text = FULL
        .replace("2 1 2 0.0 1.5", "2 1 2 abc 1.5")
        .replace("3 1 1 0.0 2.5 0.5 0.5", "3 1 3 0.0 2.5 0.5")
        .replace("1 1 1 2\n", "1 1 1 1\n");
    let (es, r) = errors(&text, "full");
    assert_eq!(es.len(), 3, "{r}");
    assert!(r.contains("error: expected a number for q, found `abc`"), "{r}");
    assert!(r.contains("--> bad.data:18:7"), "{r}");
    assert!(
        r.contains("= help: Atoms line for atom_style full is: atom-ID molecule-ID atom-type q x y z [ix iy iz]"),
        "{r}"
    );
    assert!(
        r.contains("error: expected 7 values (or 10 with image flags) in this Atoms line, found 6")
            || r.contains("expected 7 values in this Atoms line"),
        "{r}"
    );
    assert!(r.contains("atom 1 appears twice in this Bonds line"), "{r}");
}

#[test]
fn image_flags_must_be_on_every_line_or_none() {
    let (_, r) = errors(&FULL.replace("1 1 1 0.0 0.5 0.5 0.5", "1 1 1 0.0 0.5 0.5 0.5 0 0 0"), "full");
    assert!(r.contains("expected 10 values in this Atoms line (as in the first Atoms line), found 7"), "{r}");
    let df =
        parse_data_file(&FULL.replace(" 0.5 0.5\n", " 0.5 0.5 1 -1 0\n"), Default::default(), &layout("full")).unwrap();
    assert!(df.image_flags && df.atoms.iter().all(|a| a.image == [1, -1, 0]));
}

#[test]
fn counts_that_do_not_match_the_header() {
    let (_, r) = errors(&FULL.replace("3 atoms", "4 atoms"), "full");
    assert!(r.contains("error: the Atoms section has 3 lines but the header says 4 atoms"), "{r}");
    assert!(r.contains("the header's count"), "{r}");
    let (_, r) = errors(&FULL.replace("3 atoms", "2 atoms"), "full");
    assert!(r.contains("the Atoms section has more lines than the header says (2 atoms)"), "{r}");
    let (_, r) = errors(&FULL.replace("2 bonds", "3 bonds"), "full");
    assert!(r.contains("the Bonds section has 2 lines but the header says 3 bonds"), "{r}");
    let (_, r) = errors(&FULL.replace("Bonds\n\n1 1 1 2\n2 1 2 3\n", ""), "full");
    assert!(r.contains("Bonds section for 2 bonds not found"), "{r}");
    let (_, r) = errors(&FULL.replace("2 1 2 0.0", "\n2 1 2 0.0"), "full");
    assert!(r.contains("blank or comment line inside the Atoms section"), "{r}");
}

#[test]
fn unknown_sections_and_header_lines_get_suggestions() {
    let (_, r) = errors(&FULL.replace("Masses", "Mases"), "full");
    assert!(r.contains("unknown section `Mases` in data file") && r.contains("did you mean `Masses`?"), "{r}");
    let (es, r) = errors(&FULL.replace("3 atoms", "3 atom").replace("2 atom types", "2.0 atom types"), "full");
    assert!(r.contains("unknown header line `3 atom`") && r.contains("did you mean `atoms`?"), "{r}");
    assert!(r.contains("expected a non-negative integer count, found `2.0`"), "{r}");
    assert!(es.len() >= 2);
    let (_, r) = errors(&FULL.replace("Atoms # full\n\n", "Atoms # full\n"), "full");
    assert!(r.contains("expected a blank line after `Atoms`"), "{r}");
}

#[test]
fn box_errors() {
    let (_, r) = errors(&FULL.replace("0 4 xlo xhi\n", ""), "full");
    assert!(r.contains("no `xlo xhi` line"), "{r}");
    let (_, r) = errors(&FULL.replace("0 4 ylo yhi", "4 0 ylo yhi"), "full");
    assert!(r.contains("box bounds are invalid: ylo 4 must be below yhi 0"), "{r}");
    let df = parse_data_file(&FULL.replace("0 4 zlo zhi\n", ""), Default::default(), &layout("full")).unwrap();
    assert_eq!((df.header.boxlo[2], df.header.boxhi[2]), (-0.5, 0.5));
    assert_eq!(df.warnings.len(), 1);
    let (_, r) = errors(&FULL.replace("0 4 ylo yhi", "0 4y ylo yhi").replace("0 4 xlo xhi", "x0 4 xlo xhi"), "full");
    assert!(r.contains("expected a number for the box, found `4y`") && r.contains("found `x0`"), "{r}");
    let (_, r) = errors(&FULL.replace("0 4 zlo zhi", "0 4 zlo zhi\n1 0 0 avec"), "full");
    assert!(r.contains("general triclinic"), "{r}");
}

#[test]
fn values_lammps_rejects() {
    let cases = [
        (FULL.replace("3 1 1 0.0", "0 1 1 0.0"), "invalid atom ID 0"),
        (FULL.replace("3 1 1 0.0", "2 1 1 0.0"), "duplicate atom ID 2"),
        (FULL.replace("3 1 1 0.0", "3 1 1.0 0.0"), "expected an atom type, found `1.0`"),
        (FULL.replace("3 1 1 0.0 2.5", "3 1 1 0.0 2.5x"), "expected a number for x, found `2.5x`"),
        (FULL.replace("3 1 1 0.0 2.5", "3 1 1 0.0 1e400"), "expected a number for x, found `1e400`"),
        (FULL.replace("2 2.0", "2 0.0"), "invalid mass 0.0: must be > 0"),
        (FULL.replace("2 2.0", "2 2.0 5"), "expected 2 values in this Masses line, found 3"),
        (FULL.replace("2 1 2 3\n", "2 2 2 3\n"), "bond type 2 is out of range: the header says 1 bond types"),
        (FULL.replace("2 1 2 3\n", "2 1 2 5\n"), "no atom has ID 5"),
        (FULL.replace("2 1 2 3\n", "2 1 2 3 4\n"), "expected 4 values in this Bonds line, found 5"),
        (
            FULL.replace("Masses\n\n1 1.0\n2 2.0\n\n", "") + "\nVelocities\n\n1 1 2 3\n2 1 2 3\n4 1 2 3\n",
            "invalid atom ID 4 in the Velocities section",
        ),
        (
            FULL.replace("Masses", "Velocities\n\n1 1 2 3\n2 1 2 3\n3 1 2 3\n\nMasses"),
            "the Velocities section comes before the Atoms section",
        ),
        (FULL.replace("2 bonds\n1 bond types\n", "").replace("Bonds\n\n1 1 1 2\n2 1 2 3\n", ""), "__ok__"),
        (FULL.to_string() + "\nAtoms\n\n4 1 1 0 0 0 0\n5 1 1 0 0 0 0\n6 1 1 0 0 0 0\n", "a second Atoms section"),
        (FULL.to_string() + "\nEllipsoids\n\n", "invalid data file section Ellipsoids"),
        (FULL.replace("2 atom types", "2 atom types\n1 ellipsoids"), "unknown header line `1 ellipsoids`"),
    ];
    for (text, want) in cases {
        let r = parse_data_file(&text, Default::default(), &layout("full"));
        if want == "__ok__" {
            assert!(r.is_ok(), "{:?}", r.err());
            continue;
        }
        let es = r.expect_err(want);
        assert!(
            es.iter().any(|e| e.message.contains(want)),
            "want `{want}`, got {:#?}",
            es.iter().map(|e| &e.message).collect::<Vec<_>>()
        );
        assert!(es.iter().all(|e| e.primary_span().is_some() || e.message.contains("too many")), "{es:?}");
    }
}

#[test]
fn style_specific_rules() {
    let sphere = "t\n2 atoms\n1 atom types\n0 4 xlo xhi\n0 4 ylo yhi\n0 4 zlo zhi\n\nAtoms # sphere\n\n1 1 1.0 2.0 0.5 0.5 0.5\n2 1 0.0 2.0 1.5 0.5 0.5\n\nVelocities\n\n1 1 2 3 4 5 6\n2 1 2 3 4 5 6\n";
    let df = parse_data_file(sphere, Default::default(), &layout("sphere")).unwrap();
    assert_eq!(df.atoms[1].diameter, 0.0);
    let (_, r) = errors(&sphere.replace("2 1 0.0 2.0", "2 1 0.0 0.0"), "sphere");
    assert!(r.contains("invalid density 0.0: must be > 0"), "{r}");
    let (_, r) = errors(&sphere.replace("Atoms # sphere", "Masses\n\n1 1.0\n\nAtoms # sphere"), "sphere");
    assert!(r.contains("atom_style sphere has per-atom masses: a Masses section is not allowed"), "{r}");
    let (_, r) = errors(&sphere.replace("2 1 2 3 4 5 6", "2 1 2 3"), "sphere");
    assert!(
        r.contains("expected 7 values in this Velocities line, found 4")
            && r.contains("Velocities line for atom_style sphere is: atom-ID vx vy vz wx wy wz"),
        "{r}"
    );
    let (_, r) = errors(&sphere.replace("1 atom types", "1 atom types\n1 bonds\n1 bond types"), "sphere");
    assert!(r.contains("no bonds allowed with atom_style sphere"), "{r}");
    // the hint after `Atoms` only warns (as LAMMPS)
    let df =
        parse_data_file(&sphere.replace("Atoms # sphere", "Atoms # atomic"), Default::default(), &layout("sphere"))
            .unwrap();
    assert!(df.warnings[0].message.contains("says atom_style atomic"));
}

#[test]
fn comments_follow_lammps_rules() {
    // a word starting with `#` ends an Atoms line; a glued `#` is an error there, but not in Velocities
    let text = FULL.replace("3 1 1 0.0 2.5 0.5 0.5", "3 1 1 0.0 2.5 0.5 0.5 # last")
        + "\nVelocities\n\n1 1 2 3#c\n2 1 2 3\n3 1 2 3\n";
    let df = parse_data_file(&text, Default::default(), &layout("full")).unwrap();
    assert_eq!(df.velocities.unwrap()[0].v, [1.0, 2.0, 3.0]);
    let (_, r) = errors(&FULL.replace("3 1 1 0.0 2.5 0.5 0.5", "3 1 1 0.0 2.5 0.5 0.5#x"), "full");
    assert!(r.contains("found `0.5#x`"), "{r}");
    // header comments, CRLF line ends, a comment in place of the blank line after a section name
    let text = FULL
        .replace("3 atoms", "3 atoms # three")
        .replace("Atoms # full\n\n", "Atoms # full\n# c\n")
        .replace('\n', "\r\n");
    assert!(parse_data_file(&text, Default::default(), &layout("full")).is_ok());
}

#[test]
fn type_labels() {
    let text = FULL
        .replace("Masses", "Atom Type Labels\n\n1 A\n2 B\n\nBond Type Labels\n\n1 A-B\n\nMasses")
        .replace("2 2.0", "B 2.0")
        .replace("2 1 2 0.0", "2 1 B 0.0")
        .replace("2 1 2 3\n", "2 A-B 2 3\n");
    let df = parse_data_file(&text, Default::default(), &layout("full")).unwrap();
    assert_eq!(df.masses[1].atom_type, 2);
    assert_eq!(df.atoms[1].atom_type, 2);
    assert_eq!(df.bonds[1].topo_type, 1);
    let (_, r) = errors(&text.replace("2 1 B 0.0", "2 1 C 0.0"), "full");
    assert!(r.contains("unknown atom type label `C`"), "{r}");
    let (_, r) = errors(&text.replace("2 B\n", "2 3B\n"), "full");
    assert!(r.contains("invalid type label `3B`"), "{r}");
    let (_, r) = errors(&text.replace("2 B\n", "2 A\n"), "full");
    assert!(r.contains("type label `A` is used twice"), "{r}");
    // labels after Masses are too late (LAMMPS: "Must read Type Labels before any section involving types")
    let late = FULL.replace("Atoms # full", "Atom Type Labels\n\n1 A\n2 B\n\nAtoms # full");
    let (_, r) = errors(&late, "full");
    assert!(r.contains("Atom Type Labels must come before Masses"), "{r}");
    // LAMMPS takes no labels in coefficient sections
    let (_, r) = errors(&(text.clone() + "\nBond Coeffs # harmonic\n\nA-B 100 1.0\n"), "full");
    assert!(r.contains("expected a bond type number, found `A-B`"), "{r}");
}

#[test]
fn coefficient_sections_keep_words_for_the_style() {
    let text = FULL.to_string() + "\nPairIJ Coeffs # lj/cut\n\n1 1 1.0 1.0\n1 2 1.0 1.1 2.5\n2 2 1.0 1.2\n\nBond Coeffs # hybrid\n\n1 harmonic 100 1.0 # note\n";
    let df = parse_data_file(&text, Default::default(), &layout("full")).unwrap();
    let ij = &df.coeffs[0];
    assert_eq!(ij.kind, CoeffKind::PairIJ);
    assert_eq!(ij.lines[1].types, [1, 2]);
    let w: Vec<String> = ij.lines[1].command_args(CoeffKind::PairIJ).iter().map(|w| w.text.clone()).collect();
    assert_eq!(w, ["1", "2", "1.0", "1.1", "2.5"]);
    let b = &df.coeffs[1].lines[0];
    assert_eq!(b.args.iter().map(|w| w.text.as_str()).collect::<Vec<_>>(), ["harmonic", "100", "1.0"]);
    // class2 cross terms: the keyword goes after the type, or after a hybrid sub-style name
    let l = CoeffLine::new(vec![1], &["1.5", "2.0"]);
    assert_eq!(
        l.command_args(CoeffKind::BondBond).iter().map(|w| w.text.as_str()).collect::<Vec<_>>(),
        ["1", "bb", "1.5", "2.0"]
    );
    let l = CoeffLine::new(vec![1], &["class2", "1.5"]);
    assert_eq!(
        l.command_args(CoeffKind::AngleAngle).iter().map(|w| w.text.as_str()).collect::<Vec<_>>(),
        ["1", "class2", "aa", "1.5"]
    );
    let (_, r) = errors(&(FULL.to_string() + "\nPair Coeffs\n\n1 1 1\n\n2 1 1\n"), "full");
    assert!(r.contains("blank or comment line inside the Pair Coeffs section"), "{r}");
    let (_, r) = errors(&(FULL.to_string() + "\nPair Coeffs\n\n1 1 1\n3 1 1\n"), "full");
    assert!(r.contains("atom type 3 is out of range"), "{r}");
    let atomic =
        "t\n1 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n1 1 0 0 0\n\nBond Coeffs\n\n";
    let (_, r) = errors(atomic, "atomic");
    assert!(r.contains("invalid data file section Bond Coeffs: atom_style atomic has no bonds"), "{r}");
}

#[test]
fn error_count_is_capped() {
    let mut text = String::from("t\n100 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n");
    for i in 1..=100 {
        text.push_str(&format!("{i} 1 x 0 0\n"));
    }
    let (es, _) = errors(&text, "atomic");
    assert_eq!(es.len(), 26);
    assert!(es[25].message.contains("too many errors"));
}

#[test]
fn a_missing_title_is_explained() {
    // LAMMPS always skips the first line: here it is `3 atoms`, so the Atoms lines are one too many
    let text = FULL.replace("title\n", "");
    let (es, r) = errors(&text, "full");
    assert!(!es[0].is_error() && es[0].message.contains("first line of a data file is its title"), "{r}");
}

#[test]
fn broken_atoms_do_not_cascade() {
    // atoms 2 and 3 are rejected: the bonds naming them get no second error
    let text = FULL.replace("2 1 2 0.0 1.5", "2 1 2 x 1.5").replace("3 atoms", "2 atoms");
    let (es, r) = errors(&text, "full");
    assert_eq!(es.len(), 2, "{r}");
}
