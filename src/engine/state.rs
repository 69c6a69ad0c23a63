//! The state the stages borrow: atoms, box, topology, units, groups, regions, the neighbour and
//! bonded lists derived from them, and the clock. Models read and change it through the
//! arguments of their hooks; nothing in it refers to a model.

use crate::engine::atoms::{AtomFeatures, Atoms};
use crate::engine::bonded_lists::BondedLists;
use crate::engine::domain::{BoundaryKind, Domain};
use crate::engine::groups::Groups;
use crate::engine::lattice::Lattice;
use crate::engine::neighbor::{Neighbor, NeighborSettings, SpecialTable};
use crate::engine::region::Region;
use crate::engine::special::{build_special, SpecialBonds, Topology as SpecialTopology};
use crate::engine::tally::Tally;
use crate::engine::topology::Topology;
use crate::engine::units::{UnitStyle, Units};

/// An error during a run: the step, and what went wrong. Results already written stay.
#[derive(Debug, Clone, PartialEq)]
pub struct RunError {
    pub step: i64,
    pub message: String,
    /// The checks before the run refused the deck (a deck error: exit 2, as `dmhs check`
    /// reports it), rather than the run failing on its way.
    pub setup: Option<SetupError>,
}

impl RunError {
    pub fn new(step: i64, message: impl Into<String>) -> RunError {
        RunError { step, message: message.into(), setup: None }
    }
    /// The checks before a run at `step` refused the deck.
    pub fn setup(step: i64, e: SetupError) -> RunError {
        RunError { step, message: e.message.clone(), setup: Some(e) }
    }
}

/// A check before a run failed: the deck cannot run as written. `at` is the command that set up
/// what is wrong (the `pair_style` line for a pair style that does not fit the atom style), when
/// one is known; otherwise the error is shown at the `run` command.
#[derive(Debug, Clone, PartialEq)]
pub struct SetupError {
    pub message: String,
    pub at: Option<dmhs_parser::Span>,
}

impl SetupError {
    pub fn new(message: impl Into<String>) -> SetupError {
        SetupError { message: message.into(), at: None }
    }
}

impl From<String> for SetupError {
    fn from(message: String) -> SetupError {
        SetupError::new(message)
    }
}

impl From<&str> for SetupError {
    fn from(message: &str) -> SetupError {
        SetupError::new(message)
    }
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "step {}: {}", self.step, self.message)
    }
}

/// Energies and virial of the last force evaluation that tallied them.
#[derive(Clone, Copy, Debug, Default)]
pub struct Energies {
    pub pair: Tally,
    pub ebond: f64,
    pub eangle: f64,
    pub edihed: f64,
    /// Total virial (pair + bonded + fixes), xx yy zz xy xz yz.
    pub virial: [f64; 6],
    /// Step at which these were computed (-1: never).
    pub step: i64,
}

/// One per-type-pair parameter of the pair style set to a value (types i <= j).
#[derive(Clone, Debug, PartialEq)]
pub struct PairParamChange {
    pub param: String,
    pub i: usize,
    pub j: usize,
    pub value: f64,
}

pub struct State {
    pub units: Units,
    pub dimension: usize,
    pub boundary: [[BoundaryKind; 2]; 3],
    pub atom_style: Vec<String>,
    pub newton_pair: bool,
    pub newton_bond: bool,
    pub domain: Option<Domain>,
    /// The box as created, before the shrink-wrap padding (LAMMPS `set_initial_box`: the `small`
    /// margins and the `m` bounds come from it).
    pub box_initial: Option<Domain>,
    pub atoms: Atoms,
    pub ntypes: usize,
    /// Per-type mass (index 0 unused) and whether it was set.
    pub type_mass: Vec<f64>,
    /// The masses granular contacts use for the effective mass: each rigid body atom's body
    /// mass, else its own (LAMMPS' mass_rigid, refreshed on list rebuilds; owned and ghost
    /// atoms); empty without a rigid fix.
    pub rigid_mass: Vec<f64>,
    pub mass_set: Vec<bool>,
    pub topo: Topology,
    pub special_bonds: SpecialBonds,
    pub special_table: SpecialTable,
    /// Bonded interactions with local indices and periodic shifts, valid after a rebuild.
    pub bonded_lists: BondedLists,
    pub neigh_settings: NeighborSettings,
    pub neighbor: Neighbor,
    /// LAMMPS' local order of the owned atoms (for models whose bits depend on atom order).
    pub lammps_order: super::lammps_order::LammpsOrder,
    pub comm_vel: bool,
    /// `comm_modify cutoff`: the least ghost cutoff of a distributed run (bonded partners
    /// farther than the pair cutoff + skin); a serial run's periodic ghosts need none.
    pub comm_cutoff: f64,
    /// A distributed run cuts its sub-domains where they hold equal shares of the atoms, at its
    /// start and whenever the load grows uneven (`balance`; LAMMPS cuts uniformly unless told).
    pub balance: bool,
    pub groups: Groups,
    pub lattice: Option<Lattice>,
    pub regions: Vec<Region>,
    /// Molecule templates (`molecule` command).
    pub molecules: Vec<crate::engine::molecule::Molecule>,
    /// Molecules an inserting fix (pour) added this step as bodies of a rigid fix, handed to
    /// that fix before the lists are rebuilt (LAMMPS' direct set_molecule call).
    pub rigid_inserts: Vec<crate::engine::molecule::RigidInsert>,
    pub dt: f64,
    pub dt_set: bool,
    pub step: i64,
    /// Simulation time at `atimestep` (time = atime + (step - atimestep) * dt, as LAMMPS).
    pub atime: f64,
    pub atimestep: i64,
    /// First and last step of the current run.
    pub run_window: Option<(i64, i64)>,
    pub energies: Energies,
    /// Per-atom energies and virials of the last force evaluation that made them (for compute
    /// pe/atom and stress/atom).
    pub peratom: Option<crate::engine::tally::PerAtomTally>,
    /// Why the styles could not make `peratom` on that step: LAMMPS tallies per-atom energies
    /// only when a compute that needs them is evaluated, so the refusal waits for that.
    pub peratom_missing: Option<(i64, String)>,
    /// Lists and ghosts are valid for the current atoms.
    pub lists_valid: bool,
    /// Number of atoms at the start of the run (lost-atom check).
    pub natoms_expected: usize,
    /// A fix asked for neighbour lists to be rebuilt on this step (LAMMPS `next_reneighbor`).
    pub rebuild_requested: bool,
    /// The topology changed since the special lists were built.
    pub special_dirty: bool,
    /// The special lists were kept when `delete_bonds ... remove` (without `special`) removed
    /// interactions, as LAMMPS keeps them: runs do not rebuild them from the topology until a
    /// command that rebuilds them does.
    pub special_frozen: bool,
    /// Lines for the screen and the log from models (e.g. a fix's warnings during a run),
    /// printed and cleared by the command or step that produced them.
    pub messages: Vec<String>,
    /// A fix halt stopped the run (LAMMPS' expired timer): the run loop stops before its next
    /// step and later `run` and `minimize` commands do nothing, until a `continue` halt resets it.
    pub halted: bool,
    /// `dmhs check`: the deck's commands are built, no run runs and no output file is opened.
    pub check_only: bool,
    /// Pair parameters a fix asked to change (fix adapt), applied by the simulation before
    /// the forces.
    pub pair_changes: Vec<PairParamChange>,
    /// The ranks of a distributed run (None: one rank). Between runs every rank holds every
    /// atom, as a serial run does; during a run each holds its sub-domain's (`distributed`).
    pub decomp: Option<crate::engine::decomp::Decomp>,
    /// The `processors` command's settings (Px Py Pz, None: `*`, chosen by the decomposition).
    pub procs: crate::engine::procmap::ProcSettings,
    /// The box's face areas when it was made (create_box, read_data, read_restart, replicate):
    /// a run on ranks chooses its processor grid from them, as LAMMPS sets its grid then
    /// (Comm::set_proc_grid), not from the box of the run.
    pub grid_areas: Option<[f64; 3]>,
    /// The atoms are spread over the ranks now, each holding its own (the total in `natoms`).
    pub distributed: Option<usize>,
    /// The interactions by the atom each is stored on, for a distributed run's bonded lists
    /// (made at its first list build, dropped when the run ends).
    pub stored_on: Option<crate::engine::topology::StoredOn>,
}

impl Default for State {
    fn default() -> Self {
        State::new()
    }
}

impl State {
    /// `atom_style sphere 1` (or bpm/sphere 1): radii may change during a run (LAMMPS'
    /// radvary, which fix adapt's atom diameter requires).
    pub fn radius_dynamic(&self) -> bool {
        self.atom_style.windows(2).any(|w| matches!(w[0].as_str(), "sphere" | "bpm/sphere") && w[1] == "1")
    }
    pub fn new() -> State {
        let units = Units::new(UnitStyle::Lj);
        State {
            units,
            dimension: 3,
            boundary: [[BoundaryKind::Periodic; 2]; 3],
            atom_style: vec!["atomic".to_string()],
            newton_pair: true,
            newton_bond: true,
            domain: None,
            box_initial: None,
            atoms: Atoms::new(AtomFeatures::default()),
            ntypes: 0,
            type_mass: vec![0.0],
            rigid_mass: Vec::new(),
            mass_set: vec![false],
            topo: Topology::default(),
            special_bonds: SpecialBonds::default(),
            special_table: SpecialTable::default(),
            bonded_lists: Default::default(),
            neigh_settings: NeighborSettings::new(units.skin),
            neighbor: Neighbor::default(),
            lammps_order: Default::default(),
            comm_vel: false,
            comm_cutoff: 0.0,
            balance: true,
            groups: Groups::default(),
            lattice: None,
            regions: Vec::new(),
            molecules: Vec::new(),
            rigid_inserts: Vec::new(),
            dt: units.dt,
            dt_set: false,
            step: 0,
            atime: 0.0,
            atimestep: 0,
            run_window: None,
            energies: Energies { step: -1, ..Energies::default() },
            peratom: None,
            peratom_missing: None,
            lists_valid: false,
            natoms_expected: 0,
            rebuild_requested: false,
            special_dirty: false,
            special_frozen: false,
            messages: Vec::new(),
            halted: false,
            check_only: false,
            pair_changes: Vec::new(),
            decomp: None,
            procs: Default::default(),
            grid_areas: None,
            distributed: None,
            stored_on: None,
        }
    }

    /// Number of owned atoms.
    /// Atoms in the system (on every rank of a distributed run).
    pub fn natoms(&self) -> usize {
        self.distributed.unwrap_or(self.atoms.nlocal)
    }
    /// Sum `v` over the ranks of a distributed run (every rank calls this at the same point).
    pub fn sum_ranks(&self, v: &mut [f64]) {
        if let (Some(d), Some(_)) = (&self.decomp, self.distributed) {
            d.comm.sum(v);
        }
    }
    /// The sum of one value over the ranks of a distributed run (a fix's global energy or force).
    pub fn summed_over_ranks(&self, x: f64) -> f64 {
        let mut v = [x];
        self.sum_ranks(&mut v);
        v[0]
    }
    /// Whether this process writes the files of fix outputs (fix print, ave/time): rank 0 of
    /// several (set before the deck's first command), or a rank alone, as LAMMPS' `me == 0`;
    /// none under `dmhs check`.
    pub fn writes_files(&self) -> bool {
        !self.check_only && self.decomp.as_ref().is_none_or(|d| d.rank() == 0)
    }
    /// The largest of `v` over the ranks of a distributed run, element by element.
    pub fn max_ranks(&self, v: &mut [f64]) {
        if let (Some(d), Some(_)) = (&self.decomp, self.distributed) {
            d.comm.max(v);
        }
    }
    /// The least of `v` over the ranks of a distributed run, element by element.
    pub fn min_ranks(&self, v: &mut [f64]) {
        if let (Some(d), Some(_)) = (&self.decomp, self.distributed) {
            d.comm.min(v);
        }
    }
    /// Every rank's `v`, joined in rank order (a distributed run; otherwise `v` itself).
    pub fn allgather_ranks(&self, v: Vec<f64>) -> Vec<f64> {
        match (&self.decomp, self.distributed) {
            (Some(d), Some(_)) => d.comm.allgather(v).concat(),
            _ => v,
        }
    }
    /// Whether any rank of a distributed run says yes (a rank alone: itself).
    pub fn any_ranks(&self, yes: bool) -> bool {
        match (&self.decomp, self.distributed) {
            (Some(d), Some(_)) => d.comm.any(yes),
            _ => yes,
        }
    }
    /// Delete the owned atoms marked in `gone`, between runs (delete_atoms, read_dump's purge
    /// and trim): LAMMPS' local order loses them as its copy of the last atom into each hole,
    /// and their bonds, angles and dihedrals go with them. No ghosts may be present. Returns
    /// how many were deleted.
    pub fn delete_owned(&mut self, gone: &[bool]) -> usize {
        let tags: std::collections::HashSet<i64> = (0..self.atoms.nlocal).filter(|&i| gone[i]).map(|i| self.atoms.tag[i]).collect();
        self.lammps_order.before_rebuild(&self.atoms);
        self.atoms.retain(gone);
        self.lammps_order.before_rebuild(&self.atoms);
        self.topo.remove_atoms(&tags);
        tags.len()
    }

    /// Shrink-wrapped faces around the atoms (LAMMPS' `Domain::reset_box`): those of every rank
    /// in a distributed run, so that every rank cuts the same box. On a triclinic box the
    /// positions are in box fractions (as a rebuild keeps them) and stay so.
    pub fn shrink_wrap(&mut self) {
        let (Some(initial), Some(domain)) = (self.box_initial.as_ref(), self.domain.as_mut()) else { return };
        let ranks = self.decomp.as_ref().filter(|_| self.distributed.is_some());
        crate::engine::boundary::reset_shrink_wrap_over(domain, initial, &mut self.atoms, |v| {
            if let Some(d) = ranks {
                d.comm.max(v);
            }
        });
    }
    /// LAMMPS' preparation of write_data and write_restart: every owned atom wrapped into the
    /// periodic box (LAMMPS' pbc, in box fractions on a triclinic box) and the shrink-wrapped
    /// faces reset around the atoms. The file then holds the box LAMMPS' holds.
    pub fn settle_into_box(&mut self) {
        let Some(domain) = self.domain.clone() else { return };
        let tilted = domain.triclinic();
        if tilted {
            crate::engine::boundary::to_fractions(&domain, &mut self.atoms);
        }
        crate::engine::boundary::pbc_owned(&domain, &mut self.atoms);
        self.shrink_wrap();
        if tilted {
            crate::engine::boundary::to_box(self.domain.as_ref().expect("a box"), &mut self.atoms);
        }
        self.lists_valid = false;
    }
    /// The largest atom ID and molecule ID over every rank's owned atoms: inserted atoms and
    /// molecules are numbered after them.
    pub fn max_ids(&self) -> (i64, i64) {
        // IDs are below 2^53, so exact as doubles
        let mut v = [self.atoms.max_tag() as f64, self.atoms.max_molecule() as f64];
        self.max_ranks(&mut v);
        (v[0] as i64, v[1] as i64)
    }
    /// Each owned atom's ID and value, for every atom of every rank (a distributed run; otherwise
    /// the owned atoms'): values kept by atom ID that must hold wherever the atoms migrate.
    pub fn values_by_id(&self, value: impl Fn(usize) -> usize) -> std::collections::HashMap<i64, usize> {
        let a = &self.atoms;
        if self.distributed.is_none() {
            return (0..a.nlocal).map(|i| (a.tag[i], value(i))).collect();
        }
        // IDs and chunk-like values are below 2^53, so exact as doubles
        let flat = (0..a.nlocal).flat_map(|i| [a.tag[i] as f64, value(i) as f64]).collect();
        self.allgather_ranks(flat).chunks_exact(2).map(|p| (p[0] as i64, p[1] as usize)).collect()
    }
    /// Whether this rank takes an atom inserted at `x` during a run: the one whose sub-domain
    /// holds it (a rank alone takes every one).
    pub fn owns_point(&self, x: &[f64; 3]) -> bool {
        match (&self.decomp, self.distributed, &self.domain) {
            (Some(d), Some(_), Some(domain)) => d.owner(domain, x) == d.rank(),
            _ => true,
        }
    }
    /// Fresh ghost positions in a distributed run, where ghosts are copies sent by other ranks
    /// (serial ghosts are not read between rebuilds: owned atoms are taken at a shift instead).
    pub fn forward_positions_ranks(&mut self) {
        if let (Some(d), Some(_), Some(domain)) = (&self.decomp, self.distributed, &self.domain) {
            d.forward_positions(&mut self.atoms, domain);
        }
    }
    /// The owners' values of a per-atom vector for every ghost (serial or distributed), without
    /// changing the ghosts' copies.
    pub fn owners_vectors(&self, get: fn(&Atoms) -> &[[f64; 3]]) -> Vec<[f64; 3]> {
        match (&self.decomp, self.distributed, &self.domain) {
            (Some(d), Some(_), Some(domain)) => d.owners_vectors(&self.atoms, domain, get),
            _ => self.atoms.ghost_owner.iter().map(|&o| get(&self.atoms)[o as usize]).collect(),
        }
    }
    /// The face areas a run on ranks chooses its processor grid from: the box's as it was made
    /// (`grid_areas`), or the box's now where no command recorded them.
    pub fn grid_face_areas(&self, domain: &Domain) -> [f64; 3] {
        self.grid_areas.unwrap_or_else(|| domain.face_areas())
    }
    /// Fresh ghost state (positions, velocities and every per-atom value ghosts carry) from
    /// the owners, serial or distributed.
    pub fn forward_ghost_state(&mut self) {
        match (&self.decomp, self.distributed, &self.domain) {
            (Some(d), Some(_), Some(domain)) => d.forward_state(&mut self.atoms, domain),
            _ => self.atoms.forward_state(),
        }
        self.deform_ghost_velocities();
    }
    /// The velocities of ghosts of fix deform's `remap v` group as LAMMPS' forward
    /// communication makes them with `comm_modify vel yes`: each periodic exchange adds the
    /// box's rate of its dimension, x, y, then z. A serial ghost starts from its owner's
    /// velocity, a distributed one from the owner's velocity its rank sent.
    pub fn deform_ghost_velocities(&mut self) {
        let Some(d) = &self.domain else { return };
        let Some(group) = d.rate.vremap else { return };
        if !self.comm_vel {
            return;
        }
        let distributed = self.distributed.is_some();
        let a = &mut self.atoms;
        let n = a.nlocal;
        for (k, s) in a.ghost_shift.iter().enumerate() {
            let o = if distributed { n + k } else { a.ghost_owner[k] as usize };
            if a.mask[o] & group == 0 {
                continue;
            }
            let mut v = a.v[o];
            for dim in 0..3 {
                for _ in 0..s[dim].unsigned_abs() {
                    d.rate.cross(&mut v, dim, s[dim].signum() as f64);
                }
            }
            a.v[n + k] = v;
        }
    }
    /// A per-rank quantity needed whole (group functions, per-atom lookups) that dmhs does not
    /// gather during a distributed run yet.
    pub fn whole_system(&self, what: &str) -> Result<(), String> {
        match self.distributed {
            Some(_) => Err(format!("{what} is not available during a run on several ranks yet")),
            None => Ok(()),
        }
    }
    pub fn time(&self) -> f64 {
        self.atime + (self.step - self.atimestep) as f64 * self.dt
    }
    pub fn domain(&self) -> Result<&Domain, String> {
        self.domain.as_ref().ok_or_else(|| "the simulation box is not defined yet (create_box or read_data)".to_string())
    }
    /// Mass of owned atom `i`.
    #[inline]
    pub fn mass(&self, i: usize) -> f64 {
        self.atoms.mass(i, &self.type_mass)
    }
    pub fn group_bit(&self, name: &str) -> Result<u32, String> {
        self.groups.bit(name).ok_or_else(|| format!("group `{name}` does not exist"))
    }
    /// Owned atoms in a group.
    pub fn group_count(&self, bit: u32) -> usize {
        let n = self.atoms.mask[..self.atoms.nlocal].iter().filter(|&&m| m & bit != 0).count();
        let mut v = [n as f64];
        self.sum_ranks(&mut v);
        v[0] as usize
    }
    /// Kinetic energy of a group, 0.5 * mvv2e * sum m v^2.
    pub fn kinetic_energy(&self, bit: u32) -> f64 {
        let a = &self.atoms;
        let mut t = 0.0;
        for i in 0..a.nlocal {
            if a.mask[i] & bit != 0 {
                let v = a.v[i];
                t += (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * self.mass(i);
            }
        }
        let mut v = [t];
        self.sum_ranks(&mut v);
        0.5 * self.units.mvv2e * v[0]
    }

    /// Total potential energy of the last tallied evaluation.
    pub fn potential_energy(&self) -> f64 {
        let e = &self.energies;
        e.pair.evdwl + e.pair.ecoul + e.ebond + e.eangle + e.edihed
    }

    /// Center of mass (unwrapped) and total mass of a group.
    pub fn group_xcm(&self, bit: u32) -> ([f64; 3], f64) {
        let a = &self.atoms;
        let Some(d) = self.domain.as_ref() else { return ([0.0; 3], 0.0) };
        // the moments and the mass in LAMMPS' atom order, summed over the ranks before the
        // division
        let mut s = [0.0; 4];
        for &i in self.lammps_order.indices(a.nlocal).iter() {
            if a.mask[i] & bit != 0 {
                let mi = self.mass(i);
                let u = d.unmap(a.x[i], a.image[i]);
                for k in 0..3 {
                    s[k] += u[k] * mi;
                }
                s[3] += mi;
            }
        }
        self.sum_ranks(&mut s);
        let (mut c, m) = ([s[0], s[1], s[2]], s[3]);
        if m > 0.0 {
            for v in &mut c {
                *v /= m;
            }
        }
        (c, m)
    }

    /// Centre-of-mass velocity of a group (sums in LAMMPS' atom order, over the ranks).
    pub fn group_vcm(&self, bit: u32) -> [f64; 3] {
        let a = &self.atoms;
        let mut s = [0.0; 4];
        for &i in self.lammps_order.indices(a.nlocal).iter() {
            if a.mask[i] & bit != 0 {
                let mi = self.mass(i);
                for k in 0..3 {
                    s[k] += a.v[i][k] * mi;
                }
                s[3] += mi;
            }
        }
        self.sum_ranks(&mut s);
        let (mut p, m) = ([s[0], s[1], s[2]], s[3]);
        if m > 0.0 {
            for v in &mut p {
                *v /= m;
            }
        }
        p
    }

    /// Lattice spacings for `units lattice` arguments.
    pub fn lattice_scale(&self) -> Result<[f64; 3], String> {
        // LAMMPS starts with `lattice none 1.0`
        Ok(self.lattice.as_ref().map(|l| l.spacing()).unwrap_or([1.0; 3]))
    }

    /// Bonds, angles or dihedrals changed: special lists and neighbour lists are rebuilt before
    /// the next force evaluation.
    pub fn topology_changed(&mut self) {
        self.special_dirty = true;
        self.rebuild_requested = true;
    }
    /// The special partners (1-2, 1-3, 1-4) by atom ID from the current topology.
    pub fn rebuild_special(&mut self) -> Result<(), String> {
        let flags = self.special_bonds.flags(false);
        if self.topo.bonds.is_empty() {
            self.special_table = SpecialTable::from_lists(&[], vec![], flags, true);
        } else {
            let bonds: Vec<[i64; 2]> = self.topo.bonds.iter().map(|b| b.atoms).collect();
            let angles: Vec<[i64; 3]> = self.topo.angles.iter().map(|a| a.atoms).collect();
            let dihedrals: Vec<[i64; 4]> = self.topo.dihedrals.iter().map(|d| d.atoms).collect();
            // a rank of a distributed run holds only some atoms: the lists of every atom the
            // topology names (the others have none), as every rank holds the whole topology
            let named: Vec<i64>;
            let ids = if self.distributed.is_some() {
                let mut t: Vec<i64> = bonds.iter().flatten().chain(angles.iter().flatten()).chain(dihedrals.iter().flatten()).copied().collect();
                t.sort_unstable();
                t.dedup();
                named = t;
                &named[..]
            } else {
                &self.atoms.tag[..self.atoms.nlocal]
            };
            let (lists, _stats) = build_special(&self.special_bonds, ids, SpecialTopology { bonds: &bonds, angles: &angles, dihedrals: &dihedrals })?;
            let symmetric = !self.special_bonds.angle && !self.special_bonds.dihedral;
            self.special_table = SpecialTable::from_lists(ids, lists, flags, symmetric);
        }
        self.special_dirty = false;
        self.special_frozen = false;
        Ok(())
    }
}
