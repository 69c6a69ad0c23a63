//! The columns of the `Atoms` and `Velocities` lines of a data file for each atom style dmhs
//! supports, as LAMMPS' `fields_data_atom` / `fields_data_vel` order them (hybrid styles: id
//! type x, then each sub-style's own fields in order, without repeats).

use crate::ast::Word;
use crate::diag::Diagnostic;
use crate::span::Span;
use crate::suggest::did_you_mean_help;

use super::TypeKind;

/// One column of an `Atoms` or `Velocities` line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Column {
    Id,
    Type,
    Molecule,
    Q,
    X,
    Y,
    Z,
    /// sphere, bpm/sphere: particle diameter (LAMMPS stores radius = diameter / 2).
    Diameter,
    /// sphere, bpm/sphere: density (LAMMPS stores the mass computed from it).
    Density,
    /// sph: density.
    Rho,
    /// sph: internal energy.
    Esph,
    /// sph: heat capacity.
    Cv,
    Vx,
    Vy,
    Vz,
    /// Angular velocity (sphere, bpm/sphere), written `wx wy wz` in the LAMMPS manual.
    OmegaX,
    OmegaY,
    OmegaZ,
}

impl Column {
    /// The column's name as the LAMMPS `read_data` manual writes it.
    pub fn name(self) -> &'static str {
        match self {
            Column::Id => "atom-ID",
            Column::Type => "atom-type",
            Column::Molecule => "molecule-ID",
            Column::Q => "q",
            Column::X => "x",
            Column::Y => "y",
            Column::Z => "z",
            Column::Diameter => "diameter",
            Column::Density => "density",
            Column::Rho => "rho",
            Column::Esph => "esph",
            Column::Cv => "cv",
            Column::Vx => "vx",
            Column::Vy => "vy",
            Column::Vz => "vz",
            Column::OmegaX => "wx",
            Column::OmegaY => "wy",
            Column::OmegaZ => "wz",
        }
    }
    /// Integer columns (parsed and written as integers).
    pub fn is_integer(self) -> bool {
        matches!(self, Column::Id | Column::Type | Column::Molecule)
    }
}

use Column as C;

/// One atom style dmhs supports: its data-file columns (LAMMPS' `fields_data_atom` and
/// `fields_data_vel`, in that order) and what it allows.
struct StyleDef {
    name: &'static str,
    atoms: &'static [Column],
    vels: &'static [Column],
    bonds: bool,
    angles: bool,
    dihedrals: bool,
    impropers: bool,
    /// Per-type masses (a `Masses` section); otherwise per-atom masses.
    per_type_mass: bool,
    /// Takes the optional 0/1 argument (static or dynamic radii).
    takes_flag: bool,
}

const V: &[Column] = &[C::Id, C::Vx, C::Vy, C::Vz];
const V_OMEGA: &[Column] = &[C::Id, C::Vx, C::Vy, C::Vz, C::OmegaX, C::OmegaY, C::OmegaZ];

const STYLES: &[StyleDef] = &[
    StyleDef {
        name: "atomic",
        atoms: &[C::Id, C::Type, C::X, C::Y, C::Z],
        vels: V,
        bonds: false,
        angles: false,
        dihedrals: false,
        impropers: false,
        per_type_mass: true,
        takes_flag: false,
    },
    StyleDef {
        name: "charge",
        atoms: &[C::Id, C::Type, C::Q, C::X, C::Y, C::Z],
        vels: V,
        bonds: false,
        angles: false,
        dihedrals: false,
        impropers: false,
        per_type_mass: true,
        takes_flag: false,
    },
    StyleDef {
        name: "bond",
        atoms: &[C::Id, C::Molecule, C::Type, C::X, C::Y, C::Z],
        vels: V,
        bonds: true,
        angles: false,
        dihedrals: false,
        impropers: false,
        per_type_mass: true,
        takes_flag: false,
    },
    StyleDef {
        name: "angle",
        atoms: &[C::Id, C::Molecule, C::Type, C::X, C::Y, C::Z],
        vels: V,
        bonds: true,
        angles: true,
        dihedrals: false,
        impropers: false,
        per_type_mass: true,
        takes_flag: false,
    },
    StyleDef {
        name: "molecular",
        atoms: &[C::Id, C::Molecule, C::Type, C::X, C::Y, C::Z],
        vels: V,
        bonds: true,
        angles: true,
        dihedrals: true,
        impropers: true,
        per_type_mass: true,
        takes_flag: false,
    },
    StyleDef {
        name: "full",
        atoms: &[C::Id, C::Molecule, C::Type, C::Q, C::X, C::Y, C::Z],
        vels: V,
        bonds: true,
        angles: true,
        dihedrals: true,
        impropers: true,
        per_type_mass: true,
        takes_flag: false,
    },
    StyleDef {
        name: "sphere",
        atoms: &[C::Id, C::Type, C::Diameter, C::Density, C::X, C::Y, C::Z],
        vels: V_OMEGA,
        bonds: false,
        angles: false,
        dihedrals: false,
        impropers: false,
        per_type_mass: false,
        takes_flag: true,
    },
    StyleDef {
        name: "bpm/sphere",
        atoms: &[C::Id, C::Molecule, C::Type, C::Diameter, C::Density, C::X, C::Y, C::Z],
        vels: V_OMEGA,
        bonds: true,
        angles: false,
        dihedrals: false,
        impropers: false,
        per_type_mass: false,
        takes_flag: true,
    },
    StyleDef {
        name: "sph",
        atoms: &[C::Id, C::Type, C::Rho, C::Esph, C::Cv, C::X, C::Y, C::Z],
        vels: V,
        bonds: false,
        angles: false,
        dihedrals: false,
        impropers: false,
        per_type_mass: true,
        takes_flag: false,
    },
];

/// LAMMPS atom styles dmhs knows by name but does not support (a clearer error than "unknown").
const UNSUPPORTED_STYLES: &[&str] = &[
    "amoeba",
    "body",
    "dielectric",
    "dipole",
    "dpd",
    "edpd",
    "electron",
    "ellipsoid",
    "line",
    "mdpd",
    "oxdna",
    "peri",
    "rheo",
    "rheo/thermal",
    "smd",
    "spin",
    "tdpd",
    "template",
    "tri",
    "wavepacket",
    "apip",
];

/// The columns of the `Atoms` and `Velocities` lines for one atom style, and what the style
/// allows in a data file.
#[derive(Clone, Debug, PartialEq)]
pub struct AtomLayout {
    /// `full`, `sphere`, ... or `hybrid` (what `write_data` writes after `Atoms #`).
    pub style: String,
    /// The sub-styles of a hybrid style in order; for a plain style, that style alone.
    pub substyles: Vec<String>,
    /// `Atoms` columns without the optional trailing image flags `ix iy iz`.
    pub atoms: Vec<Column>,
    /// `Velocities` columns.
    pub velocities: Vec<Column>,
    pub bonds: bool,
    pub angles: bool,
    pub dihedrals: bool,
    pub impropers: bool,
    /// Masses are per type (a `Masses` section is allowed).
    pub per_type_mass: bool,
    /// Masses are per atom (sphere, bpm/sphere: computed from diameter and density).
    pub per_atom_mass: bool,
}

fn is_lammps_bool(s: &str) -> bool {
    matches!(s, "yes" | "no" | "on" | "off" | "true" | "false" | "1" | "0")
}

fn supported_style_names() -> String {
    STYLES.iter().map(|s| s.name).collect::<Vec<_>>().join(", ")
}

fn style_def(w: &Word) -> Result<&'static StyleDef, Diagnostic> {
    if let Some(d) = STYLES.iter().find(|d| d.name == w.text) {
        return Ok(d);
    }
    let help = format!("supported atom styles: {}, hybrid", supported_style_names());
    if UNSUPPORTED_STYLES.contains(&w.text.as_str()) {
        return Err(Diagnostic::at(
            w.span,
            format!("atom_style {} is a LAMMPS style that dmhs does not support", w.text),
            "not supported",
        )
        .with_help(help));
    }
    let mut d = Diagnostic::at(w.span, format!("unknown atom style `{}`", w.text), "unknown atom style");
    let names = STYLES.iter().map(|s| s.name).chain(["hybrid"]);
    if let Some(h) = did_you_mean_help(&w.text, names) {
        d = d.with_help(h);
    }
    Err(d.with_help(help))
}

impl AtomLayout {
    /// The layout for the words after `atom_style` (e.g. `full`, `sphere 1`,
    /// `hybrid sph sphere angle`).
    pub fn from_words(words: &[Word]) -> Result<AtomLayout, Diagnostic> {
        let Some(first) = words.first() else {
            return Err(Diagnostic::error("missing atom style")
                .with_help(format!("supported atom styles: {}, hybrid", supported_style_names())));
        };
        let mut defs: Vec<&'static StyleDef> = vec![];
        let hybrid = first.text == "hybrid";
        let rest = if hybrid { &words[1..] } else { words };
        // a word is a style name, or the 0/1 argument of the style before it
        let mut flag_taken = false;
        for w in rest {
            let prev = defs.last().copied();
            let is_style = STYLES.iter().any(|d| d.name == w.text) || UNSUPPORTED_STYLES.contains(&w.text.as_str());
            if !is_style {
                if let Some(p) = prev {
                    let starts_like_name =
                        w.text.starts_with(|c: char| c.is_ascii_alphabetic()) && !is_lammps_bool(&w.text);
                    if !starts_like_name {
                        if !p.takes_flag || flag_taken {
                            return Err(Diagnostic::at(
                                w.span,
                                format!("unexpected argument `{}` for atom_style {}", w.text, p.name),
                                "not expected here",
                            )
                            .with_help(format!(
                                "atom_style {} takes {}",
                                p.name,
                                if p.takes_flag { "one optional argument: 0 or 1" } else { "no arguments" }
                            )));
                        }
                        if !is_lammps_bool(&w.text) {
                            return Err(Diagnostic::at(
                                w.span,
                                format!("expected 0 or 1 for atom_style {}, found `{}`", p.name, w.text),
                                "expected 0 or 1",
                            )
                            .with_help(format!(
                                "syntax: atom_style {} [0|1]  (1: particle radii may change)",
                                p.name
                            )));
                        }
                        flag_taken = true;
                        continue;
                    }
                }
            }
            if w.text == "hybrid" {
                return Err(Diagnostic::at(
                    w.span,
                    "atom_style hybrid cannot have hybrid as a sub-style",
                    "not allowed here",
                ));
            }
            if !hybrid && !defs.is_empty() {
                return Err(Diagnostic::at(
                    w.span,
                    format!("unexpected argument `{}` for atom_style {}", w.text, defs[0].name),
                    "not expected here",
                )
                .with_help("several styles at once need `atom_style hybrid style1 style2 ...`"));
            }
            let d = style_def(w)?;
            if defs.iter().any(|x| x.name == d.name) {
                return Err(Diagnostic::at(
                    w.span,
                    format!("atom_style hybrid cannot use atom style {} twice", d.name),
                    "repeated",
                ));
            }
            defs.push(d);
            flag_taken = false;
        }
        let mut layout = AtomLayout {
            style: if hybrid { "hybrid".to_string() } else { defs[0].name.to_string() },
            substyles: defs.iter().map(|d| d.name.to_string()).collect(),
            atoms: vec![],
            velocities: vec![],
            bonds: defs.iter().any(|d| d.bonds),
            angles: defs.iter().any(|d| d.angles),
            dihedrals: defs.iter().any(|d| d.dihedrals),
            impropers: defs.iter().any(|d| d.impropers),
            per_type_mass: defs.iter().any(|d| d.per_type_mass),
            per_atom_mass: defs.iter().any(|d| !d.per_type_mass),
        };
        if hybrid {
            // LAMMPS' hybrid: id type x, then each sub-style's own fields in order, no repeats
            layout.atoms = vec![C::Id, C::Type, C::X, C::Y, C::Z];
            layout.velocities = V.to_vec();
            for d in &defs {
                for c in d.atoms {
                    if !layout.atoms.contains(c) {
                        layout.atoms.push(*c);
                    }
                }
                for c in d.vels {
                    if !layout.velocities.contains(c) {
                        layout.velocities.push(*c);
                    }
                }
            }
            if defs.is_empty() {
                // plain `atom_style hybrid`: id type x with per-type masses (as LAMMPS)
                layout.per_type_mass = true;
            }
        } else {
            layout.atoms = defs[0].atoms.to_vec();
            layout.velocities = defs[0].vels.to_vec();
        }
        Ok(layout)
    }

    /// [`AtomLayout::from_words`] for plain strings (no source spans).
    pub fn from_names(names: &[&str]) -> Result<AtomLayout, Diagnostic> {
        let words: Vec<Word> = names.iter().map(|n| Word::new(*n, Span::default())).collect();
        AtomLayout::from_words(&words)
    }

    /// `full`, or `hybrid sph sphere angle`.
    pub fn style_label(&self) -> String {
        if self.style == "hybrid" {
            let mut s = "hybrid".to_string();
            for sub in &self.substyles {
                s.push(' ');
                s.push_str(sub);
            }
            s
        } else {
            self.style.clone()
        }
    }

    /// Index of a column in the `Atoms` line.
    pub fn atom_column(&self, c: Column) -> Option<usize> {
        self.atoms.iter().position(|x| *x == c)
    }

    /// Index of a column in the `Velocities` line.
    pub fn velocity_column(&self, c: Column) -> Option<usize> {
        self.velocities.iter().position(|x| *x == c)
    }

    /// `Atoms line for atom_style full is: atom-ID molecule-ID atom-type q x y z [ix iy iz]`
    pub fn atoms_help(&self) -> String {
        let cols: Vec<&str> = self.atoms.iter().map(|c| c.name()).collect();
        format!("Atoms line for atom_style {} is: {} [ix iy iz]", self.style_label(), cols.join(" "))
    }

    /// `Velocities line for atom_style sphere is: atom-ID vx vy vz wx wy wz`
    pub fn velocities_help(&self) -> String {
        let cols: Vec<&str> = self.velocities.iter().map(|c| c.name()).collect();
        format!("Velocities line for atom_style {} is: {}", self.style_label(), cols.join(" "))
    }

    pub(super) fn allows(&self, k: TypeKind) -> bool {
        match k {
            TypeKind::Atom => true,
            TypeKind::Bond => self.bonds,
            TypeKind::Angle => self.angles,
            TypeKind::Dihedral => self.dihedrals,
            TypeKind::Improper => self.impropers,
        }
    }
}
