//! `pair_style gran/hooke/history Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]`: the
//! Hookean spring-dashpot contact with a tangential spring (shear history) and Coulomb friction,
//! as LAMMPS 2025 computes it (arithmetic in LAMMPS' order, so forces agree to round-off):
//!
//! * F_n = (Kn delta - m_eff gamma_n v_n) n (clamped at 0 with `limit_damping`);
//! * shear s += v_tr dt, |s| taken before it is projected onto the tangent plane (no rescale);
//! * F_t = -(Kt s + m_eff gamma_t v_tr), limited to xmu |F_n| with s set back to match;
//! * torques -R (n x F_t) on both spheres with the full radii.
//!
//! Kt NULL = 2/7 Kn, gamma_t NULL = gamma_n/2, dampflag 0 = no tangential damping.
//! Special-bond weights scale the force and torques (LAMMPS 2025).

use super::contact::{compute_contacts, Contact, ContactForce, ContactModel};
use super::{PairInput, PairModify, PairOutput, PairSetup, PairStyle, Tally};
use crate::contact_history::ContactHistory;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style gran/hooke/history Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]  (Kt, gamma_t may be NULL)";
pub const COEFF_SYNTAX: &str = "pair_coeff * *  (granular styles take no coefficients)";

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
}

impl Classic {
    /// Parse the settings as LAMMPS does (NULL defaults, dampflag 0|1, limit_damping).
    pub fn from_lammps(args: &[Word], cmd: &Command, syntax: &'static str) -> DResult<Classic> {
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
        Ok(Classic { kn, kt, gamman, gammat, xmu, dampflag, limit_damping })
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
}

/// Type-pair bookkeeping shared by the granular styles: which diagonal pairs `pair_coeff` set,
/// and cutoffs from the largest radius of each type (LAMMPS `init_one`: sum of the two types'
/// largest radii).
#[derive(Clone, Debug, Default)]
pub struct GranTypes {
    pub setflag: Vec<bool>,
    pub ntypes: usize,
    pub maxrad: Vec<f64>,
}

impl GranTypes {
    /// `pair_coeff I J` for styles without per-pair coefficients.
    pub fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = COEFF_SYNTAX;
        args.finish()?;
        self.set_range(ilo, ihi, jlo, jhi);
        Ok(())
    }
    pub fn set_range(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize) {
        self.grow(ihi.max(jhi));
        let s = self.ntypes + 1;
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.setflag[i * s + j] = true;
                self.setflag[j * s + i] = true;
            }
        }
    }
    fn grow(&mut self, n: usize) {
        if n <= self.ntypes && !self.setflag.is_empty() {
            return;
        }
        let (old, so, s) = (self.ntypes, self.ntypes + 1, n + 1);
        let mut g = vec![false; s * s];
        for i in 0..=old {
            for j in 0..=old {
                if let Some(&b) = self.setflag.get(i * so + j) {
                    g[i * s + j] = b;
                }
            }
        }
        self.setflag = g;
        self.ntypes = n;
    }
    pub fn is_set(&self, i: usize, j: usize) -> bool {
        self.setflag.get(i * (self.ntypes + 1) + j).copied().unwrap_or(false)
    }
    /// Every I,I pair (of the active ones) must be set.
    pub fn check(&mut self, ntypes: usize, active: Option<&[bool]>, style: &str) -> Result<(), String> {
        self.grow(ntypes);
        for i in 1..=ntypes {
            if let Some(a) = active {
                if !(1..=ntypes).any(|j| a[i * (ntypes + 1) + j]) {
                    continue;
                }
            }
            if !self.is_set(i, i) {
                return Err(format!("pair {style} coefficients for types {i} {i} are not set (use pair_coeff * *)"));
            }
        }
        Ok(())
    }
    /// Largest radius per type over the owned atoms.
    pub fn init_radii(&mut self, setup: &PairSetup) {
        let a = setup.atoms;
        let n = self.ntypes.max(setup.ntypes);
        self.maxrad = vec![0.0; n + 1];
        for i in 0..a.nlocal {
            let t = a.typ[i];
            if t <= n {
                self.maxrad[t] = self.maxrad[t].max(a.radius[i]);
            }
        }
    }
    pub fn cutoff(&self, it: usize, jt: usize) -> f64 {
        match (self.maxrad.get(it), self.maxrad.get(jt)) {
            (Some(a), Some(b)) => a + b,
            _ => 0.0,
        }
    }
}

/// Checks every granular style makes before a run.
pub fn check_setup(setup: &PairSetup, style: &str) -> Result<(), String> {
    if !setup.atoms.features.sphere {
        return Err(format!("pair {style} requires atom attributes radius, rmass (atom_style sphere, or hybrid with sphere)"));
    }
    if !setup.comm_vel {
        return Err(format!("pair {style} requires ghost atoms store velocity: add `comm_modify vel yes`"));
    }
    Ok(())
}

pub struct GranHookeHistory {
    pub settings: Classic,
    types: GranTypes,
    history: ContactHistory,
}

impl GranHookeHistory {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<GranHookeHistory> {
        let settings = Classic::from_lammps(args, cmd, SYNTAX)?;
        Ok(GranHookeHistory { settings, types: GranTypes::default(), history: ContactHistory::new(3) })
    }
}

impl ContactModel for Classic {
    type Params = Classic;
    const HISTORY: usize = 3;
    #[inline(always)]
    fn params(&self, _ti: usize, _tj: usize) -> &Classic {
        self
    }
    #[inline(always)]
    fn contact(p: &Classic, c: &Contact, shear: &mut [f64], update: bool, dt: f64) -> ContactForce {
        let [delx, dely, delz] = c.del;
        let rsq = c.rsq;
        let (radi, radj) = (c.radi, c.radj);
        let radsum = radi + radj;
        let r = rsq.sqrt();
        let rinv = 1.0 / r;
        let rsqinv = 1.0 / rsq;

        // relative translational velocity, its normal and tangential parts
        let vr1 = c.vi[0] - c.vj[0];
        let vr2 = c.vi[1] - c.vj[1];
        let vr3 = c.vi[2] - c.vj[2];
        let vnnr = vr1 * delx + vr2 * dely + vr3 * delz;
        let vn1 = delx * vnnr * rsqinv;
        let vn2 = dely * vnnr * rsqinv;
        let vn3 = delz * vnnr * rsqinv;
        let vt1 = vr1 - vn1;
        let vt2 = vr2 - vn2;
        let vt3 = vr3 - vn3;

        // relative rotational velocity (full radii)
        let wr1 = (radi * c.omegai[0] + radj * c.omegaj[0]) * rinv;
        let wr2 = (radi * c.omegai[1] + radj * c.omegaj[1]) * rinv;
        let wr3 = (radi * c.omegai[2] + radj * c.omegaj[2]) * rinv;

        let meff = c.mi * c.mj / (c.mi + c.mj);

        // normal force = Hookean contact + normal velocity damping
        let damp = meff * p.gamman * vnnr * rsqinv;
        let mut ccel = p.kn * (radsum - r) * rinv - damp;
        if p.limit_damping && ccel < 0.0 {
            ccel = 0.0;
        }

        // relative tangential velocity at the contact
        let vtr1 = vt1 - (delz * wr2 - dely * wr3);
        let vtr2 = vt2 - (delx * wr3 - delz * wr1);
        let vtr3 = vt3 - (dely * wr1 - delx * wr2);

        // shear history
        if update {
            shear[0] += vtr1 * dt;
            shear[1] += vtr2 * dt;
            shear[2] += vtr3 * dt;
        }
        let shrmag = (shear[0] * shear[0] + shear[1] * shear[1] + shear[2] * shear[2]).sqrt();
        // rotate the shear displacement into the tangent plane
        let rsht = (shear[0] * delx + shear[1] * dely + shear[2] * delz) * rsqinv;
        if update {
            shear[0] -= rsht * delx;
            shear[1] -= rsht * dely;
            shear[2] -= rsht * delz;
        }

        // tangential force = shear spring + tangential velocity damping
        let mg = meff * p.gammat;
        let mut fs1 = -(p.kt * shear[0] + mg * vtr1);
        let mut fs2 = -(p.kt * shear[1] + mg * vtr2);
        let mut fs3 = -(p.kt * shear[2] + mg * vtr3);

        // Coulomb limit: rescale the force and the shear that produces it
        let fs = (fs1 * fs1 + fs2 * fs2 + fs3 * fs3).sqrt();
        let fn_ = p.xmu * (ccel * r).abs();
        if fs > fn_ {
            if shrmag != 0.0 {
                let ratio = fn_ / fs;
                shear[0] = ratio * (shear[0] + mg * vtr1 / p.kt) - mg * vtr1 / p.kt;
                shear[1] = ratio * (shear[1] + mg * vtr2 / p.kt) - mg * vtr2 / p.kt;
                shear[2] = ratio * (shear[2] + mg * vtr3 / p.kt) - mg * vtr3 / p.kt;
                fs1 *= ratio;
                fs2 *= ratio;
                fs3 *= ratio;
            } else {
                fs1 = 0.0;
                fs2 = 0.0;
                fs3 = 0.0;
            }
        }
        classic_force(c, ccel, rinv, [fs1, fs2, fs3])
    }
}

/// Force on i and torques of the classic styles (torque -R (n x F_t) with the full radii).
#[inline(always)]
pub fn classic_force(c: &Contact, ccel: f64, rinv: f64, fs: [f64; 3]) -> ContactForce {
    let [delx, dely, delz] = c.del;
    let [fs1, fs2, fs3] = fs;
    let f = [delx * ccel + fs1, dely * ccel + fs2, delz * ccel + fs3];
    let tor1 = rinv * (dely * fs3 - delz * fs2);
    let tor2 = rinv * (delz * fs1 - delx * fs3);
    let tor3 = rinv * (delx * fs2 - dely * fs1);
    ContactForce {
        f,
        ti: [-(c.radi * tor1), -(c.radi * tor2), -(c.radi * tor3)],
        tj: [-(c.radj * tor1), -(c.radj * tor2), -(c.radj * tor3)],
    }
}

impl PairStyle for GranHookeHistory {
    fn style(&self) -> &str {
        "gran/hooke/history"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.types.coeff(ilo, ihi, jlo, jhi, args)
    }
    fn init_sim(&mut self, setup: &PairSetup) -> Result<(), String> {
        check_setup(setup, self.style())?;
        self.types.init_radii(setup);
        Ok(())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.types.check(ntypes, active, "gran/hooke/history")
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.types.cutoff(it, jt)
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        compute_contacts(&self.settings, input, out, Some(&mut self.history))
    }
    fn rebuilt(&mut self, input: &PairInput, _order: &[usize]) {
        rebuild_history(&mut self.history, input);
    }
    fn histories(&mut self) -> Vec<&mut ContactHistory> {
        vec![&mut self.history]
    }
    fn describe(&self) -> String {
        self.settings.describe("gran/hooke/history")
    }
}

/// Carry a history store over a list rebuild: pairs that overlap now keep their contact.
pub fn rebuild_history(history: &mut ContactHistory, input: &PairInput) {
    let a = input.atoms;
    let (x, radius) = (&a.x, &a.radius);
    history.rebuilt(a, input.list, |i, j| {
        let del = [x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]];
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        let radsum = radius[i] + radius[j];
        rsq < radsum * radsum
    });
}
