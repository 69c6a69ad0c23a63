//! The `molecule` command: a molecule file (syntax in the parser crate) becomes a template in
//! `State::molecules`, with LAMMPS' offsets, `scale` and checks against the box.

use crate::engine::molecule::Molecule;
use crate::sim::Simulation;
use dmhs_parser::molecule_file::{parse_molecule_file, MoleculeFile};
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Span};

const SYNTAX: &str = "molecule ID file [offset Toff Boff Aoff Doff Ioff] [toff N] [boff N] [aoff N] [doff N] [ioff N] [scale s]";

/// Offsets and scale of one file of a `molecule` command.
#[derive(Clone, Copy)]
struct Options {
    toff: i64,
    boff: i64,
    aoff: i64,
    doff: i64,
    ioff: i64,
    scale: f64,
}

pub fn molecule(sim: &mut Simulation, cmd: &Command, sources: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, SYNTAX);
    let idw = a.word("molecule template ID")?;
    if !idw.text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(a.error_at(idw, "molecule template ID must be alphanumeric or underscore characters", "invalid ID"));
    }
    if sim.state.molecules.iter().any(|m| m.id == idw.text) {
        return Err(a.error_at(idw, format!("reuse of molecule template ID `{}`", idw.text), "already defined"));
    }
    let fw = a.word("molecule file")?;
    if fw.text.ends_with(".json") {
        return Err(a.error_at(fw, "JSON molecule files are not supported yet", "native molecule files only"));
    }
    let mut o = Options { toff: 0, boff: 0, aoff: 0, doff: 0, ioff: 0, scale: 1.0 };
    let off = |a: &mut Args, what: &str| a.i64_in(what, 0, i32::MAX as i64);
    while let Some(kw) = a.peek() {
        match kw.text.as_str() {
            "offset" => {
                a.skip(1);
                o.toff = off(&mut a, "atom type offset")?;
                o.boff = off(&mut a, "bond type offset")?;
                o.aoff = off(&mut a, "angle type offset")?;
                o.doff = off(&mut a, "dihedral type offset")?;
                o.ioff = off(&mut a, "improper type offset")?;
            }
            "toff" | "boff" | "aoff" | "doff" | "ioff" => {
                a.skip(1);
                let v = off(&mut a, &format!("{} value", kw.text))?;
                match kw.text.as_str() {
                    "toff" => o.toff = v,
                    "boff" => o.boff = v,
                    "aoff" => o.aoff = v,
                    "doff" => o.doff = v,
                    _ => o.ioff = v,
                }
            }
            "scale" => {
                a.skip(1);
                o.scale = a.positive_f64("scale factor")?;
            }
            _ => {
                return Err(a
                    .error_at(kw, "molecule templates of several files (several molecules in one ID) are not supported yet", "second file or unknown keyword")
                    .with_help("keywords are: offset, toff, boff, aoff, doff, ioff, scale"));
            }
        }
    }
    let path = sim.path(&fw.text);
    let bytes = std::fs::read(&path).map_err(|e| a.error_at(fw, format!("cannot open molecule file `{}`: {e}", path.display()), "this file"))?;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let file = sources.add(path.display().to_string(), text);
    let mf = parse_molecule_file(&sources.file(file).text, file).map_err(|d| d.with_label(fw.span, "read by this molecule command"))?;
    let m = template(sim, &idw.text, &mf, o, cmd.span).map_err(|d| d.with_label(fw.span, "read by this molecule command"))?;
    sim.out.print(&format!(
        "Read molecule template {}:\n{}\n  {} molecules\n  {} fragments\n  0 bodies\n  {} atoms with max type {}\n  {} bonds with max type {}\n  {} angles with max type {}\n  {} dihedrals with max type {}\n  0 impropers with max type 0",
        m.id,
        mf.title,
        m.nmolecules(),
        mf.nfragments,
        m.natoms(),
        m.max_type(),
        m.bonds.len(),
        m.bonds.iter().map(|b| b.0).max().unwrap_or(0),
        m.angles.len(),
        m.angles.iter().map(|b| b.0).max().unwrap_or(0),
        m.dihedrals.len(),
        m.dihedrals.iter().map(|b| b.0).max().unwrap_or(0),
    ));
    sim.state.molecules.push(m);
    Ok(())
}

/// The template of a parsed file: offsets, scale and the checks LAMMPS makes when the box exists.
fn template(sim: &Simulation, id: &str, mf: &MoleculeFile, o: Options, cmd_span: Span) -> DResult<Molecule> {
    let st = &sim.state;
    let boxed = st.domain.is_some();
    if let Some(i) = mf.impropers.first() {
        return Err(Diagnostic::at(i.span, "impropers are not supported (the molecule file has an Impropers section)", "not supported"));
    }
    let s = o.scale;
    let Some(coords) = &mf.coords else {
        // LAMMPS allows templates without coordinates (for fixes that only need topology);
        // every dmhs user of templates needs them
        return Err(Diagnostic::at(cmd_span, "the molecule file has no Coords section (dmhs' uses of molecule templates need coordinates)", "no Coords"));
    };
    let x: Vec<[f64; 3]> = coords.values.iter().map(|p| [p[0] * s, p[1] * s, p[2] * s]).collect();
    if st.dimension == 2 {
        if let Some(k) = x.iter().position(|p| p[2] != 0.0) {
            return Err(Diagnostic::at(coords.spans[k], "molecule file z coordinate must be 0.0 for 2d", "z is not 0"));
        }
    }
    let mut m = Molecule::new(id.to_string(), x);
    if let Some(t) = &mf.types {
        let mut typ = Vec::with_capacity(t.values.len());
        for (k, &v) in t.values.iter().enumerate() {
            let v = v + o.toff;
            if v <= 0 || (boxed && v as usize > st.ntypes) {
                return Err(Diagnostic::at(t.spans[k], format!("invalid atom type {v} in molecule file (the box has {} atom types)", st.ntypes), "atom type out of range"));
            }
            typ.push(v as usize);
        }
        m.typ = Some(typ);
    }
    m.molecule = mf.molecules.as_ref().map(|v| v.values.clone());
    m.q = mf.charges.as_ref().map(|v| v.values.clone());
    m.radius = mf.diameters.as_ref().map(|v| v.values.iter().map(|d| d * s * 0.5).collect());
    m.rmass = mf.masses.as_ref().map(|v| v.values.iter().map(|x| x * (s * s * s)).collect());
    m.user_mass = mf.mass.map(|v| v * (s * s * s));
    m.user_com = mf.com.map(|c| c.map(|v| v * s));
    m.user_inertia = mf.inertia.map(|t| t.map(|v| v * s.powi(5)));
    if (!mf.bonds.is_empty() || !mf.angles.is_empty() || !mf.dihedrals.is_empty()) && !st.atoms.features.molecular() {
        return Err(Diagnostic::at(cmd_span, format!("the molecule has bonds, angles or dihedrals, but atom style {} has no bonds", st.atom_style.join(" ")), "atom style cannot hold them"));
    }
    let t = &st.topo;
    let check = |typ: i64, off: i64, ntypes: usize, span: Span, kind: &str| -> DResult<usize> {
        let v = typ + off;
        if v <= 0 || (boxed && v as usize > ntypes) {
            return Err(Diagnostic::at(span, format!("invalid {kind} type {v} in the molecule file (the box has {ntypes} {kind} types)"), format!("{kind} type out of range")));
        }
        Ok(v as usize)
    };
    for b in &mf.bonds {
        m.bonds.push((check(b.typ, o.boff, t.nbondtypes, b.type_span, "bond")?, b.atoms.map(|a| a - 1)));
    }
    for b in &mf.angles {
        m.angles.push((check(b.typ, o.aoff, t.nangletypes, b.type_span, "angle")?, b.atoms.map(|a| a - 1)));
    }
    for b in &mf.dihedrals {
        m.dihedrals.push((check(b.typ, o.doff, t.ndihedraltypes, b.type_span, "dihedral")?, b.atoms.map(|a| a - 1)));
    }
    // special lists: dmhs derives them from the bonds of the whole system, so a file's own
    // lists must be the ones its bonds imply
    if let (Some(counts), Some(lists)) = (&mf.special_counts, &mf.specials) {
        let derived = m.special_lists();
        for i in 0..m.natoms() {
            let c = counts.values[i];
            let given = &lists.values[i];
            let parts = [&given[..c[0]], &given[c[0]..c[0] + c[1]], &given[c[0] + c[1]..]];
            for level in 0..3 {
                let mut g: Vec<usize> = parts[level].iter().map(|a| a - 1).collect();
                let mut d = derived[i][level].clone();
                g.sort_unstable();
                d.sort_unstable();
                if g != d {
                    return Err(Diagnostic::at(lists.spans[i], format!("the 1-{} special partners of atom {} differ from the ones its bonds imply ({:?}); special lists other than those of the bonds are not supported", level + 2, i + 1, d.iter().map(|a| a + 1).collect::<Vec<_>>()), "unsupported special list"));
                }
            }
        }
    }
    Ok(m.with_radius())
}
