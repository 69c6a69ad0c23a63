//! `create_box` and `create_atoms`: the box from a region, and new atoms on lattice sites,
//! at single points or at random points, generated in exactly the order LAMMPS creates them
//! on one MPI rank, so that atom IDs `first_id, first_id + 1, ...` assigned in that order
//! match LAMMPS' IDs atom by atom.

use crate::engine::domain::{BoundaryKind, Domain};
use crate::engine::lattice::Lattice;
use crate::engine::molecule::Molecule;
use crate::engine::random_park::RanPark;
use crate::engine::region::Region;
use dmhs_parser::{Args, Command, DResult, Diagnostic, Span};
use nalgebra::Vector3;

const BOX_SYNTAX: &str = "create_box N region-ID keyword value ... \
(keywords: bond/types, angle/types, dihedral/types, improper/types, extra/bond/per/atom, \
extra/angle/per/atom, extra/dihedral/per/atom, extra/improper/per/atom, extra/special/per/atom)";

const ATOMS_SYNTAX: &str = "create_atoms type box|region ID|single x y z|random N seed region-ID|NULL \
keyword value ... (keywords: basis M itype, remap yes|no, units lattice|box, overlap d, maxtry n, mol template-ID seed, rotate theta Rx Ry Rz)";

/// Relative shrink of the insertion box at periodic faces (LAMMPS `EPSILON`).
const EPSILON: f64 = 1.0e-6;
/// Seed for min/max searches.
const BIG: f64 = 1.0e30;

/// What `create_box` defines: the number of atom types, the box, and the topology counts.
#[derive(Clone, Debug, PartialEq)]
pub struct CreateBox {
    pub ntypes: usize,
    pub domain: Domain,
    /// The box before the shrink-wrap padding: LAMMPS' `small` margins (1e-4 of its lengths)
    /// come from it, not from the padded box.
    pub unpadded: Domain,
    pub bond_types: usize,
    pub angle_types: usize,
    pub dihedral_types: usize,
    pub improper_types: usize,
    pub extra_bond_per_atom: usize,
    pub extra_angle_per_atom: usize,
    pub extra_dihedral_per_atom: usize,
    pub extra_improper_per_atom: usize,
    pub extra_special_per_atom: usize,
}

/// Parse `create_box N region-ID ...`: the box is the region's bounding box (as LAMMPS does
/// for every non-prism region), padded at shrink-wrapped faces. `boundary` comes from the
/// `boundary` command (per face: `[dim][0]` lower, `[dim][1]` upper).
pub fn create_box(
    cmd: &Command,
    regions: &[Region],
    dimension: usize,
    boundary: [[BoundaryKind; 2]; 3],
) -> DResult<CreateBox> {
    let mut a = Args::new(cmd, BOX_SYNTAX);
    // dmhs keeps tables per type and per pair of types: MAX_TYPES, not LAMMPS' 2^31 - 1
    let max_types = dmhs_parser::data_file::MAX_TYPES as i64;
    let ntypes = a.i64_in("number of atom types", 1, max_types)? as usize;
    crate::sim::memory::check_types(ntypes).map_err(|e| Diagnostic::at(cmd.span, format!("create_box {ntypes} atom types: {e}"), "too many atom types"))?;
    let rw = a.word("region ID")?;
    if rw.text == "NULL" {
        return Err(a.error_at(
            rw,
            "create_box with a general triclinic box (NULL region) is not supported",
            "not supported",
        ));
    }
    let Some(region) = regions.iter().find(|r| r.id == rw.text) else {
        return Err(a.error_at(rw, format!("create_box region `{}` does not exist", rw.text), "unknown region ID"));
    };
    // a prism gives a triclinic box of its own bounds and tilts (LAMMPS' CreateBox)
    let prism = region.prism();
    let Some((lo, hi)) = prism.map(|(lo, hi, _)| (lo, hi)).or_else(|| region.extent()) else {
        return Err(a.error_at(
            rw,
            format!("create_box region `{}` does not support a bounding box", rw.text),
            "no bounding box (side out or unbounded)",
        ));
    };
    if dimension == 2 && (lo[2] >= 0.0 || hi[2] <= 0.0) {
        return Err(a.error_at(
            rw,
            "create_box region zlo/zhi for a 2d simulation must straddle 0.0",
            "z range must contain 0",
        ));
    }
    if (0..3).any(|d| lo[d] >= hi[d]) {
        return Err(a.error_at(
            rw,
            format!("create_box region `{}` gives invalid box bounds (lo >= hi)", rw.text),
            "empty box",
        ));
    }
    if let Some(d) = (0..3).find(|&d| !(hi[d] - lo[d]).is_finite()) {
        return Err(a.error_at(
            rw,
            format!("create_box region `{}`: the box length {} - ({}) overflows a double in {}", rw.text, crate::output::format::g(hi[d]), crate::output::format::g(lo[d]), ["x", "y", "z"][d]),
            "box too large",
        ));
    }
    // LAMMPS `Domain::set_initial_box(1)`: shrink-wrapped (`s`) faces are pushed out by
    // 1e-4 of the box length, so lattice sites on those faces fall inside the box.
    let mut unpadded = Domain::new(dimension, lo, hi, boundary);
    if let Some((_, _, tilt)) = prism {
        unpadded.tilt = Some(tilt);
        crate::deck::tilt_check(&unpadded).map_err(|e| a.error_at(rw, e, "triclinic box"))?;
    }
    let domain = crate::engine::boundary::pad_shrink_faces(&unpadded);
    let mut out = CreateBox {
        ntypes,
        domain,
        unpadded,
        bond_types: 0,
        angle_types: 0,
        dihedral_types: 0,
        improper_types: 0,
        extra_bond_per_atom: 0,
        extra_angle_per_atom: 0,
        extra_dihedral_per_atom: 0,
        extra_improper_per_atom: 0,
        extra_special_per_atom: 0,
    };
    const KEYWORDS: [&str; 9] = [
        "bond/types",
        "angle/types",
        "dihedral/types",
        "improper/types",
        "extra/bond/per/atom",
        "extra/angle/per/atom",
        "extra/dihedral/per/atom",
        "extra/improper/per/atom",
        "extra/special/per/atom",
    ];
    while let Some(kw) = a.peek() {
        a.skip(1);
        let Some(k) = KEYWORDS.iter().position(|s| *s == kw.text) else {
            return Err(a.unknown_keyword(kw, &KEYWORDS));
        };
        let n = a.i64_in(KEYWORDS[k], 0, if k < 4 { max_types } else { i32::MAX as i64 })? as usize;
        let slot = match k {
            0 => &mut out.bond_types,
            1 => &mut out.angle_types,
            2 => &mut out.dihedral_types,
            3 => &mut out.improper_types,
            4 => &mut out.extra_bond_per_atom,
            5 => &mut out.extra_angle_per_atom,
            6 => &mut out.extra_dihedral_per_atom,
            7 => &mut out.extra_improper_per_atom,
            _ => &mut out.extra_special_per_atom,
        };
        *slot = n;
    }
    Ok(out)
}

/// Where `create_atoms` puts atoms.
#[derive(Clone, Debug, PartialEq)]
pub enum CreateStyle {
    /// On every lattice site in the box.
    Box,
    /// On every lattice site in the region with this ID.
    Region(String),
    /// One atom at this position (already in box units).
    Single([f64; 3]),
    /// `n` atoms at uniformly random points, optionally restricted to a region.
    Random { n: usize, seed: i32, region: Option<String> },
}

/// A parsed `create_atoms` command.
#[derive(Clone, Debug, PartialEq)]
pub struct CreateAtoms {
    pub style: CreateStyle,
    /// Type of each lattice basis atom (all `type` unless changed with `basis`).
    pub basis_types: Vec<usize>,
    /// The type argument (used for single and random atoms).
    pub atom_type: usize,
    pub remap: bool,
    /// Minimum distance to existing atoms for `random` (box units).
    pub overlap: Option<f64>,
    pub maxtry: usize,
    /// `mol ID seed`: a copy of this molecule template, randomly rotated, at each point (the
    /// generated points are then molecule centres).
    pub mol: Option<(String, i64)>,
    /// `rotate theta Rx Ry Rz`: this rotation for every molecule instead of random ones.
    pub rotate: Option<[[f64; 3]; 3]>,
    pub span: Span,
}

/// The atoms one `create_atoms` command makes, in LAMMPS' creation order, and any warnings
/// (e.g. LAMMPS' "Only inserted N particles out of M").
#[derive(Clone, Debug, PartialEq)]
pub struct Created {
    pub atoms: Vec<([f64; 3], usize)>,
    /// The orientation of each molecule, where the overlap test chose them (random with mol
    /// and overlap); empty: add_molecules draws them.
    pub rotations: Vec<[[f64; 3]; 3]>,
    pub warnings: Vec<Diagnostic>,
}

impl CreateAtoms {
    /// Parse `create_atoms`. `ntypes` is the number of atom types of the box.
    pub fn from_lammps(
        cmd: &Command,
        ntypes: usize,
        dimension: usize,
        lattice: Option<&Lattice>,
        regions: &[Region],
        molecules: &[Molecule],
    ) -> DResult<CreateAtoms> {
        let none = Lattice::none(1.0);
        let lattice = lattice.unwrap_or(&none);
        let mut a = Args::new(cmd, ATOMS_SYNTAX);
        let type_word = a.peek();
        let atom_type = a.i64("atom type")?;
        let style_word = a.word("create_atoms style")?;
        let find_region = |a: &Args, w: &dmhs_parser::Word| -> DResult<String> {
            if regions.iter().any(|r| r.id == w.text) {
                Ok(w.text.clone())
            } else {
                Err(a.error_at(w, format!("create_atoms region `{}` does not exist", w.text), "unknown region ID"))
            }
        };
        let mut single_words = None;
        let mut style = match style_word.text.as_str() {
            "box" => CreateStyle::Box,
            "region" => {
                let w = a.word("region ID")?;
                CreateStyle::Region(find_region(&a, w)?)
            }
            "single" => {
                let x = [a.f64("x")?, a.f64("y")?, a.f64("z")?];
                single_words = a.last();
                CreateStyle::Single(x)
            }
            "random" => {
                let n = a.i64_in("number of random atoms", 0, i32::MAX as i64)? as usize;
                let seed = a.i64_in("random seed", 1, i32::MAX as i64)? as i32;
                let w = a.word("region ID or NULL")?;
                let region = if w.text == "NULL" { None } else { Some(find_region(&a, w)?) };
                CreateStyle::Random { n, seed, region }
            }
            "mesh" => return Err(a.error_at(style_word, "create_atoms mesh is not supported", "not supported")),
            _ => return Err(a.unknown_keyword(style_word, &["box", "region", "single", "random"])),
        };
        let is_random = matches!(style, CreateStyle::Random { .. });

        let nbasis = lattice.nbasis();
        let mut basis_types = vec![atom_type.max(0) as usize; nbasis];
        let mut remap = false;
        let mut lattice_units = true;
        let mut overlap = None;
        let mut maxtry = 1000;
        let mut mol = None;
        let mut mol_word = None;
        let mut rotate = None;
        const KEYWORDS: [&str; 7] = ["basis", "remap", "units", "overlap", "maxtry", "mol", "rotate"];
        while let Some(kw) = a.peek() {
            a.skip(1);
            match kw.text.as_str() {
                "basis" => {
                    let ib = a.i64_in("basis atom index", 1, nbasis.max(1) as i64)? as usize;
                    if nbasis == 0 {
                        return Err(a.error_at(
                            a.last().unwrap(),
                            "create_atoms basis needs a lattice with basis atoms",
                            "no lattice basis",
                        ));
                    }
                    let it = a.i64_in("basis atom type", 1, ntypes as i64)? as usize;
                    basis_types[ib - 1] = it;
                }
                "remap" => remap = a.logical("remap")?,
                "units" => lattice_units = a.choice("units", &["lattice", "box"])? == 0,
                "overlap" | "maxtry" if !is_random => {
                    return Err(a.error_at(
                        kw,
                        format!("create_atoms {} can only be used with the random style", kw.text),
                        "random style only",
                    ));
                }
                "overlap" => overlap = Some(a.positive_f64("overlap distance")?),
                "maxtry" => maxtry = a.i64_in("maxtry", 1, i32::MAX as i64)? as usize,
"mol" => {
                    let w = a.word("molecule template ID")?;
                    let Some(m) = molecules.iter().find(|m| m.id == w.text) else {
                        return Err(a.error_at(w, format!("molecule template `{}` for create_atoms does not exist", w.text), "unknown molecule template ID"));
                    };
                    if m.typ.is_none() {
                        return Err(a.error_at(w, "create_atoms molecule must have atom types (a Types section)", "template without types"));
                    }
                    let seed = a.i64_in("molecule random seed", 1, *crate::engine::random_mars::SEED_RANGE.end())?;
                    mol_word = Some(w);
                    mol = Some((w.text.clone(), seed));
                }
                "rotate" => {
                    let theta = a.f64("rotation angle (degrees)")?;
                    let r = [a.f64("Rx")?, a.f64("Ry")?, a.f64("Rz")?];
                    if r == [0.0; 3] {
                        return Err(a.error_at(a.last().unwrap(), "create_atoms rotate needs a nonzero rotation axis", "zero axis"));
                    }
                    if dimension == 2 && (r[0] != 0.0 || r[1] != 0.0) {
                        return Err(a.error_at(a.last().unwrap(), "invalid create_atoms rotation vector for 2d model (must be along z)", "not along z"));
                    }
                    rotate = Some(crate::engine::molecule::rotation(r, theta * std::f64::consts::PI / 180.0));
                }
                "var" | "set" | "ratio" | "subset" | "meshmode" | "radscale" => {
                    return Err(a.error_at(
                        kw,
                        format!("create_atoms keyword `{}` is not supported", kw.text),
                        "not supported",
                    ));
                }
                _ => return Err(a.unknown_keyword(kw, &KEYWORDS)),
            }
        }
        if let (Some((id, _)), Some(w)) = (&mol, mol_word) {
            // the type argument offsets the template's types
            let maxt = molecules.iter().find(|m| &m.id == id).map(|m| m.max_type()).unwrap_or(0) as i64;
            if atom_type < 0 || atom_type + maxt > ntypes as i64 {
                return Err(a.error_at(w, format!("invalid atom type in create_atoms mol: the offset {atom_type} plus the template's largest type {maxt} exceeds the {ntypes} atom types of the box"), "type out of range"));
            }
        } else if atom_type < 1 || atom_type as usize > ntypes {
            let w = type_word.unwrap();
            return Err(a.error_at(
                w,
                format!("invalid atom type {atom_type} in create_atoms (box has {ntypes} types)"),
                "type out of range",
            ));
        }
        match &mut style {
            CreateStyle::Box | CreateStyle::Region(_) => {
                if nbasis == 0 {
                    return Err(a
                        .error_at(
                            style_word,
                            "cannot create atoms on a lattice before a `lattice` command",
                            "lattice undefined",
                        )
                        .with_note("define a lattice first, e.g. `lattice sq 1.0`"));
                }
            }
            CreateStyle::Single(x) => {
                if dimension == 2 && x[2] != 0.0 {
                    return Err(a.error_at(
                        single_words.unwrap(),
                        "create_atoms single for a 2d simulation requires z = 0.0",
                        "z must be 0",
                    ));
                }
                if lattice_units {
                    x[0] *= lattice.xlattice;
                    x[1] *= lattice.ylattice;
                    x[2] *= lattice.zlattice;
                }
                if !x.iter().all(|c| c.is_finite()) {
                    return Err(a.error_at(single_words.unwrap(), format!("create_atoms single: the point {x:?} in box units is not finite"), "overflows"));
                }
            }
            CreateStyle::Random { .. } => {
                if lattice_units {
                    overlap = overlap.map(|d| d * lattice.xlattice);
                }
            }
        }
        Ok(CreateAtoms { style, basis_types, atom_type: atom_type as usize, remap, overlap, maxtry, mol, rotate, span: cmd.span })
    }

    /// Generate the atoms on one rank owning the whole `domain`, in LAMMPS' order.
    /// `existing` are the positions of atoms already in the system (for `overlap`).
    pub fn generate(
        &self,
        domain: &Domain,
        lattice: Option<&Lattice>,
        regions: &[Region],
        molecules: &[Molecule],
        existing: &[[f64; 3]],
    ) -> DResult<Created> {
        let none = Lattice::none(1.0);
        let lattice = lattice.unwrap_or(&none);
        let region = |id: &String| regions.iter().find(|r| &r.id == id);
        let mut out = Created { atoms: vec![], rotations: vec![], warnings: vec![] };

        // Insertion bounds: the sub-domain, for lattice styles shifted at periodic faces
        // (lower face down by eps, upper face down by 2 eps) so that of two periodic images
        // "on" the boundary exactly one is created.
        // A triclinic box's bounds are box fractions (eps then is EPSILON itself).
        let tri = domain.triclinic();
        let prd = if tri { [1.0; 3] } else { domain.prd() };
        let (mut sublo, mut subhi) = if tri { ([0.0; 3], [1.0; 3]) } else { (domain.lo, domain.hi) };
        if matches!(self.style, CreateStyle::Box | CreateStyle::Region(_)) {
            for d in 0..3 {
                if domain.periodic(d) {
                    let eps = prd[d] * EPSILON;
                    sublo[d] -= eps;
                    subhi[d] -= 2.0 * eps;
                }
            }
        }
        let in_sub = |x: [f64; 3]| {
            let c = if tri { domain.x2lamda(x) } else { x };
            (0..3).all(|d| c[d] >= sublo[d] && c[d] < subhi[d])
        };

        match &self.style {
            CreateStyle::Single(x) => {
                let mut x = *x;
                if self.remap {
                    domain.remap(&mut x, &mut [0; 3]);
                }
                if in_sub(x) {
                    out.atoms.push((x, self.atom_type));
                }
            }
            CreateStyle::Random { n, seed, region: rid } => {
                let reg = rid.as_ref().and_then(region);
                let template = self.mol.as_ref().and_then(|(id, seed)| Some((molecules.iter().find(|m| &m.id == id)?, *seed)));
                self.add_random(domain, *n, *seed, reg, template, existing, &in_sub, &mut out)?;
            }
            CreateStyle::Box | CreateStyle::Region(_) => {
                let reg = match &self.style {
                    CreateStyle::Region(id) => match region(id) {
                        Some(r) => Some(r),
                        None => {
                            return Err(Diagnostic::at(
                                self.span,
                                format!("create_atoms region `{id}` does not exist"),
                                "unknown region",
                            ))
                        }
                    },
                    _ => None,
                };
                self.add_lattice(domain, lattice, reg, &in_sub, &mut out)?;
            }
        }
        Ok(out)
    }

    #[allow(clippy::too_many_arguments)]
    fn add_random(
        &self,
        domain: &Domain,
        n: usize,
        seed: i32,
        region: Option<&Region>,
        template: Option<(&Molecule, i64)>,
        existing: &[[f64; 3]],
        in_sub: &dyn Fn([f64; 3]) -> bool,
        out: &mut Created,
    ) -> DResult<()> {
        // 2d points sit mid-box in z (the box's, not the region's)
        let zmid = domain.lo[2] + 0.5 * (domain.hi[2] - domain.lo[2]);
        let mut random = RanPark::new(seed);
        // LAMMPS warms up the generator to decorrelate consecutive seeds.
        for _ in 0..30 {
            random.uniform();
        }
        // a triclinic box: points in its bounding box, those outside the box itself rejected
        let (mut lo, mut hi) = domain.bounds();
        if let Some((rlo, rhi)) = region.and_then(|r| r.extent()) {
            for d in 0..3 {
                lo[d] = if lo[d] > rlo[d] { lo[d] } else { rlo[d] };
                hi[d] = if hi[d] < rhi[d] { hi[d] } else { rhi[d] };
            }
        }
        if (0..3).any(|d| lo[d] > hi[d]) {
            return Err(Diagnostic::at(
                self.span,
                "no overlap of box and region for create_atoms",
                "region outside the box",
            ));
        }
        self.fits(n as f64)?;
        // a molecule is tested atom by atom, in the orientation drawn for the trial (LAMMPS 22
        // Jul 2025 inserts as many trimers as this, not as a test of the centre alone, widened
        // by the molecule's radius); the accepted trial's orientation is the copy's
        let odistsq = self.overlap.map(|d| d * d);
        // what the overlap test sees: the atoms there before, then each insertion (a
        // molecule's atoms as LAMMPS has them until the end of the command: not yet wrapped)
        let mut placed: Vec<[f64; 3]> = if odistsq.is_some() { existing.to_vec() } else { vec![] };
        let mut ranmol = template.map(|(_, seed)| crate::engine::random_mars::RanMars::new(seed as i32));
        let mut ninsert = 0;
        for _ in 0..n {
            let mut found = None;
            for _ in 0..self.maxtry {
                let mut x = [
                    lo[0] + random.uniform() * (hi[0] - lo[0]),
                    lo[1] + random.uniform() * (hi[1] - lo[1]),
                    lo[2] + random.uniform() * (hi[2] - lo[2]),
                ];
                if domain.dimension == 2 {
                    x[2] = zmid;
                }
                if let Some(r) = region {
                    if !r.matches(x) {
                        continue;
                    }
                }
                if domain.triclinic() && !domain.contains(x) {
                    continue;
                }
                let mut rot = None;
                if let Some(od2) = odistsq {
                    let close = |y: [f64; 3]| {
                        placed.iter().any(|p| {
                            let mut dx = [y[0] - p[0], y[1] - p[1], y[2] - p[2]];
                            domain.minimum_image(&mut dx);
                            dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2] < od2
                        })
                    };
                    let reject = match (template, ranmol.as_mut()) {
                        (Some((m, _)), Some(ran)) => {
                            let r = copy_rotation(ran, domain.dimension, self.rotate);
                            rot = Some(r);
                            let hit = m.unwrapped(&r, x).any(close);
                            hit
                        }
                        _ => close(x),
                    };
                    if reject {
                        continue;
                    }
                }
                found = Some((x, rot));
                break;
            }
            let Some((x, rot)) = found else { continue };
            ninsert += 1;
            if in_sub(x) {
                out.atoms.push((x, self.atom_type));
                match (template, rot) {
                    (Some((m, _)), Some(rot)) => {
                        out.rotations.push(rot);
                        placed.extend(m.unwrapped(&rot, x));
                    }
                    _ if odistsq.is_some() => placed.push(x),
                    _ => {}
                }
            }
        }
        if ninsert < n {
            out.warnings.push(
                Diagnostic::warning(format!("only inserted {ninsert} particles out of {n}"))
                    .with_label(self.span, "create_atoms random"),
            );
        }
        Ok(())
    }

    /// Refuse to make `n` atoms that would not fit in memory: each is held while made (32
    /// bytes) and then stored (at least the arrays of the plainest atom style).
    fn fits(&self, n: f64) -> DResult<()> {
        crate::sim::memory::check_atoms(n, crate::engine::atoms::AtomFeatures::default(), 0, std::mem::size_of::<([f64; 3], usize)>())
            .map_err(|e| Diagnostic::at(self.span, format!("create_atoms would make about {n:.3e} atoms: {e}"), "too many atoms for this machine"))
    }

    fn add_lattice(
        &self,
        domain: &Domain,
        lattice: &Lattice,
        region: Option<&Region>,
        in_sub: &dyn Fn([f64; 3]) -> bool,
        out: &mut Created,
    ) -> DResult<()> {
        // Bounding box of the sub-domain (LAMMPS' bbox of a triclinic box's fractions),
        // narrowed by the region's extent.
        let (mut blo, mut bhi) = if domain.triclinic() { domain.bbox([0.0; 3], [1.0; 3]) } else { (domain.lo, domain.hi) };
        if let Some((rlo, rhi)) = region.and_then(|r| r.extent()) {
            for d in 0..3 {
                if rlo[d] > blo[d] {
                    blo[d] = if rlo[d] > bhi[d] { bhi[d] } else { rlo[d] };
                }
                if rhi[d] < bhi[d] {
                    bhi[d] = if rhi[d] < blo[d] { blo[d] } else { rhi[d] };
                }
            }
        }
        // Its 8 corners in lattice space -> loop bounds, padded by one cell each way.
        let mut lmin = [BIG; 3];
        let mut lmax = [-BIG; 3];
        for corner in 0..8 {
            let p = Vector3::new(
                if corner & 1 == 0 { blo[0] } else { bhi[0] },
                if corner & 2 == 0 { blo[1] } else { bhi[1] },
                if corner & 4 == 0 { blo[2] } else { bhi[2] },
            );
            let q = lattice.box2lattice(p);
            for d in 0..3 {
                lmin[d] = if q[d] < lmin[d] { q[d] } else { lmin[d] };
                lmax[d] = if q[d] > lmax[d] { q[d] } else { lmax[d] };
            }
        }
        let mut lo = [0i64; 3];
        let mut hi = [0i64; 3];
        for d in 0..3 {
            // C++ static_cast<int> truncates toward zero; one more cell below for negatives.
            lo[d] = lmin[d] as i32 as i64 - 1;
            hi[d] = lmax[d] as i32 as i64 + 1;
            if lmin[d] < 0.0 {
                lo[d] -= 1;
            }
        }
        // 2d: only the z = 0 plane of sites (LAMMPS 2025 creates no other layers).
        if domain.dimension == 2 {
            lo[2] = 0;
            hi[2] = 0;
        }
        let ncells = (0..3).map(|d| (hi[d] - lo[d] + 1).max(0) as u128).product::<u128>() * lattice.nbasis() as u128;
        if ncells > i32::MAX as u128 {
            return Err(Diagnostic::at(
                self.span,
                "create_atoms lattice size overflow (too many lattice sites to scan)",
                "lattice too fine for this box",
            ));
        }
        // the sites in the bounding box: its volume (area in 2d) over the unit cell's, times
        // the basis (a region inside it makes fewer)
        let origin = lattice.lattice2box(Vector3::zeros());
        let [a1, a2, a3] = [Vector3::x(), Vector3::y(), Vector3::z()].map(|e| lattice.lattice2box(e) - origin);
        let ext = |d: usize| (bhi[d] - blo[d]).max(0.0);
        let (cell, volume) = if domain.dimension == 2 { (a1.cross(&a2).z.abs(), ext(0) * ext(1)) } else { (a1.dot(&a2.cross(&a3)).abs(), ext(0) * ext(1) * ext(2)) };
        if cell > 0.0 {
            self.fits(volume / cell * lattice.nbasis() as f64)?;
        }
        for k in lo[2]..=hi[2] {
            for j in lo[1]..=hi[1] {
                for i in lo[0]..=hi[0] {
                    for (m, b) in lattice.basis.iter().enumerate() {
                        let x: [f64; 3] = lattice.lattice2box(Vector3::new(i as f64, j as f64, k as f64) + b).into();
                        if let Some(r) = region {
                            if !r.matches(x) {
                                continue;
                            }
                        }
                        if !in_sub(x) {
                            continue;
                        }
                        out.atoms.push((x, self.basis_types[m]));
                    }
                }
            }
        }
        Ok(())
    }
}

/// Copies of the template `m` centred at `centers` (in LAMMPS' creation order), each turned by a
/// random rotation from LAMMPS' molecule stream (`RanMars(seed + rank)`, rank 0): a random axis
/// (3d; z in 2d) and angle, or the fixed rotation `rotate`. Atom and molecule IDs follow the
/// largest present ones.
pub fn add_molecules(state: &mut crate::engine::state::State, m: &Molecule, seed: i64, rotate: Option<[[f64; 3]; 3]>, type_offset: usize, centers: &[[f64; 3]], rotations: &[[[f64; 3]; 3]]) -> Result<(), String> {
    m.check_types(state)?;
    let mut ran = crate::engine::random_mars::RanMars::new(seed as i32);
    let domain = state.domain.clone().ok_or("create_atoms before the box is defined")?;
    let mut mol_offset = state.atoms.max_molecule();
    let mut tag = state.atoms.max_tag();
    for (k, c) in centers.iter().enumerate() {
        let rot = match rotations.get(k) {
            Some(r) => *r,
            None => copy_rotation(&mut ran, domain.dimension, rotate),
        };
        let placed = m.place(&rot, *c, &domain);
        m.push_copy(state, &placed, tag, mol_offset, type_offset, [0.0; 3]);
        tag += m.natoms() as i64;
        mol_offset += m.nmolecules();
    }
    if !centers.is_empty() && m.has_topology() {
        state.rebuild_special()?;
    }
    Ok(())
}

/// The orientation of the next copy: `rotate`, or LAMMPS' random one from the molecule
/// stream `ran` (a random axis, z in 2d, and angle; add_molecule).
fn copy_rotation(ran: &mut crate::engine::random_mars::RanMars, dimension: usize, rotate: Option<[[f64; 3]; 3]>) -> [[f64; 3]; 3] {
    if let Some(rot) = rotate {
        return rot;
    }
    let r = if dimension == 3 { [ran.uniform() - 0.5, ran.uniform() - 0.5, ran.uniform() - 0.5] } else { [0.0, 0.0, 1.0] };
    crate::engine::molecule::rotation(r, ran.uniform() * std::f64::consts::TAU)
}



/// Parse and run a `create_atoms` command in one call.
pub fn create_atoms(
    cmd: &Command,
    domain: &Domain,
    ntypes: usize,
    lattice: Option<&Lattice>,
    regions: &[Region],
    molecules: &[Molecule],
    existing: &[[f64; 3]],
) -> DResult<Created> {
    CreateAtoms::from_lammps(cmd, ntypes, domain.dimension, lattice, regions, molecules)?
        .generate(domain, lattice, regions, molecules, existing)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::engine::lattice::tests::cmd;
    use crate::engine::units::{UnitStyle, Units};

    /// What the geometry commands of a test deck produced.
    pub(crate) struct Deck {
        pub dim: usize,
        pub lattice: Option<Lattice>,
        pub boxed: Option<CreateBox>,
        pub regions: Vec<Region>,
        pub atoms: Vec<([f64; 3], usize)>,
    }

    /// Run the geometry commands of a deck (one command per line; other commands are
    /// skipped) and return the resulting state; atoms are in creation (= LAMMPS ID) order.
    pub(crate) fn run_deck_state(deck: &str) -> DResult<Deck> {
        let mut units = Units::new(UnitStyle::Lj);
        let mut st = Deck { dim: 3, lattice: None, boxed: None, regions: vec![], atoms: vec![] };
        let mut boundary = [[BoundaryKind::Periodic; 2]; 3];
        for line in deck.lines().map(str::trim).filter(|l| !l.is_empty()) {
            let c = cmd(line);
            let args = c.arg_strs();
            match c.name() {
                "units" => {
                    units = Units::new(match args[0] {
                        "lj" => UnitStyle::Lj,
                        "si" => UnitStyle::Si,
                        "cgs" => UnitStyle::Cgs,
                        u => panic!("test deck uses unsupported units {u}"),
                    })
                }
                "dimension" => st.dim = args[0].parse().unwrap(),
                "boundary" => {
                    for d in 0..3 {
                        let k = match args[d] {
                            "p" => BoundaryKind::Periodic,
                            "f" => BoundaryKind::Fixed,
                            "s" => BoundaryKind::Shrink,
                            _ => BoundaryKind::ShrinkMin,
                        };
                        boundary[d] = [k, k];
                    }
                }
                "lattice" => st.lattice = Some(Lattice::from_lammps(&c, &units, st.dim)?),
                "region" => {
                    let r = Region::from_lammps(
                        &c,
                        st.boxed.as_ref().map(|b| &b.domain),
                        st.lattice.as_ref(),
                        &st.regions,
                        &mut |n| Err(format!("variable {n} is not defined in this test")),
                    )?;
                    st.regions.push(r);
                }
                "create_box" => st.boxed = Some(create_box(&c, &st.regions, st.dim, boundary)?),
                "create_atoms" => {
                    let b = st.boxed.as_ref().unwrap();
                    let existing: Vec<[f64; 3]> = st.atoms.iter().map(|a| a.0).collect();
                    let made = create_atoms(&c, &b.domain, b.ntypes, st.lattice.as_ref(), &st.regions, &[], &existing)?;
                    st.atoms.extend(made.atoms);
                }
                _ => {}
            }
        }
        Ok(st)
    }

    pub(crate) fn run_deck(deck: &str) -> DResult<Vec<([f64; 3], usize)>> {
        Ok(run_deck_state(deck)?.atoms)
    }

    /// FNV-1a over (id, type, x, y, z) little-endian bytes in ID order; the same digest is
    /// computed from LAMMPS' extract_atom arrays by the script that made the fixtures.
    pub(crate) fn digest(atoms: &[([f64; 3], usize)]) -> u64 {
        let mut h: u64 = 0xcbf29ce484222325;
        let mut eat = |bytes: [u8; 8]| {
            for b in bytes {
                h = (h ^ b as u64).wrapping_mul(0x100000001b3);
            }
        };
        for (i, (x, t)) in atoms.iter().enumerate() {
            eat((i as u64 + 1).to_le_bytes());
            eat((*t as u64).to_le_bytes());
            for c in x {
                eat(c.to_le_bytes());
            }
        }
        h
    }

    fn check(deck: &str, n: usize, fnv: u64, first: [f64; 3], last: [f64; 3]) {
        let atoms = run_deck(deck).unwrap();
        assert_eq!(atoms.len(), n);
        assert_eq!(atoms[0].0, first);
        assert_eq!(atoms[n - 1].0, last);
        assert_eq!(digest(&atoms), fnv, "coordinates/types/order differ from LAMMPS");
    }

    // Fixtures: LAMMPS 22 Jul 2025, one rank, positions by atom ID via extract_atom.

    #[test]
    fn dambreak_deck_matches_lammps() {
        let deck = "dimension 2\nunits lj\nboundary f f p
            region box block -0.035000000000000003331 3.2550000000000003375 -0.035000000000000003331 1.8 -0.0050000000000000001041 0.0050000000000000001041 units box
            create_box 2 box
            lattice sq 10000 origin 0.5 0.5 0.0
            region water block 0 0.7 0 1.4 EDGE EDGE units box
            region wall2 block -0.02999999999999999889 3.25 -0.02999999999999999889 1.8 EDGE EDGE units box
            create_atoms 1 region water
            region notinner block 0 3.22 0 2.7999999999999998224 EDGE EDGE side out units box
            region wallreg intersect 2 wall2 notinner
            create_atoms 2 region wallreg";
        check(deck, 11864, 0x628976a0c33d9416, [0.005, 0.005, 0.0], [3.245, 1.795, 0.0]);
        let atoms = run_deck(deck).unwrap();
        assert_eq!(atoms.iter().filter(|a| a.1 == 1).count(), 9800);
    }

    #[test]
    fn poiseuille_deck_matches_lammps() {
        let deck = "dimension 2\nunits si\nboundary p f p
            region box block 0 0.001 -3.0000000000000004148e-05 0.0010300000000000000995 -5.000000000000000409e-06 5.000000000000000409e-06 units box
            create_box 2 box
            lattice sq 1e-05 origin 0.5 0.5 0.0
            region fluid block 0 0.001 0 0.001 EDGE EDGE units box
            region wlo block 0 0.001 -3.0000000000000004148e-05 0 EDGE EDGE units box
            region whi block 0 0.001 0.001 0.0010300000000000000995 EDGE EDGE units box
            create_atoms 1 region fluid
            create_atoms 2 region wlo
            create_atoms 2 region whi";
        check(deck, 10600, 0xc8fceee81633790a, [5e-06, 5e-06, 0.0], [0.000995, 0.001025, 0.0]);
        assert_eq!(run_deck(deck).unwrap()[1].0, [1.5000000000000002e-05, 5e-06, 0.0]);
    }

    #[test]
    fn fcc_periodic_box_matches_lammps() {
        let deck = "units lj\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 box";
        check(deck, 256, 0xc4a721635fdb6ae6, [0.0; 3], [5.038788574147522, 5.878586669838775, 5.878586669838775]);
    }

    #[test]
    fn region_shapes_match_lammps() {
        let deck = "units lj\nboundary p f p\nlattice fcc 0.8442
            region box block 0 6 0 6 0 6
            create_box 3 box
            region s sphere 3 3 3 1.6
            region c cylinder y 1.5 4.5 1.1 0.3 5.2
            region u union 2 s c
            region blo block 0.5 4.5 0.2 3.3 0.5 5.5
            region i intersect 2 blo s
            region out sphere 3 3 3 2.5 side out
            region p prism 0.5 5 1 5 0.5 5 1.5 0.5 -0.75
            region pl plane 3 3 3 1 1 0.5
            create_atoms 1 region u
            create_atoms 2 region i basis 2 3
            create_atoms 3 region out
            create_atoms 1 region p
            create_atoms 2 region pl";
        check(
            deck,
            1506,
            0x38ab29bf6ad60c2c,
            [5.038788574147522, 4.198990478456269, 2.519394287073761],
            [8.397980956912537, 9.23777905260379, 9.23777905260379],
        );
    }

    #[test]
    fn oriented_hcp_with_origin_matches_lammps() {
        let deck = "units si\nlattice hcp 3.2 orient x 1 0 0 orient y 0 1 1 orient z 0 -1 1 origin 0.1 0.2 0.3
            region box block 0 3 0 3 0 3\ncreate_box 2 box\ncreate_atoms 1 box basis 3 2";
        check(
            deck,
            216,
            0xcfb0c99ccbe8a1b9,
            [1.9200000000000002, 2.71716865891796, 4.78498571952899],
            [8.32, 21.95764547054791, 18.79988441322149],
        );
    }

    #[test]
    fn hex_2d_cylinder_and_single_match_lammps() {
        let deck = "units lj\ndimension 2\nboundary p s p\nlattice hex 0.7 origin 0.25 0.1 0
            region box block 0 5 0 4 -0.5 0.5\ncreate_box 1 box
            region c cylinder z 2.5 2 1.3 INF INF
            create_atoms 1 region c
            create_atoms 1 single 0.5 0.5 0
            create_atoms 1 single 7.1 -2.2 0 units box remap yes";
        check(
            deck,
            8,
            0x810b0ab192dfa6bf,
            [2.2476242691805113, 3.5593137650701823, 0.0],
            [0.6421783626230032, 1.1122855515844319, 0.0],
        );
    }

    #[test]
    fn random_3d_with_region_and_overlap_matches_lammps() {
        let deck = "units lj\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 2 box
            region s sphere 3 3 3 1.5
            create_atoms 1 random 50 4821 s
            create_atoms 2 random 40 777 NULL overlap 0.9 maxtry 50";
        check(
            deck,
            79,
            0x25400e6ab7bf8b1e,
            [5.276971230956113, 4.857179395934454, 3.7198119934264655],
            [0.20113230189597706, 1.0830609040820878, 2.900285086800351],
        );
    }

    #[test]
    fn random_2d_matches_lammps() {
        let deck = "units lj\ndimension 2\nlattice sq 0.8\nregion box block 0 10 0 10 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 random 30 12345 NULL";
        check(
            deck,
            30,
            0x979ef700a9c79249,
            [10.181403293570474, 3.743176867540669, 0.0],
            [4.66724113565348, 1.057116235409361, 0.0],
        );
    }

    #[test]
    fn shrink_wrapped_faces_are_padded_like_lammps() {
        // boundary f s m: y faces padded by 1e-4 * 4.5, so sites at y = 3 are created;
        // sites on the fixed (x = 2) and min-shrink (z = 0) upper faces are not.
        let deck = "units lj\nboundary f s m\nlattice sc 1.0\nregion box block -2 2 -1.5 3 -3 0\ncreate_box 1 box\ncreate_atoms 1 box";
        check(deck, 60, 0x766be3c42b27e5b1, [-2.0, -1.0, -3.0], [1.0, 3.0, -1.0]);
        let st = run_deck_state(deck).unwrap();
        assert_eq!(st.boxed.unwrap().domain.hi, [2.0, 3.00045, 0.0]);
    }

    #[test]
    fn custom_lattice_and_outside_cylinder_match_lammps() {
        let deck = "units lj\nboundary p p f
            lattice custom 1.3 a1 1 0 0 a2 0.5 0.8 0 a3 0.2 0.3 0.9 basis 0 0 0 basis 0.5 0.25 0.1 origin 0.3 0.1 0.6
            region box block -1 3 0 4 -2 2\ncreate_box 2 box
            region cyl cylinder x 2 0 1.5 INF EDGE side out
            create_atoms 1 region cyl basis 2 2";
        check(
            deck,
            127,
            0xe98edbf99565b1fd,
            [-1.7903290113107562, 0.3992820097167875, -1.6228881685262975],
            [6.066510534729254, 4.6497034034761375, 1.8547293354586256],
        );
    }

    #[test]
    fn fcc_111_orientation_matches_lammps() {
        let deck = "units lj\nlattice fcc 0.8442 orient x 1 1 1 orient y -1 1 0 orient z -1 -1 2
            region box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box";
        check(
            deck,
            432,
            0x97096ee5460365ee,
            [0.0, 1.187653856581669, 0.0],
            [7.757722505796487, 4.750615426326676, 6.856922738015239],
        );
    }

    #[test]
    fn single_remap_wraps_several_periods_like_lammps() {
        // LAMMPS: create_atoms 1 single 9.5 -7.25 3.0 units box remap yes -> (1.5, 0.75, 3.0)
        let deck = "units lj\nregion box block 0 4 0 4 0 4 units box\ncreate_box 1 box
            create_atoms 1 single 9.5 -7.25 3.0 units box remap yes
            create_atoms 1 single 4.0 1 1 units box
            create_atoms 1 single 0.0 1 1 units box";
        let atoms = run_deck(deck).unwrap();
        assert_eq!(atoms, vec![([1.5, 0.75, 3.0], 1), ([0.0, 1.0, 1.0], 1)]);
    }

    #[test]
    fn errors_are_located() {
        let e = run_deck("units lj\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 box").unwrap_err();
        assert!(e.message.contains("lattice"), "{}", e.message);
        let e = run_deck("units lj\nlattice sc 1\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 2 box")
            .unwrap_err();
        assert!(e.message.contains("invalid atom type 2"), "{}", e.message);
        let e = run_deck("units lj\ndimension 2\nregion box block 0 4 0 4 0.1 0.5\ncreate_box 1 box").unwrap_err();
        assert!(e.message.contains("straddle"), "{}", e.message);
        let e = run_deck(
            "units lj\ndimension 2\nregion box block 0 4 0 4 -1 1\ncreate_box 1 box\ncreate_atoms 1 single 1 1 0.5",
        )
        .unwrap_err();
        assert!(e.message.contains("z = 0.0"), "{}", e.message);
        let e = run_deck("units lj\nregion box block 0 4 0 4 0 4 side out\ncreate_box 1 box").unwrap_err();
        assert!(e.message.contains("bounding box"), "{}", e.message);
        let e =
            run_deck("units lj\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 single 1 1 1 overlap 1")
                .unwrap_err();
        assert!(e.message.contains("random"), "{}", e.message);
    }
}
