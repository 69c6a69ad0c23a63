//! Fixes: operations applied to a group of atoms at fixed points of the time step
//! (LAMMPS' `Fix` hooks). Each style lives in its own file; [`new_fix`] is the registry.

pub mod adapt;
pub mod addforce;
pub mod aveforce;
pub mod box_relax;
pub mod box_stress;
pub mod deform;
pub mod ave_atom;
pub mod ave_chunk;
pub mod ave_histo;
pub mod ave_correlate;
pub mod ave_time;
pub mod balance;
pub mod bond_break;
pub mod bond_create;
pub mod dmhs_cooling;
pub mod dmhs_phase;
pub mod dmhs_diffusion;
pub mod dmhs_stokes;
pub mod dmhs_swell;
pub mod dt_reset;
pub mod ehex;
pub mod value;
pub mod deposit;
pub mod enforce2d;
pub mod freeze;
pub mod gravity;
pub mod group_dynamic;
pub mod halt;
pub mod heat;
pub mod heat_flow;
pub mod indent;
pub mod langevin;
pub mod momentum;
#[path = "move.rs"]
pub mod moves;
pub mod nve;
pub mod nve_bpm_sphere;
pub mod nve_sphere;
pub mod nh;
pub mod pour;
pub mod sampling;
pub mod print;
pub mod property_atom;
pub mod recenter;
pub mod rigid;
pub mod rigid_nh_small;
pub mod rigid_small;
pub mod setforce;
pub mod slab_swaps;
pub mod sph;
pub mod spring;
pub mod spring_rg;
pub mod spring_self;
pub mod store_local;
pub mod temp_csvr;
pub mod temp_scale;
pub mod thermal_conductivity;
pub mod thermostat;
pub mod vector;
pub mod viscosity;
pub mod viscous;
pub mod wall_gran;
pub mod wall_colloid;
pub mod wall_flat;
pub mod wall_gran_region;
pub mod wall_harmonic;
pub mod wall_lj1043;
pub mod wall_lj126;
pub mod wall_lj93;
pub mod wall_morse;
pub mod wall_region;
pub mod wall_reflect;

use crate::engine::state::{RunError, State};

/// One fix's global state in a restart file: the numbers of LAMMPS' write_restart of that
/// style, restored to a fix of the same ID and style defined after read_restart.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixState {
    pub id: String,
    pub style: String,
    pub values: Vec<f64>,
}
use crate::models::bonded::{AngleStyle, BondStyle};
use crate::models::pair::PairStyle;
use crate::models::compute::Compute;
use crate::models::world::World;
use dmhs_parser::{Command, DResult, EvalContext, Word};

/// Where a fix acts in the step (LAMMPS' setmask bits), so the engine calls only what is used.
#[derive(Clone, Copy, Debug, Default)]
pub struct FixHooks {
    pub initial_integrate: bool,
    /// Before atoms are wrapped, sorted and given ghosts, on steps that rebuild the lists
    /// (where insertions happen).
    pub pre_exchange: bool,
    pub post_integrate: bool,
    pub post_force: bool,
    /// Before the forces of a step, after the neighbour lists (LAMMPS' pre_force; fix adapt).
    pub pre_force: bool,
    /// After pair granular mdr's work before the forces, outside a run's setup (a region wall
    /// with the mdr model: LAMMPS' fix GRANULAR/MDR updates it last in its pre_force).
    pub mdr_pre_force: bool,
    pub final_integrate: bool,
    pub end_of_step: bool,
}

/// Evaluates expressions for a fix while its hook runs, with every fix, compute and variable
/// visible (implemented by the simulation, which owns them).
pub trait Expressions {
    /// The value of equal-style variable `name` now; `running` is the fix whose hook asks.
    fn equal(&mut self, state: &State, running: &dyn Fix, name: &str) -> Result<f64, String>;
    /// Run `work` with the read-only view of everything (computes, fixes) and an expression
    /// context, for fixes that read `c_`, `f_` and `v_` values (fix ave/time, fix print).
    fn with_eval(&mut self, state: &State, running: &dyn Fix, work: &mut dyn FnMut(&World, &mut dyn EvalContext) -> Result<(), String>) -> Result<(), String>;
}

/// What a fix hook may use besides the state: the force-field models (read only) and
/// expression evaluation.
pub struct FixCtx<'a> {
    /// The other fixes: those defined before and after the running one.
    pub others: [&'a [Box<dyn Fix>]; 2],
    pub pair: Option<&'a dyn PairStyle>,
    pub bond_style: Option<&'a dyn BondStyle>,
    pub angle_style: Option<&'a dyn AngleStyle>,
    pub expressions: &'a mut dyn Expressions,
}

/// LAMMPS' init checks of a fix that inserts molecules as rigid bodies (`who`: pour,
/// deposit): the rigid fix `fix_id` exists, is of the rigid/small family and makes its bodies
/// from the same molecule template.
pub fn check_rigid_insert(ctx: &FixCtx, who: &str, fix_id: &str, template: &str) -> Result<(), String> {
    let f = ctx.other_fixes().find(|f| f.id() == fix_id).ok_or_else(|| format!("fix {who} rigid fix ID {fix_id} does not exist"))?;
    let Some(t) = f.rigid_template() else { return Err(format!("fix {who} rigid fix {fix_id} ({}) is not a rigid/small fix", f.style())) };
    if t != template {
        return Err(format!("fix {who} and fix rigid/small not using same molecule template ID"));
    }
    Ok(())
}

impl FixCtx<'_> {
    /// The other fixes in definition order.
    pub fn other_fixes(&self) -> impl Iterator<Item = &dyn Fix> {
        self.others.into_iter().flatten().map(|f| f.as_ref())
    }
    /// The value of equal-style variable `name`; pass the calling fix as `running` (a variable
    /// may read that fix's own values, as in LAMMPS).
    pub fn equal(&mut self, state: &State, running: &dyn Fix, name: &str) -> Result<f64, String> {
        self.expressions.equal(state, running, name)
    }
    /// `work` with the view of every compute, fix and variable (see [`Expressions::with_eval`]).
    pub fn eval<R>(&mut self, state: &State, running: &dyn Fix, work: impl FnOnce(&World, &mut dyn EvalContext) -> Result<R, String>) -> Result<R, RunError> {
        let mut work = Some(work);
        let mut out = None;
        self.expressions
            .with_eval(state, running, &mut |w, ev| {
                out = Some(work.take().expect("called once")(w, ev)?);
                Ok(())
            })
            .map_err(|e| RunError::new(state.step, e))?;
        Ok(out.expect("with_eval runs its work"))
    }
    /// The current value of a fix argument (None for NULL), evaluated as [`FixCtx::equal`].
    pub fn value(&mut self, state: &State, running: &dyn Fix, v: &value::FixValue) -> Result<Option<f64>, RunError> {
        v.eval(&mut |name| self.expressions.equal(state, running, name)).map_err(|e| RunError::new(state.step, e))
    }
    /// The current value of a fix argument that may also be an atom-style variable (one value
    /// per local atom), as LAMMPS' fixes that take both (addforce, setforce).
    pub fn value_per_atom(&mut self, state: &State, running: &dyn Fix, v: &value::FixValue) -> Result<value::Evaluated, RunError> {
        let value::FixValue::Variable(name) = v else {
            return Ok(self.value(state, running, v)?.map_or(value::Evaluated::Null, value::Evaluated::One));
        };
        let what = format!("fix {} {}", running.style(), running.id());
        match self.eval(state, running, |_, ev| Ok(ev.variables().style(name)))? {
            None => Err(RunError::new(state.step, format!("{what}: Variable name for fix {} does not exist (v_{name})", running.style()))),
            Some("atom" | "atomfile") => {
                let vals = self.eval(state, running, |w, ev| crate::models::atom_formula::atom_variable(name, w, ev).map_err(|e| format!("{what}: {e}")))?;
                Ok(value::Evaluated::PerAtom(vals))
            }
            Some(_) => Ok(value::Evaluated::One(self.equal(state, running, name).map_err(|e| RunError::new(state.step, format!("{what}: variable `{name}`: {e}")))?)),
        }
    }
}

/// What a fix does during `minimize` (LAMMPS calls only a fix's min_* hooks there).
#[derive(Clone, Debug, PartialEq)]
pub enum MinRole {
    /// No minimization hook in LAMMPS: the fix does nothing while minimizing (integrators,
    /// thermostats, output fixes).
    Inert,
    /// LAMMPS' min_setup and min_post_force are its setup and post_force: applied after each
    /// force evaluation.
    PostForce,
    /// Refused, with the reason (acts on forces or energy in LAMMPS' minimizer, not here).
    Refused(String),
}

/// A fix that adds global degrees of freedom to the minimizer (LAMMPS' MIN_ENERGY fixes: fix
/// box/relax). `fextra` and `hextra` are the fix's own slice of the minimizer's extra force and
/// search direction.
pub trait MinExtra {
    /// How many degrees of freedom (LAMMPS' min_dof).
    fn min_dof(&self) -> usize;
    /// Their energy, and their forces into `fextra`, from the virial of the last force
    /// evaluation (LAMMPS' min_energy).
    fn min_energy(&mut self, state: &State, virial: &[f64; 6], fextra: &mut [f64]) -> Result<f64, String>;
    /// Keep their values where a line search starts (LAMMPS' min_store).
    fn min_store(&mut self, state: &State) -> Result<(), String>;
    /// Set them to the stored start plus alpha hextra, moving what depends on them (LAMMPS'
    /// min_step).
    fn min_step(&mut self, state: &mut State, alpha: f64, hextra: &[f64]) -> Result<(), String>;
    /// The largest alpha they allow along hextra (LAMMPS' max_alpha).
    fn max_alpha(&self, hextra: &[f64]) -> f64;
    /// After a successful line search: renew the reference state if due (`begin` is the first
    /// step of the minimization); true if it was renewed (LAMMPS' min_reset_ref).
    fn min_reset_ref(&mut self, state: &State, begin: i64) -> Result<bool, String>;
}

/// What a fix may add to thermo's energy and pressure (LAMMPS' energy_global_flag and
/// virial_global_flag; `fix_modify energy yes` and `virial yes` switch them on, both off by
/// default for every fix dmhs has). Only fixes that own one accept `fix_modify energy`.
#[derive(Clone, Debug, Default)]
pub struct ThermoTally {
    /// The fix tallies a virial (LAMMPS' virial_global_flag).
    pub has_virial: bool,
    /// The fix has no energy (LAMMPS' energy_global_flag unset: the rigid fixes).
    pub no_energy: bool,
    /// `fix_modify energy yes`: the fix's scalar counts in pe (LAMMPS' thermo_energy).
    pub energy: bool,
    /// `fix_modify virial yes`: [`ThermoTally::virial`] counts in the pressure.
    pub virial_on: bool,
    /// The virial of the fix's last force application (xx yy zz xy xz yz).
    pub virial: [f64; 6],
}

impl ThermoTally {
    pub fn new(has_virial: bool) -> ThermoTally {
        ThermoTally { has_virial, ..ThermoTally::default() }
    }
    /// A force application starts (LAMMPS' v_init): the virial restarts if it is used.
    pub fn v_init(&mut self) {
        if self.virial_on {
            self.virial = [0.0; 6];
        }
    }
    /// One diagonal term `n` (LAMMPS' v_tally(n, i, vn), flat walls).
    #[inline]
    pub fn v_tally_n(&mut self, n: usize, vn: f64) {
        if self.virial_on {
            self.virial[n] += vn;
        }
    }
    /// A whole virial term (LAMMPS' v_tally(i, v)).
    #[inline]
    pub fn v_tally(&mut self, v: [f64; 6]) {
        if self.virial_on {
            for k in 0..6 {
                self.virial[k] += v[k];
            }
        }
    }
}

pub trait Fix: Send + Sync {
    /// The fix's part in `minimize`; by default a fix that changes forces is refused (LAMMPS
    /// applies many of them through hooks dmhs' fixes do not have).
    fn min_role(&self) -> MinRole {
        match self.hooks().post_force {
            true => MinRole::Refused(format!("fix {} ({}) acts on forces; dmhs' minimize supports fix setforce, aveforce, enforce2d, addforce, indent, spring, spring/self, viscous, wall/* and wall/region", self.id(), self.style())),
            false => MinRole::Inert,
        }
    }
    fn id(&self) -> &str;
    fn style(&self) -> &str;
    /// Extra degrees of freedom of the minimizer (fix box/relax); None for the other fixes.
    fn min_extra(&mut self) -> Option<&mut dyn MinExtra> {
        None
    }
    /// The fix changes the box or the sub-domains (LAMMPS' box_change flags): thermo style one
    /// then prints the volume.
    fn changes_box(&self) -> bool {
        false
    }
    /// Bitmask of the fix group.
    fn groupbit(&self) -> u32;
    fn hooks(&self) -> FixHooks;
    /// Checks before a run (e.g. enforce2d in 3D); errors stop the run before it starts.
    fn init(&mut self, _state: &State, _ctx: &FixCtx) -> Result<(), String> {
        Ok(())
    }
    /// The box's rate of change the fix sets at its init (fix deform: LAMMPS' h_rate, and the
    /// group of `remap v`); None for the other fixes.
    fn box_rate(&self) -> Option<crate::engine::domain::BoxRate> {
        None
    }
    /// What fix deform's `remap` moves with the box; None for the other fixes.
    fn deform_remap(&self) -> Option<deform::Remap> {
        None
    }
    /// The warnings LAMMPS prints when a run starts, given the fixes defined before and after
    /// this one.
    fn init_warnings(&self, _others: [&[Box<dyn Fix>]; 2]) -> Vec<String> {
        Vec::new()
    }
    /// Called once per run before the forces of step 0 are computed (LAMMPS `setup_pre_force`).
    fn setup_pre_force(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    /// Called once per run after the forces of step 0 (LAMMPS `setup`): by default
    /// fixes that modify forces apply `post_force`.
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if self.hooks().post_force {
            self.post_force(state, ctx)?;
        }
        Ok(())
    }
    fn initial_integrate(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    fn post_integrate(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    fn pre_exchange(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    /// The step on which this fix needs the lists rebuilt (LAMMPS `next_reneighbor` of a fix
    /// with `force_reneighbor`), if any.
    fn next_reneighbor(&self) -> Option<i64> {
        None
    }
    /// Whether this fix reads values on `step` that need the energies and virial of that step
    /// (LAMMPS' `addstep_compute`: fix ave/time and fix print ask for their output steps).
    fn wants_energy(&self, _step: i64) -> bool {
        false
    }
    /// Steps between which the fix's global values are current (LAMMPS' global_freq): thermo
    /// output must come on multiples of it.
    fn global_freq(&self) -> i64 {
        1
    }
    /// Per-atom values (owned atoms, local order), for dumps and compute reduce (`f_ID[N]`).
    fn peratom(&self, _state: &State) -> Result<crate::models::compute::PerAtom, String> {
        Err(format!("fix {} ({}) does not compute per-atom values", self.id(), self.style()))
    }
    /// Columns of per-atom output (None: not per-atom).
    fn peratom_cols(&self) -> Option<usize> {
        None
    }
    /// Length of the global vector (for `mode vector` of fix ave/time), 0 if none.
    fn size_vector(&self) -> usize {
        0
    }
    /// Gravity this fix applies (fix gravity), for fixes that insert falling particles.
    fn gravity(&self) -> Option<gravity::Gravity> {
        None
    }
    /// Largest radius of the particles of type `itype` this fix will insert (LAMMPS
    /// `extract("radius")`), so that granular cutoffs cover atoms that do not exist yet.
    fn insert_radius(&self, _itype: usize) -> f64 {
        0.0
    }
    fn post_force(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    /// See [`FixHooks::pre_force`].
    fn pre_force(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    /// At the end of a run (LAMMPS' post_run; fix adapt restores its parameters).
    fn post_run(&mut self, _state: &mut State) {}
    /// See [`FixHooks::mdr_pre_force`].
    fn mdr_pre_force(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    fn final_integrate(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    fn end_of_step(&mut self, _state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        Ok(())
    }
    /// Global scalar (`f_ID`), if the fix has one.
    fn scalar(&self, _state: &State) -> Option<f64> {
        None
    }
    /// Global vector element `f_ID[i]` (1-based), if the fix has one.
    fn vector(&self, _state: &State, _i: usize) -> Option<f64> {
        None
    }
    /// Global array element `f_ID[i][j]` (1-based), if the fix has an array.
    fn array(&self, _state: &State, _i: usize, _j: usize) -> Option<f64> {
        None
    }
    /// Rows and columns of the global array, if the fix has one.
    fn size_array(&self) -> Option<(usize, usize)> {
        None
    }
    /// Whether the global array is extensive (LAMMPS' extarray).
    fn array_extensive(&self) -> bool {
        false
    }
    /// Whether the global scalar (`index` None) or vector element `index` (1-based) is
    /// extensive: thermo output divides it by the atom count under `thermo_modify norm yes`.
    fn extensive(&self, _index: Option<usize>) -> bool {
        false
    }
    /// A rigid fix: per atom (owned and ghost), the mass of its rigid body, 0 outside bodies
    /// (LAMMPS' extract "body" and "masstotal", read by granular pairs and walls).
    fn rigid_body_mass(&self, _state: &State) -> Option<Vec<f64>> {
        None
    }
    /// The fix moves atoms in time (LAMMPS' time_integrate: the nve family, the Nose-Hoover
    /// fixes, the rigid fixes, fix move, fix sph); a run with none warns that atoms won't move.
    fn time_integrate(&self) -> bool {
        false
    }
    /// A rigid fix: its bodies' translational and rotational kinetic energies without mvv2e,
    /// 1/2 sum M vcm^2 and 1/2 sum I w_body^2 (LAMMPS' extract_ke, extract_erotational).
    fn rigid_kinetic(&self) -> Option<[f64; 2]> {
        None
    }
    /// `fix_modify ID dynamic/dof yes|no` (LAMMPS' Fix::dynamic): fixes that count degrees of
    /// freedom of their own recount them every step. Others ignore it.
    fn set_dynamic_dof(&mut self, _on: bool) {}
    /// `fix_modify ID bodyforces early|late` (the rigid fixes' modify_param); others refuse.
    fn set_body_forces_early(&mut self, _early: bool) -> Result<(), String> {
        Err(format!("fix {} ({}) does not support fix_modify bodyforces (a keyword of the rigid fixes)", self.id(), self.style()))
    }
    /// A rigid fix: the molecule template its inserted bodies are made from (`mol TEMPLATE`;
    /// LAMMPS' extract("onemol")), `Some("")` without one. `None`: not a rigid fix.
    fn rigid_template(&self) -> Option<&str> {
        None
    }
    /// A rigid fix: make a body of a molecule another fix has just inserted (LAMMPS'
    /// set_molecule). Other fixes refuse.
    fn add_rigid_molecule(&mut self, _state: &State, _insert: &crate::engine::molecule::RigidInsert) -> Result<(), String> {
        Err(format!("fix {} ({}) does not make rigid bodies of inserted molecules", self.id(), self.style()))
    }
    /// The fix's scalar is energy it exchanged with a reservoir (LAMMPS' ecouple_flag: the
    /// thermostats and barostats), summed by thermo's `ecouple` and `econserve`.
    fn couples_energy(&self) -> bool {
        false
    }
    /// Degrees of freedom this fix removes from atoms of a group (for temperature).
    fn dof_removed(&self, _state: &State, _groupbit: u32) -> f64 {
        0.0
    }
    /// The phase-change equation of state, for fix dmhs/phase (read by compute dmhs/phase/atom).
    fn phase_eos(&self) -> Option<crate::models::fix::dmhs_phase::PhaseEos> {
        None
    }
    /// `fix_modify ID temp CID`: measure the temperature as compute CID does (its group, extra
    /// degrees of freedom and velocity bias).
    fn modify_temp(&mut self, _spec: crate::models::compute::temp_bias::TempSpec) -> Result<(), String> {
        Err(format!("fix {} ({}) has no temperature to replace", self.id(), self.style()))
    }
    /// The fix's energy and virial for thermo (None: it tallies neither, and `fix_modify
    /// energy`/`virial` refuse it). Its energy is its scalar.
    fn thermo_tally(&self) -> Option<&ThermoTally> {
        None
    }
    fn thermo_tally_mut(&mut self) -> Option<&mut ThermoTally> {
        None
    }
    /// dt changed (`timestep` between runs, fix dt/reset during one; LAMMPS' reset_dt): `state`
    /// has the new dt; a fix renews what it made from dt, or refuses the change with an error.
    fn reset_dt(&mut self, _state: &State) -> Result<(), String> {
        Ok(())
    }
    /// Free per-atom storage when the fix is deleted.
    fn cleanup(&mut self, _state: &mut State) {}
    /// The fix's global state for a restart file (LAMMPS' write_restart of the style, same
    /// numbers); None when the style stores none.
    fn write_restart(&self) -> Option<Vec<f64>> {
        None
    }
    /// Take the state of [`Fix::write_restart`] from a restart file (LAMMPS' restart), given
    /// to a fix of the same ID and style defined after read_restart.
    fn restart(&mut self, _values: &[f64]) {}
    /// Wall planes drawn by `dump image ... fix ID`: (axis, coordinate) at the current step.
    /// `equal` evaluates an equal-style variable by name.
    fn image_planes(&self, _state: &State, _equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<Vec<(usize, f64)>, String> {
        Ok(vec![])
    }
    /// One-line description for `dmhs check`.
    /// The internal fix STORE/LOCAL of a BPM bond style.
    fn as_store_local(&mut self) -> Option<&mut store_local::FixStoreLocal> {
        None
    }
    /// Local data for `dump local`: the rows, the number of columns (0: a local vector) and
    /// how often the rows are renewed (LAMMPS' `local_freq`).
    fn local(&self) -> Option<(&[Vec<f64>], usize, i64)> {
        None
    }
    /// A section of a data file given to this fix by `read_data ... fix ID NULL Section`
    /// (LAMMPS' read_data_section), its atom IDs shifted by `id_offset`.
    fn read_data_section(&mut self, _state: &mut State, section: &dmhs_parser::data_file::FixSection, _id_offset: i64) -> DResult<()> {
        let span = section.lines.first().map(|l| l.0).unwrap_or_default();
        Err(dmhs_parser::Diagnostic::at(span, format!("fix {} ({}) reads no data file sections (section {})", self.id(), self.style(), section.name), "not read by this fix"))
    }
    fn describe(&self) -> String {
        format!("fix {} {}", self.id(), self.style())
    }
}

/// Half kick v += dtfm f, component by component (LAMMPS' arithmetic).
#[inline(always)]
pub fn kick(v: &mut [f64; 3], dtfm: f64, f: &[f64; 3]) {
    v[0] += dtfm * f[0];
    v[1] += dtfm * f[1];
    v[2] += dtfm * f[2];
}

/// dtf/m for each type's mass (empty with per-atom masses): the same division LAMMPS makes per
/// atom, made once per type, so the same bits.
pub fn dtfm_by_type(dtf: f64, type_mass: &[f64], per_atom: bool) -> Vec<f64> {
    if per_atom {
        Vec::new()
    } else {
        type_mass.iter().map(|&m| dtf / m).collect()
    }
}

/// Drift x += dt v.
#[inline(always)]
pub fn drift(x: &mut [f64; 3], dt: f64, v: &[f64; 3]) {
    x[0] += dt * v[0];
    x[1] += dt * v[1];
    x[2] += dt * v[2];
}

/// The group bit of fix freeze among `fixes` (0: none), which granular contacts read
/// (LAMMPS' freeze_group_bit).
pub fn freeze_bit<'a>(mut fixes: impl Iterator<Item = &'a dyn Fix>) -> u32 {
    fixes.find(|f| f.style() == "freeze").map_or(0, |f| f.groupbit())
}

/// What `fix ID group style args...` gives a fix's constructor.
pub struct FixDef<'a> {
    pub cmd: &'a Command,
    /// The fixes defined so far.
    pub fixes: &'a [Box<dyn Fix>],
    /// The computes defined so far.
    pub computes: &'a [Box<dyn Compute>],
    /// Directory for relative file names (None: the working directory).
    pub base_dir: Option<&'a std::path::Path>,
    /// The values over the owned atoms of an atom-style variable the fix takes as an argument
    /// when it is defined (fix rigid `custom v_name`), evaluated by the fix command.
    pub atom_values: Option<&'a [f64]>,
    pub id: String,
    pub groupbit: u32,
    pub style: &'a Word,
    pub args: &'a [Word],
}

type FixCtor = fn(FixDef, &mut State) -> DResult<Box<dyn Fix>>;

/// Every fix style this build implements.
const STYLES: &[(&str, FixCtor)] = &[
    ("nve", |d, _| Ok(Box::new(nve::FixNve::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("nve/sphere", |d, state| Ok(Box::new(nve_sphere::FixNveSphere::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("nve/bpm/sphere", |d, state| Ok(Box::new(nve_bpm_sphere::FixNveBpmSphere::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("gravity", |d, state| Ok(Box::new(gravity::FixGravity::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("addforce", |d, state| Ok(Box::new(addforce::FixAddForce::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("setforce", |d, state| Ok(Box::new(setforce::FixSetForce::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("adapt", |d, state| Ok(Box::new(adapt::FixAdapt::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("aveforce", |d, state| Ok(Box::new(aveforce::FixAveForce::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("box/relax", |d, state| Ok(Box::new(box_relax::FixBoxRelax::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("deform", |d, state| Ok(Box::new(deform::FixDeform::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("freeze", |d, state| Ok(Box::new(freeze::FixFreeze::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("enforce2d", |d, _| Ok(Box::new(enforce2d::FixEnforce2d::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("viscous", |d, state| Ok(Box::new(viscous::FixViscous::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("vector", |d, state| Ok(Box::new(vector::FixVector::from_lammps(d, state)?))),
    ("momentum", |d, _| Ok(Box::new(momentum::FixMomentum::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("wall/reflect", |d, state| Ok(Box::new(wall_reflect::FixWallReflect::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("wall/gran", |d, state| Ok(Box::new(wall_gran::FixWallGran::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("wall/gran/region", |d, state| Ok(Box::new(wall_gran_region::FixWallGranRegion::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("balance", |d, state| Ok(Box::new(balance::FixBalance::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("ave/atom", |d, state| Ok(Box::new(ave_atom::FixAveAtom::from_lammps(d, state)?))),
    ("ave/chunk", |d, state| Ok(Box::new(ave_chunk::FixAveChunk::from_lammps(d, state)?))),
    ("ave/time", |d, state| Ok(Box::new(ave_time::FixAveTime::from_lammps(d, state)?))),
    ("ave/correlate", |d, state| Ok(Box::new(ave_correlate::FixAveCorrelate::from_lammps(d, state)?))),
    ("print", |d, state| Ok(Box::new(print::FixPrint::from_lammps(d, state)?))),
    ("recenter", |d, state| Ok(Box::new(recenter::FixRecenter::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("spring/rg", |d, _| Ok(Box::new(spring_rg::FixSpringRg::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("ave/histo", |d, state| Ok(Box::new(ave_histo::FixAveHisto::from_lammps(d, state)?))),
    ("halt", |d, _| Ok(Box::new(halt::FixHalt::from_lammps(d)?))),
    ("spring", |d, state| Ok(Box::new(spring::FixSpring::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("spring/self", |d, state| Ok(Box::new(spring_self::FixSpringSelf::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("wall/lj93", |d, state| Ok(Box::new(wall_flat::FixWall::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("wall/lj126", |d, state| Ok(Box::new(wall_flat::FixWall::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("wall/lj1043", |d, state| Ok(Box::new(wall_flat::FixWall::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("wall/harmonic", |d, state| Ok(Box::new(wall_flat::FixWall::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("wall/morse", |d, state| Ok(Box::new(wall_flat::FixWall::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("wall/region", |d, state| Ok(Box::new(wall_region::FixWallRegion::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("indent", |d, state| Ok(Box::new(indent::FixIndent::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("pour", |d, state| Ok(Box::new(pour::FixPour::from_lammps(d, state)?))),
    ("deposit", |d, state| Ok(Box::new(deposit::FixDeposit::from_lammps(d, state)?))),
    ("move", |d, state| {
        let replacing = d.fixes.iter().any(|f| f.id() == d.id);
        Ok(Box::new(moves::FixMove::from_lammps(d.id, d.groupbit, d.args, d.cmd, replacing, state)?))
    }),
    ("sph", |d, state| Ok(Box::new(sph::FixSph::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("sph/stationary", |d, state| Ok(Box::new(sph::FixSph::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("bond/break", |d, state| Ok(Box::new(bond_break::FixBondBreak::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("dmhs/bond/break", |d, state| Ok(Box::new(bond_break::FixBondBreak::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("bond/create", |d, state| Ok(Box::new(bond_create::FixBondCreate::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("dmhs/phase", |d, state| Ok(Box::new(dmhs_phase::FixDmhsPhase::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("dmhs/cooling", |d, state| Ok(Box::new(dmhs_cooling::FixDmhsCooling::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("dmhs/diffusion", |d, state| Ok(Box::new(dmhs_diffusion::FixDiffusion::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("dmhs/swell", |d, state| Ok(Box::new(dmhs_swell::FixSwell::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("langevin", |d, state| Ok(Box::new(langevin::FixLangevin::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("dt/reset", |d, state| Ok(Box::new(dt_reset::FixDtReset::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("temp/rescale", |d, _| Ok(Box::new(temp_scale::FixTempScale::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd)?))),
    ("temp/berendsen", |d, _| Ok(Box::new(temp_scale::FixTempScale::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd)?))),
    ("temp/csvr", |d, _| Ok(Box::new(temp_scale::FixTempScale::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd)?))),
    ("nvt", |d, state| Ok(Box::new(nh::FixNh::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("nvt/sllod", |d, state| Ok(Box::new(nh::FixNh::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("npt", |d, state| Ok(Box::new(nh::FixNh::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("nph", |d, state| Ok(Box::new(nh::FixNh::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
    ("property/atom", |d, state| Ok(Box::new(property_atom::FixPropertyAtom::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("ehex", |d, state| Ok(Box::new(ehex::FixEhex::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("viscosity", |d, _| Ok(Box::new(viscosity::FixViscosity::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("thermal/conductivity", |d, _| Ok(Box::new(thermal_conductivity::FixThermalConductivity::from_lammps(d.id, d.groupbit, d.args, d.cmd)?))),
    ("heat", |d, state| Ok(Box::new(heat::FixHeat::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("heat/flow", |d, state| Ok(Box::new(heat_flow::FixHeatFlow::from_lammps(d.id, d.groupbit, d.args, d.cmd, state)?))),
    ("rigid/small", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/small", state)?))),
    ("rigid/nve/small", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/nve/small", state)?))),
    ("rigid/nvt/small", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/nvt/small", state)?))),
    ("rigid/npt/small", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/npt/small", state)?))),
    ("rigid/nph/small", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/nph/small", state)?))),
    ("rigid", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid", state)?))),
    ("rigid/nve", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/nve", state)?))),
    ("rigid/nvt", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/nvt", state)?))),
    ("rigid/npt", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/npt", state)?))),
    ("rigid/nph", |d, state| Ok(Box::new(rigid_small::FixRigidSmall::from_lammps(d, "rigid/nph", state)?))),
    ("dmhs/stokes", |d, state| Ok(Box::new(dmhs_stokes::FixStokes::from_lammps(d.id, d.groupbit, d.style, d.args, d.cmd, state)?))),
];

impl FixDef<'_> {
    /// A file name of the fix's arguments, relative to the deck's directory if one is set.
    pub fn path(&self, name: &str) -> std::path::PathBuf {
        match self.base_dir {
            Some(d) if std::path::Path::new(name).is_relative() => d.join(name),
            _ => std::path::PathBuf::from(name),
        }
    }
}

/// What is defined when a fix is made.
pub struct Defined<'a> {
    pub fixes: &'a [Box<dyn Fix>],
    pub computes: &'a [Box<dyn Compute>],
    pub base_dir: Option<&'a std::path::Path>,
    /// See [`FixDef::atom_values`].
    pub atom_values: Option<&'a [f64]>,
}

/// Build a fix from `fix ID group style args...`; `defined` are the fixes and computes so far.
pub fn new_fix(cmd: &Command, id: &Word, groupbit: u32, style: &Word, args: &[Word], defined: Defined, state: &mut State) -> DResult<Box<dyn Fix>> {
    match STYLES.iter().find(|(n, _)| *n == style.text) {
        Some((_, ctor)) => ctor(FixDef { cmd, fixes: defined.fixes, computes: defined.computes, base_dir: defined.base_dir, atom_values: defined.atom_values, id: id.text.clone(), groupbit, style, args }, state),
        None => Err(crate::models::styles::unsupported_style("fix", style, &style.text, &supported())),
    }
}

/// Names of the fix styles this build implements.
pub fn supported() -> Vec<&'static str> {
    STYLES.iter().map(|(n, _)| *n).collect()
}
