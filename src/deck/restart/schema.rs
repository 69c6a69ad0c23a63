//! The restart file, format "dmhs restart" version 2 (described in the module comment of
//! `restart`), and the checks every file passes on read and on write. The field names are the
//! file format: renaming one, or changing what it means, makes a new version.

use crate::engine::atoms::AtomFeatures;
use crate::engine::domain::BoundaryKind;
use crate::engine::groups::MAX_GROUPS;
use crate::engine::topology::BOND_HISTORY;
use crate::engine::units::UnitStyle;
use serde::{Deserialize, Serialize};
use std::collections::HashSet;

pub const FORMAT: &str = "dmhs restart";
pub const VERSION: u32 = 2;
/// The largest atom ID: LAMMPS' MAXTAGINT in its default (smallbig) build.
pub const MAX_ID: i64 = i32::MAX as i64;
/// The largest type count, as create_box and the data-file reader allow.
const MAX_TYPES: usize = dmhs_parser::data_file::MAX_TYPES;
/// The commands read_restart replays; the same list as the private `commands::FORCE_FIELD`,
/// which decides what write_restart stores.
const FORCE_FIELD: &[&str] = &["pair_style", "pair_coeff", "pair_modify", "bond_style", "bond_coeff", "angle_style", "angle_coeff", "dihedral_style", "dihedral_coeff", "special_bonds"];

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Restart {
    pub format: String,
    pub version: u32,
    pub settings: Settings,
    #[serde(rename = "box")]
    pub bounds: BoxSection,
    pub types: Types,
    /// Group names by their bit in the atom masks; null for a free bit.
    pub groups: Vec<Option<String>>,
    pub atoms: AtomSection,
    pub topology: TopologySection,
    /// The force-field commands as words, in the order they were given.
    pub force_field: Vec<Vec<String>>,
    /// The contact-history stores of the pair style, in the style's order.
    pub contact_histories: Vec<History>,
    /// The global state of fixes (LAMMPS' Fix::write_restart), restored to a fix of the same
    /// ID and style defined after read_restart.
    #[serde(default)]
    pub fixes: Vec<FixState>,
}

pub use crate::models::fix::FixState;

/// LAMMPS' local order of the owned atoms and its `atom_modify sort` settings (see
/// `engine::lammps_order`).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrderSection {
    pub ids: Vec<i64>,
    pub sortfreq: i64,
    pub binsize: f64,
    /// `atom_modify first GROUP` (LAMMPS keeps the group's name in its restart header).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first: Option<String>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Settings {
    pub units: String,
    pub dimension: u32,
    /// One word per dimension, as in the `boundary` command.
    pub boundary: [String; 3],
    /// The words of the `atom_style` command.
    pub atom_style: Vec<String>,
    pub newton_pair: bool,
    pub newton_bond: bool,
    /// `comm_modify vel yes`.
    pub comm_vel: bool,
    pub dt: f64,
    /// The timestep was given by `timestep` (else it follows the units).
    pub dt_set: bool,
    pub step: i64,
    pub time_origin: TimeOrigin,
}

/// time = time_origin.time + (step - time_origin.step) * dt, as LAMMPS counts it.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeOrigin {
    pub step: i64,
    pub time: f64,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSection {
    pub current: Bounds,
    /// The box as created (the minimum of `m` boundaries); null if there is none.
    pub initial: Option<Bounds>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bounds {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
    /// A triclinic box's `[xy, xz, yz]` (absent for an orthogonal box).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tilt: Option<[f64; 3]>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Types {
    pub atom_types: usize,
    /// The mass of types 1, 2, ...; null where none was set.
    pub masses: Vec<Option<f64>>,
}

/// One array per per-atom quantity, in storage order; the optional ones are present exactly
/// when the atom style has them.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtomSection {
    pub count: usize,
    pub id: Vec<i64>,
    /// Wider than the engine's type so that a bad value is reported, not refused by the parser.
    #[serde(rename = "type")]
    pub typ: Vec<i64>,
    pub mask: Vec<u32>,
    pub x: Vec<[f64; 3]>,
    pub v: Vec<[f64; 3]>,
    pub image: Vec<[i32; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub molecule: Option<Vec<i64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rmass: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub omega: Option<Vec<[f64; 3]>>,
    /// Orientations (atom_style bpm/sphere).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quat: Option<Vec<[f64; 4]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rho: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drho: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub esph: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub desph: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cv: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vest: Option<Vec<[f64; 3]>>,
    /// Per-atom arrays of fixes, in the order they were registered.
    pub fix_arrays: Vec<FixArray>,
    /// LAMMPS' order of these atoms (sums and random numbers over atoms follow it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lammps_order: Option<OrderSection>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixArray {
    pub name: String,
    pub stride: usize,
    /// Ghost images carry the values too.
    pub ghosts: bool,
    /// `stride` values per atom.
    pub values: Vec<Vec<f64>>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TopologySection {
    pub bond_types: usize,
    pub angle_types: usize,
    pub dihedral_types: usize,
    pub improper_types: usize,
    /// [type, atom ID, atom ID]
    pub bonds: Vec<[i64; 3]>,
    /// [type, 3 atom IDs]
    pub angles: Vec<[i64; 4]>,
    /// [type, 4 atom IDs]
    pub dihedrals: Vec<[i64; 5]>,
    /// Per bond (as `bonds`), when a BPM style keeps a reference state: the values of
    /// `Bond::history` (LAMMPS' fix bond/history per-atom array).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bond_history: Option<Vec<[f64; BOND_HISTORY]>>,
    /// Per bond: its place in each of its atoms' bond lists (LAMMPS' bond_atom order, which a
    /// broken bond changes; 4294967295 for none yet).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bond_slots: Option<Vec<[u32; 2]>>,
    /// The BPM style has stored every bond's reference state (LAMMPS' fix bond/history
    /// `stored_flag`, its write_restart).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub bond_history_stored: bool,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct History {
    /// Values per contact.
    pub size: usize,
    pub contacts: Vec<Contact>,
}

/// [owner ID, partner ID, image difference, values] (see `engine::contact_history`).
#[derive(Serialize, Deserialize)]
pub struct Contact(pub i64, pub i64, pub [i32; 3], pub Vec<f64>);

/// Only the format and version of a file, read when the whole does not parse: a file of
/// another version fails on its fields, and its version makes the better message.
#[derive(Deserialize)]
pub struct Header {
    pub format: String,
    pub version: u64,
}

/// The settings of a checked file, in engine terms.
pub struct Checked {
    pub units: UnitStyle,
    pub boundary: [[BoundaryKind; 2]; 3],
    pub features: AtomFeatures,
}

/// Refuse a file of another format or version.
pub fn identify(format: &str, version: u64) -> Result<(), String> {
    if format != FORMAT {
        return Err(format!("not a dmhs restart file (its `format` is `{format}`, not `{FORMAT}`)"));
    }
    if version > VERSION as u64 {
        return Err(format!("restart format version {version} is from a newer dmhs; this one reads version {VERSION}"));
    }
    if version != VERSION as u64 {
        return Err(format!("restart format version {version} is not read by this dmhs (it reads version {VERSION}): write the file again with write_restart"));
    }
    Ok(())
}

/// A `boundary` word: one letter for both faces or a pair (`fs`); both faces or neither periodic.
pub fn boundary_kinds(word: &str) -> Option<[BoundaryKind; 2]> {
    let kind = |c| match c {
        'p' => Some(BoundaryKind::Periodic),
        'f' => Some(BoundaryKind::Fixed),
        's' => Some(BoundaryKind::Shrink),
        'm' => Some(BoundaryKind::ShrinkMin),
        _ => None,
    };
    let c: Vec<char> = word.chars().collect();
    let pair = match c[..] {
        [a] => [kind(a)?; 2],
        [a, b] => [kind(a)?, kind(b)?],
        _ => return None,
    };
    ((pair[0] == BoundaryKind::Periodic) == (pair[1] == BoundaryKind::Periodic)).then_some(pair)
}

pub fn boundary_word(b: &[BoundaryKind; 2]) -> String {
    if b[0] == b[1] { b[0].letter().to_string() } else { format!("{}{}", b[0].letter(), b[1].letter()) }
}

/// Ok if every value is finite; else what is wrong, to follow the field's name.
fn finite(v: &[f64]) -> Result<(), String> {
    match v {
        _ if v.iter().all(|x| x.is_finite()) => Ok(()),
        [x] => Err(format!("is {x}: not a finite number")),
        _ => Err(format!("is {v:?}: not all finite")),
    }
}

fn in_types(t: i64, n: usize, count: &str) -> Result<(), String> {
    if (1..=n as i64).contains(&t) { Ok(()) } else { Err(format!("is {t}, outside 1..={n} ({count})")) }
}

impl Restart {
    /// Check every field; the first error names it (as a path in the file) and, for per-atom
    /// values, the atom ID.
    pub fn check(&self) -> Result<Checked, String> {
        identify(&self.format, self.version as u64)?;
        let s = &self.settings;
        let units = match s.units.as_str() {
            "lj" => UnitStyle::Lj,
            "si" => UnitStyle::Si,
            "cgs" => UnitStyle::Cgs,
            u => return Err(format!("settings.units is `{u}`: dmhs supports lj, si and cgs")),
        };
        if s.dimension != 2 && s.dimension != 3 {
            return Err(format!("settings.dimension is {}, not 2 or 3", s.dimension));
        }
        let mut boundary = [[BoundaryKind::Periodic; 2]; 3];
        for (d, w) in s.boundary.iter().enumerate() {
            boundary[d] = boundary_kinds(w).ok_or_else(|| format!("settings.boundary[{d}] is `{w}`: expected p, f, s, m or a pair of f, s, m"))?;
        }
        if s.dimension == 2 && boundary[2][0] != BoundaryKind::Periodic {
            return Err("settings.boundary[2]: a 2d simulation must be periodic in z".into());
        }
        let features = atom_style_features(&s.atom_style)?;
        finite(&[s.dt]).map_err(|e| format!("settings.dt {e}"))?;
        if s.step < 0 {
            return Err(format!("settings.step is {}: must be >= 0", s.step));
        }
        if !(0..=s.step).contains(&s.time_origin.step) {
            return Err(format!("settings.time_origin.step is {}: must be in 0..={} (settings.step)", s.time_origin.step, s.step));
        }
        finite(&[s.time_origin.time]).map_err(|e| format!("settings.time_origin.time {e}"))?;
        check_bounds("box.current", &self.bounds.current, s.dimension)?;
        if let Some(b) = &self.bounds.initial {
            check_bounds("box.initial", b, s.dimension)?;
        }
        self.check_types()?;
        let group_bits = self.check_groups()?;
        let ids = self.check_atoms(features, group_bits)?;
        self.check_topology(features, &ids)?;
        self.check_order(&ids)?;
        for (k, f) in self.fixes.iter().enumerate() {
            finite(&f.values).map_err(|e| format!("fixes[{k}] (fix {} {}) values {e}", f.id, f.style))?;
        }
        for (k, words) in self.force_field.iter().enumerate() {
            match words.first() {
                Some(w) if FORCE_FIELD.contains(&w.as_str()) => {}
                _ => return Err(format!("force_field[{k}] `{}` is not one of the force-field commands ({})", words.join(" "), FORCE_FIELD.join(", "))),
            }
        }
        for (k, h) in self.contact_histories.iter().enumerate() {
            for (c, Contact(owner, partner, _, values)) in h.contacts.iter().enumerate() {
                let at = || format!("contact_histories[{k}].contacts[{c}]");
                for id in [owner, partner] {
                    if !ids.contains(id) {
                        return Err(format!("{} refers to atom {id}, which does not exist", at()));
                    }
                }
                if values.len() != h.size {
                    return Err(format!("{} has {} values, not {} (contact_histories[{k}].size)", at(), values.len(), h.size));
                }
                finite(values).map_err(|e| format!("{} (atoms {owner} and {partner}) {e}", at()))?;
            }
        }
        Ok(Checked { units, boundary, features })
    }

    fn check_types(&self) -> Result<(), String> {
        let t = &self.types;
        if t.atom_types > MAX_TYPES {
            return Err(format!("types.atom_types is {}: at most {MAX_TYPES}", t.atom_types));
        }
        if t.masses.len() != t.atom_types {
            return Err(format!("types.masses has {} entries for {} types (types.atom_types)", t.masses.len(), t.atom_types));
        }
        for (k, m) in t.masses.iter().enumerate() {
            if let Some(m) = *m {
                if !(m.is_finite() && m > 0.0) {
                    return Err(format!("types.masses[{k}] (type {}) is {m}: a mass must be > 0", k + 1));
                }
            }
        }
        Ok(())
    }

    /// The mask bits of the groups.
    fn check_groups(&self) -> Result<u32, String> {
        let g = &self.groups;
        if g.len() > MAX_GROUPS {
            return Err(format!("groups has {} entries: at most {MAX_GROUPS}", g.len()));
        }
        if g.first().and_then(|n| n.as_deref()) != Some("all") {
            return Err("groups[0] must be `all`".into());
        }
        let mut seen = HashSet::new();
        let mut bits = 0u32;
        for (k, name) in g.iter().enumerate() {
            let Some(name) = name else { continue };
            if name.is_empty() || name.contains(char::is_whitespace) {
                return Err(format!("groups[{k}] `{name}` is not a group ID"));
            }
            if !seen.insert(name) {
                return Err(format!("groups[{k}]: group `{name}` appears twice"));
            }
            bits |= 1 << k;
        }
        Ok(bits)
    }

    /// The atom IDs.
    fn check_atoms(&self, ft: AtomFeatures, group_bits: u32) -> Result<HashSet<i64>, String> {
        let a = &self.atoms;
        let n = a.count;
        let style = self.settings.atom_style.join(" ");
        let length = |name: &str, len: usize| {
            if len == n { Ok(()) } else { Err(format!("atoms.{name} has {len} entries for {n} atoms (atoms.count)")) }
        };
        length("id", a.id.len())?;
        length("type", a.typ.len())?;
        length("mask", a.mask.len())?;
        length("x", a.x.len())?;
        length("v", a.v.len())?;
        length("image", a.image.len())?;
        let optional = |name: &str, len: Option<usize>, wanted: bool| match (len, wanted) {
            (Some(len), true) => length(name, len),
            (None, false) => Ok(()),
            (None, true) => Err(format!("atoms.{name} is missing (atom style {style} has it)")),
            (Some(_), false) => Err(format!("atoms.{name} is given, but atom style {style} has no {name}")),
        };
        optional("molecule", a.molecule.as_ref().map(Vec::len), ft.molecule)?;
        optional("q", a.q.as_ref().map(Vec::len), ft.charge)?;
        optional("radius", a.radius.as_ref().map(Vec::len), ft.sphere)?;
        optional("rmass", a.rmass.as_ref().map(Vec::len), ft.sphere)?;
        optional("omega", a.omega.as_ref().map(Vec::len), ft.sphere)?;
        optional("quat", a.quat.as_ref().map(Vec::len), ft.quat)?;
        for (name, v) in [("rho", &a.rho), ("drho", &a.drho), ("esph", &a.esph), ("desph", &a.desph), ("cv", &a.cv)] {
            optional(name, v.as_ref().map(Vec::len), ft.sph)?;
        }
        optional("vest", a.vest.as_ref().map(Vec::len), ft.sph)?;

        let mut ids = HashSet::with_capacity(n);
        for (i, &id) in a.id.iter().enumerate() {
            if !(1..=MAX_ID).contains(&id) {
                return Err(format!("atoms.id[{i}] is {id}: atom IDs must be in 1..={MAX_ID}"));
            }
            if !ids.insert(id) {
                return Err(format!("atoms.id[{i}]: atom ID {id} appears twice"));
            }
        }
        // each value by its field, index and atom ID
        let each = |name: &str, ok: &dyn Fn(usize) -> Result<(), String>| {
            (0..n).try_for_each(|i| ok(i).map_err(|e| format!("atoms.{name}[{i}] (atom {}) {e}", a.id[i])))
        };
        let ntypes = self.types.atom_types;
        each("type", &|i| in_types(a.typ[i], ntypes, "types.atom_types"))?;
        each("mask", &|i| match a.mask[i] {
            m if m & 1 == 0 => Err(format!("is {m}: every atom is in group all (bit 0)")),
            m if m & !group_bits != 0 => Err(format!("is {m}: bit {} is not a group in `groups`", (m & !group_bits).trailing_zeros())),
            _ => Ok(()),
        })?;
        each("x", &|i| finite(&a.x[i]))?;
        each("v", &|i| finite(&a.v[i]))?;
        if let Some(q) = &a.q {
            each("q", &|i| finite(&q[i..=i]))?;
        }
        if let (Some(radius), Some(rmass), Some(omega)) = (&a.radius, &a.rmass, &a.omega) {
            each("radius", &|i| match radius[i] {
                r if r.is_finite() && r >= 0.0 => Ok(()),
                r => Err(format!("is {r}: a radius must be >= 0")),
            })?;
            each("rmass", &|i| match rmass[i] {
                m if m.is_finite() && m > 0.0 => Ok(()),
                m => Err(format!("is {m}: a mass must be > 0")),
            })?;
            each("omega", &|i| finite(&omega[i]))?;
        }
        if let Some(quat) = &a.quat {
            each("quat", &|i| finite(&quat[i]))?;
        }
        for (name, v) in [("rho", &a.rho), ("drho", &a.drho), ("esph", &a.esph), ("desph", &a.desph), ("cv", &a.cv)] {
            if let Some(v) = v {
                each(name, &|i| finite(&v[i..=i]))?;
            }
        }
        if let Some(vest) = &a.vest {
            each("vest", &|i| finite(&vest[i]))?;
        }
        let mut names = HashSet::new();
        for (k, f) in a.fix_arrays.iter().enumerate() {
            if f.name.is_empty() || !names.insert(&f.name) {
                return Err(format!("atoms.fix_arrays[{k}]: the name `{}` is empty or appears twice", f.name));
            }
            if f.stride == 0 {
                return Err(format!("atoms.fix_arrays[{k}] (`{}`): stride must be >= 1", f.name));
            }
            length(&format!("fix_arrays[{k}].values"), f.values.len())?;
            each(&format!("fix_arrays[{k}].values"), &|i| match &f.values[i] {
                row if row.len() != f.stride => Err(format!("has {} values, not {} (the stride)", row.len(), f.stride)),
                row => finite(row),
            })?;
        }
        Ok(ids)
    }

    fn check_topology(&self, ft: AtomFeatures, ids: &HashSet<i64>) -> Result<(), String> {
        let t = &self.topology;
        for (kind, n) in [("bond", t.bond_types), ("angle", t.angle_types), ("dihedral", t.dihedral_types), ("improper", t.improper_types)] {
            if n > MAX_TYPES {
                return Err(format!("topology.{kind}_types is {n}: at most {MAX_TYPES}"));
            }
        }
        check_records("bond", &t.bonds, t.bond_types, ft.bonds, ids)?;
        check_records("angle", &t.angles, t.angle_types, ft.angles, ids)?;
        check_records("dihedral", &t.dihedrals, t.dihedral_types, ft.dihedrals, ids)?;
        let n = t.bonds.len();
        if let Some(h) = &t.bond_history {
            if h.len() != n {
                return Err(format!("topology.bond_history has {} entries for {n} bonds", h.len()));
            }
            if let Some(k) = h.iter().position(|v| finite(v).is_err()) {
                return Err(format!("topology.bond_history[{k}] {}", finite(&h[k]).unwrap_err()));
            }
        }
        if let Some(s) = &t.bond_slots {
            if s.len() != n {
                return Err(format!("topology.bond_slots has {} entries for {n} bonds", s.len()));
            }
            // an atom's slots are distinct (its bond list has one bond per place)
            let mut seen = HashSet::new();
            for (k, (b, slots)) in t.bonds.iter().zip(s).enumerate() {
                for side in 0..2 {
                    if slots[side] != u32::MAX && !seen.insert((b[side + 1], slots[side])) {
                        return Err(format!("topology.bond_slots[{k}]: atom {} has two bonds at place {}", b[side + 1], slots[side]));
                    }
                }
            }
        }
        Ok(())
    }

    /// LAMMPS' order: a permutation of the atom IDs.
    fn check_order(&self, ids: &HashSet<i64>) -> Result<(), String> {
        let Some(o) = &self.atoms.lammps_order else { return Ok(()) };
        let distinct: HashSet<i64> = o.ids.iter().copied().collect();
        if o.ids.len() != ids.len() || distinct != *ids {
            return Err(format!("atoms.lammps_order.ids is not an order of the {} atom IDs of atoms.id", ids.len()));
        }
        if o.sortfreq < 0 || !(o.binsize.is_finite() && o.binsize >= 0.0) {
            return Err(format!("atoms.lammps_order: sortfreq {} and binsize {} must be >= 0", o.sortfreq, o.binsize));
        }
        Ok(())
    }
}

/// As read_data checks a box: finite, lo below hi, a length that is finite, and in 2d a z
/// range around 0.
fn check_bounds(name: &str, b: &Bounds, dimension: u32) -> Result<(), String> {
    finite(&b.lo).map_err(|e| format!("{name}.lo {e}"))?;
    finite(&b.hi).map_err(|e| format!("{name}.hi {e}"))?;
    if let Some(d) = (0..3).find(|&d| b.lo[d] >= b.hi[d]) {
        return Err(format!("{name}: lo[{d}] = {} is not below hi[{d}] = {}", b.lo[d], b.hi[d]));
    }
    if let Some(d) = (0..3).find(|&d| !(b.hi[d] - b.lo[d]).is_finite()) {
        return Err(format!("{name}: the length hi[{d}] - lo[{d}] = {:?} - ({:?}) overflows a double", b.hi[d], b.lo[d]));
    }
    if dimension == 2 && !(b.lo[2] < 0.0 && b.hi[2] > 0.0) {
        return Err(format!("{name}: a 2d box must have lo[2] < 0 < hi[2], not {} .. {}", b.lo[2], b.hi[2]));
    }
    Ok(())
}

/// The features of an atom style given as the words of the command.
fn atom_style_features(words: &[String]) -> Result<AtomFeatures, String> {
    // `sphere 1` / `bpm/sphere 1`: the dynamic-radius flag is not a style
    let words: Vec<String> = words.iter().enumerate().filter(|(k, w)| !(*w == "1" && *k > 0 && matches!(words[k - 1].as_str(), "sphere" | "bpm/sphere"))).map(|(_, w)| w.clone()).collect();
    let styles: Vec<&str> = match &words[..] {
        [h, subs @ ..] if h == "hybrid" && !subs.is_empty() => subs.iter().map(String::as_str).collect(),
        [s] if s != "hybrid" => vec![s.as_str()],
        _ => return Err(format!("settings.atom_style `{}` is not an atom style", words.join(" "))),
    };
    crate::deck::commands::features_of(&styles).map_err(|s| format!("settings.atom_style: `{s}` is not an atom style dmhs supports"))
}

/// Bonds, angles or dihedrals: [type, atom IDs...].
fn check_records<const N: usize>(kind: &str, records: &[[i64; N]], ntypes: usize, allowed: bool, ids: &HashSet<i64>) -> Result<(), String> {
    if !records.is_empty() && !allowed {
        return Err(format!("topology.{kind}s: the atom style has no {kind}s"));
    }
    for (k, r) in records.iter().enumerate() {
        // negative: turned off by delete_bonds
        in_types(r[0].checked_abs().unwrap_or(0), ntypes, &format!("topology.{kind}_types")).map_err(|e| format!("topology.{kind}s[{k}]: the type {e}"))?;
        if let Some(id) = r[1..].iter().find(|id| !ids.contains(id)) {
            return Err(format!("topology.{kind}s[{k}] refers to atom {id}, which does not exist"));
        }
    }
    Ok(())
}
