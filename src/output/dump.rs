//! `dump atom`, `dump custom` and `dump xyz` snapshots in LAMMPS' text formats (readable by
//! OVITO and VMD, and by `read_dump`), unsorted in LAMMPS' local order as LAMMPS writes them on
//! one process. Every snapshot is formatted in memory and written with one call; per-snapshot
//! files (`*` in the name) are written atomically.

use crate::models::compute::property::Field;
use crate::output::log::write_atomic;
use crate::models::world::World;
use std::path::Path;
use dmhs_parser::numfmt::format_printf;
use dmhs_parser::{Args, Command, DResult, Word};
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::PathBuf;

pub const SYNTAX: &str = "dump ID group atom|custom|xyz|dcd|local|vtk|image|movie N file [custom fields: id type x y z xu vx fx c_ID c_ID[N] ...] [local fields: index c_ID c_ID[N] f_ID f_ID[N]]";

#[derive(Clone, Debug)]
pub(crate) enum Column {
    Attr(Field),
    /// a per-atom compute or fix column
    PerAtom(crate::models::compute::PerAtomRef),
    /// dump local: a compute's or fix's local vector or array column
    Local(crate::models::compute::LocalRef),
    /// dump local: the row number, from 1
    Index,
}

pub struct Dump {
    pub id: String,
    pub groupbit: u32,
    pub style: String,
    pub every: i64,
    /// `dump_modify every v_name`: an equal-style variable gives the step of each next
    /// snapshot (LAMMPS' var_dump), evaluated at each run's setup and after each snapshot.
    pub every_var: Option<String>,
    /// The step of the next snapshot under `every_var`.
    pub next: i64,
    pub path: PathBuf,
    names: Vec<String>,
    columns: Vec<Column>,
    pub sort: bool,
    pub image: bool,
    pub first: bool,
    pub append: bool,
    format_line: Option<Vec<String>>,
    format_int: Option<String>,
    format_float: Option<String>,
    format_column: Vec<(usize, String)>,
    pub last_written: Option<i64>,
    file: Option<File>,
    /// `dump image` / `dump movie` settings.
    pub picture: Option<Box<crate::output::dump_image::ImageDump>>,
    /// dump vtk: binary (appended raw) arrays, else ASCII (`dump_modify ID binary no`).
    pub binary: bool,
    /// dump vtk: the snapshots written, (time, file name), for the .pvd collection.
    series: Vec<(f64, String)>,
    /// `dump_modify header yes/no`: the ITEM lines before each snapshot.
    pub header: bool,
    /// dump xyz: `dump_modify element E1 .. EN`, the name written for each type (the type
    /// number without it).
    elements: Option<Vec<String>>,
    /// dump xyz: `dump_modify time yes`, the time after the step in the comment line.
    time: bool,
    /// dump dcd: the binary trajectory's state.
    dcd: Option<Box<crate::output::dump_dcd::Dcd>>,
}

impl Dump {
    /// `base_dir`: the folder relative file names resolve in.
    pub fn from_lammps(cmd: &Command, w: &World, base_dir: Option<&Path>) -> DResult<Dump> {
        let mut a = Args::new(cmd, SYNTAX);
        let id = a.word("dump ID")?.text.clone();
        let gw = a.word("group ID")?;
        let groupbit = w.state.groups.bit(&gw.text).ok_or_else(|| a.error_at(gw, format!("group `{}` does not exist", gw.text), "unknown group"))?;
        let style_w = a.word("dump style")?;
        let style = style_w.text.clone();
        if !["atom", "custom", "xyz", "dcd", "local", "vtk", "image", "movie"].contains(&style.as_str()) {
            let msg = if dmhs_parser::commands::is_lammps_style(dmhs_parser::commands::StyleKind::Dump, &style) {
                format!("dump style `{style}` is a LAMMPS style that dmhs does not support (use atom, custom, xyz, dcd, local, vtk, image or movie)")
            } else {
                format!("unknown dump style `{style}`")
            };
            return Err(a.error_at(style_w, msg, "expected atom, custom, xyz, dcd, local, vtk, image or movie"));
        }
        let every = a.i64_in("N (dump every N steps)", 1, i64::MAX)?;
        let fw = a.word("file name")?;
        let picture = if style == "image" || style == "movie" {
            let mut ia = Args::from_words(a.remaining(), cmd.span, crate::output::dump_image::SYNTAX);
            Some(Box::new(crate::output::dump_image::ImageDump::from_lammps(&mut ia, fw, style == "movie", w, base_dir)?))
        } else {
            None
        };
        if picture.is_none() && (fw.text.ends_with(".gz") || fw.text.ends_with(".zst") || fw.text.contains('%')) {
            return Err(a.error_at(fw, "compressed (.gz, .zst) and per-processor (%) dump files are not supported", "plain file name expected"));
        }
        let mut d = Dump {
            id,
            groupbit,
            style: style.clone(),
            every,
            every_var: None,
            next: 0,
            path: crate::output::log::resolve_path(base_dir, &fw.text),
            names: vec![],
            columns: vec![],
            // LAMMPS' DumpXYZ sorts by ID unless told `sort off`; DumpDCD always
            sort: style == "xyz" || style == "dcd",
            image: false,
            first: false,
            append: false,
            format_line: None,
            format_int: None,
            format_float: None,
            format_column: vec![],
            last_written: None,
            file: None,
            picture,
            binary: true,
            series: vec![],
            header: true,
            elements: None,
            time: false,
            dcd: None,
        };
        if d.picture.is_some() {
            return Ok(d);
        }
        if style == "vtk" && !fw.text.ends_with(".vtu") {
            return Err(a.error_at(fw, "dump vtk writes VTK XML files: the name must end in .vtu (with * for the step, e.g. out.*.vtu)", "expected a .vtu file name"));
        }
        if style == "local" {
            if a.is_empty() {
                return Err(a.missing("at least one local field (index, f_ID, f_ID[N])"));
            }
            while let Some(word) = a.peek() {
                a.skip(1);
                if word.text == "index" {
                    d.names.push(word.text.clone());
                    d.columns.push(Column::Index);
                    continue;
                }
                let refs = match crate::models::compute::LocalRef::parse(&word.text, w, Some(every)) {
                    Some(r) => r.map_err(|e| a.error_at(word, e, "bad dump local field"))?,
                    None => return Err(a.error_at(word, format!("Invalid attribute `{}` in dump local command (expected index, c_ID, c_ID[N], f_ID or f_ID[N])", word.text), "bad dump local field")),
                };
                for r in refs {
                    // `[*]` is written as its columns, as LAMMPS expands it
                    d.names.push(match (word.text.ends_with("[*]"), r.col) {
                        (true, Some(c)) => format!("{}[{}]", &word.text[..word.text.len() - 3], c + 1),
                        _ => word.text.clone(),
                    });
                    d.columns.push(Column::Local(r));
                }
            }
            if !d.columns.iter().any(|c| matches!(c, Column::Local(..))) {
                return Err(a.error_at(style_w, "Dump local attributes contain no compute or fix", "needs a c_ID or f_ID field"));
            }
        } else if style == "atom" {
            a.finish()?;
            d.set_atom_columns();
        } else if style == "dcd" {
            a.finish()?;
            if fw.text.contains('*') {
                return Err(a.error_at(fw, format!("Invalid dump dcd filename {}: a DCD file holds every snapshot (no *)", fw.text), "one file"));
            }
            let at = &w.state.atoms;
            let natoms = (0..at.nlocal).filter(|&i| at.mask[i] & groupbit != 0).count();
            d.dcd = Some(Box::new(crate::output::dump_dcd::Dcd::new(natoms)));
        } else if style == "xyz" {
            a.finish()?;
            d.names = ["type", "x", "y", "z"].map(String::from).to_vec();
            d.columns = d.names.iter().map(|n| Column::Attr(Field::parse(n).expect("an attribute"))).collect();
        } else if style == "vtk" && a.is_empty() {
            for name in crate::output::dump_vtu::default_fields(w.state) {
                d.names.push(name.to_string());
                d.columns.push(Column::Attr(Field::parse(name).unwrap()));
            }
        } else {
            if a.is_empty() {
                return Err(a.missing("at least one per-atom field"));
            }
            while let Some(word) = a.peek() {
                a.skip(1);
                let col = parse_column(&word.text, w).map_err(|e| a.error_at(word, e, "bad dump field"))?;
                d.names.push(word.text.clone());
                d.columns.push(col);
            }
        }
        Ok(d)
    }

    fn set_atom_columns(&mut self) {
        let mut names = vec!["id", "type", "xs", "ys", "zs"];
        if self.image {
            names.extend(["ix", "iy", "iz"]);
        }
        self.names = names.iter().map(|s| s.to_string()).collect();
        self.columns = names.iter().map(|n| Column::Attr(Field::parse(n).unwrap())).collect();
    }

    /// `dump_modify ID keyword value ...`
    /// `ntypes`: the number of atom types (`element` names one per type).
    pub fn modify(&mut self, a: &mut Args, ntypes: usize) -> DResult<()> {
        let keys = ["sort", "format", "every", "first", "image", "append", "flush", "binary", "header", "element", "time", "unwrap"];
        while let Some(w) = a.peek() {
            a.skip(1);
            if let Some(p) = self.picture.as_mut() {
                if p.modify(w, a)? {
                    continue;
                }
            }
            match w.text.as_str() {
                "sort" if self.style == "dcd" => {
                    let v = a.word("sort setting")?;
                    if v.text != "id" {
                        return Err(a.error_at(v, "Dump dcd requires sorting by atom ID", "dump dcd is sorted by ID"));
                    }
                }
                "unwrap" if self.style == "dcd" => self.dcd.as_mut().expect("a dcd dump").unwrap = a.yes_no("unwrap")?,
                "format" if self.style == "dcd" => return Err(a.error_at(w, "dump_modify format is not for dump dcd (a binary file of floats)", "not for dump dcd")),
                "sort" => {
                    let v = a.word("sort setting (id or off)")?;
                    self.sort = match v.text.as_str() {
                        "id" => true,
                        "off" => false,
                        _ => return Err(a.error_at(v, "dmhs sorts dumps only by `id` (or `off`)", "expected id or off")),
                    };
                }
                "element" if self.style == "xyz" => {
                    let mut names = Vec::with_capacity(ntypes);
                    for t in 1..=ntypes {
                        names.push(a.word(&format!("element name of atom type {t} (one per type)"))?.text.clone());
                    }
                    self.elements = Some(names);
                }
                "time" if self.style == "xyz" => self.time = a.yes_no("time")?,
                "format" if self.style == "xyz" => return Err(a.error_at(w, "dump_modify format is not supported for dump xyz (its lines are `%s %g %g %g`: element or type, x, y, z)", "not for dump xyz")),
                "format" => {
                    let which = a.word("format kind (line, int, float, N or none)")?;
                    match which.text.as_str() {
                        "none" => {
                            self.format_line = None;
                            self.format_int = None;
                            self.format_float = None;
                            self.format_column.clear();
                        }
                        "line" => self.format_line = Some(a.printf_line("format string")?),
                        "int" => self.format_int = Some(a.printf_format("format string")?.to_string()),
                        "float" => self.format_float = Some(a.printf_format("format string")?.to_string()),
                        n => match n.parse::<usize>() {
                            Ok(k) if k >= 1 && k <= self.columns.len() => {
                                let f = a.printf_format("format string")?.to_string();
                                self.format_column.retain(|(c, _)| *c != k);
                                self.format_column.push((k, f));
                            }
                            _ => return Err(a.error_at(which, format!("expected line, int, float, none or a column 1..{}", self.columns.len()), "bad format kind")),
                        },
                    }
                }
                "every" => {
                    let n = a.word("every")?;
                    // the variable is looked up when a run starts (LAMMPS' Output::init)
                    if let Some(v) = n.text.strip_prefix("v_") {
                        if self.style == "dcd" {
                            return Err(a.error_at(n, "Cannot use variable every setting for dump dcd", "a DCD file has one interval"));
                        }
                        self.every_var = Some(v.to_string());
                    } else {
                        self.every = dmhs_parser::args::word_i64(n, "every")?;
                        if self.every < 1 {
                            return Err(a.error_at(n, "dump_modify every must be >= 1", "expected N >= 1 or v_name"));
                        }
                        // (LAMMPS refuses it at the next run's init)
                        if let Some(old) = self.dcd.as_ref().and_then(|d| d.fixed_every()).filter(|&o| o != self.every) {
                            return Err(a.error_at(n, format!("Cannot change dump_modify every for dump dcd (its file's interval is {old})"), "fixed by the first snapshot"));
                        }
                        self.every_var = None;
                    }
                }
                "first" => self.first = a.yes_no("first")?,
                "header" => self.header = a.yes_no("header")?,
                "append" => self.append = a.yes_no("append")?,
                "binary" if self.style == "vtk" => self.binary = a.yes_no("binary")?,
                "flush" => {
                    a.yes_no("flush")?;
                }
                "image" => {
                    self.image = a.yes_no("image")?;
                    if self.style == "atom" {
                        self.set_atom_columns();
                    }
                }
                _ if self.picture.is_some() => return Err(a.unknown_keyword(w, &[&keys[..], crate::output::dump_image::MODIFY_KEYWORDS].concat())),
                _ => return Err(a.unknown_keyword(w, &keys)),
            }
        }
        Ok(())
    }

    /// Should a snapshot be written at this step? At a run's setup (LAMMPS' Output::setup):
    /// with `first yes` if the dump never wrote, or at a multiple of N (not under `every
    /// v_name`); later at multiples of N or at the step the variable gave. Never twice at one
    /// step (the last step of the run before).
    pub fn due(&self, step: i64, setup: bool) -> bool {
        if self.last_written == Some(step) {
            return false;
        }
        let on_schedule = match self.every_var {
            Some(_) => !setup && step == self.next,
            None => step % self.every == 0,
        };
        on_schedule || (setup && self.first && self.last_written.is_none())
    }

    fn format_of(&self, k: usize, int: bool) -> String {
        if let Some((_, f)) = self.format_column.iter().find(|(c, _)| *c == k + 1) {
            return f.clone();
        }
        if let Some(line) = &self.format_line {
            if let Some(f) = line.get(k) {
                return f.clone();
            }
        }
        if int {
            self.format_int.clone().unwrap_or_else(|| "%d".into())
        } else {
            self.format_float.clone().unwrap_or_else(|| "%g".into())
        }
    }

    /// The ITEM lines of a snapshot up to the column names (`what`: ATOMS or ENTRIES).
    fn header_lines(&self, w: &World, what: &str, count: usize) -> Result<String, String> {
        let dom = w.state.domain()?;
        let mut s = format!("ITEM: TIMESTEP\n{}\nITEM: NUMBER OF {what}\n{}\n", w.state.step, count);
        let bstr: Vec<String> = (0..3).map(|d| format!("{}{}", dom.boundary[d][0].letter(), dom.boundary[d][1].letter())).collect();
        match dom.tilt {
            None => {
                s += &format!("ITEM: BOX BOUNDS {}\n", bstr.join(" "));
                for d in 0..3 {
                    s += &format!("{} {}\n", sci16(dom.lo[d]), sci16(dom.hi[d]));
                }
            }
            Some(tilt) => {
                // the bounding box, and the tilts xy xz yz in turn
                let (lo, hi) = dom.bounds();
                s += &format!("ITEM: BOX BOUNDS xy xz yz {}\n", bstr.join(" "));
                for d in 0..3 {
                    s += &format!("{} {} {}\n", sci16(lo[d]), sci16(hi[d]), sci16(tilt[d]));
                }
            }
        }
        s += &format!("ITEM: {what} {}\n", self.names.join(" "));
        Ok(s)
    }

    /// A `dump local` snapshot: one line per row of the fixes' local data, each value followed
    /// by a space (LAMMPS' DumpLocal).
    fn snapshot_local(&self, w: &World, mut ev: Option<&mut dyn dmhs_parser::EvalContext>) -> Result<String, String> {
        // each compute or fix's rows once, however many of its columns are written
        let mut fetched: Vec<((bool, &str), Vec<Vec<f64>>)> = vec![];
        let mut data: Vec<(usize, &crate::models::compute::LocalRef)> = vec![];
        let mut rows: Option<usize> = None;
        for c in &self.columns {
            if let Column::Local(r) = c {
                let key = (r.fix, r.id.as_str());
                let k = match fetched.iter().position(|(f, _)| *f == key) {
                    Some(k) => k,
                    None => {
                        fetched.push((key, r.rows(w, ev.as_mut().map(|e| &mut **e as &mut dyn dmhs_parser::EvalContext)).map_err(|e| format!("dump {}: {e}", self.id))?));
                        fetched.len() - 1
                    }
                };
                let n = fetched[k].1.len();
                if rows.is_some_and(|m| m != n) {
                    return Err(format!("dump {}: Dump local count is not consistent across input fields", self.id));
                }
                rows = Some(n);
                data.push((k, r));
            }
        }
        let n = rows.unwrap_or(0);
        let fmts: Vec<String> = self.columns.iter().enumerate().map(|(k, c)| self.format_of(k, matches!(c, Column::Index))).collect();
        let mut s = if self.header { self.header_lines(w, "ENTRIES", n)? } else { String::new() };
        for r in 0..n {
            let mut fixcol = 0;
            for (k, c) in self.columns.iter().enumerate() {
                let v = match c {
                    Column::Index => (r + 1) as f64,
                    _ => {
                        let (k, lr) = data[fixcol];
                        fixcol += 1;
                        lr.get(&fetched[k].1[r])
                    }
                };
                s += &format_printf(&fmts[k], v).map_err(|e| format!("dump {} format `{}`: {e}", self.id, fmts[k]))?;
                s.push(' ');
            }
            s.push('\n');
        }
        Ok(s)
    }

    /// Format a snapshot of the current state.
    pub fn snapshot(&self, w: &World) -> Result<String, String> {
        self.snapshot_with(w, None)
    }

    /// [`Dump::snapshot`]; `ev` evaluates the variables of local computes.
    fn snapshot_with(&self, w: &World, ev: Option<&mut dyn dmhs_parser::EvalContext>) -> Result<String, String> {
        if self.style == "local" {
            return self.snapshot_local(w, ev);
        }
        if self.style == "xyz" {
            return self.snapshot_xyz(w);
        }
        let a = &w.state.atoms;
        let mut idx = local_order(w, self.groupbit);
        if self.sort {
            idx.sort_by_key(|&i| a.tag[i]);
        }
        let mut peratom: Vec<Option<crate::models::compute::PerAtom>> = Vec::new();
        for c in &self.columns {
            peratom.push(match c {
                Column::PerAtom(r) => Some(r.values(w).map_err(|e| format!("dump {}: {e}", self.id))?),
                _ => None,
            });
        }
        let ints: Vec<bool> = self.columns.iter().map(|c| matches!(c, Column::Attr(f) if f.is_int())).collect();
        let fmts: Vec<String> = (0..self.columns.len()).map(|k| self.format_of(k, ints[k])).collect();
        let mut s = String::with_capacity(64 * (idx.len() + 10));
        if self.header {
            s += &self.header_lines(w, "ATOMS", idx.len())?;
        }
        for &i in &idx {
            for (k, c) in self.columns.iter().enumerate() {
                let v = match c {
                    Column::Attr(f) => f.value(w.state, i),
                    Column::PerAtom(r) => r.get(peratom[k].as_ref().unwrap(), i),
                    Column::Local(..) | Column::Index => unreachable!("local columns only in dump local"),
                };
                let text = format_printf(&fmts[k], if ints[k] { v.round() } else { v }).map_err(|e| format!("dump {} format `{}`: {e}", self.id, fmts[k]))?;
                s += &text;
                s.push(' ');
            }
            s.pop();
            s.push('\n');
        }
        Ok(s)
    }

    /// A dump xyz snapshot: the atom count, a comment line with the step (and the time), then
    /// `name x y z` per atom, name the type's element or its number (LAMMPS' DumpXYZ).
    fn snapshot_xyz(&self, w: &World) -> Result<String, String> {
        let a = &w.state.atoms;
        // by ID (the default), or with `sort off` in LAMMPS' local order
        let mut idx = local_order(w, self.groupbit);
        if self.sort {
            idx.sort_by_key(|&i| a.tag[i]);
        }
        let mut s = String::with_capacity(48 * (idx.len() + 2));
        s += &format!("{}\n Atoms. Timestep: {}", idx.len(), w.state.step);
        if self.time {
            s += &format!(" Time: {}", format_printf("%.6f", w.state.time())?);
        }
        s.push('\n');
        for &i in &idx {
            let t = a.typ[i];
            // (a type added after dump_modify element has no name: its number)
            match self.elements.as_ref().and_then(|names| names.get(t - 1)) {
                Some(name) => s += name,
                None => s += &t.to_string(),
            }
            for d in 0..3 {
                s.push(' ');
                s += &format_printf("%g", a.x[i][d])?;
            }
            s.push('\n');
        }
        Ok(s)
    }

    /// The snapshot as a VTK XML document (positions as points, columns as point data;
    /// x, y, z columns are left out: they are the points).
    fn snapshot_vtu(&self, w: &World) -> Result<String, String> {
        let a = &w.state.atoms;
        let mut idx: Vec<usize> = (0..a.nlocal).filter(|&i| a.mask[i] & self.groupbit != 0).collect();
        idx.sort_by_key(|&i| a.tag[i]);
        let points: Vec<[f64; 3]> = idx.iter().map(|&i| a.x[i]).collect();
        let mut columns = vec![];
        for (name, c) in self.names.iter().zip(&self.columns) {
            if matches!(name.as_str(), "x" | "y" | "z") {
                continue;
            }
            let values = column_values(c, w, &idx).map_err(|e| format!("dump {}: {e}", self.id))?;
            columns.push((name.clone(), values, matches!(c, Column::Attr(f) if f.is_int())));
        }
        let fields = crate::output::dump_vtu::fields(columns);
        Ok(crate::output::dump_vtu::document(&points, &fields, w.state.step, w.state.time(), self.binary))
    }

    /// Write a VTU snapshot and rewrite the run's .pvd collection with it.
    fn write_vtu(&mut self, w: &World) -> Result<(), String> {
        let text = self.snapshot_vtu(w)?;
        let name = self.path.to_string_lossy().to_string();
        let step = w.state.step.to_string();
        let p = if name.contains('*') { PathBuf::from(name.replace('*', &step)) } else { PathBuf::from(name.replace(".vtu", &format!(".{step}.vtu"))) };
        write_atomic(&p, text.as_bytes()).map_err(|e| format!("dump {}: cannot write {}: {e}", self.id, p.display()))?;
        let file = p.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
        self.series.retain(|(_, f)| *f != file);
        self.series.push((w.state.time(), file));
        let pvd = self.pvd_path();
        write_atomic(&pvd, crate::output::dump_vtu::collection(&self.series).as_bytes()).map_err(|e| format!("dump {}: cannot write {}: {e}", self.id, pvd.display()))
    }

    /// The .pvd beside the snapshots: the file pattern without its `*` and `.vtu`
    /// (out.*.vtu -> out.pvd).
    fn pvd_path(&self) -> PathBuf {
        let file = self.path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
        let stem = file.trim_end_matches(".vtu").replace('*', "");
        let stem = stem.trim_matches(|c| c == '.' || c == '_' || c == '-');
        let stem = if stem.is_empty() { "dump" } else { stem };
        self.path.with_file_name(format!("{stem}.pvd"))
    }

    /// Write a snapshot now; `ev` evaluates variables (pictures' view settings, local computes).
    /// The dump writes values of computes or fixes (per-atom or local), not only atom values.
    pub fn reads_models(&self) -> bool {
        self.columns.iter().any(|c| matches!(c, Column::PerAtom(_) | Column::Local(_)))
    }

    /// The per-atom compute and fix columns (`c_ID`, `f_ID`), and the local ones.
    pub fn model_columns(&self) -> (Vec<&crate::models::compute::PerAtomRef>, Vec<&crate::models::compute::LocalRef>) {
        let peratom = self.columns.iter().filter_map(|c| if let Column::PerAtom(r) = c { Some(r) } else { None }).collect();
        (peratom, self.columns.iter().filter_map(|c| if let Column::Local(r) = c { Some(r) } else { None }).collect())
    }

    pub fn write(&mut self, w: &World, ev: &mut dyn dmhs_parser::EvalContext) -> Result<(), String> {
        if let Some(p) = &self.picture {
            p.write(w, &mut |name| dmhs_parser::variables::compute_equal(ev, name), self.groupbit).map_err(|e| format!("dump {}: {e}", self.id))?;
            self.last_written = Some(w.state.step);
            return Ok(());
        }
        if self.style == "vtk" {
            self.write_vtu(w)?;
            self.last_written = Some(w.state.step);
            return Ok(());
        }
        if let Some(dcd) = self.dcd.as_mut() {
            // write_dump's one snapshot has no interval (LAMMPS writes 0)
            let every = (self.id != "WRITE_DUMP").then_some(self.every);
            let mut idx = local_order(w, self.groupbit);
            idx.sort_by_key(|&i| w.state.atoms.tag[i]);
            dcd.write(w, &idx, every, &self.path).map_err(|e| format!("dump {}: {e}", self.id))?;
            self.last_written = Some(w.state.step);
            return Ok(());
        }
        let text = self.snapshot_with(w, Some(ev))?;
        let name = self.path.to_string_lossy().to_string();
        if name.contains('*') {
            let p = PathBuf::from(name.replace('*', &w.state.step.to_string()));
            write_atomic(&p, text.as_bytes()).map_err(|e| format!("dump {}: cannot write {}: {e}", self.id, p.display()))?;
        } else {
            if self.file.is_none() {
                let f = if self.append {
                    OpenOptions::new().create(true).append(true).open(&self.path)
                } else {
                    File::create(&self.path)
                };
                self.file = Some(f.map_err(|e| format!("dump {}: cannot open {}: {e}", self.id, self.path.display()))?);
            }
            let f = self.file.as_mut().unwrap();
            f.write_all(text.as_bytes()).and_then(|_| f.flush()).map_err(|e| format!("dump {}: cannot write {}: {e}", self.id, self.path.display()))?;
        }
        self.last_written = Some(w.state.step);
        Ok(())
    }
}

/// The owned atoms of the group `groupbit` in LAMMPS' local order, as an unsorted dump lists
/// them (the atoms gathered from the ranks of a distributed run: in rank order).
fn local_order(w: &World, groupbit: u32) -> Vec<usize> {
    let a = &w.state.atoms;
    let order: Vec<usize> = if w.state.decomp.is_some() { (0..a.nlocal).collect() } else { w.state.lammps_order.indices(a.nlocal).into_owned() };
    order.into_iter().filter(|&i| a.mask[i] & groupbit != 0).collect()
}

/// The values of one column for the owned atoms `idx`.
pub(crate) fn column_values(c: &Column, w: &World, idx: &[usize]) -> Result<Vec<f64>, String> {
    Ok(match c {
        Column::Attr(f) => idx.iter().map(|&i| f.value(w.state, i)).collect(),
        Column::PerAtom(r) => {
            let p = r.values(w)?;
            idx.iter().map(|&i| r.get(&p, i)).collect()
        }
        Column::Local(..) | Column::Index => return Err("local fields are for dump local only".into()),
    })
}

/// LAMMPS' `%-1.16e` for box bounds.
fn sci16(x: f64) -> String {
    format_printf("%-1.16e", x).unwrap_or_else(|_| format!("{x:e}"))
}

pub(crate) fn parse_column(name: &str, w: &World) -> Result<Column, String> {
    if let Some(r) = crate::models::compute::PerAtomRef::parse(name, w) {
        return Ok(Column::PerAtom(r?));
    }
    if name.starts_with("v_") || name.starts_with("d_") || name.starts_with("i_") {
        return Err(format!("dump field `{name}` is not supported yet (attributes, per-atom computes and fixes are)"));
    }
    let f = Field::parse(name).ok_or_else(|| format!("unknown dump field `{name}`"))?;
    f.check(w.state)?;
    Ok(Column::Attr(f))
}

/// Parse the `dump` words needed to find the ID (for `undump` / `dump_modify`).
pub fn find(dumps: &[Dump], w: &Word) -> Option<usize> {
    dumps.iter().position(|d| d.id == w.text)
}
