//! `fix ID group rigid|rigid/nve|rigid/nvt|rigid/npt|rigid/nph bodystyle ...` (LAMMPS'
//! FixRigid family, 22 Jul 2025): one set of bodies, fixed when the fix is defined:
//!
//! * `single`: the whole group is one body;
//! * `molecule`: one body per molecule ID of the group, numbered by increasing ID;
//! * `group N g1 ... gN`: one body per listed group (atoms of the fix group in it), in the
//!   listed order; an atom in two of them is an error;
//! * `custom i_name|v_name`: as molecule, with the IDs an integer per atom from fix
//!   property/atom or an atom-style variable (evaluated when the fix is defined), truncated and
//!   shifted so that the group's least is 1.
//!
//! The bodies move as rigid/small's (rigid_small.rs, with the same step and thermostats); what
//! differs, as in LAMMPS: the bodies are set up at the run's init (before the atoms are wrapped
//! and sorted, summing in their order then), `force M x y z` and `torque M x y z` switch
//! components of bodies M (a range) off, `reinit no` keeps the first run's bodies, `infile`
//! gives bodies from a file, and the fix's scalar is the bodies' temperature over their
//! unconstrained degrees of freedom. Atoms created after the fix belong to no body.

use dmhs_parser::{Args, DResult, Word};
use std::collections::{BTreeMap, HashMap};

use crate::engine::state::State;

/// The bodies of a `fix rigid` and its per-body switches.
#[derive(Clone, Debug)]
pub struct Global {
    /// The body of each atom, by atom ID (LAMMPS' body[i], set when the fix is defined).
    pub body_of: HashMap<i64, usize>,
    pub nbody: usize,
    /// Per body: force components on (1.0) or off (0.0), LAMMPS' fflag.
    pub fflag: Vec<[f64; 3]>,
    /// Per body: torque components on or off, LAMMPS' tflag.
    pub tflag: Vec<[f64; 3]>,
    /// `molecule`: each molecule ID's body (the IDs of a body file are molecule IDs).
    pub mol_to_body: Option<HashMap<i64, usize>>,
}

/// One body of a fix rigid `infile`.
#[derive(Clone, Debug)]
pub struct FileBody {
    pub mass: f64,
    pub xcm: [f64; 3],
    /// The inertia tensor about the centre, Voigt order xx yy zz yz xz xy.
    pub itensor: [f64; 6],
    pub vcm: [f64; 3],
    pub angmom: [f64; 3],
    pub image: [i32; 3],
}

/// The bodies an `infile` sets: by body index (fix rigid) or by molecule ID (rigid/small).
#[derive(Clone, Debug, Default)]
pub struct Infile {
    pub bodies: BTreeMap<usize, FileBody>,
}

impl Global {
    /// The body style and its bodies (`single`, `molecule`, `group N g1 ... gN`), with
    /// LAMMPS' checks; every body needs two atoms or more.
    pub fn parse(a: &mut Args, style: &str, groupbit: u32, state: &State, atom_values: Option<&[f64]>) -> DResult<Global> {
        let kind = a.word("body style (single, molecule, custom or group)")?;
        let atoms = &state.atoms;
        let owned = 0..atoms.nlocal;
        let in_fix = |i: usize| atoms.mask[i] & groupbit != 0;
        let mut body_of = HashMap::new();
        let mut mol_to_body = None;
        let nbody = match kind.text.as_str() {
            "single" => {
                for i in owned.filter(|&i| in_fix(i)) {
                    body_of.insert(atoms.tag[i], 0);
                }
                1
            }
            "molecule" | "custom" => {
                // custom: an integer per atom (i_name of fix property/atom, or an atom-style
                // variable truncated), shifted so that the group's least is 1, as molecule IDs
                let ids: Vec<i64> = if kind.text == "molecule" {
                    if !atoms.features.molecule {
                        return Err(a.error_at(kind, format!("fix {style} molecule requires atom attribute molecule"), "no molecule IDs").with_help("use an atom style with molecule IDs (bond, molecular, full, or hybrid sphere molecular)"));
                    }
                    atoms.molecule[..atoms.nlocal].to_vec()
                } else {
                    custom_ids(a, style, state, groupbit, atom_values)?
                };
                let mut mols: Vec<i64> = owned.clone().filter(|&i| in_fix(i)).map(|i| ids[i]).collect();
                mols.sort_unstable();
                mols.dedup();
                let index: HashMap<i64, usize> = mols.iter().enumerate().map(|(k, &m)| (m, k)).collect();
                for i in owned.filter(|&i| in_fix(i)) {
                    body_of.insert(atoms.tag[i], index[&ids[i]]);
                }
                mol_to_body = Some(index);
                mols.len()
            }
            "group" => {
                let n = a.usize_min("number of bodies N", 1)?;
                let mut bits = Vec::with_capacity(n);
                for _ in 0..n {
                    let g = a.word("group ID of a body")?;
                    let bit = state.groups.bit(&g.text).ok_or_else(|| a.error_at(g, format!("could not find fix {style} group ID `{}`", g.text), "unknown group"))?;
                    bits.push(bit);
                }
                for i in owned.filter(|&i| in_fix(i)) {
                    let mut inside = bits.iter().enumerate().filter(|(_, &b)| atoms.mask[i] & b != 0);
                    if let Some((k, _)) = inside.next() {
                        if inside.next().is_some() {
                            return Err(a.error_at(kind, format!("one or more atoms belong to multiple rigid bodies (atom {})", atoms.tag[i]), "groups overlap"));
                        }
                        body_of.insert(atoms.tag[i], k);
                    }
                }
                n
            }
            _ => return Err(a.error_at(kind, format!("illegal fix {style} body style `{}`", kind.text), "expected single, molecule, custom or group")),
        };
        if nbody == 0 {
            return Err(a.error_at(kind, "no rigid bodies defined", "the fix group has no atoms"));
        }
        let mut count = vec![0usize; nbody];
        for &b in body_of.values() {
            count[b] += 1;
        }
        if count.iter().any(|&c| c <= 1) {
            return Err(a.error_at(kind, "one or zero atoms in rigid body", "every body needs 2 atoms or more"));
        }
        let (fflag, tflag) = if state.dimension == 2 { ([1.0, 1.0, 0.0], [0.0, 0.0, 1.0]) } else { ([1.0; 3], [1.0; 3]) };
        Ok(Global { body_of, nbody, fflag: vec![fflag; nbody], tflag: vec![tflag; nbody], mol_to_body })
    }

    /// `force M xflag yflag zflag` or `torque M ...` (`w` the keyword): components of the bodies
    /// in range M switched on or off.
    pub fn parse_flags(&mut self, a: &mut Args, w: &Word, style: &str, dimension: usize) -> DResult<()> {
        let (lo, hi) = a.type_range("body range M (n, *, *n, n*, m*n)", self.nbody)?;
        let mut on = [0.0; 3];
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            on[k] = if a.on_off(&format!("{axis} flag (on or off)"))? { 1.0 } else { 0.0 };
        }
        let force = w.text == "force";
        if dimension == 2 && force && on[2] == 1.0 {
            return Err(a.error_at(w, format!("fix {style} z force cannot be on for 2d simulation"), "z off in 2d"));
        }
        if dimension == 2 && !force && (on[0] == 1.0 || on[1] == 1.0) {
            return Err(a.error_at(w, format!("fix {style} xy torque cannot be on for 2d simulation"), "x and y off in 2d"));
        }
        let flags = if force { &mut self.fflag } else { &mut self.tflag };
        for f in &mut flags[lo - 1..hi] {
            *f = on;
        }
        Ok(())
    }

    /// The bodies' degrees of freedom for the fix's temperature (LAMMPS' init: 6 per body
    /// less the switched-off components, one less per linear body).
    pub fn ndof(&self, nlinear: usize) -> f64 {
        let sum: f64 = self.fflag.iter().chain(&self.tflag).map(|f| f[0] + f[1] + f[2]).sum();
        sum - nlinear as f64
    }

    /// The body index of a fix rigid infile's ID (the molecule ID for `molecule`, else the
    /// body number).
    pub fn file_body(&self, id: i64) -> Result<usize, String> {
        let body = match &self.mol_to_body {
            Some(m) => m.get(&id).copied(),
            None => usize::try_from(id - 1).ok().filter(|&b| b < self.nbody),
        };
        body.ok_or_else(|| format!("invalid rigid body ID {id} in fix rigid infile"))
    }
}

/// The body IDs of the `custom i_name|v_name` body style, one per owned atom: the integer
/// property of fix property/atom, or the atom-style variable evaluated when the fix is defined
/// (`atom_values`) truncated, shifted so that the fix group's least is 1 (LAMMPS' fix rigid
/// and rigid/small).
pub fn custom_ids(a: &mut Args, style: &str, state: &State, groupbit: u32, atom_values: Option<&[f64]>) -> DResult<Vec<i64>> {
    let atoms = &state.atoms;
    let w = a.word("custom property (i_name or v_name)")?;
    let raw: Vec<f64> = if let Some(name) = w.text.strip_prefix("i_") {
        let k = atoms.find_extra(&w.text).ok_or_else(|| a.error_at(w, format!("fix {style} custom requires previously defined property/atom `{name}`"), "no such property"))?;
        atoms.extra[k].data[..atoms.nlocal].to_vec()
    } else if w.text.starts_with("v_") {
        atom_values.ok_or_else(|| a.error_at(w, "the atom-style variable was not evaluated", "internal"))?.to_vec()
    } else {
        return Err(a.error_at(w, format!("unsupported fix {style} custom property `{}`", w.text), "expected i_name or v_name"));
    };
    let int: Vec<i64> = raw.iter().map(|&v| v as i32 as i64).collect();
    let min = (0..atoms.nlocal).filter(|&i| atoms.mask[i] & groupbit != 0).map(|i| int[i]).min().unwrap_or(0);
    Ok(int.iter().map(|&v| v - min + 1).collect())
}

/// LAMMPS' readfile: the first line that is not blank or a comment gives the number of bodies
/// N, then N lines of `ID mass xcm ycm zcm ixx iyy izz ixy ixz iyz vxcm vycm vzcm lx ly lz ixcm
/// iycm izcm`; `key` turns an ID into the body's key in the result (or says why it is invalid).
pub fn read_infile(path: &std::path::Path, style: &str, key: impl Fn(i64) -> Result<usize, String>) -> Result<Infile, String> {
    let name = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot open fix {style} infile {name}: {e}"))?;
    let mut lines = text.lines().enumerate();
    let (n, count_line) = loop {
        let Some((k, l)) = lines.next() else { return Err(format!("{name}: unexpected end of fix {style} infile (no body count)")) };
        let t = l.trim();
        if !t.is_empty() && !t.starts_with('#') {
            let n: usize = t.parse().map_err(|_| format!("{name}:{}: fix {style} infile has incorrect format: expected the number of bodies, found `{t}`", k + 1))?;
            break (n, k + 1);
        }
    };
    let mut out = Infile::default();
    for _ in 0..n {
        let Some((k, l)) = lines.next() else { return Err(format!("{name}: unexpected end of fix {style} infile: {n} bodies announced at line {count_line}")) };
        let at = k + 1;
        let words: Vec<&str> = l.split('#').next().unwrap_or("").split_whitespace().collect();
        if words.len() != 20 {
            return Err(format!("{name}:{at}: incorrect rigid body format in fix {style} infile: expected 20 values (ID mass xcm ycm zcm ixx iyy izz ixy ixz iyz vxcm vycm vzcm lx ly lz ixcm iycm izcm), found {}", words.len()));
        }
        let int = |w: &str| w.parse::<i64>().map_err(|_| format!("{name}:{at}: expected an integer, found `{w}`"));
        let mut v = [0.0f64; 20];
        for (j, w) in words.iter().enumerate().skip(1).take(16) {
            v[j] = w.parse::<f64>().map_err(|_| format!("{name}:{at}: expected a number, found `{w}`"))?;
        }
        let body = key(int(words[0])?).map_err(|e| format!("{name}:{at}: {e}"))?;
        let image = [int(words[17])? as i32, int(words[18])? as i32, int(words[19])? as i32];
        out.bodies.insert(body, FileBody { mass: v[1], xcm: [v[2], v[3], v[4]], itensor: [v[5], v[6], v[7], v[10], v[9], v[8]], vcm: [v[11], v[12], v[13]], angmom: [v[14], v[15], v[16]], image });
    }
    Ok(out)
}
