//! The time step, read top to bottom as LAMMPS' Verlet integrator does it:
//! initial integrate -> (rebuild | refresh ghosts) -> forces -> post-force -> final integrate
//! -> output. Each stage is timed.

use crate::models::bonded::pass::BondedStyles;
use crate::models::fix::{Fix, FixCtx, FixHooks};
use crate::models::world::{FixesView, World};
use crate::sim::eval::{Eval, HookExpressions};
use crate::engine::lammps_order::Sort;
use crate::engine::neighbor::NeighError;
use crate::models::pair::{PairInput, PairOutput, Tally};
use crate::sim::{Energies, RunError, SetupError, Simulation, State};
use crate::engine::fields::Field;
use crate::engine::timing::Stage;
use crate::engine::domain::BoundaryKind;
use std::time::Instant;

/// Options of the `run` command.
#[derive(Clone, Debug)]
pub struct RunOptions {
    pub nsteps: i64,
    pub upto: bool,
    pub start: Option<i64>,
    pub stop: Option<i64>,
    /// `pre no`: skip reneighbouring in setup when nothing changed since the last run.
    pub pre: bool,
    /// `post no`: skip the timing summary.
    pub post: bool,
}

impl RunOptions {
    pub fn steps(n: i64) -> RunOptions {
        RunOptions { nsteps: n, upto: false, start: None, stop: None, pre: true, post: true }
    }
}

type Hook = fn(&mut dyn Fix, &mut State, &mut FixCtx) -> Result<(), RunError>;

impl Simulation {
    /// Pair parameters the fixes asked to change (fix adapt), then the pair style's init
    /// (LAMMPS' Pair::reinit).
    pub(crate) fn apply_pair_changes(&mut self) -> Result<(), RunError> {
        if self.state.pair_changes.is_empty() {
            return Ok(());
        }
        let changes = std::mem::take(&mut self.state.pair_changes);
        let step = self.state.step;
        let p = self.pair.as_mut().ok_or_else(|| RunError::new(step, "fix adapt: no pair style"))?;
        for c in &changes {
            if !p.adapt_set(&c.param, c.i, c.j, c.value) {
                return Err(RunError::new(step, format!("fix adapt: pair style {} has no parameter `{}` for types {} {}", p.style(), c.param, c.i, c.j)));
            }
        }
        self.init_pair(false).map_err(|e| RunError::new(step, e))
    }

    /// LAMMPS' Domain::init box_change (a shrink-wrapped face, or a fix that changes the box),
    /// then Thermo::init's Volume column of style one.
    pub(crate) fn init_thermo_columns(&mut self) {
        let shrink = self.state.domain.as_ref().is_some_and(|d| {
            d.boundary.iter().flatten().any(|b| matches!(b, BoundaryKind::Shrink | BoundaryKind::ShrinkMin))
        });
        let box_change = shrink || self.fixes.iter().any(|f| f.changes_box());
        self.thermo.init_volume_column(box_change);
    }

    /// Run `work` on fix `k` with the state and a context in which expressions see every fix
    /// (the running one passes itself), every compute and every variable.
    pub(crate) fn with_fix<R>(&mut self, k: usize, work: impl FnOnce(&mut dyn Fix, &mut State, &mut FixCtx) -> R) -> R {
        let cpu = self.cpu_seconds();
        let (before, rest) = self.fixes.split_at_mut(k);
        let (fix, after) = rest.split_first_mut().expect("fix index in range");
        let (before, after): (&[Box<dyn Fix>], &[Box<dyn Fix>]) = (before, after);
        let (pair, bond) = (self.pair.as_deref(), self.bond_style.as_deref());
        let mut expressions = HookExpressions { computes: &self.computes, before, after, thermo: &self.thermo, variables: &mut self.variables, cpu, bond, pair };
        let mut ctx = FixCtx { others: [before, after], pair: self.pair.as_deref(), bond_style: self.bond_style.as_deref(), angle_style: self.angle_style.as_deref(), expressions: &mut expressions };
        work(fix.as_mut(), &mut self.state, &mut ctx)
    }

    /// Call one hook of every fix that uses it, in definition order. Called between a stamp
    /// and a charge of the Modify stage, which charges the last fix that ran (the clock is
    /// read between fixes only).
    pub(crate) fn fix_hook(&mut self, wanted: fn(&FixHooks) -> bool, hook: Hook) -> Result<(), RunError> {
        for k in 0..self.fixes.len() {
            if !wanted(&self.fixes[k].hooks()) {
                continue;
            }
            self.timers.fix_starts();
            let result = self.with_fix(k, hook);
            self.timers.fix_ran(k);
            result?;
        }
        Ok(())
    }

    /// The pair style's checks against the atoms (`checked`; else only what sets its cutoffs
    /// runs, e.g. granular radii) and its mixing (LAMMPS' Pair::init), before a run or a
    /// command that needs its cutoffs.
    pub fn init_pair(&mut self, checked: bool) -> Result<(), String> {
        let ntypes = self.state.ntypes;
        let Some(mut p) = self.pair.take() else { return Ok(()) };
        let insert_radius = (0..=ntypes).map(|t| self.fixes.iter().map(|f| f.insert_radius(t)).fold(0.0, f64::max)).collect();
        if crate::models::pair::granular::mdr_state::ensure_fields_for(p.atom_fields(), &mut self.state.atoms) {
            self.state.lists_valid = false;
        }
        let setup = crate::models::pair::PairSetup { atoms: &self.state.atoms, ntypes, comm_vel: self.state.comm_vel, newton_pair: self.state.newton_pair, insert_radius };
        let sim_checks = p.init_sim(&setup);
        let r = if checked { sim_checks } else { Ok(()) }.and_then(|_| p.init(ntypes, &self.pair_modify, None));
        self.pair = Some(p);
        r
    }

    /// Checks before a run; errors name what is missing.
    pub fn init_run(&mut self) -> Result<(), SetupError> {
        let domain = self.state.domain.as_ref().ok_or("run before the simulation box is defined (use create_box or read_data)")?;
        let _ = domain;
        let type_mass_needed = !self.state.atoms.features.per_atom_mass() || self.pair.as_ref().map(|p| p.needs_type_mass()).unwrap_or(false);
        if type_mass_needed {
            for t in 1..=self.state.ntypes {
                if !self.state.mass_set[t] {
                    return Err(format!("mass of atom type {t} is not set (use the mass command or a Masses section)").into());
                }
            }
        }
        self.init_pair(true).map_err(|message| SetupError { message, at: self.pair_span })?;
        // LAMMPS' Neighbor::init: the builds and dangerous builds are counted per run
        (self.state.neighbor.nbuilds, self.state.neighbor.ndanger) = (0, 0);
        let warnings = crate::models::bonded::pass::init_bonded(&mut self.state, self.bond_style.as_mut(), self.angle_style.as_mut(), self.dihedral_style.as_mut())?;
        for w in warnings {
            self.out.print(&format!("WARNING: {w}"));
        }
        self.init_fixes(true)?;
        let warnings: Vec<String> = self.computes.iter().flat_map(|c| c.init_warnings(&self.world())).collect();
        for w in warnings {
            self.out.print(&format!("WARNING: {w}"));
        }
        self.init_thermo_columns();
        // LAMMPS' Output::init: output intervals given by variables
        let intervals = self.thermo.every_var.iter().map(|v| (v, "thermo".to_string())).chain(self.dumps.iter().filter_map(|d| d.every_var.as_ref().map(|v| (v, format!("dump {}", d.id)))));
        for (v, what) in intervals {
            match self.variables.style(v) {
                None => return Err(format!("Variable name {v} for {what} every does not exist").into()),
                Some("equal" | "internal" | "timer") => {}
                Some(_) => return Err(format!("Variable {v} for {what} every is invalid style (it must be equal-style)").into()),
            }
        }
        // LAMMPS' Thermo::init: a fix in a thermo column must be current on thermo steps
        for c in &self.thermo.columns {
            use crate::output::thermo::Field;
            if let Field::Fix(id, _) | Field::FixArray(id, _, _) = &c.field {
                if let Some(f) = self.fixes.iter().find(|f| f.id() == id) {
                    let freq = f.global_freq();
                    if self.thermo.every % freq != 0 {
                        return Err(format!("thermo every {} and fix {id} ({}) are not computed at compatible times: its values are current every {freq} steps", self.thermo.every, f.style()).into());
                    }
                }
            }
        }
        self.setup_computes(None);
        Ok(())
    }

    /// LAMMPS' Modify::init of the fixes (with their warnings when `warn`).
    pub(crate) fn init_fixes(&mut self, warn: bool) -> Result<(), String> {
        // LAMMPS' Domain::init finds fix deform's remap v group again at each run
        if let Some(d) = self.state.domain.as_mut() {
            d.rate.vremap = None;
        }
        for k in 0..self.fixes.len() {
            self.with_fix(k, |fix, state, ctx| fix.init(state, ctx).map_err(|e| format!("fix {} ({}): {e}", fix.id(), fix.style())))?;
            if let (Some(rate), Some(d)) = (self.fixes[k].box_rate(), self.state.domain.as_mut()) {
                d.rate = rate;
            }
            if warn {
                for w in self.fixes[k].init_warnings([&self.fixes[..k], &self.fixes[k + 1..]]) {
                    self.out.print(&format!("WARNING: {w}"));
                }
            }
        }
        Ok(())
    }

    /// LAMMPS' Update::reset_timestep: the step becomes `step`; the time goes on as if the
    /// steps in between were taken, or restarts at 0 when the step goes back. Outside a run
    /// (`in_run` false) a dump that has written a snapshot to one file refuses it, as LAMMPS'
    /// "Cannot reset timestep with active dump - must undump first".
    pub fn reset_timestep(&mut self, step: i64, in_run: bool) -> Result<(), String> {
        if step < 0 {
            return Err("Timestep must be >= 0".to_string());
        }
        if !in_run {
            if let Some(d) = self.dumps.iter().find(|d| d.last_written.is_some() && !d.path.to_string_lossy().contains('*')) {
                return Err(format!("Cannot reset timestep with active dump - must undump first (dump {} has written to {})", d.id, d.path.display()));
            }
        }
        let st = &mut self.state;
        if step >= st.step {
            st.atime += (step - st.atimestep) as f64 * st.dt;
        } else {
            st.atime = 0.0;
        }
        st.atimestep = step;
        st.step = step;
        for d in &mut self.dumps {
            d.last_written = None;
        }
        Ok(())
    }

    /// Wrap periodic coordinates, resize shrink-wrapped boxes, remove atoms that left a fixed
    /// box, sort, make ghosts and build the lists.
    pub fn rebuild(&mut self) -> Result<(), RunError> {
        self.rebuild_at(false).map(|_| ())
    }

    /// [`Simulation::rebuild`]; `setup`: at the setup of a run (LAMMPS sorts its atoms then).
    /// Returns the permutation applied to the owned atoms (`new k <- old order[k]`), for
    /// per-atom vectors kept outside the atoms (the minimizer's).
    pub(crate) fn rebuild_at(&mut self, setup: bool) -> Result<Vec<usize>, RunError> {
        self.rebuild_sorting(if setup { Sort::Setup } else { Sort::Due })
    }

    /// [`Simulation::rebuild_at`] with LAMMPS' atom sort as `sort` says.
    pub(crate) fn rebuild_sorting(&mut self, sort: Sort) -> Result<Vec<usize>, RunError> {
        let step = self.state.step;
        if self.state.special_dirty {
            // every rank of a distributed run changed the same topology: they agree here
            let special = self.state.rebuild_special().map_err(|e| RunError::new(step, e));
            self.agree(special)?;
            // the record indices of a distributed run's index moved with the topology
            self.state.stored_on = None;
        }
        let Some(domain) = self.state.domain.as_mut() else { return Err(RunError::new(step, "no simulation box")) };
        self.state.atoms.clear_ghosts();
        // a triclinic box wraps its atoms in box fractions and keeps them so until the list
        // build places them again (LAMMPS' x2lamda, pbc, ..., lamda2x: their last bits change)
        let tilted = domain.triclinic();
        if tilted {
            crate::engine::boundary::to_fractions(domain, &mut self.state.atoms);
        }
        crate::engine::boundary::pbc_owned(domain, &mut self.state.atoms);
        self.state.shrink_wrap();
        let lost = crate::sim::stability::check_lost(self);
        if self.state.any_ranks(lost.is_err()) {
            return Err(lost.err().unwrap_or_else(|| RunError::new(step, "another rank lost atoms")));
        }
        let domain = self.state.domain.as_ref().unwrap();
        let ghost_cut = self.ghost_cutoff();
        // where the ranks cut the box: a triclinic box's atoms are box fractions here
        let frame = crate::engine::decomp::frame(domain);
        if let (Some(d), Some(_)) = (&mut self.state.decomp, self.state.distributed) {
            let departed = d.migrate(&mut self.state.atoms, &frame, false).map_err(|e| RunError::new(step, e))?;
            if let Some(pair) = self.pair.as_mut() {
                for h in pair.histories() {
                    d.carry_contacts(h, &departed, domain, false);
                }
            }
            // an uneven load moves the cuts (every rank sees the same counts, so all agree)
            if self.state.balance && d.imbalance(self.state.atoms.nlocal) > crate::sim::distributed::REBALANCE {
                let hist = d.histograms(&self.state.atoms, &frame, true);
                if d.balance(domain, &hist, ghost_cut) {
                    let departed = d.migrate(&mut self.state.atoms, &frame, true).map_err(|e| RunError::new(step, e))?;
                    if let Some(pair) = self.pair.as_mut() {
                        for h in pair.histories() {
                            d.carry_contacts(h, &departed, domain, true);
                        }
                    }
                }
            }
            // atoms lost through fixed faces (thermo_modify lost ignore) leave the count
            self.state.distributed = Some(d.comm.sum1(self.state.atoms.nlocal as f64) as usize);
        }
        self.state.lammps_order.before_rebuild(&self.state.atoms);
        if let Some(name) = &self.state.lammps_order.first {
            let bit = self.state.groups.bit(name).ok_or_else(|| RunError::new(step, format!("could not find atom_modify first group ID `{name}`")))?;
            self.state.lammps_order.first_reorder(&self.state.atoms, bit);
        }
        // a triclinic box: the list cutoff the build will find, for LAMMPS' sort bins
        let tilted_cutneighmax = tilted.then(|| self.pair_cutoff_max() + self.state.neigh_settings.skin);
        let pair = self.pair.as_deref();
        let cut = |i: usize, j: usize| pair.map(|p| p.cutoff(i, j)).unwrap_or(0.0);
        // (a granular style without radii stops at its init, never here)
        let sizes = pair.is_some_and(|p| p.size_list()) && self.state.atoms.features.sphere;
        let ghosts = match (&mut self.state.decomp, self.state.distributed) {
            (Some(d), Some(_)) => Some((d.subdomain(&frame, d.rank()), d)),
            _ => None,
        };
        let built = match ghosts {
            Some((sub, d)) => {
                let comm_cutoff = self.state.comm_cutoff;
                let mut make = |atoms: &mut crate::engine::atoms::Atoms, cut: f64, lamda: &[[f64; 3]]| d.borders(atoms, domain, cut.max(comm_cutoff), lamda);
                let given = crate::engine::neighbor::Ghosts::Given { sub, make: &mut make };
                self.state.neighbor.build_with(&mut self.state.atoms, domain, &self.state.neigh_settings, self.state.ntypes, &cut, sizes, &self.state.special_table, given)
            }
            None => {
                let kind = match tilted_cutneighmax {
                    Some(cutneighmax) => crate::engine::neighbor::Ghosts::Tilted { resorted: self.state.lammps_order.sorts(domain, cutneighmax, step, sort) },
                    None => crate::engine::neighbor::Ghosts::Periodic,
                };
                self.state.neighbor.build_with(&mut self.state.atoms, domain, &self.state.neigh_settings, self.state.ntypes, &cut, sizes, &self.state.special_table, kind)
            }
        };
        let order = built
            .map_err(|e| match e {
                NeighError::BoxTooSmall { dim, cut, length } => RunError::new(
                    step,
                    format!("the neighbour cutoff {cut} (pair cutoff + skin) is longer than the periodic box ({length}) in dimension {}", ["x", "y", "z"][dim]),
                ),
                NeighError::BadPosition { index } => RunError::new(step, format!("atom {} has a non-finite position", self.state.atoms.tag[index])),
                NeighError::TooLarge { lo, hi, cut } => {
                    let g = crate::output::format::g;
                    RunError::new(
                        step,
                        format!(
                            "the region to bin for neighbours, the box and its atoms widened by the cutoff {} (pair cutoff + skin), ({}, {}, {}) to ({}, {}, {}), is too large: its extent overflows a double",
                            g(cut), g(lo[0]), g(lo[1]), g(lo[2]), g(hi[0]), g(hi[1]), g(hi[2])
                        ),
                    )
                }
                NeighError::OutOfMemory { entries, cut } => RunError::new(
                    step,
                    format!(
                        "the neighbour list does not fit in memory (the allocator refused more after {entries} entries of one chunk, with {} atoms): the neighbour cutoff {} (pair cutoff + skin) reaches too many atoms; check `neighbor` (skin) and the pair cutoffs",
                        self.state.atoms.nall(),
                        crate::output::format::g(cut)
                    ),
                ),
                NeighError::NoRoomAfter { entries, cut } => RunError::new(
                    step,
                    format!(
                        "the neighbour list ({entries} entries for {} atoms, neighbour cutoff {}) leaves too little memory for the rest of the step; use fewer atoms, a shorter cutoff or skin, or a machine with more memory",
                        self.state.atoms.nall(),
                        crate::output::format::g(cut)
                    ),
                ),
            });
        // one rank's failure stops every rank here, before the next exchange
        let order = self.agreed(order)?;
        let cutneighmax = self.state.neighbor.cutneighmax.max(self.state.neigh_settings.skin);
        self.state.lammps_order.after_rebuild(&self.state.atoms, domain, cutneighmax, step, sort);
        self.state.lammps_order.make_sides(&self.state.atoms, domain, cutneighmax, self.state.neigh_settings.binsize, self.state.newton_pair);
        self.state.deform_ghost_velocities();
        if self.pair.is_some() {
            self.with_pair(|p, input, _| p.rebuilt(input, &order), false, false);
        }
        let bonded = crate::models::bonded::pass::build_bonded_lists(&mut self.state, BondedStyles::of(&self.bond_style, &self.angle_style, &self.dihedral_style));
        self.agreed(bonded)?;
        self.state.lists_valid = true;
        Ok(order)
    }

    /// Call `work` with the pair style, its input and the per-atom outputs (taken out of the
    /// atoms for the duration, so the style can read the atoms while writing forces).
    pub fn with_pair<R>(&mut self, work: impl FnOnce(&mut dyn crate::models::pair::PairStyle, &PairInput, &mut PairOutput) -> R, eflag: bool, advance: bool) -> R {
        self.with_pair_peratom(work, eflag, advance, None)
    }

    /// [`Simulation::with_pair`] that also hands the style the per-atom tallies to add to.
    pub fn with_pair_peratom<R>(
        &mut self,
        work: impl FnOnce(&mut dyn crate::models::pair::PairStyle, &PairInput, &mut PairOutput) -> R,
        eflag: bool,
        advance: bool,
        peratom: Option<&mut crate::engine::tally::PerAtomTally>,
    ) -> R {
        let mut pair = self.pair.take().expect("pair style");
        let (mut f, mut torque, mut drho, mut desph) = (
            std::mem::take(&mut self.state.atoms.f),
            std::mem::take(&mut self.state.atoms.torque),
            std::mem::take(&mut self.state.atoms.drho),
            std::mem::take(&mut self.state.atoms.desph),
        );
        let rate_fields: Vec<(usize, Field)> = crate::engine::fields::RATES.iter().chain(crate::engine::fields::PAIR_SUMS).filter_map(|&fl| self.state.atoms.field(fl).map(|k| (k, fl))).collect();
        let mut rates: Vec<Vec<f64>> = rate_fields.iter().map(|&(k, _)| std::mem::take(&mut self.state.atoms.extra[k].data)).collect();
        let freeze_bit = crate::models::fix::freeze_bit(self.fixes.iter().map(|f| f.as_ref()));
        let input = PairInput::of_state(&self.state, freeze_bit, eflag, advance);
        let fields = rate_fields.iter().zip(rates.iter_mut()).map(|(&(_, fl), v)| (fl, &mut v[..])).collect();
        let mut out = PairOutput { f: &mut f, torque: &mut torque, drho: &mut drho, desph: &mut desph, fields, peratom };
        // a pass over few pairs (sparse contacts) is not worth sharing among threads
        let r = if input.list.npairs() < crate::engine::par::PARALLEL_MIN_WORK { crate::engine::par::alone(|| work(pair.as_mut(), &input, &mut out)) } else { work(pair.as_mut(), &input, &mut out) };
        self.state.atoms.f = f;
        self.state.atoms.torque = torque;
        self.state.atoms.drho = drho;
        self.state.atoms.desph = desph;
        for ((k, _), v) in rate_fields.into_iter().zip(rates) {
            self.state.atoms.extra[k].data = v;
        }
        self.pair = Some(pair);
        r
    }

    /// Molecules inserted this step as rigid bodies go to their rigid fix.
    fn deliver_rigid_inserts(&mut self) -> Result<(), RunError> {
        for ins in std::mem::take(&mut self.state.rigid_inserts) {
            let step = self.state.step;
            let Some(f) = self.fixes.iter_mut().find(|f| f.id() == ins.fix_id) else {
                return Err(RunError::new(step, format!("the rigid fix {} of inserted molecules does not exist", ins.fix_id)));
            };
            f.add_rigid_molecule(&self.state, &ins).map_err(|e| RunError::new(step, e))?;
        }
        Ok(())
    }

    /// The granular effective masses of rigid body atoms (`State::rigid_mass`) from the first
    /// rigid fix, after each list build, as LAMMPS' granular pairs and walls refresh theirs
    /// (neighbor->ago == 0).
    fn refresh_rigid_mass(&mut self) {
        let build = self.state.neighbor.list.generation;
        if self.rigid_mass_build == Some(build) {
            return;
        }
        self.rigid_mass_build = Some(build);
        let body = self.fixes.iter().find_map(|f| f.rigid_body_mass(&self.state));
        let a = &self.state.atoms;
        self.state.rigid_mass = match body {
            Some(m) => m.iter().zip(&a.rmass).map(|(&mb, &mi)| if mb > 0.0 { mb } else { mi }).collect(),
            None => Vec::new(),
        };
    }

    /// Zero forces and rates, then pair and bonded forces. Tallies energies if `eflag`.
    /// `advance`: false during run setup (contact histories are not advanced, as in LAMMPS).
    pub fn compute_forces(&mut self, eflag: bool, advance: bool) -> Result<(), RunError> {
        self.compute_forces_listed(eflag, advance, None)
    }

    /// [`Simulation::compute_forces`], the pair forces (not the density summation) over
    /// `force_list` when given.
    pub(crate) fn compute_forces_listed(&mut self, eflag: bool, advance: bool, force_list: Option<crate::engine::neighbor::NeighList>) -> Result<(), RunError> {
        self.timers.stamp();
        self.forces_timed(eflag, advance, force_list)
    }

    /// The forces, timed from the last reading of the timers (the step charged the stage
    /// before: one clock reading less per step). The clearing of forces and rates is charged
    /// to Pair.
    fn forces_timed(&mut self, eflag: bool, advance: bool, force_list: Option<crate::engine::neighbor::NeighList>) -> Result<(), RunError> {
        let a = &mut self.state.atoms;
        clear(&mut a.f, [0.0; 3]);
        if a.features.sphere {
            clear(&mut a.torque, [0.0; 3]);
        }
        if a.features.sph {
            clear(&mut a.drho, 0.0);
            clear(&mut a.desph, 0.0);
        }
        for &fl in crate::engine::fields::RATES {
            if let Some(k) = a.field(fl) {
                clear(&mut a.extra[k].data, 0.0);
            }
        }
        let mut pair_tally = Tally::default();
        // per-atom tallies (compute pe/atom, stress/atom): loops with contact histories add
        // to them while computing the forces
        let mut peratom = (eflag && self.computes.iter().any(|c| c.uses_peratom_tally())).then(|| crate::engine::tally::PerAtomTally::new(self.state.atoms.nlocal, self.state.step));
        if self.pair.is_some() && self.state.atoms.features.sph {
            // density summation (sph/rhosum) before the forces that read the densities
            let mut rho = std::mem::take(&mut self.state.atoms.rho);
            let changed = self.with_pair(|p, input, _| p.density_pass(input, &mut rho), false, advance);
            self.state.atoms.rho = rho;
            if changed {
                match (&self.state.decomp, self.state.distributed, self.state.domain.as_ref()) {
                    (Some(d), Some(_), Some(domain)) => d.forward_field(&mut self.state.atoms, domain, |a| &a.rho, |a| &mut a.rho),
                    _ => {
                        let n = self.state.atoms.nlocal;
                        crate::engine::atoms::Atoms::forward_field(&mut self.state.atoms.rho, n, &self.state.atoms.ghost_owner);
                    }
                }
            }
        }
        self.refresh_rigid_mass();
        if self.pair.is_some() {
            let full = force_list.map(|l| std::mem::replace(&mut self.state.neighbor.list, l));
            pair_tally = self.with_pair_peratom(|p, input, out| p.compute(input, out), eflag, advance, peratom.as_mut());
            if let Some(full) = full {
                self.state.neighbor.list = full;
            }
        }
        self.timers.charge(Stage::Pair);
        // no bonded style: no pass and, as LAMMPS without molecular atoms, no clock reading
        let bonded = if self.bond_style.is_none() && self.angle_style.is_none() && self.dihedral_style.is_none() {
            crate::models::bonded::pass::BondedTally::default()
        } else {
            let bonded = match self.bond_style.as_deref().and_then(|b| b.as_bpm()) {
                Some(bpm) => {
                    let (tally, broken) = bpm.compute(&mut self.state, eflag, peratom.as_mut())?;
                    if self.state.distributed.is_some() {
                        self.bonds_broken_ranks(&broken)?;
                    } else if !broken.is_empty() {
                        self.bonds_broken(&broken)?;
                    }
                    tally
                }
                None => crate::models::bonded::pass::compute_bonded(&mut self.state, BondedStyles::of(&self.bond_style, &self.angle_style, &self.dihedral_style), eflag)?,
            };
            self.timers.charge(Stage::Bond);
            bonded
        };
        if let Some(t) = peratom {
            self.tally_peratom(t)?;
            // the per-atom pass is charged to no stage (as before: the step stamps after it)
            self.timers.stamp();
        }
        if eflag {
            let mut virial = pair_tally.virial;
            for k in 0..6 {
                virial[k] += bonded.virial[k];
            }
            let mut e = Energies { pair: pair_tally, ebond: bonded.ebond, eangle: bonded.eangle, edihed: bonded.edihed, virial, step: self.state.step };
            if self.state.distributed.is_some() {
                let p = &e.pair;
                let mut v = [p.evdwl, p.ecoul, p.virial[0], p.virial[1], p.virial[2], p.virial[3], p.virial[4], p.virial[5], e.ebond, e.eangle, e.edihed, virial[0], virial[1], virial[2], virial[3], virial[4], virial[5]];
                self.state.sum_ranks(&mut v);
                e.pair.evdwl = v[0];
                e.pair.ecoul = v[1];
                e.pair.virial.copy_from_slice(&v[2..8]);
                (e.ebond, e.eangle, e.edihed) = (v[8], v[9], v[10]);
                e.virial.copy_from_slice(&v[11..17]);
            }
            self.state.energies = e;
        }
        Ok(())
    }

    /// Per-atom energies and virials of the current forces, for compute pe/atom and
    /// stress/atom (LAMMPS' eatom and vatom, made on the steps that tally energies).
    fn tally_peratom(&mut self, mut t: crate::engine::tally::PerAtomTally) -> Result<(), RunError> {
        let step = self.state.step;
        self.state.peratom_missing = None;
        if self.pair.is_some() {
            if let Err(why) = self.with_pair(|p, input, _| p.tally_peratom(input, &mut t), true, false) {
                // a compute pe/atom or stress/atom that no output reads is no error (as in LAMMPS)
                self.state.peratom = None;
                self.state.peratom_missing = Some((step, why));
                return Ok(());
            }
        }
        // a BPM bond style added its bonds while computing them
        let mut styles = BondedStyles::of(&self.bond_style, &self.angle_style, &self.dihedral_style);
        if self.bond_style.as_deref().is_some_and(|b| b.as_bpm().is_some()) {
            styles.bond = None;
        }
        crate::models::bonded::pass::bonded_peratom(&self.state, styles, &mut t);
        self.state.peratom = Some(t);
        Ok(())
    }

    /// Bonds of a BPM style broke in this force evaluation: their records go to the style's
    /// fix store/local, then they leave the topology, the special table, the neighbour list and
    /// the bonded lists.
    fn bonds_broken(&mut self, broken: &[crate::models::bonded::bpm::Broken]) -> Result<(), RunError> {
        let bpm = self.bond_style.as_deref().and_then(|b| b.as_bpm()).expect("a BPM bond style");
        if let Some(sl) = &bpm.shared().store_local {
            let rows: Vec<Vec<f64>> = broken.iter().map(|b| crate::models::bonded::bpm::record(&sl.values, &self.state, b)).collect();
            let masks: Vec<[u32; 2]> = broken.iter().map(|b| b.atoms.map(|i| self.state.atoms.mask[i as usize])).collect();
            let fix = self.fixes.iter_mut().find(|f| f.id() == sl.fix_id).and_then(|f| f.as_store_local());
            let Some(fix) = fix else { return Err(RunError::new(self.state.step, format!("Cannot find fix STORE/LOCAL id {}", sl.fix_id))) };
            fix.add_rows(rows, &masks);
        }
        crate::models::bonded::bpm::remove_broken(&mut self.state, broken);
        Ok(())
    }

    /// [`Simulation::bonds_broken`] on the ranks of a distributed run: each rank's broken bonds
    /// (with their store/local rows, made where the bond was computed) go to every rank, which
    /// records each once, in rank order, and removes it from its topology, special table and
    /// neighbour list, so every rank keeps the same topology. A bond across ranks breaks on both
    /// (they compute it with the same bits).
    fn bonds_broken_ranks(&mut self, broken: &[crate::models::bonded::bpm::Broken]) -> Result<(), RunError> {
        use crate::models::bonded::bpm;
        let sl = self.bond_style.as_deref().and_then(|b| b.as_bpm()).and_then(|b| b.shared().store_local.clone());
        let width = 3 + sl.as_ref().map_or(0, |s| s.values.len());
        let mut mine = Vec::with_capacity(broken.len() * width);
        for b in broken {
            let a = &self.state.atoms;
            mine.push(b.rec as f64);
            mine.extend(b.atoms.map(|i| a.mask[i as usize] as f64));
            if let Some(sl) = &sl {
                mine.extend(bpm::record(&sl.values, &self.state, b));
            }
        }
        let all = self.state.allgather_ranks(mine);
        let mut seen = vec![false; self.state.topo.bonds.len()];
        let (mut recs, mut rows, mut masks) = (vec![], vec![], vec![]);
        for r in all.chunks_exact(width) {
            let rec = r[0] as usize;
            let Some(seen) = seen.get_mut(rec) else {
                return Err(RunError::new(self.state.step, format!("the ranks' bond records differ: record {rec} of {} broke on another rank", self.state.topo.bonds.len())));
            };
            if std::mem::replace(seen, true) {
                continue;
            }
            recs.push(rec);
            masks.push([r[1] as u32, r[2] as u32]);
            rows.push(r[3..].to_vec());
        }
        if let Some(sl) = sl.filter(|_| !rows.is_empty()) {
            let fix = self.fixes.iter_mut().find(|f| f.id() == sl.fix_id).and_then(|f| f.as_store_local());
            let Some(fix) = fix else { return Err(RunError::new(self.state.step, format!("Cannot find fix STORE/LOCAL id {}", sl.fix_id))) };
            fix.add_rows(rows, &masks);
        }
        bpm::remove_broken_records(&mut self.state, recs);
        Ok(())
    }

    /// LAMMPS `Verlet::setup`: lists, forces of the current state, fix setup, first output.
    pub fn setup(&mut self, pre: bool) -> Result<(), RunError> {
        self.setup_sorting(pre, Sort::Setup)
    }

    /// [`Simulation::setup`]; `sort`: whether the build sorts LAMMPS' order (a rerun
    /// snapshot's setup, LAMMPS' setup_minimal, does not).
    pub(crate) fn setup_sorting(&mut self, pre: bool, sort: Sort) -> Result<(), RunError> {
        // LAMMPS' Modify::init drops the restart file's fix states no fix took
        for s in std::mem::take(&mut self.restart_fixes) {
            self.out.print(&format!("WARNING: fix {} {} of the restart file was not defined again: its stored state is dropped", s.id, s.style));
        }
        if pre || !self.state.lists_valid {
            self.timers.stamp();
            // the setup's build is not counted (LAMMPS' Verlet::setup zeroes ncalls after it)
            let builds = self.state.neighbor.nbuilds;
            self.rebuild_sorting(sort)?;
            self.state.neighbor.nbuilds = builds;
            self.timers.charge(Stage::Neigh);
        } else {
            self.forward_ghosts(true);
        }
        self.setup_computes_after_build();
        self.state.natoms_expected = self.state.atoms.nlocal;
        self.timers.stamp();
        // LAMMPS quirk reproduced: ghosts are made (borders) before fixes' setup_pre_force, and
        // not refreshed after it, so a ghost keeps the velocity estimate it had when it was
        // made (fix sph sets vest = v on owned atoms only); the setup forces of pairs across
        // periodic faces see the old vest on the side LAMMPS' newton list gives them
        // (src/sim/stale_vest.rs).
        let vest_before = self.vest_before_setup();
        self.prematch_regions(None).map_err(|e| RunError::new(self.state.step, e))?;
        self.fix_hook(|_| true, |f, s, c| f.setup_pre_force(s, c))?;
        self.apply_pair_changes()?;
        self.pair_pre_force(true)?;
        self.timers.charge(Stage::Modify);
        // what fixes noticed when the run starts (e.g. a region defined again)
        self.flush_messages();
        self.setup_forces_stale_vest(vest_before)?;
        self.timers.stamp();
        let dt = self.state.dt;
        self.fix_hook(|_| true, |f, s, c| f.setup(s, c))?;
        self.dt_changed(dt)?;
        self.timers.charge(Stage::Modify);
        // lines fixes printed in their setup (fix print)
        self.flush_messages();
        Ok(())
    }

    /// The pair style's work before a force evaluation ([`crate::models::pair::PairStyle::pre_force`]).
    fn pair_pre_force(&mut self, setup: bool) -> Result<(), RunError> {
        let Some(mut p) = self.pair.take() else { return Ok(()) };
        let r = p.pre_force(&mut self.state, setup);
        self.pair = Some(p);
        r.map_err(|e| RunError::new(self.state.step, e))
    }

    /// A fix (dt/reset) changed dt from `before`: every fix renews what it made from dt (LAMMPS'
    /// reset_dt calls), or the run stops with its refusal.
    fn dt_changed(&mut self, before: f64) -> Result<(), RunError> {
        if self.state.dt == before {
            return Ok(());
        }
        for f in &mut self.fixes {
            f.reset_dt(&self.state).map_err(|e| RunError::new(self.state.step, e))?;
        }
        Ok(())
    }

    /// Advance one step (LAMMPS `Verlet::run` body).
    pub fn step_once(&mut self, eflag: bool) -> Result<(), RunError> {
        self.state.step += 1;
        self.timers.stamp();
        self.prematch_regions(None).map_err(|e| RunError::new(self.state.step, e))?;
        self.fix_hook(|h| h.initial_integrate, |f, s, c| f.initial_integrate(s, c))?;
        self.fix_hook(|h| h.post_integrate, |f, s, c| f.post_integrate(s, c))?;
        self.timers.charge(Stage::Modify);

        // a fix that changed the topology or must see fresh lists asks for a rebuild
        // (LAMMPS' Neighbor::decide checks fixes' next_reneighbor before counting steps)
        let step = self.state.step;
        let requested = std::mem::take(&mut self.state.rebuild_requested) || self.fixes.iter().any(|f| f.next_reneighbor() == Some(step));
        // a fix that changes the box (fix deform) shrinks the distance that triggers a rebuild
        // by how far the box's corners moved (LAMMPS' boxcheck)
        let moving = self.state.domain.as_ref().filter(|_| self.fixes.iter().any(|f| f.changes_box()));
        let moved = !requested && self.state.neighbor.decide_in(&self.state.neigh_settings, &self.state.atoms, moving);
        // the ranks of a distributed run rebuild together when any of them must
        if self.state.any_ranks(moved) || requested {
            self.timers.stamp();
            self.fix_hook(|h| h.pre_exchange, |f, s, c| f.pre_exchange(s, c))?;
            self.deliver_rigid_inserts()?;
            self.timers.charge(Stage::Modify);
            self.flush_messages();
            self.rebuild()?;
            self.timers.charge(Stage::Neigh);
        } else {
            let with_state = self.needs_ghost_state();
            self.forward_ghosts(with_state);
            self.timers.charge(Stage::Comm);
        }

        if self.fixes.iter().any(|f| f.hooks().pre_force) {
            self.fix_hook(|h| h.pre_force, |f, s, c| f.pre_force(s, c))?;
            self.apply_pair_changes()?;
            self.timers.charge(Stage::Modify);
        }
        self.pair_pre_force(false)?;
        self.fix_hook(|h| h.mdr_pre_force, |f, s, c| f.mdr_pre_force(s, c))?;
        // the stages follow each other: each starts at the reading that ended the last
        self.forces_timed(eflag, true, None)?;

        self.fix_hook(|h| h.post_force, |f, s, c| f.post_force(s, c))?;
        self.fix_hook(|h| h.final_integrate, |f, s, c| f.final_integrate(s, c))?;
        let dt = self.state.dt;
        self.fix_hook(|h| h.end_of_step, |f, s, c| f.end_of_step(s, c))?;
        self.dt_changed(dt)?;
        self.timers.charge(Stage::Modify);
        if !self.state.messages.is_empty() {
            self.flush_messages();
        }
        Ok(())
    }

    /// Fresh ghost positions (and, `with_state`, velocities and per-atom state) from their
    /// owners: on this rank, or on the others of a distributed run.
    fn forward_ghosts(&mut self, with_state: bool) {
        let domain = self.state.domain.as_ref().expect("a box");
        match (&self.state.decomp, self.state.distributed) {
            // (a rank's exchange of the state carries the positions too)
            (Some(_), Some(_)) if with_state => {}
            (Some(d), Some(_)) => d.forward_positions(&mut self.state.atoms, domain),
            _ => self.state.atoms.forward_positions(domain.periods()),
        }
        if with_state {
            self.state.forward_ghost_state();
        }
    }

    /// Print the lines models left for the screen and the log.
    pub fn flush_messages(&mut self) {
        for m in std::mem::take(&mut self.state.messages) {
            self.out.print(&m);
        }
    }

    /// Each active model with its seconds in this run: pair styles (hybrid: per sub-style and
    /// its type pairs), the bonded styles together (they share one pass), and each fix.
    fn model_rows(&self) -> Vec<(String, f64)> {
        use crate::engine::timing::Stage;
        let stage = |st: Stage| self.timers.seconds[crate::engine::timing::STAGES.iter().position(|(s, _)| *s == st).unwrap()];
        let mut rows = Vec::new();
        if let Some(p) = &self.pair {
            let parts = p.model_seconds();
            if parts.is_empty() {
                rows.push((format!("pair {}", p.style()), stage(Stage::Pair)));
            } else {
                rows.extend(parts.into_iter().map(|(l, t)| (format!("pair {l}"), t)));
            }
        }
        let bonded: Vec<String> = [
            self.bond_style.as_ref().filter(|_| !self.state.topo.bonds.is_empty()).map(|b| format!("bond {}", b.name())),
            self.angle_style.as_ref().filter(|_| !self.state.topo.angles.is_empty()).map(|b| format!("angle {}", b.name())),
            self.dihedral_style.as_ref().filter(|_| !self.state.topo.dihedrals.is_empty()).map(|b| format!("dihedral {}", b.name())),
        ]
        .into_iter()
        .flatten()
        .collect();
        if !bonded.is_empty() {
            rows.push((bonded.join(" + "), stage(Stage::Bond)));
        }
        for (k, f) in self.fixes.iter().enumerate() {
            rows.push((format!("fix {} {}", f.id(), f.style()), self.timers.fix_seconds.get(k).copied().unwrap_or(0.0)));
        }
        rows
    }

    /// Ghost atoms need fresh velocities and per-atom state only for styles that read them.
    pub(crate) fn needs_ghost_state(&self) -> bool {
        self.state.comm_vel || self.state.atoms.features.sph || self.state.atoms.features.sphere || self.state.atoms.extra.iter().any(|e| e.ghosts)
    }

    /// The `run` command.
    pub fn run(&mut self, opts: &RunOptions) -> Result<(), RunError> {
        // after a fix halt with `error soft`, LAMMPS' runs return at once, printing nothing
        if self.state.halted {
            return Ok(());
        }
        let nsteps = if opts.upto { opts.nsteps - self.state.step } else { opts.nsteps };
        if nsteps < 0 {
            return Err(RunError::new(self.state.step, format!("run upto {} is before the current step {}", opts.nsteps, self.state.step)));
        }
        let first = self.state.step;
        let last = self.state.step + nsteps;
        let start = opts.start.unwrap_or(first);
        let stop = opts.stop.unwrap_or(last);
        if start > first || stop < last {
            return Err(RunError::new(self.state.step, format!("run start/stop must bracket the run: start {start} <= {first}, stop {stop} >= {last}")));
        }
        // `pre no` after a first run skips LAMMPS' init, which restarts the build counts
        // `pre no` after a first run: LAMMPS' output->setup only (no init, no setup banner)
        let brief = !opts.pre && self.state.run_window.is_some();
        let counts = brief.then_some((self.state.neighbor.nbuilds, self.state.neighbor.ndanger));
        self.state.run_window = Some((start, stop));
        self.init_run().map_err(|e| RunError::setup(self.state.step, e))?;
        // LAMMPS' Verlet::init (skipped with `pre no`)
        if !brief && !self.fixes.iter().any(|f| f.time_integrate()) {
            self.out.print("WARNING: No fixes with time integration, atoms won't move");
        }
        if let Some((nbuilds, ndanger)) = counts {
            (self.state.neighbor.nbuilds, self.state.neighbor.ndanger) = (nbuilds, ndanger);
        }
        if self.state.decomp.is_some() {
            self.distribute()?;
        }
        let mut outcome = self.run_steps(opts, first, last, brief);
        // LAMMPS' post_run (fix adapt's reset)
        for f in self.fixes.iter_mut() {
            f.post_run(&mut self.state);
        }
        if let Ok(Ok(())) = outcome {
            outcome = Ok(self.apply_pair_changes());
        }
        self.state.pair_changes.clear();
        let counts = self.rank_counts();
        self.gather_ranks();
        // a setup that failed prints no loop line
        let result = outcome?;
        let (loop_time, done) = (self.last_loop_seconds, self.last_loop_steps);
        self.out.print(&format!(
            "Loop time of {} on {} procs for {} steps with {} atoms\n",
            crate::output::format::g6(loop_time),
            self.nranks(),
            done,
            self.state.atoms.nlocal
        ));
        if opts.post && result.is_ok() {
            self.print_run_summary(loop_time, done, None, counts);
        }
        self.out.flush();
        // thermo keywords and variables refer to the current run window until the next run
        result
    }

    /// The setup (its error: the outer one) and the steps of a run, until `last` or the first
    /// error (on any rank).
    /// `brief`: `pre no` after a first run, which prints no setup banner and no memory line.
    fn run_steps(&mut self, opts: &RunOptions, first: i64, last: i64, brief: bool) -> Result<Result<(), RunError>, RunError> {
        let nsteps = last - first;
        if !brief {
            self.out.print(&format!(
                "Setting up Verlet run ...\n  Unit style    : {}\n  Current step  : {}\n  Time step     : {}\n",
                self.state.units.name(),
                self.state.step,
                crate::output::format::g(self.state.dt)
            ));
        }
        // the ranks of a distributed run stop together when one fails in setup (a fix's check
        // of the atoms it owns), as they do after a step
        let set_up = self.setup(opts.pre);
        self.agree(set_up)?;
        if self.want_capture && self.capture_setup.is_none() {
            // crosscheck: the forces after the setup of the first run, as lammps_driver.py's
            // dump writes them (`first yes`)
            self.capture_setup = Some(crate::output::atom_table::forces_table(&self.state));
            self.capture_first_step = Some(self.state.step);
        }
        let (_, warnings) = crate::sim::stability::report(self, &crate::sim::stability::limits(self, true));
        for w in warnings {
            self.out.print(&format!("WARNING: {w}"));
        }
        if !brief {
            let mem = crate::sim::memory::bytes_per_rank(self) as f64 / (1024.0 * 1024.0);
            self.out.print(&format!("Per MPI rank memory allocation (min/avg/max) = {mem:.4} | {mem:.4} | {mem:.4} Mbytes"));
        }
        if let Some(h) = self.thermo.header() {
            self.out.print(&h);
        }
        let first_output = self.output_step(true, last);
        self.agree(first_output)?;

        // the breakdown covers the loop only, as LAMMPS' (its timers start after setup): with
        // the setup's neighbour build and forces in it, the stages added up to more than the loop
        self.timers.reset();
        if let Some(p) = self.pair.as_mut() {
            p.reset_model_seconds();
        }
        let t0 = Instant::now();
        self.loop_start = Some(t0);
        let progress = crate::output::progress::Progress::new(nsteps as u64, self.out.screen);
        let mut result = Ok(());
        for _ in 0..nsteps {
            // a fix halt met on the last step: this run ends here (LAMMPS' check_timeout)
            if self.state.halted {
                break;
            }
            if self.cancel.swap(false, std::sync::atomic::Ordering::Relaxed) {
                result = Err(RunError::new(self.state.step, "run interrupted"));
                break;
            }
            let next = self.state.step + 1;
            let eflag = self.output_due(next, last);
            let stepped = self.step_once(eflag).and_then(|_| crate::sim::stability::check_state(self));
            // the ranks of a distributed run stop together
            if let Err(e) = self.agree(stepped) {
                result = Err(e);
                break;
            }
            if eflag {
                self.timers.stamp();
                let written = self.output_step(false, last);
                if let Err(e) = self.agree(written) {
                    result = Err(e);
                    break;
                }
                self.timers.charge(Stage::Output);
            }
            if let Some(first) = self.capture_first_step {
                let k = self.state.step - first;
                if k > 0 && k & (k - 1) == 0 {
                    self.capture_checkpoint();
                }
            }
            progress.tick();
        }
        if result.is_ok() && self.capture_first_step.is_some() {
            self.capture_checkpoint();
        }
        progress.finish();
        let loop_time = t0.elapsed().as_secs_f64();
        self.loop_start = None;
        if let Some(f) = self.thermo.footer() {
            self.out.print(f);
        }
        let done = self.state.step - first;
        // LAMMPS' update_time at the end of a run: the time origin moves to the last step
        (self.state.atime, self.state.atimestep) = (self.state.time(), self.state.step);
        self.last_loop_seconds = loop_time;
        self.last_loop_steps = done;
        Ok(result)
    }

    /// A crosscheck checkpoint now (once per step number).
    fn capture_checkpoint(&mut self) {
        let step = self.state.step;
        if self.capture_checkpoints.last().map(|c| c.0) != Some(step) {
            self.capture_checkpoints.push((step, crate::output::atom_table::checkpoint_table(&self.state)));
        }
    }

    /// Energies are needed on thermo steps, the last step, dump steps and the steps on which a
    /// fix reads values (fix ave/time, fix print).
    pub(crate) fn output_due(&self, step: i64, last: i64) -> bool {
        self.thermo_due(step, last)
            || self.dumps.iter().any(|d| d.due(step, false))
            || self.fixes.iter().any(|f| f.wants_energy(step))
    }

    /// Whether a thermo line is printed at `step` (after the run's setup line): at the steps
    /// `thermo v_name` gives, else every N steps and the run's last step.
    pub(crate) fn thermo_due(&self, step: i64, last: i64) -> bool {
        match self.thermo.every_var {
            Some(_) => step == self.thermo.next,
            None => step == last || (self.thermo.every > 0 && step % self.thermo.every == 0),
        }
    }

    /// Thermo line and dumps for the current step.
    fn output_step(&mut self, setup: bool, last: i64) -> Result<(), RunError> {
        self.output_now(setup, last, false)
    }

    /// [`Simulation::output_step`]; `all_dumps`: every dump writes now (the last step of a
    /// minimization that stopped early, as LAMMPS' Min::run).
    pub(crate) fn output_now(&mut self, setup: bool, last: i64, all_dumps: bool) -> Result<(), RunError> {
        let step = self.state.step;
        let thermo_now = setup || self.thermo_due(step, last);
        // thermo's cpu and a multi block's CPU: the seconds of the run so far, 0 at its setup
        // (LAMMPS' compute_cpu)
        let cpu = if setup { 0.0 } else { self.cpu_seconds() };
        if thermo_now {
            self.write_thermo(setup, last, cpu)?;
        }
        let due: Vec<usize> = (0..self.dumps.len()).filter(|&k| self.dumps[k].due(step, setup) || (all_dumps && self.dumps[k].last_written != Some(step))).collect();
        let distributed = self.state.distributed.is_some();
        if distributed && !due.is_empty() {
            self.write_dumps_gathered(&due)?;
        }
        let world = World { state: &self.state, computes: &self.computes, fixes: FixesView::all(&self.fixes), bond: self.bond_style.as_deref(), pair: self.pair.as_deref() };
        let mut ev = Eval { world, thermo: &self.thermo, variables: &mut self.variables, cpu };
        for (k, d) in self.dumps.iter_mut().enumerate() {
            let written = due.contains(&k);
            if written && !distributed {
                d.write(&world, &mut ev).map_err(|e| RunError::new(step, e))?;
            }
            // `every v_name`: the next snapshot's step, at setup and after each snapshot
            // (LAMMPS' calculate_next_dump)
            if let Some(v) = d.every_var.as_ref().filter(|_| setup || written) {
                d.next = next_output_step(&mut ev, v, step).map_err(|e| RunError::new(step, format!("Dump {} every variable {v} {e}", d.id)))?;
            }
        }
        Ok(())
    }

    /// The thermo line of the current step (`setup`: a run's first, whose next output step is
    /// not capped at `last`); `cpu`: the seconds the thermo `cpu` keyword shows.
    pub(crate) fn write_thermo(&mut self, setup: bool, last: i64, cpu: f64) -> Result<(), RunError> {
        let step = self.state.step;
        self.out.warnings_notice();
        let world = World { state: &self.state, computes: &self.computes, fixes: FixesView::all(&self.fixes), bond: self.bond_style.as_deref(), pair: self.pair.as_deref() };
        let mut ev = Eval { world, thermo: &self.thermo, variables: &mut self.variables, cpu };
        let vals = crate::output::thermo::values(&self.thermo, &world, &mut ev).map_err(|e| RunError::new(step, format!("thermo output: {e}")))?;
        let line = self.thermo.format_line(&vals, step, cpu);
        self.out.print(&line);
        if self.thermo.flush {
            self.out.flush();
        }
        // the next output step, from the variable after each output (LAMMPS' Output::setup
        // and write: only the later ones are capped at the run's last step)
        if let Some(v) = &self.thermo.every_var {
            let next = next_output_step(&mut ev, v, step).map_err(|e| RunError::new(step, format!("Thermo every variable {v} {e}")))?;
            self.thermo.next = if setup { next } else { next.min(last) };
        }
        Ok(())
    }

    /// Dumps of a distributed run: rank 0 writes them from the whole system, gathered for the
    /// moment (the others only note the step as written).
    fn write_dumps_gathered(&mut self, due: &[usize]) -> Result<(), RunError> {
        let step = self.state.step;
        let d = self.state.decomp.as_ref().expect("a decomposition");
        let mut whole = d.gathered(&self.state.atoms);
        // the per-atom energies and virials of this step, in the same rank order (dumps of
        // compute pe/atom and stress/atom)
        let mut tally = self.state.peratom.as_ref().map(|t| crate::engine::tally::PerAtomTally::from_flat(t.step, &d.comm.allgather(t.flat()).concat()));
        let rank0 = d.rank() == 0;
        std::mem::swap(&mut self.state.atoms, &mut whole);
        std::mem::swap(&mut self.state.peratom, &mut tally);
        let natoms = self.state.distributed.take();
        let mut result = Ok(());
        {
            let world = World { state: &self.state, computes: &self.computes, fixes: FixesView::all(&self.fixes), bond: self.bond_style.as_deref(), pair: self.pair.as_deref() };
            let mut ev = Eval { world, thermo: &self.thermo, variables: &mut self.variables, cpu: self.last_loop_seconds };
            for &k in due {
                if rank0 {
                    if let Err(e) = self.dumps[k].write(&world, &mut ev) {
                        result = Err(RunError::new(step, e));
                        break;
                    }
                } else {
                    self.dumps[k].last_written = Some(step);
                }
            }
        }
        self.state.distributed = natoms;
        std::mem::swap(&mut self.state.atoms, &mut whole);
        std::mem::swap(&mut self.state.peratom, &mut tally);
        result
    }

    /// The summary after a run's loop; `stats`: printed after the CPU line (a minimization's).
    pub(crate) fn print_run_summary(&mut self, loop_time: f64, steps: i64, stats: Option<&str>, counts: Option<crate::sim::distributed::RankCounts>) {
        let n = self.state.atoms.nlocal as f64;
        if loop_time > 0.0 && steps > 0 {
            let tps = steps as f64 / loop_time;
            let unit_time = if self.state.units.style == crate::engine::units::UnitStyle::Lj { "tau/day" } else { "ns/day" };
            let per_day = if self.state.units.style == crate::engine::units::UnitStyle::Lj { 86400.0 * tps * self.state.dt } else { 86400.0 * tps * self.state.dt * 1e9 };
            self.out.print(&format!(
                "Performance: {per_day:.3} {unit_time}, {tps:.3} timesteps/s, {:.3} Matom-step/s\n",
                tps * n / 1e6
            ));
        }
        let threads = crate::engine::par::threads();
        self.out.print(&format!("100.0% CPU use with {} MPI tasks x {threads} threads\n", self.nranks()));
        if let Some(stats) = stats {
            self.out.print(stats);
        }
        self.out.print(&self.timers.report(loop_time, counts.as_ref().map(|c| &c.stages)));
        self.out.print(&crate::engine::timing::model_report(&self.model_rows(), loop_time));
        self.out.print(&format!(
            "Memory per particle: {:.0} bytes ({:.4} Mbytes in all)\n",
            crate::sim::memory::bytes_per_particle(self),
            crate::sim::memory::bytes_per_rank(self) as f64 / (1024.0 * 1024.0)
        ));
        // per rank: the sum, the least and the most (one rank: its own count three times)
        let counts = counts.unwrap_or_else(|| {
            let one = |x: usize| [x as f64; 3];
            let stages = [crate::engine::timing::Spread::default(); 6];
            crate::sim::distributed::RankCounts { nlocal: one(self.state.atoms.nlocal), nghost: one(self.state.atoms.nghost()), neighs: [self.state.neighbor.list.lammps_count(self.state.atoms.nlocal, &self.state.special_bonds.lj, &self.state.special_bonds.coul, self.state.newton_pair); 3], stages }
        });
        let ranks = self.nranks() as f64;
        let g = crate::output::format::g;
        let ave = |c: [f64; 3]| if ranks == 1.0 { c[0].to_string() } else { g(c[0] / ranks) };
        let row = |c: [f64; 3]| format!("{} ave {} max {} min", ave(c), c[2], c[1]);
        self.out.print(&format!(
            "Nlocal:    {}\nNghost:    {}\nNeighs:    {}\n\nTotal # of neighbors = {}\nAve neighs/atom = {:.7}\nNeighbor list builds = {}\nDangerous builds = {}\n",
            row(counts.nlocal),
            row(counts.nghost),
            row(counts.neighs),
            counts.neighs[0],
            if n > 0.0 { counts.neighs[0] / n } else { 0.0 },
            self.state.neighbor.nbuilds,
            self.state.neighbor.ndanger
        ));
    }
}

/// Set every element to `zero`, in the integrators' blocks of atoms (so each thread clears
/// the forces it then adds to, in its own cache).
fn clear<T: Copy + Send + Sync>(v: &mut [T], zero: T) {
    use crate::engine::par::{ranges, AtomsMut};
    ranges(v.len(), 1024, AtomsMut::new(v), |r, mut w| w.slice(r).fill(zero));
}

/// The step of the next output (thermo or a dump) that variable `v` gives at `step`: its value
/// truncated toward zero as LAMMPS' static_cast<bigint> (10.7 is step 10; saturating, NaN is
/// 0), which must lie after `step`. The error completes "... every variable NAME ".
fn next_output_step(ev: &mut Eval, v: &str, step: i64) -> Result<i64, String> {
    let value = dmhs_parser::variables::compute_equal(ev, v).map_err(|e| format!("could not be evaluated: {e}"))?;
    let next = value as i64;
    if next <= step {
        return Err(format!("returned a bad timestep ({value}): it must be after the current step {step}"));
    }
    Ok(next)
}
