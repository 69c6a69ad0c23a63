//! Twisting sub-models of `pair_style granular` (LAMMPS gran_sub_mod_twisting.cpp): a torque
//! M_t n on i (and -M_t n on j) from the relative spin about the normal,
//! omega_t = (omega_i - omega_j).n.
//!
//! Both keep a twist angle phi (LAMMPS reserves 3 history values and uses the first):
//! phi += omega_t dt (when advanced), M_t = -k_t phi - gamma_t omega_t, limited to
//! mu_t F_n,crit with phi set back to (mu_t F_n,crit sign(omega_t) - gamma_t omega_t)/k_t.
//!
//! * `sds k_twist gamma_twist mu_twist`: the coefficients as given.
//! * `marshall` (no coefficients): from the tangential model and the contact radius a
//!   (Marshall 2009): k_t = Kt a^2/2, gamma_t = eta_t a^2/2 (eta_t the tangential damping
//!   x_gt eta_n), mu_t = 2/3 mu a.
//!
//! omega_t does not change when i and j swap, so neither does phi; but LAMMPS 22 Jul 2025 negates
//! phi when its list moves the contact to the other atom (transfer factor -1), and so does dmhs
//! (`flip`, engine/contact_history.rs).

use super::{geometric, nn, Coeff, Flags, Style};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Twisting {
    Sds { k: f64, damp: f64, mu: f64 },
    /// the tangential model's stiffness and friction coefficient
    Marshall { k_tang: f64, mu_tang: f64 },
}

const SDS: &[Coeff] = &[nn("k_twist", "twisting stiffness"), nn("gamma_twist", "twisting damping"), nn("mu_twist", "twisting friction coefficient")];

const TWOTHIRDS: f64 = 2.0 / 3.0;

/// The twisting models dmhs supports; the parser, the error messages and the docs read this table.
pub static STYLES: &[Style<Twisting>] = &[
    Style {
        name: "marshall",
        coeffs: &[],
        history: 3,
        flags: Flags { contact_radius: true, keep: 0b111, flip: 0b111, ..Flags::NONE },
        build: |_, ctx| Twisting::Marshall { k_tang: ctx.tangential_k_mu.0, mu_tang: ctx.tangential_k_mu.1 },
        mix: geometric,
    },
    Style {
        name: "sds",
        coeffs: SDS,
        history: 3,
        flags: Flags { keep: 0b111, flip: 0b111, ..Flags::NONE },
        build: |c, _| Twisting::Sds { k: c[0], damp: c[1], mu: c[2] },
        mix: geometric,
    },
];

/// What a twisting model reads of the contact.
pub struct TwistingIn {
    /// relative spin about the normal, (omega_i - omega_j).n
    pub magtwist: f64,
    pub fncrit: f64,
    /// contact radius
    pub a: f64,
    /// the tangential damping x_gt eta_n
    pub tangential_damp: f64,
    pub update: bool,
    pub dt: f64,
}

impl Twisting {
    /// The twisting torque about n on i; `h` is this model's history.
    #[inline(always)]
    pub fn torque(&self, t: &TwistingIn, h: &mut [f64]) -> f64 {
        let (k, damp, mu) = match *self {
            Twisting::Sds { k, damp, mu } => (k, damp, mu),
            Twisting::Marshall { k_tang, mu_tang } => {
                (0.5 * k_tang * t.a * t.a, 0.5 * t.tangential_damp * t.a * t.a, TWOTHIRDS * mu_tang * t.a)
            }
        };
        if t.update {
            h[0] += t.magtwist * t.dt;
        }
        let mut magtortwist = -k * h[0] - damp * t.magtwist;
        let signtwist = ((t.magtwist > 0.0) as i32 - (t.magtwist < 0.0) as i32) as f64;
        let mtcrit = mu * t.fncrit;
        if magtortwist.abs() > mtcrit {
            h[0] = (mtcrit * signtwist - damp * t.magtwist) / k;
            magtortwist = -mtcrit * signtwist;
        }
        magtortwist
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twisting_torque_is_limited_by_friction() {
        let m = Twisting::Sds { k: 100.0, damp: 1.0, mu: 0.5 };
        let mut h = [0.0; 3];
        // sticking: M_t = -k phi - gamma omega_t with phi = omega_t dt
        let t = TwistingIn { magtwist: 2.0, fncrit: 10.0, a: 0.0, tangential_damp: 0.0, update: true, dt: 0.01 };
        assert_eq!(m.torque(&t, &mut h), -100.0 * 0.02 - 2.0);
        // sliding: |M_t| = mu F_n,crit against the spin, phi set back to match
        let t = TwistingIn { magtwist: -20.0, fncrit: 2.0, ..t };
        assert_eq!(m.torque(&t, &mut h), 1.0);
        assert_eq!(-100.0 * h[0] - 1.0 * -20.0, 1.0);
    }
}
