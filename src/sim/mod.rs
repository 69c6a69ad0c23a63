//! The simulation state: everything a deck sets up, and what expressions can read from it.

pub mod distributed;
pub mod eval;
pub mod memory;
pub mod minimize;
pub mod rerun;
pub mod run;
pub mod stability;
mod stale_vest;

pub use crate::engine::state::{Energies, RunError, SetupError, State};
use crate::models::bonded::{AngleStyle, BondStyle, DihedralStyle};
use crate::models::compute::Compute;
use crate::output::dump::Dump;
use crate::models::fix::Fix;
use crate::output::log::Output;
use crate::models::pair::{PairModify, PairStyle};
use crate::output::thermo::Thermo;
use crate::engine::timing::Timers;
use dmhs_parser::variables::Variables;
use dmhs_parser::EvalContext;
use crate::models::world::{FixesView, World};
use eval::Eval;

pub struct Simulation {
    pub state: State,
    pub pair: Option<Box<dyn PairStyle>>,
    /// The `pair_style` command that defined `pair` (where set-up errors of the style point).
    pub pair_span: Option<dmhs_parser::Span>,
    pub pair_modify: PairModify,
    pub bond_style: Option<Box<dyn BondStyle>>,
    pub angle_style: Option<Box<dyn AngleStyle>>,
    pub dihedral_style: Option<Box<dyn DihedralStyle>>,
    /// The force-field commands as given (pair/bond/angle/dihedral styles and coefficients,
    /// pair_modify, special_bonds), replayed by read_restart.
    pub ff_commands: Vec<Vec<String>>,
    /// Every command executed, as words after substitution (when Some; for translating a deck
    /// to another engine).
    pub command_log: Option<Vec<Vec<String>>>,
    pub fixes: Vec<Box<dyn Fix>>,
    pub computes: Vec<Box<dyn Compute>>,
    pub thermo: Thermo,
    pub dumps: Vec<Dump>,
    pub variables: Variables,
    pub out: Output,
    pub timers: Timers,
    /// Seconds of the last run's loop, for `Loop time` and benchmarks.
    pub last_loop_seconds: f64,
    /// When the current run's (or minimization's) loop started.
    pub loop_start: Option<std::time::Instant>,
    pub last_loop_steps: i64,
    /// A run failed (exit code 1 rather than 2 for a deck error).
    pub runtime_failed: bool,
    /// Directory for relative file names in commands (None: the working directory).
    pub base_dir: Option<std::path::PathBuf>,
    /// Per-atom forces captured after the setup of the first run (for crosscheck).
    pub capture_setup: Option<crate::output::atom_table::AtomTable>,
    pub want_capture: bool,
    /// Crosscheck checkpoints: state and forces at the end of steps first + 1, 2, 4, 8, ...
    /// (first: the step of the first run) and at the end of every run, in step order.
    pub capture_checkpoints: Vec<(i64, crate::output::atom_table::AtomTable)>,
    pub capture_first_step: Option<i64>,
    pub checked_runs: usize,
    pub guard: crate::sim::stability::Guard,
    /// Set from another thread (the Python module on Ctrl-C) to stop a run at the next step;
    /// the run ends with an error "run interrupted" and clears the flag.
    pub cancel: std::sync::Arc<std::sync::atomic::AtomicBool>,
    /// `min_style` and `min_modify`.
    pub min: minimize::MinSettings,
    /// What the last `minimize` did.
    pub min_stats: Option<minimize::MinStats>,
    /// Global fix states read by read_restart, for fixes defined later with the same ID and
    /// style; dropped at the next run, as LAMMPS drops what no fix took.
    pub restart_fixes: Vec<crate::models::fix::FixState>,
    /// The generator of random() and normal() in atom-style variables (made at first use).
    pub random_atom: crate::models::atom_formula::AtomRandom,
    /// The list build `State::rigid_mass` was made for.
    pub rigid_mass_build: Option<u64>,
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation::new()
    }
}

impl Simulation {
    pub fn new() -> Simulation {
        Simulation {
            state: State::new(),
            pair: None,
            pair_span: None,
            pair_modify: PairModify::default(),
            bond_style: None,
            angle_style: None,
            dihedral_style: None,
            ff_commands: Vec::new(),
            command_log: None,
            fixes: Vec::new(),
            computes: crate::models::compute::default_computes(),
            thermo: Thermo::default(),
            dumps: Vec::new(),
            variables: Variables::default(),
            out: Output::default(),
            timers: Timers::default(),
            last_loop_seconds: 0.0,
            loop_start: None,
            last_loop_steps: 0,
            runtime_failed: false,
            base_dir: None,
            capture_setup: None,
            want_capture: false,
            capture_checkpoints: Vec::new(),
            capture_first_step: None,
            checked_runs: 0,
            guard: Default::default(),
            cancel: Default::default(),
            min: Default::default(),
            min_stats: None,
            restart_fixes: Vec::new(),
            random_atom: None,
            rigid_mass_build: None,
        }
    }

    /// A file name from a command, resolved against `base_dir`.
    pub fn path(&self, name: &str) -> std::path::PathBuf {
        crate::output::log::resolve_path(self.base_dir.as_deref(), name)
    }

    pub fn find_fix(&self, id: &str) -> Option<usize> {
        self.fixes.iter().position(|f| f.id() == id)
    }
    pub fn find_compute(&self, id: &str) -> Option<usize> {
        self.computes.iter().position(|c| c.id() == id)
    }

    /// The once-per-run setup of computes `which` (all: None), e.g. a temperature's count of
    /// degrees of freedom (LAMMPS' compute setup); a compute's setup sees the computes defined
    /// before it (msd/chunk reads its chunk/atom).
    pub fn setup_computes(&mut self, which: Option<usize>) {
        let mut computes = std::mem::take(&mut self.computes);
        for k in 0..computes.len() {
            if which.is_some_and(|w| w != k) {
                continue;
            }
            let (before, rest) = computes.split_at_mut(k);
            let world = World { state: &self.state, computes: before, fixes: FixesView::all(&self.fixes), bond: self.bond_style.as_deref(), pair: self.pair.as_deref() };
            rest[0].setup(&world);
        }
        self.computes = computes;
    }

    /// The computes' setup that needs the atoms as the setup's list build left them
    /// ([`crate::models::compute::Compute::setup_after_build`]).
    pub(crate) fn setup_computes_after_build(&mut self) {
        let mut computes = std::mem::take(&mut self.computes);
        for k in 0..computes.len() {
            let (before, rest) = computes.split_at_mut(k);
            let world = World { state: &self.state, computes: before, fixes: FixesView::all(&self.fixes), bond: self.bond_style.as_deref(), pair: self.pair.as_deref() };
            rest[0].setup_after_build(&world);
        }
        self.computes = computes;
    }

    /// The seconds of the current run's loop so far; between runs, the last run's (LAMMPS'
    /// timer total, read by thermo's `cpu`).
    pub fn cpu_seconds(&self) -> f64 {
        self.loop_start.map_or(self.last_loop_seconds, |t| t.elapsed().as_secs_f64())
    }

    /// The read-only view of the whole simulation.
    pub fn world(&self) -> World<'_> {
        World { state: &self.state, computes: &self.computes, fixes: FixesView::all(&self.fixes), bond: self.bond_style.as_deref(), pair: self.pair.as_deref() }
    }

    /// The values of the thermo columns now.
    pub fn thermo_values(&mut self) -> Result<Vec<f64>, String> {
        let thermo = &self.thermo;
        let world = World { state: &self.state, computes: &self.computes, fixes: FixesView::all(&self.fixes), bond: self.bond_style.as_deref(), pair: self.pair.as_deref() };
        crate::output::thermo::values(thermo, &world, &mut Eval { world, thermo, variables: &mut self.variables, cpu: self.last_loop_seconds })
    }

    /// LAMMPS' `prematch` of every region that moves or has a variable shape: their variables
    /// evaluated now, so that what reads `state.regions` (fixes, computes, commands) finds each
    /// where it is at this step. LAMMPS evaluates them at each use; a variable of the time gives
    /// the same values, one that reads positions may not.
    /// `only`: that region alone (a command that names it).
    pub fn prematch_regions(&mut self, only: Option<&str>) -> Result<(), String> {
        let wanted = |r: &crate::engine::region::Region| r.is_dynamic() && only.is_none_or(|id| r.id == id);
        if !self.state.regions.iter().any(wanted) {
            return Ok(());
        }
        let mut regions = std::mem::take(&mut self.state.regions);
        let mut ev = self.eval();
        let mut result = Ok(());
        for r in regions.iter_mut().filter(|r| wanted(r)) {
            if let Err(e) = r.prematch(&mut |name| dmhs_parser::variables::compute_equal(&mut ev, name)) {
                result = Err(format!("region {}: {e}", r.id));
                break;
            }
        }
        self.state.regions = regions;
        result
    }

    /// The evaluation context of expressions, and the view it reads.
    pub fn eval(&mut self) -> Eval<'_> {
        Eval {
            world: World { state: &self.state, computes: &self.computes, fixes: FixesView::all(&self.fixes), bond: self.bond_style.as_deref(), pair: self.pair.as_deref() },
            thermo: &self.thermo,
            variables: &mut self.variables,
            cpu: self.last_loop_seconds,
        }
    }
}

/// A simulation evaluates expressions as its [`Eval`] does.
impl EvalContext for Simulation {
    fn variables(&mut self) -> &mut Variables {
        &mut self.variables
    }
    fn thermo_keyword(&mut self, name: &str) -> Option<Result<f64, String>> {
        self.eval().thermo_keyword(name)
    }
    fn compute_value(&mut self, id: &str, index: Option<usize>) -> Result<f64, String> {
        self.eval().compute_value(id, index)
    }
    fn fix_value(&mut self, id: &str, index: Option<usize>) -> Result<f64, String> {
        self.eval().fix_value(id, index)
    }
    fn compute_array_value(&mut self, id: &str, i: usize, j: usize) -> Result<f64, String> {
        self.eval().compute_array_value(id, i, j)
    }
    fn fix_array_value(&mut self, id: &str, i: usize, j: usize) -> Result<f64, String> {
        self.eval().fix_array_value(id, i, j)
    }
    fn global_values(&mut self, compute: bool, id: &str, column: Option<usize>) -> Result<Vec<f64>, String> {
        self.eval().global_values(compute, id, column)
    }
    fn peratom_element(&mut self, compute: bool, id: &str, column: Option<usize>, atom: i64) -> Result<f64, String> {
        self.eval().peratom_element(compute, id, column, atom)
    }
    fn atom_variable_element(&mut self, name: &str, atom: i64) -> Result<f64, String> {
        self.eval().atom_variable_element(name, atom)
    }
    fn vector_variable(&mut self, name: &str) -> Result<Vec<f64>, String> {
        self.eval().vector_variable(name)
    }
    fn group_function(&mut self, name: &str, args: &[String]) -> Option<Result<f64, String>> {
        self.eval().group_function(name, args)
    }
    fn atom_value(&mut self, keyword: &str, id: i64) -> Option<Result<f64, String>> {
        self.eval().atom_value(keyword, id)
    }
    fn run_window(&mut self) -> Option<(i64, i64)> {
        self.state.run_window
    }
}
