//! `rerun`: a pseudo run over dump snapshots (LAMMPS' Rerun::command). The run is set up once;
//! then each snapshot sets the step, replaces the atoms, and gets LAMMPS' setup_minimal (lists
//! built without sorting, forces and energies, the fixes' setup), the fixes' end_of_step and
//! the output due at its step. Nothing is integrated.

use crate::engine::lammps_order::Sort;
use crate::sim::{RunError, Simulation};

/// Where a rerun's snapshots come from (read_dump's dump files, src/deck/read_dump.rs).
pub trait SnapshotSource {
    /// The first snapshot whose step is at least `first` (None: there is none).
    fn seek(&mut self, first: i64) -> Result<Option<i64>, String>;
    /// The next snapshot after step `current` up to `last`, a multiple of `every` (0: any),
    /// one in `skip` (LAMMPS' counting); None when there is none.
    fn next(&mut self, current: i64, last: i64, every: i64, skip: i64) -> Result<Option<i64>, String>;
    /// Read the snapshot found last; `first`: the first of the rerun.
    fn read(&mut self, first: bool) -> Result<(), String>;
    /// Put the snapshot read last into the system.
    fn apply(&mut self, sim: &mut Simulation) -> Result<(), String>;
}

/// The keywords of `rerun` before `dump`.
#[derive(Clone, Copy, Debug)]
pub struct RerunOptions {
    /// Snapshots from this step on.
    pub first: i64,
    /// Snapshots up to this step.
    pub last: i64,
    /// Only steps that are multiples of it (0: all).
    pub every: i64,
    /// One snapshot in `skip` after the first.
    pub skip: i64,
    /// The pseudo run's start and stop (for fixes that ramp over a run).
    pub start: Option<i64>,
    pub stop: Option<i64>,
    /// The summary after the loop.
    pub post: bool,
}

impl Default for RerunOptions {
    fn default() -> Self {
        // LAMMPS' last: the largest bigint less one, so that output can add 1
        RerunOptions { first: 0, last: i64::MAX - 1, every: 0, skip: 1, start: None, stop: None, post: false }
    }
}

impl Simulation {
    /// The `rerun` command over the snapshots of `src`.
    pub fn rerun(&mut self, src: &mut dyn SnapshotSource, o: &RerunOptions) -> Result<(), RunError> {
        let step = self.state.step;
        self.state.run_window = Some((o.start.unwrap_or(o.first), o.stop.unwrap_or(o.last)));
        self.init_run().map_err(|e| RunError::setup(step, e))?;
        if !self.fixes.iter().any(|f| f.time_integrate()) {
            self.out.print("WARNING: No fixes with time integration, atoms won't move");
        }
        let first = src.seek(o.first).map_err(|e| RunError::new(step, e))?;
        let Some(first) = first else {
            return Err(RunError::new(step, format!("Rerun dump file does not contain requested snapshot (a step >= {})", o.first)));
        };
        let t0 = std::time::Instant::now();
        self.loop_start = Some(t0);
        self.timers.reset();
        let mut ndump = 0;
        let outcome = self.rerun_snapshots(src, o, first, &mut ndump);
        // LAMMPS' post_run (fix adapt's reset)
        for f in self.fixes.iter_mut() {
            f.post_run(&mut self.state);
        }
        let counts = self.rank_counts();
        // every rank holds the whole system again, even after a failure
        self.gather_ranks();
        let loop_time = t0.elapsed().as_secs_f64();
        self.loop_start = None;
        outcome?;
        if let Some(f) = self.thermo.footer() {
            self.out.print(f);
        }
        self.last_loop_seconds = loop_time;
        self.last_loop_steps = ndump;
        self.out.print(&format!("Loop time of {} on {} procs for {ndump} steps with {} atoms\n", crate::output::format::g6(loop_time), self.nranks(), self.state.atoms.nlocal));
        if o.post {
            self.print_run_summary(loop_time, ndump, None, counts);
        }
        self.out.flush();
        Ok(())
    }

    /// The snapshots from step `first` on (`ndump` counts them): each read, set up and
    /// output, then a thermo line for the last one if its step had none.
    fn rerun_snapshots(&mut self, src: &mut dyn SnapshotSource, o: &RerunOptions, first: i64, ndump: &mut i64) -> Result<(), RunError> {
        let mut next = Some(first);
        let mut last_thermo = None;
        while let Some(t) = next {
            let first = *ndump == 0;
            *ndump += 1;
            // (every rank reads the same snapshot into the whole system, then takes its part)
            self.gather_ranks();
            src.read(first).map_err(|e| RunError::new(t, e))?;
            self.reset_timestep(t, true).map_err(|e| RunError::new(t, e))?;
            src.apply(self).map_err(|e| RunError::new(t, e))?;
            // LAMMPS' Modify::init before each snapshot's setup
            self.init_fixes(false).map_err(|e| RunError::new(t, e))?;
            if self.state.decomp.is_some() {
                self.distribute_with(first)?;
            }
            let set_up = self.setup_sorting(true, Sort::Never);
            self.agree(set_up)?;
            let ended = self.fix_hook(|h| h.end_of_step, |f, s, c| f.end_of_step(s, c));
            self.agree(ended)?;
            if first {
                let mem = crate::sim::memory::bytes_per_rank(self) as f64 / (1024.0 * 1024.0);
                self.out.print(&format!("Per MPI rank memory allocation (min/avg/max) = {mem:.4} | {mem:.4} | {mem:.4} Mbytes"));
                if let Some(h) = self.thermo.header() {
                    self.out.print(&h);
                }
                let written = self.output_now(true, o.last, false);
                self.agree(written)?;
                last_thermo = Some(t);
            } else {
                let thermo = self.thermo_due(t, o.last);
                let written = self.output_now(false, o.last, false);
                self.agree(written)?;
                if thermo {
                    last_thermo = Some(t);
                }
            }
            next = src.next(t, o.last, o.every, o.skip).map_err(|e| RunError::new(t, e))?;
            if let (Some(n), Some(stop)) = (next, o.stop) {
                if n > stop {
                    return Err(RunError::new(t, format!("Read rerun dump file timestep > specified stop: snapshot {n} after stop {stop}")));
                }
            }
        }
        // a thermo line for the last snapshot, if its step had none
        let t = self.state.step;
        if last_thermo != Some(t) {
            let cpu = self.cpu_seconds();
            let written = self.write_thermo(false, o.last, cpu);
            self.agree(written)?;
        }
        Ok(())
    }
}
