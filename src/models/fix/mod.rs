//! Fixes: operations applied to a group of atoms at fixed points of the time step
//! (LAMMPS' `Fix` hooks). Each style lives in its own file; [`new_fix`] is the registry.

pub mod addforce;
pub mod bond_break;
pub mod bond_create;
pub mod dmhs_cooling;
pub mod dmhs_phase;
pub mod dmhs_diffusion;
pub mod dmhs_stokes;
pub mod dmhs_swell;
pub mod value;
pub mod enforce2d;
pub mod gravity;
pub mod move_linear;
pub mod nve;
pub mod nve_sphere;
pub mod setforce;
pub mod sph;
pub mod viscous;
pub mod wall_gran;
pub mod wall_reflect;

use crate::sim::{RunError, Simulation};
use dmhs_parser::{Command, DResult, Word};

/// Where a fix acts in the step (LAMMPS' setmask bits), so the engine calls only what is used.
#[derive(Clone, Copy, Debug, Default)]
pub struct FixHooks {
    pub initial_integrate: bool,
    pub post_integrate: bool,
    pub post_force: bool,
    pub final_integrate: bool,
    pub end_of_step: bool,
}

pub trait Fix: Send {
    fn id(&self) -> &str;
    fn style(&self) -> &str;
    /// Bitmask of the fix group.
    fn groupbit(&self) -> u32;
    fn hooks(&self) -> FixHooks;
    /// Checks before a run (e.g. enforce2d in 3D); errors stop the run before it starts.
    fn init(&mut self, _sim: &Simulation) -> Result<(), String> {
        Ok(())
    }
    /// Called once per run before the forces of step 0 are computed (LAMMPS `setup_pre_force`).
    fn setup_pre_force(&mut self, _sim: &mut Simulation) -> Result<(), RunError> {
        Ok(())
    }
    /// Called once per run after the forces of step 0 (LAMMPS `setup`): by default
    /// fixes that modify forces apply `post_force`.
    fn setup(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        if self.hooks().post_force {
            self.post_force(sim)?;
        }
        Ok(())
    }
    fn initial_integrate(&mut self, _sim: &mut Simulation) -> Result<(), RunError> {
        Ok(())
    }
    fn post_integrate(&mut self, _sim: &mut Simulation) -> Result<(), RunError> {
        Ok(())
    }
    fn post_force(&mut self, _sim: &mut Simulation) -> Result<(), RunError> {
        Ok(())
    }
    fn final_integrate(&mut self, _sim: &mut Simulation) -> Result<(), RunError> {
        Ok(())
    }
    fn end_of_step(&mut self, _sim: &mut Simulation) -> Result<(), RunError> {
        Ok(())
    }
    /// Global scalar (`f_ID`), if the fix has one.
    fn scalar(&self, _sim: &Simulation) -> Option<f64> {
        None
    }
    /// Global vector element `f_ID[i]` (1-based), if the fix has one.
    fn vector(&self, _sim: &Simulation, _i: usize) -> Option<f64> {
        None
    }
    /// Degrees of freedom this fix removes from atoms of a group (for temperature).
    fn dof_removed(&self, _sim: &Simulation, _groupbit: u32) -> f64 {
        0.0
    }
    /// The phase-change equation of state, for fix dmhs/phase (read by compute dmhs/phase/atom).
    fn phase_eos(&self) -> Option<crate::models::fix::dmhs_phase::PhaseEos> {
        None
    }
    /// Free per-atom storage when the fix is deleted.
    fn cleanup(&mut self, _sim: &mut Simulation) {}
    /// Wall planes drawn by `dump image ... fix ID`: (axis, coordinate) at the current step.
    fn image_planes(&self, _sim: &mut Simulation) -> Result<Vec<(usize, f64)>, String> {
        Ok(vec![])
    }
    /// One-line description for `dmhs check`.
    fn describe(&self) -> String {
        format!("fix {} {}", self.id(), self.style())
    }
}

/// Run `work` over index ranges covering `0..n` (`chunk` indices each), in parallel when the
/// pool has several threads: for per-atom loops whose atoms are independent, so the results are
/// the same either way. With one thread it is one plain loop, without the pool's overhead.
pub fn for_each_range(n: usize, chunk: usize, work: impl Fn(std::ops::Range<usize>) + Sync + Send) {
    use rayon::prelude::*;
    if rayon::current_num_threads() == 1 || n <= chunk {
        work(0..n);
    } else {
        (0..n.div_ceil(chunk)).into_par_iter().with_max_len(1).for_each(|c| work(c * chunk..((c + 1) * chunk).min(n)));
    }
}

/// Indices per parallel work item of [`any_index`].
const ANY_CHUNK: usize = 4096;

/// Whether `bad(i)` holds for some i in `0..n`: chunks in parallel, each folded without
/// branches (so it vectorizes). The answer is a boolean, the same for every thread count.
pub fn any_index(n: usize, bad: impl Fn(usize) -> bool + Sync) -> bool {
    use rayon::prelude::*;
    let chunk_bad = |c: usize| (c * ANY_CHUNK..((c + 1) * ANY_CHUNK).min(n)).fold(false, |acc, i| acc | bad(i));
    let chunks = n.div_ceil(ANY_CHUNK);
    if rayon::current_num_threads() == 1 || chunks <= 1 {
        (0..chunks).any(chunk_bad)
    } else {
        (0..chunks).into_par_iter().any(chunk_bad)
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

/// Fix styles this build implements.
pub const SUPPORTED: &[&str] = &["nve", "nve/sphere", "gravity", "addforce", "setforce", "enforce2d", "viscous", "wall/reflect", "wall/gran", "move", "sph", "sph/stationary", "bond/break", "bond/create", "dmhs/bond/break", "dmhs/phase", "dmhs/cooling", "dmhs/diffusion", "dmhs/swell", "dmhs/stokes"];

/// Build a fix from `fix ID group style args...`.
pub fn new_fix(cmd: &Command, id: &Word, groupbit: u32, style: &Word, args: &[Word], sim: &mut Simulation) -> DResult<Box<dyn Fix>> {
    let id = id.text.clone();
    match style.text.as_str() {
        "nve" => Ok(Box::new(nve::FixNve::from_lammps(id, groupbit, args, cmd)?)),
        "nve/sphere" => Ok(Box::new(nve_sphere::FixNveSphere::from_lammps(id, groupbit, args, cmd, sim)?)),
        "gravity" => Ok(Box::new(gravity::FixGravity::from_lammps(id, groupbit, args, cmd, sim)?)),
        "addforce" => Ok(Box::new(addforce::FixAddForce::from_lammps(id, groupbit, args, cmd, sim)?)),
        "setforce" => Ok(Box::new(setforce::FixSetForce::from_lammps(id, groupbit, args, cmd, sim)?)),
        "enforce2d" => Ok(Box::new(enforce2d::FixEnforce2d::from_lammps(id, groupbit, args, cmd)?)),
        "viscous" => Ok(Box::new(viscous::FixViscous::from_lammps(id, groupbit, args, cmd, sim)?)),
        "wall/reflect" => Ok(Box::new(wall_reflect::FixWallReflect::from_lammps(id, groupbit, args, cmd, sim)?)),
        "wall/gran" => Ok(Box::new(wall_gran::FixWallGran::from_lammps(id, groupbit, args, cmd, sim)?)),
        "move" => Ok(Box::new(move_linear::FixMove::from_lammps(id, groupbit, args, cmd, sim)?)),
        "sph" | "sph/stationary" => Ok(Box::new(sph::FixSph::from_lammps(id, groupbit, style, args, cmd, sim)?)),
        "bond/break" | "dmhs/bond/break" => Ok(Box::new(bond_break::FixBondBreak::from_lammps(id, groupbit, style, args, cmd, sim)?)),
        "bond/create" => Ok(Box::new(bond_create::FixBondCreate::from_lammps(id, groupbit, style, args, cmd, sim)?)),
        "dmhs/phase" => Ok(Box::new(dmhs_phase::FixDmhsPhase::from_lammps(id, groupbit, style, args, cmd, sim)?)),
        "dmhs/cooling" => Ok(Box::new(dmhs_cooling::FixDmhsCooling::from_lammps(id, groupbit, style, args, cmd, sim)?)),
        "dmhs/diffusion" => Ok(Box::new(dmhs_diffusion::FixDiffusion::from_lammps(id, groupbit, style, args, cmd, sim)?)),
        "dmhs/swell" => Ok(Box::new(dmhs_swell::FixSwell::from_lammps(id, groupbit, style, args, cmd, sim)?)),
        "dmhs/stokes" => Ok(Box::new(dmhs_stokes::FixStokes::from_lammps(id, groupbit, style, args, cmd, sim)?)),
        other => Err(crate::models::styles::unsupported_style("fix", style, other, SUPPORTED)),
    }
}
