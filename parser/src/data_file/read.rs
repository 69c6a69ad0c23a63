//! Reading a data file as LAMMPS' `read_data` reads it, with located diagnostics.

use std::collections::{HashMap, HashSet};

use crate::args::{is_lammps_float, is_lammps_integer};
use crate::ast::Word;
use crate::diag::Diagnostic;
use crate::span::{FileId, Span};
use crate::suggest::did_you_mean_help;

use super::*;

/// Stop collecting errors after this many (a broken million-line file gives one screen of them).
const MAX_ERRORS: usize = 25;

const HEADER_HELP: &str = "header lines are: `N atoms`, `N atom types`, `N bonds`, `N bond types` (likewise angles, dihedrals, impropers), `N extra bond per atom`, `XLO XHI xlo xhi`, `YLO YHI ylo yhi`, `ZLO ZHI zlo zhi`, `XY XZ YZ xy xz yz`";

/// Header keywords after the count, for suggestions.
const HEADER_KEYWORDS: &[&str] = &[
    "atoms",
    "bonds",
    "angles",
    "dihedrals",
    "impropers",
    "atom types",
    "bond types",
    "angle types",
    "dihedral types",
    "improper types",
    "extra bond per atom",
    "extra angle per atom",
    "extra dihedral per atom",
    "extra improper per atom",
    "extra special per atom",
    "xlo xhi",
    "ylo yhi",
    "zlo zhi",
    "xy xz yz",
];

/// The sections of a data file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Section {
    Atoms,
    Velocities,
    Masses,
    Coeffs(CoeffKind),
    Topology(TypeKind),
    TypeLabels(TypeKind),
    /// Ellipsoids, Lines, Triangles, Bodies: sections of atom styles dmhs does not support.
    Bonus(&'static str),
    /// A section `read_data ... fix ID NULL NAME` gives to a fix: the index of its name.
    Fix(usize),
}

const BONUS_SECTIONS: [&str; 4] = ["Ellipsoids", "Lines", "Triangles", "Bodies"];

fn section_names() -> Vec<&'static str> {
    let mut v = vec!["Atoms", "Velocities", "Masses", "Bonds", "Angles", "Dihedrals", "Impropers"];
    v.extend(CoeffKind::ALL.iter().map(|k| k.section_name()));
    v.extend([
        "Atom Type Labels",
        "Bond Type Labels",
        "Angle Type Labels",
        "Dihedral Type Labels",
        "Improper Type Labels",
    ]);
    v.extend(BONUS_SECTIONS);
    v
}

/// A section name of LAMMPS' own (which a fix's section may not take).
pub fn is_section_name(name: &str) -> bool {
    section_from_name(name).is_some()
}

fn section_from_name(name: &str) -> Option<Section> {
    Some(match name {
        "Atoms" => Section::Atoms,
        "Velocities" => Section::Velocities,
        "Masses" => Section::Masses,
        "Bonds" => Section::Topology(TypeKind::Bond),
        "Angles" => Section::Topology(TypeKind::Angle),
        "Dihedrals" => Section::Topology(TypeKind::Dihedral),
        "Impropers" => Section::Topology(TypeKind::Improper),
        _ => {
            if let Some(k) = CoeffKind::ALL.iter().find(|k| k.section_name() == name) {
                return Some(Section::Coeffs(*k));
            }
            if let Some(k) = TypeKind::ALL.iter().find(|k| format!("{} Type Labels", k.title()) == name) {
                return Some(Section::TypeLabels(*k));
            }
            return BONUS_SECTIONS.iter().find(|b| **b == name).map(|b| Section::Bonus(b));
        }
    })
}

fn topo_section_name(k: TypeKind) -> &'static str {
    match k {
        TypeKind::Atom => "Atoms",
        TypeKind::Bond => "Bonds",
        TypeKind::Angle => "Angles",
        TypeKind::Dihedral => "Dihedrals",
        TypeKind::Improper => "Impropers",
    }
}

fn topo_help(k: TypeKind) -> String {
    let n = topo_width(k);
    let atoms: Vec<String> = (1..=n).map(|i| format!("atom{i}")).collect();
    format!("{} line is: {}-ID {}-type {}", topo_section_name(k), k.name(), k.name(), atoms.join(" "))
}

fn topo_width(k: TypeKind) -> usize {
    match k {
        TypeKind::Atom => 1,
        TypeKind::Bond => 2,
        TypeKind::Angle => 3,
        TypeKind::Dihedral | TypeKind::Improper => 4,
    }
}

/// One line of the file.
pub(crate) struct Line<'a> {
    /// Byte offset of the line's start.
    pub(crate) start: usize,
    /// The text without its line end.
    pub(crate) text: &'a str,
}

pub(crate) fn split_lines(text: &str) -> Vec<Line<'_>> {
    let mut out = vec![];
    let mut start = 0;
    for piece in text.split_inclusive('\n') {
        let t = piece.strip_suffix('\n').unwrap_or(piece);
        let t = t.strip_suffix('\r').unwrap_or(t);
        out.push(Line { start, text: t });
        start += piece.len();
    }
    out
}

/// LAMMPS' word separators (its `Tokenizer` default).
pub(crate) fn is_sep(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\r' | '\n' | '\x0c')
}

/// How a data line's comment is found: LAMMPS cuts at the first `#` in some sections
/// (`Velocities`, coefficients, header) and at the first word starting with `#` in others
/// (`Atoms`, `Masses`, `Bonds`, ...), so `1.0#x` is an error only in the latter; a fix's section
/// keeps every word (fix property/atom's reader strips no comment).
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Comment {
    AnyHash,
    HashWord,
    None,
}

pub(crate) fn words_of(line: &Line, file: FileId, comment: Comment) -> Vec<Word> {
    let text = match comment {
        Comment::AnyHash => line.text.split('#').next().unwrap_or(""),
        Comment::HashWord | Comment::None => line.text,
    };
    let mut out = vec![];
    let mut i = 0;
    let b = text.as_bytes();
    while i < b.len() {
        while i < b.len() && is_sep(b[i] as char) {
            i += 1;
        }
        if i >= b.len() {
            break;
        }
        let s = i;
        while i < b.len() && !is_sep(b[i] as char) {
            i += 1;
        }
        let w = &text[s..i];
        if comment == Comment::HashWord && w.starts_with('#') {
            break;
        }
        out.push(Word::new(w, Span::new(file, line.start + s, line.start + i)));
    }
    out
}

/// Blank, or a comment only (LAMMPS skips such lines between sections).
fn is_blank_or_comment(text: &str) -> bool {
    let t = text.trim_start_matches(is_sep);
    t.is_empty() || t.starts_with('#')
}

fn parse_f64(w: &Word) -> Option<f64> {
    if !is_lammps_float(&w.text) {
        return None;
    }
    w.text.parse::<f64>().ok().filter(|x| x.is_finite())
}

fn parse_i64(w: &Word) -> Option<i64> {
    if !is_lammps_integer(&w.text) {
        return None;
    }
    w.text.parse::<i64>().ok()
}

/// An integer too large for i64 (as i64::MAX, to be refused as too large by the caller).
fn too_large_integer(w: &Word) -> Option<i64> {
    (is_lammps_integer(&w.text) && !w.text.starts_with('-')).then_some(i64::MAX)
}

/// Reads a data file for an atom style.
///
/// `Err` holds located diagnostics with help lines, in file order: every error the file
/// allows to find (at most 25, then a note), and the warnings found on the way. On success
/// the warnings are in [`DataFile::warnings`].
pub fn parse_data_file(text: &str, file: FileId, layout: &AtomLayout) -> Result<DataFile, Vec<Diagnostic>> {
    parse_data_file_with(text, file, layout, &[])
}

/// [`parse_data_file`] with the section names that `read_data ... fix ID NULL NAME` gives to
/// fixes (LAMMPS looks for them before its own section names): their lines, one per atom, are
/// kept as words in [`DataFile::fix_sections`].
pub fn parse_data_file_with(text: &str, file: FileId, layout: &AtomLayout, fix_sections: &[String]) -> Result<DataFile, Vec<Diagnostic>> {
    let mut r = Reader {
        fix_names: fix_sections.to_vec(),
        lines: split_lines(text),
        file,
        layout,
        errors: vec![],
        df: DataFile::default(),
        seen: HashSet::new(),
        type_sections_seen: false,
        max_atom_id: 0,
        atom_index: HashMap::new(),
        atoms_incomplete: false,
        velocity_ids: HashMap::new(),
        section_spans: HashMap::new(),
        first_atom_line_done: false,
    };
    r.run();
    if r.errors.is_empty() {
        return Ok(r.df);
    }
    let too_many = r.errors.len() > MAX_ERRORS;
    r.errors.truncate(MAX_ERRORS);
    // the warnings found so far often explain the errors (e.g. a header line read as the title)
    let mut all = std::mem::take(&mut r.df.warnings);
    all.append(&mut r.errors);
    all.sort_by_key(|d| d.primary_span().map(|s| s.lo).unwrap_or(u32::MAX));
    if too_many {
        all.push(Diagnostic::error(format!("too many errors in the data file; only the first {MAX_ERRORS} are shown")));
    }
    Err(all)
}

struct Reader<'a> {
    /// Section names that fixes read (`read_data ... fix`).
    fix_names: Vec<String>,
    lines: Vec<Line<'a>>,
    file: FileId,
    layout: &'a AtomLayout,
    errors: Vec<Diagnostic>,
    df: DataFile,
    /// Sections read so far.
    seen: HashSet<Section>,
    /// A section that uses types (Masses, coefficients) was read: type labels must come first.
    type_sections_seen: bool,
    max_atom_id: i64,
    /// Atom ID -> index in `df.atoms`.
    atom_index: HashMap<i64, usize>,
    /// The Atoms section had errors: a missing atom ID elsewhere is not a new error.
    atoms_incomplete: bool,
    /// Velocity atom ID -> span of its first line.
    velocity_ids: HashMap<i64, Span>,
    section_spans: HashMap<Section, Span>,
    /// The first Atoms line was read (it decides whether lines carry image flags).
    first_atom_line_done: bool,
}

impl<'a> Reader<'a> {
    fn err(&mut self, d: Diagnostic) {
        // keep one past the limit so the caller knows there were more
        if self.errors.len() <= MAX_ERRORS {
            self.errors.push(d);
        }
    }
    fn warn(&mut self, d: Diagnostic) {
        let mut d = d;
        d.severity = crate::diag::Severity::Warning;
        self.df.warnings.push(d);
    }
    fn line_span(&self, i: usize) -> Span {
        let l = &self.lines[i];
        let lead = l.text.len() - l.text.trim_start_matches(is_sep).len();
        let trimmed = l.text.trim_end_matches(is_sep);
        Span::new(self.file, l.start + lead.min(trimmed.len()), l.start + trimmed.len())
    }
    /// A point just past the end of the file (for "unexpected end of file").
    fn eof_span(&self) -> Span {
        let end = self.lines.last().map(|l| l.start + l.text.len()).unwrap_or(0);
        Span::new(self.file, end, end)
    }

    fn run(&mut self) {
        if self.lines.is_empty() {
            self.err(
                Diagnostic::at(Span::new(self.file, 0, 0), "the data file is empty", "expected a title line")
                    .with_help("a data file starts with a title line, then header lines such as `N atoms`"),
            );
            return;
        }
        self.df.title = self.lines[0].text.to_string();
        if self.header_line_kind(0).is_some() {
            let span = self.line_span(0);
            self.warn(
                Diagnostic::at(span, "the first line of a data file is its title and is ignored", "read as the title")
                    .with_help("start the file with a title line"),
            );
        }
        let errors_before = self.errors.len();
        let first_section = self.header();
        if self.errors.len() > errors_before {
            // every section's length comes from the header: reading on would only add noise
            return;
        }
        self.header_checks();
        let mut pos = first_section;
        while let Some(i) = pos {
            pos = self.section(i);
        }
        self.final_checks();
    }

    // ----- header ------------------------------------------------------------------------

    /// Recognizes a header line: (key, number of leading value words).
    fn header_line_kind(&self, i: usize) -> Option<(HeaderKey, usize)> {
        let words = words_of(&self.lines[i], self.file, Comment::AnyHash);
        let t: Vec<&str> = words.iter().map(|w| w.text.as_str()).collect();
        header_key(&t)
    }

    /// Reads header lines from line 1; returns the index of the first section line.
    fn header(&mut self) -> Option<usize> {
        let mut i = 1;
        while i < self.lines.len() {
            let words = words_of(&self.lines[i], self.file, Comment::AnyHash);
            if words.is_empty() {
                i += 1;
                continue;
            }
            let t: Vec<&str> = words.iter().map(|w| w.text.as_str()).collect();
            match header_key(&t) {
                Some((key, nvalues)) => {
                    self.header_values(key, &words[..nvalues], words[0].span.to(words[words.len() - 1].span))
                }
                None => {
                    if self.general_triclinic(&words) {
                        i += 1;
                        continue;
                    }
                    // a section name ends the header; anything else starting with a number is a
                    // header line LAMMPS does not know
                    let name = section_keyword(self.lines[i].text).0;
                    let header_like = looks_numeric(&words[0].text) || box_values(&t).is_some();
                    if self.section_of(name).is_some() || !header_like {
                        return Some(i);
                    }
                    self.bad_header_line(&words);
                }
            }
            i += 1;
        }
        None
    }

    fn general_triclinic(&mut self, words: &[Word]) -> bool {
        let t: Vec<&str> = words.iter().map(|w| w.text.as_str()).collect();
        let vec_line = t.len() >= 4 && matches!(t[3], "avec" | "bvec" | "cvec");
        let origin = t.len() >= 5 && t[3] == "abc" && t[4] == "origin";
        if (vec_line || origin) && t[..3].iter().all(|w| looks_numeric(w)) {
            let span = words[0].span.to(words[words.len() - 1].span);
            self.err(Diagnostic::at(span, "general triclinic boxes (avec bvec cvec abc origin) are not supported by dmhs", "not supported")
                .with_help("describe the box as a restricted triclinic box: `xlo xhi`, `ylo yhi`, `zlo zhi` and `xy xz yz` lines"));
            return true;
        }
        false
    }

    fn bad_header_line(&mut self, words: &[Word]) {
        let span = words[0].span.to(words[words.len() - 1].span);
        let rest: Vec<&str> = words[1..].iter().map(|w| w.text.as_str()).collect();
        let rest = rest.join(" ");
        // a box line with a bad number
        let t: Vec<&str> = words.iter().map(|w| w.text.as_str()).collect();
        if let Some(n) = box_values(&t) {
            for w in words[..n].iter().filter(|w| parse_f64(w).is_none()) {
                self.err(
                    Diagnostic::at(
                        w.span,
                        format!("expected a number for the box, found `{}`", w.text),
                        "not a number",
                    )
                    .with_help(HEADER_HELP),
                );
            }
            return;
        }
        // a known keyword with a bad count (`3.0 atoms`, `-1 atoms`, `x atoms`)
        let known = HEADER_KEYWORDS.iter().any(|k| rest.starts_with(k) && !k.contains("lo ") && *k != "xy xz yz");
        if known {
            self.err(
                Diagnostic::at(
                    words[0].span,
                    format!("expected a non-negative integer count, found `{}`", words[0].text),
                    "not a count",
                )
                .with_help(HEADER_HELP),
            );
            return;
        }
        let mut d = Diagnostic::at(
            span,
            format!("unknown header line `{}`", words.iter().map(|w| w.text.as_str()).collect::<Vec<_>>().join(" ")),
            "not a header line",
        );
        if let Some(h) = did_you_mean_help(&rest, HEADER_KEYWORDS.iter().copied()) {
            d = d.with_help(h);
        }
        self.err(d.with_help(HEADER_HELP));
    }

    fn header_values(&mut self, key: HeaderKey, values: &[Word], span: Span) {
        self.df.header.spans.insert(key, span);
        let count = |r: &mut Reader, w: &Word| -> Option<usize> {
            // LAMMPS reads counts as 64-bit integers (types as 32-bit)
            let ok = w.text.parse::<i64>().ok().filter(|n| *n >= 0);
            if ok.is_none() {
                r.err(Diagnostic::at(w.span, format!("count `{}` is out of range", w.text), "out of range"));
            }
            ok.map(|n| n as usize)
        };
        match key {
            HeaderKey::Atoms | HeaderKey::Bonds | HeaderKey::Angles | HeaderKey::Dihedrals | HeaderKey::Impropers => {
                if let Some(n) = count(self, &values[0]) {
                    let k = match key {
                        HeaderKey::Atoms => TypeKind::Atom,
                        HeaderKey::Bonds => TypeKind::Bond,
                        HeaderKey::Angles => TypeKind::Angle,
                        HeaderKey::Dihedrals => TypeKind::Dihedral,
                        _ => TypeKind::Improper,
                    };
                    *self.df.header.count_mut(k) = n;
                }
            }
            HeaderKey::Types(k) => {
                if let Some(n) = count(self, &values[0]) {
                    if n > super::MAX_TYPES {
                        self.err(Diagnostic::at(
                            values[0].span,
                            format!("too many {} types: {n}; dmhs accepts at most {} (it keeps tables per type and per pair of types)", k.name(), super::MAX_TYPES),
                            "out of range",
                        ));
                    } else {
                        *self.df.header.types_mut(k) = n;
                    }
                }
            }
            HeaderKey::ExtraPerAtom(k) => {
                if let Some(n) = self.extra_value(&values[0]) {
                    let h = &mut self.df.header;
                    match k {
                        TypeKind::Bond => h.extra_bond_per_atom = n,
                        TypeKind::Angle => h.extra_angle_per_atom = n,
                        TypeKind::Dihedral => h.extra_dihedral_per_atom = n,
                        _ => h.extra_improper_per_atom = n,
                    }
                }
            }
            HeaderKey::ExtraSpecialPerAtom => {
                if let Some(n) = self.extra_value(&values[0]) {
                    self.df.header.extra_special_per_atom = n;
                }
            }
            HeaderKey::XloXhi | HeaderKey::YloYhi | HeaderKey::ZloZhi => {
                let d = match key {
                    HeaderKey::XloXhi => 0,
                    HeaderKey::YloYhi => 1,
                    _ => 2,
                };
                let lo = self.float_value(&values[0], "box bound");
                let hi = self.float_value(&values[1], "box bound");
                if let (Some(lo), Some(hi)) = (lo, hi) {
                    self.df.header.boxlo[d] = lo;
                    self.df.header.boxhi[d] = hi;
                }
            }
            HeaderKey::Tilt => {
                let v: Vec<Option<f64>> = values.iter().map(|w| self.float_value(w, "tilt factor")).collect();
                if let [Some(a), Some(b), Some(c)] = v[..] {
                    self.df.header.tilt = Some([a, b, c]);
                }
            }
        }
    }

    fn extra_value(&mut self, w: &Word) -> Option<usize> {
        match parse_i64(w) {
            Some(n) if n >= 0 && n <= i32::MAX as i64 => Some(n as usize),
            _ => {
                self.err(
                    Diagnostic::at(
                        w.span,
                        format!("expected a non-negative integer, found `{}`", w.text),
                        "not a count",
                    )
                    .with_help(HEADER_HELP),
                );
                None
            }
        }
    }

    fn float_value(&mut self, w: &Word, what: &str) -> Option<f64> {
        let v = parse_f64(w);
        if v.is_none() {
            self.err(
                Diagnostic::at(w.span, format!("expected a number for the {what}, found `{}`", w.text), "not a number")
                    .with_help(HEADER_HELP),
            );
        }
        v
    }

    /// Checks on the header as a whole (LAMMPS does them before reading any section).
    fn header_checks(&mut self) {
        let h = self.df.header.clone();
        let file = self.file;
        let at = |key: HeaderKey| h.span(key).unwrap_or_else(|| Span::new(file, 0, 0));
        for k in [TypeKind::Bond, TypeKind::Angle, TypeKind::Dihedral, TypeKind::Improper] {
            let key = header_count_key(k);
            if (h.count(k) > 0 || h.types(k) > 0) && !self.layout.allows(k) {
                let span = h.span(key).or(h.span(HeaderKey::Types(k))).unwrap_or_default();
                self.err(Diagnostic::at(span, format!("no {}s allowed with atom_style {}", k.name(), self.layout.style_label()), format!("atom_style {} has no {}s", self.layout.style_label(), k.name()))
                    .with_help("use an atom style with molecular topology (bond, angle, molecular, full, or hybrid with one of them)"));
            } else if h.count(k) > 0 && h.types(k) == 0 {
                self.err(
                    Diagnostic::at(
                        at(key),
                        format!("{}s defined but no {} types", k.name(), k.name()),
                        format!("needs an `N {} types` line", k.name()),
                    )
                    .with_help(format!("add a header line `N {} types`", k.name())),
                );
            }
        }
        for (d, key) in [HeaderKey::XloXhi, HeaderKey::YloYhi, HeaderKey::ZloZhi].into_iter().enumerate() {
            let axis = ["x", "y", "z"][d];
            match h.span(key) {
                None if d < 2 => {
                    self.err(Diagnostic::at(Span::new(self.file, 0, 0), format!("the data file has no `{axis}lo {axis}hi` line"), "box bounds missing")
                        .with_help(format!("add a header line `{axis}lo {axis}hi {axis}lo {axis}hi` with the box bounds (LAMMPS would silently use -0.5 0.5)")));
                }
                None => {
                    self.warn(Diagnostic::warning(
                        "the data file has no `zlo zhi` line; the z bounds are -0.5 0.5 (as in LAMMPS)",
                    ));
                }
                Some(span) if h.boxlo[d] >= h.boxhi[d] => {
                    let msg = format!(
                        "box bounds are invalid: {axis}lo {} must be below {axis}hi {}",
                        h.boxlo[d], h.boxhi[d]
                    );
                    self.err(Diagnostic::at(span, msg, "lo >= hi"));
                }
                Some(span) if !(h.boxhi[d] - h.boxlo[d]).is_finite() => {
                    let msg = format!(
                        "box bounds are invalid: the length {axis}hi - {axis}lo = {} - ({}) overflows a double",
                        h.boxhi[d], h.boxlo[d]
                    );
                    self.err(Diagnostic::at(span, msg, "box too large"));
                }
                Some(_) => {}
            }
        }
    }

    // ----- sections ----------------------------------------------------------------------

    /// The section a name starts: a fix's first, as LAMMPS' read_data checks them first.
    fn section_of(&self, name: &str) -> Option<Section> {
        match self.fix_names.iter().position(|f| f == name) {
            Some(k) => Some(Section::Fix(k)),
            None => section_from_name(name),
        }
    }

    /// Reads the section whose name is on line `i` (or skips blank lines to it); returns the
    /// line where the next section name is expected.
    fn section(&mut self, i: usize) -> Option<usize> {
        // skip blank and comment lines (LAMMPS' parse_keyword)
        let mut i = i;
        while i < self.lines.len() && is_blank_or_comment(self.lines[i].text) {
            i += 1;
        }
        if i >= self.lines.len() {
            return None;
        }
        let (name, hint) = section_keyword(self.lines[i].text);
        let name_span = self.keyword_span(i, name);
        let Some(section) = self.section_of(name) else {
            self.unknown_section(i, name, name_span);
            return self.next_section_line(i + 1);
        };
        let hint_word = hint.map(|(h, off)| {
            Word::new(h, Span::new(self.file, self.lines[i].start + off, self.lines[i].start + off + h.len()))
        });
        self.section_spans.entry(section).or_insert(name_span);

        let count = self.section_line_count(section);
        // the line after the name is discarded by LAMMPS: it must be blank
        let mut body = i + 1;
        if body < self.lines.len() {
            if is_blank_or_comment(self.lines[body].text) {
                body += 1;
            } else {
                let span = self.line_span(body);
                self.err(
                    Diagnostic::at(span, format!("expected a blank line after `{name}`"), "LAMMPS skips this line")
                        .with_help("a section is its name, one blank line, then its lines"),
                );
            }
        }
        if !self.section_allowed(section, name, name_span, count) {
            // skip its lines so that the next section is still read
            return self.skip_body(body, count);
        }
        match section {
            Section::Atoms => {
                self.check_style_hint(hint_word.as_ref());
                self.df.atoms_style_hint = hint_word;
            }
            Section::Coeffs(kind) => {
                self.df.coeffs.push(CoeffSection { kind, style: hint_word, lines: vec![], span: name_span })
            }
            Section::Masses => self.type_sections_seen = true,
            _ => {}
        }
        if let Section::Coeffs(_) = section {
            self.type_sections_seen = true;
        }
        self.seen.insert(section);
        self.section_body(section, name, name_span, body, count)
    }

    /// LAMMPS warns when the `# style` after `Atoms` is not the atom style.
    fn check_style_hint(&mut self, hint: Option<&Word>) {
        let Some(h) = hint else { return };
        if h.text != self.layout.style {
            let msg = format!(
                "the Atoms section says atom_style {}, but the atom style is {}",
                h.text,
                self.layout.style_label()
            );
            let d = Diagnostic::at(h.span, msg, "differs from the atom style").with_help(self.layout.atoms_help());
            self.warn(d);
        }
    }

    /// Reads the `count` lines of a section starting at line `body`; returns the line after them.
    fn section_body(
        &mut self,
        section: Section,
        name: &str,
        name_span: Span,
        body: usize,
        count: usize,
    ) -> Option<usize> {
        let mut read = 0;
        let mut j = body;
        let mut stray_blank_reported = false;
        while read < count {
            if j >= self.lines.len() {
                self.short_section(section, name, name_span, read, None);
                return None;
            }
            let text = self.lines[j].text;
            let is_name = |t: &str| self.section_of(section_keyword(t).0).is_some();
            if is_blank_or_comment(text) || is_name(text) {
                // a stray blank line with more data after it, or the end of a short section
                let next = (j + 1..self.lines.len()).find(|&k| !is_blank_or_comment(self.lines[k].text));
                let data_follows = !is_name(text) && next.is_some_and(|k| !is_name(self.lines[k].text));
                if !data_follows {
                    self.short_section(section, name, name_span, read, Some(j));
                    return Some(j);
                }
                if !stray_blank_reported {
                    let span = Span::new(self.file, self.lines[j].start, self.lines[j].start + text.len().max(1));
                    let d = Diagnostic::at(
                        span,
                        format!("blank or comment line inside the {name} section"),
                        "LAMMPS counts this as a line",
                    )
                    .with_help(format!(
                        "LAMMPS reads exactly {count} lines after `{name}` and its blank line; remove this line"
                    ));
                    self.err(d);
                    stray_blank_reported = true;
                }
                j += 1;
                continue;
            }
            self.section_line(section, j);
            read += 1;
            j += 1;
        }
        Some(j)
    }

    fn keyword_span(&self, i: usize, name: &str) -> Span {
        let l = &self.lines[i];
        let off = l.text.find(name).unwrap_or(0);
        Span::new(self.file, l.start + off, l.start + off + name.len().max(1))
    }

    fn unknown_section(&mut self, i: usize, name: &str, span: Span) {
        let first = name.split(is_sep).next().unwrap_or("");
        if looks_numeric(first) {
            // data where a section name belongs: a section with more lines than the header says
            if let Some((sec, sec_span)) = self.last_counted_section(i) {
                if sec == Section::Atoms {
                    self.atoms_incomplete = true;
                }
                let (what, key) = section_count_words(sec, &self.df.header);
                let mut d = Diagnostic::at(
                    self.line_span(i),
                    format!(
                        "the {sec_name} section has more lines than the header says ({what})",
                        sec_name = section_label(sec)
                    ),
                    "one line too many",
                );
                if let Some(k) = key.and_then(|k| self.df.header.span(k)) {
                    d = d.with_label(k, "the header's count");
                }
                d = d.with_label(sec_span, "section starts here");
                self.err(d.with_help("make the header count match the number of lines"));
                return;
            }
        }
        let mut d = Diagnostic::at(span, format!("unknown section `{name}` in data file"), "not a section name");
        if let Some(h) = did_you_mean_help(name, section_names()) {
            d = d.with_help(h);
        }
        self.err(d.with_help(format!("sections are: {}", section_names().join(", "))));
    }

    /// The counted section just before line `i`, if only blank lines separate them.
    fn last_counted_section(&self, i: usize) -> Option<(Section, Span)> {
        // walk back over data lines to the section name
        let mut k = i;
        while k > 0 {
            k -= 1;
            let text = self.lines[k].text;
            if is_blank_or_comment(text) {
                // the blank line after a section name, or the gap after its lines
                continue;
            }
            if let Some(s) = self.section_of(section_keyword(text).0) {
                return self.section_spans.get(&s).map(|sp| (s, *sp));
            }
        }
        None
    }

    /// First line at or after `from` that names a section.
    fn next_section_line(&self, from: usize) -> Option<usize> {
        (from..self.lines.len()).find(|&k| self.section_of(section_keyword(self.lines[k].text).0).is_some())
    }

    fn skip_body(&self, body: usize, count: usize) -> Option<usize> {
        let end = body + count;
        if end >= self.lines.len() {
            None
        } else {
            Some(end)
        }
    }

    fn short_section(&mut self, section: Section, name: &str, name_span: Span, read: usize, at: Option<usize>) {
        if section == Section::Atoms {
            self.atoms_incomplete = true;
        }
        let (what, key) = section_count_words(section, &self.df.header);
        let span = match at {
            Some(j) => Span::new(self.file, self.lines[j].start, self.lines[j].start + self.lines[j].text.len().max(1)),
            None => self.eof_span(),
        };
        let label = if at.is_some() { "section ends here" } else { "end of file" };
        let mut d = Diagnostic::at(
            span,
            format!(
                "the {name} section has {read} line{} but the header says {what}",
                if read == 1 { "" } else { "s" }
            ),
            label,
        )
        .with_label(name_span, "section starts here");
        if let Some(k) = key.and_then(|k| self.df.header.span(k)) {
            d = d.with_label(k, "the header's count");
        }
        self.err(d.with_help(
            "make the header count match the number of lines (blank lines inside a section count as lines)",
        ));
    }

    /// How many lines a section has, from the header.
    fn section_line_count(&self, s: Section) -> usize {
        let h = &self.df.header;
        match s {
            Section::Atoms | Section::Velocities => h.atoms,
            Section::Masses => h.atom_types,
            Section::Coeffs(CoeffKind::PairIJ) => h.atom_types * (h.atom_types + 1) / 2,
            Section::Coeffs(k) => h.types(k.type_kind()),
            Section::Topology(k) => h.count(k),
            Section::TypeLabels(k) => h.types(k),
            Section::Bonus(_) => 0,
            Section::Fix(_) => h.atoms,
        }
    }

    /// LAMMPS' checks on a section before it reads its lines.
    fn section_allowed(&mut self, s: Section, name: &str, span: Span, count: usize) -> bool {
        let style = self.layout.style_label();
        let fail = |r: &mut Reader, msg: String, label: &str, help: String| {
            r.err(Diagnostic::at(span, msg, label).with_help(help));
            false
        };
        match s {
            Section::Bonus(b) => fail(
                self,
                format!("invalid data file section {b}: atom_style {style} has no {}", b.to_lowercase()),
                "not allowed",
                "Ellipsoids, Lines, Triangles and Bodies belong to atom styles dmhs does not support".into(),
            ),
            Section::Atoms if self.seen.contains(&s) => {
                fail(self, "a second Atoms section".into(), "repeated", "a data file has one Atoms section".into())
            }
            Section::Velocities if self.seen.contains(&s) => fail(
                self,
                "a second Velocities section".into(),
                "repeated",
                "a data file has one Velocities section".into(),
            ),
            Section::Velocities if !self.seen.contains(&Section::Atoms) => fail(
                self,
                "the Velocities section comes before the Atoms section".into(),
                "must come after Atoms",
                "LAMMPS reads Atoms before Velocities".into(),
            ),
            Section::Topology(k) => {
                if !self.layout.allows(k) || count == 0 {
                    let why = if !self.layout.allows(k) {
                        format!("atom_style {style} has no {}s", k.name())
                    } else {
                        format!("the header declares no {}s", k.name())
                    };
                    fail(
                        self,
                        format!("invalid data file section {name}: {why}"),
                        "not allowed",
                        format!("add `N {}s` to the header, with an atom style that has them", k.name()),
                    )
                } else if self.seen.contains(&s) {
                    fail(
                        self,
                        format!("a second {name} section"),
                        "repeated",
                        format!("a data file has one {name} section"),
                    )
                } else if !self.seen.contains(&Section::Atoms) {
                    fail(
                        self,
                        format!("the {name} section comes before the Atoms section"),
                        "must come after Atoms",
                        format!("LAMMPS reads Atoms before {name}"),
                    )
                } else {
                    true
                }
            }
            Section::Masses if !self.layout.per_type_mass => fail(
                self,
                format!("atom_style {style} has per-atom masses: a Masses section is not allowed"),
                "not allowed",
                "the mass of each particle comes from its diameter and density in the Atoms section".into(),
            ),
            Section::Coeffs(k) if !self.layout.allows(k.type_kind()) => fail(
                self,
                format!("invalid data file section {name}: atom_style {style} has no {}s", k.type_kind().name()),
                "not allowed",
                format!("{name} need an atom style with {}s", k.type_kind().name()),
            ),
            Section::TypeLabels(k) => {
                if self.type_sections_seen {
                    fail(
                        self,
                        format!("{name} must come before Masses and coefficient sections"),
                        "too late",
                        "LAMMPS reads type labels before any section that uses types".into(),
                    )
                } else if self.seen.contains(&Section::Atoms) && k == TypeKind::Atom
                    || self.seen.contains(&Section::Topology(k)) && k != TypeKind::Atom
                {
                    fail(
                        self,
                        format!("{name} must come before the {} section", topo_section_name(k)),
                        "too late",
                        "LAMMPS reads type labels before the lines that use them".into(),
                    )
                } else {
                    true
                }
            }
            _ => true,
        }
    }

    fn section_line(&mut self, s: Section, j: usize) {
        match s {
            Section::Atoms => self.atom_line(j),
            Section::Velocities => self.velocity_line(j),
            Section::Masses => self.mass_line(j),
            Section::Coeffs(k) => self.coeff_line(k, j),
            Section::Topology(TypeKind::Bond) => {
                if let Some(t) = self.topo_line::<2>(TypeKind::Bond, j) {
                    self.df.bonds.push(t)
                }
            }
            Section::Topology(TypeKind::Angle) => {
                if let Some(t) = self.topo_line::<3>(TypeKind::Angle, j) {
                    self.df.angles.push(t)
                }
            }
            Section::Topology(TypeKind::Dihedral) => {
                if let Some(t) = self.topo_line::<4>(TypeKind::Dihedral, j) {
                    self.df.dihedrals.push(t)
                }
            }
            Section::Topology(TypeKind::Improper) => {
                if let Some(t) = self.topo_line::<4>(TypeKind::Improper, j) {
                    self.df.impropers.push(t)
                }
            }
            Section::Topology(TypeKind::Atom) | Section::Bonus(_) => {}
            Section::TypeLabels(k) => self.label_line(k, j),
            Section::Fix(k) => {
                let words = words_of(&self.lines[j], self.file, Comment::None);
                let span = self.line_span(j);
                let name = &self.fix_names[k];
                let sec = match self.df.fix_sections.iter_mut().find(|s| &s.name == name) {
                    Some(s) => s,
                    None => {
                        self.df.fix_sections.push(FixSection { name: name.clone(), lines: vec![] });
                        self.df.fix_sections.last_mut().expect("pushed")
                    }
                };
                sec.lines.push((span, words));
            }
        }
    }

    /// A type word: a number in 1..=N, or a label when the file has type labels of that kind.
    fn resolve_type(&self, w: &Word, k: TypeKind, help: &str) -> Result<usize, Diagnostic> {
        let n = self.df.header.types(k);
        if !w.text.is_empty() && w.text.bytes().all(|c| c.is_ascii_digit()) {
            let t = w.text.parse::<usize>().unwrap_or(usize::MAX);
            if t >= 1 && t <= n {
                return Ok(t);
            }
            return Err(Diagnostic::at(
                w.span,
                format!("{} type {} is out of range: the header says {n} {} types", k.name(), w.text, k.name()),
                format!("must be in 1..={n}"),
            )
            .with_help(help.to_string()));
        }
        let labels = self.df.type_labels.of(k);
        if labels.is_empty() {
            return Err(Diagnostic::at(
                w.span,
                format!("expected {} type, found `{}`", a_type(k), w.text),
                "not a type",
            )
            .with_help(help.to_string())
            .with_note(format!("type labels need a `{} Type Labels` section before this one", k.title())));
        }
        match self.df.type_labels.find(k, &w.text) {
            Some(t) => Ok(t),
            None => {
                let mut d =
                    Diagnostic::at(w.span, format!("unknown {} type label `{}`", k.name(), w.text), "not a type label");
                if let Some(h) = did_you_mean_help(&w.text, labels.iter().map(|l| l.text.as_str())) {
                    d = d.with_help(h);
                }
                Err(d.with_help(help.to_string()))
            }
        }
    }

    fn atom_line(&mut self, j: usize) {
        let words = words_of(&self.lines[j], self.file, Comment::HashWord);
        let layout = self.layout;
        let ncol = layout.atoms.len();
        let help = layout.atoms_help();
        // the first line decides whether all lines have image flags (as LAMMPS)
        let first = !self.first_atom_line_done;
        if first && words.len() == ncol + 3 {
            self.df.image_flags = true;
        }
        self.first_atom_line_done = true;
        let expected = if self.df.image_flags { ncol + 3 } else { ncol };
        if words.len() != expected {
            let span = if words.is_empty() { self.line_span(j) } else { words[0].span.to(words[words.len() - 1].span) };
            let msg = if first {
                format!(
                    "expected {ncol} values (or {} with image flags) in this Atoms line, found {}",
                    ncol + 3,
                    words.len()
                )
            } else {
                format!(
                    "expected {expected} values in this Atoms line (as in the first Atoms line), found {}",
                    words.len()
                )
            };
            self.err(Diagnostic::at(span, msg, format!("{} values", words.len())).with_help(help));
            self.atoms_incomplete = true;
            return;
        }
        let mut atom = AtomLine::new(0, 0, [0.0; 3]);
        let mut errs: Vec<Diagnostic> = vec![];
        for (c, w) in layout.atoms.iter().zip(&words) {
            match c {
                C::Id => match parse_i64(w).or_else(|| too_large_integer(w)) {
                    Some(id) if id > super::MAX_ATOM_ID => errs.push(
                        Diagnostic::at(
                            w.span,
                            format!("invalid atom ID {}: atom IDs must be at most {} (LAMMPS' largest ID, a 32-bit tagint)", w.text, super::MAX_ATOM_ID),
                            "too large",
                        )
                        .with_help(help.clone()),
                    ),
                    Some(id) if id > 0 => atom.id = id,
                    Some(_) => errs.push(
                        Diagnostic::at(
                            w.span,
                            format!("invalid atom ID {}: atom IDs must be positive", w.text),
                            "must be > 0",
                        )
                        .with_help(help.clone()),
                    ),
                    None => errs.push(
                        Diagnostic::at(
                            w.span,
                            format!("expected an integer atom ID, found `{}`", w.text),
                            "not an integer",
                        )
                        .with_help(help.clone()),
                    ),
                },
                C::Type => match self.resolve_type(w, TypeKind::Atom, &help) {
                    Ok(t) => atom.atom_type = t,
                    Err(d) => errs.push(d),
                },
                C::Molecule => match parse_i64(w) {
                    Some(m) => atom.molecule = m,
                    None => errs.push(
                        Diagnostic::at(
                            w.span,
                            format!("expected an integer molecule ID, found `{}`", w.text),
                            "not an integer",
                        )
                        .with_help(help.clone()),
                    ),
                },
                _ => match parse_f64(w) {
                    Some(v) => {
                        atom.set_float(*c, v);
                        if *c == C::Diameter && v < 0.0 {
                            errs.push(
                                Diagnostic::at(
                                    w.span,
                                    format!("invalid diameter {}: must be >= 0", w.text),
                                    "negative",
                                )
                                .with_help(help.clone()),
                            );
                        }
                        if *c == C::Density && v <= 0.0 {
                            errs.push(
                                Diagnostic::at(
                                    w.span,
                                    format!("invalid density {}: must be > 0", w.text),
                                    "must be > 0",
                                )
                                .with_help(help.clone()),
                            );
                        }
                    }
                    None => errs.push(
                        Diagnostic::at(
                            w.span,
                            format!("expected a number for {}, found `{}`", c.name(), w.text),
                            "not a number",
                        )
                        .with_help(help.clone()),
                    ),
                },
            }
        }
        if self.df.image_flags {
            for (k, w) in words[ncol..].iter().enumerate() {
                match parse_i64(w).filter(|v| *v >= i32::MIN as i64 && *v <= i32::MAX as i64) {
                    Some(v) => atom.image[k] = v as i32,
                    None => errs.push(
                        Diagnostic::at(
                            w.span,
                            format!("expected an integer image flag, found `{}`", w.text),
                            "not an integer",
                        )
                        .with_help(help.clone()),
                    ),
                }
            }
        }
        if !errs.is_empty() {
            for d in errs {
                self.err(d);
            }
            self.atoms_incomplete = true;
            return;
        }
        if let Some(&prev) = self.atom_index.get(&atom.id) {
            let prev_span = self.df.atoms[prev].words.first().map(|w| w.span).unwrap_or_default();
            self.err(
                Diagnostic::at(words[0].span, format!("duplicate atom ID {}", atom.id), "repeated")
                    .with_label(prev_span, "first used here"),
            );
            return;
        }
        atom.span = self.line_span(j);
        atom.words = words;
        self.max_atom_id = self.max_atom_id.max(atom.id);
        self.atom_index.insert(atom.id, self.df.atoms.len());
        self.df.atoms.push(atom);
    }

    fn velocity_line(&mut self, j: usize) {
        let words = words_of(&self.lines[j], self.file, Comment::AnyHash);
        let layout = self.layout;
        let help = layout.velocities_help();
        let n = layout.velocities.len();
        if words.len() != n {
            let span = words[0].span.to(words[words.len() - 1].span);
            self.err(
                Diagnostic::at(
                    span,
                    format!("expected {n} values in this Velocities line, found {}", words.len()),
                    format!("{} values", words.len()),
                )
                .with_help(help),
            );
            return;
        }
        let mut vel = VelocityLine::new(0, [0.0; 3], [0.0; 3]);
        let mut ok = true;
        for (c, w) in layout.velocities.iter().zip(&words) {
            if *c == C::Id {
                match parse_i64(w) {
                    Some(id) => vel.id = id,
                    None => {
                        self.err(
                            Diagnostic::at(
                                w.span,
                                format!("expected an integer atom ID, found `{}`", w.text),
                                "not an integer",
                            )
                            .with_help(help.clone()),
                        );
                        ok = false;
                    }
                }
            } else {
                match parse_f64(w) {
                    Some(v) => vel.set_float(*c, v),
                    None => {
                        self.err(
                            Diagnostic::at(
                                w.span,
                                format!("expected a number for {}, found `{}`", c.name(), w.text),
                                "not a number",
                            )
                            .with_help(help.clone()),
                        );
                        ok = false;
                    }
                }
            }
        }
        if !ok {
            return;
        }
        let id_span = words[0].span;
        if self.atoms_incomplete && !self.atom_index.contains_key(&vel.id) {
            return;
        }
        if vel.id <= 0 || vel.id > self.max_atom_id {
            self.err(
                Diagnostic::at(
                    id_span,
                    format!("invalid atom ID {} in the Velocities section", vel.id),
                    "no such atom",
                )
                .with_help(format!("atom IDs in this file are 1..={}", self.max_atom_id)),
            );
            return;
        }
        if !self.atom_index.contains_key(&vel.id) {
            self.warn(Diagnostic::at(
                id_span,
                format!("no atom has ID {}; LAMMPS ignores this velocity", vel.id),
                "no such atom",
            ));
        } else if let Some(prev) = self.velocity_ids.get(&vel.id).copied() {
            self.warn(
                Diagnostic::at(
                    id_span,
                    format!("a second velocity for atom {}; LAMMPS uses the last one", vel.id),
                    "repeated",
                )
                .with_label(prev, "first given here"),
            );
        } else {
            self.velocity_ids.insert(vel.id, id_span);
        }
        vel.span = self.line_span(j);
        vel.words = words;
        self.df.velocities.get_or_insert_with(Vec::new).push(vel);
    }

    fn mass_line(&mut self, j: usize) {
        let words = words_of(&self.lines[j], self.file, Comment::HashWord);
        let help = "Masses line is: atom-type mass";
        if words.len() != 2 {
            let span = words[0].span.to(words[words.len() - 1].span);
            self.err(
                Diagnostic::at(
                    span,
                    format!("expected 2 values in this Masses line, found {}", words.len()),
                    format!("{} values", words.len()),
                )
                .with_help(help),
            );
            return;
        }
        let t = self.resolve_type(&words[0], TypeKind::Atom, help);
        let m = parse_f64(&words[1]);
        if let Err(d) = &t {
            self.err(d.clone());
        }
        match m {
            None => self.err(
                Diagnostic::at(
                    words[1].span,
                    format!("expected a number for the mass, found `{}`", words[1].text),
                    "not a number",
                )
                .with_help(help),
            ),
            Some(m) if m <= 0.0 => self.err(
                Diagnostic::at(words[1].span, format!("invalid mass {}: must be > 0", words[1].text), "must be > 0")
                    .with_help(help),
            ),
            Some(m) => {
                if let Ok(t) = t {
                    let span = self.line_span(j);
                    self.df.masses.push(MassLine { atom_type: t, mass: m, words, span });
                }
            }
        }
    }

    fn coeff_line(&mut self, kind: CoeffKind, j: usize) {
        let words = words_of(&self.lines[j], self.file, Comment::AnyHash);
        let nt = kind.type_columns();
        let tk = kind.type_kind();
        let help = if nt == 2 {
            format!("{} line is: atom-type atom-type coefficients...", kind.section_name())
        } else {
            format!("{} line is: {}-type coefficients...", kind.section_name(), tk.name())
        };
        if words.len() < nt {
            let span = self.line_span(j);
            self.err(
                Diagnostic::at(
                    span,
                    format!("expected {nt} types at the start of this {} line", kind.section_name()),
                    "too few values",
                )
                .with_help(help),
            );
            return;
        }
        let n = self.df.header.types(tk);
        let mut types = vec![];
        for w in &words[..nt] {
            // LAMMPS reads the type with inumeric: a plain integer, no label
            match parse_i64(w) {
                Some(t) if t >= 1 && (t as usize) <= n => types.push(t as usize),
                Some(_) => self.err(
                    Diagnostic::at(
                        w.span,
                        format!(
                            "{} type {} is out of range: the header says {n} {} types",
                            tk.name(),
                            w.text,
                            tk.name()
                        ),
                        format!("must be in 1..={n}"),
                    )
                    .with_help(help.clone()),
                ),
                None => self.err(
                    Diagnostic::at(
                        w.span,
                        format!("expected {} type number, found `{}`", a_type(tk), w.text),
                        "not an integer",
                    )
                    .with_help(help.clone())
                    .with_note("LAMMPS does not accept type labels in coefficient sections"),
                ),
            }
        }
        if types.len() != nt {
            return;
        }
        let span = self.line_span(j);
        let line = CoeffLine { types, args: words[nt..].to_vec(), span };
        if let Some(sec) = self.df.coeffs.last_mut() {
            sec.lines.push(line);
        }
    }

    fn topo_line<const N: usize>(&mut self, k: TypeKind, j: usize) -> Option<TopoLine<N>> {
        let words = words_of(&self.lines[j], self.file, Comment::HashWord);
        let help = topo_help(k);
        if words.len() != N + 2 {
            let span = words[0].span.to(words[words.len() - 1].span);
            self.err(
                Diagnostic::at(
                    span,
                    format!("expected {} values in this {} line, found {}", N + 2, topo_section_name(k), words.len()),
                    format!("{} values", words.len()),
                )
                .with_help(help),
            );
            return None;
        }
        let mut ok = true;
        let t = match self.resolve_type(&words[1], k, &help) {
            Ok(t) => t,
            Err(d) => {
                self.err(d);
                ok = false;
                0
            }
        };
        let mut atoms = [0i64; N];
        for (a, w) in atoms.iter_mut().zip(&words[2..]) {
            match parse_i64(w) {
                Some(id) if self.atom_index.contains_key(&id) => *a = id,
                Some(_) if self.atoms_incomplete => ok = false,
                Some(id) => {
                    self.err(
                        Diagnostic::at(w.span, format!("no atom has ID {id}"), "no such atom").with_help(help.clone()),
                    );
                    ok = false;
                }
                None => {
                    self.err(
                        Diagnostic::at(
                            w.span,
                            format!("expected an integer atom ID, found `{}`", w.text),
                            "not an integer",
                        )
                        .with_help(help.clone()),
                    );
                    ok = false;
                }
            }
        }
        if !ok {
            return None;
        }
        for a in 0..N {
            for b in a + 1..N {
                if atoms[a] == atoms[b] {
                    self.err(
                        Diagnostic::at(
                            words[2 + b].span,
                            format!("atom {} appears twice in this {} line", atoms[a], topo_section_name(k)),
                            "repeated",
                        )
                        .with_label(words[2 + a].span, "first here")
                        .with_help(help.clone()),
                    );
                    return None;
                }
            }
        }
        let span = self.line_span(j);
        Some(TopoLine { topo_type: t, atoms, words, span })
    }

    fn label_line(&mut self, k: TypeKind, j: usize) {
        let words = words_of(&self.lines[j], self.file, Comment::HashWord);
        let help = format!("{} Type Labels line is: {}-type label", k.title(), k.name());
        if words.len() != 2 {
            let span = words[0].span.to(words[words.len() - 1].span);
            self.err(
                Diagnostic::at(
                    span,
                    format!("expected 2 values in this {} Type Labels line, found {}", k.title(), words.len()),
                    format!("{} values", words.len()),
                )
                .with_help(help),
            );
            return;
        }
        let n = self.df.header.types(k);
        let t = match parse_i64(&words[0]) {
            Some(t) if t >= 1 && t as usize <= n => t as usize,
            _ => {
                self.err(
                    Diagnostic::at(
                        words[0].span,
                        format!("expected {} type in 1..={n}, found `{}`", a_type(k), words[0].text),
                        "not a type",
                    )
                    .with_help(help),
                );
                return;
            }
        };
        let label = &words[1];
        if !is_type_label(&label.text) {
            self.err(
                Diagnostic::at(label.span, format!("invalid type label `{}`", label.text), "not a label")
                    .with_help("a type label must not start with a digit, `*` or `#`, and is ASCII without spaces"),
            );
            return;
        }
        let labels = &mut self.df.type_labels.labels[k.index()];
        if labels.len() < n {
            labels.resize(n, Word::new("", Span::default()));
        }
        if let Some(prev) = labels.iter().position(|w| w.text == label.text) {
            if prev + 1 != t {
                let prev_span = labels[prev].span;
                self.err(
                    Diagnostic::at(label.span, format!("type label `{}` is used twice", label.text), "repeated")
                        .with_label(prev_span, "first used here")
                        .with_help(format!("every {} type needs its own label", k.name())),
                );
                return;
            }
        }
        labels[t - 1] = label.clone();
    }

    // ----- end of file -------------------------------------------------------------------

    fn final_checks(&mut self) {
        let h = self.df.header.clone();
        if h.atoms > 0 && !self.seen.contains(&Section::Atoms) {
            let span = h.span(HeaderKey::Atoms).unwrap_or_default();
            self.err(
                Diagnostic::at(
                    span,
                    format!("the header says {} atoms but the file has no Atoms section", h.atoms),
                    "no Atoms section",
                )
                .with_help(self.layout.atoms_help()),
            );
        }
        for k in [TypeKind::Bond, TypeKind::Angle, TypeKind::Dihedral, TypeKind::Improper] {
            if h.count(k) > 0 && self.layout.allows(k) && h.types(k) > 0 && !self.seen.contains(&Section::Topology(k)) {
                let span = h.span(header_count_key(k)).unwrap_or_default();
                self.err(
                    Diagnostic::at(
                        span,
                        format!("{} section for {} {}s not found", topo_section_name(k), h.count(k), k.name()),
                        format!("no {} section", topo_section_name(k)),
                    )
                    .with_help(topo_help(k)),
                );
            }
        }
        for k in TypeKind::ALL {
            let labels = self.df.type_labels.of(k);
            if !labels.is_empty() && labels.iter().any(|w| w.text.is_empty()) {
                let span = self.section_spans.get(&Section::TypeLabels(k)).copied().unwrap_or_default();
                self.err(Diagnostic::at(
                    span,
                    format!("{} Type Labels map is incomplete: every {} type needs a label", k.title(), k.name()),
                    "incomplete",
                ));
            }
        }
    }
}

fn header_count_key(k: TypeKind) -> HeaderKey {
    match k {
        TypeKind::Atom => HeaderKey::Atoms,
        TypeKind::Bond => HeaderKey::Bonds,
        TypeKind::Angle => HeaderKey::Angles,
        TypeKind::Dihedral => HeaderKey::Dihedrals,
        TypeKind::Improper => HeaderKey::Impropers,
    }
}

fn section_label(s: Section) -> String {
    match s {
        Section::Atoms => "Atoms".into(),
        Section::Velocities => "Velocities".into(),
        Section::Fix(_) => "fix".into(),
        Section::Masses => "Masses".into(),
        Section::Coeffs(k) => k.section_name().into(),
        Section::Topology(k) => topo_section_name(k).into(),
        Section::TypeLabels(k) => format!("{} Type Labels", k.title()),
        Section::Bonus(b) => b.into(),
    }
}

/// `"3 atoms"` and the header line that sets it, for count messages.
fn section_count_words(s: Section, h: &Header) -> (String, Option<HeaderKey>) {
    match s {
        Section::Atoms | Section::Velocities | Section::Fix(_) => (format!("{} atoms", h.atoms), Some(HeaderKey::Atoms)),
        Section::Masses => (format!("{} atom types", h.atom_types), Some(HeaderKey::Types(TypeKind::Atom))),
        Section::Coeffs(CoeffKind::PairIJ) => (
            format!("{} atom types, so {} lines", h.atom_types, h.atom_types * (h.atom_types + 1) / 2),
            Some(HeaderKey::Types(TypeKind::Atom)),
        ),
        Section::Coeffs(k) => (
            format!("{} {} types", h.types(k.type_kind()), k.type_kind().name()),
            Some(HeaderKey::Types(k.type_kind())),
        ),
        Section::Topology(k) => (format!("{} {}s", h.count(k), k.name()), Some(header_count_key(k))),
        Section::TypeLabels(k) => (format!("{} {} types", h.types(k), k.name()), Some(HeaderKey::Types(k))),
        Section::Bonus(_) => ("0".into(), None),
    }
}

/// The section name and the optional `# style` after it (with its byte offset in the line).
fn section_keyword(text: &str) -> (&str, Option<(&str, usize)>) {
    match text.find('#') {
        Some(k) => {
            let name = text[..k].trim_matches(is_sep);
            let after = &text[k + 1..];
            let lead = after.len() - after.trim_start_matches(is_sep).len();
            let hint = after.trim_matches(is_sep);
            let hint = if hint.is_empty() { None } else { Some((hint, k + 1 + lead)) };
            (name, hint)
        }
        None => (text.trim_matches(is_sep), None),
    }
}

/// LAMMPS' `\d+`, `\f+` word tests as used in the header patterns.
fn is_digits(s: &str) -> bool {
    !s.is_empty() && s.bytes().all(|c| c.is_ascii_digit())
}

fn looks_numeric(s: &str) -> bool {
    !s.is_empty()
        && s.bytes().all(|c| c.is_ascii_digit() || matches!(c, b'.' | b'e' | b'E' | b'+' | b'-'))
        && s.bytes().any(|c| c.is_ascii_digit())
}

/// Recognizes a header line as LAMMPS' patterns do (words after the keyword are ignored).
/// Returns the key and the number of value words before the keyword.
fn header_key(t: &[&str]) -> Option<(HeaderKey, usize)> {
    let kw = |n: usize, k: &[&str]| t.len() >= n + k.len() && t[n..n + k.len()] == *k;
    if !t.is_empty() && is_digits(t[0]) {
        let single = [
            ("atoms", HeaderKey::Atoms),
            ("bonds", HeaderKey::Bonds),
            ("angles", HeaderKey::Angles),
            ("dihedrals", HeaderKey::Dihedrals),
            ("impropers", HeaderKey::Impropers),
        ];
        for (name, key) in single {
            if kw(1, &[name]) {
                return Some((key, 1));
            }
        }
        for k in TypeKind::ALL {
            if kw(1, &[k.name(), "types"]) {
                return Some((HeaderKey::Types(k), 1));
            }
        }
    }
    if !t.is_empty() && is_lammps_integer(t[0]) {
        for k in [TypeKind::Bond, TypeKind::Angle, TypeKind::Dihedral, TypeKind::Improper] {
            if kw(1, &["extra", k.name(), "per", "atom"]) {
                return Some((HeaderKey::ExtraPerAtom(k), 1));
            }
        }
        if kw(1, &["extra", "special", "per", "atom"]) {
            return Some((HeaderKey::ExtraSpecialPerAtom, 1));
        }
    }
    if t.len() >= 4 && looks_numeric(t[0]) && looks_numeric(t[1]) {
        for (a, b, key) in
            [("xlo", "xhi", HeaderKey::XloXhi), ("ylo", "yhi", HeaderKey::YloYhi), ("zlo", "zhi", HeaderKey::ZloZhi)]
        {
            if t[2] == a && t[3] == b {
                return Some((key, 2));
            }
        }
    }
    if t.len() >= 6 && t[..3].iter().all(|w| looks_numeric(w)) && t[3..6] == ["xy", "xz", "yz"] {
        return Some((HeaderKey::Tilt, 3));
    }
    None
}

/// `an atom`, `a bond`, ... (for messages).
fn a_type(k: TypeKind) -> String {
    let article = if k == TypeKind::Atom || k == TypeKind::Angle || k == TypeKind::Improper { "an" } else { "a" };
    format!("{article} {}", k.name())
}

/// A box line (`lo hi xlo xhi`, `xy xz yz xy xz yz`) whatever its numbers: how many values.
fn box_values(t: &[&str]) -> Option<usize> {
    let pairs = [["xlo", "xhi"], ["ylo", "yhi"], ["zlo", "zhi"]];
    if t.len() >= 4 && pairs.iter().any(|p| t[2..4] == *p) {
        return Some(2);
    }
    if t.len() >= 6 && t[3..6] == ["xy", "xz", "yz"] {
        return Some(3);
    }
    None
}

/// LAMMPS' `utils::is_type(s) == 1`: a valid type label.
fn is_type_label(s: &str) -> bool {
    let Some(c) = s.chars().next() else { return false };
    !(c.is_ascii_digit() || c == '*' || c == '#') && s.is_ascii() && !s.chars().any(is_sep)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn section_keyword_and_hint() {
        assert_eq!(section_keyword("Atoms # full"), ("Atoms", Some(("full", 8))));
        assert_eq!(section_keyword("  Pair Coeffs   #  lj/cut  "), ("Pair Coeffs", Some(("lj/cut", 19))));
        assert_eq!(section_keyword("Masses"), ("Masses", None));
        assert_eq!(section_keyword("Masses #"), ("Masses", None));
    }

    #[test]
    fn header_patterns() {
        let k = |s: &str| header_key(&s.split_whitespace().collect::<Vec<_>>()).map(|x| x.0);
        assert_eq!(k("3 atoms"), Some(HeaderKey::Atoms));
        assert_eq!(k("3 atoms in box"), Some(HeaderKey::Atoms));
        assert_eq!(k("2 atom types"), Some(HeaderKey::Types(TypeKind::Atom)));
        assert_eq!(k("3 atom"), None);
        assert_eq!(k("3.0 atoms"), None);
        assert_eq!(k("+3 atoms"), None);
        assert_eq!(k("0 4 xlo xhi"), Some(HeaderKey::XloXhi));
        assert_eq!(k("0.5 0 0 xy xz yz"), Some(HeaderKey::Tilt));
        assert_eq!(k("2 extra bond per atom"), Some(HeaderKey::ExtraPerAtom(TypeKind::Bond)));
        assert_eq!(k("Atoms"), None);
    }

    #[test]
    fn labels_follow_lammps_is_type() {
        assert!(is_type_label("C-H") && is_type_label("B") && is_type_label("-1"));
        assert!(!is_type_label("3B") && !is_type_label("*a") && !is_type_label("#x") && !is_type_label(""));
    }
}
