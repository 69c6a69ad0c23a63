//! A run over several ranks (`State::decomp`): what such a run supports so far, handing the
//! atoms out at its start and back at its end, and agreeing on what every rank must know.
//!
//! Between runs every rank holds the whole system, so the deck's commands work as in a serial
//! run; a run spreads the atoms over the sub-domains, and its end gathers them again.

use crate::engine::comm::Comm;
use crate::engine::decomp::Decomp;
use crate::engine::procmap::layout;
use crate::sim::{RunError, Simulation};
use std::sync::Arc;

/// What a distributed run supports so far: atomic, bonded, granular and SPH systems (contact
/// histories travel with their atoms; bonded styles that keep no per-bond state), the
/// integrators and forces that act atom by atom, and the thermo computes that are sums.
const PAIRS: &[&str] = &[
    "lj/cut", "soft", "sph/taitwater", "sph/taitwater/morris", "sph/rhosum", "sph/idealgas", "sph/lj", "sph/heatconduction",
    "gran/hooke", "gran/hooke/history", "gran/hertz/history", "granular", "dmhs/sph/diffusion", "dmhs/lj/wet",
    "dmhs/heatconduction", "dmhs/blend", "bpm/spring", "dmhs/sph/delta", "zero",
];
/// (GROUP: a dynamic group's update, per owned atom; atom values by ID stop the run on ranks.)
const FIXES: &[&str] = &["nve", "nve/sphere", "viscous", "enforce2d", "gravity", "sph", "sph/stationary", "setforce", "addforce", "langevin", "freeze", "wall/gran", "bond/break", "dmhs/stokes", "dmhs/diffusion", "dmhs/swell",
    "dmhs/phase", "dmhs/cooling", "dmhs/bond/break", "wall/reflect", "GROUP", "nve/bpm/sphere", "STORE/LOCAL",
    "wall/lj93", "wall/lj126", "wall/lj1043", "wall/harmonic", "wall/morse", "wall/region", "indent", "temp/rescale", "temp/berendsen", "nvt", "npt", "nph", "deform",
    "move", "print", "ave/time", "dt/reset", "spring", "spring/self", "wall/gran/region", "heat/flow", "property/atom", "momentum",
    "halt", "recenter", "spring/rg", "temp/csvr", "nvt/sllod", "ave/histo", "vector", "pour", "deposit", "ave/chunk", "ave/atom", "aveforce", "adapt", "balance", "bond/create", "heat", "ehex", "thermal/conductivity", "viscosity", "ave/correlate",
    "rigid", "rigid/nve", "rigid/nvt", "rigid/npt", "rigid/nph", "rigid/small", "rigid/nve/small", "rigid/nvt/small", "rigid/npt/small", "rigid/nph/small"];
const COMPUTES: &[&str] = &["temp", "pe", "pressure", "ke", "erotate/sphere", "temp/sphere", "com", "reduce", "property/atom", "dmhs/phase/atom", "nbond/atom", "gyration", "vacf", "msd", "coord/atom", "ke/atom", "chunk/atom", "rdf", "pe/atom", "stress/atom",
    "temp/partial", "temp/com", "temp/region", "temp/ramp", "temp/profile", "temp/deform", "displace/atom", "sph/rho/atom", "sph/e/atom", "sph/t/atom",
    "erotate/sphere/atom", "contact/atom", "ke/rigid", "erotate/rigid", "heat/flux", "msd/chunk", "centro/atom"];
/// Per-atom computes a dump can evaluate on the whole system gathered at rank 0 (they read
/// only the atoms' own values, which travel with them, or the step's per-atom energies and
/// virials, gathered with them).
const GATHERED_COMPUTES: &[&str] = &["property/atom", "dmhs/phase/atom", "ke/atom", "pe/atom", "stress/atom", "displace/atom", "sph/rho/atom", "sph/e/atom", "sph/t/atom", "erotate/sphere/atom"];
/// Fixes whose per-atom values a dump reads from the gathered atoms (they keep them in an
/// array that travels with the atoms).
const GATHERED_FIXES: &[&str] = &["ave/atom"];
/// (The BPM styles keep each bond's reference state in every rank's topology; see
/// `bpm::rank_bond_list`.)
const BONDS: &[&str] = &["harmonic", "fene", "fene/expand", "morse", "bpm/rotational", "bpm/spring", "bpm/spring/plastic", "zero"];
const ANGLES: &[&str] = &["harmonic"];
const DIHEDRALS: &[&str] = &["harmonic", "quadratic"];

/// A distributed run moves its cuts when the most loaded rank owns this much more than the
/// mean (checked at each neighbour-list rebuild).
pub const REBALANCE: f64 = 1.2;

/// Per-rank counts at the end of a distributed run, for the run summary (sum, min, max).
pub struct RankCounts {
    pub nlocal: [f64; 3],
    pub nghost: [f64; 3],
    pub neighs: [f64; 3],
    /// Each stage's seconds over the ranks.
    pub stages: [crate::engine::timing::Spread; 6],
}

impl Simulation {
    /// Run as one of the ranks `comm` connects (before the deck's first command). Ranks other
    /// than 0 write neither the screen nor the log.
    pub fn set_comm(&mut self, comm: Arc<dyn Comm>) {
        if comm.size() > 1 {
            self.out.muted = comm.rank() != 0;
            self.state.decomp = Some(Decomp::new(comm, [1, 1, 1]));
        }
    }

    /// The number of ranks (1 for an ordinary run).
    pub fn nranks(&self) -> usize {
        self.state.decomp.as_ref().map_or(1, |d| d.comm.size())
    }

    /// The ghost cutoff of a distributed run: the longest pair cutoff plus the skin, or the
    /// `comm_modify cutoff` if longer (the least thickness of a sub-domain).
    pub(crate) fn ghost_cutoff(&self) -> f64 {
        (self.pair_cutoff_max() + self.state.neigh_settings.skin).max(self.state.comm_cutoff)
    }

    /// The longest pair cutoff over the type pairs (0 without a pair style).
    pub(crate) fn pair_cutoff_max(&self) -> f64 {
        let n = self.state.ntypes;
        self.pair.as_deref().map_or(0.0, |p| (1..=n).flat_map(|i| (i..=n).map(move |j| (i, j))).map(|(i, j)| p.cutoff(i, j)).fold(0.0, f64::max))
    }

    /// Why this deck cannot run on several ranks yet (None: it can).
    pub fn distributed_refusal(&self) -> Option<String> {
        self.distributed_refusal_for(self.nranks())
    }

    fn distributed_refusal_for(&self, ranks: usize) -> Option<String> {
        let what = if let Some(b) = self.bond_style.as_ref().filter(|b| !BONDS.contains(&b.name())) {
            Some(format!("bond_style {}", b.name()))
        } else if let Some(b) = self.bond_style.as_ref().filter(|b| b.as_bpm().is_some_and(|p| p.shared().volume)) {
            // each bond reads both atoms' volume sums: a ghost's would have to travel mid-pass
            Some(format!("bond_style {} volume/factor yes", b.name()))
        } else if let Some(b) = self.angle_style.as_ref().filter(|b| !ANGLES.contains(&b.name())) {
            Some(format!("angle_style {}", b.name()))
        } else if let Some(b) = self.dihedral_style.as_ref().filter(|b| !DIHEDRALS.contains(&b.name())) {
            Some(format!("dihedral_style {}", b.name()))
        } else if let Some(p) = self.pair.as_ref().and_then(|p| p.sub_styles().into_iter().find(|s| !PAIRS.contains(s))) {
            Some(format!("pair_style {p}"))
        } else if let Some(r) = self.pair.as_ref().and_then(|p| p.ranks_refusal()) {
            Some(r)
        } else if let Some(f) = self.fixes.iter().find(|f| !FIXES.contains(&f.style())) {
            Some(format!("fix {} ({})", f.id(), f.style()))
        } else if let Some(f) = self.fixes.iter().find(|f| f.rigid_template().is_some_and(|t| !t.is_empty())) {
            // bodies inserted by fix deposit or pour would be made by the inserting rank alone
            Some(format!("fix {} ({}) with a molecule template (mol)", f.id(), f.style()))
        } else if let Some(c) = self.computes.iter().find(|c| !COMPUTES.contains(&c.style())) {
            Some(format!("compute {} ({})", c.id(), c.style()))
        } else if let Some((c, (fix, id))) = self.computes.iter().find_map(|c| c.reads().into_iter().find(|r| !self.reads_on_ranks(r)).map(|r| (c, r))) {
            Some(format!("compute {} ({}) of {} {id}", c.id(), c.style(), if fix { "fix" } else { "compute" }))
        } else if let Some(d) = self.dumps.iter().find(|d| !self.dump_gathers(d)) {
            Some(format!("dump {} (it writes values of computes or fixes)", d.id))
        } else {
            None
        };
        let supported = format!(
            "pair styles {}; bond styles {}; angle styles {}; dihedral styles {}; fixes {}; computes {}",
            PAIRS.join(", "), BONDS.join(", "), ANGLES.join(", "), DIHEDRALS.join(", "), FIXES.join(", "), COMPUTES.join(", ")
        );
        what.map(|w| format!("{w} cannot run on {ranks} ranks yet; a run on several ranks supports atomic, bonded, granular and SPH systems with {supported}, and dumps of atom values, of the per-atom computes that read an atom's own values (property/atom, ke/atom, pe/atom, stress/atom, displace/atom, the sph/*/atom computes, ...), of fix ave/atom and of the broken bonds of a BPM style's store/local (run on one rank)"))
    }

    /// Whether rank 0 can write dump `d` from the gathered atoms: its compute and fix columns
    /// are of computes that read only the atoms' own values and of fixes that keep theirs with
    /// the atoms. A dump local may read fix STORE/LOCAL, whose rows (broken BPM bonds) every
    /// rank holds.
    fn dump_gathers(&self, d: &crate::output::dump::Dump) -> bool {
        let (peratom, local) = d.model_columns();
        local.iter().all(|r| r.fix && self.fixes.iter().any(|f| f.id() == r.id && f.style() == "STORE/LOCAL"))
            && peratom.iter().all(|r| match r.fix {
                true => self.fixes.iter().any(|f| f.id() == r.id && GATHERED_FIXES.contains(&f.style())),
                false => self.computes.iter().any(|c| c.id() == r.id && GATHERED_COMPUTES.contains(&c.style())),
            })
    }

    /// Whether a compute may read compute or fix `id` on ranks: one of the allowed computes
    /// with per-atom values (local rows are per rank) or one of the allowed fixes.
    fn reads_on_ranks(&self, (fix, id): &(bool, String)) -> bool {
        if *fix {
            self.fixes.iter().any(|f| f.id() == id && FIXES.contains(&f.style()) && f.local().is_none())
        } else {
            self.computes.iter().any(|c| c.id() == id && COMPUTES.contains(&c.style()) && c.local_cols().is_none())
        }
    }

    /// What a run on `n` ranks would do with the atoms there are now (`dmhs check --ranks N`):
    /// the processor grid, the atoms each rank would own, and what it cannot run yet.
    pub fn decomposition_plan(&self, n: usize) -> String {
        let Some(domain) = self.state.domain.as_ref() else { return format!("on {n} ranks: no box yet\n") };
        let l = match layout(n, &self.state.procs, self.state.grid_face_areas(domain), self.state.dimension) {
            Ok(l) => l,
            Err(e) => return format!("on {n} ranks: {e}\n"),
        };
        let procs = l.procs;
        let mut d = Decomp::new(Arc::new(crate::engine::comm::Serial), procs);
        d.set_layout(l);
        if self.state.balance {
            let hist = d.box_histograms(&self.state.atoms, domain);
            d.balance(domain, &hist, self.ghost_cutoff());
        }
        let mut owned = vec![0usize; n];
        for x in &self.state.atoms.x[..self.state.atoms.nlocal] {
            owned[d.owner(domain, x)] += 1;
        }
        let (min, max) = (owned.iter().min().copied().unwrap_or(0), owned.iter().max().copied().unwrap_or(0));
        let mut s = format!("on {n} ranks: {} by {} by {} processor grid; atoms per rank {min} to {max}", procs[0], procs[1], procs[2]);
        if n <= 16 {
            s += &format!(" ({})", owned.iter().map(|c| c.to_string()).collect::<Vec<_>>().join(", "));
        }
        s += "\n";
        if let Some(why) = self.distributed_refusal_for(n) {
            s += &format!("on {n} ranks: {why}\n");
        }
        s
    }

    /// The start of a distributed run: the processor grid for the box now, and each rank keeps
    /// the atoms in its sub-domain.
    pub(crate) fn distribute(&mut self) -> Result<(), RunError> {
        self.distribute_with(true)
    }

    /// [`Simulation::distribute`]; `report`: print the processor grid (a rerun prints it for
    /// its first snapshot only).
    pub(crate) fn distribute_with(&mut self, report: bool) -> Result<(), RunError> {
        let step = self.state.step;
        if let Some(why) = self.distributed_refusal() {
            return Err(RunError::new(step, why));
        }
        // shrink-wrapped faces around the atoms (every rank holds them all here) before the box
        // is cut: the setup's rebuild finds the same box, so every atom starts on its owner. A
        // triclinic box is shrink-wrapped in box fractions, as the rebuild does; the atoms keep
        // their positions for it
        if let Some(domain) = self.state.domain.as_ref().filter(|d| d.triclinic()) {
            let kept = self.state.atoms.x.clone();
            crate::engine::boundary::to_fractions(domain, &mut self.state.atoms);
            self.state.shrink_wrap();
            self.state.atoms.x = kept;
        } else {
            self.state.shrink_wrap();
        }
        let domain = self.state.domain.as_ref().ok_or_else(|| RunError::new(step, "no simulation box"))?;
        let ghost_cut = self.ghost_cutoff();
        let grid_file = self.state.procs.file.as_ref().map(|f| self.path(f));
        let areas = self.state.grid_face_areas(domain);
        let d = self.state.decomp.as_mut().expect("a decomposition");
        d.set_layout(layout(d.comm.size(), &self.state.procs, areas, self.state.dimension).map_err(|e| RunError::new(step, e))?);
        if let Some(path) = grid_file {
            // (every rank takes part in gathering the names)
            let names = d.comm.processor_names();
            if d.rank() == 0 {
                crate::output::log::write_atomic(&path, d.layout().file_text(&names).as_bytes()).map_err(|e| RunError::new(step, format!("Cannot open processors output file {}: {e}", path.display())))?;
            }
        }
        if self.state.balance {
            // every rank holds every atom here: the same counts, the same cuts
            let hist = d.box_histograms(&self.state.atoms, domain);
            d.balance(domain, &hist, ghost_cut);
        }
        let natoms = self.state.atoms.nlocal;
        self.state.atoms.clear_ghosts();
        d.distribute(&mut self.state.atoms, domain);
        self.state.distributed = Some(natoms);
        self.state.stored_on = None;
        self.state.lists_valid = false;
        // the per-atom order LAMMPS would keep is a serial notion: start afresh on each rank
        self.state.lammps_order = Default::default();
        let p = d.procs;
        if report {
            self.out.print(&format!("  {} by {} by {} MPI processor grid", p[0], p[1], p[2]));
        }
        Ok(())
    }

    /// The end of a distributed run: every rank holds the whole system again, contact
    /// histories included (the next run may hand an atom to another rank; write_restart
    /// writes them all).
    pub(crate) fn gather_ranks(&mut self) {
        if self.state.distributed.take().is_none() {
            return;
        }
        self.state.stored_on = None;
        let d = self.state.decomp.as_ref().expect("a decomposition");
        self.state.atoms = d.gathered(&self.state.atoms);
        if let Some(pair) = self.pair.as_mut() {
            for h in pair.histories() {
                d.gather_contacts(h);
            }
        }
        self.state.lists_valid = false;
        self.state.lammps_order = Default::default();
    }


    /// The ranks of a distributed run agree on a step's outcome: if any failed, every rank
    /// fails with the error of the first rank that did (its message names the rank).
    pub(crate) fn agree(&self, outcome: Result<(), RunError>) -> Result<(), RunError> {
        let Some(d) = self.state.decomp.as_ref().filter(|_| self.state.distributed.is_some()) else { return outcome };
        if !d.comm.any(outcome.is_err()) {
            return Ok(());
        }
        let mine: Vec<f64> = outcome.as_ref().err().map_or(Vec::new(), |e| e.message.bytes().map(f64::from).collect());
        let all = d.comm.allgather(mine);
        let (rank, text) = all.iter().enumerate().find(|(_, m)| !m.is_empty()).map(|(k, m)| (k, String::from_utf8_lossy(&m.iter().map(|&b| b as u8).collect::<Vec<u8>>()).into_owned())).unwrap_or_default();
        // (an outcome agreed on before, inside this step, already names the rank it came from)
        let size = d.comm.size();
        let named = (0..size).any(|r| text.starts_with(&format!("on rank {r} of {size}: ")));
        let message = if named { text } else { format!("on rank {rank} of {size}: {text}") };
        Err(match outcome {
            Err(e) => RunError { message, ..e },
            Ok(()) => RunError::new(self.state.step, message),
        })
    }

    /// [`Simulation::agree`] on a result with a value: the value where every rank succeeded.
    pub(crate) fn agreed<T>(&self, outcome: Result<T, RunError>) -> Result<T, RunError> {
        match outcome {
            Ok(v) => self.agree(Ok(())).map(|_| v),
            Err(e) => {
                let step = e.step;
                Err(self.agree(Err(e)).err().unwrap_or_else(|| RunError::new(step, "a rank failed")))
            }
        }
    }

    /// The sum, minimum and maximum over the ranks of each count.
    pub(crate) fn rank_counts(&self) -> Option<RankCounts> {
        let d = self.state.decomp.as_ref().filter(|_| self.state.distributed.is_some())?;
        let local = [self.state.atoms.nlocal as f64, self.state.atoms.nghost() as f64, self.state.neighbor.list.lammps_count(self.state.atoms.nlocal, &self.state.special_bonds.lj, &self.state.special_bonds.coul, self.state.newton_pair)];
        let (mut sum, mut max, mut min) = (local, local, local);
        d.comm.sum(&mut sum);
        d.comm.max(&mut max);
        d.comm.min(&mut min);
        let k = |i: usize| [sum[i], min[i], max[i]];
        let t = self.timers.seconds;
        let (mut tsum, mut tmax, mut tmin) = (t, t, t);
        let mut tsq = t.map(|x| x * x);
        d.comm.sum(&mut tsum);
        d.comm.sum(&mut tsq);
        d.comm.max(&mut tmax);
        d.comm.min(&mut tmin);
        let n = d.comm.size() as f64;
        let stages = std::array::from_fn(|s| crate::engine::timing::Spread::from_sums(tmin[s], tsum[s] / n, tmax[s], tsq[s] / n));
        Some(RankCounts { nlocal: k(0), nghost: k(1), neighs: k(2), stages })
    }
}
