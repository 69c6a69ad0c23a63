//! `write_restart FILE` and `read_restart FILE`: everything a continued run needs, so that
//! `read_restart` followed by the same commands continues bit for bit where `write_restart`
//! left off (contact histories included, which LAMMPS' data files cannot carry).
//!
//! The file is plain text in dmhs' own format (numbers in Rust's shortest round-trip form, so
//! every double comes back exactly). It holds:
//! * units, dimension, boundary, atom style, newton flags, `comm_modify vel`, timestep size,
//!   current step and time, the box (and the box as created, for shrink-wrapping);
//! * atom types and per-type masses, group names, topology type counts;
//! * every owned atom with all its per-atom arrays, in the current storage order (the order
//!   decides how forces are summed, so it is kept), and the per-atom arrays of fixes (e.g. the
//!   wall spring of fix wall/gran), restored to a fix defined again with the same ID;
//! * bonds, angles, dihedrals;
//! * the force-field commands (pair_style, pair_coeff, pair_modify, bond/angle/dihedral styles
//!   and coefficients, special_bonds) as they were given; read_restart replays them;
//! * the contact histories of the pair style, by atom IDs and periodic image.
//!
//! As with LAMMPS, fixes, computes, outputs, variables, regions and the neighbour settings
//! (`neighbor`, `neigh_modify`) are not stored: the continuing deck defines them again.
//! A continuation is bit-identical when it does so with the same values and runs with
//! `pre yes` (the default), like the `run` that would have followed `write_restart`.

use crate::engine::atoms::{AtomFeatures, Atoms, ExtraArray};
use crate::engine::contact_history::ContactRecord;
use crate::engine::domain::{BoundaryKind, Domain};
use crate::sim::Simulation;
use crate::engine::topology::{Angle, Bond, Dihedral};
use crate::engine::units::{UnitStyle, Units};
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Span, Word};
use std::fmt::Write as _;

const MAGIC: &str = "DMHS restart 1";

/// Encode a word so that it contains no whitespace (percent-encoding of space, tab, newline, %).
fn enc(w: &str) -> String {
    let mut s = String::with_capacity(w.len());
    for c in w.chars() {
        match c {
            '%' => s.push_str("%25"),
            ' ' => s.push_str("%20"),
            '\t' => s.push_str("%09"),
            '\n' => s.push_str("%0A"),
            '\r' => s.push_str("%0D"),
            _ => s.push(c),
        }
    }
    s
}

fn dec(w: &str) -> String {
    w.replace("%20", " ").replace("%09", "\t").replace("%0A", "\n").replace("%0D", "\r").replace("%25", "%")
}

fn boundary_word(b: &[BoundaryKind; 2]) -> String {
    if b[0] == b[1] { b[0].letter().to_string() } else { format!("{}{}", b[0].letter(), b[1].letter()) }
}

fn boundary_from(s: &str) -> Option<[BoundaryKind; 2]> {
    let k = |c: char| match c {
        'p' => Some(BoundaryKind::Periodic),
        'f' => Some(BoundaryKind::Fixed),
        's' => Some(BoundaryKind::Shrink),
        'm' => Some(BoundaryKind::ShrinkMin),
        _ => None,
    };
    let c: Vec<char> = s.chars().collect();
    match c.len() {
        1 => k(c[0]).map(|b| [b, b]),
        2 => Some([k(c[0])?, k(c[1])?]),
        _ => None,
    }
}

fn f3(s: &mut String, v: &[f64; 3]) {
    let _ = write!(s, " {:?} {:?} {:?}", v[0], v[1], v[2]);
}

/// The restart text of the current state.
pub fn restart_text(sim: &mut Simulation) -> Result<String, String> {
    let domain = sim.state.domain.clone().ok_or("write_restart before the simulation box is defined")?;
    let mut s = String::new();
    let _ = writeln!(s, "{MAGIC}");
    let _ = writeln!(s, "step {}", sim.state.step);
    let _ = writeln!(s, "atime {:?} {}", sim.state.atime, sim.state.atimestep);
    let _ = writeln!(s, "dt {:?} {}", sim.state.dt, sim.state.dt_set as i32);
    let _ = writeln!(s, "units {}", sim.state.units.name());
    let _ = writeln!(s, "dimension {}", sim.state.dimension);
    let _ = writeln!(s, "boundary {}", sim.state.boundary.iter().map(boundary_word).collect::<Vec<_>>().join(" "));
    let _ = writeln!(s, "atom_style {}", sim.state.atom_style.iter().map(|w| enc(w)).collect::<Vec<_>>().join(" "));
    let _ = writeln!(s, "newton {} {}", sim.state.newton_pair as i32, sim.state.newton_bond as i32);
    let _ = writeln!(s, "comm_vel {}", sim.state.comm_vel as i32);
    let mut line = String::from("box");
    f3(&mut line, &domain.lo);
    f3(&mut line, &domain.hi);
    let _ = writeln!(s, "{line}");
    if let Some(b) = &sim.state.box_initial {
        let mut line = String::from("box_initial");
        f3(&mut line, &b.lo);
        f3(&mut line, &b.hi);
        let _ = writeln!(s, "{line}");
    }
    let _ = writeln!(s, "ntypes {}", sim.state.ntypes);
    let mut line = String::from("masses");
    for t in 1..=sim.state.ntypes {
        let _ = write!(line, " {:?} {}", sim.state.type_mass[t], sim.state.mass_set[t] as i32);
    }
    let _ = writeln!(s, "{line}");
    let t = &sim.state.topo;
    let _ = writeln!(s, "topology_types {} {} {} {}", t.nbondtypes, t.nangletypes, t.ndihedraltypes, t.nimpropertypes);
    for (k, name) in sim.state.groups.names() {
        let _ = writeln!(s, "group {k} {}", enc(name));
    }

    // atoms, in storage order
    let a = &sim.state.atoms;
    let n = a.nlocal;
    let ft = a.features;
    let _ = writeln!(s, "atoms {n}");
    for i in 0..n {
        let mut l = format!("{} {} {}", a.tag[i], a.typ[i], a.mask[i]);
        f3(&mut l, &a.x[i]);
        f3(&mut l, &a.v[i]);
        let _ = write!(l, " {} {} {}", a.image[i][0], a.image[i][1], a.image[i][2]);
        if ft.molecule {
            let _ = write!(l, " {}", a.molecule[i]);
        }
        if ft.charge {
            let _ = write!(l, " {:?}", a.q[i]);
        }
        if ft.sphere {
            let _ = write!(l, " {:?} {:?}", a.radius[i], a.rmass[i]);
            f3(&mut l, &a.omega[i]);
        }
        if ft.sph {
            let _ = write!(l, " {:?} {:?} {:?} {:?} {:?}", a.rho[i], a.drho[i], a.esph[i], a.desph[i], a.cv[i]);
            f3(&mut l, &a.vest[i]);
        }
        let _ = writeln!(s, "{l}");
    }
    for e in &a.extra {
        let _ = writeln!(s, "extra {} {} {}", enc(&e.name), e.stride, if e.ghosts { "ghosts" } else { "owned" });
        for i in 0..n {
            let vals: Vec<String> = e.data[i * e.stride..(i + 1) * e.stride].iter().map(|v| format!("{v:?}")).collect();
            let _ = writeln!(s, "{}", vals.join(" "));
        }
    }
    let _ = writeln!(s, "bonds {}", t.bonds.len());
    for b in &t.bonds {
        let _ = writeln!(s, "{} {} {}", b.typ, b.atoms[0], b.atoms[1]);
    }
    let _ = writeln!(s, "angles {}", t.angles.len());
    for b in &t.angles {
        let _ = writeln!(s, "{} {} {} {}", b.typ, b.atoms[0], b.atoms[1], b.atoms[2]);
    }
    let _ = writeln!(s, "dihedrals {}", t.dihedrals.len());
    for b in &t.dihedrals {
        let _ = writeln!(s, "{} {} {} {} {}", b.typ, b.atoms[0], b.atoms[1], b.atoms[2], b.atoms[3]);
    }
    for words in &sim.ff_commands {
        let _ = writeln!(s, "command {}", words.iter().map(|w| enc(w)).collect::<Vec<_>>().join(" "));
    }
    if let Some(p) = sim.pair.as_mut() {
        for (k, h) in p.histories().into_iter().enumerate() {
            let recs = h.records();
            let _ = writeln!(s, "contacts {k} {} {}", h.size(), recs.len());
            for r in recs {
                let mut l = format!("{} {} {} {} {}", r.owner, r.partner, r.image[0], r.image[1], r.image[2]);
                for v in &r.values {
                    let _ = write!(l, " {v:?}");
                }
                let _ = writeln!(s, "{l}");
            }
        }
    }
    let _ = writeln!(s, "end");
    Ok(s)
}

pub const WRITE_SYNTAX: &str = "write_restart file  (a * in the name becomes the current step)";
pub const READ_SYNTAX: &str = "read_restart file";

/// `write_restart file`: written to a temporary name, then renamed (no half-written files).
pub fn write_restart(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, WRITE_SYNTAX);
    let w = a.word("file name")?;
    while let Some(k) = a.peek() {
        a.skip(1);
        match k.text.as_str() {
            "fileper" | "nfile" => return Err(a.error_at(k, format!("write_restart {} is for MPI runs (dmhs writes one file)", k.text), "not supported")),
            "noinit" => {}
            _ => return Err(a.unknown_keyword(k, &["noinit"])),
        }
    }
    let name = w.text.replace('*', &sim.state.step.to_string());
    let path = sim.path(&name);
    let text = restart_text(sim).map_err(|e| Diagnostic::at(cmd.span, e, "here"))?;
    let tmp = path.with_extension("tmp-restart");
    std::fs::write(&tmp, text)
        .and_then(|_| std::fs::rename(&tmp, &path))
        .map_err(|e| a.error_at(w, format!("cannot write restart file `{}`: {e}", path.display()), "cannot write"))?;
    Ok(())
}

/// A line cursor over the restart text with located errors.
struct Reader<'t> {
    lines: Vec<&'t str>,
    pos: usize,
    file: String,
}

impl<'t> Reader<'t> {
    fn err(&self, msg: impl std::fmt::Display) -> String {
        format!("restart file {} line {}: {msg}", self.file, self.pos)
    }
    fn next(&mut self) -> Result<&'t str, String> {
        let l = self.lines.get(self.pos).copied().ok_or_else(|| self.err("unexpected end of file"))?;
        self.pos += 1;
        Ok(l)
    }
    /// The next line, which must start with `key`; returns the remaining words.
    fn keyed(&mut self, key: &str) -> Result<Vec<&'t str>, String> {
        let l = self.next()?;
        let mut w = l.split_whitespace();
        if w.next() != Some(key) {
            return Err(self.err(format!("expected `{key}`, found `{l}`")));
        }
        Ok(w.collect())
    }
    fn peek_key(&self) -> Option<&'t str> {
        self.lines.get(self.pos).and_then(|l| l.split_whitespace().next())
    }
    fn num<T: std::str::FromStr>(&self, w: Option<&&str>) -> Result<T, String> {
        let w = w.ok_or_else(|| self.err("missing value"))?;
        w.parse::<T>().map_err(|_| self.err(format!("bad number `{w}`")))
    }
}

/// `read_restart file`: restore the state written by write_restart (before any box exists).
pub fn read_restart(sim: &mut Simulation, cmd: &Command, sources: &mut SourceMap) -> DResult<()> {
    crate::deck::commands::before_box(sim, cmd)?;
    let mut a = Args::new(cmd, READ_SYNTAX);
    let w = a.word("file name")?;
    a.finish()?;
    let path = sim.path(&w.text);
    let text = std::fs::read_to_string(&path).map_err(|e| a.error_at(w, format!("cannot read restart file `{}`: {e}", path.display()), "cannot read"))?;
    let commands = restore(sim, &text, &path.display().to_string()).map_err(|e| Diagnostic::at(w.span, e, "this restart file"))?;
    // replay the force-field commands
    let pending = commands.1;
    for words in commands.0 {
        let line = words.join(" ");
        let id = sources.add(format!("{} (force field)", path.display()), line.clone());
        let mut ws = Vec::new();
        let mut off = 0;
        for t in &words {
            ws.push(Word::new(t.clone(), Span::new(id, off, off + t.len())));
            off += t.len() + 1;
        }
        let name = ws.remove(0);
        let span = Span::new(id, 0, line.len());
        let c = Command { name, args: ws, span };
        sim.execute_command(&c, sources).map_err(|d| d.with_note(format!("while replaying the force field stored in restart file {}", path.display())))?;
    }
    if let Some(p) = sim.pair.as_mut() {
        let mut hs = p.histories();
        for (k, size, recs) in pending {
            match hs.get_mut(k) {
                Some(h) if h.size() == size => h.restore(recs),
                _ => return Err(Diagnostic::at(w.span, format!("restart file {}: contact history {k} does not fit the pair style", path.display()), "this restart file")),
            }
        }
    }
    sim.out.print(&format!("Read restart file {} at step {}: {} atoms", path.display(), sim.state.step, sim.state.atoms.nlocal));
    Ok(())
}

type Pending = Vec<(usize, usize, Vec<ContactRecord>)>;

/// Restore the state; returns the force-field commands to replay and the contact histories.
fn restore(sim: &mut Simulation, text: &str, file: &str) -> Result<(Vec<Vec<String>>, Pending), String> {
    let mut r = Reader { lines: text.lines().collect(), pos: 0, file: file.to_string() };
    if r.next()? != MAGIC {
        return Err(r.err(format!("not a dmhs restart file (the first line must be `{MAGIC}`)")));
    }
    let v = r.keyed("step")?;
    let step: i64 = r.num(v.first())?;
    let v = r.keyed("atime")?;
    let atime: f64 = r.num(v.first())?;
    let atimestep: i64 = r.num(v.get(1))?;
    let v = r.keyed("dt")?;
    let dt: f64 = r.num(v.first())?;
    let dt_set = r.num::<i32>(v.get(1))? != 0;
    let v = r.keyed("units")?;
    let units = match v.first().copied() {
        Some("lj") => UnitStyle::Lj,
        Some("si") => UnitStyle::Si,
        Some("cgs") => UnitStyle::Cgs,
        other => return Err(r.err(format!("unknown units {other:?}"))),
    };
    let v = r.keyed("dimension")?;
    let dimension: usize = r.num(v.first())?;
    let v = r.keyed("boundary")?;
    if v.len() != 3 {
        return Err(r.err("boundary needs 3 entries"));
    }
    let mut boundary = [[BoundaryKind::Periodic; 2]; 3];
    for d in 0..3 {
        boundary[d] = boundary_from(v[d]).ok_or_else(|| r.err(format!("bad boundary `{}`", v[d])))?;
    }
    let v = r.keyed("atom_style")?;
    let atom_style: Vec<String> = v.iter().map(|w| dec(w)).collect();
    let names: Vec<&str> = atom_style.iter().map(|s| s.as_str()).filter(|s| *s != "hybrid").collect();
    let features: AtomFeatures = crate::deck::commands::features_of(&names).map_err(|e| r.err(format!("unknown atom style `{e}`")))?;
    let v = r.keyed("newton")?;
    let newton = (r.num::<i32>(v.first())? != 0, r.num::<i32>(v.get(1))? != 0);
    let v = r.keyed("comm_vel")?;
    let comm_vel = r.num::<i32>(v.first())? != 0;
    let v = r.keyed("box")?;
    let nums = |r: &Reader, v: &[&str]| -> Result<Vec<f64>, String> { v.iter().map(|w| w.parse::<f64>().map_err(|_| r.err(format!("bad number `{w}`")))).collect() };
    let b = nums(&r, &v)?;
    if b.len() != 6 {
        return Err(r.err("box needs 6 numbers"));
    }
    let domain = Domain { dimension, lo: [b[0], b[1], b[2]], hi: [b[3], b[4], b[5]], boundary };
    let mut box_initial = None;
    if r.peek_key() == Some("box_initial") {
        let v = r.keyed("box_initial")?;
        let b = nums(&r, &v)?;
        if b.len() != 6 {
            return Err(r.err("box_initial needs 6 numbers"));
        }
        box_initial = Some(Domain { dimension, lo: [b[0], b[1], b[2]], hi: [b[3], b[4], b[5]], boundary });
    }
    let v = r.keyed("ntypes")?;
    let ntypes: usize = r.num(v.first())?;
    let v = r.keyed("masses")?;
    if v.len() != 2 * ntypes {
        return Err(r.err("masses needs a mass and a flag per type"));
    }
    let mut type_mass = vec![0.0; ntypes + 1];
    let mut mass_set = vec![false; ntypes + 1];
    for t in 1..=ntypes {
        type_mass[t] = r.num(v.get(2 * (t - 1)))?;
        mass_set[t] = r.num::<i32>(v.get(2 * (t - 1) + 1))? != 0;
    }
    let v = r.keyed("topology_types")?;
    let tt: Vec<usize> = v.iter().map(|w| w.parse::<usize>().map_err(|_| r.err("bad count"))).collect::<Result<_, _>>()?;
    if tt.len() != 4 {
        return Err(r.err("topology_types needs 4 counts"));
    }
    let mut groups = crate::engine::groups::Groups::default();
    while r.peek_key() == Some("group") {
        let v = r.keyed("group")?;
        let k: usize = r.num(v.first())?;
        let name = dec(v.get(1).ok_or_else(|| r.err("group without a name"))?);
        groups.set_index(k, &name).map_err(|e| r.err(e))?;
    }

    // atoms
    let v = r.keyed("atoms")?;
    let n: usize = r.num(v.first())?;
    let mut atoms = Atoms::new(features);
    for _ in 0..n {
        let l = r.next()?;
        let w: Vec<&str> = l.split_whitespace().collect();
        let mut c = 0usize;
        let mut take = |r: &Reader| -> Result<&str, String> {
            let x = w.get(c).copied().ok_or_else(|| r.err("too few values for an atom"))?;
            c += 1;
            Ok(x)
        };
        let f = |r: &Reader, s: &str| s.parse::<f64>().map_err(|_| r.err(format!("bad number `{s}`")));
        let i = |r: &Reader, s: &str| s.parse::<i64>().map_err(|_| r.err(format!("bad integer `{s}`")));
        atoms.tag.push(i(&r, take(&r)?)?);
        atoms.typ.push(i(&r, take(&r)?)? as usize);
        atoms.mask.push(i(&r, take(&r)?)? as u32);
        atoms.x.push([f(&r, take(&r)?)?, f(&r, take(&r)?)?, f(&r, take(&r)?)?]);
        atoms.v.push([f(&r, take(&r)?)?, f(&r, take(&r)?)?, f(&r, take(&r)?)?]);
        atoms.image.push([i(&r, take(&r)?)? as i32, i(&r, take(&r)?)? as i32, i(&r, take(&r)?)? as i32]);
        atoms.f.push([0.0; 3]);
        if features.molecule {
            atoms.molecule.push(i(&r, take(&r)?)?);
        }
        if features.charge {
            atoms.q.push(f(&r, take(&r)?)?);
        }
        if features.sphere {
            atoms.radius.push(f(&r, take(&r)?)?);
            atoms.rmass.push(f(&r, take(&r)?)?);
            atoms.omega.push([f(&r, take(&r)?)?, f(&r, take(&r)?)?, f(&r, take(&r)?)?]);
            atoms.torque.push([0.0; 3]);
        }
        if features.sph {
            atoms.rho.push(f(&r, take(&r)?)?);
            atoms.drho.push(f(&r, take(&r)?)?);
            atoms.esph.push(f(&r, take(&r)?)?);
            atoms.desph.push(f(&r, take(&r)?)?);
            atoms.cv.push(f(&r, take(&r)?)?);
            atoms.vest.push([f(&r, take(&r)?)?, f(&r, take(&r)?)?, f(&r, take(&r)?)?]);
        }
        if c != w.len() {
            return Err(r.err("too many values for an atom"));
        }
        atoms.nlocal += 1;
    }
    while r.peek_key() == Some("extra") {
        let v = r.keyed("extra")?;
        let name = dec(v.first().ok_or_else(|| r.err("extra array without a name"))?);
        let stride: usize = r.num(v.get(1))?;
        let ghosts = match v.get(2).copied() {
            Some("ghosts") => true,
            Some("owned") | None => false,
            Some(other) => return Err(r.err(format!("expected `ghosts` or `owned` after the stride of extra array `{name}`, found `{other}`"))),
        };
        let mut data = Vec::with_capacity(n * stride);
        for _ in 0..n {
            let l = r.next()?;
            let vals = nums(&r, &l.split_whitespace().collect::<Vec<_>>())?;
            if vals.len() != stride {
                return Err(r.err(format!("extra array `{name}` needs {stride} values per atom")));
            }
            data.extend(vals);
        }
        atoms.extra.push(ExtraArray { name, stride, data, ghosts });
    }
    let mut topo = crate::engine::topology::Topology { nbondtypes: tt[0], nangletypes: tt[1], ndihedraltypes: tt[2], nimpropertypes: tt[3], ..Default::default() };
    let ints = |r: &Reader, l: &str, k: usize| -> Result<Vec<i64>, String> {
        let v: Vec<i64> = l.split_whitespace().map(|w| w.parse::<i64>().map_err(|_| r.err(format!("bad integer `{w}`")))).collect::<Result<_, _>>()?;
        if v.len() != k {
            return Err(r.err(format!("expected {k} integers")));
        }
        Ok(v)
    };
    let v = r.keyed("bonds")?;
    for _ in 0..r.num::<usize>(v.first())? {
        let l = r.next()?;
        let b = ints(&r, l, 3)?;
        topo.bonds.push(Bond { typ: b[0] as usize, atoms: [b[1], b[2]] });
    }
    let v = r.keyed("angles")?;
    for _ in 0..r.num::<usize>(v.first())? {
        let l = r.next()?;
        let b = ints(&r, l, 4)?;
        topo.angles.push(Angle { typ: b[0] as usize, atoms: [b[1], b[2], b[3]] });
    }
    let v = r.keyed("dihedrals")?;
    for _ in 0..r.num::<usize>(v.first())? {
        let l = r.next()?;
        let b = ints(&r, l, 5)?;
        topo.dihedrals.push(Dihedral { typ: b[0] as usize, atoms: [b[1], b[2], b[3], b[4]] });
    }
    let mut commands = Vec::new();
    while r.peek_key() == Some("command") {
        let v = r.keyed("command")?;
        if v.is_empty() {
            return Err(r.err("empty command"));
        }
        commands.push(v.iter().map(|w| dec(w)).collect());
    }
    let mut pending: Pending = Vec::new();
    while r.peek_key() == Some("contacts") {
        let v = r.keyed("contacts")?;
        let k: usize = r.num(v.first())?;
        let size: usize = r.num(v.get(1))?;
        let count: usize = r.num(v.get(2))?;
        let mut recs = Vec::with_capacity(count);
        for _ in 0..count {
            let l = r.next()?;
            let w: Vec<&str> = l.split_whitespace().collect();
            if w.len() != 5 + size {
                return Err(r.err(format!("a contact needs {} values", 5 + size)));
            }
            let ii = |s: &str| s.parse::<i64>().map_err(|_| r.err(format!("bad integer `{s}`")));
            let values = nums(&r, &w[5..])?;
            recs.push(ContactRecord { owner: ii(w[0])?, partner: ii(w[1])?, image: [ii(w[2])? as i32, ii(w[3])? as i32, ii(w[4])? as i32], values });
        }
        pending.push((k, size, recs));
    }
    if r.next()? != "end" {
        return Err(r.err("expected `end`"));
    }

    // all read: apply
    let old = sim.state.units;
    sim.state.units = Units::new(units);
    if sim.state.neigh_settings.skin == old.skin {
        sim.state.neigh_settings.skin = sim.state.units.skin;
    }
    sim.state.dt = dt;
    sim.state.dt_set = dt_set;
    sim.state.step = step;
    sim.state.atime = atime;
    sim.state.atimestep = atimestep;
    sim.state.dimension = dimension;
    sim.state.boundary = boundary;
    sim.state.atom_style = atom_style;
    sim.state.newton_pair = newton.0;
    sim.state.newton_bond = newton.1;
    sim.state.comm_vel = comm_vel;
    sim.state.domain = Some(domain);
    sim.state.box_initial = box_initial;
    sim.state.ntypes = ntypes;
    sim.state.type_mass = type_mass;
    sim.state.mass_set = mass_set;
    sim.state.groups = groups;
    sim.state.atoms = atoms;
    sim.state.topo = topo;
    sim.state.lists_valid = false;
    Ok((commands, pending))
}
