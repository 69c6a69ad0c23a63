//! Pair styles and the engine-owned pair loop.
//!
//! A style file holds its parameters, its `pair_style`/`pair_coeff` parsing and a kernel;
//! the loop over the neighbour list, Newton's third law, threading and energy/virial tallies
//! live here. Adding a style touches one list: [`new_pair_style`].

pub mod bpm_spring;
pub mod classic;
pub mod contact;
pub mod dmhs_blend;
pub mod dmhs_heatconduction;
pub mod dmhs_lj_wet;
pub mod dmhs_sph_delta;
pub mod dmhs_sph_diffusion;
pub mod gran_hooke;
pub mod gran_hooke_history;
pub mod granular;
pub mod hybrid;
pub mod lj_cut;
pub mod peratom;
pub mod soft;
pub mod sph;
pub mod sph_loop;
pub mod sph_heatconduction;
pub mod sph_idealgas;
pub mod sph_lj;
pub mod sph_rhosum;
pub mod sph_taitwater;
pub mod sph_taitwater_morris;
pub mod zero;

use crate::engine::atoms::Atoms;
use crate::engine::fields::Field;
use crate::engine::neighbor::{special_level, NeighList, NEIGH_MASK};
use crate::engine::par::{slab_phase, AtomsMut};
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

/// `pair_modify` settings: the style's, or one hybrid sub-style's (`pair_modify pair M ...`).
#[derive(Clone, Copy, Debug, PartialEq)]
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
    /// The rate fields ([`crate::engine::fields::RATES`]) and pair sums
    /// ([`crate::engine::fields::PAIR_SUMS`]) some model registered.
    pub fields: Vec<(Field, &'a mut [f64])>,
    /// The per-atom tallies of this force evaluation, when compute pe/atom or stress/atom needs
    /// them: styles whose loops cannot evaluate a pair again (contact histories) add their
    /// pairs here as they go, and their [`PairStyle::tally_peratom`] adds nothing.
    pub peratom: Option<&'a mut crate::engine::tally::PerAtomTally>,
}

/// A per-particle rate a pair style adds to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rate {
    /// drho/dt (`drho`)
    Density,
    /// d(esph)/dt (`desph`)
    Energy,
    /// a rate field such as [`crate::engine::fields::WATER_RATE`]
    Field(Field),
}

impl<'a> PairOutput<'a> {
    /// The forces and the slices two different rates add to; a rate that is `None`, that the
    /// atoms lack, or that is asked for twice gives an empty slice.
    pub fn forces_and_rates(&mut self, first: Option<Rate>, second: Option<Rate>) -> (&mut [[f64; 3]], &mut [f64], &mut [f64]) {
        let mut drho = Some(&mut *self.drho);
        let mut desph = Some(&mut *self.desph);
        let mut fields: Vec<Option<(Field, &mut [f64])>> = self.fields.iter_mut().map(|(f, s)| Some((*f, &mut **s))).collect();
        let a = take_rate(first, &mut drho, &mut desph, &mut fields);
        let b = take_rate(second, &mut drho, &mut desph, &mut fields);
        (&mut *self.f, a, b)
    }
}

fn take_rate<'s>(r: Option<Rate>, drho: &mut Option<&'s mut [f64]>, desph: &mut Option<&'s mut [f64]>, fields: &mut [Option<(Field, &'s mut [f64])>]) -> &'s mut [f64] {
    let slice = match r {
        None => None,
        Some(Rate::Density) => drho.take(),
        Some(Rate::Energy) => desph.take(),
        Some(Rate::Field(want)) => fields.iter_mut().find(|e| matches!(e, Some((f, _)) if *f == want)).and_then(|e| e.take()).map(|(_, s)| s),
    };
    slice.unwrap_or_default()
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
    /// `newton_pair on`: LAMMPS' global virial is then F dot r of the forces (virial_fdotr),
    /// which differs from the pairs' ev_tally for a force not along the pair (Morris viscosity).
    pub newton_pair: bool,
    /// Which atom of a pair LAMMPS lists it from, as of the last rebuild.
    pub sides: Option<&'a crate::engine::lammps_order::ListSides>,
    /// Granular effective masses with rigid bodies ([`crate::engine::state::State::rigid_mass`]);
    /// None: the atoms' rmass.
    pub rigid_mass: Option<&'a [f64]>,
    /// The group bit of fix freeze (0: none): a granular contact with a frozen sphere takes
    /// the other sphere's mass as m_eff (LAMMPS' freeze_group_bit).
    pub freeze_bit: u32,
}

impl<'a> PairInput<'a> {
    /// The input of the engine's pair style on `state` (its list, special weights and masses),
    /// with fix freeze's group bit (0: none).
    pub fn of_state(state: &'a crate::engine::state::State, freeze_bit: u32, eflag: bool, advance: bool) -> PairInput<'a> {
        PairInput {
            atoms: &state.atoms,
            list: &state.neighbor.list,
            special_lj: state.special_bonds.lj,
            special_coul: state.special_bonds.coul,
            eflag,
            ntypes: state.ntypes,
            type_filter: None,
            type_mass: &state.type_mass,
            dt: state.dt,
            step: state.step,
            advance,
            dimension: state.dimension,
            newton_pair: state.newton_pair,
            sides: state.lammps_order.sides(),
            rigid_mass: (!state.rigid_mass.is_empty()).then_some(&state.rigid_mass[..]),
            freeze_bit,
        }
    }

    /// Whether atom `i` (owned or ghost) is in fix freeze's group.
    #[inline(always)]
    pub fn frozen(&self, i: usize) -> bool {
        self.freeze_bit != 0 && self.atoms.mask[i] & self.freeze_bit != 0
    }
}

/// What a pair style may check and read before a run (granular styles need the atoms'
/// radii for their cutoffs and ghost velocities for their forces).
pub struct PairSetup<'a> {
    pub atoms: &'a Atoms,
    pub ntypes: usize,
    /// `comm_modify vel yes`
    pub comm_vel: bool,
    /// `newton on` (for pairs)
    pub newton_pair: bool,
    /// Per type, the largest radius of particles fixes will insert during the run (granular
    /// cutoffs must cover them before they exist).
    pub insert_radius: Vec<f64>,
}

impl PairSetup<'_> {
    /// Largest radius of each type 0..=n among the owned atoms and the particles fixes will
    /// insert (granular cutoffs: LAMMPS' maxrad_dynamic).
    pub fn max_radii(&self, n: usize) -> Vec<f64> {
        let a = self.atoms;
        let mut r: Vec<f64> = (0..=n).map(|t| self.insert_radius.get(t).copied().unwrap_or(0.0)).collect();
        for i in 0..a.nlocal {
            if let Some(m) = r.get_mut(a.typ[i]) {
                *m = m.max(a.radius[i]);
            }
        }
        r
    }
}

/// A pair style as the engine drives it.
pub trait PairStyle: Send + Sync {
    fn style(&self) -> &str;
    /// The styles that compute forces: this one, or a hybrid's sub-styles.
    fn sub_styles(&self) -> Vec<&str> {
        vec![self.style()]
    }
    /// `pair_modify pair M [k] ...`: the settings of the hybrid sub-style named by the next
    /// words of `args` (its instance number `k` when it is listed more than once), made from
    /// `global` the first time. Other styles have no sub-styles (LAMMPS' error).
    fn sub_modify(&mut self, args: &mut Args, _global: &PairModify) -> DResult<&mut PairModify> {
        let w = args.word("sub-style name")?;
        Err(args.error_at(w, "pair_modify pair can only be used with pair_style hybrid or hybrid/overlay", "not a hybrid pair style"))
    }
    /// The sub-styles' own settings (`pair_modify pair`), each changed with the keywords of a
    /// `pair_modify` without `pair`, which apply to every sub-style too.
    fn each_sub_modify(&mut self, _f: &mut dyn FnMut(&mut PairModify)) {}
    /// `pair_coeff I J args...` with the type ranges already parsed (`args` starts after them).
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()>;
    /// A per-type-pair parameter that fix adapt may change (LAMMPS' Pair::extract with
    /// dim 2): its value for types i <= j; None if the style has no such parameter.
    fn adapt_get(&self, _param: &str, _i: usize, _j: usize) -> Option<f64> {
        None
    }
    /// Set it (false: no such parameter); `init` then re-derives mixed and cached values
    /// (LAMMPS' Pair::reinit).
    fn adapt_set(&mut self, _param: &str, _i: usize, _j: usize, _value: f64) -> bool {
        false
    }
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
    /// Whether the style's neighbour list holds the pairs within their radii sum + skin at
    /// each build (LAMMPS' size lists, which granular styles request) instead of the type
    /// cutoff + skin: a sphere that grew since the run began is listed as in LAMMPS.
    fn size_list(&self) -> bool {
        false
    }
    /// Add forces (and torques, density and energy rates) on owned atoms to `out`; return the
    /// tallies when `input.eflag`. `&mut self` lets a style keep state such as contact history.
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally;
    /// Whether `compute` adds its pairs to [`PairOutput::peratom`] itself (then
    /// `tally_peratom` has nothing left to add).
    fn tallies_in_loop(&self) -> bool {
        false
    }
    /// Per-atom energies and virials of this style's pairs, into the pair tallies of `out`
    /// (compute pe/atom and stress/atom); an error for styles that do not tally them yet.
    fn tally_peratom(&mut self, _input: &PairInput, _out: &mut crate::engine::tally::PerAtomTally) -> Result<(), String> {
        if self.tallies_in_loop() {
            return Ok(());
        }
        Err(format!("pair style {} does not tally per-atom energies and virials yet (compute pe/atom and stress/atom need them; supported: lj/cut, soft, zero, the granular, SPH and BPM styles, hybrid of these)", self.style()))
    }
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
    /// A style that only adds to the density rate of an SPH density style (dmhs/sph/delta):
    /// the rest density it assumes per type (index 0 unused, 0: not covered), which `hybrid`
    /// checks against the density style's.
    fn diffuses_density(&self) -> Option<Vec<f64>> {
        None
    }
    /// The density diffusivity kappa (m^2/s) the style gives type `t` with itself (dmhs/sph/delta:
    /// delta h c0 / 2), which damps sound waves as the kinematic viscosity does (the
    /// sound-viscosity limit becomes 2 (nu + kappa)/c^2, src/sim/stability.rs).
    fn density_diffusivity(&self, _t: usize) -> f64 {
        0.0
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
    /// The largest curvature V''(r_min) of a pair potential's well (force per length), for the
    /// time-step estimate of potentials without another (Lennard-Jones).
    fn well_stiffness(&self) -> Option<f64> {
        None
    }
    /// Per-atom fields the style keeps on the atoms (made at pair_coeff and before a run).
    fn atom_fields(&self) -> &'static [crate::engine::fields::Field] {
        &[]
    }
    /// Work on the atoms and the style's contact histories before each force evaluation of a
    /// run (`setup`: at its setup, after the fixes' setup_pre_force), as the fix a LAMMPS style
    /// adds for itself does (pair granular mdr: fix GRANULAR/MDR).
    fn pre_force(&mut self, _state: &mut crate::engine::state::State, _setup: bool) -> Result<(), String> {
        Ok(())
    }
    /// The `mdr` normal model of pair granular, when its pairs use it (after `init`): granular
    /// region walls with mdr must agree with it (LAMMPS' fix GRANULAR/MDR checks).
    fn mdr_model(&self) -> Option<crate::models::pair::granular::mdr::Mdr> {
        None
    }
    /// Why the style cannot run on several ranks yet (None: it can if its name is supported).
    fn ranks_refusal(&self) -> Option<String> {
        None
    }
    /// Start the per-part clocks of [`PairStyle::model_seconds`] again (at run setup).
    fn reset_model_seconds(&mut self) {}
    /// Other time-step limits of the style (e.g. explicit diffusion), for `dmhs check` and the
    /// warnings at the start of a run.
    fn dt_limits(&self) -> Vec<crate::models::Limit> {
        vec![]
    }
    /// How many extra values [`PairStyle::single`] gives (LAMMPS' single_extra, the `pN` of
    /// compute pair/local); None: the style has no single (LAMMPS' single_enable 0).
    fn single_extra(&self) -> Option<usize> {
        None
    }
    /// LAMMPS' Pair::single: the interaction of the listed pair i-j at `rsq` with the special
    /// weights, as the style reports one pair (compute pair/local): its energy, its force over
    /// r and its extra values. Contact styles read the stored history without advancing it.
    /// Err: why the pair cannot be evaluated.
    fn single(&self, _input: &PairInput, _i: usize, _j: usize, _rsq: f64, _factor_coul: f64, _factor_lj: f64) -> Result<Single, String> {
        Err(format!("Pair style {} does not support compute pair/local", self.style()))
    }
}

/// The most extra values of [`PairStyle::single`] (pair granular's 12).
pub const MAX_SINGLE_EXTRA: usize = 12;

/// One pair as [`PairStyle::single`] reports it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Single {
    pub eng: f64,
    /// The force on i over r (LAMMPS' fforce): F_i = fpair (x_i - x_j).
    pub fpair: f64,
    /// The style's extra values (LAMMPS' svector), the first `single_extra` of them.
    pub extra: [f64; MAX_SINGLE_EXTRA],
}

/// [`PairStyle::single`] of a central kernel: the force loop's formula for one pair (0 outside
/// the cutoff, as the loop does not reach it).
pub fn central_single<K: CentralKernel>(kernel: &K, ti: usize, tj: usize, rsq: f64, factor: f64, si: &K::Site, sj: &K::Site) -> Single {
    let p = &kernel.row(ti)[tj];
    if rsq >= K::cutsq(p, si, sj) {
        return Single::default();
    }
    let (fpair, eng) = K::eval::<true>(p, rsq, factor, si, sj);
    Single { eng, fpair, extra: [0.0; MAX_SINGLE_EXTRA] }
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
pub fn sph_cutsq<T: Clone + Default>(pairs: &sph::PairTable<T>, n: usize, active: Option<&[bool]>, h_of: impl Fn(&T) -> f64) -> Result<Vec<f64>, String> {
    let mut c = type_pair_vec(n, 0.0)?;
    for i in 1..=n {
        for j in 1..=n {
            let on = active.map(|a| a[i * (n + 1) + j]).unwrap_or(true);
            if on && pairs.is_set(i, j) {
                let h = h_of(pairs.get(i, j));
                c[i * (n + 1) + j] = h * h;
            }
        }
    }
    Ok(c)
}

type PairCtor = fn(&Word, &[Word], &Command) -> DResult<Box<dyn PairStyle>>;

/// Every pair style this build implements: `pair_style NAME args...` builds it.
const STYLES: &[(&str, PairCtor)] = &[
    ("lj/cut", |_, args, cmd| Ok(Box::new(lj_cut::LjCut::from_lammps(args, cmd)?))),
    ("soft", |_, args, cmd| Ok(Box::new(soft::Soft::from_lammps(args, cmd)?))),
    ("bpm/spring", |_, args, cmd| Ok(Box::new(bpm_spring::PairBpmSpring::from_lammps(args, cmd)?))),
    ("sph/taitwater", |_, args, cmd| Ok(Box::new(sph_taitwater::SphTaitwater::from_lammps(args, cmd)?))),
    ("sph/taitwater/morris", |_, args, cmd| Ok(Box::new(sph_taitwater_morris::SphTaitwaterMorris::from_lammps(args, cmd)?))),
    ("sph/heatconduction", |_, args, cmd| Ok(Box::new(sph_heatconduction::SphHeatConduction::from_lammps(args, cmd)?))),
    ("sph/idealgas", |_, args, cmd| Ok(Box::new(sph_idealgas::SphIdealGas::from_lammps(args, cmd)?))),
    ("sph/lj", |_, args, cmd| Ok(Box::new(sph_lj::SphLj::from_lammps(args, cmd)?))),
    ("sph/rhosum", |_, args, cmd| Ok(Box::new(sph_rhosum::SphRhoSum::from_lammps(args, cmd)?))),
    ("dmhs/blend", |_, args, cmd| Ok(Box::new(dmhs_blend::DmhsBlend::from_lammps(args, cmd)?))),
    ("dmhs/heatconduction", |_, args, cmd| Ok(Box::new(dmhs_heatconduction::DmhsHeatConduction::from_lammps(args, cmd)?))),
    ("dmhs/sph/delta", |_, args, cmd| Ok(Box::new(dmhs_sph_delta::SphDelta::from_lammps(args, cmd)?))),
    ("dmhs/sph/diffusion", |_, args, cmd| Ok(Box::new(dmhs_sph_diffusion::SphDiffusion::from_lammps(args, cmd)?))),
    ("dmhs/lj/wet", |_, args, cmd| Ok(Box::new(dmhs_lj_wet::LjWet::from_lammps(args, cmd)?))),
    ("gran/hooke", |_, args, cmd| Ok(Box::new(gran_hooke::GranHooke::from_lammps(args, cmd)?))),
    ("gran/hooke/history", |_, args, cmd| Ok(Box::new(gran_hooke_history::GranHookeHistory::from_lammps(args, cmd, false)?))),
    ("gran/hertz/history", |_, args, cmd| Ok(Box::new(gran_hooke_history::GranHookeHistory::from_lammps(args, cmd, true)?))),
    ("granular", |_, args, cmd| Ok(Box::new(granular::Granular::from_lammps(args, cmd)?))),
    ("zero", |_, args, cmd| Ok(Box::new(zero::PairZero::from_lammps(args, cmd)?))),
    ("hybrid", |name, args, cmd| Ok(Box::new(hybrid::Hybrid::from_lammps(name, args, cmd)?))),
    ("hybrid/overlay", |name, args, cmd| Ok(Box::new(hybrid::Hybrid::from_lammps(name, args, cmd)?))),
];

/// Build a pair style from `pair_style NAME args...`.
pub fn new_pair_style(name: &Word, args: &[Word], cmd: &Command) -> DResult<Box<dyn PairStyle>> {
    match STYLES.iter().find(|(n, _)| *n == name.text) {
        Some((_, ctor)) => ctor(name, args, cmd),
        None => Err(crate::models::styles::unsupported_style("pair", name, &name.text, &supported())),
    }
}

/// Names of the pair styles this build implements.
pub fn supported() -> Vec<&'static str> {
    STYLES.iter().map(|(n, _)| *n).collect()
}

/// A kernel for a central pair force between two point particles. Parameters are looked up
/// once per atom i as a row over j's type, then evaluated per pair.
pub trait CentralKernel: Sync {
    type Params: Sync;
    /// Per-atom values the kernel reads of both atoms besides positions and types (`()` for
    /// most styles; dmhs/lj/wet: water concentration and swelling).
    type Site: Copy + Send + Sync;
    /// The sites of all atoms (owned, then ghosts).
    fn sites(&self, input: &PairInput) -> Vec<Self::Site>;
    /// Parameters of type pairs (ti, 0..=ntypes), indexed by j's type.
    fn row(&self, ti: usize) -> &[Self::Params];
    /// Squared cutoff of a pair.
    fn cutsq(p: &Self::Params, si: &Self::Site, sj: &Self::Site) -> f64;
    /// `(fpair, energy)` for `rsq` inside the cutoff, where the force on i is
    /// `fpair * (x_i - x_j)`; `factor` is the special-bond weight. The energy is only used
    /// when `EFLAG`.
    fn eval<const EFLAG: bool>(p: &Self::Params, rsq: f64, factor: f64, si: &Self::Site, sj: &Self::Site) -> (f64, f64);
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
    let list = input.list;
    let sites = kernel.sites(input);
    let bounds = list.bounds();
    let mut parts = vec![Tally::default(); list.chunks.len()];
    for parity in 0..2 {
        slab_phase(&bounds, parity, AtomsMut::new(f), &mut parts, |c, mut f| central_chunk::<K, EFLAG, SPECIAL, FILTER>(kernel, input, &sites, c, &mut f));
    }
    sum_tallies(&parts)
}

/// The pairs of chunk `c` of [`central_loop`], with the forces of its window.
fn central_chunk<K: CentralKernel, const EFLAG: bool, const SPECIAL: bool, const FILTER: bool>(kernel: &K, input: &PairInput, sites: &[K::Site], c: usize, f: &mut AtomsMut<[f64; 3]>) -> Tally {
        let a = input.atoms;
        let nlocal = a.nlocal;
        let stride = input.ntypes + 1;
        let (x, typ) = (&a.x[..], &a.typ[..]);
        let chunk = &input.list.chunks[c];
        let mut t = Tally::default();
        for i in chunk.start..chunk.end {
            let xi = x[i];
            let ti = typ[i];
            let si = &sites[i];
            let row = kernel.row(ti);
            let filter = if FILTER { &input.type_filter.unwrap()[ti * stride..(ti + 1) * stride] } else { &[][..] };
            let mut fi = [0.0f64; 3];
            for &jraw in chunk.neighbors(i) {
                let j = (jraw & NEIGH_MASK) as usize;
                let (xj, tj) = (x[j], typ[j]);
                if FILTER && !filter[tj] {
                    continue;
                }
                let del = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
                let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                let p = &row[tj];
                let sj = &sites[j];
                // branch-free cutoff: about a quarter of the listed pairs (those in the skin)
                // are outside, which a branch predicts badly; their force is masked to +0
                let keep = if rsq < K::cutsq(p, si, sj) { u64::MAX } else { 0 };
                let factor = if SPECIAL { input.special_lj[special_level(jraw)] } else { 1.0 };
                let (fpair, e) = K::eval::<EFLAG>(p, rsq, factor, si, sj);
                let fpair = f64::from_bits(fpair.to_bits() & keep);
                let e = f64::from_bits(e.to_bits() & keep);
                fi[0] += del[0] * fpair;
                fi[1] += del[1] * fpair;
                fi[2] += del[2] * fpair;
                let w = if j < nlocal {
                    let fj = &mut f[j];
                    fj[0] -= del[0] * fpair;
                    fj[1] -= del[1] * fpair;
                    fj[2] -= del[2] * fpair;
                    1.0
                } else {
                    0.5
                };
                if EFLAG {
                    t.central(w, e, del, fpair);
                }
            }
            let fo = &mut f[i];
            fo[0] += fi[0];
            fo[1] += fi[1];
            fo[2] += fi[2];
        }
        t
}

/// A kernel that adds a scalar per pair to both atoms (sph/rhosum's density sum).
pub trait ScalarKernel: Sync {
    /// Squared cutoffs of type pairs (row-major over `0..=ntypes`).
    fn cutsq(&self) -> &[f64];
    /// What atoms i and j receive from a pair at squared distance `rsq` inside the cutoff.
    fn eval(&self, input: &PairInput, ti: usize, tj: usize, rsq: f64) -> (f64, f64);
}

/// Add every listed pair's [`ScalarKernel`] values to `out` of owned atoms (i's value, then
/// j's, pair by pair in list order).
pub fn compute_scalar<K: ScalarKernel>(kernel: &K, input: &PairInput, out: &mut [f64]) {
    let a = input.atoms;
    let (nlocal, stride) = (a.nlocal, input.ntypes + 1);
    let cutsq = kernel.cutsq();
    let list = input.list;
    let bounds = list.bounds();
    let mut parts = vec![(); list.chunks.len()];
    for parity in 0..2 {
        slab_phase(&bounds, parity, AtomsMut::new(&mut *out), &mut parts, |c, mut out| {
            let chunk = &list.chunks[c];
            for i in chunk.start..chunk.end {
                let (ti, xi) = (a.typ[i], a.x[i]);
                for &jraw in chunk.neighbors(i) {
                    let j = (jraw & NEIGH_MASK) as usize;
                    let tj = a.typ[j];
                    if input.type_filter.is_some_and(|fl| !fl[ti * stride + tj]) {
                        continue;
                    }
                    let xj = a.x[j];
                    let (dx, dy, dz) = (xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]);
                    let rsq = dx * dx + dy * dy + dz * dz;
                    if !(rsq < cutsq[ti * stride + tj]) {
                        continue;
                    }
                    let (vi, vj) = kernel.eval(input, ti, tj, rsq);
                    out[i] += vi;
                    if j < nlocal {
                        out[j] += vj;
                    }
                }
            }
        });
    }
}

/// What a [`PairKernel`] gives one pair: the force on i (j gets its negative), torques on i
/// and j, and the rates (drho, desph) of i and j.
#[derive(Clone, Copy, Debug, Default)]
pub struct PairResult {
    pub f: [f64; 3],
    pub ti: [f64; 3],
    pub tj: [f64; 3],
    pub rate_i: [f64; 2],
    pub rate_j: [f64; 2],
    /// The pair's energy (tallied when energies are).
    pub energy: f64,
}

/// A kernel for any pair interaction, one pair at a time.
pub trait PairKernel: Sync {
    /// The pair (i, j) with `del` = x_i - x_j, or None if it does not interact; `factor` is
    /// the pair's special-bond lj weight (1 for a pair that is not special).
    fn pair(&self, input: &PairInput, i: usize, j: usize, del: [f64; 3], rsq: f64, factor: f64) -> Option<PairResult>;
    /// The pair with its contact history (a kernel whose style keeps a
    /// [`ContactHistory`](crate::engine::contact_history::ContactHistory)): `hist` holds the
    /// entry's values; the kernel sets `touch` to whether the pair is in contact now, and the
    /// loop zeroes the values of a pair that is not (a contact that ends forgets its history).
    fn pair_with_history(&self, input: &PairInput, i: usize, j: usize, del: [f64; 3], rsq: f64, factor: f64, _hist: &mut [f64], _touch: &mut bool) -> Option<PairResult> {
        self.pair(input, i, j, del, rsq, factor)
    }
}

/// Every listed pair through a [`PairKernel`], on one thread in list order (the order
/// dmhs/blend's scenes were validated with; its pairs are few): results are added to i and, if
/// owned, to j, pair by pair; the virial as LAMMPS' `ev_tally_xyz`. With `history` (aligned
/// with the list by [`ContactHistory::rebuilt`](crate::engine::contact_history::ContactHistory::rebuilt))
/// each pair is evaluated by [`PairKernel::pair_with_history`] with its entry's values.
pub fn compute_pairs<K: PairKernel>(kernel: &K, input: &PairInput, out: &mut PairOutput, mut history: Option<&mut crate::engine::contact_history::ContactHistory>) -> Tally {
    let a = input.atoms;
    let (nlocal, stride) = (a.nlocal, input.ntypes + 1);
    let has_rates = !out.drho.is_empty();
    let (f, torque, drho, desph) = (&mut *out.f, &mut *out.torque, &mut *out.drho, &mut *out.desph);
    let hsize = history.as_ref().map_or(0, |h| h.size());
    if let Some(h) = &history {
        assert!(h.chunks.len() == input.list.chunks.len(), "contact history not aligned with the neighbour list");
    }
    let mut t = Tally::default();
    for (c, chunk) in input.list.chunks.iter().enumerate() {
        for i in chunk.start..chunk.end {
            let (ti, xi) = (a.typ[i], a.x[i]);
            let k0 = chunk.first_entry(i);
            for (k, &jraw) in chunk.neighbors(i).iter().enumerate() {
                let j = (jraw & NEIGH_MASK) as usize;
                if input.type_filter.is_some_and(|fl| !fl[ti * stride + a.typ[j]]) {
                    continue;
                }
                let xj = a.x[j];
                let del = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
                let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                let factor = if input.list.has_special { input.special_lj[special_level(jraw)] } else { 1.0 };
                let result = match history.as_deref_mut() {
                    None => kernel.pair(input, i, j, del, rsq, factor),
                    Some(h) => {
                        let (e, hc) = (k0 + k, &mut h.chunks[c]);
                        let values = &mut hc.values[e * hsize..(e + 1) * hsize];
                        let mut touch = false;
                        let r = kernel.pair_with_history(input, i, j, del, rsq, factor, values, &mut touch);
                        if !touch {
                            values.iter_mut().for_each(|v| *v = 0.0);
                        }
                        hc.touch[e] = touch as u8;
                        r
                    }
                };
                let Some(r) = result else { continue };
                let owned = j < nlocal;
                if has_rates {
                    drho[i] += r.rate_i[0];
                    desph[i] += r.rate_i[1];
                    if owned {
                        drho[j] += r.rate_j[0];
                        desph[j] += r.rate_j[1];
                    }
                }
                if !torque.is_empty() {
                    for k in 0..3 {
                        torque[i][k] += r.ti[k];
                        if owned {
                            torque[j][k] += r.tj[k];
                        }
                    }
                }
                for k in 0..3 {
                    f[i][k] += r.f[k];
                    if owned {
                        f[j][k] -= r.f[k];
                    }
                }
                if input.eflag {
                    let w = if owned { 1.0 } else { 0.5 };
                    t.evdwl += w * r.energy;
                    t.xyz(w, del, r.f);
                    if let Some(pa) = out.peratom.as_deref_mut() {
                        pa.add_pairs(&[crate::engine::tally::PairShare::xyz(i, j, r.energy, del, r.f)]);
                    }
                }
            }
        }
    }
    t
}

/// A per-type-pair vector of `fill`, row-major over `0..=ntypes`: refused with a message when it
/// would not fit in memory (thousands of types and a large value per pair), where a plain `vec!`
/// would abort the process.
pub fn type_pair_vec<T: Clone>(ntypes: usize, fill: T) -> Result<Vec<T>, String> {
    let len = (ntypes + 1) * (ntypes + 1);
    let bytes = len as f64 * std::mem::size_of::<T>().max(1) as f64;
    if bytes > 1.0e6 {
        let what = format!("{ntypes} atom types: a pair style's table of (N+1)^2 = {len} type pairs x {} bytes", std::mem::size_of::<T>());
        crate::engine::memory::check_fits(bytes, &what)?;
    }
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| format!("{ntypes} atom types: the memory for a pair style's table of {len} type pairs could not be allocated"))?;
    v.resize(len, fill);
    Ok(v)
}

/// Per-type-pair table (row-major over `0..=ntypes`), symmetric by construction.
#[derive(Clone, Debug, Default)]
pub struct TypeTable<T: Clone + Default> {
    pub n: usize,
    pub data: Vec<T>,
}

impl<T: Clone + Default> TypeTable<T> {
    /// The table for `ntypes` types, every pair at its default; an error when it cannot fit.
    pub fn new(ntypes: usize) -> Result<Self, String> {
        Ok(TypeTable { n: ntypes, data: type_pair_vec(ntypes, T::default())? })
    }
    /// No types yet (a style before its first pair_coeff).
    pub fn empty() -> Self {
        TypeTable { n: 0, data: vec![T::default()] }
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
    /// Make room for types 1..=n, keeping the values set so far (a larger table only).
    pub fn grow(&mut self, n: usize) -> Result<(), String> {
        if self.n < n {
            let mut t = TypeTable::new(n)?;
            for i in 1..=self.n {
                for j in 1..=self.n {
                    t.set(i, j, self.get(i, j).clone());
                }
            }
            *self = t;
        }
        Ok(())
    }
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, v: T) {
        let s = self.n + 1;
        self.data[i * s + j] = v.clone();
        self.data[j * s + i] = v;
    }
}

/// The type-pair lines of a style's `describe` (`dmhs check`): the pairs I <= J of `1..=n` that
/// `listed` selects, `line` formatted for the first hundred, then how many more there are.
pub fn pair_lines(n: usize, listed: impl Fn(usize, usize) -> bool, line: impl Fn(usize, usize) -> String) -> String {
    const SHOWN: usize = 100;
    let (mut s, mut count) = (String::new(), 0usize);
    for i in 1..=n {
        for j in i..=n {
            if listed(i, j) {
                if count < SHOWN {
                    s += &format!("\n    {i} {j}: {}", line(i, j));
                }
                count += 1;
            }
        }
    }
    if count > SHOWN {
        s += &format!("\n    ... and {} more type pairs", count - SHOWN);
    }
    s
}

/// A per-type-pair table of a few distinct values, each pair holding an index: for values of
/// hundreds of bytes (a granular model) that thousands of types share from a few pair_coeff
/// commands. Each value counts the cells that hold it, so only values in use are listed.
#[derive(Clone, Debug)]
pub struct SharedTable<T: Clone> {
    pub n: usize,
    index: Vec<u32>,
    vals: Vec<T>,
    refs: Vec<usize>,
}

impl<T: Clone> SharedTable<T> {
    /// `ntypes` types, every pair holding `fill`; an error when the index cannot fit.
    pub fn new(ntypes: usize, fill: T) -> Result<Self, String> {
        let index = type_pair_vec(ntypes, 0u32)?;
        let refs = vec![index.len()];
        Ok(SharedTable { n: ntypes, index, vals: vec![fill], refs })
    }
    /// No types yet (a style before its first pair_coeff).
    pub fn empty(fill: T) -> Self {
        SharedTable { n: 0, index: vec![0], vals: vec![fill], refs: vec![1] }
    }
    #[inline(always)]
    pub fn get(&self, i: usize, j: usize) -> &T {
        &self.vals[self.index[i * (self.n + 1) + j] as usize]
    }
    /// The value of pair (i, j) as an index into the distinct values.
    pub fn index_of(&self, i: usize, j: usize) -> u32 {
        self.index[i * (self.n + 1) + j]
    }
    /// A new distinct value; [`SharedTable::set`] puts it on pairs.
    pub fn push(&mut self, v: T) -> u32 {
        self.vals.push(v);
        self.refs.push(0);
        (self.vals.len() - 1) as u32
    }
    /// Pairs (i, j) and (j, i) hold value `k`.
    pub fn set(&mut self, i: usize, j: usize, k: u32) {
        let s = self.n + 1;
        for c in [i * s + j, j * s + i] {
            self.refs[self.index[c] as usize] -= 1;
            self.index[c] = k;
            self.refs[k as usize] += 1;
        }
    }
    /// The values some pair holds.
    pub fn values(&self) -> impl Iterator<Item = &T> {
        self.vals.iter().zip(&self.refs).filter(|(_, &r)| r > 0).map(|(v, _)| v)
    }
    /// Make room for types 1..=n (new pairs hold the first value, the fill).
    pub fn grow(&mut self, n: usize) -> Result<(), String> {
        if self.n < n {
            let mut t = SharedTable { n, index: type_pair_vec(n, 0u32)?, vals: std::mem::take(&mut self.vals), refs: vec![] };
            t.refs = vec![0; t.vals.len()];
            t.refs[0] = t.index.len();
            for i in 1..=self.n {
                for j in i..=self.n {
                    t.set(i, j, self.index_of(i, j));
                }
            }
            *self = t;
        }
        Ok(())
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
