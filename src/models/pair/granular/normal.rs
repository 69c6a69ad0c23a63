//! Normal sub-models of `pair_style granular` (LAMMPS gran_sub_mod_normal.cpp): the elastic
//! (and cohesive) normal force F_n(delta) and the F_n,crit that limits friction.
//!
//! * `hooke Kn eta_n0`: F_n = Kn delta.
//! * `hertz Kn eta_n0`: F_n = Kn a delta, a = sqrt(delta R_eff) the contact radius.
//! * `hertz/material E eta_n0 nu`: Hertz with Kn = 4/3 E_eff, E_eff = 1/(2 (1-nu^2)/E) between
//!   two spheres of the type pair, E/(2 (1-nu^2)) against a wall (a rigid plane).
//! * `dmt E eta_n0 nu gamma`: hertz/material minus the pull-off 4 pi gamma R_eff;
//!   F_n,crit = |F_n + 2 F_pulloff|. Cohesive: no `limit_damping`, no tsuji/coeff_restitution.
//!
//! eta_n0 is the damping model's coefficient (a restitution coefficient for coeff_restitution).
//! Mixing (unset I,J pairs): geometric means, except E: Kn = 4/3 E_eff(E_i, nu_i, E_j, nu_j)
//! (measured in LAMMPS 2025).

use super::{geometric, nn, poisson, Coeff, Coeffs, Ctx, Flags, Style};
use std::f64::consts::PI;

/// The normal force law of one type pair (coefficients as the contact uses them).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Normal {
    #[default]
    None,
    Hooke { k: f64 },
    /// hertz and hertz/material (k from E and nu)
    Hertz { k: f64 },
    Dmt { k: f64, cohesion: f64 },
}

/// Every normal model's second coefficient is eta_n0, the damping model's (LAMMPS `damp`).
pub const DAMP_COEFF: usize = 1;

const FOURTHIRDS: f64 = 4.0 / 3.0;

const HOOKE: &[Coeff] = &[nn("Kn", ""), nn("eta_n0", "normal damping")];
const MATERIAL: &[Coeff] = &[nn("E", "Young's modulus"), nn("eta_n0", "normal damping"), poisson()];
const DMT: &[Coeff] = &[
    nn("E", "Young's modulus"),
    nn("eta_n0", "normal damping"),
    poisson(),
    Coeff::any("gamma", "surface energy"),
];

/// The normal models dmhs supports; the parser, the error messages and the docs read this table.
pub static STYLES: &[Style<Normal>] = &[
    Style { name: "hooke", coeffs: HOOKE, history: 0, flags: Flags::NONE, build: |c, _| Normal::Hooke { k: c[0] }, mix: geometric },
    Style {
        name: "hertz",
        coeffs: HOOKE,
        history: 0,
        flags: Flags { contact_radius: true, ..Flags::NONE },
        build: |c, _| Normal::Hertz { k: c[0] },
        mix: geometric,
    },
    Style {
        name: "hertz/material",
        coeffs: MATERIAL,
        history: 0,
        flags: Flags { contact_radius: true, material: true, ..Flags::NONE },
        build: |c, ctx| Normal::Hertz { k: material_k(c, ctx) },
        mix: mix_material,
    },
    Style {
        name: "dmt",
        coeffs: DMT,
        history: 0,
        flags: Flags { contact_radius: true, cohesive: true, material: true, ..Flags::NONE },
        build: |c, ctx| Normal::Dmt { k: material_k(c, ctx), cohesion: c[3] },
        mix: mix_material,
    },
];

/// LAMMPS mix_stiffnessE: the effective modulus of two materials.
pub fn mix_stiffness_e(e1: f64, e2: f64, nu1: f64, nu2: f64) -> f64 {
    let f1 = (1.0 - nu1 * nu1) / e1;
    let f2 = (1.0 - nu2 * nu2) / e2;
    1.0 / (f1 + f2)
}

/// LAMMPS mix_stiffnessE_wall: a material against a rigid wall.
pub fn mix_stiffness_e_wall(e: f64, nu: f64) -> f64 {
    let factor = 2.0 * (1.0 - nu * nu);
    e / factor
}

/// Kn = 4/3 E_eff of `E eta nu ...` (a wall uses its own rule, as LAMMPS' contact_type WALL);
/// mixed coefficients already hold E_eff.
fn material_k(c: &[f64], ctx: &Ctx) -> f64 {
    let (e, nu) = (c[0], c[2]);
    if ctx.mixed {
        FOURTHIRDS * e
    } else {
        FOURTHIRDS * if ctx.wall { mix_stiffness_e_wall(e, nu) } else { mix_stiffness_e(e, e, nu, nu) }
    }
}

/// E becomes E_eff of the two materials (LAMMPS keeps it in the first coefficient).
fn mix_material(a: &[f64], b: &[f64]) -> Coeffs {
    let mut m = geometric(a, b);
    m[0] = mix_stiffness_e(a[0], b[0], a[2], b[2]);
    m
}

impl Normal {
    /// F_n (LAMMPS `Fnormal`); `a` is the contact radius (0 when no sub-model asked for it).
    #[inline(always)]
    pub fn force(&self, delta: f64, reff: f64, a: f64) -> f64 {
        match *self {
            Normal::Hooke { k } => k * delta,
            Normal::Hertz { k } => k * a * delta,
            Normal::Dmt { k, cohesion } => {
                let fne = k * a * delta;
                fne - pulloff(cohesion, reff)
            }
            Normal::None => 0.0,
        }
    }

    /// F_n,crit, the normal force that limits the friction (LAMMPS `set_fncrit`).
    #[inline(always)]
    pub fn fncrit(&self, fntot: f64, fnormal: f64, reff: f64) -> f64 {
        match *self {
            Normal::Dmt { cohesion, .. } => (fnormal + 2.0 * pulloff(cohesion, reff)).abs(),
            _ => fntot.abs(),
        }
    }

    /// The stiffness of a linear law (for the time-step estimate); None when it grows with
    /// the overlap.
    pub fn linear_stiffness(&self) -> Option<f64> {
        match *self {
            Normal::Hooke { k } => Some(k),
            _ => None,
        }
    }
}

/// DMT pull-off force 4 pi gamma R_eff.
#[inline(always)]
fn pulloff(cohesion: f64, reff: f64) -> f64 {
    4.0 * PI * cohesion * reff
}
