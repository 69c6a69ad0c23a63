//! LAMMPS data files (`read_data` / `write_data`), syntax only.
//!
//! The format, as LAMMPS 22 Jul 2025 reads it (`ReadData`, `Atom::data_*`, `AtomVec*`):
//! * the first line is a title and is always skipped;
//! * header lines follow (`N atoms`, `N atom types`, `xlo xhi`, ... in any order, `#` starts a
//!   comment, blank lines are skipped); the first line that is not a header line must be a
//!   section name;
//! * each section is its name (optionally `# style` after it), one line that LAMMPS discards
//!   (it must be blank), then exactly as many lines as the header implies (`Atoms`: N atoms,
//!   `Masses`: N atom types, `PairIJ Coeffs`: N(N+1)/2, ...). Blank lines *inside* a section
//!   count as lines, so they are errors; blank lines between sections are skipped.
//!
//! [`AtomLayout`] gives the columns of the `Atoms` and `Velocities` lines for an atom style,
//! [`parse_data_file`] reads a file into a [`DataFile`] (every value with its span, all errors
//! found at once where the file allows), and [`DataFile::write`] writes the layout LAMMPS'
//! `write_data` writes, with every floating-point number at full round-trip precision.

mod layout;
pub(crate) mod read;
mod write;

pub use layout::{AtomLayout, Column};
pub use read::{is_section_name, parse_data_file, parse_data_file_with};
pub use write::{format_float, write_data_title};

use std::collections::HashMap;

use crate::ast::Word;
use crate::diag::Diagnostic;
use crate::span::Span;

use Column as C;

/// The largest atom ID LAMMPS accepts: `MAXTAGINT` of its default build (`LAMMPS_SMALLBIG`:
/// `tagint` is a 32-bit int), 2^31 - 1.
pub const MAX_ATOM_ID: i64 = i32::MAX as i64;

/// The most types of one kind dmhs accepts (create_box, data file headers). It keeps tables per
/// type and per pair of atom types ((N + 1)^2 entries), so 2^31 types (accepted by LAMMPS'
/// parser) was an allocation of gigabytes that aborted.
pub const MAX_TYPES: usize = 4096;

/// The five kinds of types (atom, bond, angle, dihedral, improper).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TypeKind {
    Atom,
    Bond,
    Angle,
    Dihedral,
    Improper,
}

impl TypeKind {
    pub const ALL: [TypeKind; 5] =
        [TypeKind::Atom, TypeKind::Bond, TypeKind::Angle, TypeKind::Dihedral, TypeKind::Improper];
    /// `atom`, `bond`, ... (lower case, as in `N bond types`).
    pub fn name(self) -> &'static str {
        match self {
            TypeKind::Atom => "atom",
            TypeKind::Bond => "bond",
            TypeKind::Angle => "angle",
            TypeKind::Dihedral => "dihedral",
            TypeKind::Improper => "improper",
        }
    }
    /// `Atom`, `Bond`, ... (as in `Bond Type Labels`).
    pub fn title(self) -> &'static str {
        match self {
            TypeKind::Atom => "Atom",
            TypeKind::Bond => "Bond",
            TypeKind::Angle => "Angle",
            TypeKind::Dihedral => "Dihedral",
            TypeKind::Improper => "Improper",
        }
    }
    fn index(self) -> usize {
        self as usize
    }
}

/// A coefficient section. The lines are kept as words for the style's own coefficient parser.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CoeffKind {
    Pair,
    PairIJ,
    Bond,
    Angle,
    Dihedral,
    Improper,
    // class2 cross terms
    BondBond,
    BondAngle,
    UreyBradley,
    MiddleBondTorsion,
    EndBondTorsion,
    AngleTorsion,
    AngleAngleTorsion,
    BondBond13,
    AngleAngle,
}

impl CoeffKind {
    pub const ALL: [CoeffKind; 15] = [
        CoeffKind::Pair,
        CoeffKind::PairIJ,
        CoeffKind::Bond,
        CoeffKind::Angle,
        CoeffKind::Dihedral,
        CoeffKind::Improper,
        CoeffKind::BondBond,
        CoeffKind::BondAngle,
        CoeffKind::UreyBradley,
        CoeffKind::MiddleBondTorsion,
        CoeffKind::EndBondTorsion,
        CoeffKind::AngleTorsion,
        CoeffKind::AngleAngleTorsion,
        CoeffKind::BondBond13,
        CoeffKind::AngleAngle,
    ];
    /// The section name, e.g. `Pair Coeffs`.
    pub fn section_name(self) -> &'static str {
        match self {
            CoeffKind::Pair => "Pair Coeffs",
            CoeffKind::PairIJ => "PairIJ Coeffs",
            CoeffKind::Bond => "Bond Coeffs",
            CoeffKind::Angle => "Angle Coeffs",
            CoeffKind::Dihedral => "Dihedral Coeffs",
            CoeffKind::Improper => "Improper Coeffs",
            CoeffKind::BondBond => "BondBond Coeffs",
            CoeffKind::BondAngle => "BondAngle Coeffs",
            CoeffKind::UreyBradley => "UreyBradley Coeffs",
            CoeffKind::MiddleBondTorsion => "MiddleBondTorsion Coeffs",
            CoeffKind::EndBondTorsion => "EndBondTorsion Coeffs",
            CoeffKind::AngleTorsion => "AngleTorsion Coeffs",
            CoeffKind::AngleAngleTorsion => "AngleAngleTorsion Coeffs",
            CoeffKind::BondBond13 => "BondBond13 Coeffs",
            CoeffKind::AngleAngle => "AngleAngle Coeffs",
        }
    }
    /// Which types the lines are for.
    pub fn type_kind(self) -> TypeKind {
        match self {
            CoeffKind::Pair | CoeffKind::PairIJ => TypeKind::Atom,
            CoeffKind::Bond => TypeKind::Bond,
            CoeffKind::Angle | CoeffKind::BondBond | CoeffKind::BondAngle | CoeffKind::UreyBradley => TypeKind::Angle,
            CoeffKind::Dihedral
            | CoeffKind::MiddleBondTorsion
            | CoeffKind::EndBondTorsion
            | CoeffKind::AngleTorsion
            | CoeffKind::AngleAngleTorsion
            | CoeffKind::BondBond13 => TypeKind::Dihedral,
            CoeffKind::Improper | CoeffKind::AngleAngle => TypeKind::Improper,
        }
    }
    /// Number of type columns at the start of a line (2 for `PairIJ Coeffs`).
    pub fn type_columns(self) -> usize {
        if self == CoeffKind::PairIJ {
            2
        } else {
            1
        }
    }
    /// The keyword LAMMPS inserts for a class2 cross-term section (`bb` for `BondBond Coeffs`...).
    pub fn class2_keyword(self) -> Option<&'static str> {
        match self {
            CoeffKind::BondBond => Some("bb"),
            CoeffKind::BondAngle => Some("ba"),
            CoeffKind::UreyBradley => Some("ub"),
            CoeffKind::MiddleBondTorsion => Some("mbt"),
            CoeffKind::EndBondTorsion => Some("ebt"),
            CoeffKind::AngleTorsion => Some("at"),
            CoeffKind::AngleAngleTorsion => Some("aat"),
            CoeffKind::BondBond13 => Some("bb13"),
            CoeffKind::AngleAngle => Some("aa"),
            _ => None,
        }
    }
    /// Coefficient sections whose `# style` comment LAMMPS writes and checks.
    fn has_style_comment(self) -> bool {
        self.class2_keyword().is_none()
    }
}

/// Which header line a span belongs to (see [`Header::span`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HeaderKey {
    Atoms,
    Bonds,
    Angles,
    Dihedrals,
    Impropers,
    Types(TypeKind),
    ExtraPerAtom(TypeKind),
    ExtraSpecialPerAtom,
    XloXhi,
    YloYhi,
    ZloZhi,
    Tilt,
}

/// The header of a data file.
#[derive(Clone, Debug, PartialEq)]
pub struct Header {
    pub atoms: usize,
    pub bonds: usize,
    pub angles: usize,
    pub dihedrals: usize,
    pub impropers: usize,
    pub atom_types: usize,
    pub bond_types: usize,
    pub angle_types: usize,
    pub dihedral_types: usize,
    pub improper_types: usize,
    /// `N extra bond per atom` etc. (0 when absent); LAMMPS uses the larger of this and the
    /// `read_data extra/bond/per/atom` keyword.
    pub extra_bond_per_atom: usize,
    pub extra_angle_per_atom: usize,
    pub extra_dihedral_per_atom: usize,
    pub extra_improper_per_atom: usize,
    pub extra_special_per_atom: usize,
    pub boxlo: [f64; 3],
    pub boxhi: [f64; 3],
    /// `xy xz yz` for a (restricted) triclinic box.
    pub tilt: Option<[f64; 3]>,
    /// The span of each header line that was present.
    pub spans: HashMap<HeaderKey, Span>,
}

impl Default for Header {
    fn default() -> Header {
        Header {
            atoms: 0,
            bonds: 0,
            angles: 0,
            dihedrals: 0,
            impropers: 0,
            atom_types: 0,
            bond_types: 0,
            angle_types: 0,
            dihedral_types: 0,
            improper_types: 0,
            extra_bond_per_atom: 0,
            extra_angle_per_atom: 0,
            extra_dihedral_per_atom: 0,
            extra_improper_per_atom: 0,
            extra_special_per_atom: 0,
            // LAMMPS' defaults when a box line is missing
            boxlo: [-0.5; 3],
            boxhi: [0.5; 3],
            tilt: None,
            spans: HashMap::new(),
        }
    }
}

impl Header {
    /// Number of types of a kind.
    pub fn types(&self, k: TypeKind) -> usize {
        match k {
            TypeKind::Atom => self.atom_types,
            TypeKind::Bond => self.bond_types,
            TypeKind::Angle => self.angle_types,
            TypeKind::Dihedral => self.dihedral_types,
            TypeKind::Improper => self.improper_types,
        }
    }
    fn types_mut(&mut self, k: TypeKind) -> &mut usize {
        match k {
            TypeKind::Atom => &mut self.atom_types,
            TypeKind::Bond => &mut self.bond_types,
            TypeKind::Angle => &mut self.angle_types,
            TypeKind::Dihedral => &mut self.dihedral_types,
            TypeKind::Improper => &mut self.improper_types,
        }
    }
    /// Number of bonds/angles/dihedrals/impropers (atoms for [`TypeKind::Atom`]).
    pub fn count(&self, k: TypeKind) -> usize {
        match k {
            TypeKind::Atom => self.atoms,
            TypeKind::Bond => self.bonds,
            TypeKind::Angle => self.angles,
            TypeKind::Dihedral => self.dihedrals,
            TypeKind::Improper => self.impropers,
        }
    }
    fn count_mut(&mut self, k: TypeKind) -> &mut usize {
        match k {
            TypeKind::Atom => &mut self.atoms,
            TypeKind::Bond => &mut self.bonds,
            TypeKind::Angle => &mut self.angles,
            TypeKind::Dihedral => &mut self.dihedrals,
            TypeKind::Improper => &mut self.impropers,
        }
    }
    /// The span of a header line, if the file had it.
    pub fn span(&self, key: HeaderKey) -> Option<Span> {
        self.spans.get(&key).copied()
    }
}

/// One `Masses` line.
#[derive(Clone, Debug, PartialEq)]
pub struct MassLine {
    pub atom_type: usize,
    pub mass: f64,
    /// The words as written (empty for a line built in code).
    pub words: Vec<Word>,
    pub span: Span,
}

impl MassLine {
    pub fn new(atom_type: usize, mass: f64) -> MassLine {
        MassLine { atom_type, mass, words: vec![], span: Span::default() }
    }
}

/// One line of a coefficient section.
#[derive(Clone, Debug, PartialEq)]
pub struct CoeffLine {
    /// The type (two for `PairIJ Coeffs`).
    pub types: Vec<usize>,
    /// The words after the type(s): coefficients, or a hybrid sub-style name and its
    /// coefficients, as the style's `*_coeff` command takes them.
    pub args: Vec<Word>,
    pub span: Span,
}

impl CoeffLine {
    /// A line built in code (for writing).
    pub fn new(types: Vec<usize>, args: &[&str]) -> CoeffLine {
        CoeffLine { types, args: args.iter().map(|a| Word::new(*a, Span::default())).collect(), span: Span::default() }
    }

    /// The arguments of the equivalent `pair_coeff` / `bond_coeff` / ... command, built as
    /// LAMMPS' `read_data` builds them: `Pair Coeffs` `i c...` becomes `i i c...`; a class2
    /// cross-term line `i c...` becomes `i kw c...` (`i style kw c...` when the second word is a
    /// hybrid sub-style name, i.e. starts with a lower-case letter).
    pub fn command_args(&self, kind: CoeffKind) -> Vec<Word> {
        let type_word = |t: usize| Word::new(t.to_string(), self.span);
        let mut out: Vec<Word> = self.types.iter().map(|t| type_word(*t)).collect();
        if kind == CoeffKind::Pair {
            out.push(type_word(self.types[0]));
        }
        match kind.class2_keyword() {
            Some(kw) => {
                let kw = Word::new(kw, self.span);
                let hybrid =
                    self.args.first().map(|w| w.text.starts_with(|c: char| c.is_ascii_lowercase())).unwrap_or(false);
                if hybrid {
                    out.push(self.args[0].clone());
                    out.push(kw);
                    out.extend(self.args[1..].iter().cloned());
                } else {
                    out.push(kw);
                    out.extend(self.args.iter().cloned());
                }
            }
            None => out.extend(self.args.iter().cloned()),
        }
        out
    }
}

/// A coefficient section and its lines.
#[derive(Clone, Debug, PartialEq)]
pub struct CoeffSection {
    pub kind: CoeffKind,
    /// The `# style` comment after the section name (e.g. `lj/cut`).
    pub style: Option<Word>,
    pub lines: Vec<CoeffLine>,
    /// The section-name line.
    pub span: Span,
}

/// One `Atoms` line. Columns the atom style does not have keep their defaults (those of a
/// LAMMPS `create_atoms`: molecule 0, q 0, diameter 1, density 1, rho 0, esph 0, cv 1).
#[derive(Clone, Debug, PartialEq)]
pub struct AtomLine {
    pub id: i64,
    pub atom_type: usize,
    pub molecule: i64,
    pub q: f64,
    pub x: [f64; 3],
    pub diameter: f64,
    pub density: f64,
    pub rho: f64,
    pub esph: f64,
    pub cv: f64,
    /// Image flags (0 0 0 when the file has none).
    pub image: [i32; 3],
    /// The words as written, in layout order, image flags included (empty for a line built in code).
    pub words: Vec<Word>,
    pub span: Span,
}

impl AtomLine {
    /// An atom with every other column at its default.
    pub fn new(id: i64, atom_type: usize, x: [f64; 3]) -> AtomLine {
        AtomLine {
            id,
            atom_type,
            molecule: 0,
            q: 0.0,
            x,
            diameter: 1.0,
            density: 1.0,
            rho: 0.0,
            esph: 0.0,
            cv: 1.0,
            image: [0; 3],
            words: vec![],
            span: Span::default(),
        }
    }

    /// The value of an `Atoms` column (integers converted to f64); None for velocity columns.
    pub fn get(&self, c: Column) -> Option<f64> {
        Some(match c {
            C::Id => self.id as f64,
            C::Type => self.atom_type as f64,
            C::Molecule => self.molecule as f64,
            C::Q => self.q,
            C::X => self.x[0],
            C::Y => self.x[1],
            C::Z => self.x[2],
            C::Diameter => self.diameter,
            C::Density => self.density,
            C::Rho => self.rho,
            C::Esph => self.esph,
            C::Cv => self.cv,
            _ => return None,
        })
    }

    /// The word a column was read from (None for a line built in code).
    pub fn word(&self, layout: &AtomLayout, c: Column) -> Option<&Word> {
        layout.atom_column(c).and_then(|i| self.words.get(i))
    }

    fn set_float(&mut self, c: Column, v: f64) {
        match c {
            C::Q => self.q = v,
            C::X => self.x[0] = v,
            C::Y => self.x[1] = v,
            C::Z => self.x[2] = v,
            C::Diameter => self.diameter = v,
            C::Density => self.density = v,
            C::Rho => self.rho = v,
            C::Esph => self.esph = v,
            C::Cv => self.cv = v,
            _ => {}
        }
    }
}

/// One `Velocities` line (omega is 0 0 0 for styles without it).
#[derive(Clone, Debug, PartialEq)]
pub struct VelocityLine {
    pub id: i64,
    pub v: [f64; 3],
    pub omega: [f64; 3],
    pub words: Vec<Word>,
    pub span: Span,
}

impl VelocityLine {
    pub fn new(id: i64, v: [f64; 3], omega: [f64; 3]) -> VelocityLine {
        VelocityLine { id, v, omega, words: vec![], span: Span::default() }
    }
    /// The value of a `Velocities` column; None for atom columns other than the id.
    pub fn get(&self, c: Column) -> Option<f64> {
        Some(match c {
            C::Id => self.id as f64,
            C::Vx => self.v[0],
            C::Vy => self.v[1],
            C::Vz => self.v[2],
            C::OmegaX => self.omega[0],
            C::OmegaY => self.omega[1],
            C::OmegaZ => self.omega[2],
            _ => return None,
        })
    }
    fn set_float(&mut self, c: Column, x: f64) {
        match c {
            C::Vx => self.v[0] = x,
            C::Vy => self.v[1] = x,
            C::Vz => self.v[2] = x,
            C::OmegaX => self.omega[0] = x,
            C::OmegaY => self.omega[1] = x,
            C::OmegaZ => self.omega[2] = x,
            _ => {}
        }
    }
}

/// One `Bonds` (N = 2), `Angles` (3), `Dihedrals` or `Impropers` (4) line.
#[derive(Clone, Debug, PartialEq)]
pub struct TopoLine<const N: usize> {
    /// The bond/angle/dihedral/improper type.
    pub topo_type: usize,
    /// Atom IDs in file order.
    pub atoms: [i64; N],
    /// The words as written; the first (the line's number) is ignored, as LAMMPS does.
    pub words: Vec<Word>,
    pub span: Span,
}

impl<const N: usize> TopoLine<N> {
    pub fn new(topo_type: usize, atoms: [i64; N]) -> TopoLine<N> {
        TopoLine { topo_type, atoms, words: vec![], span: Span::default() }
    }
}

pub type BondLine = TopoLine<2>;
pub type AngleLine = TopoLine<3>;
pub type DihedralLine = TopoLine<4>;
pub type ImproperLine = TopoLine<4>;

/// Type labels (`Atom Type Labels` ...): `labels[kind][type - 1]`, empty when the file has none.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TypeLabels {
    pub labels: [Vec<Word>; 5],
}

impl TypeLabels {
    pub fn of(&self, k: TypeKind) -> &[Word] {
        &self.labels[k.index()]
    }
    /// The type a label names.
    pub fn find(&self, k: TypeKind, label: &str) -> Option<usize> {
        self.of(k).iter().position(|w| w.text == label).map(|i| i + 1)
    }
}

/// A section a fix reads (`read_data ... fix ID NULL NAME`): its lines as words, one line per
/// atom, with each line's span.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FixSection {
    pub name: String,
    pub lines: Vec<(Span, Vec<Word>)>,
}

/// A data file: what `read_data` reads, or what `write_data` writes.
///
/// Types in every section are resolved to numbers (type labels included). Lines are in file
/// order. Counts in `header` are those the file declared; the writer writes the lengths of the
/// vectors instead.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DataFile {
    /// The first line (ignored by LAMMPS).
    pub title: String,
    pub header: Header,
    pub type_labels: TypeLabels,
    /// `Masses` lines (a later `Masses` section adds lines that override earlier ones).
    pub masses: Vec<MassLine>,
    /// Coefficient sections in file order.
    pub coeffs: Vec<CoeffSection>,
    /// The `# style` comment after `Atoms` (LAMMPS warns when it differs from the atom style).
    pub atoms_style_hint: Option<Word>,
    pub atoms: Vec<AtomLine>,
    /// The `Atoms` lines carry image flags.
    pub image_flags: bool,
    /// `Velocities` lines, if the file has the section.
    pub velocities: Option<Vec<VelocityLine>>,
    pub bonds: Vec<BondLine>,
    pub angles: Vec<AngleLine>,
    pub dihedrals: Vec<DihedralLine>,
    pub impropers: Vec<ImproperLine>,
    /// Sections read for fixes (`read_data ... fix`), in the order first met.
    pub fix_sections: Vec<FixSection>,
    /// Warnings found while reading (things LAMMPS accepts but that are probably mistakes).
    pub warnings: Vec<Diagnostic>,
}
