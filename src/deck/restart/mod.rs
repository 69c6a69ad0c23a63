//! `write_restart FILE` and `read_restart FILE`: everything a continued run needs, so that
//! `read_restart` followed by the same commands continues bit for bit where `write_restart`
//! left off (contact histories included, which LAMMPS' data files cannot carry).
//!
//! # The file: format "dmhs restart", version 2
//!
//! A JSON document written and read with serde ([`schema`] holds the types). Numbers are
//! written in their shortest round-trip form and parsed exactly (serde_json's
//! `float_roundtrip`), so every double comes back bit for bit, -0.0 and subnormals included.
//! JSON has no NaN or infinity: write_restart refuses a state holding one. Members:
//! * `format`: "dmhs restart"; `version`: 2;
//! * `settings`: `units`, `dimension`, `boundary` (one word per dimension, as in the command),
//!   `atom_style` (the words of the command), `newton_pair`, `newton_bond`, `comm_vel`
//!   (`comm_modify vel`), `dt`, `dt_set` (given by `timestep`), `step` and `time_origin`
//!   {`step`, `time`} (time = time_origin.time + (step - time_origin.step) dt, as LAMMPS);
//! * `box`: `current` and `initial` (the box as created, for shrink-wrapping; null if none),
//!   each {`lo`, `hi`};
//! * `types`: `atom_types` and `masses` (one per type; null where none was set);
//! * `groups`: the group names by their bit in the atom masks (null for a free bit; `all` first);
//! * `atoms`: `count`, then one array per per-atom quantity in the current storage order (the
//!   order decides how forces are summed, so it is kept): `id`, `type`, `mask`, `x`, `v`,
//!   `image`, and as the atom style has them `molecule`, `q`, `radius`, `rmass`, `omega`
//!   (sphere), `rho`, `drho`, `esph`, `desph`, `cv`, `vest` (sph); `fix_arrays`: the per-atom
//!   arrays of fixes ({`name`, `stride`, `ghosts`, `values`: `stride` numbers per atom}, e.g. the
//!   wall spring of fix wall/gran), restored to a fix defined again with the same ID (and kept
//!   over what the replayed force field sets, e.g. x/ref of a BPM style's store/local);
//!   `lammps_order` {`ids`, `sortfreq`, `binsize`, `first`}: LAMMPS' local order of the atoms
//!   and its `atom_modify sort` and `first` (sums and random numbers over atoms follow it);
//! * `topology`: `bond_types`, `angle_types`, `dihedral_types`, `improper_types`; `bonds`
//!   [type, id, id], `angles` [type, 3 ids], `dihedrals` [type, 4 ids]; with a BPM bond style
//!   `bond_history` (per bond its reference state, LAMMPS' fix bond/history) and
//!   `bond_history_stored` (its stored_flag); `bond_slots` (per bond its place in each atom's
//!   bond list, which broken bonds reorder as LAMMPS does);
//! * `force_field`: the force-field commands (pair_style, pair_coeff, pair_modify,
//!   bond/angle/dihedral styles and coefficients, special_bonds) as words, in the order given;
//!   read_restart replays them;
//! * `contact_histories`: per history store of the pair style, {`size`, `contacts`: [owner ID,
//!   partner ID, [image difference], [`size` values]]} (the key of `engine::contact_history`);
//! * `fixes`: [{`id`, `style`, `values`}], the global state of fixes as LAMMPS' write_restart
//!   of the style stores it (fix nvt: 1, chain length, eta, eta_dot, 0; temp/berendsen and
//!   temp/rescale: the energy), given to a fix of the same ID and style defined after
//!   read_restart and dropped at the next run if none is (LAMMPS' Modify). fix langevin
//!   stores nothing, as in LAMMPS (its generator is seeded again when it is defined).
//!
//! The layout (layout.rs) puts one atom's triple, one bond, one contact per line. read_restart
//! checks every field as read_data checks a data file (types in range, IDs positive, unique and
//! at most 2^31-1, masses and radii, finite numbers, array lengths, bonds naming existing atoms,
//! ...) and reports the first error by its place in the file and its atom ID; write_restart
//! applies the same checks first, so whatever it writes can be read. The file is written to a
//! temporary file in the same folder and renamed. Files of the text format of dmhs before
//! version 2 ("DMHS restart 1") and LAMMPS binary restarts are recognised and refused with a
//! message saying what to do.
//!
//! As with LAMMPS, fixes (but for their stored state), computes, outputs, variables, regions and the neighbour settings
//! (`neighbor`, `neigh_modify`) are not stored: the continuing deck defines them again.
//! A continuation is bit-identical when it does so with the same values and runs with
//! `pre yes` (the default), like the `run` that would have followed `write_restart`.

mod layout;
mod locate;
pub mod schema;

use crate::engine::atoms::{Atoms, ExtraArray};
use crate::engine::contact_history::ContactRecord;
use crate::engine::domain::Domain;
use crate::engine::groups::Groups;
use crate::engine::topology::{Angle, Bond, Dihedral, Topology};
use crate::engine::units::Units;
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Span, Word};
use schema::*;
use serde::Serialize;
use std::collections::HashSet;

pub const WRITE_SYNTAX: &str = "write_restart file  (a * in the name becomes the current step)";
pub const READ_SYNTAX: &str = "read_restart file";

/// First line of the text format of dmhs before restart version 2.
const OLD_MAGIC: &[u8] = b"DMHS restart 1";
/// LAMMPS writes this near the start of its binary restart files.
const LAMMPS_MAGIC: &[u8] = b"LammpS RestartT";
const LAMMPS_BINARY: &str = "dmhs does not read LAMMPS binary restart files; convert it with LAMMPS (`lmp -restart2data FILE data.file`, or read_restart then write_data) and use read_data";

/// A type as a restart file stores it: negative when turned off by delete_bonds.
fn signed_type(typ: usize, off: bool) -> i64 {
    if off { -(typ as i64) } else { typ as i64 }
}

/// `write_restart file`: written to a temporary name, then renamed (no half-written files).
pub fn write_restart(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, WRITE_SYNTAX);
    let w = a.word("file name")?;
    let mut init = true;
    while let Some(k) = a.peek() {
        a.skip(1);
        match k.text.as_str() {
            "fileper" | "nfile" => return Err(a.error_at(k, format!("write_restart {} is for MPI runs (dmhs writes one file)", k.text), "not supported")),
            "noinit" => init = false,
            _ => return Err(a.unknown_keyword(k, &["noinit"])),
        }
    }
    // LAMMPS' set-up before the file (skipped by noinit): atoms into the box, shrink-wrapped faces
    if init && !sim.state.check_only {
        sim.state.settle_into_box();
    }
    let name = w.text.replace('*', &sim.state.step.to_string());
    let path = sim.path(&name);
    let bytes = restart_json(sim).map_err(|e| Diagnostic::at(cmd.span, format!("cannot write restart file `{}`: {e}", path.display()), "here"))?;
    // `dmhs check` writes no file (the state is checked as read_restart would check it)
    if sim.state.check_only {
        return Ok(());
    }
    crate::output::log::write_atomic(&path, &bytes).map_err(|e| a.error_at(w, format!("cannot write restart file `{}`: {e}", path.display()), "cannot write"))?;
    Ok(())
}

/// The restart file of the current state, checked as read_restart checks it.
fn restart_json(sim: &mut Simulation) -> Result<Vec<u8>, String> {
    let r = snapshot(sim)?;
    r.check()?;
    let mut out = Vec::new();
    r.serialize(&mut serde_json::Serializer::with_formatter(&mut out, layout::Layout::default())).map_err(|e| e.to_string())?;
    out.push(b'\n');
    Ok(out)
}

/// The owned atoms' values of an array the atom style has (None if it has not).
fn rows<T: Clone>(on: bool, v: &[T], n: usize) -> Option<Vec<T>> {
    on.then(|| v[..n].to_vec())
}

/// The state as a restart file (owned atoms only: ghosts are rebuilt).
fn snapshot(sim: &mut Simulation) -> Result<Restart, String> {
    let st = &sim.state;
    let domain = st.domain.as_ref().ok_or("write_restart before the simulation box is defined")?;
    let bounds = |d: &Domain| Bounds { lo: d.lo, hi: d.hi, tilt: d.tilt };
    let a = &st.atoms;
    let n = a.nlocal;
    let ft = a.features;
    let ids: HashSet<i64> = a.tag[..n].iter().copied().collect();
    let contact_histories = match sim.pair.as_mut() {
        Some(p) => p
            .histories()
            .into_iter()
            .map(|h| History {
                size: h.size(),
                // the list is from the last rebuild: contacts of atoms deleted since can never apply
                contacts: h.records().into_iter().filter(|r| ids.contains(&r.owner) && ids.contains(&r.partner)).map(|r| Contact(r.owner, r.partner, r.image, r.values)).collect(),
            })
            .collect(),
        None => Vec::new(),
    };
    let t = &st.topo;
    let bpm = sim.bond_style.as_ref().and_then(|b| b.as_bpm()).map(|b| b.shared().is_stored());
    let any_slot = t.bonds.iter().any(|b| b.slots != [u32::MAX; 2]);
    let any_history = t.bonds.iter().any(|b| b.history.iter().any(|&h| h != 0.0));
    // LAMMPS' order as of now: atoms gone or added since the last rebuild accounted for
    let mut order = st.lammps_order.clone();
    order.before_rebuild(a);
    Ok(Restart {
        format: FORMAT.to_string(),
        version: VERSION,
        settings: Settings {
            units: st.units.name().to_string(),
            dimension: st.dimension as u32,
            boundary: st.boundary.map(|b| boundary_word(&b)),
            atom_style: st.atom_style.clone(),
            newton_pair: st.newton_pair,
            newton_bond: st.newton_bond,
            comm_vel: st.comm_vel,
            dt: st.dt,
            dt_set: st.dt_set,
            step: st.step,
            time_origin: TimeOrigin { step: st.atimestep, time: st.atime },
        },
        bounds: BoxSection { current: bounds(domain), initial: st.box_initial.as_ref().map(bounds) },
        types: Types { atom_types: st.ntypes, masses: (1..=st.ntypes).map(|t| st.mass_set[t].then_some(st.type_mass[t])).collect() },
        groups: {
            let mut g = Vec::new();
            for (k, name) in st.groups.names() {
                g.resize(k + 1, None);
                g[k] = Some(name.to_string());
            }
            g
        },
        atoms: AtomSection {
            count: n,
            id: a.tag[..n].to_vec(),
            typ: a.typ[..n].iter().map(|&t| t as i64).collect(),
            mask: a.mask[..n].to_vec(),
            x: a.x[..n].to_vec(),
            v: a.v[..n].to_vec(),
            image: a.image[..n].to_vec(),
            molecule: rows(ft.molecule, &a.molecule, n),
            q: rows(ft.charge, &a.q, n),
            radius: rows(ft.sphere, &a.radius, n),
            rmass: rows(ft.sphere, &a.rmass, n),
            omega: rows(ft.sphere, &a.omega, n),
            quat: rows(ft.quat, &a.quat, n),
            rho: rows(ft.sph, &a.rho, n),
            drho: rows(ft.sph, &a.drho, n),
            esph: rows(ft.sph, &a.esph, n),
            desph: rows(ft.sph, &a.desph, n),
            cv: rows(ft.sph, &a.cv, n),
            vest: rows(ft.sph, &a.vest, n),
            fix_arrays: a.extra.iter().map(|e| FixArray { name: e.name.clone(), stride: e.stride, ghosts: e.ghosts, values: e.data[..n * e.stride].chunks(e.stride).map(<[f64]>::to_vec).collect() }).collect(),
            lammps_order: Some(OrderSection { ids: order.ids().to_vec(), sortfreq: order.sortfreq, binsize: order.binsize, first: order.first.clone() }),
        },
        topology: TopologySection {
            bond_types: t.nbondtypes,
            angle_types: t.nangletypes,
            dihedral_types: t.ndihedraltypes,
            improper_types: t.nimpropertypes,
            // a turned-off interaction has its type negated, as LAMMPS stores it
            bonds: t.bonds.iter().map(|b| [signed_type(b.typ, b.off), b.atoms[0], b.atoms[1]]).collect(),
            angles: t.angles.iter().map(|b| [signed_type(b.typ, b.off), b.atoms[0], b.atoms[1], b.atoms[2]]).collect(),
            dihedrals: t.dihedrals.iter().map(|b| [signed_type(b.typ, b.off), b.atoms[0], b.atoms[1], b.atoms[2], b.atoms[3]]).collect(),
            bond_history: (bpm.is_some() || any_history).then(|| t.bonds.iter().map(|b| b.history).collect()),
            bond_slots: any_slot.then(|| t.bonds.iter().map(|b| b.slots).collect()),
            bond_history_stored: bpm == Some(true),
        },
        force_field: sim.ff_commands.clone(),
        contact_histories,
        fixes: sim.fixes.iter().filter_map(|f| f.write_restart().map(|values| FixState { id: f.id().to_string(), style: f.style().to_string(), values })).collect(),
    })
}

/// `read_restart file`: restore the state written by write_restart (before any box exists).
pub fn read_restart(sim: &mut Simulation, cmd: &Command, sources: &mut SourceMap) -> DResult<()> {
    crate::deck::commands::before_box(sim, cmd)?;
    let mut a = Args::new(cmd, READ_SYNTAX);
    let w = a.word("file name")?;
    a.finish()?;
    let path = sim.path(&w.text);
    let bytes = std::fs::read(&path).map_err(|e| a.error_at(w, format!("cannot read restart file `{}`: {e}", path.display()), "cannot read"))?;
    let fail = |e: String| Diagnostic::at(w.span, format!("restart file {}: {e}", path.display()), "this restart file");
    // errors of the file's contents point into the file (added to the sources for that)
    let in_file = |sources: &mut SourceMap, e: String, at: Option<(usize, usize)>| match (at, std::str::from_utf8(&bytes)) {
        (Some((lo, hi)), Ok(text)) => {
            let id = sources.add(path.display().to_string(), text.to_string());
            Diagnostic::at(Span::new(id, lo, hi.max(lo + 1)), format!("restart file {}: {e}", path.display()), "here").with_label(w.span, "read by this command")
        }
        _ => fail(e),
    };
    let restart = parse(&bytes).map_err(|(e, at)| in_file(sources, e, at))?;
    let checked = restart.check().map_err(|e| {
        let at = std::str::from_utf8(&bytes).ok().and_then(|text| locate::locate(text, locate::leading_path(&e)));
        in_file(sources, e, at)
    })?;
    let Stored { commands, histories, stored_flag, fixes } = restore(sim, restart, checked).map_err(fail)?;
    // the replayed commands must not change the stored per-atom arrays (bond_style store/local
    // sets x/ref to the current positions): put them back afterwards
    let arrays = sim.state.atoms.extra.clone();
    for words in commands {
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
    let atoms = &mut sim.state.atoms;
    let nlocal = atoms.nlocal;
    for e in &arrays {
        if let Some(k) = atoms.find_extra(&e.name).filter(|&k| atoms.extra[k].stride == e.stride) {
            atoms.extra[k].data[..nlocal * e.stride].copy_from_slice(&e.data[..nlocal * e.stride]);
        }
    }
    if stored_flag {
        match sim.bond_style.as_ref().and_then(|b| b.as_bpm()) {
            Some(b) => b.shared().set_stored(),
            None => return Err(fail("topology.bond_history_stored is true, but the bond style of the file's force field is not a BPM style".into())),
        }
    }
    sim.restart_fixes = fixes;
    let mut stores = sim.pair.as_mut().map(|p| p.histories()).unwrap_or_default();
    if stores.len() != histories.len() {
        return Err(fail(format!("contact_histories has {} stores; the pair style of the file's force field has {}", histories.len(), stores.len())));
    }
    for (k, (store, h)) in stores.iter_mut().zip(histories).enumerate() {
        if store.size() != h.size {
            return Err(fail(format!("contact_histories[{k}] has {} values per contact; the pair style's store has {}", h.size, store.size())));
        }
        store.restore(h.contacts.into_iter().map(|Contact(owner, partner, image, values)| ContactRecord { owner, partner, image, values }).collect());
    }
    sim.out.print(&format!("Read restart file {} at step {}: {} atoms", path.display(), sim.state.step, sim.state.atoms.nlocal));
    Ok(())
}

/// The file as a restart, or why it is none (and where in the file, when the JSON does not
/// parse as a restart).
fn parse(bytes: &[u8]) -> Result<Restart, (String, Option<(usize, usize)>)> {
    parse_whole(bytes).map_err(|e| match e {
        ParseError::Whole(m) => (m, None),
        ParseError::At(m, line, column) => {
            let at = std::str::from_utf8(bytes).ok().map(|text| locate::offset_of(text, line, column));
            (m, at.map(|lo| (lo, lo + 1)))
        }
    })
}

enum ParseError {
    /// About the file as a whole.
    Whole(String),
    /// At a line and column of the JSON text.
    At(String, usize, usize),
}

fn parse_whole(bytes: &[u8]) -> Result<Restart, ParseError> {
    use ParseError::Whole;
    if bytes.starts_with(OLD_MAGIC) {
        return Err(Whole("this file is in the text format of dmhs before restart version 2 (`DMHS restart 1`), which is no longer read: write it again by running the deck that wrote it with this dmhs".into()));
    }
    if bytes[..bytes.len().min(64)].windows(LAMMPS_MAGIC.len()).any(|w| w == LAMMPS_MAGIC) {
        return Err(Whole(LAMMPS_BINARY.into()));
    }
    match bytes.iter().find(|b| !b.is_ascii_whitespace()) {
        None => return Err(Whole("the file is empty".into())),
        Some(b'{') => {}
        Some(_) if std::str::from_utf8(bytes).is_err() => return Err(Whole(format!("a binary file, not a dmhs restart file (if it is a LAMMPS restart: {LAMMPS_BINARY})"))),
        Some(_) => return Err(Whole("not a dmhs restart file (write_restart writes a JSON object)".into())),
    }
    serde_json::from_slice::<Restart>(bytes).map_err(|e| {
        if let Ok(h) = serde_json::from_slice::<Header>(bytes) {
            if let Err(m) = identify(&h.format, h.version) {
                return Whole(m);
            }
        }
        match e.classify() {
            serde_json::error::Category::Eof => Whole(format!("the file ends early, at line {} column {} (truncated?)", e.line(), e.column())),
            _ => ParseError::At(e.to_string(), e.line(), e.column()),
        }
    })
}

/// What read_restart gives the models after the state is set.
struct Stored {
    /// The force-field commands to replay.
    commands: Vec<Vec<String>>,
    /// The contact histories for the pair style they define.
    histories: Vec<History>,
    /// The BPM bond style has stored its reference states.
    stored_flag: bool,
    /// For fixes defined later with the same ID and style.
    fixes: Vec<FixState>,
}

/// Set the state from a checked file; returns what the models it defines get.
fn restore(sim: &mut Simulation, r: Restart, c: Checked) -> Result<Stored, String> {
    let s = r.settings;
    let st = &mut sim.state;
    let old = st.units;
    st.units = Units::new(c.units);
    if st.neigh_settings.skin == old.skin {
        st.neigh_settings.skin = st.units.skin;
    }
    st.dt = s.dt;
    st.dt_set = s.dt_set;
    st.step = s.step;
    st.atime = s.time_origin.time;
    st.atimestep = s.time_origin.step;
    st.dimension = s.dimension as usize;
    st.boundary = c.boundary;
    st.atom_style = s.atom_style;
    st.newton_pair = s.newton_pair;
    st.newton_bond = s.newton_bond;
    st.comm_vel = s.comm_vel;
    let domain = |b: &Bounds| Domain { tilt: b.tilt, ..Domain::new(s.dimension as usize, b.lo, b.hi, c.boundary) };
    st.domain = Some(domain(&r.bounds.current));
    st.grid_areas = st.domain.as_ref().map(Domain::face_areas);
    st.box_initial = r.bounds.initial.as_ref().map(domain);
    st.ntypes = r.types.atom_types;
    st.type_mass = std::iter::once(0.0).chain(r.types.masses.iter().map(|m| m.unwrap_or(0.0))).collect();
    st.mass_set = std::iter::once(false).chain(r.types.masses.iter().map(Option::is_some)).collect();
    let mut groups = Groups::default();
    for (k, name) in r.groups.iter().enumerate() {
        if let Some(name) = name {
            groups.set_index(k, name)?;
        }
    }
    st.groups = groups;

    let a = r.atoms;
    let n = a.count;
    let ft = c.features;
    st.atoms = Atoms {
        features: ft,
        nlocal: n,
        tag: a.id,
        typ: a.typ.into_iter().map(|t| t as usize).collect(),
        mask: a.mask,
        x: a.x,
        v: a.v,
        f: vec![[0.0; 3]; n],
        image: a.image,
        molecule: a.molecule.unwrap_or_default(),
        q: a.q.unwrap_or_default(),
        radius: a.radius.unwrap_or_default(),
        rmass: a.rmass.unwrap_or_default(),
        omega: a.omega.unwrap_or_default(),
        quat: a.quat.unwrap_or_default(),
        torque: if ft.sphere { vec![[0.0; 3]; n] } else { Vec::new() },
        rho: a.rho.unwrap_or_default(),
        drho: a.drho.unwrap_or_default(),
        esph: a.esph.unwrap_or_default(),
        desph: a.desph.unwrap_or_default(),
        cv: a.cv.unwrap_or_default(),
        vest: a.vest.unwrap_or_default(),
        extra: a.fix_arrays.into_iter().map(|f| ExtraArray { name: f.name, stride: f.stride, data: f.values.concat(), ghosts: f.ghosts }).collect(),
        ..Atoms::default()
    };
    let t = r.topology;
    if let Some(o) = a.lammps_order {
        st.lammps_order = crate::engine::lammps_order::LammpsOrder::restored(o.ids, o.sortfreq, o.binsize);
        st.lammps_order.first = o.first;
    }
    let history = t.bond_history.unwrap_or_else(|| vec![[0.0; crate::engine::topology::BOND_HISTORY]; t.bonds.len()]);
    let slots = t.bond_slots.unwrap_or_else(|| vec![[u32::MAX; 2]; t.bonds.len()]);
    st.topo = Topology {
        nbondtypes: t.bond_types,
        nangletypes: t.angle_types,
        ndihedraltypes: t.dihedral_types,
        nimpropertypes: t.improper_types,
        bonds: t.bonds.iter().zip(history).zip(slots).map(|((b, history), slots)| Bond { off: b[0] < 0, history, slots, ..Bond::new(b[0].unsigned_abs() as usize, [b[1], b[2]]) }).collect(),
        angles: t.angles.iter().map(|b| Angle { off: b[0] < 0, ..Angle::new(b[0].unsigned_abs() as usize, [b[1], b[2], b[3]]) }).collect(),
        dihedrals: t.dihedrals.iter().map(|b| Dihedral { off: b[0] < 0, ..Dihedral::new(b[0].unsigned_abs() as usize, [b[1], b[2], b[3], b[4]]) }).collect(),
    };
    st.lists_valid = false;
    Ok(Stored { commands: r.force_field, histories: r.contact_histories, stored_flag: t.bond_history_stored, fixes: r.fixes })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::commands::run_plain;

    /// 64 spheres with charges and SPH fields and a fix array of stride 2.
    fn sim() -> Simulation {
        let deck = "units lj\natom_style hybrid sphere charge sph\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\nlattice sc 1.0\ncreate_atoms 1 box\n";
        let mut sim = Simulation::new();
        sim.out.captured = Some(String::new());
        run_plain(&mut sim, deck).unwrap();
        sim.state.atoms.extra_array("test", 2);
        sim
    }

    /// Signed zeros, subnormals, extremes, values with 17-digit shortest forms, then random
    /// bit patterns.
    fn awkward() -> impl Iterator<Item = f64> {
        let fixed = [-0.0, 0.0, 5e-324, -5e-324, 2.225073858507201e-308, f64::MIN_POSITIVE, 1e308, -1e308, f64::MAX, f64::MIN, f64::EPSILON, 0.1 + 0.2, 1.0 / 3.0, 2f64.powi(53) + 2.0, 123456789.12345679, -7.0e-310];
        let mut s = 0x9E37_79B9_7F4A_7C15u64;
        let random = std::iter::repeat_with(move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            f64::from_bits(s)
        });
        fixed.into_iter().chain(random.filter(|x| x.is_finite()))
    }

    /// The bits of every double of the owned atoms.
    fn bits(a: &Atoms) -> Vec<u64> {
        let n = a.nlocal;
        let mut out = Vec::new();
        for v in [&a.x, &a.v, &a.omega, &a.vest] {
            out.extend(v[..n].iter().flatten().map(|x| x.to_bits()));
        }
        for v in [&a.q, &a.radius, &a.rmass, &a.rho, &a.drho, &a.esph, &a.desph, &a.cv] {
            out.extend(v[..n].iter().map(|x| x.to_bits()));
        }
        out.extend(a.extra.iter().flat_map(|e| e.data[..n * e.stride].iter().map(|x| x.to_bits())));
        out
    }

    #[test]
    fn every_double_round_trips_exactly() {
        let mut sim = sim();
        let mut vals = awkward();
        let mut next = || vals.next().unwrap();
        let a = &mut sim.state.atoms;
        for i in 0..a.nlocal {
            for v in [&mut a.x, &mut a.v, &mut a.omega, &mut a.vest] {
                v[i] = [next(), next(), next()];
            }
            for v in [&mut a.q, &mut a.rho, &mut a.drho, &mut a.esph, &mut a.desph, &mut a.cv] {
                v[i] = next();
            }
            // radii >= 0 and masses > 0 (the checks refuse others)
            a.radius[i] = next().abs();
            a.rmass[i] = next().abs().max(5e-324);
            a.extra[0].data[2 * i..2 * i + 2].copy_from_slice(&[next(), next()]);
        }
        sim.state.dt = next();
        sim.state.atime = next();
        let json = restart_json(&mut sim).unwrap();
        let text = std::str::from_utf8(&json).unwrap();
        assert!(text.contains("-0.0,") && text.contains("5e-324") && text.contains("1e+308"), "{}", &text[..2000]);
        let r = parse(&json).unwrap();
        let c = r.check().unwrap();
        let mut back = Simulation::new();
        restore(&mut back, r, c).unwrap();
        assert!(bits(&back.state.atoms) == bits(&sim.state.atoms), "a double changed");
        assert_eq!((back.state.dt.to_bits(), back.state.atime.to_bits()), (sim.state.dt.to_bits(), sim.state.atime.to_bits()));
        // and the file written from the restored state is the same file
        assert!(restart_json(&mut back).unwrap() == json);
    }

    #[test]
    fn non_finite_values_are_refused_on_write() {
        type Spoil = fn(&mut Simulation);
        let cases: [(&str, Spoil); 4] = [
            ("atoms.v[3] (atom 4) is [0.0, NaN, 0.0]: not all finite", |s| s.state.atoms.v[3] = [0.0, f64::NAN, 0.0]),
            ("atoms.q[5] (atom 6) is inf: not a finite number", |s| s.state.atoms.q[5] = f64::INFINITY),
            ("atoms.fix_arrays[0].values[1] (atom 2) is [-inf, 0.0]: not all finite", |s| s.state.atoms.extra[0].data[2] = f64::NEG_INFINITY),
            ("settings.dt is NaN: not a finite number", |s| s.state.dt = f64::NAN),
        ];
        for (message, spoil) in cases {
            let mut sim = sim();
            spoil(&mut sim);
            assert_eq!(restart_json(&mut sim).unwrap_err(), message);
        }
    }
}
