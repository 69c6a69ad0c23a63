//! Pair styles and the engine-owned pair loop.
//!
//! A style file holds its parameters, its `pair_style`/`pair_coeff` parsing and a kernel;
//! the loop over the neighbour list, Newton's third law, threading and energy/virial tallies
//! live here. Adding a style touches one list: [`new_pair_style`].

pub mod contact;
pub mod dmhs_blend;
pub mod dmhs_heatconduction;
pub mod dmhs_lj_wet;
pub mod dmhs_sph_diffusion;
pub mod gran_hooke;
pub mod gran_hooke_history;
pub mod granular;
pub mod hybrid;
pub mod lj_cut;
pub mod sph;
pub mod sph_loop;
pub mod sph_heatconduction;
pub mod sph_rhosum;
pub mod sph_taitwater;
pub mod sph_taitwater_morris;
pub mod zero;

use crate::engine::atoms::Atoms;
use crate::engine::neighbor::{special_level, NeighList, NEIGH_MASK};
pub use crate::engine::par::{at, for_each_chunk, for_each_chunk_then, for_each_slab, SharedMut, PARALLEL_MIN_ATOMS};
pub use crate::engine::tally::{sum_tallies, Tally};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

/// How unset I,J coefficients are derived from I,I and J,J (`pair_modify mix`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MixRule {
    Geometric,
    Arithmetic,
    SixthPower,
}

impl MixRule {
    /// LAMMPS `Pair::mix_energy`.
    pub fn energy(self, eps1: f64, eps2: f64, sig1: f64, sig2: f64) -> f64 {
        match self {
            MixRule::Geometric | MixRule::Arithmetic => (eps1 * eps2).sqrt(),
            MixRule::SixthPower => {
                2.0 * (eps1 * eps2).sqrt() * sig1.powf(3.0) * sig2.powf(3.0) / (sig1.powf(6.0) + sig2.powf(6.0))
            }
        }
    }
    /// LAMMPS `Pair::mix_distance`.
    pub fn distance(self, sig1: f64, sig2: f64) -> f64 {
        match self {
            MixRule::Geometric => (sig1 * sig2).sqrt(),
            MixRule::Arithmetic => 0.5 * (sig1 + sig2),
            MixRule::SixthPower => (0.5 * (sig1.powf(6.0) + sig2.powf(6.0))).powf(1.0 / 6.0),
        }
    }
}

/// `pair_modify` settings shared by all styles.
#[derive(Clone, Debug)]
pub struct PairModify {
    pub mix: MixRule,
    pub shift: bool,
}

impl Default for PairModify {
    fn default() -> Self {
        PairModify { mix: MixRule::Geometric, shift: false }
    }
}

/// Per-atom outputs a pair style adds to (owned atoms; empty slices for arrays the atom style
/// does not have).
pub struct PairOutput<'a> {
    pub f: &'a mut [[f64; 3]],
    pub torque: &'a mut [[f64; 3]],
    pub drho: &'a mut [f64],
    pub desph: &'a mut [f64],
    /// Water-mass rates (`dmhs/dwater`; empty without a water field).
    pub dwater: &'a mut [f64],
}

/// What a pair computation may read.
pub struct PairInput<'a> {
    pub atoms: &'a Atoms,
    pub list: &'a NeighList,
    /// `special_bonds` lj weights for levels 0..=3 (level 0 = 1.0).
    pub special_lj: [f64; 4],
    pub special_coul: [f64; 4],
    /// Compute energies and virial on this step.
    pub eflag: bool,
    pub ntypes: usize,
    /// Type pairs this style handles (row-major over `0..=ntypes`); None = all
    /// (set by `hybrid` for its sub-styles).
    pub type_filter: Option<&'a [bool]>,
    /// Per-type masses (index 0 unused).
    pub type_mass: &'a [f64],
    pub dt: f64,
    pub step: i64,
    /// False during run setup (LAMMPS' `shearupdate`: contact histories are not advanced).
    pub advance: bool,
    pub dimension: usize,
}

/// What a pair style may check and read before a run (granular styles need the atoms'
/// radii for their cutoffs and ghost velocities for their forces).
pub struct PairSetup<'a> {
    pub atoms: &'a Atoms,
    pub ntypes: usize,
    /// `comm_modify vel yes`
    pub comm_vel: bool,
}

/// A pair style as the engine drives it.
pub trait PairStyle: Send + Sync {
    fn style(&self) -> &str;
    /// `pair_coeff I J args...` with the type ranges already parsed (`args` starts after them).
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()>;
    /// Checks against the atoms before a run (called before `init`); an error stops the run.
    fn init_sim(&mut self, _setup: &PairSetup) -> Result<(), String> {
        Ok(())
    }
    /// Prepare for a run (mixing, offsets). An error names what is missing.
    /// `active` (row-major over `0..=ntypes`) limits the type pairs that must be set, for
    /// sub-styles of `hybrid`; the others get no interaction.
    fn init(&mut self, ntypes: usize, modify: &PairModify, active: Option<&[bool]>) -> Result<(), String>;
    /// Interaction cutoff for a type pair after `init` (0 = no interaction).
    fn cutoff(&self, it: usize, jt: usize) -> f64;
    /// Add forces (and torques, density and energy rates) on owned atoms to `out`; return the
    /// tallies when `input.eflag`. `&mut self` lets a style keep state such as contact history.
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally;
    /// Called after every neighbour-list rebuild (before `compute`); `order` is the permutation
    /// applied to owned atoms (new k takes old `order[k]`).
    fn rebuilt(&mut self, _input: &PairInput, _order: &[usize]) {}
    /// The contact-history stores of the style (granular styles), for write_restart and
    /// read_restart; empty for styles without history.
    fn histories(&mut self) -> Vec<&mut crate::engine::contact_history::ContactHistory> {
        vec![]
    }
    /// The words of `pair_coeff` for type I (for write_data's "Pair Coeffs"); None if the
    /// style has no per-type form.
    fn data_coeffs(&self, _it: usize) -> Option<String> {
        None
    }
    /// One line per line of `pair_coeff` to reproduce the settings (for `dmhs check`).
    fn describe(&self) -> String {
        self.style().to_string()
    }
    /// The style uses per-type masses (`mass`), even for atom styles with per-atom masses.
    fn needs_type_mass(&self) -> bool {
        false
    }
    /// A density pass before the force pass (sph/rhosum): may overwrite `rho` of owned atoms;
    /// returns true if it did (the engine then refreshes ghosts).
    fn density_pass(&mut self, _input: &PairInput, _rho: &mut [f64]) -> bool {
        false
    }
    /// SPH parameters for stability estimates (`dmhs check`), if this is an SPH style.
    fn sph_info(&self) -> Option<SphInfo> {
        None
    }
    /// Seconds spent in each part of the style since the last reset, with a label per part
    /// (hybrid: one per sub-style); empty when the style is a single model (the Pair stage
    /// time is then its time).
    fn model_seconds(&self) -> Vec<(String, f64)> {
        Vec::new()
    }
    /// The largest normal contact stiffness k_n (force per overlap) of a granular contact style,
    /// for the DEM time-step estimate of `dmhs check`.
    fn contact_stiffness(&self) -> Option<f64> {
        None
    }
    /// Start the per-part clocks of [`PairStyle::model_seconds`] again (at run setup).
    fn reset_model_seconds(&mut self) {}
    /// Other time-step limits of the style (e.g. explicit diffusion), for `dmhs check` and the
    /// warnings at the start of a run.
    fn dt_limits(&self) -> Vec<crate::sim::stability::Limit> {
        vec![]
    }
}

/// What stability estimates need from SPH styles.
#[derive(Clone, Debug, Default)]
pub struct SphInfo {
    /// Smallest kernel support h over all pairs.
    pub h_min: f64,
    /// Largest sound speed c0 and the smallest rho0 over types with parameters.
    pub c_max: f64,
    pub rho0_min: f64,
    /// Largest dynamic viscosity (Morris styles).
    pub mu_max: Option<f64>,
    /// Reference density per type (index 0 unused; 0 = no Tait parameters for that type).
    pub rho0: Vec<f64>,
    /// Morris styles: (type, rho0, c0, mu of the type with itself) for each type with Tait
    /// parameters, for the sound-viscosity limit (stability.rs).
    pub sound_visc: Vec<(usize, f64, f64, f64)>,
}

impl SphInfo {
    /// From the Tait tables; `morris`: the pair value is a dynamic viscosity.
    pub fn from_tait(types: &sph::TaitTypes, pairs: &sph::PairTable<(f64, f64)>, n: usize, morris: Option<()>) -> SphInfo {
        let mut info = SphInfo { h_min: f64::INFINITY, c_max: 0.0, rho0_min: f64::INFINITY, mu_max: morris.map(|_| 0.0), rho0: types.rho0.clone(), sound_visc: vec![] };
        for i in 1..=n.min(types.rho0.len().saturating_sub(1)) {
            if types.rho0[i] > 0.0 {
                info.c_max = info.c_max.max(types.c0[i]);
                info.rho0_min = info.rho0_min.min(types.rho0[i]);
                if morris.is_some() && i <= pairs.n && pairs.is_set(i, i) {
                    info.sound_visc.push((i, types.rho0[i], types.c0[i], pairs.get(i, i).0));
                }
            }
            for j in i..=n.min(pairs.n) {
                if pairs.is_set(i, j) {
                    let (x, h) = *pairs.get(i, j);
                    info.h_min = info.h_min.min(h);
                    if let Some(m) = info.mu_max.as_mut() {
                        *m = m.max(x);
                    }
                }
            }
        }
        info
    }
}

/// Squared cutoffs per type pair from an SPH table (`h_of` picks h); 0 for pairs not active.
pub fn sph_cutsq<T: Clone + Default>(pairs: &sph::PairTable<T>, n: usize, active: Option<&[bool]>, h_of: impl Fn(&T) -> f64) -> Vec<f64> {
    let mut c = vec![0.0; (n + 1) * (n + 1)];
    for i in 1..=n {
        for j in 1..=n {
            let on = active.map(|a| a[i * (n + 1) + j]).unwrap_or(true);
            if on && pairs.is_set(i, j) {
                let h = h_of(pairs.get(i, j));
                c[i * (n + 1) + j] = h * h;
            }
        }
    }
    c
}

/// Build a pair style from `pair_style NAME args...`.
pub fn new_pair_style(name: &Word, args: &[Word], cmd: &Command) -> DResult<Box<dyn PairStyle>> {
    match name.text.as_str() {
        "lj/cut" => Ok(Box::new(lj_cut::LjCut::from_lammps(args, cmd)?)),
        "sph/taitwater" => Ok(Box::new(sph_taitwater::SphTaitwater::from_lammps(args, cmd)?)),
        "sph/taitwater/morris" => Ok(Box::new(sph_taitwater_morris::SphTaitwaterMorris::from_lammps(args, cmd)?)),
        "sph/heatconduction" => Ok(Box::new(sph_heatconduction::SphHeatConduction::from_lammps(args, cmd)?)),
        "sph/rhosum" => Ok(Box::new(sph_rhosum::SphRhoSum::from_lammps(args, cmd)?)),
        "dmhs/blend" => Ok(Box::new(dmhs_blend::DmhsBlend::from_lammps(args, cmd)?)),
        "dmhs/heatconduction" => Ok(Box::new(dmhs_heatconduction::DmhsHeatConduction::from_lammps(args, cmd)?)),
        "dmhs/sph/diffusion" => Ok(Box::new(dmhs_sph_diffusion::SphDiffusion::from_lammps(args, cmd)?)),
        "dmhs/lj/wet" => Ok(Box::new(dmhs_lj_wet::LjWet::from_lammps(args, cmd)?)),
        "gran/hooke" => Ok(Box::new(gran_hooke::GranHooke::from_lammps(args, cmd)?)),
        "gran/hooke/history" => Ok(Box::new(gran_hooke_history::GranHookeHistory::from_lammps(args, cmd)?)),
        "granular" => Ok(Box::new(granular::Granular::from_lammps(args, cmd)?)),
        "zero" => Ok(Box::new(zero::PairZero::from_lammps(args, cmd)?)),
        "hybrid" | "hybrid/overlay" => Ok(Box::new(hybrid::Hybrid::from_lammps(name, args, cmd)?)),
        other => Err(crate::models::styles::unsupported_style("pair", name, other, SUPPORTED)),
    }
}

/// Pair styles this build implements.
pub const SUPPORTED: &[&str] = &["lj/cut", "gran/hooke", "gran/hooke/history", "granular", "zero", "sph/taitwater", "sph/taitwater/morris", "sph/heatconduction", "sph/rhosum", "dmhs/sph/diffusion", "dmhs/lj/wet", "hybrid", "hybrid/overlay", "dmhs/heatconduction", "dmhs/blend"];

/// A kernel for a central pair force between two point particles. Parameters are looked up
/// once per atom i as a row over j's type, then evaluated per pair.
pub trait CentralKernel: Sync {
    type Params: Sync;
    /// Parameters of type pairs (ti, 0..=ntypes), indexed by j's type.
    fn row(&self, ti: usize) -> &[Self::Params];
    /// Squared cutoff of a type pair.
    fn cutsq(p: &Self::Params) -> f64;
    /// `(fpair, energy)` for `rsq` inside the cutoff, where the force on i is
    /// `fpair * (x_i - x_j)`; `factor` is the special-bond weight. The energy is only used
    /// when `EFLAG`.
    fn eval<const EFLAG: bool>(p: &Self::Params, rsq: f64, factor: f64) -> (f64, f64);
}

/// The loop for central forces: every listed pair, Newton's third law for owned partners,
/// energy and virial with LAMMPS' `ev_tally` weights (a pair with a ghost counts half on
/// each side, because each side lists it). Specialised at compile time on whether energies
/// are tallied, special weights exist and a type filter applies, so the common case pays for
/// none of them.
pub fn compute_central<K: CentralKernel>(kernel: &K, input: &PairInput, f: &mut [[f64; 3]]) -> Tally {
    let special = input.list.has_special;
    match (input.eflag, special, input.type_filter.is_some()) {
        (false, false, false) => central_loop::<K, false, false, false>(kernel, input, f),
        (true, false, false) => central_loop::<K, true, false, false>(kernel, input, f),
        (false, true, false) => central_loop::<K, false, true, false>(kernel, input, f),
        (true, true, false) => central_loop::<K, true, true, false>(kernel, input, f),
        (false, false, true) => central_loop::<K, false, false, true>(kernel, input, f),
        (true, false, true) => central_loop::<K, true, false, true>(kernel, input, f),
        (false, true, true) => central_loop::<K, false, true, true>(kernel, input, f),
        (true, true, true) => central_loop::<K, true, true, true>(kernel, input, f),
    }
}

fn central_loop<K: CentralKernel, const EFLAG: bool, const SPECIAL: bool, const FILTER: bool>(
    kernel: &K,
    input: &PairInput,
    f: &mut [[f64; 3]],
) -> Tally {
    let a = input.atoms;
    let nlocal = a.nlocal;
    let stride = input.ntypes + 1;
    let x = &a.x[..];
    let typ = &a.typ[..];
    assert!(x.len() == typ.len() && f.len() >= nlocal);
    let shared = SharedMut::new(f);
    let parts = for_each_chunk(input.list, |chunk| {
        let mut t = Tally::default();
        for i in chunk.start..chunk.end {
            let xi = x[i];
            let ti = typ[i];
            let row = kernel.row(ti);
            let filter = if FILTER { &input.type_filter.unwrap()[ti * stride..(ti + 1) * stride] } else { &[][..] };
            let mut fi = [0.0f64; 3];
            for &jraw in chunk.neighbors(i) {
                let j = (jraw & NEIGH_MASK) as usize;
                // SAFETY: the list builder stores only indices < nall = x.len() = typ.len()
                let (xj, tj) = unsafe { (*x.get_unchecked(j), *typ.get_unchecked(j)) };
                if FILTER && !filter[tj] {
                    continue;
                }
                let dx = xi[0] - xj[0];
                let dy = xi[1] - xj[1];
                let dz = xi[2] - xj[2];
                let rsq = dx * dx + dy * dy + dz * dz;
                let p = &row[tj];
                // branch-free cutoff: about a quarter of the listed pairs (those in the skin)
                // are outside, which a branch predicts badly; their force is masked to +0
                let keep = if rsq < K::cutsq(p) { u64::MAX } else { 0 };
                let factor = if SPECIAL { input.special_lj[special_level(jraw)] } else { 1.0 };
                let (fpair, e) = K::eval::<EFLAG>(p, rsq, factor);
                let fpair = f64::from_bits(fpair.to_bits() & keep);
                let e = f64::from_bits(e.to_bits() & keep);
                fi[0] += dx * fpair;
                fi[1] += dy * fpair;
                fi[2] += dz * fpair;
                let w = if j < nlocal {
                    // SAFETY: j is an owned atom of this chunk or the next (see for_each_chunk)
                    let fj = unsafe { shared.get(j) };
                    fj[0] -= dx * fpair;
                    fj[1] -= dy * fpair;
                    fj[2] -= dz * fpair;
                    1.0
                } else {
                    0.5
                };
                if EFLAG {
                    t.evdwl += w * e;
                    t.virial[0] += w * dx * dx * fpair;
                    t.virial[1] += w * dy * dy * fpair;
                    t.virial[2] += w * dz * dz * fpair;
                    t.virial[3] += w * dx * dy * fpair;
                    t.virial[4] += w * dx * dz * fpair;
                    t.virial[5] += w * dy * dz * fpair;
                }
            }
            // SAFETY: i belongs to this chunk
            let fo = unsafe { shared.get(i) };
            fo[0] += fi[0];
            fo[1] += fi[1];
            fo[2] += fi[2];
        }
        t
    });
    sum_tallies(&parts)
}

/// Per-type-pair table (row-major over `0..=ntypes`), symmetric by construction.
#[derive(Clone, Debug, Default)]
pub struct TypeTable<T: Clone + Default> {
    pub n: usize,
    pub data: Vec<T>,
}

impl<T: Clone + Default> TypeTable<T> {
    pub fn new(ntypes: usize) -> Self {
        TypeTable { n: ntypes, data: vec![T::default(); (ntypes + 1) * (ntypes + 1)] }
    }
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> &T {
        &self.data[i * (self.n + 1) + j]
    }
    /// Row i: the values for (i, 0..=n).
    #[inline]
    pub fn row(&self, i: usize) -> &[T] {
        &self.data[i * (self.n + 1)..(i + 1) * (self.n + 1)]
    }
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, v: T) {
        let s = self.n + 1;
        self.data[i * s + j] = v.clone();
        self.data[j * s + i] = v;
    }
}

/// Parse the two type ranges of `pair_coeff I J ...`; LAMMPS only sets pairs with I <= J.
pub fn coeff_type_ranges(args: &mut Args, ntypes: usize) -> DResult<(usize, usize, usize, usize)> {
    let (ilo, ihi) = args.type_range("atom type I", ntypes)?;
    let (jlo, jhi) = args.type_range("atom type J", ntypes)?;
    Ok((ilo, ihi, jlo, jhi))
}

/// Error for a `pair_coeff` that sets no pair (e.g. `pair_coeff 2 1` with only I > J).
pub fn no_pairs_set(cmd: &Command) -> Diagnostic {
    Diagnostic::at(cmd.span, "pair_coeff sets no type pair (LAMMPS needs I <= J)", "no I <= J pair in these ranges")
}
