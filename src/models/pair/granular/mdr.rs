//! The `mdr` normal model of `pair_style granular` (Zunker and Kamrin's mechanically derived
//! contact model for elastic-perfectly plastic, adhesive spheres under large deformation;
//! LAMMPS 22 Jul 2025 GranSubModNormalMDR):
//!
//! ```text
//! pair_coeff I J mdr E nu Y gamma psi_b damp damping mdr 1|2 tangential ...
//! ```
//!
//! E Young's modulus (> 0), nu Poisson's ratio in [0, 0.5], Y yield stress, gamma effective
//! surface energy (0: no adhesion), psi_b the free-area ratio below which the bulk response
//! starts, damp the coefficient of `damping mdr` (type 1: eta_n = damp sqrt(2 m_eff E_eff a),
//! type 2: eta_n = damp while in contact).
//!
//! Each contact places a rigid flat at the overlap and evaluates both spheres against it (side 0
//! is the atom of the larger ID): the overlap is split between the sides by the largest overlap
//! seen (capped at 0.95 R), each side follows the elastic (Hertzian, in the method of
//! dimensionality reduction) then plastic (elliptical indenter after yield) law with adhesion,
//! plus a bulk term once the free surface ratio psi falls below psi_b; the force is the mean of
//! the two sides, scaled by the contact's penalty weight (contacts screened by a third sphere).
//! A wall contact is one side, magnified near full overlap. 27 history values per contact, kept
//! as they are from either side (LAMMPS' transfer factor +1).
//!
//! The per-atom state (apparent radius growth, volumes, areas, psi) is kept by
//! [`super::mdr_state`] between force evaluations, as LAMMPS' internal fix GRANULAR/MDR does.

use super::normal::Normal;
use super::{granular_contact_with, Coeff, Range};
use crate::engine::contact_history::{ContactHistory, HistoryChunk};
use crate::engine::fields::{self, Field};
use crate::engine::neighbor::{special_level, NEIGH_MASK};
use crate::engine::par::cmath::cbrt;
use crate::engine::tally::PairShare;
use crate::models::pair::contact::{effective_mass, Contact, ContactModel};
use crate::models::pair::{PairInput, PairOutput, Tally};
use std::f64::consts::PI;

/// History values of the model (LAMMPS Granular_MDR_NS): each pair of indices holds side 0, 1.
pub const HISTORY: usize = 27;
const DELTA: usize = 0;
const DELTAO: usize = 2;
const DELTA_MDR: usize = 4;
const DELTA_BULK: usize = 6;
const DELTAMAX_MDR: usize = 8;
const YFLAG: usize = 10;
const DELTAY: usize = 12;
const CA: usize = 14;
const AADH: usize = 16;
/// contact area of each side at the last step
pub const AC: usize = 18;
const EPS_BAR: usize = 20;
/// the contact's penalty (set before each force evaluation by [`super::mdr_state`])
pub const PENALTY: usize = 22;
pub const DELTA_MAX: usize = 23;
/// the rigid flat's place on each side
pub const DELTAP: usize = 24;
/// sqrt(2 m_eff E_eff a): the scale of `damping mdr` type 1
pub const DAMP_SCALE: usize = 26;

/// The most history values of a contact with the mdr model and the other sub-models.
pub const MAX_TOTAL_HISTORY: usize = 40;

/// Largest share of a radius one side of a contact may be pushed in.
pub const OVERLAP_LIMIT: f64 = 0.95;

const MAX_IT: usize = 100;
const EPSILON1: f64 = 1e-10;
const EPSILON2: f64 = 1e-16;
const EPSILON3: f64 = 1e-20;
// LAMMPS' literals
const PISQ: f64 = 9.869_604_401_089_358;
const PIINV: f64 = std::f64::consts::FRAC_1_PI;
const PITOFIVETHIRDS: f64 = 6.738_808_595_698_141;
const CBRT2: f64 = 1.259_921_049_894_873_2;
const SQRTHALFPI: f64 = 1.253_314_137_315_500_1;
const CBRTHALFPI: f64 = 1.162_447_351_509_626_5;
const FOURTHIRDS: f64 = 4.0 / 3.0;
const THIRD: f64 = 1.0 / 3.0;

pub const COEFFS: &[Coeff] = &[
    Coeff { name: "E", about: "Young's modulus", range: Range::Positive },
    Coeff { name: "nu", about: "Poisson's ratio", range: Range::Closed(0.0, 0.5) },
    Coeff { name: "Y", about: "yield stress", range: Range::NonNegative },
    Coeff { name: "gamma", about: "effective surface energy", range: Range::NonNegative },
    Coeff { name: "psi_b", about: "free-area ratio that starts the bulk response", range: Range::Closed(0.0, 1.0) },
    Coeff { name: "damp", about: "damping coefficient of damping mdr", range: Range::NonNegative },
];

/// The model's constants (LAMMPS coeffs_to_local).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Mdr {
    pub e: f64,
    pub nu: f64,
    pub y: f64,
    pub gamma: f64,
    pub psi_b: f64,
    pub damp: f64,
    g: f64,
    kappa: f64,
    eeff: f64,
    eeffinv: f64,
    eeffsq: f64,
    eeffsqinv: f64,
    gammasq: f64,
    gamma3: f64,
    gamma4: f64,
}

impl Mdr {
    pub fn new(c: &[f64]) -> Mdr {
        let (e, nu, y, gamma, psi_b, damp) = (c[0], c[1], c[2], c[3], c[4], c[5]);
        let eeff = e / (1.0 - nu * nu);
        let eeffinv = 1.0 / eeff;
        let gammasq = gamma * gamma;
        Mdr {
            e,
            nu,
            y,
            gamma,
            psi_b,
            damp,
            g: e / (2.0 * (1.0 + nu)),
            kappa: e / (3.0 * (1.0 - 2.0 * nu)),
            eeff,
            eeffinv,
            eeffsq: eeff * eeff,
            eeffsqinv: eeffinv * eeffinv,
            gammasq,
            gamma3: gammasq * gamma,
            gamma4: gammasq * gammasq,
        }
    }
}

/// What a contact reads of one of its atoms.
#[derive(Clone, Copy, Debug, Default)]
pub struct MdrAtom {
    pub tag: i64,
    /// the apparent radius
    pub radius: f64,
    /// the radius the atom was created with
    pub ro: f64,
    pub psi: f64,
    pub ddelta_bar: f64,
    pub vgeo: f64,
    pub acon0: f64,
    pub velas: f64,
}

/// The per-atom sums of the pair pass ([`crate::engine::fields::MDR_SUMS`] order), owned atoms.
pub struct Sums<'a>(pub [&'a mut [f64]; 9]);

const VCAPS: usize = 0;
const EPS: usize = 1;
const DRNUM: usize = 2;
const DRDEN: usize = 3;
const ACON1: usize = 4;
const ATOT_SUM: usize = 5;
const SIGMA: usize = 6;

impl Sums<'_> {
    /// Add to the sum `k` of atom `a` (a ghost's sums are not kept: its owner lists the pair
    /// too).
    #[inline]
    fn add(&mut self, k: usize, a: usize, x: f64) {
        if let Some(s) = self.0[k].get_mut(a) {
            *s += x;
        }
    }
}

/// One contact's result.
#[derive(Clone, Copy, Debug, Default)]
pub struct MdrForce {
    /// the normal force magnitude (repulsive positive)
    pub f: f64,
    /// the mean contact area of the two sides (LAMMPS' svector entry)
    pub area: f64,
    /// a newly inserted overlap yielded at once (LAMMPS warns once)
    pub warn: bool,
}

#[inline(always)]
fn cmax(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

#[inline(always)]
fn cmin(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// The force of an elliptical indenter pushed `delta` deep (LAMMPS calculate_nonadhesive_mdr_force).
#[inline]
fn nonadhesive(delta: f64, ainv: f64, eeff: f64, a: f64, b: f64) -> f64 {
    let x = delta * ainv;
    let mut f = (1.0 - 2.0 * delta * ainv).acos();
    f -= (2.0 - 4.0 * delta * ainv) * (x - x * x).sqrt();
    f * (0.25 * eeff * a * b)
}

/// Values in (-1e-20, 0) from round-off become 0.
#[inline]
fn round_up_negative_epsilon(v: f64) -> f64 {
    if v < 0.0 && v > -EPSILON3 { 0.0 } else { v }
}

/// LAMMPS GranSubModNormalMDR::calculate_forces. `at` are the contact's atoms i and j (a wall:
/// j unused) with their local indices `idx`, `delta` = R_i + R_j - r (a wall: R_i - distance),
/// `nx` the unit vector from j to i, `h` the model's history values. Adds the atoms' sums when
/// `update` (outside run setup) and stores DAMP_SCALE for `damping mdr`.
#[allow(clippy::too_many_arguments)]
pub fn normal_force(m: &Mdr, at: [&MdrAtom; 2], idx: [usize; 2], wall: bool, delta_in: f64, nx: &[f64; 3], meff: f64, h: &mut [f64], update: bool, sums: &mut Sums) -> MdrForce {
    let mut out = MdrForce::default();
    let (mut f0, mut f1) = (0.0, 0.0);
    let mut ac_avg = 0.0;
    let mut a_damp = 0.0;
    let deltap0 = h[DELTAP];
    let deltap1 = h[DELTAP + 1];
    // the largest overlap seen is kept even during setup (it cannot change before the next step)
    let deltamaxi = h[DELTA_MAX];
    if delta_in >= h[DELTA_MAX] {
        h[DELTA_MAX] = delta_in;
    }
    let deltamax = h[DELTA_MAX];
    let itag_greater = at[0].tag > at[1].tag;

    for side in 0..2 {
        // side 0 is the atom of the larger ID (so both listings of a pair agree)
        let (s, o) = if wall || (side == 0 && itag_greater) || (side != 0 && !itag_greater) { (0, 1) } else { (1, 0) };
        let mut delta = delta_in;
        if !wall {
            let (radi, radj) = (at[s].radius, at[o].radius);
            // the largest geometric overlaps on either side of the rigid flat
            let denom = 1.0 / (2.0 * (deltamax - radi - radj));
            let opt1 = deltamax * (deltamax - 2.0 * radj) * denom;
            let opt2 = deltamax * (deltamax - 2.0 * radi) * denom;
            let (mut geo, alt) = if radi < radj { (cmax(opt1, opt2), cmin(opt1, opt2)) } else { (cmin(opt1, opt2), cmax(opt1, opt2)) };
            // a side pushed in beyond the limit passes the rest to the other side
            if geo / radi > OVERLAP_LIMIT {
                geo = radi * OVERLAP_LIMIT;
            } else if alt / radj > OVERLAP_LIMIT {
                geo = deltamax - radj * OVERLAP_LIMIT;
            }
            let deltap = deltap0 + deltap1;
            let dp = if side == 0 { deltap0 } else { deltap1 };
            delta = geo + (dp - geo) * (delta_in - deltamax) / (deltap - deltamax);
        } else if side != 0 {
            break;
        }
        let a = &at[s];
        let ai = idx[s];
        let (ro, r) = (a.ro, a.radius);

        let ddelta = delta - h[DELTA + side];
        if update {
            h[DELTA + side] = delta;
        }
        let deltao = delta - (r - ro);
        let ddeltao = deltao - h[DELTAO + side];
        if update {
            h[DELTAO + side] = deltao;
        }
        // with the bulk response on, the mean surface displacement goes to the bulk part
        let (ddelta_mdr, ddelta_bulk) =
            if a.psi < m.psi_b { (cmin(ddelta - a.ddelta_bar, delta - h[DELTA_MDR + side]), a.ddelta_bar) } else { (ddelta, 0.0) };
        let delta_mdr = h[DELTA_MDR + side] + ddelta_mdr;
        if update {
            h[DELTA_MDR + side] = delta_mdr;
        }
        let delta_bulk = cmax(0.0, h[DELTA_BULK + side] + ddelta_bulk);
        if update {
            h[DELTA_BULK + side] = delta_bulk;
        }
        if delta_mdr > h[DELTAMAX_MDR + side] {
            h[DELTAMAX_MDR + side] = delta_mdr;
        }
        let deltamax_mdr = h[DELTAMAX_MDR + side];

        // mean pressure along the yield surface
        let py = m.y * (1.75 * (-4.4 * deltamax_mdr / r).exp() + 1.0);
        if h[YFLAG + side] == 0.0 && delta_mdr >= deltamax_mdr {
            let phertz = 4.0 * m.eeff * delta_mdr.sqrt() / (3.0 * PI * r.sqrt());
            if !update && deltamaxi == 0.0 && phertz > py {
                out.warn = true;
            }
            if update && phertz > py {
                h[YFLAG + side] = 1.0;
                h[DELTAY + side] = delta_mdr;
                let dy = delta_mdr;
                h[CA + side] = PI * (dy * dy - dy * r);
            }
        }

        let ca = h[CA + side];
        let (aa, ainv, b, deltae1d, amax);
        if h[YFLAG + side] == 0.0 {
            // elastic
            aa = 4.0 * r;
            ainv = 1.0 / aa;
            b = 2.0 * r;
            deltae1d = delta_mdr;
            amax = (deltamax_mdr * r).sqrt();
        } else {
            // plastic: an elliptical indenter of height A and width B
            amax = (2.0 * deltamax_mdr * r - deltamax_mdr * deltamax_mdr + ca * PIINV).sqrt();
            let amaxsq = amax * amax;
            aa = 4.0 * py * m.eeffinv * amax;
            ainv = 1.0 / aa;
            b = 2.0 * amax;
            let deltae1dmax = aa * 0.5;
            // the force of the indenter pushed in to A/2 (LAMMPS subtracts the second term
            // without the prefactor; it vanishes up to round-off)
            let x = deltae1dmax * ainv;
            let mut fmax = m.eeff * (aa * b * 0.25) * (1.0 - 2.0 * deltae1dmax * ainv).acos();
            fmax -= (2.0 - 4.0 * deltae1dmax * ainv) * (x - x * x).sqrt();
            // depth of the particle centre
            let zr = r - (deltamax_mdr - deltae1dmax);
            let root = (amaxsq + zr * zr).sqrt();
            let mut delta_r = 2.0 * amaxsq * (-1.0 + m.nu) - (-1.0 + 2.0 * m.nu) * zr * (-zr + root);
            delta_r *= fmax / (2.0 * PI * amaxsq * m.g * root);
            deltae1d = (delta_mdr - deltamax_mdr + deltae1dmax + delta_r) / (1.0 + delta_r / deltae1dmax);
            if update {
                h[DELTAP + side] = deltamax_mdr - (deltae1dmax + delta_r);
            }
        }

        let a_fac = 0.99;
        let a_na = if deltae1d >= 0.0 { b * (aa - deltae1d).sqrt() * deltae1d.sqrt() * ainv } else { 0.0 };
        let mut aadh = h[AADH + side];
        if aadh > a_fac * amax {
            aadh = a_fac * amax;
        }
        let f_mdr = if m.gamma <= 0.0 {
            if update {
                h[AADH + side] = a_na;
            }
            if deltae1d <= 0.0 { 0.0 } else { nonadhesive(deltae1d, ainv, m.eeff, aa, b) }
        } else if delta_mdr == deltamax_mdr || a_na >= aadh {
            // no tensile springs: purely compressive
            if update {
                h[AADH + side] = a_fac * a_na;
            }
            if deltae1d <= 0.0 { 0.0 } else { nonadhesive(deltae1d, ainv, m.eeff, aa, b) }
        } else {
            let f = adhesive(m, aa, ainv, b, deltae1d, &mut aadh);
            if update {
                h[AADH + side] = aadh;
            }
            f
        };

        // the penalty of a contact screened by a third sphere
        let wij = cmax(1.0 - h[PENALTY], 0.0);
        let mut ac = if h[YFLAG + side] == 0.0 { PI * delta * r } else { PI * (2.0 * delta * r - delta * delta) + ca };
        if ac < 0.0 {
            ac = 0.0;
        }
        if update {
            sums.add(ATOT_SUM, ai, wij * (ac - 2.0 * PI * r * (deltamax_mdr + delta_bulk)));
            sums.add(ACON1, ai, wij * ac);
        }
        ac_avg += wij * ac;
        a_damp += if m.gamma > 0.0 { aadh } else { a_na };

        let f_bulk = if delta_bulk <= 0.0 { 0.0 } else { (1.0 / a.vgeo) * a.acon0 * delta_bulk * m.kappa * ac };
        if side == 0 {
            f0 = f_mdr + f_bulk;
        } else {
            f1 = f_mdr + f_bulk;
        }
        if update {
            h[AC + side] = wij * ac;
            sums.add(VCAPS, ai, PI * THIRD * (delta * delta) * (3.0 * r - delta));
        }

        let fntmp = wij * (f_mdr + f_bulk);
        let fv = [fntmp * nx[0], fntmp * nx[1], fntmp * nx[2]];
        let bv = [-(ro - deltao) * nx[0], -(ro - deltao) * nx[1], -(ro - deltao) * nx[2]];
        let eps_bar_contact = (fv[0] * bv[0] + fv[1] * bv[1] + fv[2] * bv[2]) / (3.0 * m.kappa * a.velas);
        if update {
            sums.add(EPS, ai, eps_bar_contact);
        }
        if update && delta_mdr == deltamax_mdr && h[YFLAG + side] > 0.0 && f_mdr > 0.0 {
            let vo = FOURTHIRDS * PI * (ro * ro * ro);
            sums.add(DRNUM, ai, -(vo * (eps_bar_contact - h[EPS_BAR + side])));
            sums.add(DRNUM, ai, -(wij * PI * ddeltao * (2.0 * deltao * ro - deltao * deltao + r * r - ro * ro)));
            sums.add(DRDEN, ai, wij * 2.0 * PI * r * (deltao + r - ro));
        }
        if update {
            h[EPS_BAR + side] = eps_bar_contact;
            for d in 0..3 {
                sums.add(SIGMA + d, ai, fv[d] * bv[d] / a.velas);
            }
        }
    }
    out.area = ac_avg * 0.5;

    let wij = cmax(1.0 - h[PENALTY], 0.0);
    let damp_scale;
    if wall {
        a_damp /= 2.0;
        // E_eff/2 of two particles against the wall's E_eff
        damp_scale = (meff * 2.0 * (0.5 * m.eeff) * a_damp).sqrt();
        // the wall pushes harder as the sphere approaches full overlap
        let wfm = (10.7 * h[DELTAO] / at[0].ro - 10.0).exp() + 1.0;
        out.f = wij * f0 * wfm;
    } else {
        damp_scale = (meff * 2.0 * m.eeff * a_damp).sqrt();
        out.f = wij * (f0 + f1) * 0.5;
    }
    if update {
        h[DAMP_SCALE] = if a_damp <= 0.0 { 0.0 } else { damp_scale };
    }
    out
}

/// The adhesive force (cases 2 and 3 of LAMMPS: tensile springs at the edge of the contact,
/// within or beyond their critical length); `aadh` is the adhesive contact radius in and out.
fn adhesive(m: &Mdr, aa: f64, ainv: f64, b: f64, deltae1d: f64, aadh: &mut f64) -> f64 {
    let ainvsq = ainv * ainv;
    let asq = aa * aa;
    let a4 = asq * asq;
    let binv = 1.0 / b;
    let bsq = b * b;
    let b4 = bsq * bsq;
    let b6 = {
        // LAMMPS MathSpecial::powint(B, 6)
        let b2 = b * b;
        let b4 = b2 * b2;
        b2 * b4
    };
    let gamma = m.gamma;
    let lmax = (2.0 * PI * *aadh * gamma * m.eeffinv).sqrt();
    let g_of = |a: f64| round_up_negative_epsilon(aa * 0.5 - aa * binv * (bsq * 0.25 - a * a).sqrt());
    let g_aadh = g_of(*aadh);

    let einv3 = m.eeffinv * m.eeffinv * m.eeffinv;
    let mut tmp = 27.0 * a4 * b4 * gamma * m.eeffinv;
    tmp -= 2.0 * b6 * m.gamma3 * PISQ * einv3;
    tmp += 27f64.sqrt() * asq * b4 * (27.0 * a4 * m.eeffsq * m.gammasq - 4.0 * bsq * m.gamma4 * PISQ).sqrt() * m.eeffsqinv;
    let tmp = cbrt(tmp);
    let mut acrit = -bsq * gamma * PI * ainvsq * m.eeffinv;
    acrit += CBRT2 * b4 * m.gammasq * PITOFIVETHIRDS / (asq * m.eeffsq * tmp);
    acrit += CBRTHALFPI * tmp * ainvsq;
    acrit /= 6.0;

    if deltae1d + lmax - g_aadh >= 0.0 {
        // the springs hold
        let f_na = nonadhesive(g_aadh, ainv, m.eeff, aa, b);
        return f_na + 2.0 * m.eeff * (deltae1d - g_aadh) * *aadh;
    }
    // the springs at the edge break: the contact radius shrinks until they hold (Newton-Raphson)
    if *aadh < acrit {
        *aadh = 0.0;
        return 0.0;
    }
    let mut a = *aadh;
    for it in 0..MAX_IT {
        let fa_tmp = deltae1d - aa * 0.5 + aa * (bsq * 0.25 - a * a).sqrt() * binv;
        let fa = fa_tmp + (2.0 * PI * a * gamma * m.eeffinv).sqrt();
        if fa.abs() < EPSILON1 {
            break;
        }
        let mut dfda = -a * aa / (b * (-(a * a) + bsq * 0.25).sqrt());
        dfda += gamma * SQRTHALFPI / (a * gamma * m.eeff).sqrt();
        a -= fa / dfda;
        let fa2 = fa_tmp + (2.0 * PI * a * gamma * m.eeffinv).sqrt();
        if (fa - fa2).abs() < EPSILON2 {
            break;
        }
        if it == MAX_IT - 1 {
            a = 0.0;
        }
    }
    *aadh = a;
    if a < acrit {
        *aadh = 0.0;
        return 0.0;
    }
    let g = g_of(a);
    nonadhesive(g, ainv, m.eeff, aa, b) + 2.0 * m.eeff * (deltae1d - g) * a
}

/// Whether the pair of entry `e` (atoms i, j) overlaps, with x_i - x_j, r^2 and R_i + R_j; a
/// contact that ended forgets its history (LAMMPS' check_contact in the pair loop and in
/// fix GRANULAR/MDR).
pub(super) fn touching(hc: &mut HistoryChunk, e: usize, x: &[[f64; 3]], radius: &[f64], i: usize, j: usize) -> Option<([f64; 3], f64, f64)> {
    let del = [x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]];
    let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
    let radsum = radius[i] + radius[j];
    let touch = rsq < radsum * radsum;
    hc.touch[e] = touch as u8;
    if !touch {
        let size = hc.values.len() / hc.touch.len().max(1);
        hc.values[e * size..(e + 1) * size].iter_mut().for_each(|v| *v = 0.0);
        return None;
    }
    Some((del, rsq, radsum))
}

/// The contact loop of pair granular with the mdr model: LAMMPS' pair loop in list order, on one
/// thread (each contact adds to its atoms' sums in that order). Forces and torques go to owned
/// atoms; a pair with a ghost is computed from both sides. Returns the tallies and whether a
/// newly inserted overlap yielded at once during setup (LAMMPS' warning).
pub fn compute_contacts(models: &super::GranularModels, history: &mut ContactHistory, input: &PairInput, out: &mut PairOutput) -> (Tally, bool) {
    let a = input.atoms;
    let mut t = Tally::default();
    let mut warn = false;
    let read = |f: Field| a.field_values(f).unwrap_or(&[]);
    let (ro, psi, ddelta_bar, vgeo, acon0, velas) = (read(fields::MDR_RO), read(fields::MDR_PSI), read(fields::MDR_DDELTA_BAR), read(fields::MDR_VGEO), read(fields::MDR_ACON0), read(fields::MDR_VELAS));
    let nall = a.nall();
    if [ro, psi, ddelta_bar, vgeo, acon0, velas].iter().any(|v| v.len() < nall) {
        return (t, warn);
    }
    let mut slots: [&mut [f64]; 9] = Default::default();
    for (f, v) in out.fields.iter_mut() {
        if let Some(k) = fields::MDR_SUMS.iter().position(|s| s == f) {
            slots[k] = &mut **v;
        }
    }
    let mut sums = Sums(slots);
    let (f, torque) = (&mut *out.f, &mut *out.torque);
    let mut shares = Vec::new();
    let record = input.eflag && out.peratom.is_some();
    let rmass = input.rigid_mass.unwrap_or(&a.rmass[..]);
    let (x, radius, typ, nlocal) = (&a.x, &a.radius, &a.typ, a.nlocal);
    let size = history.size();
    let stride = input.ntypes + 1;
    let atom = |i: usize| MdrAtom { tag: a.tag[i], radius: radius[i], ro: ro[i], psi: psi[i], ddelta_bar: ddelta_bar[i], vgeo: vgeo[i], acon0: acon0[i], velas: velas[i] };
    for (c, chunk) in input.list.chunks.iter().enumerate() {
        let hc = &mut history.chunks[c];
        for i in chunk.start..chunk.end {
            let k0 = chunk.first_entry(i);
            for (k, &jraw) in chunk.neighbors(i).iter().enumerate() {
                let j = (jraw & NEIGH_MASK) as usize;
                let e = k0 + k;
                let factor = input.special_lj[special_level(jraw)];
                if factor == 0.0 || input.type_filter.is_some_and(|fl| !fl[typ[i] * stride + typ[j]]) {
                    continue;
                }
                let Some((del, rsq, radsum)) = touching(hc, e, x, radius, i, j) else { continue };
                let h = &mut hc.values[e * size..(e + 1) * size];
                let m = models.params(typ[i], typ[j]);
                let Normal::Mdr(mdr) = &m.normal else { continue };
                let r = rsq.sqrt();
                let rinv = 1.0 / r;
                let nx = [rinv * del[0], rinv * del[1], rinv * del[2]];
                let (mi, mj) = (rmass[i], rmass[j]);
                let meff = effective_mass(mi, mj, input.frozen(i), input.frozen(j));
                let (ai, aj) = (atom(i), atom(j));
                let n = normal_force(mdr, [&ai, &aj], [i, j], false, radsum - r, &nx, meff, &mut h[..HISTORY], input.advance, &mut sums);
                warn |= n.warn;
                let g = Contact { del, rsq, radi: radius[i], radj: radius[j], vi: &a.v[i], vj: &a.v[j], omegai: &a.omega[i], omegaj: &a.omega[j], meff };
                let mut cf = granular_contact_with(m, &g, false, h, input.advance, input.dt, Some(n.f));
                for d in 0..3 {
                    cf.f[d] *= factor;
                    cf.ti[d] *= factor;
                    cf.tj[d] *= factor;
                    f[i][d] += cf.f[d];
                    torque[i][d] += cf.ti[d];
                }
                let w = if j < nlocal {
                    for d in 0..3 {
                        f[j][d] -= cf.f[d];
                        torque[j][d] += cf.tj[d];
                    }
                    1.0
                } else {
                    0.5
                };
                if input.eflag {
                    t.xyz(w, del, cf.f);
                    if record {
                        shares.push(PairShare::xyz(i, j, 0.0, del, cf.f));
                    }
                }
            }
        }
    }
    if let Some(pa) = out.peratom.as_deref_mut() {
        pa.add_pairs(&shares);
    }
    (t, warn)
}
