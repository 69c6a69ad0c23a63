//! Computes: quantities derived from the current state (LAMMPS `compute`), read by thermo
//! output, variables and dumps. Each style lives in its own file; [`new_compute`] is the
//! registry. Computes only read the simulation.

pub mod bond_local;
pub mod centro_atom;
pub mod chunk_atom;
pub mod com;
pub mod contact_atom;
pub mod cluster_atom;
pub mod coord_atom;
pub mod displace_atom;
pub mod dmhs_phase_atom;
pub mod erotate_sphere;
pub mod erotate_sphere_atom;
pub mod gyration;
pub mod heat_flux;
pub mod ke;
pub mod ke_atom;
pub mod msd;
pub mod msd_chunk;
pub mod nbond_atom;
pub mod pe;
pub mod pe_atom;
pub mod pressure;
pub mod property;
pub mod property_atom;
pub mod pair_local;
pub mod property_local;
pub mod rdf;
pub mod reduce;
pub mod rigid_energy;
pub mod sph_atom;
pub mod stress_atom;
pub mod temp;
pub mod temp_bias;
pub mod temp_com;
pub mod temp_deform;
pub mod temp_partial;
pub mod temp_profile;
pub mod temp_ramp;
pub mod temp_region;
pub mod temp_sphere;
pub mod vacf;

use crate::engine::state::State;
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};

/// Per-atom values of a compute: `cols` values per owned atom (1 for a per-atom vector).
#[derive(Clone, Debug, Default)]
pub struct PerAtom {
    pub cols: usize,
    pub data: Vec<f64>,
}

impl PerAtom {
    #[inline]
    pub fn get(&self, i: usize, col: usize) -> f64 {
        self.data[i * self.cols + col]
    }
}

/// A per-atom value that dumps and compute reduce read: `c_ID`, `c_ID[N]` of a per-atom compute
/// or `f_ID`, `f_ID[N]` of a fix with per-atom output (fix ave/atom).
#[derive(Clone, Debug)]
pub struct PerAtomRef {
    pub fix: bool,
    pub id: String,
    /// Column (0-based); None for a per-atom vector.
    pub col: Option<usize>,
}

/// `c_REST` or `f_REST`: (is a fix, REST); None for other names.
fn split_ref(name: &str) -> Option<(bool, &str)> {
    match (name.strip_prefix("c_"), name.strip_prefix("f_")) {
        (Some(r), _) => Some((false, r)),
        (_, Some(r)) => Some((true, r)),
        _ => None,
    }
}

impl PerAtomRef {
    /// `name` as a per-atom reference; None if it starts with neither `c_` nor `f_`.
    pub fn parse(name: &str, w: &World) -> Option<Result<PerAtomRef, String>> {
        let (fix, rest) = split_ref(name)?;
        Some((|| {
            let (id, col) = match rest.find('[') {
                Some(k) if rest.ends_with(']') => (&rest[..k], Some(rest[k + 1..rest.len() - 1].parse::<usize>().map_err(|_| format!("bad column index in `{name}`"))?)),
                _ => (rest, None),
            };
            let (kind, cols) = if fix {
                let f = w.fix(id).ok_or_else(|| format!("fix `{id}` does not exist"))?;
                ("fix", f.peratom_cols().ok_or_else(|| format!("fix `{id}` does not compute per-atom values"))?)
            } else {
                let c = w.compute(id).ok_or_else(|| format!("compute `{id}` does not exist"))?;
                ("compute", c.peratom_cols().ok_or_else(|| format!("compute `{id}` does not compute per-atom values"))?)
            };
            let p = &name[..2];
            let col = match col {
                None if cols == 1 => None,
                None => return Err(format!("{kind} `{id}` has {cols} per-atom columns: pick one with {p}{id}[N]")),
                Some(n) if n >= 1 && n <= cols => Some(n - 1),
                Some(n) => return Err(format!("column {n} of {kind} `{id}` is out of range 1..{cols}")),
            };
            Ok(PerAtomRef { fix, id: id.to_string(), col })
        })())
    }
    /// The values now (owned atoms, in local order).
    pub fn values(&self, w: &World) -> Result<PerAtom, String> {
        if self.fix {
            w.fix(&self.id).ok_or_else(|| format!("fix `{}` does not exist", self.id))?.peratom(w.state)
        } else {
            w.compute(&self.id).ok_or_else(|| format!("compute `{}` does not exist", self.id))?.peratom(w)
        }
    }
    /// Atom `i`'s value in `p` (from [`PerAtomRef::values`]).
    #[inline]
    pub fn get(&self, p: &PerAtom, i: usize) -> f64 {
        p.get(i, self.col.unwrap_or(0))
    }
}

/// A local value that dump local and compute reduce read: `c_ID`, `c_ID[N]` of a local compute
/// (bond/local) or `f_ID`, `f_ID[N]` of a fix with local data; `[*]` stands for every column.
#[derive(Clone, Debug)]
pub struct LocalRef {
    pub fix: bool,
    pub id: String,
    /// Column (0-based); None for a local vector.
    pub col: Option<usize>,
}

impl LocalRef {
    /// `name` as local references (several for `[*]`); None if it starts with neither `c_` nor
    /// `f_`. `every`: the dump's interval, checked against a fix's (LAMMPS' compatible times).
    pub fn parse(name: &str, w: &World, every: Option<i64>) -> Option<Result<Vec<LocalRef>, String>> {
        let (fix, rest) = split_ref(name)?;
        Some((|| {
            let (id, col) = match rest.find('[') {
                Some(k) if rest.ends_with(']') => (&rest[..k], Some(&rest[k + 1..rest.len() - 1])),
                Some(_) => return Err(format!("Invalid local value `{name}`")),
                None => (rest, None),
            };
            let cols = if fix {
                let f = w.fix(id).ok_or_else(|| format!("Could not find local fix ID `{id}`"))?;
                let (_, cols, freq) = f.local().ok_or_else(|| format!("fix `{id}` does not compute local info"))?;
                if let Some(every) = every.filter(|e| e % freq != 0) {
                    return Err(format!("Dump local and fix not computed at compatible times (dump every {every}, fix `{id}` every {freq})"));
                }
                cols
            } else {
                let c = w.compute(id).ok_or_else(|| format!("Could not find local compute ID `{id}`"))?;
                c.local_cols().ok_or_else(|| format!("compute `{id}` ({}) does not compute local info", c.style()))?
            };
            let kind = if fix { "fix" } else { "compute" };
            let one = |col| LocalRef { fix, id: id.to_string(), col };
            Ok(match col {
                None if cols > 0 => return Err(format!("{kind} `{id}` does not compute a local vector (use {}{id}[N], N in 1..{cols}, or [*])", &name[..2])),
                None => vec![one(None)],
                Some(_) if cols == 0 => return Err(format!("{kind} `{id}` does not compute a local array")),
                Some("*") => (0..cols).map(|c| one(Some(c))).collect(),
                Some(n) => match n.parse::<usize>() {
                    Ok(n) if n >= 1 && n <= cols => vec![one(Some(n - 1))],
                    Ok(n) => return Err(format!("{kind} `{id}` local array is accessed out-of-range: column {n} of 1..{cols}")),
                    Err(_) => return Err(format!("bad column in `{name}`")),
                },
            })
        })())
    }
    /// The rows now; `ev` evaluates a compute's variables.
    pub fn rows(&self, w: &World, ev: Option<&mut dyn dmhs_parser::EvalContext>) -> Result<Vec<Vec<f64>>, String> {
        if self.fix {
            let f = w.fix(&self.id).ok_or_else(|| format!("fix `{}` does not exist", self.id))?;
            Ok(f.local().ok_or_else(|| format!("fix `{}` has no local data", self.id))?.0.to_vec())
        } else {
            w.compute(&self.id).ok_or_else(|| format!("compute `{}` does not exist", self.id))?.local(w, ev)
        }
    }
    /// This reference's value in `row` (from [`LocalRef::rows`]).
    pub fn get(&self, row: &[f64]) -> f64 {
        row[self.col.unwrap_or(0)]
    }
}

pub trait Compute: Send + Sync {
    fn id(&self) -> &str;
    fn style(&self) -> &str;
    fn groupbit(&self) -> u32;
    /// Global scalar.
    fn scalar(&self, _w: &World) -> Result<f64, String> {
        Err(format!("compute {} ({}) does not compute a global scalar", self.id(), self.style()))
    }
    /// Global vector.
    fn vector(&self, _w: &World) -> Result<Vec<f64>, String> {
        Err(format!("compute {} ({}) does not compute a global vector", self.id(), self.style()))
    }
    /// Length of the global vector when it is known before the compute runs (fix ave/time
    /// expands `c_ID[*]` with it).
    fn size_vector(&self) -> Option<usize> {
        None
    }
    /// Global array, row by row (compute rdf); read as columns by fix ave/time `c_ID[j]`.
    fn array(&self, _w: &World) -> Result<Vec<Vec<f64>>, String> {
        Err(format!("compute {} ({}) does not compute a global array", self.id(), self.style()))
    }
    /// Columns of the global array (None: no array).
    fn array_cols(&self) -> Option<usize> {
        None
    }
    /// Whether the global scalar (`index` None) or vector element `index` (1-based) is
    /// extensive: thermo output divides it by the atom count under `thermo_modify norm yes`.
    fn extensive(&self, _index: Option<usize>) -> bool {
        false
    }
    /// Per-atom values (for owned atoms, in local order).
    fn peratom(&self, _w: &World) -> Result<PerAtom, String> {
        Err(format!("compute {} ({}) does not compute per-atom values", self.id(), self.style()))
    }
    /// Columns of per-atom output (None: not per-atom).
    fn peratom_cols(&self) -> Option<usize> {
        None
    }
    /// Local rows (compute bond/local): one row of `local_cols` values per bond (one value for
    /// a local vector), in LAMMPS' order. `ev` evaluates variables (None where there is none:
    /// then values that need one are an error).
    fn local(&self, _w: &World, _ev: Option<&mut dyn dmhs_parser::EvalContext>) -> Result<Vec<Vec<f64>>, String> {
        Err(format!("compute {} ({}) does not compute local values", self.id(), self.style()))
    }
    /// Whether local column `col` (0-based) is a variable's value, which only dump local
    /// evaluates (compute reduce reads local data without variables).
    fn local_needs_variables(&self, _col: usize) -> bool {
        false
    }
    /// Columns of the local array (Some(0): a local vector; None: no local output).
    fn local_cols(&self) -> Option<usize> {
        None
    }
    /// Degrees of freedom (temperature computes only).
    fn dof(&self, _w: &World) -> Option<f64> {
        None
    }
    /// Recompute what LAMMPS computes once per run (a temperature's degrees of freedom); called
    /// before each run and by `velocity`.
    fn setup(&mut self, _w: &World) {}
    /// The warnings LAMMPS prints at the compute's init, when a run starts.
    fn init_warnings(&self, _w: &World) -> Vec<String> {
        Vec::new()
    }
    /// Once per run after the setup's list build, with the atoms wrapped and sorted (LAMMPS'
    /// compute setup comes after Verlet::setup's build; msd/chunk keeps its reference there).
    fn setup_after_build(&mut self, _w: &World) {}
    /// `compute_modify extra/dof` and `dynamic/dof` (only temperatures use them; LAMMPS accepts
    /// them for every compute).
    fn modify_dof(&mut self, _extra: Option<f64>, _dynamic: Option<bool>) {}
    /// For a temperature of translational velocities (compute temp and the bias computes, not
    /// temp/sphere): its group, extra degrees of freedom and bias, so that a thermostat given it
    /// by `fix_modify temp` (or `velocity ... temp ID`) measures and scales as it does. None for
    /// other computes.
    fn temp_spec(&self) -> Option<temp_bias::TempSpec> {
        None
    }
    /// A pressure compute's temperature compute becomes `temp_id` (LAMMPS
    /// `reset_extra_compute_fix`, used by `thermo_modify temp`); false for other computes.
    fn reset_temperature(&mut self, _temp_id: &str) -> bool {
        false
    }
    /// Whether the compute reads per-atom energies or virials (pe/atom, stress/atom): the
    /// force evaluations that tally energies then also tally them per atom.
    fn uses_peratom_tally(&self) -> bool {
        false
    }
    /// The computes and fixes whose values this one reads: (is a fix, ID).
    fn reads(&self) -> Vec<(bool, String)> {
        Vec::new()
    }
    /// A compute chunk/atom (read by fix ave/chunk); None for other computes.
    fn as_chunk(&self) -> Option<&chunk_atom::ComputeChunkAtom> {
        None
    }
    fn describe(&self) -> String {
        format!("compute {} {}", self.id(), self.style())
    }
}

/// What `compute ID group style args...` gives a compute's constructor.
pub struct ComputeDef<'a> {
    pub cmd: &'a Command,
    pub id: String,
    pub groupbit: u32,
    pub style: &'a Word,
    pub args: &'a [Word],
}

type ComputeCtor = fn(ComputeDef, &World) -> DResult<Box<dyn Compute>>;

/// Every compute style this build implements.
const STYLES: &[(&str, ComputeCtor)] = &[
    ("temp", |d, _| Ok(Box::new(temp::ComputeTemp::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("temp/partial", |d, w| Ok(Box::new(temp_partial::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("temp/ramp", |d, w| Ok(Box::new(temp_ramp::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("temp/profile", |d, w| Ok(Box::new(temp_profile::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("temp/com", |d, _| Ok(Box::new(temp_com::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("temp/deform", |d, _| Ok(Box::new(temp_deform::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("temp/region", |d, w| Ok(Box::new(temp_region::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("temp/sphere", |d, w| Ok(Box::new(temp_sphere::ComputeTempSphere::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("ke", |d, _| Ok(Box::new(ke::ComputeKe::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("ke/atom", |d, _| Ok(Box::new(ke_atom::ComputeKeAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("erotate/sphere", |d, w| Ok(Box::new(erotate_sphere::ComputeErotateSphere::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("ke/rigid", |d, _| Ok(Box::new(rigid_energy::ComputeRigidEnergy::from_lammps(d.id, d.groupbit, rigid_energy::Part::Translational, d.args, d.cmd)?))),
    ("erotate/rigid", |d, _| Ok(Box::new(rigid_energy::ComputeRigidEnergy::from_lammps(d.id, d.groupbit, rigid_energy::Part::Rotational, d.args, d.cmd)?))),
    ("nbond/atom", |d, w| Ok(Box::new(nbond_atom::ComputeNBondAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("coord/atom", |d, w| Ok(Box::new(coord_atom::ComputeCoordAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("cluster/atom", |d, w| Ok(Box::new(cluster_atom::ComputeClusterAtom::from_lammps(d.id, d.groupbit, "cluster/atom", d.args, d.cmd, w)?))),
    ("fragment/atom", |d, w| Ok(Box::new(cluster_atom::ComputeClusterAtom::from_lammps(d.id, d.groupbit, "fragment/atom", d.args, d.cmd, w)?))),
    ("aggregate/atom", |d, w| Ok(Box::new(cluster_atom::ComputeClusterAtom::from_lammps(d.id, d.groupbit, "aggregate/atom", d.args, d.cmd, w)?))),
    ("contact/atom", |d, w| Ok(Box::new(contact_atom::ComputeContactAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("erotate/sphere/atom", |d, w| Ok(Box::new(erotate_sphere_atom::ComputeErotateSphereAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("pe", |d, _| Ok(Box::new(pe::ComputePe::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("pe/atom", |d, _| Ok(Box::new(pe_atom::ComputePeAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("stress/atom", |d, w| Ok(Box::new(stress_atom::ComputeStressAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("centro/atom", |d, _| Ok(Box::new(centro_atom::ComputeCentroAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("heat/flux", |d, w| Ok(Box::new(heat_flux::ComputeHeatFlux::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("pressure", |d, w| Ok(Box::new(pressure::ComputePressure::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("vacf", |d, w| Ok(Box::new(vacf::ComputeVacf::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("msd", |d, w| Ok(Box::new(msd::ComputeMsd::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("msd/chunk", |d, w| Ok(Box::new(msd_chunk::ComputeMsdChunk::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("displace/atom", |d, w| Ok(Box::new(displace_atom::ComputeDisplaceAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("rdf", |d, w| Ok(Box::new(rdf::ComputeRdf::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("bond/local", |d, w| Ok(Box::new(bond_local::ComputeBondLocal::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("property/local", |d, w| Ok(Box::new(property_local::ComputePropertyLocal::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("pair/local", |d, w| Ok(Box::new(pair_local::ComputePairLocal::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("chunk/atom", |d, w| Ok(Box::new(chunk_atom::ComputeChunkAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("gyration", |d, _| Ok(Box::new(gyration::ComputeGyration::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("com", |d, _| Ok(Box::new(com::ComputeCom::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("property/atom", |d, w| Ok(Box::new(property_atom::ComputePropertyAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("reduce", |d, w| Ok(Box::new(reduce::ComputeReduce::from_lammps(d.id, d.groupbit, d.args, d.cmd, w)?))),
    ("sph/rho/atom", |d, w| Ok(Box::new(sph_atom::ComputeSphAtom::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, w)?))),
    ("sph/e/atom", |d, w| Ok(Box::new(sph_atom::ComputeSphAtom::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, w)?))),
    ("sph/t/atom", |d, w| Ok(Box::new(sph_atom::ComputeSphAtom::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, w)?))),
    ("dmhs/phase/atom", |d, w| Ok(Box::new(dmhs_phase_atom::ComputeDmhsPhaseAtom::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, w)?))),
];

/// A compute that reads the pair style's neighbour list (through [`group_pairs`]) can be read
/// only when the lists are built: during or after a run.
pub fn need_lists(s: &State, c: &dyn Compute) -> Result<(), String> {
    match s.lists_valid {
        true => Ok(()),
        false => Err(format!("compute {} {} needs neighbour lists: it can be read only during or after a run", c.style(), c.id())),
    }
}

/// Each pair of the pair style's neighbour list between an atom of group `gi` and one of group
/// `gj`, special pairs of weight 0 left out (as LAMMPS' lists leave them out): `visit(i, j,
/// rsq, count_i, count_j, level)` (level: the pair's special level), where `count_i` says owned atom i is in `gi` and j in `gj`, and
/// `count_j` the same the other way round for an owned j. A pair of owned atoms is listed
/// once; a pair with a ghost is listed by each owned end, which counts for itself.
pub fn group_pairs(s: &State, gi: u32, gj: u32, mut visit: impl FnMut(usize, usize, f64, bool, bool, usize)) {
    use crate::engine::neighbor::{special_level, NEIGH_MASK};
    let at = &s.atoms;
    let (lj, coul) = (s.special_bonds.lj, s.special_bonds.coul);
    for chunk in &s.neighbor.list.chunks {
        for i in chunk.start..chunk.end {
            let (mi, xi) = (at.mask[i], at.x[i]);
            if mi & (gi | gj) == 0 {
                continue;
            }
            for &e in chunk.neighbors(i) {
                let level = special_level(e);
                if lj[level] == 0.0 && coul[level] == 0.0 {
                    continue;
                }
                let j = (e & NEIGH_MASK) as usize;
                let mj = at.mask[j];
                let count_i = mi & gi != 0 && mj & gj != 0;
                let count_j = j < at.nlocal && mj & gi != 0 && mi & gj != 0;
                if count_i || count_j {
                    let (dx, dy, dz) = (xi[0] - at.x[j][0], xi[1] - at.x[j][1], xi[2] - at.x[j][2]);
                    visit(i, j, dx * dx + dy * dy + dz * dz, count_i, count_j, level);
                }
            }
        }
    }
}

/// Each pair of group atoms in the pair style's neighbour list once (compute property/local and
/// pair/local): `visit(i, j, rsq, level)` with the pair's special level. A pair of owned atoms
/// as listed; a pair with a ghost from the atom LAMMPS' binning lists it from (its partner's
/// ghost then carries the ghost's values, as in LAMMPS), or where the sides are not known (on
/// several ranks) from the lower atom ID, an atom with its own image from the side the image
/// lies above (in z, then y, then x).
pub fn group_pairs_once(s: &State, groupbit: u32, mut visit: impl FnMut(usize, usize, f64, usize)) {
    let at = &s.atoms;
    group_pairs(s, groupbit, groupbit, |i, j, rsq, both, _, level| {
        if !both {
            return;
        }
        if j >= at.nlocal {
            let keep = match s.lammps_order.sides() {
                Some(sides) => sides.first(i, j, &at.x),
                None => {
                    let (xi, xj) = (at.x[i], at.x[j]);
                    let above = (xj[2], xj[1], xj[0]) > (xi[2], xi[1], xi[0]);
                    if at.tag[i] == at.tag[j] { above } else { at.tag[i] < at.tag[j] }
                }
            };
            if !keep {
                return;
            }
        }
        visit(i, j, rsq, level);
    });
}

/// Build a compute from `compute ID group style args...`.
pub fn new_compute(cmd: &Command, id: &Word, groupbit: u32, style: &Word, args: &[Word], w: &World) -> DResult<Box<dyn Compute>> {
    match STYLES.iter().find(|(n, _)| *n == style.text) {
        Some((_, ctor)) => ctor(ComputeDef { cmd, id: id.text.clone(), groupbit, style, args }, w),
        None => Err(crate::models::styles::unsupported_style("compute", style, &style.text, &supported())),
    }
}

/// Names of the compute styles this build implements.
pub fn supported() -> Vec<&'static str> {
    STYLES.iter().map(|(n, _)| *n).collect()
}

/// The computes LAMMPS creates for thermo output: thermo_temp, thermo_press, thermo_pe.
pub fn default_computes() -> Vec<Box<dyn Compute>> {
    vec![
        Box::new(temp::ComputeTemp::new("thermo_temp".into(), 1)),
        Box::new(pressure::ComputePressure::new("thermo_press".into(), "thermo_temp".into())),
        Box::new(pe::ComputePe::new("thermo_pe".into())),
    ]
}

/// Group functions of expressions: count(g[,region]), mass(g[,region]), xcm(g,dim), vcm(g,dim), fcm(g,dim),
/// bound(g,xmin|xmax|...), ke(g), gyration(g), angmom(g,dim), torque(g,dim), inertia(g,dimdim),
/// omega(g,dim) (the last four about the centre of mass of the unwrapped positions, in LAMMPS'
/// atom order, summed over the ranks). `None` if `name` is not a group function.
pub fn group_function(state: &State, name: &str, args: &[String]) -> Option<Result<f64, String>> {
    let known = ["count", "mass", "charge", "xcm", "vcm", "fcm", "bound", "ke", "gyration", "angmom", "torque", "inertia", "omega"];
    if !known.contains(&name) {
        return None;
    }
    Some((|| {
        let g = args.first().ok_or_else(|| format!("{name}() needs a group ID"))?;
        let bit = state.group_bit(g)?;
        let a = &state.atoms;
        // LAMMPS' optional last argument of count() and mass(): only atoms in a region
        let region = match (name, args.get(1)) {
            ("count" | "mass", Some(r)) => Some(state.regions.iter().find(|reg| &reg.id == r).ok_or_else(|| format!("{name}(): region `{r}` does not exist"))?),
            _ => None,
        };
        let members = (0..a.nlocal).filter(|&i| a.mask[i] & bit != 0);
        // a sum over this rank's atoms, summed over the ranks of a distributed run
        let summed = |x: f64| {
            let mut v = [x];
            state.sum_ranks(&mut v);
            v[0]
        };
        let dim_of = |k: usize| -> Result<usize, String> {
            match args.get(k).map(|s| s.as_str()) {
                Some("x") => Ok(0),
                Some("y") => Ok(1),
                Some("z") => Ok(2),
                _ => Err(format!("{name}() needs a dimension x, y or z")),
            }
        };
        Ok(match name {
            "count" => match region {
                Some(r) => summed(members.filter(|&i| r.matches(a.x[i])).count() as f64),
                None => state.group_count(bit) as f64,
            },
            "mass" => summed(members.filter(|&i| region.is_none_or(|r| r.matches(a.x[i]))).map(|i| state.mass(i)).sum()),
            "charge" => {
                if !a.features.charge {
                    return Err("charge() needs an atom style with charges".into());
                }
                summed(members.map(|i| a.q[i]).sum())
            }
            "xcm" => state.group_xcm(bit).0[dim_of(1)?],
            "vcm" => state.group_vcm(bit)[dim_of(1)?],
            "fcm" => {
                let d = dim_of(1)?;
                summed(members.map(|i| a.f[i][d]).sum())
            }
            "ke" => state.kinetic_energy(bit),
            "angmom" | "omega" | "inertia" | "torque" => {
                let Some(r) = crate::engine::group_rotation::of_group(state, bit) else { return Ok(0.0) };
                match name {
                    "angmom" => r.angmom[dim_of(1)?],
                    "omega" => r.omega()?[dim_of(1)?],
                    "inertia" => {
                        let pair = args.get(1).map(|s| s.as_str()).unwrap_or("");
                        let (p, q) = match pair {
                            "xx" => (0, 0),
                            "yy" => (1, 1),
                            "zz" => (2, 2),
                            "xy" => (0, 1),
                            "yz" => (1, 2),
                            "xz" => (0, 2),
                            _ => return Err("inertia() needs xx, yy, zz, xy, yz or xz".into()),
                        };
                        r.inertia[p][q]
                    }
                    _ => {
                        // LAMMPS' Group::torque: the sum of r x f about the centre of mass
                        let d = dim_of(1)?;
                        let dom = state.domain()?;
                        let mut t = [0.0; 3];
                        for &i in state.lammps_order.indices(a.nlocal).iter().filter(|&&i| a.mask[i] & bit != 0) {
                            let u = dom.unmap(a.x[i], a.image[i]);
                            let (dx, dy, dz) = (u[0] - r.cm[0], u[1] - r.cm[1], u[2] - r.cm[2]);
                            let f = a.f[i];
                            t[0] += dy * f[2] - dz * f[1];
                            t[1] += dz * f[0] - dx * f[2];
                            t[2] += dx * f[1] - dy * f[0];
                        }
                        state.sum_ranks(&mut t);
                        t[d]
                    }
                }
            }
            "gyration" => gyration::radius(state, bit)?,
            "bound" => {
                let which = args.get(1).map(|s| s.as_str()).unwrap_or("");
                let (d, max) = match which {
                    "xmin" => (0, false),
                    "xmax" => (0, true),
                    "ymin" => (1, false),
                    "ymax" => (1, true),
                    "zmin" => (2, false),
                    "zmax" => (2, true),
                    _ => return Err("bound() needs xmin, xmax, ymin, ymax, zmin or zmax".into()),
                };
                let vals = members.map(|i| a.x[i][d]);
                let mut b = [if max { vals.fold(f64::NEG_INFINITY, f64::max) } else { vals.fold(f64::INFINITY, f64::min) }];
                if max { state.max_ranks(&mut b) } else { state.min_ranks(&mut b) }
                b[0]
            }
            _ => unreachable!(),
        })
    })())
}

/// `x[ID]`-style references in expressions.
pub fn atom_value(state: &State, keyword: &str, id: i64) -> Option<Result<f64, String>> {
    let field = property::Field::parse(keyword)?;
    Some((|| {
        field.check(state)?;
        by_atom_id(state, id, |i| field.value(state, i))
    })())
}

/// Atom `id`'s `value(i)` (i its owned index), as LAMMPS' peratom2global reads `x[ID]`,
/// `C_ID[ID]` and `v_name[ID]`: an ID beyond the largest is an error, an ID no atom has reads
/// 0, and on several ranks the owner's value is summed over the ranks.
pub fn by_atom_id(state: &State, id: i64, value: impl Fn(usize) -> f64) -> Result<f64, String> {
    let n = state.atoms.nlocal;
    let mut max = [state.atoms.tag[..n].iter().copied().max().unwrap_or(0) as f64];
    state.max_ranks(&mut max);
    if id as f64 > max[0] {
        return Err(format!("Variable atom ID is out of range: atom ID {id}, the largest is {}", max[0]));
    }
    let mut v = [(0..n).find(|&i| state.atoms.tag[i] == id).map_or(0.0, value)];
    state.sum_ranks(&mut v);
    Ok(v[0])
}

/// Parse `compute ID group style` with no further arguments.
pub fn expect_no_args(args: &[Word], cmd: &Command, syntax: &str) -> DResult<()> {
    dmhs_parser::Args::from_words(args, cmd.span, syntax).finish()
}
