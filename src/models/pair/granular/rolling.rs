//! Rolling sub-models of `pair_style granular` (LAMMPS gran_sub_mod_rolling.cpp): a resistance
//! to the rolling velocity v_rl = R_eff (omega_i - omega_j) x n, giving a torque R_eff n x F_r
//! on i and its opposite on j.
//!
//! * `sds k_roll gamma_roll mu_roll`: a spring-dashpot-slider. Its spring s (3 history values)
//!   is turned into the tangent plane and rescaled to its old length when its normal part
//!   matters (|s.n| k_roll > 1e-10 mu_roll F_n,crit), then s += v_rl dt;
//!   F_r = -k_roll s - gamma_roll v_rl, limited to mu_roll F_n,crit with s set back to match.
//!   The spring is stored only when it is advanced (not during run setup). v_rl does not change
//!   when i and j swap, so neither does s; but LAMMPS 22 Jul 2025 negates s when its list moves
//!   the contact to the other atom (transfer factor -1), and so does dmhs (`flip`,
//!   engine/contact_history.rs).

use super::tangential::{len3, rotate_rescale, FRAME_EPS};
use super::{geometric, nn, Coeff, Flags, Style};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rolling {
    Sds { k: f64, gamma: f64, mu: f64 },
}

const SDS: &[Coeff] = &[nn("k_roll", "rolling stiffness"), nn("gamma_roll", "rolling damping"), nn("mu_roll", "rolling friction coefficient")];

/// The rolling models dmhs supports; the parser, the error messages and the docs read this table.
pub static STYLES: &[Style<Rolling>] = &[Style {
    name: "sds",
    coeffs: SDS,
    history: 3,
    flags: Flags { keep: 0b111, flip: 0b111, ..Flags::NONE },
    build: |c, _| Rolling::Sds { k: c[0], gamma: c[1], mu: c[2] },
    mix: geometric,
}];

/// What a rolling model reads of the contact.
pub struct RollingIn<'a> {
    /// rolling velocity R_eff (omega_i - omega_j) x n
    pub vrl: &'a [f64; 3],
    pub nx: &'a [f64; 3],
    /// `synchronized_verlet`: the full-step normal (`nx` is then the half-step one)
    pub full: Option<&'a [f64; 3]>,
    pub fncrit: f64,
    pub update: bool,
    pub dt: f64,
}

impl Rolling {
    /// F_r (the torque on i is R_eff n x F_r); `h` is this model's history.
    #[inline(always)]
    pub fn force(&self, r: &RollingIn, h: &mut [f64]) -> [f64; 3] {
        let Rolling::Sds { k, gamma, mu } = *self;
        let (nx, vrl) = (r.nx, r.vrl);
        let frcrit = mu * r.fncrit;
        // a copy, stored back only when advanced
        let mut s = [h[0], h[1], h[2]];
        if r.update {
            let rolldotn = s[0] * nx[0] + s[1] * nx[1] + s[2] * nx[2];
            if rolldotn.abs() * k > FRAME_EPS * frcrit {
                rotate_rescale(&mut s, nx, rolldotn);
            }
            s[0] += r.dt * vrl[0];
            s[1] += r.dt * vrl[1];
            s[2] += r.dt * vrl[2];
            // synchronized_verlet: turned into the full-step tangent plane
            if let Some(n) = r.full {
                let rolldotn = s[0] * n[0] + s[1] * n[1] + s[2] * n[2];
                if rolldotn.abs() * k > FRAME_EPS * frcrit {
                    rotate_rescale(&mut s, n, rolldotn);
                }
            }
        }
        let mut fr = [-k * s[0] - gamma * vrl[0], -k * s[1] - gamma * vrl[1], -k * s[2] - gamma * vrl[2]];
        let magfr = len3(fr[0], fr[1], fr[2]);
        if magfr > frcrit {
            if len3(s[0], s[1], s[2]) != 0.0 {
                let k_inv = 1.0 / k;
                let magfr_inv = 1.0 / magfr;
                let (a, b) = (-frcrit * k_inv * magfr_inv, -gamma * k_inv);
                let scale = frcrit * magfr_inv;
                for d in 0..3 {
                    s[d] = a * fr[d] + b * vrl[d];
                    fr[d] *= scale;
                }
            } else {
                fr = [0.0; 3];
            }
        }
        if r.update {
            h[..3].copy_from_slice(&s);
        }
        fr
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rolling_resistance_is_limited_by_friction() {
        let m = Rolling::Sds { k: 100.0, gamma: 0.0, mu: 0.1 };
        let nx = [0.0, 0.0, 1.0];
        let mut h = [0.0; 3];
        // sticking: F_r = -k v_rl dt; not stored without update
        let r = RollingIn { vrl: &[1.0, 0.0, 0.0], nx: &nx, full: None, fncrit: 100.0, update: false, dt: 0.01 };
        assert_eq!(m.force(&r, &mut h), [-0.0, -0.0, -0.0]);
        let r = RollingIn { update: true, ..r };
        assert_eq!(m.force(&r, &mut h), [-1.0, -0.0, -0.0]);
        assert_eq!(h, [0.01, 0.0, 0.0]);
        // sliding: |F_r| = mu F_n,crit, the spring set back to -F_r/k
        let r = RollingIn { vrl: &[0.0, 100.0, 0.0], fncrit: 10.0, ..r };
        let f = m.force(&r, &mut h);
        assert!((len3(f[0], f[1], f[2]) - 1.0).abs() < 1e-15 && f[1] < 0.0);
        assert!((h[1] + f[1] / 100.0).abs() < 1e-15);
    }
}
