//! `bond_style bpm/rotational` (LAMMPS BPM package, src/BPM/bond_bpm_rotational.cpp): the bond
//! of breakable bonded solids between two bpm/sphere atoms, with normal, shear, bending and
//! twisting springs and dampers (Wang 2009, Wang & Mora 2009; damping from Wang,
//! Alonso-Marroquin & Guo 2015). The keywords, checks and breaking all BPM styles share are
//! `crate::models::bonded::bpm`'s.
//!
//! Each bond stores, at the first evaluation, r0 = |x1 - x2| and the unit vector of x1 - x2
//! (atom 1 the lower ID). The bond vector is taken into atom 2's frame (rotated by its
//! inverse orientation) and compared with the reference: the normal force Kr (r - r0), a shear
//! force and torque from the angle between them (Ks); the relative orientation of the two atoms,
//! seen in a frame whose z axis is the bond, gives a twist angle psi (torque Kt psi) and a bend
//! angle theta (torque Kb theta, with more shear). `normalize yes` divides Kr and Ks by r0.
//! The bond breaks when
//!
//!   B = max(0, Fr/Fcr + |Fs|/Fcs + |Tb|/Tcb + |Tt|/Tct) >= 1
//!
//! (never with `break no`, which needs `smooth no`). Dampers on the relative normal and sliding velocities (gnorm,
//! gslide) and on rolling and twisting spins (groll, gtwist) are added, and everything is scaled
//! by 1 - B^4 with `smooth yes` (the default). LAMMPS tallies no energy for this style (0) and
//! the virial of the force on atom 2 (`ev_tally_xyz`).

use super::bpm::{Bpm, BondOut, BpmAtoms, BpmStyle};
use super::{fmt_g, BondStyle, SingleBond, TypeTable, Vec3};
use crate::engine::quat::{cross3, norm3, qconjugate, quatquat, quatrotvec, Quat};
use crate::engine::state::State;
use crate::engine::topology::BOND_HISTORY;
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N Kr Ks Kt Kb Fcr Fcs Tct Tcb gnorm gslide groll gtwist";
pub const SETTINGS_SYNTAX: &str =
    "bond_style bpm/rotational [store/local fixID N id1|id2|time|x|y|z|x/ref|y/ref|z/ref ...] [overlay/pair yes/no] [break yes/no] [smooth yes/no] [normalize yes/no]";
/// LAMMPS `MathConst::MY_SQRT2`.
const MY_SQRT2: f64 = std::f64::consts::SQRT_2;

#[derive(Clone, Copy, Debug, PartialEq)]
struct Params {
    kr: f64,
    ks: f64,
    kt: f64,
    kb: f64,
    fcr: f64,
    fcs: f64,
    tct: f64,
    tcb: f64,
    gnorm: f64,
    gslide: f64,
    groll: f64,
    gtwist: f64,
}

#[derive(Debug, Default)]
pub struct BondBpmRotational {
    types: TypeTable<Params>,
    pub bpm: Bpm,
}

/// `acos` of a cosine clamped to [-1, 1].
fn acos_limit(c: f64) -> f64 {
    c.clamp(-1.0, 1.0).acos()
}

/// A negative value becomes 0 (a NaN stays, as LAMMPS' `if (x < 0.0) x = 0.0`).
fn clamp_negative(x: f64) -> f64 {
    if x < 0.0 { 0.0 } else { x }
}

fn dot3(a: &Vec3, b: &Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn len3(a: &Vec3) -> f64 {
    dot3(a, a).sqrt()
}
fn scale3(s: f64, a: &Vec3) -> Vec3 {
    [s * a[0], s * a[1], s * a[2]]
}
fn add3(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub3(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The springs of one bond: the force on atom 2 from atom 1, the torques on 2 and on 1, and
/// the breaking criterion B.
struct Elastic {
    f12: Vec3,
    t12: Vec3,
    t21: Vec3,
    breaking: f64,
}

impl BondBpmRotational {
    /// LAMMPS' elastic_forces: `r = x1 - x2` (length `r_mag`), `r0` the reference vector.
    #[allow(clippy::too_many_arguments)]
    fn elastic(&self, p: &Params, q1: &Quat, q2: &Quat, r_mag: f64, r0_mag: f64, r_mag_inv: f64, r: &Vec3, r0: &Vec3) -> Elastic {
        let r0_mag_inv = 1.0 / r0_mag;
        let (mut kr, mut ks) = (p.kr, p.ks);
        if self.bpm.normalize {
            kr *= r0_mag_inv;
            ks *= r0_mag_inv;
        }
        // normal force, with rb the bond vector in atom 2's frame
        let q2inv = qconjugate(q2);
        let rb = quatrotvec(&q2inv, r);
        let fr = kr * (r_mag - r0_mag);
        let mut f_rot = scale3(fr * r_mag_inv, &rb);

        // shear force and torque from the tangential displacement (no rotation)
        let c = dot3(r0, &rb) * r_mag_inv * r0_mag_inv;
        let gamma = acos_limit(c);
        let mut s = cross3(&rb, &cross3(&rb, r0));
        norm3(&mut s);
        let mut fs = scale3(ks * r_mag * gamma, &s);
        let mut t = cross3(r0, &rb);
        norm3(&mut t);
        let mut ts = scale3(0.5 * r_mag * ks * r_mag * gamma, &t);

        // mq turns the z axis onto rb (Wang & Mora's X'Y'Z' representation of rotations)
        let mut mq = [0.0; 4];
        let temp = clamp_negative(r_mag + rb[2]);
        mq[0] = MY_SQRT2 * 0.5 * (temp * r_mag_inv).sqrt();
        let temp = (rb[0] * rb[0] + rb[1] * rb[1]).sqrt();
        if temp != 0.0 {
            mq[1] = -MY_SQRT2 * 0.5 / temp;
            let temp = clamp_negative(r_mag - rb[2]);
            mq[1] *= (temp * r_mag_inv).sqrt();
            mq[2] = -mq[1];
            mq[1] *= rb[1];
            mq[2] *= rb[0];
        }
        // the relative rotation of the atoms in that frame
        let qp21 = quatquat(&q2inv, q1);
        let q21 = quatquat(&quatquat(&qconjugate(&mq), &qp21), &mq);

        // twist angle about the bond
        let temp = (q21[0] * q21[0] + q21[3] * q21[3]).sqrt();
        let mut psi = if temp != 0.0 { 2.0 * acos_limit(q21[0] / temp) } else { 0.0 };
        if q21[3] < 0.0 {
            psi = -psi;
        }
        if q21[3] == 0.0 {
            psi = 0.0;
        }
        // bend angle and its direction in the plane normal to the bond
        let c = q21[0] * q21[0] - q21[1] * q21[1] - q21[2] * q21[2] + q21[3] * q21[3];
        let theta = acos_limit(c);
        let mag_out_plane = q21[0] * q21[0] + q21[3] * q21[3];
        let mag_in_plane = q21[1] * q21[1] + q21[2] * q21[2];
        let (cos_phi, sin_phi) = if mag_in_plane == 0.0 {
            (0.0, 0.0)
        } else if mag_out_plane == 0.0 {
            (q21[2] / mag_in_plane.sqrt(), -q21[1] / mag_in_plane.sqrt())
        } else {
            let norm = (mag_out_plane * mag_in_plane).sqrt();
            ((q21[1] * q21[3] + q21[0] * q21[2]) / norm, (q21[2] * q21[3] - q21[0] * q21[1]) / norm)
        };

        let tbp = [-p.kb * theta * sin_phi, p.kb * theta * cos_phi, 0.0];
        let ttp = [0.0, 0.0, p.kt * psi];
        let fsp = [-0.5 * ks * r_mag * theta * cos_phi, -0.5 * ks * r_mag * theta * sin_phi, 0.0];
        let tsp = [0.25 * ks * r_mag * r_mag * theta * sin_phi, -0.25 * ks * r_mag * r_mag * theta * cos_phi, 0.0];

        // back from the bond frame, then from atom 2's frame
        fs = add3(&fs, &quatrotvec(&mq, &fsp));
        ts = add3(&ts, &quatrotvec(&mq, &tsp));
        let tb = quatrotvec(&mq, &tbp);
        let tt = quatrotvec(&mq, &ttp);
        f_rot = add3(&f_rot, &fs);
        let f12 = quatrotvec(q2, &f_rot);
        let t12 = quatrotvec(q2, &add3(&add3(&ts, &tt), &tb));
        let t21 = quatrotvec(q2, &sub3(&sub3(&ts, &tt), &tb));

        let breaking = fr / p.fcr + len3(&fs) / p.fcs + len3(&tb) / p.tcb + len3(&tt) / p.tct;
        Elastic { f12, t12, t21, breaking: clamp_negative(breaking) }
    }

    /// LAMMPS' damping_forces, added to `e`: relative normal and sliding velocities, rolling and
    /// twisting spins.
    #[allow(clippy::too_many_arguments)]
    fn damping(p: &Params, e: &mut Elastic, rhat: &Vec3, r: &Vec3, v1: &Vec3, v2: &Vec3, w1: &Vec3, w2: &Vec3) {
        let vn1 = scale3(dot3(v1, rhat), rhat);
        let vn2 = scale3(dot3(v2, rhat), rhat);
        let tmp = scale3(p.gnorm, &sub3(&vn1, &vn2));
        e.f12 = add3(&e.f12, &tmp);

        let vt1 = sub3(v1, &vn1);
        let vt2 = sub3(v2, &vn2);
        let tmp = scale3(0.5, &sub3(&vt2, &vt1));
        let s1 = sub3(&scale3(-0.5, &cross3(w1, r)), &tmp);
        let s2 = add3(&scale3(0.5, &cross3(w2, r)), &tmp);
        let tmp = scale3(p.gslide, &sub3(&s1, &s2));
        e.f12 = add3(&e.f12, &tmp);
        let tdamp = scale3(0.5, &cross3(r, &tmp));
        e.t12 = add3(&e.t12, &tdamp);
        e.t21 = add3(&e.t21, &tdamp);

        let vroll = sub3(&cross3(w1, rhat), &cross3(w2, rhat));
        let tdamp = scale3(0.5 * p.groll, &cross3(r, &vroll));
        e.t12 = add3(&e.t12, &tdamp);
        e.t21 = add3(&e.t21, &scale3(-1.0, &tdamp));

        let wn1 = scale3(dot3(w1, rhat), rhat);
        let wn2 = scale3(dot3(w2, rhat), rhat);
        let tdamp = scale3(0.5 * p.gtwist, &sub3(&wn1, &wn2));
        e.t12 = add3(&e.t12, &tdamp);
        e.t21 = add3(&e.t21, &scale3(-1.0, &tdamp));
    }

    /// The factor 1 - B^4 of `smooth yes`.
    fn smoothing(&self, breaking: f64) -> f64 {
        if self.bpm.smooth {
            let s = breaking * breaking;
            1.0 - s * s
        } else {
            1.0
        }
    }

    /// LAMMPS' BondBPM::init_style and BondBPMRotational::init_style checks.
    fn check(&self, state: &State, many_body: bool) -> Result<(), String> {
        self.bpm.check(state, many_body)?;
        let f = &state.atoms.features;
        if !f.quat || !f.sphere {
            return Err("Bond bpm/rotational requires atom style bpm/sphere".into());
        }
        if !state.comm_vel {
            return Err("Bond bpm/rotational requires ghost atoms store velocity (comm_modify vel yes)".into());
        }
        Ok(())
    }
}

impl BpmStyle for BondBpmRotational {
    const TORQUES: bool = true;
    fn bpm(&self) -> &Bpm {
        &self.bpm
    }
    /// LAMMPS' store_data / store_bond: r0 and the unit vector of `del`.
    fn reference(&self, del: Vec3) -> [f64; BOND_HISTORY] {
        let r = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
        let rinv = 1.0 / r;
        [r, del[0] * rinv, del[1] * rinv, del[2] * rinv]
    }
    fn bond(&self, btype: usize, hist: &[f64; BOND_HISTORY], i1: usize, i2: usize, r: Vec3, atoms: &BpmAtoms) -> Option<BondOut> {
        let p = self.types.get(btype);
        let r0_mag = hist[0];
        let r0 = [hist[1] * r0_mag, hist[2] * r0_mag, hist[3] * r0_mag];
        let r_mag = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let r_mag_inv = 1.0 / r_mag;
        let rhat = scale3(r_mag_inv, &r);
        let mut e = self.elastic(p, &atoms.quat[i1], &atoms.quat[i2], r_mag, r0_mag, r_mag_inv, &r, &r0);
        if e.breaking >= 1.0 && self.bpm.break_bonds {
            return None;
        }
        Self::damping(p, &mut e, &rhat, &r, &atoms.v[i1], &atoms.v[i2], &atoms.omega[i1], &atoms.omega[i2]);
        let smooth = self.smoothing(e.breaking);
        // atom 1 gets minus the force on atom 2; the virial is that of the force on atom 1
        let f1 = e.f12.map(|c| -(c * smooth));
        let virial = [r[0] * f1[0], r[1] * f1[1], r[2] * f1[2], r[0] * f1[1], r[0] * f1[2], r[1] * f1[2]];
        Some(BondOut { f1, t1: e.t21.map(|c| c * smooth), t2: e.t12.map(|c| c * smooth), energy: 0.0, virial, history: None })
    }
}

impl BondStyle for BondBpmRotational {
    crate::bpm_bond_style_common!();
    fn name(&self) -> &'static str {
        "bpm/rotational"
    }
    fn settings(&mut self, a: &mut Args) -> DResult<()> {
        a.syntax = SETTINGS_SYNTAX;
        self.bpm.settings(a, &[], |_, _| Ok(false))
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = SYNTAX;
        let mut v = [0.0; 12];
        for (x, name) in v.iter_mut().zip(["Kr", "Ks", "Kt", "Kb", "Fcr", "Fcs", "Tct", "Tcb", "gnorm", "gslide", "groll", "gtwist"]) {
            *x = args.f64(name)?;
        }
        args.finish()?;
        let [kr, ks, kt, kb, fcr, fcs, tct, tcb, gnorm, gslide, groll, gtwist] = v;
        self.types.set(lo, hi, Params { kr, ks, kt, kb, fcr, fcs, tct, tcb, gnorm, gslide, groll, gtwist });
        Ok(())
    }
    /// LAMMPS' single: the bond taken from its lower-ID atom with its stored reference, never
    /// breaking: the bond's force (springs and dampers) along the bond, smoothed, and energy 0.
    fn single(&self, b: &SingleBond) -> Result<(f64, f64), String> {
        let (s, a) = (b.state, &b.state.atoms);
        let (i, j, r) = if a.tag[b.j] < a.tag[b.i] { (b.j, b.i, b.del.map(|c| -c)) } else { (b.i, b.j, b.del) };
        let p = self.types.get(b.typ);
        let hist = s.topo.bonds[b.rec].history;
        let r0_mag = hist[0];
        let r0 = [hist[1] * r0_mag, hist[2] * r0_mag, hist[3] * r0_mag];
        let r_mag = b.rsq.sqrt();
        let r_mag_inv = 1.0 / r_mag;
        let rhat = scale3(r_mag_inv, &r);
        let mut e = self.elastic(p, &a.quat[i], &a.quat[j], r_mag, r0_mag, r_mag_inv, &r, &r0);
        Self::damping(p, &mut e, &rhat, &r, &a.v[i], &a.v[j], &a.omega[i], &a.omega[j]);
        // LAMMPS projects the force on atom 2 onto x2 - x1
        let fforce = -dot3(&e.f12, &rhat);
        Ok((fforce * self.smoothing(e.breaking), 0.0))
    }
    fn stiffness(&self, btype: usize) -> f64 {
        self.types.try_get(btype).map(|p| 0.5 * p.kr).unwrap_or(0.0)
    }
    fn coeff_words(&self, btype: usize) -> String {
        let p = self.types.get(btype);
        [p.kr, p.ks, p.kt, p.kb, p.fcr, p.fcs, p.tct, p.tcb, p.gnorm, p.gslide, p.groll, p.gtwist].map(fmt_g).join(" ")
    }
}
