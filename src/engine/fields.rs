//! Named per-particle fields of the DMHS models, as typed handles: the model that publishes a
//! field and the models that read it name the same constant here, not a string of their own.
//! The values live in the atoms' extra arrays ([`crate::engine::atoms::ExtraArray`]), so sorting,
//! deleting, restarting and ghost exchange carry them with everything else.

use crate::engine::atoms::Atoms;

/// One scalar per particle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// The extra array's name (also its name in restart files).
    pub name: &'static str,
    /// Ghost images carry it (pair styles read it on neighbours).
    pub ghosts: bool,
}

/// Water mass w_i of the cleaning model (Eqs 26-27); `fix dmhs/diffusion` integrates it.
pub const WATER: Field = Field { name: "dmhs/water", ghosts: true };
/// dw_i/dt, written by `pair_style dmhs/sph/diffusion` (a rate: see [`RATES`]).
pub const WATER_RATE: Field = Field { name: "dmhs/dwater", ghosts: false };
/// Swelling growth of the radius r_i - r0_i (`fix dmhs/swell`), read by `dmhs/lj/wet`.
pub const GROWTH: Field = Field { name: "dmhs/growth", ghosts: true };
/// Temperature published by `fix dmhs/phase`, read by `dmhs/heatconduction` and `fix dmhs/cooling`;
/// also LAMMPS' per-atom `temperature` (`fix property/atom temperature`), read by the heat models
/// of pair granular and integrated by `fix heat/flow`.
pub const TEMPERATURE: Field = Field { name: "dmhs/T", ghosts: true };
/// LAMMPS' per-atom `heatflow` (`fix property/atom heatflow`): the heat flowing into the particle,
/// written by the heat models of pair granular (a rate: see [`RATES`]; LAMMPS' fix heat/flow
/// zeroes it before each force computation, as the force stage zeroes every rate here).
pub const HEATFLOW: Field = Field { name: "heatflow", ghosts: false };
/// Phase label of `fix dmhs/phase` (solid or liquid).
pub const PHASE: Field = Field { name: "dmhs/phase", ghosts: false };
/// Heat capacity m c of the particle's current phase (`fix dmhs/phase`).
pub const HEAT_CAPACITY: Field = Field { name: "dmhs/c", ghosts: false };
/// Liquid weight phi(T) of `fix dmhs/phase ... mix`, read by `pair_style dmhs/blend`.
pub const LIQUID_WEIGHT: Field = Field { name: "dmhs/phi", ghosts: true };

/// Per-particle state of pair granular's `mdr` normal model (LAMMPS' fix GRANULAR/MDR keeps
/// them as `fix property/atom d_NAME ... ghost yes`, so `compute property/atom d_psi` reads
/// them here too). The model reads these on neighbours: initial radius, geometric and
/// elastic volumes, contact area of the last step, total area, free-area ratio, mean surface
/// displacement increment, the averaged radius increment and the flag of initialised atoms.
pub const MDR_RO: Field = Field { name: "d_Ro", ghosts: true };
pub const MDR_VGEO: Field = Field { name: "d_Vgeo", ghosts: true };
pub const MDR_VELAS: Field = Field { name: "d_Velas", ghosts: true };
pub const MDR_ACON0: Field = Field { name: "d_Acon0", ghosts: true };
pub const MDR_ATOT: Field = Field { name: "d_Atot", ghosts: true };
pub const MDR_PSI: Field = Field { name: "d_psi", ghosts: true };
pub const MDR_DDELTA_BAR: Field = Field { name: "d_ddelta_bar", ghosts: true };
pub const MDR_DRAVG: Field = Field { name: "d_dRavg", ghosts: true };
pub const MDR_SETUP: Field = Field { name: "d_history_setup_flag", ghosts: true };
/// The sums the `mdr` contacts add to during the pair pass (owned atoms; zeroed by the model
/// before each pass but the run's first, as LAMMPS' fix GRANULAR/MDR zeroes them in pre_force
/// outside setup): cap volumes, volume-averaged strain, the two sums of the radius update,
/// contact area, area balance, and the diagonal of the particle stress.
pub const MDR_VCAPS: Field = Field { name: "d_Vcaps", ghosts: false };
pub const MDR_EPS_BAR: Field = Field { name: "d_eps_bar", ghosts: false };
pub const MDR_DRNUM: Field = Field { name: "d_dRnumerator", ghosts: false };
pub const MDR_DRDEN: Field = Field { name: "d_dRdenominator", ghosts: false };
pub const MDR_ACON1: Field = Field { name: "d_Acon1", ghosts: false };
pub const MDR_ATOT_SUM: Field = Field { name: "d_Atot_sum", ghosts: false };
pub const MDR_SIGMAXX: Field = Field { name: "d_sigmaxx", ghosts: false };
pub const MDR_SIGMAYY: Field = Field { name: "d_sigmayy", ghosts: false };
pub const MDR_SIGMAZZ: Field = Field { name: "d_sigmazz", ghosts: false };
/// The pair pass's sums, in the order the mdr model's pair pass adds them.
pub const MDR_SUMS: [Field; 9] = [MDR_VCAPS, MDR_EPS_BAR, MDR_DRNUM, MDR_DRDEN, MDR_ACON1, MDR_ATOT_SUM, MDR_SIGMAXX, MDR_SIGMAYY, MDR_SIGMAZZ];
/// Every field of the `mdr` model.
pub const MDR_FIELDS: [Field; 18] = [
    MDR_RO, MDR_VGEO, MDR_VELAS, MDR_ACON0, MDR_ATOT, MDR_PSI, MDR_DDELTA_BAR, MDR_DRAVG, MDR_SETUP, MDR_VCAPS, MDR_EPS_BAR, MDR_DRNUM, MDR_DRDEN,
    MDR_ACON1, MDR_ATOT_SUM, MDR_SIGMAXX, MDR_SIGMAYY, MDR_SIGMAZZ,
];

/// The fields that are rates of the pair pass: zeroed before it, written by it (taken out of the
/// atoms for the pass, like the forces).
pub const RATES: &[Field] = &[WATER_RATE, HEATFLOW];

/// Fields the pair pass adds to without the force stage zeroing them (taken out of the atoms
/// for the pass like the rates): the `mdr` model's sums.
pub const PAIR_SUMS: &[Field] = &MDR_SUMS;

impl Atoms {
    /// Index of the field's array, if some model registered it.
    pub fn field(&self, f: Field) -> Option<usize> {
        self.find_extra(f.name)
    }
    /// The field's values (owned atoms, then ghosts if it has them).
    pub fn field_values(&self, f: Field) -> Option<&[f64]> {
        self.field(f).map(|k| &self.extra[k].data[..])
    }
    /// Register (or find) the field; returns its index. Call with no ghosts present.
    pub fn add_field(&mut self, f: Field) -> usize {
        self.extra_field(f.name, 1, f.ghosts)
    }
}
