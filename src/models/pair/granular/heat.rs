//! Heat sub-models of `pair_style granular` (LAMMPS gran_sub_mod_heat.cpp): conduction through
//! the contact, a heat flow Q into i (and -Q into j) from the temperature difference, with the
//! contact radius a = sqrt(delta R_eff) of the normal model:
//!
//! * `radius k`: Q = 2 k a (T_j - T_i) (k the conductivity);
//! * `area h`: Q = h pi a^2 (T_j - T_i) (h the heat transfer coefficient).
//!
//! The flow adds to the per-atom `heatflow` (`fix property/atom temperature heatflow`), which
//! `fix heat/flow` integrates into the temperature. The forces do not depend on it, so the pair
//! style sums it in its own pass over the contacts (`Granular::heat_pass`).

use super::{geometric, nn, Coeff, Flags, Style};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Heat {
    Radius { conductivity: f64 },
    Area { h: f64 },
}

impl Heat {
    /// The heat flow into i, in LAMMPS' order of operations (gran_heat_radius, gran_heat_area).
    #[inline(always)]
    pub fn flow(&self, a: f64, ti: f64, tj: f64) -> f64 {
        match *self {
            Heat::Radius { conductivity } => 2.0 * conductivity * a * (tj - ti),
            Heat::Area { h } => h * std::f64::consts::PI * a * a * (tj - ti),
        }
    }
}

/// The heat models dmhs supports; the parser, the error messages and the docs read this table.
pub static STYLES: &[Style<Heat>] = &[
    Style {
        name: "radius",
        coeffs: &[nn("k", "conductivity")] as &[Coeff],
        history: 0,
        flags: Flags { contact_radius: true, ..Flags::NONE },
        build: |c, _| Heat::Radius { conductivity: c[0] },
        mix: geometric,
    },
    Style {
        name: "area",
        coeffs: &[nn("h", "heat transfer coefficient")],
        history: 0,
        flags: Flags { contact_radius: true, ..Flags::NONE },
        build: |c, _| Heat::Area { h: c[0] },
        mix: geometric,
    },
];
