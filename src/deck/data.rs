//! `read_data` and `write_data`: LAMMPS data files (the format lives in the parser crate;
//! this file moves the values into and out of the simulation).

use crate::engine::atoms::NewAtom;
use crate::engine::domain::Domain;
use crate::sim::Simulation;
use crate::engine::topology::{Angle, Bond, Dihedral};
use dmhs_parser::data_file::{parse_data_file, write_data_title, AtomLayout, AtomLine, CoeffKind, CoeffLine, CoeffSection, DataFile, MassLine, TopoLine, VelocityLine};
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Word};

pub const READ_SYNTAX: &str = "read_data file";

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
    if let Some(kw) = a.peek() {
        return Err(a.error_at(kw, format!("read_data keyword `{}` is not supported yet", kw.text), "supported: read_data file"));
    }
    if sim.state.domain.is_some() {
        return Err(a.error_at(&cmd.name, "read_data after the box is defined (read_data ... add) is not supported yet", "box already defined"));
    }
    let path = sim.path(&fw.text);
    // the file is held whole while read: refuse one larger than the memory (a read would abort)
    if let Ok(meta) = std::fs::metadata(&path) {
        crate::sim::memory::check_fits(meta.len() as f64, &format!("the data file `{}` of {} bytes, read whole", path.display(), meta.len())).map_err(|e| a.error_at(fw, format!("read_data: {e}"), "this file"))?;
    }
    let bytes = std::fs::read(&path).map_err(|e| a.error_at(fw, format!("cannot open data file `{}`: {e}", path.display()), "this file"))?;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let file = sources.add(path.display().to_string(), text);
    let layout = layout(sim).map_err(|d| d.with_label(cmd.span, "for this read_data"))?;
    let data = parse_data_file(&sources.file(file).text.clone(), file, &layout).map_err(|d| combine(d, sources))?;
    for w in &data.warnings {
        sim.out.print(&w.render(sources));
    }
    apply(sim, cmd, &data, &layout, sources)
}

fn apply(sim: &mut Simulation, cmd: &Command, data: &DataFile, layout: &AtomLayout, sources: &mut SourceMap) -> DResult<()> {
    let h = &data.header;
    if h.tilt.is_some() {
        return Err(Diagnostic::at(cmd.span, "triclinic boxes (xy xz yz in the data file) are not supported", "triclinic data file"));
    }
    if sim.state.dimension == 2 && (h.boxlo[2] >= 0.0 || h.boxhi[2] <= 0.0) {
        return Err(Diagnostic::at(cmd.span, "a 2d data file must have zlo < 0 < zhi", "2d box"));
    }
    sim.out.print(&format!("Reading data file ...\n  orthogonal box = ({} {} {}) to ({} {} {})", h.boxlo[0], h.boxlo[1], h.boxlo[2], h.boxhi[0], h.boxhi[1], h.boxhi[2]));
    let domain = Domain { dimension: sim.state.dimension, lo: h.boxlo, hi: h.boxhi, boundary: sim.state.boundary };
    sim.state.box_initial = Some(domain.clone());
    sim.state.domain = Some(domain.clone());
    crate::sim::memory::check_types(h.atom_types).map_err(|e| Diagnostic::at(cmd.span, format!("read_data: {} atom types: {e}", h.atom_types), "too many atom types"))?;
    crate::sim::memory::check_atoms(h.atoms as f64, sim.state.atoms.features, 0, 0).map_err(|e| Diagnostic::at(cmd.span, format!("read_data: {} atoms: {e}", h.atoms), "too many atoms for this machine"))?;
    sim.state.ntypes = h.atom_types;
    sim.state.type_mass = vec![0.0; h.atom_types + 1];
    sim.state.mass_set = vec![false; h.atom_types + 1];
    let t = &mut sim.state.topo;
    t.nbondtypes = h.bond_types;
    t.nangletypes = h.angle_types;
    t.ndihedraltypes = h.dihedral_types;
    t.nimpropertypes = h.improper_types;
    if !data.impropers.is_empty() {
        return Err(Diagnostic::at(cmd.span, "impropers are not supported yet", "data file has Impropers"));
    }
    for m in &data.masses {
        if m.mass <= 0.0 {
            return Err(Diagnostic::at(m.span, format!("mass of type {} must be > 0", m.atom_type), "invalid mass"));
        }
        sim.state.type_mass[m.atom_type] = m.mass;
        sim.state.mass_set[m.atom_type] = true;
    }
    // coefficients, through the same code as the *_coeff commands
    for sec in &data.coeffs {
        let name = match sec.kind {
            CoeffKind::Pair | CoeffKind::PairIJ => "pair_coeff",
            CoeffKind::Bond => "bond_coeff",
            CoeffKind::Angle => "angle_coeff",
            CoeffKind::Dihedral => "dihedral_coeff",
            _ => return Err(Diagnostic::at(sec.span, format!("{} are not supported", sec.kind.section_name()), "unsupported section")),
        };
        for line in &sec.lines {
            let c = Command { name: Word::new(name, line.span), args: line.command_args(sec.kind), span: line.span };
            sim.execute_command(&c, sources).map_err(|d| d.with_note(format!("in the {} section of the data file", sec.kind.section_name())))?;
        }
    }
    // atoms
    let ft = sim.state.atoms.features;
    let two_pi_thirds = 4.0 * std::f64::consts::PI / 3.0;
    let mut seen = std::collections::HashSet::with_capacity(data.atoms.len());
    for al in &data.atoms {
        if !seen.insert(al.id) {
            return Err(Diagnostic::at(al.span, format!("duplicate atom ID {}", al.id), "repeated ID"));
        }
        let mut x = al.x;
        let mut image = if data.image_flags { al.image } else { [0; 3] };
        for d in 0..3 {
            if !domain.periodic(d) {
                image[d] = 0;
            }
        }
        domain.remap(&mut x, &mut image);
        if !(0..3).all(|d| domain.periodic(d) || (x[d] >= domain.lo[d] && x[d] < domain.hi[d]) || matches!(domain.boundary[d][0], crate::engine::domain::BoundaryKind::Shrink | crate::engine::domain::BoundaryKind::ShrinkMin)) {
            return Err(Diagnostic::at(al.span, format!("atom {} at ({}, {}, {}) is outside the non-periodic box", al.id, x[0], x[1], x[2]), "outside the box"));
        }
        if sim.state.dimension == 2 && x[2] != 0.0 {
            return Err(Diagnostic::at(al.span, format!("atom {} has z = {} in a 2d simulation (must be 0)", al.id, x[2]), "z must be 0"));
        }
        if al.atom_type < 1 || al.atom_type > sim.state.ntypes {
            return Err(Diagnostic::at(al.span, format!("atom {} has type {} outside 1..{}", al.id, al.atom_type, sim.state.ntypes), "bad type"));
        }
        let mut n = NewAtom::at(al.id, al.atom_type, x);
        n.image = image;
        n.molecule = al.molecule;
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
    }
    if let Some(vels) = &data.velocities {
        let map = sim.state.atoms.tag_map();
        for vl in vels {
            let Some(i) = map.get(vl.id) else {
                return Err(Diagnostic::at(vl.span, format!("velocity for atom ID {} that does not exist", vl.id), "unknown atom"));
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
        sim.state.topo.bonds.push(Bond::new(b.topo_type, b.atoms));
    }
    for b in &data.angles {
        check_type(b.topo_type, h.angle_types, b.span, "angle")?;
        sim.state.topo.angles.push(Angle { typ: b.topo_type, atoms: b.atoms });
    }
    for b in &data.dihedrals {
        check_type(b.topo_type, h.dihedral_types, b.span, "dihedral")?;
        sim.state.topo.dihedrals.push(Dihedral { typ: b.topo_type, atoms: b.atoms });
    }
    let _ = layout;
    let t = &sim.state.topo;
    sim.out.print(&format!("  {} atoms\n  {} bonds\n  {} angles\n  {} dihedrals", sim.state.atoms.nlocal, t.bonds.len(), t.angles.len(), t.dihedrals.len()));
    sim.state.lists_valid = false;
    Ok(())
}


/// `write_data file [nocoeff]`: a data file LAMMPS' read_data accepts, written atomically.
pub fn write_data(sim: &Simulation, cmd: &Command) -> Result<(), String> {
    let mut a = Args::new(cmd, "write_data file [nocoeff] [nofix] [nolabelmap]");
    let fw = a.word("file name").map_err(|d| d.message)?;
    let mut coeffs = true;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "nocoeff" => coeffs = false,
            "nofix" | "nolabelmap" => {}
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
        let (mut x, mut img) = (a.x[i], a.image[i]);
        d.remap(&mut x, &mut img);
        let mut al = AtomLine::new(a.tag[i], a.typ[i], x);
        al.image = img;
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
