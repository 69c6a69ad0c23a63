//! Damping sub-models of `pair_style granular` (LAMMPS gran_sub_mod_damping.cpp): the normal
//! damping force F_damp = -eta_n v_n. They take no coefficients of their own: eta_n0 is the
//! normal model's second coefficient. The prefactor eta_n also scales the tangential damping.
//!
//! * `velocity`: eta_n = eta_n0.
//! * `mass_velocity`: eta_n = eta_n0 m_eff.
//! * `viscoelastic` (the default): eta_n = eta_n0 m_eff a, a the contact radius.
//! * `tsuji`: eta_n = alpha sqrt(m_eff F_n/delta), alpha a polynomial of eta_n0 = e (Tsuji 1992).
//! * `coeff_restitution`: as tsuji with alpha from the restitution e = eta_n0:
//!   -2 ln e / sqrt(pi^2 + ln^2 e) for hooke, -sqrt(3/2) 2 sqrt(5/6) ln e / sqrt(pi^2 + ln^2 e)
//!   for every other normal model (Hertzian).
//!
//! * `mdr 1|2`: only with the `mdr` normal model, whose last coefficient is the damping
//!   coefficient: type 1 eta_n = damp sqrt(2 m_eff E_eff a) (the scale the normal model stores
//!   in the history), type 2 eta_n = damp while that scale is not 0.
//!
//! tsuji and coeff_restitution refuse a cohesive normal model (LAMMPS allow_cohesion = 0).

use super::{geometric, Coeff, Flags, Range, Style};
use std::f64::consts::PI;

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Damping {
    #[default]
    None,
    Velocity { damp: f64 },
    MassVelocity { damp: f64 },
    Viscoelastic { damp: f64 },
    /// tsuji and coeff_restitution (they differ in `damp` only)
    Tsuji { damp: f64 },
    /// `damping mdr`: type 1 (`scaled`) or 2
    Mdr { damp: f64, scaled: bool },
}

const NO_COHESION: Flags = Flags { no_cohesion: true, ..Flags::NONE };

/// The damping models dmhs supports; the parser, the error messages and the docs read this table.
pub static STYLES: &[Style<Damping>] = &[
    Style { name: "velocity", coeffs: &[], history: 0, flags: Flags::NONE, build: |_, ctx| Damping::Velocity { damp: ctx.normal_damp }, mix: geometric },
    Style {
        name: "mass_velocity",
        coeffs: &[],
        history: 0,
        flags: Flags::NONE,
        build: |_, ctx| Damping::MassVelocity { damp: ctx.normal_damp },
        mix: geometric,
    },
    Style {
        name: "viscoelastic",
        coeffs: &[],
        history: 0,
        flags: Flags { contact_radius: true, ..Flags::NONE },
        build: |_, ctx| Damping::Viscoelastic { damp: ctx.normal_damp },
        mix: geometric,
    },
    Style { name: "tsuji", coeffs: &[], history: 0, flags: NO_COHESION, build: |_, ctx| Damping::Tsuji { damp: tsuji(ctx.normal_damp) }, mix: geometric },
    Style {
        name: "coeff_restitution",
        coeffs: &[],
        history: 0,
        flags: NO_COHESION,
        build: |_, ctx| Damping::Tsuji { damp: from_restitution(ctx.normal_damp, ctx.normal == "hooke") },
        mix: geometric,
    },
    Style {
        name: "mdr",
        coeffs: &[Coeff { name: "type", about: "1: mdr stiffness, 2: velocity", range: Range::Whole(1, 2) }],
        history: 0,
        flags: Flags::NONE,
        build: |c, ctx| Damping::Mdr { damp: ctx.normal_damp, scaled: c[0] as i64 == 1 },
        mix: geometric,
    },
];

/// The default when `damping` is not given (LAMMPS: viscoelastic).
pub fn default_style() -> &'static Style<Damping> {
    &STYLES[2]
}

/// Tsuji's damping ratio as a polynomial of the restitution coefficient.
fn tsuji(e: f64) -> f64 {
    let mut d = 1.2728 - 4.2783 * e + 11.087 * (e * e);
    d += -22.348 * (e * e * e) + 27.467 * powint(e, 4);
    d += -18.022 * powint(e, 5) + 4.8218 * powint(e, 6);
    d
}

/// The damping ratio that gives restitution `e` for a linear (hooke) or Hertzian spring.
fn from_restitution(e: f64, hooke: bool) -> f64 {
    const ROOTTHREEBYTWO: f64 = 1.224744871391589; // sqrt(3/2), LAMMPS' literal
    const TWOROOTFIVEBYSIX: f64 = 1.8257418583505538; // 2 sqrt(5/6), LAMMPS' literal
    let l = e.ln();
    if hooke {
        -2.0 * l / (PI * PI + l * l).sqrt()
    } else {
        let d = -ROOTTHREEBYTWO * TWOROOTFIVEBYSIX * l;
        d / (PI * PI + l * l).sqrt()
    }
}

/// LAMMPS MathSpecial::powint: binary exponentiation.
fn powint(x: f64, n: i32) -> f64 {
    let mut yy = x;
    let mut ww = 1.0;
    let mut n = n;
    while n != 0 {
        if n & 1 != 0 {
            ww *= yy;
        }
        n >>= 1;
        yy *= yy;
    }
    ww
}

impl Damping {
    /// eta_n (LAMMPS `damp_prefactor`); `a` is the contact radius, `fnormal` the normal force.
    #[inline(always)]
    /// `damp_scale` is the scale the mdr normal model stored (0 for the others).
    pub fn prefactor(&self, meff: f64, a: f64, fnormal: f64, delta: f64, damp_scale: f64) -> f64 {
        match *self {
            Damping::Velocity { damp } => damp,
            Damping::MassVelocity { damp } => damp * meff,
            Damping::Viscoelastic { damp } => damp * meff * a,
            Damping::Tsuji { damp } => damp * (meff * fnormal / delta).sqrt(),
            Damping::Mdr { damp, scaled: true } => damp * damp_scale,
            Damping::Mdr { damp, scaled: false } => {
                if damp_scale == 0.0 { 0.0 } else { damp }
            }
            Damping::None => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn restitution_ratio_matches_the_linear_spring_dashpot() {
        // a linear spring-dashpot with ratio zeta = d/2 ... restitution exp(-pi zeta/sqrt(1-zeta^2))
        let e: f64 = 0.5;
        let d = from_restitution(e, true);
        let zeta = 0.5 * d;
        let back = (-PI * zeta / (1.0 - zeta * zeta).sqrt()).exp();
        assert!((back - e).abs() < 1e-14, "{back}");
    }
}
