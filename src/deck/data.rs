//! `read_data` and `write_data`: LAMMPS data files (the format lives in the parser crate;
//! this file moves the values into and out of the simulation).

use crate::engine::atoms::NewAtom;
use crate::engine::domain::Domain;
use crate::sim::Simulation;
use crate::engine::topology::{Angle, Bond, Dihedral};
use dmhs_parser::data_file::{parse_data_file_with, write_data_title, AtomLayout, AtomLine, CoeffKind, CoeffLine, CoeffSection, DataFile, MassLine, TopoLine, VelocityLine};
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Word};

pub const READ_SYNTAX: &str = "read_data file [add append|merge|IDoffset [MOLoffset]] [offset toff boff aoff doff ioff] [shift Sx Sy Sz] [extra/atom|bond|angle|dihedral|improper/types N] [extra/bond|angle|dihedral|improper|special/per/atom N] [group ID] [nocoeff] [fix ID NULL Section]";

/// How the atoms of a data file join a system that exists (`read_data ... add`).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Add {
    /// IDs after the largest atom and molecule IDs of the system.
    Append,
    /// IDs as in the file.
    Merge,
    /// IDs plus the given atom and molecule ID offsets.
    Offset { id: i64, mol: i64 },
}

/// The keywords of `read_data`.
struct ReadOptions {
    add: Option<Add>,
    /// Added to the atom, bond, angle, dihedral and improper types of the file.
    offset: [usize; 5],
    shift: [f64; 3],
    /// Types beyond the file's (first read only).
    extra_types: [usize; 5],
    /// Where the last extra/*/types keyword is (for the error of a total above MAX_TYPES).
    extra_at: Option<dmhs_parser::span::Span>,
    group: Option<u32>,
    coeffs: bool,
    /// `fix ID NULL Section`: the fix index and the section name it reads.
    fixes: Vec<(usize, String)>,
}

const KINDS: [&str; 5] = ["atom", "bond", "angle", "dihedral", "improper"];

fn read_options(sim: &mut Simulation, cmd: &Command, a: &mut Args) -> DResult<ReadOptions> {
    let mut o = ReadOptions { add: None, offset: [0; 5], shift: [0.0; 3], extra_types: [0; 5], extra_at: None, group: None, coeffs: true, fixes: vec![] };
    let (mut offset_w, mut shift_w, mut extra_w) = (None, None, None);
    let ft = sim.state.atoms.features;
    let allowed = [true, ft.bonds, ft.angles, ft.dihedrals, false];
    while let Some(w) = a.peek() {
        a.skip(1);
        let kw = w.text.as_str();
        match kw {
            "add" => {
                let v = a.peek().map(|w| w.text.as_str());
                a.skip(usize::from(matches!(v, Some("append" | "merge"))));
                o.add = Some(match v {
                    Some("append") => Add::Append,
                    Some("merge") => Add::Merge,
                    _ => {
                        let id = a.i64_in("atom ID offset", 0, i32::MAX as i64)?;
                        // LAMMPS reads a molecule ID offset only where atoms have molecule IDs
                        let mol = if ft.molecule { a.i64_in("molecule ID offset (the atom style has molecule IDs)", 0, i32::MAX as i64)? } else { 0 };
                        Add::Offset { id, mol }
                    }
                });
            }
            "offset" => {
                for (k, what) in ["toff", "boff", "aoff", "doff", "ioff"].iter().enumerate() {
                    o.offset[k] = a.i64_in(what, 0, i32::MAX as i64)? as usize;
                }
                offset_w = Some(w);
            }
            "shift" => {
                for (k, what) in ["Sx", "Sy", "Sz"].iter().enumerate() {
                    o.shift[k] = a.f64(what)?;
                }
                if sim.state.dimension == 2 && o.shift[2] != 0.0 {
                    return Err(a.error_at(a.last().unwrap(), "read_data shift in z must be 0 in a 2d simulation", "Sz must be 0"));
                }
                shift_w = Some(w);
            }
            "nocoeff" => o.coeffs = false,
            "group" => {
                let g = a.word("group ID")?;
                let k = sim.state.groups.find_or_create(&g.text).map_err(|e| a.error_at(g, e, "group"))?;
                o.group = Some(1 << k);
            }
            "fix" => {
                let id = a.word("fix ID")?;
                let k = sim.fixes.iter().position(|f| f.id() == id.text).ok_or_else(|| a.error_at(id, format!("Fix ID {} for read_data does not exist", id.text), "no such fix"))?;
                let header = a.word("header keyword (NULL)")?;
                if header.text != "NULL" {
                    return Err(a.error_at(header, format!("read_data fix with a header keyword (`{}`) is not supported: the fixes dmhs has read sections only", header.text), "expected NULL"));
                }
                let section = a.word("section name")?;
                if dmhs_parser::data_file::is_section_name(&section.text) {
                    return Err(a.error_at(section, format!("Custom data section name {} for fix {} collides with existing data section", section.text, id.text), "a data file section of LAMMPS' own"));
                }
                o.fixes.push((k, section.text.clone()));
            }
            _ => {
                let parts: Vec<&str> = kw.split('/').collect();
                match parts[..] {
                    ["extra", kind, "types"] if KINDS.contains(&kind) => {
                        let k = KINDS.iter().position(|&x| x == kind).unwrap();
                        if !allowed[k] {
                            return Err(a.error_at(w, format!("no {kind}s are allowed with atom style {}", sim.state.atom_style.join(" ")), "not with this atom style"));
                        }
                        // dmhs keeps tables per type (and per pair of atom types): at most MAX_TYPES in all
                        o.extra_types[k] = a.i64_in(&format!("number of extra {kind} types"), 0, dmhs_parser::data_file::MAX_TYPES as i64)? as usize;
                        extra_w = Some(w);
                        o.extra_at = Some(w.span);
                    }
                    ["extra", kind, "per", "atom"] if KINDS[1..].contains(&kind) || kind == "special" => {
                        if !ft.molecular() {
                            return Err(a.error_at(w, format!("no bonded interactions are allowed with atom style {}", sim.state.atom_style.join(" ")), "not with this atom style"));
                        }
                        // dmhs keeps no per-atom limit on bonds or special partners
                        a.i64_in(&format!("extra {kind}s per atom"), 0, i32::MAX as i64)?;
                    }
                    _ => return Err(a.unknown_keyword(w, &["add", "offset", "shift", "extra/atom/types", "extra/bond/types", "extra/angle/types", "extra/dihedral/types", "extra/improper/types", "extra/bond/per/atom", "extra/angle/per/atom", "extra/dihedral/per/atom", "extra/improper/per/atom", "extra/special/per/atom", "group", "nocoeff", "fix"])),
                }
            }
        }
    }
    let boxed = sim.state.domain.is_some();
    let cmd_name = &cmd.name;
    if boxed && o.add.is_none() {
        return Err(a.error_at(cmd_name, "read_data after the box is defined needs the `add` keyword (add append, add merge or add IDoffset)", "box already defined"));
    }
    if !boxed && o.add.is_some() {
        return Err(a.error_at(cmd_name, "read_data add needs a simulation box (the first read_data, or create_box, defines it)", "no box yet"));
    }
    if o.add.is_none() {
        if let Some(w) = offset_w.or(shift_w) {
            return Err(a.error_at(w, format!("read_data {} needs the `add` keyword", w.text), "only with add"));
        }
    } else if let Some(w) = extra_w {
        return Err(a.error_at(w, "read_data extra/*/types cannot be used with add (the numbers of types are set by the first read_data or create_box)", "not with add"));
    }
    Ok(o)
}

/// The data-file column layout of the current atom style.
pub fn layout(sim: &Simulation) -> Result<AtomLayout, Diagnostic> {
    let names: Vec<&str> = sim.state.atom_style.iter().map(|s| s.as_str()).collect();
    AtomLayout::from_names(&names)
}

/// Several diagnostics as one: the first, with the others as notes.
fn combine(mut diags: Vec<Diagnostic>, sources: &SourceMap) -> Diagnostic {
    let mut first = diags.remove(0);
    for d in diags.iter().take(20) {
        let loc = d.primary_span().map(|s| sources.location(s)).unwrap_or_default();
        first = first.with_note(format!("also: {loc}: {}", d.message));
    }
    if diags.len() > 20 {
        first = first.with_note(format!("and {} more errors", diags.len() - 20));
    }
    first
}

pub fn read_data(sim: &mut Simulation, cmd: &Command, sources: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, READ_SYNTAX);
    let fw = a.word("file name")?;
    let opts = read_options(sim, cmd, &mut a)?;
    let path = sim.path(&fw.text);
    // the file is held whole while read: refuse one larger than the memory (a read would abort)
    if let Ok(meta) = std::fs::metadata(&path) {
        crate::sim::memory::check_fits(meta.len() as f64, &format!("the data file `{}` of {} bytes, read whole", path.display(), meta.len())).map_err(|e| a.error_at(fw, format!("read_data: {e}"), "this file"))?;
    }
    let bytes = std::fs::read(&path).map_err(|e| a.error_at(fw, format!("cannot open data file `{}`: {e}", path.display()), "this file"))?;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let file = sources.add(path.display().to_string(), text);
    let layout = layout(sim).map_err(|d| d.with_label(cmd.span, "for this read_data"))?;
    let fix_sections: Vec<String> = opts.fixes.iter().map(|(_, s)| s.clone()).collect();
    let data = parse_data_file_with(&sources.file(file).text.clone(), file, &layout, &fix_sections).map_err(|d| combine(d, sources))?;
    for w in &data.warnings {
        sim.out.print(&w.render(sources));
    }
    apply(sim, cmd, &data, &opts, sources)
}

fn apply(sim: &mut Simulation, cmd: &Command, data: &DataFile, o: &ReadOptions, sources: &mut SourceMap) -> DResult<()> {
    let h = &data.header;
    // a file added to a system has its kind of box, and a triclinic one its tilts (LAMMPS 22 Jul
    // 2025's three errors: only the lengths grow to the union of the boxes)
    if let (Some(_), Some(d)) = (o.add.as_ref(), sim.state.domain.as_ref()) {
        let refusal = match (d.tilt, h.tilt) {
            (None, Some(_)) => Some("Read_data subsequent file cannot switch to restricted triclinic"),
            (Some(_), None) => Some("Read_data subsequent file cannot switch to orthogonal"),
            (Some(t), Some(f)) if t != f => Some("Read_data subsequent file tilt factors must be same as first file"),
            _ => None,
        };
        if let Some(r) = refusal {
            return Err(Diagnostic::at(cmd.span, r, "the box of this file"));
        }
    }
    if !data.impropers.is_empty() {
        return Err(Diagnostic::at(cmd.span, "impropers are not supported yet", "data file has Impropers"));
    }
    let [toff, boff, aoff, doff, _] = o.offset;
    let file_lo: [f64; 3] = std::array::from_fn(|d| h.boxlo[d] + o.shift[d]);
    let file_hi: [f64; 3] = std::array::from_fn(|d| h.boxhi[d] + o.shift[d]);
    sim.out.print("Reading data file ...");
    let (id_off, mol_off) = match o.add {
        None | Some(Add::Merge) => (0, 0),
        Some(Add::Append) => (sim.state.atoms.max_tag(), if sim.state.atoms.features.molecule { sim.state.atoms.max_molecule() } else { 0 }),
        Some(Add::Offset { id, mol }) => (id, mol),
    };
    let t = &sim.state.topo;
    let system_types = [sim.state.ntypes, t.nbondtypes, t.nangletypes, t.ndihedraltypes];
    let domain = match o.add {
        None => {
            if sim.state.dimension == 2 && (h.boxlo[2] >= 0.0 || h.boxhi[2] <= 0.0) {
                return Err(Diagnostic::at(cmd.span, "a 2d data file must have zlo < 0 < zhi", "2d box"));
            }
            let mut domain = Domain::new(sim.state.dimension, h.boxlo, h.boxhi, sim.state.boundary);
            domain.tilt = h.tilt;
            let max = dmhs_parser::data_file::MAX_TYPES;
            let totals = [h.atom_types + o.extra_types[0], h.bond_types + o.extra_types[1], h.angle_types + o.extra_types[2], h.dihedral_types + o.extra_types[3], h.improper_types + o.extra_types[4]];
            if let Some(k) = totals.iter().position(|&n| n > max) {
                let message = format!("read_data: {} {} types with the extra ones; dmhs accepts at most {max}", totals[k], KINDS[k]);
                return Err(Diagnostic::at(o.extra_at.unwrap_or(cmd.span), message, "too many types"));
            }
            let ntypes = totals[0];
            crate::sim::memory::check_types(ntypes).map_err(|e| Diagnostic::at(cmd.span, format!("read_data: {ntypes} atom types: {e}"), "too many atom types"))?;
            sim.state.ntypes = ntypes;
            sim.state.type_mass = vec![0.0; ntypes + 1];
            sim.state.mass_set = vec![false; ntypes + 1];
            let t = &mut sim.state.topo;
            t.nbondtypes = h.bond_types + o.extra_types[1];
            t.nangletypes = h.angle_types + o.extra_types[2];
            t.ndihedraltypes = h.dihedral_types + o.extra_types[3];
            t.nimpropertypes = h.improper_types + o.extra_types[4];
            domain
        }
        Some(_) => {
            // the file's types, offset, must be types of the system (LAMMPS sizes them once)
            let file_types = [h.atom_types, h.bond_types, h.angle_types, h.dihedral_types];
            for (k, kind) in ["atom", "bond", "angle", "dihedral"].iter().enumerate() {
                let off = [toff, boff, aoff, doff][k];
                if file_types[k] > 0 && file_types[k] + off > system_types[k] {
                    return Err(Diagnostic::at(cmd.span, format!("the data file's {} {kind} types, offset by {off}, exceed the system's {} {kind} types", file_types[k], system_types[k]), "too many types")
                        .with_help("reserve types with extra/*/types in the first read_data, or in create_box"));
                }
            }
            // the box grows to hold the file's box, shifted
            let mut d = sim.state.domain.clone().expect("add needs a box");
            let old = d.clone();
            for k in 0..3 {
                d.lo[k] = d.lo[k].min(file_lo[k]);
                d.hi[k] = d.hi[k].max(file_hi[k]);
            }
            if (d.lo != old.lo || d.hi != old.hi) && sim.state.atoms.image[..sim.state.atoms.nlocal].iter().any(|im| *im != [0; 3]) {
                sim.out.print("WARNING: Non-zero image flags with growing box can produce bad coordinates");
            }
            d
        }
    };
    sim.out.print(&format!("  {}", crate::deck::box_text(&domain)));
    if let Some(w) = crate::deck::tilt_check(&domain).map_err(|e| Diagnostic::at(cmd.span, e, "triclinic box"))? {
        sim.out.print(&w);
    }
    sim.state.box_initial = Some(domain.clone());
    // LAMMPS' set_initial_box(1) pads the shrink-wrapped faces of a new box and of the union
    // box of an `add`
    let domain = crate::engine::boundary::pad_shrink_faces(&domain);
    // (LAMMPS sets its processor grid again for the union box of an `add`)
    sim.state.grid_areas = Some(domain.face_areas());
    sim.state.domain = Some(domain.clone());
    let natoms = sim.state.atoms.nlocal + h.atoms;
    crate::sim::memory::check_atoms(natoms as f64, sim.state.atoms.features, 0, 0).map_err(|e| Diagnostic::at(cmd.span, format!("read_data: {natoms} atoms: {e}"), "too many atoms for this machine"))?;
    for m in &data.masses {
        if m.mass <= 0.0 {
            return Err(Diagnostic::at(m.span, format!("mass of type {} must be > 0", m.atom_type), "invalid mass"));
        }
        sim.state.type_mass[m.atom_type + toff] = m.mass;
        sim.state.mass_set[m.atom_type + toff] = true;
    }
    // coefficients, through the same code as the *_coeff commands (types offset)
    for sec in data.coeffs.iter().filter(|_| o.coeffs) {
        let (name, off) = match sec.kind {
            CoeffKind::Pair | CoeffKind::PairIJ => ("pair_coeff", toff),
            CoeffKind::Bond => ("bond_coeff", boff),
            CoeffKind::Angle => ("angle_coeff", aoff),
            CoeffKind::Dihedral => ("dihedral_coeff", doff),
            _ => return Err(Diagnostic::at(sec.span, format!("{} are not supported", sec.kind.section_name()), "unsupported section")),
        };
        for line in &sec.lines {
            let shifted = CoeffLine { types: line.types.iter().map(|t| t + off).collect(), ..line.clone() };
            let c = Command { name: Word::new(name, line.span), args: shifted.command_args(sec.kind), span: line.span };
            sim.execute_command(&c, sources).map_err(|d| d.with_note(format!("in the {} section of the data file", sec.kind.section_name())))?;
        }
    }
    // atoms (IDs, types and positions as the keywords say)
    let ft = sim.state.atoms.features;
    let two_pi_thirds = 4.0 * std::f64::consts::PI / 3.0;
    let existing = sim.state.atoms.tag_map();
    let mut seen = std::collections::HashSet::with_capacity(data.atoms.len());
    for al in &data.atoms {
        let id = al.id + id_off;
        if !seen.insert(al.id) {
            return Err(Diagnostic::at(al.span, format!("duplicate atom ID {}", al.id), "repeated ID"));
        }
        if existing.get(id).is_some() {
            return Err(Diagnostic::at(al.span, format!("atom ID {id} exists already in the system"), "repeated ID").with_help("read_data add append gives the file's atoms IDs after the system's"));
        }
        let mut x: [f64; 3] = std::array::from_fn(|d| al.x[d] + o.shift[d]);
        let mut image = if data.image_flags { al.image } else { [0; 3] };
        for d in 0..3 {
            if !domain.periodic(d) {
                image[d] = 0;
            }
        }
        domain.remap(&mut x, &mut image);
        // (a triclinic box's faces are planes of constant box fraction)
        let (c, lo, hi) = if domain.triclinic() { (domain.x2lamda(x), [0.0; 3], [1.0; 3]) } else { (x, domain.lo, domain.hi) };
        if !(0..3).all(|d| domain.periodic(d) || (c[d] >= lo[d] && c[d] < hi[d]) || matches!(domain.boundary[d][0], crate::engine::domain::BoundaryKind::Shrink | crate::engine::domain::BoundaryKind::ShrinkMin)) {
            return Err(Diagnostic::at(al.span, format!("atom {} at ({}, {}, {}) is outside the non-periodic box", al.id, x[0], x[1], x[2]), "outside the box"));
        }
        if sim.state.dimension == 2 && x[2] != 0.0 {
            return Err(Diagnostic::at(al.span, format!("atom {} has z = {} in a 2d simulation (must be 0)", al.id, x[2]), "z must be 0"));
        }
        let typ = al.atom_type + toff;
        if al.atom_type < 1 || typ > sim.state.ntypes {
            return Err(Diagnostic::at(al.span, format!("atom {} has type {typ} outside 1..{}", al.id, sim.state.ntypes), "bad type"));
        }
        let mut n = NewAtom::at(id, typ, x);
        n.image = image;
        n.molecule = al.molecule + mol_off;
        n.q = al.q;
        if ft.sphere {
            // LAMMPS: radius = d/2; rmass = density * 4 pi/3 r^3 (density itself when r = 0)
            let r = 0.5 * al.diameter;
            n.radius = r;
            n.rmass = if r > 0.0 { al.density * (two_pi_thirds * r * r * r) } else { al.density };
            if n.rmass <= 0.0 {
                return Err(Diagnostic::at(al.span, format!("atom {} has a non-positive mass (density {})", al.id, al.density), "invalid density"));
            }
        }
        n.rho = al.rho;
        n.esph = al.esph;
        n.cv = al.cv;
        sim.state.atoms.push(&n);
        if let Some(bit) = o.group {
            *sim.state.atoms.mask.last_mut().unwrap() |= bit;
        }
    }
    if let Some(vels) = &data.velocities {
        let map = sim.state.atoms.tag_map();
        for vl in vels {
            let Some(i) = map.get(vl.id + id_off).filter(|_| seen.contains(&vl.id)) else {
                return Err(Diagnostic::at(vl.span, format!("velocity for atom ID {} that the file does not have", vl.id), "unknown atom"));
            };
            sim.state.atoms.v[i] = vl.v;
            if ft.sphere {
                sim.state.atoms.omega[i] = vl.omega;
            }
        }
    }
    let check_type = |typ: usize, n: usize, span: dmhs_parser::Span, what: &str| -> DResult<()> {
        if typ < 1 || typ > n {
            return Err(Diagnostic::at(span, format!("{what} type {typ} outside 1..{n}"), "bad type"));
        }
        Ok(())
    };
    for b in &data.bonds {
        check_type(b.topo_type, h.bond_types, b.span, "bond")?;
        sim.state.topo.bonds.push(Bond::new(b.topo_type + boff, b.atoms.map(|a| a + id_off)));
    }
    for b in &data.angles {
        check_type(b.topo_type, h.angle_types, b.span, "angle")?;
        sim.state.topo.angles.push(Angle::new(b.topo_type + aoff, b.atoms.map(|a| a + id_off)));
    }
    for b in &data.dihedrals {
        check_type(b.topo_type, h.dihedral_types, b.span, "dihedral")?;
        sim.state.topo.dihedrals.push(Dihedral::new(b.topo_type + doff, b.atoms.map(|a| a + id_off)));
    }
    // LAMMPS migrates every atom after an `add` (in box fractions on a triclinic box: one round
    // trip), then shrink-wraps the box to the atoms at once (its margins from the file's box)
    if let Some(d) = sim.state.domain.as_ref().filter(|d| o.add.is_some() && d.triclinic()) {
        crate::engine::boundary::to_fractions(d, &mut sim.state.atoms);
        crate::engine::boundary::to_box(d, &mut sim.state.atoms);
    }
    if let (Some(d), Some(initial)) = (sim.state.domain.as_mut(), sim.state.box_initial.as_ref()) {
        crate::engine::boundary::reset_shrink_wrap_box_coords(d, initial, &mut sim.state.atoms);
    }
    sim.out.print(&format!("  {} atoms\n  {} bonds\n  {} angles\n  {} dihedrals", data.atoms.len(), data.bonds.len(), data.angles.len(), data.dihedrals.len()));
    // sections read by fixes (LAMMPS' Fix::read_data_section), atom IDs shifted by `add`
    for section in &data.fix_sections {
        let Some(&(k, _)) = o.fixes.iter().find(|(_, s)| *s == section.name) else { continue };
        sim.fixes[k].read_data_section(&mut sim.state, section, id_off).map_err(|d| d.with_label(cmd.span, "for this read_data"))?;
    }
    if o.add.is_some() && !(data.bonds.is_empty() && data.angles.is_empty() && data.dihedrals.is_empty()) {
        sim.state.topology_changed();
    }
    sim.state.lists_valid = false;
    Ok(())
}


/// `write_data file [nocoeff] [noinit]`: a data file LAMMPS' read_data accepts, written atomically.
pub fn write_data(sim: &Simulation, cmd: &Command) -> Result<(), String> {
    let mut a = Args::new(cmd, "write_data file [nocoeff] [noinit] [nofix] [nolabelmap]");
    let fw = a.word("file name").map_err(|d| d.message)?;
    let mut coeffs = true;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "nocoeff" => coeffs = false,
            "noinit" | "nofix" | "nolabelmap" => {}
            "pair" => {
                a.skip(1);
            }
            o => return Err(format!("unknown write_data keyword `{o}`")),
        }
    }
    let layout = layout(sim).map_err(|d| d.message)?;
    let text = to_data_file(sim, coeffs).write(&layout);
    crate::output::log::write_atomic(&sim.path(&fw.text), text.as_bytes()).map_err(|e| format!("cannot write {}: {e}", fw.text))
}

/// The simulation as a data file (atoms wrapped into the box, sorted by ID).
pub fn to_data_file(sim: &Simulation, coeffs: bool) -> DataFile {
    let d = sim.state.domain.as_ref().expect("box");
    let a = &sim.state.atoms;
    let mut f = DataFile { title: write_data_title(&format!("dmhs {}", env!("CARGO_PKG_VERSION")), sim.state.step, sim.state.units.name()), ..Default::default() };
    let h = &mut f.header;
    h.atom_types = sim.state.ntypes;
    h.bond_types = sim.state.topo.nbondtypes;
    h.angle_types = sim.state.topo.nangletypes;
    h.dihedral_types = sim.state.topo.ndihedraltypes;
    h.improper_types = sim.state.topo.nimpropertypes;
    h.boxlo = d.lo;
    h.boxhi = d.hi;
    h.tilt = d.tilt;
    if !a.features.per_atom_mass() {
        f.masses = (1..=sim.state.ntypes).filter(|&t| sim.state.mass_set[t]).map(|t| MassLine::new(t, sim.state.type_mass[t])).collect();
    }
    if coeffs {
        if let Some(p) = &sim.pair {
            let lines: Option<Vec<CoeffLine>> = (1..=sim.state.ntypes).map(|t| p.data_coeffs(t).map(|w| CoeffLine::new(vec![t], &w.split_whitespace().collect::<Vec<_>>()))).collect();
            if let Some(lines) = lines {
                f.coeffs.push(CoeffSection { kind: CoeffKind::Pair, style: Some(Word::new(p.style(), Default::default())), lines, span: Default::default() });
            }
        }
        let mut push = |kind: CoeffKind, style: &str, n: usize, words: &dyn Fn(usize) -> String| {
            if n > 0 {
                let lines = (1..=n).map(|t| CoeffLine::new(vec![t], &words(t).split_whitespace().collect::<Vec<_>>())).collect();
                f.coeffs.push(CoeffSection { kind, style: Some(Word::new(style, Default::default())), lines, span: Default::default() });
            }
        };
        if let Some(s) = &sim.bond_style {
            push(CoeffKind::Bond, s.name(), sim.state.topo.nbondtypes, &|t| s.coeff_words(t));
        }
        if let Some(s) = &sim.angle_style {
            push(CoeffKind::Angle, s.name(), sim.state.topo.nangletypes, &|t| s.coeff_words(t));
        }
        if let Some(s) = &sim.dihedral_style {
            push(CoeffKind::Dihedral, s.name(), sim.state.topo.ndihedraltypes, &|t| s.coeff_words(t));
        }
    }
    let mut order: Vec<usize> = (0..a.nlocal).collect();
    order.sort_by_key(|&i| a.tag[i]);
    f.image_flags = true;
    let mut vels = Vec::with_capacity(a.nlocal);
    for &i in &order {
        // as the atoms are: write_data wrapped them first (LAMMPS' pbc; a remap here would move
        // a triclinic box's atoms through box fractions once more)
        let mut al = AtomLine::new(a.tag[i], a.typ[i], a.x[i]);
        al.image = a.image[i];
        if a.features.molecule {
            al.molecule = a.molecule[i];
        }
        if a.features.charge {
            al.q = a.q[i];
        }
        if a.features.sphere {
            let r = a.radius[i];
            al.diameter = 2.0 * r;
            al.density = if r > 0.0 { a.rmass[i] / (4.0 * std::f64::consts::PI / 3.0 * r * r * r) } else { a.rmass[i] };
        }
        if a.features.sph {
            al.rho = a.rho[i];
            al.esph = a.esph[i];
            al.cv = a.cv[i];
        }
        f.atoms.push(al);
        vels.push(VelocityLine::new(a.tag[i], a.v[i], if a.features.sphere { a.omega[i] } else { [0.0; 3] }));
    }
    f.velocities = Some(vels);
    f.bonds = sim.state.topo.bonds.iter().map(|b| TopoLine::new(b.typ, b.atoms)).collect();
    f.angles = sim.state.topo.angles.iter().map(|b| TopoLine::new(b.typ, b.atoms)).collect();
    f.dihedrals = sim.state.topo.dihedrals.iter().map(|b| TopoLine::new(b.typ, b.atoms)).collect();
    f
}
