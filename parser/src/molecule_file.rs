//! LAMMPS molecule template files (the `molecule` command), syntax only.
//!
//! The format, as LAMMPS 22 Jul 2025 reads it (`Molecule::read`):
//! * the first line is a title and is always skipped;
//! * header lines follow (`N atoms`, `N bonds`, `N angles`, `N dihedrals`, `N impropers`,
//!   `N fragments`, `M mass`, `x y z com`, `Ixx Iyy Izz Ixy Ixz Iyz inertia`, `Ni Nd body`); `#`
//!   starts a comment and blank lines are skipped; the first other line is a section name;
//! * each section is its name, one line that is discarded (often a `#` comment naming the
//!   columns), then one line per atom (per bond, ...). Per-atom lines start with the atom's
//!   index (1..N) and each atom must appear exactly once; blank lines inside a section are
//!   errors, blank lines between sections are skipped.
//!
//! [`parse_molecule_file`] gives every value with its span, so the engine can report a bad type
//! or a missing coefficient at the line that holds it.

use crate::args::{is_lammps_float, is_lammps_integer};
use crate::data_file::read::{is_sep, split_lines, words_of, Comment, Line};
use crate::ast::Word;
use crate::diag::{DResult, Diagnostic};
use crate::span::{FileId, Span};
use crate::suggest::did_you_mean_help;

/// The sections LAMMPS knows. `Shake *` and `Body *` are recognised so that they can be refused
/// by name.
pub const SECTIONS: &[&str] = &[
    "Coords",
    "Types",
    "Molecules",
    "Fragments",
    "Charges",
    "Diameters",
    "Masses",
    "Bonds",
    "Angles",
    "Dihedrals",
    "Impropers",
    "Special Bond Counts",
    "Special Bonds",
    "Shake Flags",
    "Shake Atoms",
    "Shake Bond Types",
    "Body Integers",
    "Body Doubles",
];

/// One bond, angle, dihedral or improper: its type (before any offset) and its atoms (1-based
/// indices in the molecule).
#[derive(Clone, Debug, PartialEq)]
pub struct MolTopo<const N: usize> {
    pub typ: i64,
    pub atoms: [usize; N],
    /// The whole line.
    pub span: Span,
    /// The type word.
    pub type_span: Span,
}

/// A per-atom section: one value per atom, in atom order, and the span of each line.
#[derive(Clone, Debug, PartialEq)]
pub struct PerAtom<T> {
    pub values: Vec<T>,
    pub spans: Vec<Span>,
    /// The section name.
    pub span: Span,
}

/// A molecule file as read, before offsets and scaling.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MoleculeFile {
    /// The first line (LAMMPS prints it when it reads the file).
    pub title: String,
    pub natoms: usize,
    pub nbonds: usize,
    pub nangles: usize,
    pub ndihedrals: usize,
    pub nimpropers: usize,
    pub nfragments: usize,
    pub mass: Option<f64>,
    pub com: Option<[f64; 3]>,
    pub inertia: Option<[f64; 6]>,
    /// The `com` header line (2d files must have z = 0).
    pub com_span: Option<Span>,
    pub coords: Option<PerAtom<[f64; 3]>>,
    pub types: Option<PerAtom<i64>>,
    pub molecules: Option<PerAtom<i64>>,
    pub charges: Option<PerAtom<f64>>,
    pub diameters: Option<PerAtom<f64>>,
    pub masses: Option<PerAtom<f64>>,
    /// Fragment names and their atoms (1-based).
    pub fragments: Vec<(String, Vec<usize>)>,
    pub bonds: Vec<MolTopo<2>>,
    pub angles: Vec<MolTopo<3>>,
    pub dihedrals: Vec<MolTopo<4>>,
    pub impropers: Vec<MolTopo<4>>,
    /// `Special Bond Counts`: 1-2, 1-3, 1-4 counts per atom.
    pub special_counts: Option<PerAtom<[usize; 3]>>,
    /// `Special Bonds`: each atom's special partners (1-based), 1-2 first, then 1-3, then 1-4.
    pub specials: Option<PerAtom<Vec<usize>>>,
}

/// The words of a line up to a `#` comment.
fn words(line: &Line, file: FileId) -> Vec<Word> {
    words_of(line, file, Comment::AnyHash)
}

fn f64_of(w: &Word, what: &str) -> DResult<f64> {
    if is_lammps_float(&w.text) {
        if let Ok(x) = w.text.parse::<f64>() {
            if x.is_finite() {
                return Ok(x);
            }
        }
    }
    Err(Diagnostic::at(w.span, format!("expected {what} (a number), found `{}`", w.text), "not a number"))
}

fn i64_of(w: &Word, what: &str) -> DResult<i64> {
    if is_lammps_integer(&w.text) {
        if let Ok(x) = w.text.parse::<i64>() {
            return Ok(x);
        }
    }
    Err(Diagnostic::at(w.span, format!("expected {what} (an integer), found `{}`", w.text), "not an integer"))
}

fn count_of(w: &Word, what: &str) -> DResult<usize> {
    let n = i64_of(w, what)?;
    if !(0..=i32::MAX as i64).contains(&n) {
        return Err(Diagnostic::at(w.span, format!("invalid {what} {n} in molecule file"), "must be >= 0"));
    }
    Ok(n as usize)
}

/// An atom index of the molecule (1..=natoms).
fn atom_of(w: &Word, natoms: usize, section: &str) -> DResult<usize> {
    let n = i64_of(w, "an atom index")?;
    if n < 1 || n as u64 > natoms as u64 {
        return Err(Diagnostic::at(
            w.span,
            format!("invalid atom index {n} in the {section} section of the molecule file (the molecule has {natoms} atoms)"),
            format!("expected 1..{natoms}"),
        ));
    }
    Ok(n as usize)
}

struct Reader<'a> {
    lines: Vec<Line<'a>>,
    next: usize,
    file: FileId,
    end: Span,
}

impl<'a> Reader<'a> {
    /// The next line of a section, which must exist.
    fn section_line(&mut self, section: &str, k: usize, n: usize) -> DResult<(Vec<Word>, Span)> {
        let Some(line) = self.lines.get(self.next) else {
            return Err(Diagnostic::at(
                self.end,
                format!("unexpected end of molecule file in the {section} section: line {} of {n} is missing", k + 1),
                "file ends here",
            ));
        };
        self.next += 1;
        let span = Span::new(self.file, line.start, line.start + line.text.len());
        Ok((words(line, self.file), span))
    }

    /// Lines of a section with exactly `width` words each, `n` of them.
    fn fixed_lines(&mut self, section: &str, n: usize, width: usize, help: &str) -> DResult<Vec<(Vec<Word>, Span)>> {
        let mut out = Vec::with_capacity(n.min(1 << 20));
        for k in 0..n {
            let (w, span) = self.section_line(section, k, n)?;
            if w.len() != width {
                let what = if w.is_empty() { "a blank line".to_string() } else { format!("{} words", w.len()) };
                return Err(Diagnostic::at(span, format!("invalid line in the {section} section of the molecule file: expected {width} words, found {what}"), format!("expected {width} words"))
                    .with_help(help.to_string()));
            }
            out.push((w, span));
        }
        Ok(out)
    }

    /// A per-atom section: `n` lines, each `index value...` (width words), every atom once.
    fn per_atom<T: Clone + Default>(
        &mut self,
        section: &str,
        name_span: Span,
        natoms: usize,
        width: usize,
        help: &str,
        value: impl Fn(&[Word]) -> DResult<T>,
    ) -> DResult<PerAtom<T>> {
        let lines = self.fixed_lines(section, natoms, width, help)?;
        let mut values = vec![T::default(); natoms];
        let mut spans: Vec<Option<Span>> = vec![None; natoms];
        for (w, span) in lines {
            let i = atom_of(&w[0], natoms, section)?;
            if let Some(prev) = spans[i - 1] {
                return Err(Diagnostic::at(w[0].span, format!("atom {i} appears twice in the {section} section of the molecule file"), "repeated atom").with_label(prev, "first here"));
            }
            values[i - 1] = value(&w[1..])?;
            spans[i - 1] = Some(span);
        }
        let spans: Vec<Span> = spans.into_iter().collect::<Option<Vec<_>>>().expect("n lines, no repeats: every atom once");
        Ok(PerAtom { values, spans, span: name_span })
    }

    fn topo<const N: usize>(&mut self, section: &str, n: usize, natoms: usize, help: &str) -> DResult<Vec<MolTopo<N>>> {
        let lines = self.fixed_lines(section, n, N + 2, help)?;
        let mut out = Vec::with_capacity(n);
        for (w, span) in lines {
            i64_of(&w[0], "an ID")?;
            let typ = i64_of(&w[1], "a type")?;
            let mut atoms = [0; N];
            for k in 0..N {
                atoms[k] = atom_of(&w[2 + k], natoms, section)?;
                if atoms[..k].contains(&atoms[k]) {
                    return Err(Diagnostic::at(w[2 + k].span, format!("atom {} appears twice in one line of the {section} section of the molecule file", atoms[k]), "repeated atom"));
                }
            }
            out.push(MolTopo { typ, atoms, span, type_span: w[1].span });
        }
        Ok(out)
    }
}

/// Reads a molecule file. `what` names the file in messages.
pub fn parse_molecule_file(text: &str, file: FileId) -> DResult<MoleculeFile> {
    let lines = split_lines(text);
    let end = Span::new(file, text.len(), text.len());
    let mut m = MoleculeFile { title: lines.first().map(|l| l.text.to_string()).unwrap_or_default(), ..Default::default() };
    if lines.is_empty() {
        return Err(Diagnostic::at(end, "unexpected end of molecule file: it is empty", "empty file"));
    }
    let mut r = Reader { lines, next: 1, file, end };
    let header_help = "header lines are: `N atoms`, `N bonds`, `N angles`, `N dihedrals`, `N impropers`, `N fragments`, `M mass`, `x y z com`, `Ixx Iyy Izz Ixy Ixz Iyz inertia`";
    let mut atoms_span = None;
    // header
    let mut section: Option<(String, Span)> = None;
    while r.next < r.lines.len() {
        let line = &r.lines[r.next];
        let w = words(line, file);
        let span = Span::new(file, line.start, line.start + line.text.len());
        if w.is_empty() {
            r.next += 1;
            continue;
        }
        let has = |k: &str| w.iter().any(|x| x.text == k);
        let (nwant, key) = if has("atoms") {
            (2, "atoms")
        } else if has("bonds") {
            (2, "bonds")
        } else if has("angles") {
            (2, "angles")
        } else if has("dihedrals") {
            (2, "dihedrals")
        } else if has("impropers") {
            (2, "impropers")
        } else if has("fragments") {
            (2, "fragments")
        } else if has("mass") {
            (2, "mass")
        } else if has("com") {
            (4, "com")
        } else if has("inertia") {
            (7, "inertia")
        } else if has("body") {
            return Err(Diagnostic::at(span, "body particles (the `body` header of molecule files) are not supported", "not supported"));
        } else {
            // the first section name
            let text = line.text.split('#').next().unwrap_or("").trim_matches(is_sep).to_string();
            section = Some((text, span));
            r.next += 1;
            break;
        };
        if w.len() != nwant || w[nwant - 1].text != key {
            return Err(Diagnostic::at(span, format!("invalid header line in molecule file: `{key}` takes {} value(s) before it", nwant - 1), "invalid header").with_help(header_help));
        }
        match key {
            "atoms" => {
                m.natoms = count_of(&w[0], "atom count")?;
                atoms_span = Some(span);
            }
            "bonds" => m.nbonds = count_of(&w[0], "bond count")?,
            "angles" => m.nangles = count_of(&w[0], "angle count")?,
            "dihedrals" => m.ndihedrals = count_of(&w[0], "dihedral count")?,
            "impropers" => m.nimpropers = count_of(&w[0], "improper count")?,
            "fragments" => m.nfragments = count_of(&w[0], "fragment count")?,
            "mass" => m.mass = Some(f64_of(&w[0], "the total mass")?),
            "com" => {
                m.com = Some([f64_of(&w[0], "x")?, f64_of(&w[1], "y")?, f64_of(&w[2], "z")?]);
                m.com_span = Some(span);
            }
            _ => {
                let mut it = [0.0; 6];
                for k in 0..6 {
                    it[k] = f64_of(&w[k], "an inertia component")?;
                }
                m.inertia = Some(it);
            }
        }
        r.next += 1;
    }
    if m.natoms < 1 {
        let at = atoms_span.unwrap_or(Span::new(file, 0, r.lines[0].text.len()));
        return Err(Diagnostic::at(at, "no count or an invalid atom count in molecule file", "expected `N atoms` with N >= 1 in the header").with_help(header_help));
    }
    let natoms = m.natoms;
    let mut seen: Vec<&str> = vec![];
    while let Some((name, span)) = section.take() {
        // the line after a section name is skipped (often a comment naming the columns)
        if r.next < r.lines.len() {
            r.next += 1;
        }
        let Some(&known) = SECTIONS.iter().find(|s| **s == name) else {
            let mut d = Diagnostic::at(span, format!("unknown section `{name}` in molecule file"), "not a molecule file section");
            if let Some(h) = did_you_mean_help(&name, SECTIONS.iter().copied()) {
                d = d.with_help(h);
            }
            return Err(d.with_note(format!("the sections are: {}", SECTIONS.join(", "))));
        };
        if seen.contains(&known) {
            return Err(Diagnostic::at(span, format!("the {known} section appears twice in the molecule file"), "repeated section"));
        }
        seen.push(known);
        match known {
            "Coords" => m.coords = Some(r.per_atom(known, span, natoms, 4, "Coords line is: atom-index x y z", |w| Ok([f64_of(&w[0], "x")?, f64_of(&w[1], "y")?, f64_of(&w[2], "z")?]))?),
            "Types" => m.types = Some(r.per_atom(known, span, natoms, 2, "Types line is: atom-index type", |w| i64_of(&w[0], "an atom type"))?),
            "Molecules" => m.molecules = Some(r.per_atom(known, span, natoms, 2, "Molecules line is: atom-index molecule-ID", |w| {
                let v = i64_of(&w[0], "a molecule ID")?;
                if v <= 0 {
                    return Err(Diagnostic::at(w[0].span, format!("invalid molecule ID {v} in molecule file"), "must be >= 1"));
                }
                Ok(v)
            })?),
            "Charges" => m.charges = Some(r.per_atom(known, span, natoms, 2, "Charges line is: atom-index q", |w| f64_of(&w[0], "a charge"))?),
            "Diameters" => m.diameters = Some(r.per_atom(known, span, natoms, 2, "Diameters line is: atom-index diameter", |w| {
                let d = f64_of(&w[0], "a diameter")?;
                if d < 0.0 {
                    return Err(Diagnostic::at(w[0].span, format!("invalid atom diameter {d} in molecule file"), "must be >= 0"));
                }
                Ok(d)
            })?),
            "Masses" => m.masses = Some(r.per_atom(known, span, natoms, 2, "Masses line is: atom-index mass", |w| {
                let v = f64_of(&w[0], "a mass")?;
                if v <= 0.0 {
                    return Err(Diagnostic::at(w[0].span, format!("invalid atom mass {v} in molecule file"), "must be > 0"));
                }
                Ok(v)
            })?),
            "Fragments" => {
                if m.nfragments == 0 {
                    return Err(Diagnostic::at(span, "molecule file has a Fragments section but no `N fragments` header line", "no fragment count"));
                }
                for k in 0..m.nfragments {
                    let (w, lspan) = r.section_line(known, k, m.nfragments)?;
                    if w.is_empty() {
                        return Err(Diagnostic::at(lspan, "invalid line in the Fragments section of the molecule file: expected a name and atom indices", "blank line"));
                    }
                    let atoms = w[1..].iter().map(|x| atom_of(x, natoms, known)).collect::<DResult<Vec<_>>>()?;
                    m.fragments.push((w[0].text.clone(), atoms));
                }
            }
            "Bonds" | "Angles" | "Dihedrals" | "Impropers" => {
                let (n, what) = match known {
                    "Bonds" => (m.nbonds, "bonds"),
                    "Angles" => (m.nangles, "angles"),
                    "Dihedrals" => (m.ndihedrals, "dihedrals"),
                    _ => (m.nimpropers, "impropers"),
                };
                if n == 0 {
                    return Err(Diagnostic::at(span, format!("molecule file has a {known} section but no `N {what}` header line"), format!("no {what} count")));
                }
                match known {
                    "Bonds" => m.bonds = r.topo(known, n, natoms, "Bonds line is: ID type atom1 atom2")?,
                    "Angles" => m.angles = r.topo(known, n, natoms, "Angles line is: ID type atom1 atom2 atom3")?,
                    "Dihedrals" => m.dihedrals = r.topo(known, n, natoms, "Dihedrals line is: ID type atom1 atom2 atom3 atom4")?,
                    _ => m.impropers = r.topo(known, n, natoms, "Impropers line is: ID type atom1 atom2 atom3 atom4")?,
                }
            }
            "Special Bond Counts" => m.special_counts = Some(r.per_atom(known, span, natoms, 4, "Special Bond Counts line is: atom-index N12 N13 N14", |w| {
                Ok([count_of(&w[0], "a 1-2 count")?, count_of(&w[1], "a 1-3 count")?, count_of(&w[2], "a 1-4 count")?])
            })?),
            "Special Bonds" => {
                let Some(counts) = m.special_counts.as_ref() else {
                    return Err(Diagnostic::at(span, "the Special Bonds section must follow the Special Bond Counts section", "counts not read yet"));
                };
                let mut vals = vec![vec![]; natoms];
                let mut spans: Vec<Option<Span>> = vec![None; natoms];
                for k in 0..natoms {
                    let (w, lspan) = r.section_line(known, k, natoms)?;
                    if w.is_empty() {
                        return Err(Diagnostic::at(lspan, "invalid line in the Special Bonds section of the molecule file: a blank line", "expected atom-index partners..."));
                    }
                    let i = atom_of(&w[0], natoms, known)?;
                    if let Some(prev) = spans[i - 1] {
                        return Err(Diagnostic::at(w[0].span, format!("atom {i} appears twice in the Special Bonds section of the molecule file"), "repeated atom").with_label(prev, "first here"));
                    }
                    let want: usize = counts.values[i - 1].iter().sum();
                    if w.len() - 1 != want {
                        return Err(Diagnostic::at(lspan, format!("atom {i} has {} special partners in the Special Bonds section, but its Special Bond Counts line says {want}", w.len() - 1), format!("expected {want} partners")));
                    }
                    vals[i - 1] = w[1..].iter().map(|x| atom_of(x, natoms, known)).collect::<DResult<Vec<_>>>()?;
                    spans[i - 1] = Some(lspan);
                }
                m.specials = Some(PerAtom { values: vals, spans: spans.into_iter().map(|s| s.expect("every atom once")).collect(), span });
            }
            _ => {
                return Err(Diagnostic::at(span, format!("the {known} section of molecule files is not supported (SHAKE and body particles are not implemented)"), "not supported"));
            }
        }
        // the next section name, after blank or comment-only lines
        while r.next < r.lines.len() {
            let line = &r.lines[r.next];
            r.next += 1;
            let text = line.text.split('#').next().unwrap_or("").trim_matches(is_sep);
            if !text.is_empty() {
                section = Some((text.to_string(), Span::new(file, line.start, line.start + line.text.len())));
                break;
            }
        }
    }
    // LAMMPS' consistency checks
    let missing = |what: &str| Diagnostic::at(Span::new(file, 0, r.lines[0].text.len()), what.to_string(), "in this molecule file");
    if m.special_counts.is_some() != m.specials.is_some() {
        return Err(missing("molecule file needs both Special Bond sections (Special Bond Counts and Special Bonds)"));
    }
    if m.specials.is_some() && m.bonds.is_empty() {
        return Err(missing("molecule file has special bonds but no bonds"));
    }
    if m.nfragments > 0 && m.fragments.is_empty() {
        return Err(missing("molecule file has an `N fragments` header line but no Fragments section"));
    }
    for (n, got, what) in [(m.nbonds, m.bonds.len(), "Bonds"), (m.nangles, m.angles.len(), "Angles"), (m.ndihedrals, m.dihedrals.len(), "Dihedrals"), (m.nimpropers, m.impropers.len(), "Impropers")] {
        if n > 0 && got == 0 {
            return Err(missing(&format!("molecule file header counts {n} {} but there is no {what} section", what.to_lowercase())));
        }
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::SourceMap;

    fn parse(text: &str) -> (DResult<MoleculeFile>, SourceMap) {
        let mut sm = SourceMap::new();
        let f = sm.add("t.mol", text);
        (parse_molecule_file(text, f), sm)
    }

    const WATERISH: &str = "# three atoms\n3 atoms\n2 bonds\n1 angles\n\nCoords\n#ID x y z\n2 1.0 0.0 0.0\n1 0.0 0.0 0.0\n3 1.0 1.0 0.0  # last\n\nTypes\n\n1 1\n2 2\n3 1\n\nBonds\n\n1 1 1 2\n2 1 2 3\n\nAngles\n\n1 1 1 2 3\n";

    #[test]
    fn reads_sections_by_atom_index() {
        let (m, _) = parse(WATERISH);
        let m = m.unwrap();
        assert_eq!(m.title, "# three atoms");
        assert_eq!((m.natoms, m.nbonds, m.nangles), (3, 2, 1));
        assert_eq!(m.coords.as_ref().unwrap().values, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]);
        assert_eq!(m.types.as_ref().unwrap().values, vec![1, 2, 1]);
        assert_eq!(m.bonds.iter().map(|b| (b.typ, b.atoms)).collect::<Vec<_>>(), vec![(1, [1, 2]), (1, [2, 3])]);
        assert_eq!(m.angles[0].atoms, [1, 2, 3]);
    }

    #[test]
    fn errors_are_located() {
        let cases: &[(&str, &str, &str)] = &[
            ("t\n2 atoms\n\nCoords\n\n2 0 0 0\n2 1 0 0\n", "atom 2 appears twice", "7:1"),
            ("t\n2 atoms\n\nCoords\n\n1 0 0 0\n", "unexpected end of molecule file in the Coords section", ""),
            ("t\n2 atoms\n\nCoords\n\n1 0 0\n2 0 0 0\n", "expected 4 words, found 3 words", "6:1"),
            ("t\n2 atoms\n\nCoords\n\n1 0 0 0\n3 0 0 0\n", "invalid atom index 3", "7:1"),
            ("t\n2 atoms\n\nCoords\n\n1 0 x 0\n2 0 0 0\n", "expected y (a number), found `x`", "6:5"),
            ("t\n2 atoms\n\nCoord\n\n1 0 0 0\n", "unknown section `Coord`", "4:1"),
            ("t\n2 atoms\n\nBonds\n\n1 1 1 2\n", "no `N bonds` header line", "4:1"),
            ("t\n2 atoms\n1 bonds\n\nBonds\n\n1 1 1 1\n", "appears twice in one line", "7:7"),
            ("t\n\nCoords\n\n1 0 0 0\n", "invalid atom count", ""),
            ("t\n2 atoms 5\n", "invalid header line", "2:1"),
            ("t\n1 atoms\n\nShake Flags\n\n1 0\n", "not supported", "4:1"),
            ("t\n1 atoms\n\nSpecial Bonds\n\n1\n", "must follow the Special Bond Counts", "4:1"),
        ];
        for (text, msg, loc) in cases {
            let (r, sm) = parse(text);
            let e = r.expect_err(text);
            assert!(e.message.contains(msg), "{text:?}: {}", e.message);
            let rendered = e.render(&sm);
            assert!(rendered.contains(&format!("t.mol:{loc}")), "{text:?}: {rendered}");
        }
    }
}
