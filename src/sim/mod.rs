//! The simulation state: everything a deck sets up, and what expressions can read from it.

pub mod memory;
pub mod run;
pub mod stability;

use crate::engine::atoms::{AtomFeatures, Atoms};
use crate::models::bonded::{AngleStyle, BondStyle, DihedralStyle};
use crate::engine::special::SpecialBonds;
use crate::models::compute::Compute;
use crate::engine::domain::{BoundaryKind, Domain};
use crate::output::dump::Dump;
use crate::models::fix::Fix;
use crate::engine::groups::Groups;
use crate::engine::neighbor::{Neighbor, NeighborSettings, SpecialTable};
use crate::output::log::Output;
use crate::models::pair::{PairModify, PairStyle, Tally};
use crate::output::thermo::Thermo;
use crate::engine::timing::Timers;
use crate::engine::topology::Topology;
use crate::engine::units::{UnitStyle, Units};
use dmhs_parser::variables::Variables;
use dmhs_parser::EvalContext;

/// An error during a run: the step, and what went wrong. Results already written stay.
#[derive(Debug, Clone, PartialEq)]
pub struct RunError {
    pub step: i64,
    pub message: String,
}

impl RunError {
    pub fn new(step: i64, message: impl Into<String>) -> RunError {
        RunError { step, message: message.into() }
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

pub struct Simulation {
    pub units: Units,
    pub dimension: usize,
    pub boundary: [[BoundaryKind; 2]; 3],
    pub atom_style: Vec<String>,
    pub newton_pair: bool,
    pub newton_bond: bool,
    pub domain: Option<Domain>,
    /// The box as created (shrink-wrap margins and `m` bounds come from it).
    pub box_initial: Option<Domain>,
    pub atoms: Atoms,
    pub ntypes: usize,
    /// Per-type mass (index 0 unused) and whether it was set.
    pub type_mass: Vec<f64>,
    pub mass_set: Vec<bool>,
    pub topo: Topology,
    pub pair: Option<Box<dyn PairStyle>>,
    pub pair_modify: PairModify,
    pub bond_style: Option<Box<dyn BondStyle>>,
    pub angle_style: Option<Box<dyn AngleStyle>>,
    pub dihedral_style: Option<Box<dyn DihedralStyle>>,
    /// Bonded interactions with local indices and periodic shifts, valid after a rebuild.
    pub bonded_lists: crate::models::bonded::pass::BondedLists,
    pub special_bonds: SpecialBonds,
    pub special_table: SpecialTable,
    /// The force-field commands as given (pair/bond/angle/dihedral styles and coefficients,
    /// pair_modify, special_bonds), replayed by read_restart.
    pub ff_commands: Vec<Vec<String>>,
    /// Every command executed, as words after substitution (when Some; for translating a deck
    /// to another engine).
    pub command_log: Option<Vec<Vec<String>>>,
    pub neigh_settings: NeighborSettings,
    pub neighbor: Neighbor,
    pub comm_vel: bool,
    pub groups: Groups,
    pub lattice: Option<crate::deck::lattice::Lattice>,
    pub regions: Vec<crate::models::region::Region>,
    pub fixes: Vec<Box<dyn Fix>>,
    pub computes: Vec<Box<dyn Compute>>,
    pub thermo: Thermo,
    pub dumps: Vec<Dump>,
    pub dt: f64,
    pub dt_set: bool,
    pub step: i64,
    /// Simulation time at `atimestep` (time = atime + (step - atimestep) * dt, as LAMMPS).
    pub atime: f64,
    pub atimestep: i64,
    /// First and last step of the current run.
    pub run_window: Option<(i64, i64)>,
    pub variables: Variables,
    pub out: Output,
    pub timers: Timers,
    pub energies: Energies,
    /// Lists and ghosts are valid for the current atoms.
    pub lists_valid: bool,
    /// Number of atoms at the start of the run (lost-atom check).
    pub natoms_expected: usize,
    /// Seconds of the last run's loop, for `Loop time` and benchmarks.
    pub last_loop_seconds: f64,
    pub last_loop_steps: i64,
    /// A run failed (exit code 1 rather than 2 for a deck error).
    pub runtime_failed: bool,
    /// Directory for relative file names in commands (None: the working directory).
    pub base_dir: Option<std::path::PathBuf>,
    /// Per-atom forces captured after the setup of the first run (for crosscheck).
    pub capture_setup: Option<crate::tools::crosscheck::AtomTable>,
    pub want_capture: bool,
    /// `dmhs check`: commands are built but `run` does not run.
    pub check_only: bool,
    pub checked_runs: usize,
    pub guard: crate::sim::stability::Guard,
    /// A fix asked for neighbour lists to be rebuilt on this step (LAMMPS `next_reneighbor`).
    pub rebuild_requested: bool,
    /// The topology changed since the special lists were built.
    pub special_dirty: bool,
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation::new()
    }
}

impl Simulation {
    pub fn new() -> Simulation {
        let units = Units::new(UnitStyle::Lj);
        Simulation {
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
            mass_set: vec![false],
            topo: Topology::default(),
            pair: None,
            pair_modify: PairModify::default(),
            bond_style: None,
            angle_style: None,
            dihedral_style: None,
            bonded_lists: Default::default(),
            special_bonds: SpecialBonds::default(),
            special_table: SpecialTable::default(),
            ff_commands: Vec::new(),
            command_log: None,
            neigh_settings: NeighborSettings::new(units.skin),
            neighbor: Neighbor::default(),
            comm_vel: false,
            groups: Groups::default(),
            lattice: None,
            regions: Vec::new(),
            fixes: Vec::new(),
            computes: crate::models::compute::default_computes(),
            thermo: Thermo::default(),
            dumps: Vec::new(),
            dt: units.dt,
            dt_set: false,
            step: 0,
            atime: 0.0,
            atimestep: 0,
            run_window: None,
            variables: Variables::default(),
            out: Output::default(),
            timers: Timers::default(),
            energies: Energies { step: -1, ..Energies::default() },
            lists_valid: false,
            natoms_expected: 0,
            last_loop_seconds: 0.0,
            last_loop_steps: 0,
            runtime_failed: false,
            base_dir: None,
            capture_setup: None,
            want_capture: false,
            check_only: false,
            checked_runs: 0,
            guard: Default::default(),
            rebuild_requested: false,
            special_dirty: false,
        }
    }

    /// A file name from a command, resolved against `base_dir`.
    pub fn path(&self, name: &str) -> std::path::PathBuf {
        match &self.base_dir {
            Some(d) if std::path::Path::new(name).is_relative() => d.join(name),
            _ => std::path::PathBuf::from(name),
        }
    }

    /// Number of owned atoms.
    pub fn natoms(&self) -> usize {
        self.atoms.nlocal
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
    pub fn find_fix(&self, id: &str) -> Option<usize> {
        self.fixes.iter().position(|f| f.id() == id)
    }
    pub fn find_compute(&self, id: &str) -> Option<usize> {
        self.computes.iter().position(|c| c.id() == id)
    }
    pub fn group_bit(&self, name: &str) -> Result<u32, String> {
        self.groups.bit(name).ok_or_else(|| format!("group `{name}` does not exist"))
    }
    /// Owned atoms in a group.
    pub fn group_count(&self, bit: u32) -> usize {
        self.atoms.mask[..self.atoms.nlocal].iter().filter(|&&m| m & bit != 0).count()
    }
    /// Degrees of freedom removed by fixes for a group (e.g. none for the fixes so far).
    pub fn fix_dof(&self, bit: u32) -> f64 {
        self.fixes.iter().map(|f| f.dof_removed(self, bit)).sum()
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
        0.5 * self.units.mvv2e * t
    }

    /// Total potential energy of the last tallied evaluation.
    pub fn potential_energy(&self) -> f64 {
        let e = &self.energies;
        e.pair.evdwl + e.pair.ecoul + e.ebond + e.eangle + e.edihed
    }

    /// Center of mass (unwrapped) and total mass of a group.
    pub fn group_xcm(&self, bit: u32) -> ([f64; 3], f64) {
        let a = &self.atoms;
        let mut c = [0.0; 3];
        let mut m = 0.0;
        let Some(d) = self.domain.as_ref() else { return (c, 0.0) };
        for i in 0..a.nlocal {
            if a.mask[i] & bit != 0 {
                let mi = self.mass(i);
                let u = d.unmap(a.x[i], a.image[i]);
                for k in 0..3 {
                    c[k] += u[k] * mi;
                }
                m += mi;
            }
        }
        if m > 0.0 {
            for v in &mut c {
                *v /= m;
            }
        }
        (c, m)
    }

    pub fn group_vcm(&self, bit: u32) -> [f64; 3] {
        let a = &self.atoms;
        let mut p = [0.0; 3];
        let mut m = 0.0;
        for i in 0..a.nlocal {
            if a.mask[i] & bit != 0 {
                let mi = self.mass(i);
                for k in 0..3 {
                    p[k] += a.v[i][k] * mi;
                }
                m += mi;
            }
        }
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

    /// Value of a thermo keyword (`None` if the name is not one).
    pub fn thermo_keyword_value(&self, name: &str) -> Option<Result<f64, String>> {
        crate::output::thermo::keyword_value(self, name)
    }
}

impl EvalContext for Simulation {
    fn variables(&mut self) -> &mut Variables {
        &mut self.variables
    }
    fn thermo_keyword(&mut self, name: &str) -> Option<Result<f64, String>> {
        crate::output::thermo::keyword_value(self, name)
    }
    fn compute_value(&mut self, id: &str, index: Option<usize>) -> Result<f64, String> {
        let k = self.find_compute(id).ok_or_else(|| format!("compute `{id}` does not exist"))?;
        let c = &self.computes[k];
        match index {
            None => c.scalar(self),
            Some(i) => {
                let v = c.vector(self)?;
                v.get(i.wrapping_sub(1)).copied().ok_or_else(|| format!("compute `{id}` vector has {} values, index {i} is out of range", v.len()))
            }
        }
    }
    fn fix_value(&mut self, id: &str, index: Option<usize>) -> Result<f64, String> {
        let k = self.find_fix(id).ok_or_else(|| format!("fix `{id}` does not exist"))?;
        let f = &self.fixes[k];
        match index {
            None => f.scalar(self).ok_or_else(|| format!("fix `{id}` ({}) has no global scalar", f.style())),
            Some(i) => f.vector(self, i).ok_or_else(|| format!("fix `{id}` ({}) has no global vector element {i}", f.style())),
        }
    }
    fn group_function(&mut self, name: &str, args: &[String]) -> Option<Result<f64, String>> {
        crate::models::compute::group_function(self, name, args)
    }
    fn atom_value(&mut self, keyword: &str, id: i64) -> Option<Result<f64, String>> {
        crate::models::compute::atom_value(self, keyword, id)
    }
    fn run_window(&mut self) -> Option<(i64, i64)> {
        self.run_window
    }
}
