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

/// The fields that are rates of the pair pass: zeroed before it, written by it (taken out of the
/// atoms for the pass, like the forces).
pub const RATES: &[Field] = &[WATER_RATE, HEATFLOW];

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
