//! Tangential sub-models of `pair_style granular` (LAMMPS gran_sub_mod_tangential.cpp): the
//! friction force F_t from the relative tangential velocity v_tr at the contact point, limited
//! to mu F_n,crit. The tangential damping is x_gt eta_n (eta_n: the damping model's prefactor).
//!
//! * `linear_nohistory x_gt mu`: F_t = -min(mu F_n,crit, x_gt eta_n |v_tr|) v_tr/|v_tr|.
//! * `linear_history Kt x_gt mu`: a spring s (3 history values). Before the update s is rotated
//!   into the tangent plane AND rescaled to its old length (only when its normal part matters:
//!   |s.n| Kt > 1e-10 mu F_n,crit); s += v_tr dt; F_t = -Kt s - x_gt eta_n v_tr, limited to
//!   mu F_n,crit with s set back to match.
//! * `linear_history_classic Kt x_gt mu`: the spring of pair gran/hooke/history: s += v_tr dt
//!   first, |s| taken, then s projected onto the tangent plane without rescaling. LAMMPS 2025
//!   scales its stiffness by the contact radius (F_t = -Kt a s - x_gt eta_n v_tr) but sets s
//!   back at the Coulomb limit as if it did not (s = -(F_t + x_gt eta_n v_tr)/Kt): reproduced,
//!   measured against LAMMPS 2025.7.
//!
//! The spring is advanced only when `update` (not during run setup, LAMMPS' history_update).

use super::{geometric, nn, Coeff, Flags, Style};

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Tangential {
    #[default]
    None,
    LinearNoHistory { xt: f64, mu: f64 },
    LinearHistory { k: f64, xt: f64, mu: f64 },
    LinearHistoryClassic { k: f64, xt: f64, mu: f64 },
}

const NOHISTORY: &[Coeff] = &[nn("x_gt", "tangential damping ratio"), nn("mu", "friction coefficient")];
const HISTORY: &[Coeff] = &[nn("Kt", ""), nn("x_gt", "tangential damping ratio"), nn("mu", "friction coefficient")];

/// The tangential models dmhs supports; the parser, the error messages and the docs read this
/// table.
pub static STYLES: &[Style<Tangential>] = &[
    Style {
        name: "linear_nohistory",
        coeffs: NOHISTORY,
        history: 0,
        flags: Flags::NONE,
        build: |c, _| Tangential::LinearNoHistory { xt: c[0], mu: c[1] },
        mix: geometric,
    },
    Style {
        name: "linear_history",
        coeffs: HISTORY,
        history: 3,
        flags: Flags::NONE,
        build: |c, _| Tangential::LinearHistory { k: c[0], xt: c[1], mu: c[2] },
        mix: geometric,
    },
    Style {
        name: "linear_history_classic",
        coeffs: HISTORY,
        history: 3,
        flags: Flags { contact_radius: true, ..Flags::NONE },
        build: |c, _| Tangential::LinearHistoryClassic { k: c[0], xt: c[1], mu: c[2] },
        mix: geometric,
    },
];

/// What a tangential model reads of the contact.
pub struct TangentialIn<'a> {
    pub nx: &'a [f64; 3],
    pub vtr: &'a [f64; 3],
    pub fncrit: f64,
    /// eta_n, the normal damping prefactor
    pub damp_prefactor: f64,
    /// contact radius (0 unless a sub-model asked for it)
    pub a: f64,
    pub update: bool,
    pub dt: f64,
}

impl Tangential {
    /// F_t; `h` is this model's history (its `history` values).
    #[inline(always)]
    pub fn force(&self, t: &TangentialIn, h: &mut [f64]) -> [f64; 3] {
        let (nx, vtr) = (t.nx, t.vtr);
        match *self {
            Tangential::LinearHistory { k, xt, mu } => {
                let damp = xt * t.damp_prefactor;
                let fscrit = t.fncrit * mu;
                if t.update {
                    // rotate into the tangent plane, keeping the length, when the normal part matters
                    let rsht = h[0] * nx[0] + h[1] * nx[1] + h[2] * nx[2];
                    if rsht.abs() * k > 1e-10 * fscrit {
                        let shrmag = len3(h[0], h[1], h[2]);
                        h[0] -= rsht * nx[0];
                        h[1] -= rsht * nx[1];
                        h[2] -= rsht * nx[2];
                        let prjmag = len3(h[0], h[1], h[2]);
                        let scale = if prjmag > 0.0 { shrmag / prjmag } else { 0.0 };
                        h[0] *= scale;
                        h[1] *= scale;
                        h[2] *= scale;
                    }
                    h[0] += t.dt * vtr[0];
                    h[1] += t.dt * vtr[1];
                    h[2] += t.dt * vtr[2];
                }
                let fs = [-k * h[0] - damp * vtr[0], -k * h[1] - damp * vtr[1], -k * h[2] - damp * vtr[2]];
                coulomb(fs, None, fscrit, k, damp, vtr, h)
            }
            Tangential::LinearHistoryClassic { k, xt, mu } => {
                let damp = xt * t.damp_prefactor;
                let fscrit = t.fncrit * mu;
                if t.update {
                    h[0] += t.dt * vtr[0];
                    h[1] += t.dt * vtr[1];
                    h[2] += t.dt * vtr[2];
                }
                // the length before the projection decides the Coulomb branch below
                let shrmag = len3(h[0], h[1], h[2]);
                if t.update {
                    let rsht = h[0] * nx[0] + h[1] * nx[1] + h[2] * nx[2];
                    h[0] -= rsht * nx[0];
                    h[1] -= rsht * nx[1];
                    h[2] -= rsht * nx[2];
                }
                let ka = -k * t.a;
                let fs = [ka * h[0] - damp * vtr[0], ka * h[1] - damp * vtr[1], ka * h[2] - damp * vtr[2]];
                coulomb(fs, Some(shrmag), fscrit, k, damp, vtr, h)
            }
            Tangential::LinearNoHistory { xt, mu } => {
                let damp = xt * t.damp_prefactor;
                let vrel = len3(vtr[0], vtr[1], vtr[2]);
                let fscrit = mu * t.fncrit;
                let fsmag = damp * vrel;
                let ft = if vrel != 0.0 { (if fscrit < fsmag { fscrit } else { fsmag }) / vrel } else { 0.0 };
                [-ft * vtr[0], -ft * vtr[1], -ft * vtr[2]]
            }
            Tangential::None => [0.0; 3],
        }
    }
}

/// Coulomb's limit on a spring-dashpot force: above mu F_n,crit the force is scaled down and
/// the spring set back to match; a spring of zero length gives no force at all (LAMMPS).
/// `shrmag`: the spring length that decides this (None: its length now, taken only if needed).
#[inline(always)]
fn coulomb(mut fs: [f64; 3], shrmag: Option<f64>, fscrit: f64, k: f64, damp: f64, vtr: &[f64; 3], h: &mut [f64]) -> [f64; 3] {
    let magfs = len3(fs[0], fs[1], fs[2]);
    if magfs > fscrit {
        if shrmag.unwrap_or_else(|| len3(h[0], h[1], h[2])) != 0.0 {
            let s = fscrit * (1.0 / magfs);
            let kinv = -1.0 / k;
            for d in 0..3 {
                h[d] = s * fs[d];
                h[d] += damp * vtr[d];
                h[d] *= kinv;
                fs[d] *= s;
            }
        } else {
            fs = [0.0; 3];
        }
    }
    fs
}

#[inline(always)]
pub fn len3(a: f64, b: f64, c: f64) -> f64 {
    (a * a + b * b + c * c).sqrt()
}
