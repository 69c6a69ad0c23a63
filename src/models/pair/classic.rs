//! The spring-dashpot contact of LAMMPS' classic granular styles (`gran/hooke`,
//! `gran/hooke/history`, `gran/hertz/history`; also the solid part of `dmhs/blend`), written
//! once for one pair (`f64`) and for a batch of pairs ([`L`]): the same operations per lane, so
//! the same bits.
//!
//! * F_n = (Kn delta - m_eff gamma_n v_n) n (clamped at 0 with `limit_damping`);
//! * Hertz (`gran/hertz/history`): F_n and F_t are scaled by sqrt(delta R_i R_j/(R_i + R_j));
//!   Kn and Kt are in pressure units, which need no conversion (LAMMPS' nktv2p is 1 in every
//!   unit style dmhs has);
//! * with history: shear s += v_tr dt, |s| taken before it is projected onto the tangent plane
//!   (no rescale); F_t = -(Kt s + m_eff gamma_t v_tr), limited to xmu |F_n| with s set back;
//! * without history: F_t = -min(xmu |F_n|, m_eff gamma_t |v_tr|) v_tr/|v_tr|;
//! * torques -R (n x F_t) on both spheres with the full radii.
//!
//! The arithmetic follows LAMMPS' pair_gran_hooke(_history).cpp term by term (the `granular`
//! style's hooke model normalises n first, so it is a different sum of the same physics).

use super::contact::{Contact, ContactForce};
use crate::engine::par::lanes::Real;
use dmhs_parser::{Args, Command, DResult, Word};

/// The global settings shared by gran/hooke and gran/hooke/history.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Classic {
    pub kn: f64,
    pub kt: f64,
    pub gamman: f64,
    pub gammat: f64,
    pub xmu: f64,
    pub dampflag: bool,
    pub limit_damping: bool,
    /// Hertzian scaling of both forces by the contact radius (gran/hertz/history).
    pub hertz: bool,
}

impl Classic {
    /// Parse the settings as LAMMPS does (NULL defaults, dampflag 0|1, limit_damping).
    pub fn from_lammps(args: &[Word], cmd: &Command, syntax: &'static str, hertz: bool) -> DResult<Classic> {
        let mut c = Self::from_lammps_words(args, cmd, syntax)?;
        c.hertz = hertz;
        Ok(c)
    }

    /// The six numbers `Kn Kt gamma_n gamma_t xmu dampflag` and an optional `limit_damping`
    /// (all of `args`), as LAMMPS parses them for the pair styles and the classic wall forms.
    pub fn from_lammps_words(args: &[Word], cmd: &Command, syntax: &str) -> DResult<Classic> {
        let mut a = Args::from_words(args, cmd.span, syntax);
        let kn = a.non_negative_f64("Kn")?;
        let kt = if a.peek().map(|w| w.text == "NULL").unwrap_or(false) {
            a.skip(1);
            kn * 2.0 / 7.0
        } else {
            a.non_negative_f64("Kt")?
        };
        let gamman = a.non_negative_f64("gamma_n")?;
        let mut gammat = if a.peek().map(|w| w.text == "NULL").unwrap_or(false) {
            a.skip(1);
            0.5 * gamman
        } else {
            a.non_negative_f64("gamma_t")?
        };
        let xmu = a.f64_where("xmu", "0 <= xmu <= 10000", |x| (0.0..=10000.0).contains(&x))?;
        let dampflag = a.i64_in("dampflag", 0, 1)? == 1;
        if !dampflag {
            gammat = 0.0;
        }
        let mut limit_damping = false;
        if let Some(w) = a.peek() {
            if w.text != "limit_damping" {
                return Err(a.unknown_keyword(w, &["limit_damping"]));
            }
            a.skip(1);
            limit_damping = true;
        }
        a.finish()?;
        Ok(Classic { kn, kt, gamman, gammat, xmu, dampflag, limit_damping, hertz: false })
    }

    pub fn describe(&self, style: &str) -> String {
        format!(
            "{style} Kn {} Kt {} gamma_n {} gamma_t {} xmu {} dampflag {}{}",
            self.kn,
            self.kt,
            self.gamman,
            self.gammat,
            self.xmu,
            self.dampflag as i32,
            if self.limit_damping { " limit_damping" } else { "" }
        )
    }

    /// The contact with shear history `shear` (updated when `update`; LAMMPS' `shearupdate`).
    #[inline(always)]
    pub fn with_history<T: Real>(&self, c: &Contact<T>, shear: &mut [T; 3], update: bool, dt: f64) -> ContactForce<T> {
        let (k, fs, _) = self.history_parts(c, shear, update, dt);
        force(c, k.ccel, k.rinv, fs)
    }

    /// LAMMPS' single of gran/hooke/history and gran/hertz/history (compute pair/local): the
    /// contact with the stored shear, not advanced. fpair is the normal force over r (ccel);
    /// the extra values are F_t (3), |F_t| as the friction limit left it, v_n (3) and v_t (3).
    pub fn single(&self, c: &Contact, shear: [f64; 3]) -> (f64, [f64; 10]) {
        let mut shear = shear;
        let (k, fs, fsmag) = self.history_parts(c, &mut shear, false, 0.0);
        let vn = [0, 1, 2].map(|d| c.del[d] * k.vnnr * k.rsqinv);
        let vt = [0, 1, 2].map(|d| (c.vi[d] - c.vj[d]) - vn[d]);
        (k.ccel, [fs[0], fs[1], fs[2], fsmag, vn[0], vn[1], vn[2], vt[0], vt[1], vt[2]])
    }

    /// The normal part, the tangential force and its magnitude after the friction limit.
    #[inline(always)]
    fn history_parts<T: Real>(&self, c: &Contact<T>, shear: &mut [T; 3], update: bool, dt: f64) -> (Normal<T>, [T; 3], T) {
        let k = Normal::of(self, c);
        let s = T::splat;
        let [delx, dely, delz] = c.del;
        let vtr = k.vtr;
        if update {
            for d in 0..3 {
                shear[d] += vtr[d] * s(dt);
            }
        }
        // its magnitude is taken before the rotation, and needed only where a contact slides
        let unrotated = *shear;
        // rotate the shear displacement into the tangent plane
        let rsht = (shear[0] * delx + shear[1] * dely + shear[2] * delz) * k.rsqinv;
        if update {
            shear[0] = shear[0] - rsht * delx;
            shear[1] = shear[1] - rsht * dely;
            shear[2] = shear[2] - rsht * delz;
        }

        // tangential force = shear spring + tangential velocity damping
        let mg = k.meff * s(self.gammat);
        let fs = match k.polyhertz {
            Some(p) => [0, 1, 2].map(|d| -p * (s(self.kt) * shear[d] + mg * vtr[d])),
            None => [0, 1, 2].map(|d| -(s(self.kt) * shear[d] + mg * vtr[d])),
        };

        // Coulomb limit: where |F_t| > xmu |F_n|, rescale the force and the shear that produces
        // it (or zero the force where the shear is zero)
        let fsmag = (fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]).sqrt();
        let fn_ = s(self.xmu) * (k.ccel * k.r).abs();
        let slide = fn_.lt(fsmag);
        if !T::any(slide) {
            // every contact sticks (the common case in a bed at rest): nothing to rescale
            return (k, fs, fsmag);
        }
        let shrmag = (unrotated[0] * unrotated[0] + unrotated[1] * unrotated[1] + unrotated[2] * unrotated[2]).sqrt();
        let rescale = slide & shrmag.ne(s(0.0));
        let ratio = fn_ / fsmag;
        for d in 0..3 {
            let set_back = ratio * (shear[d] + mg * vtr[d] / s(self.kt)) - mg * vtr[d] / s(self.kt);
            shear[d] = T::select(rescale, set_back, shear[d]);
        }
        let fs = fs.map(|f| T::select(slide, T::select(rescale, f * ratio, s(0.0)), f));
        let fsmag = T::select(slide, T::select(rescale, fsmag * ratio, s(0.0)), fsmag);
        (k, fs, fsmag)
    }

    /// The contact without history (gran/hooke: tangential damping limited by friction).
    #[inline(always)]
    pub fn without_history<T: Real>(&self, c: &Contact<T>) -> ContactForce<T> {
        let k = Normal::of(self, c);
        let s = T::splat;
        let vtr = k.vtr;
        let vrel = (vtr[0] * vtr[0] + vtr[1] * vtr[1] + vtr[2] * vtr[2]).sqrt();
        let fn_ = s(self.xmu) * (k.ccel * k.r).abs();
        let fsmag = k.meff * s(self.gammat) * vrel;
        let ft = T::select(vrel.ne(s(0.0)), T::select(fn_.lt(fsmag), fn_, fsmag) / vrel, s(0.0));
        force(c, k.ccel, k.rinv, vtr.map(|v| -ft * v))
    }
}

/// The normal part and the relative tangential velocity, common to both classic styles.
struct Normal<T> {
    r: T,
    rinv: T,
    rsqinv: T,
    meff: T,
    /// normal force / r (spring + normal damping)
    ccel: T,
    /// sqrt(delta R_i R_j / (R_i + R_j)) for Hertz
    polyhertz: Option<T>,
    /// relative tangential velocity at the contact point
    vtr: [T; 3],
    /// (v_i - v_j) . (x_i - x_j)
    vnnr: T,
}

impl<T: Real> Normal<T> {
    #[inline(always)]
    fn of(p: &Classic, c: &Contact<T>) -> Normal<T> {
        let s = T::splat;
        let [delx, dely, delz] = c.del;
        let (radi, radj) = (c.radi, c.radj);
        let radsum = radi + radj;
        let r = c.rsq.sqrt();
        let rinv = s(1.0) / r;
        let rsqinv = s(1.0) / c.rsq;

        // relative translational velocity, its normal and tangential parts
        let vr = [0, 1, 2].map(|d| c.vi[d] - c.vj[d]);
        let vnnr = vr[0] * delx + vr[1] * dely + vr[2] * delz;
        let vt = [0, 1, 2].map(|d| vr[d] - c.del[d] * vnnr * rsqinv);
        // relative rotational velocity (full radii)
        let wr = [0, 1, 2].map(|d| (radi * c.omegai[d] + radj * c.omegaj[d]) * rinv);

        let meff = c.meff;
        let damp = meff * s(p.gamman) * vnnr * rsqinv;
        let mut ccel = s(p.kn) * (radsum - r) * rinv - damp;
        let polyhertz = p.hertz.then(|| ((radsum - r) * radi * radj / radsum).sqrt());
        if let Some(poly) = polyhertz {
            ccel = ccel * poly;
        }
        if p.limit_damping {
            ccel = T::select(ccel.lt(s(0.0)), s(0.0), ccel);
        }
        let vtr = [
            vt[0] - (delz * wr[1] - dely * wr[2]),
            vt[1] - (delx * wr[2] - delz * wr[0]),
            vt[2] - (dely * wr[0] - delx * wr[1]),
        ];
        Normal { r, rinv, rsqinv, meff, ccel, polyhertz, vtr, vnnr }
    }
}

/// Force on i and torques (-R (n x F_t) with the full radii).
#[inline(always)]
fn force<T: Real>(c: &Contact<T>, ccel: T, rinv: T, fs: [T; 3]) -> ContactForce<T> {
    let [delx, dely, delz] = c.del;
    let [fs1, fs2, fs3] = fs;
    let f = [delx * ccel + fs1, dely * ccel + fs2, delz * ccel + fs3];
    let tor = [rinv * (dely * fs3 - delz * fs2), rinv * (delz * fs1 - delx * fs3), rinv * (delx * fs2 - dely * fs1)];
    ContactForce { f, ti: tor.map(|t| -(c.radi * t)), tj: tor.map(|t| -(c.radj * t)) }
}
