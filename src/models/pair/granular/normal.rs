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
//! * `jkr E eta_n0 nu gamma`: Johnson-Kendall-Roberts. The contact radius a solves the JKR
//!   relation between the overlap and a (LAMMPS' closed form); F_n = 4/3 E_eff a^3/R_eff -
//!   2 pi a^2 sqrt(4 gamma E_eff/(pi a)); F_n,crit = |F_n + 2 F_pulloff|, F_pulloff =
//!   3 pi gamma R_eff. Cohesive, and beyond contact: a contact made by touching holds until the
//!   centres are R_i + R_j + delta_pulloff apart, delta_pulloff = (3 pi^2/16)^(1/3)
//!   (R_eff gamma^2/E_eff^2)^(1/3) (the neighbour cutoff includes it).
//!
//! * `mdr E nu Y gamma psi_b damp`: Zunker and Kamrin's model of large elastic-plastic
//!   deformation ([`super::mdr`]); its force comes from the contact loop of that file, which
//!   keeps per-atom state. Only `damping mdr` goes with it.
//!
//! eta_n0 is the damping model's coefficient (a restitution coefficient for coeff_restitution).
//! Mixing (unset I,J pairs): geometric means, except E: Kn = 4/3 E_eff(E_i, nu_i, E_j, nu_j)
//! (measured in LAMMPS 2025).

use super::mdr::{self, Mdr};
use super::{geometric, nn, poisson, Coeff, Coeffs, Ctx, Flags, Style};
// the C library's cube root, as LAMMPS' (f64::cbrt differs from glibc's in the last bit)
use crate::engine::par::cmath::cbrt;
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
    /// k = 4/3 E_eff
    Jkr { k: f64, emix: f64, cohesion: f64 },
    /// the force is [`super::mdr::normal_force`]'s (it needs the atoms' state)
    Mdr(Mdr),
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
    Style {
        name: "jkr",
        coeffs: DMT,
        history: 0,
        flags: Flags { contact_radius: true, cohesive: true, beyond_contact: true, material: true, ..Flags::NONE },
        build: |c, ctx| {
            let emix = material_e(c, ctx);
            Normal::Jkr { k: FOURTHIRDS * emix, emix, cohesion: c[3] }
        },
        mix: mix_material,
    },
    Style {
        name: "mdr",
        coeffs: mdr::COEFFS,
        history: mdr::HISTORY,
        // every value is the same from either side (LAMMPS' transfer factor +1)
        flags: Flags { contact_radius: true, keep: (1 << mdr::HISTORY) - 1, ..Flags::NONE },
        build: |c, _| Normal::Mdr(Mdr::new(c)),
        mix: geometric,
    },
];

/// Every normal model's damping coefficient, by its place among the coefficients.
pub fn damp_coeff(name: &str) -> usize {
    if name == "mdr" { 5 } else { DAMP_COEFF }
}

/// LAMMPS' constants of the JKR closed forms.
const PI27SQ: f64 = 266.47931882941264802866; // 27 pi^2
const THREEROOT3: f64 = 5.19615242270663202362; // 3 sqrt(3)
const SIXROOT6: f64 = 14.69693845669906728801; // 6 sqrt(6)
const INVROOT6: f64 = 0.40824829046386307274; // 1/sqrt(6)
const JKRPREFIX: f64 = 1.2277228507842888; // (3 pi^2/16)^(1/3)

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

/// Kn = 4/3 E_eff of `E eta nu ...`.
fn material_k(c: &[f64], ctx: &Ctx) -> f64 {
    FOURTHIRDS * material_e(c, ctx)
}

/// E_eff of `E eta nu ...` (a wall uses its own rule, as LAMMPS' contact_type WALL); mixed
/// coefficients already hold E_eff.
fn material_e(c: &[f64], ctx: &Ctx) -> f64 {
    let (e, nu) = (c[0], c[2]);
    if ctx.mixed {
        e
    } else if ctx.wall {
        mix_stiffness_e_wall(e, nu)
    } else {
        mix_stiffness_e(e, e, nu, nu)
    }
}

/// E becomes E_eff of the two materials (LAMMPS keeps it in the first coefficient).
fn mix_material(a: &[f64], b: &[f64]) -> Coeffs {
    let mut m = geometric(a, b);
    m[0] = mix_stiffness_e(a[0], b[0], a[2], b[2]);
    m
}

impl Normal {
    /// The contact radius a from dR = delta R_eff (LAMMPS calculate_contact_radius).
    #[inline(always)]
    pub fn contact_radius(&self, dr: f64, reff: f64) -> f64 {
        match *self {
            Normal::Jkr { emix, cohesion, .. } => {
                let r2 = reff * reff;
                let dr2 = dr * dr;
                let t0 = cohesion * cohesion * r2 * r2 * emix;
                let t1 = PI27SQ * t0;
                let t2 = 8.0 * dr * dr2 * emix * emix * emix;
                let t3 = 4.0 * dr2 * emix;
                // the roots' arguments clamped at 0 against round-off, as LAMMPS
                let sqrt1 = f64::max(0.0, t0 * (t1 + 2.0 * t2));
                let t4 = cbrt(t1 + t2 + THREEROOT3 * PI * sqrt1.sqrt());
                let t5 = t3 / t4 + t4 / emix;
                let sqrt2 = f64::max(0.0, 2.0 * dr + t5);
                let t6 = sqrt2.sqrt();
                let sqrt3 = f64::max(0.0, 4.0 * dr - t5 + SIXROOT6 * cohesion * PI * r2 / (emix * t6));
                INVROOT6 * (t6 + sqrt3.sqrt())
            }
            _ => dr.sqrt(),
        }
    }

    /// Whether a pair is in contact: overlapping, or for JKR a contact that was, up to the
    /// pull-off distance (LAMMPS `touch`).
    #[inline(always)]
    pub fn touch(&self, rsq: f64, radi: f64, radj: f64, was: bool) -> bool {
        let radsum = radi + radj;
        self.touch_with(rsq, radsum, radi * radj / radsum, was)
    }

    /// [`Normal::touch`] with the contact's R_i + R_j (a wall: R_i) and R_eff given.
    #[inline(always)]
    pub fn touch_with(&self, rsq: f64, radsum: f64, reff: f64, was: bool) -> bool {
        match *self {
            Normal::Jkr { emix, cohesion, .. } if was => {
                let dist_pulloff = radsum + jkr_pulloff(reff, cohesion, emix);
                rsq < dist_pulloff * dist_pulloff
            }
            _ => rsq < radsum * radsum,
        }
    }

    /// How far beyond touching a contact holds (LAMMPS pulloff_distance): 0 but for JKR.
    pub fn pulloff_distance(&self, radi: f64, radj: f64) -> f64 {
        match *self {
            Normal::Jkr { emix, cohesion, .. } => {
                let reff = radi * radj / (radi + radj);
                if reff <= 0.0 { 0.0 } else { jkr_pulloff(reff, cohesion, emix) }
            }
            _ => 0.0,
        }
    }

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
            Normal::Jkr { k, emix, cohesion } => {
                let a2 = a * a;
                k * a * a2 / reff - 2.0 * PI * a2 * (4.0 * cohesion * emix / (PI * a)).sqrt()
            }
            // the mdr contact loop gives its force to the contact (granular_contact_with)
            Normal::None | Normal::Mdr(_) => 0.0,
        }
    }

    /// F_n,crit, the normal force that limits the friction (LAMMPS `set_fncrit`).
    #[inline(always)]
    pub fn fncrit(&self, fntot: f64, fnormal: f64, reff: f64) -> f64 {
        match *self {
            Normal::Dmt { cohesion, .. } => (fnormal + 2.0 * pulloff(cohesion, reff)).abs(),
            Normal::Jkr { cohesion, .. } => (fnormal + 2.0 * (3.0 * PI * cohesion * reff)).abs(),
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

/// The JKR pull-off distance (beyond touching).
#[inline(always)]
fn jkr_pulloff(reff: f64, cohesion: f64, emix: f64) -> f64 {
    JKRPREFIX * cbrt(reff * cohesion * cohesion / (emix * emix))
}

/// DMT pull-off force 4 pi gamma R_eff.
#[inline(always)]
fn pulloff(cohesion: f64, reff: f64) -> f64 {
    4.0 * PI * cohesion * reff
}
