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
//! * `mindlin_classic Kt x_gt mu`: the tangential model of pair gran/hertz/history; in LAMMPS
//!   2025 the same arithmetic as linear_history_classic (both scale Kt by a).
//! * `mindlin Kt x_gt mu`: linear_history with the stiffness Kt a (a the contact radius). Kt
//!   NULL: 8 G_eff from the normal model's E and nu (G_eff = 1/(2 (2-nu)(1+nu)/E) per sphere;
//!   a wall: E/(4 (2-nu)(1+nu))).
//! * `mindlin/force Kt x_gt mu`: the history holds the elastic force itself, advanced by
//!   -Kt a v_tr dt (so a changing a does not rescale what is stored).
//! * `mindlin_rescale`, `mindlin_rescale/force`: as mindlin, mindlin/force, and a 4th value keeps
//!   the contact radius of the last update: when a has shrunk since (unloading) the spring is
//!   scaled by a/a_old first. The 4th value keeps its sign from the other side of the pair.
//!
//! The spring is advanced only when `update` (not during run setup, LAMMPS' history_update).
//! With `synchronized_verlet` (`full`: the full-step normal, `nx` the half-step one) the
//! linear_history and mindlin springs are turned once more, into the full-step tangent plane,
//! after their update, and the dashpot then acts on v_tr turned the same way.

use super::{geometric, nn, Coeff, Coeffs, Ctx, Flags, Range, Style, NULL};

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Tangential {
    #[default]
    None,
    LinearNoHistory { xt: f64, mu: f64 },
    LinearHistory { k: f64, xt: f64, mu: f64 },
    LinearHistoryClassic { k: f64, xt: f64, mu: f64 },
    /// the mindlin family: `force`: the history is the force; `rescale`: a 4th value holds a
    Mindlin { k: f64, xt: f64, mu: f64, force: bool, rescale: bool },
}

const NOHISTORY: &[Coeff] = &[nn("x_gt", "tangential damping ratio"), nn("mu", "friction coefficient")];
const HISTORY: &[Coeff] = &[nn("Kt", ""), nn("x_gt", "tangential damping ratio"), nn("mu", "friction coefficient")];
const MINDLIN: &[Coeff] = &[
    Coeff { name: "Kt", about: "NULL: from E and nu", range: Range::NonNegativeOrNull },
    nn("x_gt", "tangential damping ratio"),
    nn("mu", "friction coefficient"),
];

/// linear_history_classic, and mindlin_classic: the same arithmetic in LAMMPS 2025.
const fn classic(name: &'static str) -> Style<Tangential> {
    Style {
        name,
        coeffs: HISTORY,
        history: 3,
        flags: Flags { contact_radius: true, synchronizable: true, ..Flags::NONE },
        build: |c, _| Tangential::LinearHistoryClassic { k: c[0], xt: c[1], mu: c[2] },
        mix: geometric,
    }
}

/// A row of the mindlin family.
const fn mindlin(name: &'static str, force: bool, rescale: bool) -> Style<Tangential> {
    Style {
        name,
        coeffs: MINDLIN,
        history: if rescale { 4 } else { 3 },
        flags: Flags { contact_radius: true, synchronizable: true, keep: if rescale { 1 << 3 } else { 0 }, ..Flags::NONE },
        build: match (force, rescale) {
            (false, false) => |c, ctx| Tangential::Mindlin { k: mindlin_k(c, ctx), xt: c[1], mu: c[2], force: false, rescale: false },
            (true, false) => |c, ctx| Tangential::Mindlin { k: mindlin_k(c, ctx), xt: c[1], mu: c[2], force: true, rescale: false },
            (false, true) => |c, ctx| Tangential::Mindlin { k: mindlin_k(c, ctx), xt: c[1], mu: c[2], force: false, rescale: true },
            (true, true) => |c, ctx| Tangential::Mindlin { k: mindlin_k(c, ctx), xt: c[1], mu: c[2], force: true, rescale: true },
        },
        mix: mix_mindlin,
    }
}

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
        flags: Flags { synchronizable: true, ..Flags::NONE },
        build: |c, _| Tangential::LinearHistory { k: c[0], xt: c[1], mu: c[2] },
        mix: geometric,
    },
    classic("linear_history_classic"),
    classic("mindlin_classic"),
    mindlin("mindlin", false, false),
    mindlin("mindlin/force", true, false),
    mindlin("mindlin_rescale", false, true),
    mindlin("mindlin_rescale/force", true, true),
];

/// LAMMPS mix_stiffnessG: the effective shear modulus of two materials.
pub fn mix_stiffness_g(e1: f64, e2: f64, nu1: f64, nu2: f64) -> f64 {
    let f1 = 2.0 * (2.0 - nu1) * (1.0 + nu1) / e1;
    let f2 = 2.0 * (2.0 - nu2) * (1.0 + nu2) / e2;
    1.0 / (f1 + f2)
}

/// LAMMPS mix_stiffnessG_wall: a material against a rigid wall.
pub fn mix_stiffness_g_wall(e: f64, nu: f64) -> f64 {
    let factor = 4.0 * (2.0 - nu) * (1.0 + nu);
    e / factor
}

/// Kt, or for NULL 8 G_eff from the normal model's E and nu (of the mixed coefficients for an
/// unset pair, as LAMMPS).
fn mindlin_k(c: &[f64], ctx: &Ctx) -> f64 {
    if c[0] != NULL {
        return c[0];
    }
    // the parser refuses NULL without material properties
    let (e, nu) = ctx.material.unwrap_or((0.0, 0.0));
    8.0 * if ctx.wall { mix_stiffness_g_wall(e, nu) } else { mix_stiffness_g(e, e, nu, nu) }
}

/// Geometric means; Kt stays NULL if either is.
fn mix_mindlin(a: &[f64], b: &[f64]) -> Coeffs {
    let mut m = geometric(a, b);
    if a[0] == NULL || b[0] == NULL {
        m[0] = NULL;
    }
    m
}

/// What a tangential model reads of the contact.
pub struct TangentialIn<'a> {
    pub nx: &'a [f64; 3],
    /// `synchronized_verlet`: the full-step normal (`nx` is then the half-step one)
    pub full: Option<&'a [f64; 3]>,
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
    /// The stiffness and friction coefficient (LAMMPS get_k, get_mu; marshall twisting reads them).
    pub fn k_mu(&self) -> (f64, f64) {
        match *self {
            Tangential::LinearNoHistory { mu, .. } => (0.0, mu),
            Tangential::LinearHistory { k, mu, .. } | Tangential::LinearHistoryClassic { k, mu, .. } | Tangential::Mindlin { k, mu, .. } => (k, mu),
            Tangential::None => (0.0, 0.0),
        }
    }

    /// x_gt, the tangential damping ratio (LAMMPS' tangential damp is x_gt eta_n).
    pub fn xt(&self) -> f64 {
        match *self {
            Tangential::LinearNoHistory { xt, .. } | Tangential::LinearHistory { xt, .. } | Tangential::LinearHistoryClassic { xt, .. } | Tangential::Mindlin { xt, .. } => xt,
            Tangential::None => 0.0,
        }
    }

    /// F_t; `h` is this model's history (its `history` values).
    #[inline(always)]
    pub fn force(&self, t: &TangentialIn, h: &mut [f64]) -> [f64; 3] {
        let (nx, vtr) = (t.nx, t.vtr);
        match *self {
            Tangential::LinearHistory { k, xt, mu } => {
                let damp = xt * t.damp_prefactor;
                let fscrit = t.fncrit * mu;
                let mut turned = false;
                if t.update {
                    // rotate into the tangent plane, keeping the length, when the normal part matters
                    let rsht = h[0] * nx[0] + h[1] * nx[1] + h[2] * nx[2];
                    if rsht.abs() * k > FRAME_EPS * fscrit {
                        rotate_rescale(h, nx, rsht);
                    }
                    h[0] += t.dt * vtr[0];
                    h[1] += t.dt * vtr[1];
                    h[2] += t.dt * vtr[2];
                    turned = t.full.is_some_and(|n| second_turn(h, n, |r| r.abs() * k > FRAME_EPS * fscrit));
                }
                let vd = damped_velocity(vtr, t.full, turned);
                let fs = [-k * h[0] - damp * vd[0], -k * h[1] - damp * vd[1], -k * h[2] - damp * vd[2]];
                // the spring is set back with the unturned v_tr (LAMMPS 22 Jul 2025, measured)
                coulomb(fs, None, fscrit, Some(-1.0 / k), damp, vtr, h)
            }
            Tangential::Mindlin { k, xt, mu, force, rescale } => {
                let damp = xt * t.damp_prefactor;
                let fscrit = t.fncrit * mu;
                let k_scaled = k * t.a;
                // a stored force is compared as it is, a displacement as its force
                let matters = |rsht: f64| if force { rsht.abs() } else { rsht.abs() * k_scaled } > FRAME_EPS * fscrit;
                let mut turned = false;
                // unloading since the last update: the spring shrinks with the contact radius
                if rescale && t.a < h[3] {
                    let s = t.a / h[3];
                    h[0] *= s;
                    h[1] *= s;
                    h[2] *= s;
                }
                if t.update {
                    let rsht = h[0] * nx[0] + h[1] * nx[1] + h[2] * nx[2];
                    if matters(rsht) {
                        rotate_rescale(h, nx, rsht);
                    }
                    let step = if force { -k_scaled * t.dt } else { t.dt };
                    h[0] += step * vtr[0];
                    h[1] += step * vtr[1];
                    h[2] += step * vtr[2];
                    if rescale {
                        h[3] = t.a;
                    }
                    turned = t.full.is_some_and(|n| second_turn(h, n, matters));
                }
                let vd = damped_velocity(vtr, t.full, turned);
                let fs = if force {
                    [h[0] - damp * vd[0], h[1] - damp * vd[1], h[2] - damp * vd[2]]
                } else {
                    [-k_scaled * h[0] - damp * vd[0], -k_scaled * h[1] - damp * vd[1], -k_scaled * h[2] - damp * vd[2]]
                };
                // the spring is set back with the unturned v_tr (LAMMPS)
                coulomb(fs, None, fscrit, (!force).then(|| -1.0 / k_scaled), damp, vtr, h)
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
                coulomb(fs, Some(shrmag), fscrit, Some(-1.0 / k), damp, vtr, h)
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

/// LAMMPS' threshold for turning the spring into the tangent plane (relative to F_s,crit).
pub const FRAME_EPS: f64 = 1e-10;

/// Project the spring `h` (its first 3 values) onto the plane normal to `nx` and rescale it to
/// its old length (LAMMPS rotate_rescale_vec); `rsht` = h.n.
#[inline(always)]
pub fn rotate_rescale(h: &mut [f64], nx: &[f64; 3], rsht: f64) {
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

/// `synchronized_verlet`'s second turn: the spring, advanced in the half-step tangent plane,
/// turned into the full-step one (`full`) when its normal part `matters`. Returns whether it was.
#[inline(always)]
fn second_turn(h: &mut [f64], full: &[f64; 3], matters: impl Fn(f64) -> bool) -> bool {
    let rsht = h[0] * full[0] + h[1] * full[1] + h[2] * full[2];
    let turned = matters(rsht);
    if turned {
        rotate_rescale(h, full, rsht);
    }
    turned
}

/// The velocity the tangential dashpot acts on: v_tr, turned into the full-step tangent plane
/// as the spring was (`synchronized_verlet`).
#[inline(always)]
fn damped_velocity(vtr: &[f64; 3], full: Option<&[f64; 3]>, turned: bool) -> [f64; 3] {
    let mut v = *vtr;
    if let (Some(n), true) = (full, turned) {
        let r = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
        rotate_rescale(&mut v, n, r);
    }
    v
}

/// Coulomb's limit on a spring-dashpot force: above mu F_n,crit the force is scaled down and
/// the spring set back to match; a spring of zero length gives no force at all (LAMMPS).
/// `shrmag`: the spring length that decides this (None: its length now, taken only if needed);
/// `kinv`: -1/stiffness, the spring from its force (None: the history is the force).
#[inline(always)]
fn coulomb(mut fs: [f64; 3], shrmag: Option<f64>, fscrit: f64, kinv: Option<f64>, damp: f64, vtr: &[f64; 3], h: &mut [f64]) -> [f64; 3] {
    let magfs = len3(fs[0], fs[1], fs[2]);
    if magfs > fscrit {
        if shrmag.unwrap_or_else(|| len3(h[0], h[1], h[2])) != 0.0 {
            let s = fscrit * (1.0 / magfs);
            for d in 0..3 {
                h[d] = s * fs[d];
                h[d] += damp * vtr[d];
                if let Some(kinv) = kinv {
                    h[d] *= kinv;
                }
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
