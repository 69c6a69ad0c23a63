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

use super::bpm::{BondIn, Bpm, BondOut, BpmAtoms, BpmStyle};
use super::{fmt_g, BondStyle, SingleBond, TypeTable, Vec3};
use crate::engine::par::lanes::{lanes, transpose4, Real, L, LANES};
use crate::engine::quat::{cross3, norm3, qconjugate, quatquat, quatrotvec};
use crate::engine::state::State;
use crate::engine::topology::BOND_HISTORY;
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N Kr Ks Kt Kb Fcr Fcs Tct Tcb gnorm gslide groll gtwist";
pub const SETTINGS_SYNTAX: &str =
    "bond_style bpm/rotational [store/local fixID N id1|id2|time|x|y|z|x/ref|y/ref|z/ref ...] [overlay/pair yes/no] [break yes/no] [smooth yes/no] [normalize yes/no]";
/// LAMMPS `MathConst::MY_SQRT2`.
const MY_SQRT2: f64 = std::f64::consts::SQRT_2;

#[derive(Clone, Copy, Debug, PartialEq)]
struct Params<T = f64> {
    kr: T,
    ks: T,
    kt: T,
    kb: T,
    fcr: T,
    fcs: T,
    tct: T,
    tcb: T,
    gnorm: T,
    gslide: T,
    groll: T,
    gtwist: T,
}

impl Params {
    /// The coefficients of a batch of bonds, lane by lane.
    fn lanes(p: [&Params; LANES]) -> Params<L> {
        let g = |f: fn(&Params) -> f64| lanes(|l| f(p[l]));
        Params {
            kr: g(|p| p.kr),
            ks: g(|p| p.ks),
            kt: g(|p| p.kt),
            kb: g(|p| p.kb),
            fcr: g(|p| p.fcr),
            fcs: g(|p| p.fcs),
            tct: g(|p| p.tct),
            tcb: g(|p| p.tcb),
            gnorm: g(|p| p.gnorm),
            gslide: g(|p| p.gslide),
            groll: g(|p| p.groll),
            gtwist: g(|p| p.gtwist),
        }
    }
}

#[derive(Debug, Default)]
pub struct BondBpmRotational {
    types: TypeTable<Params>,
    pub bpm: Bpm,
}

/// `acos` of a cosine clamped to [-1, 1] (the C library's, lane by lane).
#[inline(always)]
fn acos_limit<T: Real>(c: T) -> T {
    c.map(|c| c.clamp(-1.0, 1.0).acos())
}

/// A negative value becomes 0 (a NaN stays, as LAMMPS' `if (x < 0.0) x = 0.0`).
#[inline(always)]
fn clamp_negative<T: Real>(x: T) -> T {
    T::select(x.lt(T::splat(0.0)), T::splat(0.0), x)
}

#[inline(always)]
fn dot3<T: Real>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline(always)]
fn len3<T: Real>(a: &[T; 3]) -> T {
    dot3(a, a).sqrt()
}
#[inline(always)]
fn scale3<T: Real>(s: T, a: &[T; 3]) -> [T; 3] {
    [s * a[0], s * a[1], s * a[2]]
}
#[inline(always)]
fn add3<T: Real>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
#[inline(always)]
fn sub3<T: Real>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The springs of one bond (or a batch): the force on atom 2 from atom 1, the torques on 2 and
/// on 1, and the breaking criterion B.
struct Elastic<T = f64> {
    f12: [T; 3],
    t12: [T; 3],
    t21: [T; 3],
    breaking: T,
}

impl BondBpmRotational {
    /// LAMMPS' elastic_forces: `r = x1 - x2` (length `r_mag`), `r0` the reference vector.
    /// Written once for a bond and a batch: every branch of LAMMPS' code is a select.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn elastic<T: Real>(&self, p: &Params<T>, q1: &[T; 4], q2: &[T; 4], r_mag: T, r0_mag: T, r_mag_inv: T, r: &[T; 3], r0: &[T; 3]) -> Elastic<T> {
        let (zero, one) = (T::splat(0.0), T::splat(1.0));
        let r0_mag_inv = one / r0_mag;
        let (mut kr, mut ks) = (p.kr, p.ks);
        if self.bpm.normalize {
            kr = kr * r0_mag_inv;
            ks = ks * r0_mag_inv;
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
        let mut ts = scale3(T::splat(0.5) * r_mag * ks * r_mag * gamma, &t);

        // mq turns the z axis onto rb (Wang & Mora's X'Y'Z' representation of rotations); its
        // x and y parts stay 0 where rb lies on the z axis
        let half_sqrt2 = T::splat(MY_SQRT2 * 0.5);
        let temp = clamp_negative(r_mag + rb[2]);
        let mq0 = half_sqrt2 * (temp * r_mag_inv).sqrt();
        let temp = (rb[0] * rb[0] + rb[1] * rb[1]).sqrt();
        let off_axis = temp.ne(zero);
        let mut mq1 = -half_sqrt2 / temp;
        let temp2 = clamp_negative(r_mag - rb[2]);
        mq1 = mq1 * (temp2 * r_mag_inv).sqrt();
        let mq2 = -mq1;
        let mq = [mq0, T::select(off_axis, mq1 * rb[1], zero), T::select(off_axis, mq2 * rb[0], zero), zero];
        // the relative rotation of the atoms in that frame
        let qp21 = quatquat(&q2inv, q1);
        let q21 = quatquat(&quatquat(&qconjugate(&mq), &qp21), &mq);

        // twist angle about the bond (0 where q21 has no w-k part or no k part)
        let temp = (q21[0] * q21[0] + q21[3] * q21[3]).sqrt();
        let mut psi = T::select(temp.ne(zero), T::splat(2.0) * acos_limit(q21[0] / temp), zero);
        psi = T::select(q21[3].lt(zero), -psi, psi);
        psi = T::select(q21[3].ne(zero), psi, zero);
        // bend angle and its direction in the plane normal to the bond
        let c = q21[0] * q21[0] - q21[1] * q21[1] - q21[2] * q21[2] + q21[3] * q21[3];
        let theta = acos_limit(c);
        let mag_out_plane = q21[0] * q21[0] + q21[3] * q21[3];
        let mag_in_plane = q21[1] * q21[1] + q21[2] * q21[2];
        let in_root = mag_in_plane.sqrt();
        let norm = (mag_out_plane * mag_in_plane).sqrt();
        let general = ((q21[1] * q21[3] + q21[0] * q21[2]) / norm, (q21[2] * q21[3] - q21[0] * q21[1]) / norm);
        let (in_plane, out_of_plane) = (mag_in_plane.ne(zero), mag_out_plane.ne(zero));
        let cos_phi = T::select(in_plane, T::select(out_of_plane, general.0, q21[2] / in_root), zero);
        let sin_phi = T::select(in_plane, T::select(out_of_plane, general.1, -q21[1] / in_root), zero);

        let tbp = [-p.kb * theta * sin_phi, p.kb * theta * cos_phi, zero];
        let ttp = [zero, zero, p.kt * psi];
        let fsp = [T::splat(-0.5) * ks * r_mag * theta * cos_phi, T::splat(-0.5) * ks * r_mag * theta * sin_phi, zero];
        let tsp = [T::splat(0.25) * ks * r_mag * r_mag * theta * sin_phi, T::splat(-0.25) * ks * r_mag * r_mag * theta * cos_phi, zero];

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
    #[inline(always)]
    fn damping<T: Real>(p: &Params<T>, e: &mut Elastic<T>, rhat: &[T; 3], r: &[T; 3], v1: &[T; 3], v2: &[T; 3], w1: &[T; 3], w2: &[T; 3]) {
        let (half, minus_one) = (T::splat(0.5), T::splat(-1.0));
        let vn1 = scale3(dot3(v1, rhat), rhat);
        let vn2 = scale3(dot3(v2, rhat), rhat);
        let tmp = scale3(p.gnorm, &sub3(&vn1, &vn2));
        e.f12 = add3(&e.f12, &tmp);

        let vt1 = sub3(v1, &vn1);
        let vt2 = sub3(v2, &vn2);
        let tmp = scale3(half, &sub3(&vt2, &vt1));
        let s1 = sub3(&scale3(T::splat(-0.5), &cross3(w1, r)), &tmp);
        let s2 = add3(&scale3(half, &cross3(w2, r)), &tmp);
        let tmp = scale3(p.gslide, &sub3(&s1, &s2));
        e.f12 = add3(&e.f12, &tmp);
        let tdamp = scale3(half, &cross3(r, &tmp));
        e.t12 = add3(&e.t12, &tdamp);
        e.t21 = add3(&e.t21, &tdamp);

        let vroll = sub3(&cross3(w1, rhat), &cross3(w2, rhat));
        let tdamp = scale3(half * p.groll, &cross3(r, &vroll));
        e.t12 = add3(&e.t12, &tdamp);
        e.t21 = add3(&e.t21, &scale3(minus_one, &tdamp));

        let wn1 = scale3(dot3(w1, rhat), rhat);
        let wn2 = scale3(dot3(w2, rhat), rhat);
        let tdamp = scale3(half * p.gtwist, &sub3(&wn1, &wn2));
        e.t12 = add3(&e.t12, &tdamp);
        e.t21 = add3(&e.t21, &scale3(minus_one, &tdamp));
    }

    /// The factor 1 - B^4 of `smooth yes`.
    #[inline(always)]
    fn smoothing<T: Real>(&self, breaking: T) -> T {
        if self.bpm.smooth {
            let s = breaking * breaking;
            T::splat(1.0) - s * s
        } else {
            T::splat(1.0)
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
    const LANE_KERNEL: bool = true;
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
    /// The same arithmetic as [`BpmStyle::bond`], [`LANES`] bonds at once (a short batch repeats
    /// its last bond in the spare lanes).
    #[inline(always)]
    fn bonds(&self, b: &[BondIn; LANES], n: usize, atoms: &BpmAtoms, mut emit: impl FnMut(usize, Option<BondOut>)) {
        let lane = |l: usize| &b[l.min(n - 1)];
        let p = Params::lanes(std::array::from_fn(|l| self.types.get(lane(l).typ)));
        let hist = transpose4(std::array::from_fn(|l| &lane(l).hist));
        let r0_mag = hist[0];
        let r0 = [hist[1] * r0_mag, hist[2] * r0_mag, hist[3] * r0_mag];
        let vec = |f: &dyn Fn(usize) -> Vec3| -> [L; 3] { std::array::from_fn(|c| lanes(|l| f(l)[c])) };
        let r = vec(&|l| lane(l).del);
        let r_mag = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let r_mag_inv = L::splat(1.0) / r_mag;
        let rhat = scale3(r_mag_inv, &r);
        let q1 = transpose4(std::array::from_fn(|l| &atoms.quat[lane(l).i1]));
        let q2 = transpose4(std::array::from_fn(|l| &atoms.quat[lane(l).i2]));
        let mut e = self.elastic(&p, &q1, &q2, r_mag, r0_mag, r_mag_inv, &r, &r0);
        let (v1, v2) = (vec(&|l| atoms.v[lane(l).i1]), vec(&|l| atoms.v[lane(l).i2]));
        let (w1, w2) = (vec(&|l| atoms.omega[lane(l).i1]), vec(&|l| atoms.omega[lane(l).i2]));
        Self::damping(&p, &mut e, &rhat, &r, &v1, &v2, &w1, &w2);
        let smooth = self.smoothing(e.breaking);
        let f1 = e.f12.map(|c| -(c * smooth));
        let (t1, t2) = (e.t21.map(|c| c * smooth), e.t12.map(|c| c * smooth));
        let at = |v: &[L; 3], l: usize| [v[0][l], v[1][l], v[2][l]];
        for l in 0..n {
            if e.breaking[l] >= 1.0 && self.bpm.break_bonds {
                emit(l, None);
                continue;
            }
            let (r, f1) = (at(&r, l), at(&f1, l));
            let virial = [r[0] * f1[0], r[1] * f1[1], r[2] * f1[2], r[0] * f1[1], r[0] * f1[2], r[1] * f1[2]];
            emit(l, Some(BondOut { f1, t1: at(&t1, l), t2: at(&t2, l), energy: 0.0, virial, history: None }));
        }
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
