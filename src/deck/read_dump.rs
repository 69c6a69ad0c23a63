//! `read_dump` and the snapshots of `rerun`: which fields and keywords a command gives (LAMMPS'
//! ReadDump::fields_and_keywords), finding snapshots in one or more dump files (seek and next),
//! and putting a snapshot's atoms into the system (ReadDump::atoms: purge, replace, trim, add,
//! the snapshot's box, every atom remapped into the box).

use super::dump_reader::{Columns, CoordStyle, DumpReader, Field, Format, Header};
use crate::engine::atoms::NewAtom;
use crate::sim::Simulation;
use dmhs_parser::{Args, DResult};
use std::path::PathBuf;

/// What a read_dump (or rerun's `dump ...`) asks for.
#[derive(Clone, Debug)]
pub struct Spec {
    pub files: Vec<PathBuf>,
    /// The fields read; `id` first, then `type` when atoms are added.
    pub fields: Vec<Field>,
    /// `label field column`: the column of each field, where given.
    pub label: Vec<Option<String>>,
    /// `scaled` and `wrapped`: how labelled coordinate columns (and XYZ files) store positions.
    pub given: CoordStyle,
    pub boxflag: bool,
    pub timestep: bool,
    pub replace: bool,
    pub purge: bool,
    pub trim: bool,
    pub add: Add,
    pub format: Format,
}

/// `add no|yes|keep`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Add {
    No,
    /// New atoms get IDs after the largest one (LAMMPS' tag_extend).
    Yes,
    /// New atoms keep the snapshot's IDs.
    Keep,
}

pub const KEYWORDS: &str = "[box yes|no] [timestep yes|no] [replace yes|no] [purge yes|no] [trim yes|no] [add yes|keep|no] [label field column] [scaled yes|no] [wrapped yes|no] [format native|xyz]";

/// The fields and keywords after a read_dump's step (or rerun's `dump`), as LAMMPS parses them.
pub fn parse_spec(sim: &Simulation, a: &mut Args, files: Vec<PathBuf>) -> DResult<Spec> {
    let words = a.remaining();
    // `add yes|keep` anywhere makes the type a field
    let adds = words.windows(2).any(|w| w[0].text == "add" && matches!(w[1].text.as_str(), "yes" | "keep"));
    let mut fields = vec![Field::Id];
    if adds {
        fields.push(Field::Type);
    }
    let dim = sim.state.domain.as_ref().map_or(3, |d| d.dimension);
    while let Some(w) = a.peek() {
        let Some(f) = Field::named(&w.text) else { break };
        if f == Field::Q && !sim.state.atoms.features.charge {
            return Err(a.error_at(w, "Read dump of atom property that isn't allocated: q needs an atom style with charges", "no charges"));
        }
        if dim == 2 && matches!(f, Field::Z | Field::Vz | Field::Iz | Field::Fz) {
            return Err(a.error_at(w, format!("read_dump field {} in a 2d simulation", w.text), "2d"));
        }
        if fields.contains(&f) {
            return Err(a.error_at(w, format!("Duplicate fields in read_dump command: {}", w.text), "given twice"));
        }
        fields.push(f);
        a.skip(1);
    }
    if matches!(fields.last(), Some(Field::Id | Field::Type)) {
        let at = a.peek().or(a.last());
        let msg = "read_dump needs at least one field: x y z vx vy vz q ix iy iz fx fy fz";
        return Err(match at {
            Some(w) => a.error_at(w, msg, "expected a field"),
            None => a.error_command(msg, "no fields"),
        });
    }
    let mut s = Spec {
        files,
        label: vec![None; fields.len()],
        fields,
        given: CoordStyle { scaled: false, wrapped: true },
        boxflag: true,
        timestep: true,
        replace: true,
        purge: false,
        trim: false,
        add: Add::No,
        format: Format::Native,
    };
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "box" => s.boxflag = a.yes_no("box")?,
            "timestep" => s.timestep = a.yes_no("timestep")?,
            "replace" => s.replace = a.yes_no("replace")?,
            "purge" => s.purge = a.yes_no("purge")?,
            "trim" => s.trim = a.yes_no("trim")?,
            "add" => s.add = [Add::Yes, Add::Keep, Add::No][a.choice("add", &["yes", "keep", "no"])?],
            "scaled" => s.given.scaled = a.yes_no("scaled")?,
            "wrapped" => s.given.wrapped = a.yes_no("wrapped")?,
            "label" => {
                let fw = a.word("field")?;
                let k = Field::named(&fw.text).and_then(|f| s.fields.iter().position(|&g| g == f));
                let k = k.ok_or_else(|| a.error_at(fw, format!("read_dump label: `{}` is not one of the fields read", fw.text), "not a field of this read_dump"))?;
                s.label[k] = Some(a.word("column label")?.text.clone());
            }
            "nfile" => {
                a.i64("nfile")?;
                return Err(a.error_at(w, "Dump file is not a multi-proc file: nfile is for parallel dump files (% in the name), which dmhs does not read", "not a parallel dump"));
            }
            "format" => {
                let fw = a.word("format")?;
                s.format = match fw.text.as_str() {
                    "native" => Format::Native,
                    "xyz" => Format::Xyz,
                    "molfile" | "adios" => {
                        return Err(a.error_at(fw, format!("read_dump format {} needs a LAMMPS package (MOLFILE's VMD plugins or ADIOS) that dmhs does not have", fw.text), "not supported").with_help("write the dump as `dump custom` (format native) or `dump xyz`"));
                    }
                    _ => return Err(a.error_at(fw, format!("Unknown dump reader style {}", fw.text), "expected native or xyz")),
                };
                if let Some(extra) = a.peek() {
                    return Err(a.error_at(extra, format!("format {} takes no further arguments", fw.text), "unexpected"));
                }
            }
            _ => return Err(a.unknown_keyword(w, &["box", "timestep", "replace", "purge", "trim", "add", "label", "scaled", "wrapped", "nfile", "format"])),
        }
    }
    if s.purge && (s.replace || s.trim) {
        return Err(a.error_command("If read_dump purges it cannot replace or trim (purge yes needs replace no, trim no)", "purge with replace or trim"));
    }
    if let Some(p) = s.files.iter().find(|p| p.to_string_lossy().contains('%')) {
        return Err(a.error_command(format!("parallel dump files (% in `{}`) are not supported: write the dump as one file", p.display()), "parallel dump file"));
    }
    if s.format == Format::Xyz && s.given.scaled {
        return Err(a.error_command("read_dump scaled yes needs the box of a native dump file: XYZ files have none", "scaled XYZ"));
    }
    Ok(s)
}

/// Snapshots of the spec's files, read forward (LAMMPS' ReadDump seek, next, header, atoms).
pub struct DumpSource {
    pub spec: Spec,
    reader: DumpReader,
    /// The file being read.
    current: usize,
    columns: Option<Columns>,
    /// A rerun's snapshot read and not yet applied.
    pending: Option<Snapshot>,
}

/// A snapshot's header and its atoms' field values.
pub struct Snapshot {
    pub header: Header,
    pub rows: Vec<Vec<f64>>,
}

/// What a snapshot did to the system (read_dump's report).
#[derive(Clone, Copy, Debug, Default)]
pub struct Counts {
    pub snapshot: u64,
    pub purged: usize,
    pub replaced: usize,
    pub trimmed: usize,
    pub added: usize,
}

impl DumpSource {
    pub fn new(spec: Spec) -> DumpSource {
        let reader = DumpReader::new(spec.format);
        DumpSource { spec, reader, current: 0, columns: None, pending: None }
    }

    /// The first snapshot whose step is `nrequest` (`exact`) or at least `nrequest`, over the
    /// files in order; None if there is none.
    pub fn seek(&mut self, nrequest: i64, exact: bool) -> Result<Option<i64>, String> {
        let mut found = None;
        for k in 0..self.spec.files.len() {
            self.reader.open(&self.spec.files[k])?;
            self.current = k;
            while let Some(t) = self.reader.read_time()? {
                if t >= nrequest {
                    found = Some(t);
                    break;
                }
                self.reader.skip()?;
            }
            if found.is_some() {
                break;
            }
        }
        Ok(found.filter(|&t| !exact || t == nrequest))
    }

    /// The next snapshot after step `ncurrent` up to `nlast`, a multiple of `nevery` (if not
    /// 0), one in `nskip` of those (LAMMPS' count, which includes the snapshots `nevery`
    /// passes over); None when the files end or the next step is past `nlast`.
    pub fn next(&mut self, ncurrent: i64, nlast: i64, nevery: i64, nskip: i64) -> Result<Option<i64>, String> {
        let mut iskip = 0;
        let mut k = self.current;
        while k < self.spec.files.len() {
            if k != self.current {
                self.reader.open(&self.spec.files[k])?;
                self.current = k;
            }
            while let Some(t) = self.reader.read_time()? {
                if t > nlast {
                    return Ok(None);
                }
                if t <= ncurrent {
                    self.reader.skip()?;
                    continue;
                }
                if iskip == nskip {
                    iskip = 0;
                }
                iskip += 1;
                if (nevery != 0 && t % nevery != 0) || iskip < nskip {
                    self.reader.skip()?;
                } else {
                    return Ok(Some(t));
                }
            }
            k += 1;
        }
        Ok(None)
    }

    /// The snapshot found last: its header and atoms. `first`: the first of the read, whose
    /// column labels choose the columns (and whose box is checked).
    pub fn snapshot(&mut self, first: bool) -> Result<Snapshot, String> {
        let mut labels = Vec::new();
        let header = self.reader.read_header(first.then_some(&mut labels))?;
        if first {
            if header.bounds.is_none() && self.spec.boxflag {
                return Err("No box information in dump, must use 'box no' (XYZ files have no box)".to_string());
            }
            self.columns = Some(self.reader.columns(&self.spec.fields, &self.spec.label, &labels, self.spec.given)?);
        }
        let cols = self.columns.as_ref().expect("columns of the first snapshot");
        let rows = self.reader.read_atoms(header.natoms, &self.spec.fields, cols)?;
        Ok(Snapshot { header, rows })
    }

    /// How the coordinates read store positions.
    fn coords(&self) -> CoordStyle {
        self.columns.as_ref().map_or(self.spec.given, |c| c.coords)
    }

    /// Put the snapshot's atoms into the system (LAMMPS' ReadDump::atoms on one process).
    pub fn apply(&self, sim: &mut Simulation, snap: &Snapshot) -> Result<Counts, String> {
        let s = &self.spec;
        let coords = self.coords();
        let st = &mut sim.state;
        st.atoms.clear_ghosts();
        let mut counts = Counts { snapshot: snap.rows.len() as u64, ..Counts::default() };
        if s.purge {
            counts.purged = st.delete_owned(&vec![true; st.atoms.nlocal]);
        }
        let dim = st.domain.as_ref().map_or(3, |d| d.dimension);
        let tilted = st.domain.as_ref().is_some_and(|d| d.triclinic());
        let sbox = SnapBox::of(&snap.header);
        if s.boxflag && sbox.tilt.is_some() != tilted {
            return Err(format!("Read_dump triclinic status does not match simulation: the snapshot's box is {}, the simulation's {}", ["orthogonal", "triclinic"][sbox.tilt.is_some() as usize], ["orthogonal", "triclinic"][tilted as usize]));
        }
        // the columns of x, y, z among the fields
        let column = |f: Field| s.fields.iter().position(|&g| g == f);
        let cols = [column(Field::X), column(Field::Y), column(Field::Z)];
        if coords.scaled && tilted && (cols[0].is_none() || cols[1].is_none() || (dim == 3 && cols[2].is_none())) {
            return Err("All read_dump x,y,z fields must be specified for scaled, triclinic coords".to_string());
        }
        // positions in the snapshot's box (a scaled column is a fraction of it; in a triclinic
        // simulation the other fractions carry the tilts, LAMMPS' xfield/yfield/zfield)
        let (lo, prd) = (sbox.lo, sbox.prd);
        let [xy, xz, yz] = sbox.tilt.unwrap_or([0.0; 3]);
        let position = |row: &[f64], d: usize| {
            let v = row[cols[d].expect("a coordinate field")];
            let frac = |k: usize| row[cols[k].expect("x, y and z of a scaled triclinic snapshot")];
            match (coords.scaled, tilted, d) {
                (false, _, _) => v,
                (true, false, _) | (true, true, 2) => v * prd[d] + lo[d],
                (true, true, 0) if dim == 2 => prd[0] * v + xy * frac(1) + lo[0],
                (true, true, 0) => prd[0] * v + xy * frac(1) + xz * frac(2) + lo[0],
                (true, true, _) if dim == 2 => prd[1] * v + lo[1],
                (true, true, _) => prd[1] * v + yz * frac(2) + lo[1],
            }
        };
        let map = st.atoms.tag_map();
        let nlocal = st.atoms.nlocal;
        let mut updated = vec![false; nlocal];
        let mut new_rows = Vec::new();
        for row in &snap.rows {
            let tag = row[0] as i64;
            let Some(m) = map.get(tag).filter(|&m| m < nlocal) else {
                new_rows.push(row);
                continue;
            };
            updated[m] = true;
            if !s.replace {
                continue;
            }
            counts.replaced += 1;
            let a = &mut st.atoms;
            let mut image = a.image[m];
            for (k, &f) in s.fields.iter().enumerate().skip(1) {
                let v = row[k];
                match f {
                    Field::Id | Field::Type => {}
                    Field::X | Field::Y | Field::Z => {
                        let d = f.coordinate().unwrap();
                        a.x[m][d] = position(row, d);
                    }
                    Field::Vx => a.v[m][0] = v,
                    Field::Vy => a.v[m][1] = v,
                    Field::Vz => a.v[m][2] = v,
                    Field::Q => a.q[m] = v,
                    Field::Ix => image[0] = v as i32,
                    Field::Iy => image[1] = v as i32,
                    Field::Iz => image[2] = v as i32,
                    Field::Fx => a.f[m][0] = v,
                    Field::Fy => a.f[m][1] = v,
                    Field::Fz => a.f[m][2] = v,
                }
            }
            // unwrapped coordinates (or none read) start again from image 0
            a.image[m] = if coords.wrapped { image } else { [0; 3] };
        }
        if s.trim {
            let gone: Vec<bool> = updated.iter().map(|u| !u).collect();
            counts.trimmed = st.delete_owned(&gone);
        }
        if s.add != Add::No {
            let ntypes = st.ntypes;
            let mut next = st.atoms.tag[..st.atoms.nlocal].iter().copied().max().unwrap_or(0);
            for row in new_rows {
                let mut atom = NewAtom::at(0, 0, [0.0; 3]);
                for (k, &f) in s.fields.iter().enumerate() {
                    let v = row[k];
                    match f {
                        Field::Id => atom.tag = v as i64,
                        Field::Type => atom.typ = v as i64 as usize,
                        Field::X | Field::Y | Field::Z => {
                            let d = f.coordinate().unwrap();
                            atom.x[d] = position(row, d);
                        }
                        Field::Vx => atom.v[0] = v,
                        Field::Vy => atom.v[1] = v,
                        Field::Vz => atom.v[2] = v,
                        Field::Q => atom.q = v,
                        Field::Ix => atom.image[0] = v as i32,
                        Field::Iy => atom.image[1] = v as i32,
                        Field::Iz => atom.image[2] = v as i32,
                        Field::Fx | Field::Fy | Field::Fz => {}
                    }
                }
                let t = row[1];
                if !(t >= 1.0 && (t as i64 as usize) <= ntypes) {
                    return Err(format!("Invalid atom type {t} of dump atom ID {} to add (the box has types 1 to {ntypes})", row[0] as i64));
                }
                if s.add == Add::Yes {
                    next += 1;
                    atom.tag = next;
                } else if atom.tag <= 0 || atom.tag > crate::engine::atoms::MAX_ATOM_ID {
                    return Err(format!("One or more atom IDs is zero, negative or too big: dump atom ID {} cannot be kept (add keep)", atom.tag));
                }
                st.atoms.push(&atom);
                counts.added += 1;
            }
        }
        let mut warning = None;
        if let (true, Some(_)) = (s.boxflag, snap.header.bounds) {
            let domain = st.domain.as_mut().expect("a box");
            for d in 0..dim {
                if !(sbox.hi[d] > sbox.lo[d]) {
                    return Err(format!("the snapshot's box is empty or inverted in {}: {} to {}", ["x", "y", "z"][d], sbox.lo[d], sbox.hi[d]));
                }
                (domain.lo[d], domain.hi[d]) = (sbox.lo[d], sbox.hi[d]);
            }
            if let Some(t) = domain.tilt.as_mut() {
                t[0] = xy;
                if dim == 3 {
                    (t[1], t[2]) = (xz, yz);
                }
            }
            warning = crate::deck::tilt_check(domain)?;
            st.box_initial = Some(domain.clone());
        }
        let n = st.atoms.nlocal;
        if let Some(i) = (0..n).find(|&i| !st.atoms.x[i].iter().all(|c| c.is_finite())) {
            return Err(format!("atom {} has a non-finite position in the dump snapshot", st.atoms.tag[i]));
        }
        // (every rank holds every atom between runs: the shrink-wrap is the same on each)
        let domain = st.domain.as_mut().expect("a box");
        crate::engine::boundary::remap_and_migrate(domain, st.box_initial.as_ref(), &mut st.atoms);
        st.lists_valid = false;
        // unsorted output before the next build lists the atoms in LAMMPS' order
        st.lammps_order.refresh(&st.atoms);
        if let Some(w) = warning {
            sim.out.print(&w);
        }
        Ok(counts)
    }
}

/// A snapshot's box (LAMMPS' ReadDump::header): a triclinic snapshot's bounds are those of
/// the box's bounding box, so the tilts' reach is taken off them.
struct SnapBox {
    lo: [f64; 3],
    hi: [f64; 3],
    prd: [f64; 3],
    /// `[xy, xz, yz]` of a triclinic snapshot.
    tilt: Option<[f64; 3]>,
}

impl SnapBox {
    fn of(h: &Header) -> SnapBox {
        let b = h.bounds.unwrap_or([[0.0; 2]; 3]);
        let (mut lo, mut hi): ([f64; 3], [f64; 3]) = (std::array::from_fn(|d| b[d][0]), std::array::from_fn(|d| b[d][1]));
        if let Some([xy, xz, yz]) = h.tilt {
            lo[0] -= 0.0f64.min(xy).min(xz).min(xy + xz);
            hi[0] -= 0.0f64.max(xy).max(xz).max(xy + xz);
            lo[1] -= 0.0f64.min(yz);
            hi[1] -= 0.0f64.max(yz);
        }
        let prd = std::array::from_fn(|d| hi[d] - lo[d]);
        SnapBox { lo, hi, prd, tilt: h.tilt }
    }
}

impl crate::sim::rerun::SnapshotSource for DumpSource {
    fn seek(&mut self, first: i64) -> Result<Option<i64>, String> {
        DumpSource::seek(self, first, false)
    }
    fn next(&mut self, current: i64, last: i64, every: i64, skip: i64) -> Result<Option<i64>, String> {
        DumpSource::next(self, current, last, every, skip)
    }
    fn read(&mut self, first: bool) -> Result<(), String> {
        self.pending = Some(self.snapshot(first)?);
        Ok(())
    }
    fn apply(&mut self, sim: &mut Simulation) -> Result<(), String> {
        let snap = self.pending.take().ok_or("no snapshot was read")?;
        DumpSource::apply(self, sim, &snap).map(|_| ())
    }
}

/// The lines read_dump prints after a snapshot is read (LAMMPS' report).
pub fn report(sim: &mut Simulation, before: usize, c: &Counts) {
    let text = format!(
        "  {}\n  {before} atoms before read\n  {} atoms in snapshot\n  {} atoms purged\n  {} atoms replaced\n  {} atoms trimmed\n  {} atoms added\n  {} atoms after read",
        crate::deck::box_text(sim.state.domain.as_ref().expect("a box")),
        c.snapshot,
        c.purged,
        c.replaced,
        c.trimmed,
        c.added,
        sim.state.atoms.nlocal
    );
    sim.out.print(&text);
}
