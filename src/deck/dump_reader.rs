//! Reading snapshots of dump files back (`read_dump` and `rerun`): LAMMPS' native text format
//! (what `dump atom` and `dump custom` write) and the XYZ format (`dump xyz`), as LAMMPS'
//! ReaderNative and ReaderXYZ read them: snapshots found by their step, skipped whole, and
//! each wanted field taken from its column (x from a column `x`, else the first of `xs`, `xu`,
//! `xsu`). Every error names the file and line.

use std::io::BufRead;
use std::path::{Path, PathBuf};

/// The per-atom quantities a dump snapshot can give (LAMMPS' read_dump fields).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    Id,
    Type,
    X,
    Y,
    Z,
    Vx,
    Vy,
    Vz,
    Q,
    Ix,
    Iy,
    Iz,
    Fx,
    Fy,
    Fz,
}

impl Field {
    /// The field named `s` (as read_dump spells it).
    pub fn named(s: &str) -> Option<Field> {
        use Field::*;
        Some(match s {
            "id" => Id,
            "type" => Type,
            "x" => X,
            "y" => Y,
            "z" => Z,
            "vx" => Vx,
            "vy" => Vy,
            "vz" => Vz,
            "q" => Q,
            "ix" => Ix,
            "iy" => Iy,
            "iz" => Iz,
            "fx" => Fx,
            "fy" => Fy,
            "fz" => Fz,
            _ => return None,
        })
    }
    pub fn name(self) -> &'static str {
        use Field::*;
        match self {
            Id => "id",
            Type => "type",
            X => "x",
            Y => "y",
            Z => "z",
            Vx => "vx",
            Vy => "vy",
            Vz => "vz",
            Q => "q",
            Ix => "ix",
            Iy => "iy",
            Iz => "iz",
            Fx => "fx",
            Fy => "fy",
            Fz => "fz",
        }
    }
    /// The coordinate direction of x, y and z.
    pub fn coordinate(self) -> Option<usize> {
        match self {
            Field::X => Some(0),
            Field::Y => Some(1),
            Field::Z => Some(2),
            _ => None,
        }
    }
}

/// How a coordinate column stores positions: scaled by the box (`xs`) or not, wrapped into
/// the box (`x`) or unwrapped (`xu`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CoordStyle {
    pub scaled: bool,
    pub wrapped: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Native,
    Xyz,
}

/// A snapshot's header.
#[derive(Clone, Debug)]
pub struct Header {
    pub natoms: u64,
    /// lo and hi of each dimension (None: the format has no box, as XYZ).
    pub bounds: Option<[[f64; 2]; 3]>,
    /// The tilt factors `[xy, xz, yz]` when the box line names them (each line's third value).
    pub tilt: Option<[f64; 3]>,
}

/// The columns the wanted fields come from, decided by the first snapshot's labels (LAMMPS
/// keeps them for every later snapshot).
#[derive(Clone, Debug)]
pub struct Columns {
    /// Column of each wanted field (XYZ: the field itself says which value).
    pub index: Vec<usize>,
    /// How the coordinate columns store positions (all alike).
    pub coords: CoordStyle,
    /// Number of columns each atom line must have.
    pub nwords: usize,
}

/// One open dump file, read forward snapshot by snapshot.
pub struct DumpReader {
    format: Format,
    path: PathBuf,
    input: Box<dyn BufRead>,
    /// Lines read so far (the last one read is line `line`).
    line: u64,
    text: String,
    /// XYZ: the number of atoms of the snapshot whose count line was read last.
    xyz_natoms: u64,
    /// XYZ: snapshots are numbered 0, 1, ... in the order read (the format has no steps);
    /// the count goes on over the files of a rerun.
    xyz_next: i64,
}

impl DumpReader {
    pub fn new(format: Format) -> DumpReader {
        DumpReader { format, path: PathBuf::new(), input: Box::new(std::io::empty()), line: 0, text: String::new(), xyz_natoms: 0, xyz_next: 0 }
    }

    pub fn open(&mut self, path: &Path) -> Result<(), String> {
        let f = std::fs::File::open(path).map_err(|e| format!("cannot open dump file `{}`: {e}", path.display()))?;
        if path.extension().is_some_and(|e| e == "gz" || e == "zst" || e == "bin") {
            return Err(format!("cannot read dump file `{}`: compressed and binary dump files are not supported (write the dump as text)", path.display()));
        }
        self.path = path.to_path_buf();
        self.input = Box::new(std::io::BufReader::with_capacity(1 << 16, f));
        self.line = 0;
        Ok(())
    }

    /// `file:line: message` for the line read last.
    pub fn err(&self, message: impl std::fmt::Display) -> String {
        format!("{}:{}: {message}", self.path.display(), self.line)
    }

    /// Read the next line (None at the end of the file).
    fn next_line(&mut self) -> Result<Option<&str>, String> {
        self.text.clear();
        match self.input.read_line(&mut self.text) {
            Ok(0) => Ok(None),
            Ok(_) => {
                self.line += 1;
                Ok(Some(self.text.as_str()))
            }
            Err(e) => Err(format!("{}:{}: cannot read the dump file: {e}", self.path.display(), self.line + 1)),
        }
    }

    /// Read a line that must be there.
    fn need_line(&mut self, what: &str) -> Result<&str, String> {
        if self.next_line()?.is_none() {
            return Err(format!("{}:{}: unexpected end of the dump file: expected {what}", self.path.display(), self.line + 1));
        }
        Ok(self.text.as_str())
    }

    /// Skip `n` lines that must be there.
    fn skip_lines(&mut self, n: u64, what: &str) -> Result<(), String> {
        for _ in 0..n {
            self.need_line(what)?;
        }
        Ok(())
    }

    /// Parse the whole (trimmed) line as an integer.
    fn line_int(&self, what: &str) -> Result<i64, String> {
        let t = self.text.trim();
        t.parse::<i64>().map_err(|_| self.err(format!("expected {what} (an integer), found `{t}`")))
    }

    /// The next snapshot's step (None at the end of the file). Native files may have `ITEM:
    /// UNITS` and `ITEM: TIME` before `ITEM: TIMESTEP`; XYZ snapshots are numbered in order.
    pub fn read_time(&mut self) -> Result<Option<i64>, String> {
        if self.next_line()?.is_none() {
            return Ok(None);
        }
        match self.format {
            Format::Native => {
                if self.text.trim() == "ITEM: UNITS" {
                    self.skip_lines(2, "the units and the next ITEM line")?;
                }
                if self.text.trim() == "ITEM: TIME" {
                    self.skip_lines(2, "the time and ITEM: TIMESTEP")?;
                }
                if self.text.trim() != "ITEM: TIMESTEP" {
                    let t = self.text.trim().to_string();
                    return Err(self.err(format!("dump file is incorrectly formatted: expected `ITEM: TIMESTEP`, found `{t}`")));
                }
                self.need_line("the step after ITEM: TIMESTEP")?;
                Ok(Some(self.line_int("the step")?))
            }
            Format::Xyz => {
                let first = self.text.split_whitespace().next().unwrap_or("").to_string();
                let n = first.parse::<i64>().ok().filter(|&n| n >= 1).ok_or_else(|| self.err(format!("dump file is incorrectly formatted: expected the number of atoms of an XYZ snapshot (>= 1), found `{first}`")))?;
                self.xyz_natoms = n as u64;
                self.need_line("the comment line of an XYZ snapshot")?;
                let step = self.xyz_next;
                self.xyz_next += 1;
                Ok(Some(step))
            }
        }
    }

    /// Skip the rest of the snapshot whose step was read last.
    pub fn skip(&mut self) -> Result<(), String> {
        let n = match self.format {
            Format::Native => {
                self.skip_lines(2, "ITEM: NUMBER OF ATOMS and the count")?;
                let n = self.count()?;
                self.skip_lines(5, "the box bounds and ITEM: ATOMS")?;
                n
            }
            Format::Xyz => self.xyz_natoms,
        };
        self.skip_lines(n, "the snapshot's atom lines")
    }

    fn count(&self) -> Result<u64, String> {
        let n = self.line_int("the number of atoms")?;
        u64::try_from(n).map_err(|_| self.err(format!("the number of atoms must be >= 0, found {n}")))
    }

    /// The rest of the snapshot's header, after its step. With `labels` (the first snapshot
    /// of a read), also the column labels of a native file (`ITEM: ATOMS id type x ...`).
    pub fn read_header(&mut self, labels: Option<&mut Vec<String>>) -> Result<Header, String> {
        match self.format {
            Format::Xyz => Ok(Header { natoms: self.xyz_natoms, bounds: None, tilt: None }),
            Format::Native => {
                self.skip_lines(2, "ITEM: NUMBER OF ATOMS and the count")?;
                let natoms = self.count()?;
                let boxline = self.need_line("ITEM: BOX BOUNDS")?.to_string();
                if !boxline.trim_start().starts_with("ITEM: BOX BOUNDS") {
                    return Err(self.err(format!("dump file is incorrectly formatted: expected `ITEM: BOX BOUNDS`, found `{}`", boxline.trim())));
                }
                let words: Vec<&str> = boxline.split_whitespace().collect();
                let triclinic = words.windows(3).any(|w| w == ["xy", "xz", "yz"]);
                let mut bounds = [[0.0; 2]; 3];
                let mut tilt = [0.0; 3];
                for (d, b) in bounds.iter_mut().enumerate() {
                    self.need_line("a line of box bounds")?;
                    let vals: Vec<&str> = self.text.split_whitespace().collect();
                    let want = if triclinic { 3 } else { 2 };
                    if vals.len() < want {
                        return Err(self.err(format!("dump file is incorrectly formatted: expected {want} box values for {}, found `{}`", ["x", "y", "z"][d], self.text.trim())));
                    }
                    let number = |w: &str| parse_f64(w).ok_or_else(|| self.err(format!("dump file is incorrectly formatted: expected a number for the box, found `{w}`")));
                    for k in 0..2 {
                        b[k] = number(vals[k])?;
                    }
                    if triclinic {
                        tilt[d] = number(vals[2])?;
                    }
                }
                let atoms = self.need_line("ITEM: ATOMS")?.to_string();
                if let Some(labels) = labels {
                    let rest = atoms.trim_start().strip_prefix("ITEM: ATOMS").ok_or_else(|| self.err(format!("dump file is incorrectly formatted: expected `ITEM: ATOMS` and the column labels, found `{}`", atoms.trim())))?;
                    *labels = rest.split_whitespace().map(str::to_string).collect();
                }
                Ok(Header { natoms, bounds: Some(bounds), tilt: triclinic.then_some(tilt) })
            }
        }
    }

    /// The columns of the wanted `fields` in a native file with column `labels`; `label[k]`
    /// names field k's column explicitly, with `given` its storage (LAMMPS' scaled/wrapped
    /// keywords). XYZ files give type and coordinates only.
    pub fn columns(&self, fields: &[Field], label: &[Option<String>], labels: &[String], given: CoordStyle) -> Result<Columns, String> {
        if self.format == Format::Xyz {
            if let Some(f) = fields.iter().find(|f| !matches!(f, Field::Id | Field::Type | Field::X | Field::Y | Field::Z)) {
                return Err(format!("read_dump field {} is not in XYZ files (they have type, x, y and z)", f.name()));
            }
            return Ok(Columns { index: vec![0; fields.len()], coords: given, nwords: 0 });
        }
        // a label given twice names its last column, as LAMMPS' map of labels
        let find = |name: &str| labels.iter().rposition(|l| l == name);
        let mut index = Vec::with_capacity(fields.len());
        let mut style: [Option<CoordStyle>; 3] = [None; 3];
        for (k, &f) in fields.iter().enumerate() {
            let (col, st) = if let Some(l) = &label[k] {
                (find(l).ok_or_else(|| self.err(format!("read_dump field {} (label {l}) is not a column of the dump file (columns: {})", f.name(), labels.join(" "))))?, given)
            } else if let Some(d) = f.coordinate() {
                let n = ["x", "y", "z"][d];
                if let Some(c) = find(n) {
                    (c, CoordStyle { scaled: false, wrapped: true })
                } else {
                    // the first column of xs, xu, xsu
                    let kinds = [("s", true, true), ("u", false, false), ("su", true, false)];
                    let best = kinds.iter().filter_map(|(suffix, s, w)| find(&format!("{n}{suffix}")).map(|c| (c, CoordStyle { scaled: *s, wrapped: *w }))).min_by_key(|(c, _)| *c);
                    best.ok_or_else(|| self.err(format!("read_dump field {n} is not a column of the dump file (looked for {n}, {n}s, {n}u, {n}su; columns: {})", labels.join(" "))))?
                }
            } else {
                let c = find(f.name()).ok_or_else(|| self.err(format!("read_dump field {} is not a column of the dump file (columns: {})", f.name(), labels.join(" "))))?;
                (c, given)
            };
            if let Some(d) = f.coordinate() {
                style[d] = Some(st);
            }
            index.push(col);
        }
        let set: Vec<CoordStyle> = style.iter().flatten().copied().collect();
        if set.windows(2).any(|w| w[0] != w[1]) {
            return Err("Read_dump xyz fields do not have consistent scaling/wrapping".to_string());
        }
        let coords = set.first().copied().unwrap_or(CoordStyle { scaled: false, wrapped: false });
        Ok(Columns { index, coords, nwords: labels.len() })
    }

    /// The snapshot's `n` atom lines: the value of each wanted field per atom (`fields[k]` is
    /// field k of `cols`). XYZ atoms get IDs 1, 2, ... in the order of the lines and the type
    /// of a leading integer name (0 for an element name).
    pub fn read_atoms(&mut self, n: u64, fields: &[Field], cols: &Columns) -> Result<Vec<Vec<f64>>, String> {
        let mut out = Vec::with_capacity(n.min(1 << 24) as usize);
        for k in 0..n {
            self.need_line("an atom line of the snapshot")?;
            let words: Vec<&str> = self.text.split_whitespace().collect();
            let mut row = Vec::with_capacity(fields.len());
            match self.format {
                Format::Native => {
                    if words.len() < cols.nwords {
                        return Err(self.err(format!("insufficient columns in dump file: expected {}, found {}", cols.nwords, words.len())));
                    }
                    for &c in &cols.index {
                        let w = words[c];
                        let v = parse_f64(w).ok_or_else(|| self.err(format!("expected a number in column {} of the atom line, found `{w}`", c + 1)))?;
                        row.push(v);
                    }
                }
                Format::Xyz => {
                    if words.len() < 4 {
                        return Err(self.err(format!("an XYZ atom line needs a name and x y z, found `{}`", self.text.trim())));
                    }
                    let xyz: Vec<f64> = words[1..4].iter().map(|w| parse_f64(w).ok_or_else(|| self.err(format!("expected a coordinate, found `{w}`")))).collect::<Result<_, _>>()?;
                    let typ = leading_int(words[0]);
                    for f in fields {
                        row.push(match f {
                            Field::Id => (k + 1) as f64,
                            Field::Type => typ as f64,
                            Field::X => xyz[0],
                            Field::Y => xyz[1],
                            Field::Z => xyz[2],
                            _ => unreachable!("refused in columns()"),
                        });
                    }
                }
            }
            out.push(row);
        }
        Ok(out)
    }
}

/// A number as C's strtod reads a whole word (also `inf`, `nan`).
fn parse_f64(w: &str) -> Option<f64> {
    w.parse::<f64>().ok()
}

/// The integer at the start of `w`, as C's atoi (0 if none).
fn leading_int(w: &str) -> i64 {
    let b = w.as_bytes();
    let mut end = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    while end < b.len() && b[end].is_ascii_digit() {
        end += 1;
    }
    w[..end].parse().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reader(format: Format, text: &str) -> DumpReader {
        let mut r = DumpReader::new(format);
        r.path = PathBuf::from("t.dump");
        r.input = Box::new(std::io::Cursor::new(text.as_bytes().to_vec()));
        r
    }

    const NATIVE: &str = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 10\n0 10\n0 10\nITEM: ATOMS id type xs ys zs xu\n1 1 0.1 0.2 0.3 1.5\n2 1 0.4 0.5 0.6 4.5\n\
ITEM: UNITS\nlj\nITEM: TIME\n0.5\nITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 10\n0 10\n0 10\nITEM: ATOMS id type xs ys zs xu\n1 1 0.1 0.2 0.3 1.5\n";

    #[test]
    fn native_snapshots_are_found_by_step_and_columns_by_label() {
        let mut r = reader(Format::Native, NATIVE);
        assert_eq!(r.read_time().unwrap(), Some(0));
        r.skip().unwrap();
        assert_eq!(r.read_time().unwrap(), Some(100));
        let mut labels = vec![];
        let h = r.read_header(Some(&mut labels)).unwrap();
        assert_eq!((h.natoms, h.bounds.unwrap()[0]), (1, [0.0, 10.0]));
        let fields = [Field::Id, Field::X, Field::Y];
        let none = [None, None, None];
        let cols = r.columns(&fields, &none, &labels, CoordStyle { scaled: false, wrapped: true }).unwrap();
        // xs comes before xu: scaled and wrapped
        assert_eq!(cols.index, vec![0, 2, 3]);
        assert_eq!(cols.coords, CoordStyle { scaled: true, wrapped: true });
        assert_eq!(r.read_atoms(1, &fields, &cols).unwrap(), vec![vec![1.0, 0.1, 0.2]]);
        assert_eq!(r.read_time().unwrap(), None);
        // a label names the column; mixed styles are refused
        let cols = r.columns(&fields, &[None, Some("xu".into()), None], &labels, CoordStyle { scaled: false, wrapped: false });
        assert!(cols.unwrap_err().contains("consistent"));
        let e = r.columns(&[Field::Id, Field::Vx], &[None, None], &labels, CoordStyle { scaled: false, wrapped: true }).unwrap_err();
        assert!(e.contains("field vx is not a column"), "{e}");
    }

    #[test]
    fn xyz_snapshots_are_numbered_and_typed_by_leading_integers() {
        let mut r = reader(Format::Xyz, "2\n Atoms. Timestep: 0\n1 0 0 0\nH 1 2 3\n1\ncomment\n2 4 5 6\n");
        assert_eq!(r.read_time().unwrap(), Some(0));
        r.skip().unwrap();
        assert_eq!(r.read_time().unwrap(), Some(1));
        let h = r.read_header(None).unwrap();
        assert!(h.bounds.is_none());
        let fields = [Field::Id, Field::Type, Field::Z];
        let cols = r.columns(&fields, &[None, None, None], &[], CoordStyle { scaled: false, wrapped: true }).unwrap();
        assert_eq!(r.read_atoms(1, &fields, &cols).unwrap(), vec![vec![1.0, 2.0, 6.0]]);
        assert!(r.columns(&[Field::Id, Field::Vx], &[None, None], &[], CoordStyle { scaled: false, wrapped: true }).is_err());
        assert_eq!(leading_int("H"), 0);
        assert_eq!(leading_int("12abc"), 12);
    }

    #[test]
    fn bad_files_name_the_line() {
        let mut r = reader(Format::Native, "ITEM: TIMESTEP\nten\n");
        assert_eq!(r.read_time().unwrap_err(), "t.dump:2: expected the step (an integer), found `ten`");
        let mut r = reader(Format::Native, "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\nITEM: ATOMS id x\n1 0.5\n");
        r.read_time().unwrap();
        let mut labels = vec![];
        let h = r.read_header(Some(&mut labels)).unwrap();
        let fields = [Field::Id, Field::X];
        let cols = r.columns(&fields, &[None, None], &labels, CoordStyle { scaled: false, wrapped: true }).unwrap();
        let e = r.read_atoms(h.natoms, &fields, &cols).unwrap_err();
        assert!(e.starts_with("t.dump:11: unexpected end of the dump file"), "{e}");
        let mut r = reader(Format::Native, "ITEM: NUMBER\n");
        assert!(r.read_time().unwrap_err().contains("expected `ITEM: TIMESTEP`"));
    }
}
