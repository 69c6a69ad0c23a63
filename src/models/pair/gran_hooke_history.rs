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

use super::contact::{compute_contacts, lanes, Contact, ContactForce, ContactModel, LaneSrc, LanesOut, L};
use super::{PairInput, PairModify, PairOutput, PairSetup, PairStyle, Tally};
use crate::engine::contact_history::ContactHistory;
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
    #[inline(always)]
    fn contact_lanes(&self, b: &LaneSrc, update: bool, dt: f64) -> LanesOut {
        self.contact_lanes_classic(b, update, dt)
    }
}

impl Classic {
    /// [`ContactModel::contact`] for a batch of pairs, operation by operation over the lanes
    /// (vectorized by the compiler; the same operations per lane, so the same bits), with the
    /// branches of the scalar code as per-lane selects.
    #[inline(always)]
    fn contact_lanes_classic(&self, b: &LaneSrc, update: bool, dt: f64) -> LanesOut {
        let p = self;
        let [delx, dely, delz] = b.del();
        let rsq = lanes(|l| delx[l] * delx[l] + dely[l] * dely[l] + delz[l] * delz[l]);
        let (radi, radj) = (b.scalar(b.radius, 0), b.scalar(b.radius, 1));
        let (vi, vj) = (b.v3(b.v, 0), b.v3(b.v, 1));
        let (omegai, omegaj) = (b.v3(b.omega, 0), b.v3(b.omega, 1));
        let (mi, mj) = (b.scalar(b.rmass, 0), b.scalar(b.rmass, 1));
        let radsum = lanes(|l| radi[l] + radj[l]);
        let r = lanes(|l| rsq[l].sqrt());
        let rinv = lanes(|l| 1.0 / r[l]);
        let rsqinv = lanes(|l| 1.0 / rsq[l]);
        let vr1 = lanes(|l| vi[0][l] - vj[0][l]);
        let vr2 = lanes(|l| vi[1][l] - vj[1][l]);
        let vr3 = lanes(|l| vi[2][l] - vj[2][l]);
        let vnnr = lanes(|l| vr1[l] * delx[l] + vr2[l] * dely[l] + vr3[l] * delz[l]);
        let vt1 = lanes(|l| vr1[l] - delx[l] * vnnr[l] * rsqinv[l]);
        let vt2 = lanes(|l| vr2[l] - dely[l] * vnnr[l] * rsqinv[l]);
        let vt3 = lanes(|l| vr3[l] - delz[l] * vnnr[l] * rsqinv[l]);
        let wr = |d: usize| lanes(|l| (radi[l] * omegai[d][l] + radj[l] * omegaj[d][l]) * rinv[l]);
        let (wr1, wr2, wr3) = (wr(0), wr(1), wr(2));
        let meff = lanes(|l| mi[l] * mj[l] / (mi[l] + mj[l]));
        let damp = lanes(|l| meff[l] * p.gamman * vnnr[l] * rsqinv[l]);
        let mut ccel = lanes(|l| p.kn * (radsum[l] - r[l]) * rinv[l] - damp[l]);
        if p.limit_damping {
            ccel = lanes(|l| if ccel[l] < 0.0 { 0.0 } else { ccel[l] });
        }
        let vtr1 = lanes(|l| vt1[l] - (delz[l] * wr2[l] - dely[l] * wr3[l]));
        let vtr2 = lanes(|l| vt2[l] - (delx[l] * wr3[l] - delz[l] * wr1[l]));
        let vtr3 = lanes(|l| vt3[l] - (dely[l] * wr1[l] - delx[l] * wr2[l]));
        let [mut s1, mut s2, mut s3] = b.hist();
        if update {
            s1 = lanes(|l| s1[l] + vtr1[l] * dt);
            s2 = lanes(|l| s2[l] + vtr2[l] * dt);
            s3 = lanes(|l| s3[l] + vtr3[l] * dt);
        }
        let shrmag = lanes(|l| (s1[l] * s1[l] + s2[l] * s2[l] + s3[l] * s3[l]).sqrt());
        let rsht = lanes(|l| (s1[l] * delx[l] + s2[l] * dely[l] + s3[l] * delz[l]) * rsqinv[l]);
        if update {
            s1 = lanes(|l| s1[l] - rsht[l] * delx[l]);
            s2 = lanes(|l| s2[l] - rsht[l] * dely[l]);
            s3 = lanes(|l| s3[l] - rsht[l] * delz[l]);
        }
        let mg = lanes(|l| meff[l] * p.gammat);
        let fs1 = lanes(|l| -(p.kt * s1[l] + mg[l] * vtr1[l]));
        let fs2 = lanes(|l| -(p.kt * s2[l] + mg[l] * vtr2[l]));
        let fs3 = lanes(|l| -(p.kt * s3[l] + mg[l] * vtr3[l]));
        let fs = lanes(|l| (fs1[l] * fs1[l] + fs2[l] * fs2[l] + fs3[l] * fs3[l]).sqrt());
        let fn_ = lanes(|l| p.xmu * (ccel[l] * r[l]).abs());
        // Coulomb limit, where fs > fn: rescale (or zero the force when the shear is zero)
        let ratio = lanes(|l| fn_[l] / fs[l]);
        let slide = |l: usize| fs[l] > fn_[l];
        let rescale = |s: L, vtr: L| lanes(|l| if slide(l) && shrmag[l] != 0.0 { ratio[l] * (s[l] + mg[l] * vtr[l] / p.kt) - mg[l] * vtr[l] / p.kt } else { s[l] });
        let hist = [rescale(s1, vtr1), rescale(s2, vtr2), rescale(s3, vtr3)];
        let limit = |f: L| lanes(|l| if slide(l) { if shrmag[l] != 0.0 { f[l] * ratio[l] } else { 0.0 } } else { f[l] });
        let (fs1, fs2, fs3) = (limit(fs1), limit(fs2), limit(fs3));
        let tor1 = lanes(|l| rinv[l] * (dely[l] * fs3[l] - delz[l] * fs2[l]));
        let tor2 = lanes(|l| rinv[l] * (delz[l] * fs1[l] - delx[l] * fs3[l]));
        let tor3 = lanes(|l| rinv[l] * (delx[l] * fs2[l] - dely[l] * fs1[l]));
        let neg = |rad: &L, t: &L| lanes(|l| -(rad[l] * t[l]));
        LanesOut {
            f: [lanes(|l| delx[l] * ccel[l] + fs1[l]), lanes(|l| dely[l] * ccel[l] + fs2[l]), lanes(|l| delz[l] * ccel[l] + fs3[l])],
            ti: [neg(&radi, &tor1), neg(&radi, &tor2), neg(&radi, &tor3)],
            tj: [neg(&radj, &tor1), neg(&radj, &tor2), neg(&radj, &tor3)],
            hist,
        }
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
    fn contact_stiffness(&self) -> Option<f64> {
        Some(self.settings.kn)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::pair::contact::{LaneSrc, LANES};

    /// A small deterministic generator (no dependencies).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    /// The vector kernel gives exactly the bits of the one-pair kernel, in every branch
    /// (sticking, sliding, sliding with zero shear, clamped normal force, setup).
    #[test]
    fn lane_kernel_matches_scalar_kernel_bit_for_bit() {
        let mut rng = Lcg(12345);
        // xmu 0.01: every contact slides; 1000: every contact sticks; 0.3: both
        for (limit_damping, xmu) in [(false, 0.01), (false, 0.3), (false, 1000.0), (true, 0.3)] {
            let p = Classic { kn: 2.0e5, kt: 5.0e4, gamman: 300.0, gammat: 150.0, xmu, dampflag: true, limit_damping };
            for trial in 0..100 {
                // 8 atoms: pairs (0,1), (2,3), (4,5), (6,7)
                let n = 2 * LANES;
                let mut x = vec![[0.0; 3]; n];
                let (mut v, mut w) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
                let (mut rad, mut m) = (vec![0.0; n], vec![0.0; n]);
                let mut values = vec![0.0; 3 * LANES];
                for k in 0..n {
                    rad[k] = 0.5 + 0.1 * rng.next();
                    m[k] = 1.0 + 0.5 * rng.next();
                    for d in 0..3 {
                        v[k][d] = 4.0 * rng.next();
                        w[k][d] = 20.0 * rng.next();
                    }
                }
                for l in 0..LANES {
                    let (i, j) = (2 * l, 2 * l + 1);
                    let dir = [rng.next(), rng.next(), rng.next()];
                    let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
                    let r = (rad[i] + rad[j]) * (1.0 - 0.02 * (rng.next() + 0.5));
                    for d in 0..3 {
                        x[i][d] = 3.0 * rng.next();
                        x[j][d] = x[i][d] - r * dir[d] / len;
                        // zero shear in some lanes, large shear (sliding) in others
                        values[3 * l + d] = if (trial + l) % 3 == 0 { 0.0 } else { 1e-3 * rng.next() };
                    }
                }
                for update in [false, true] {
                    let typ = vec![1usize; n];
                    let src = LaneSrc {
                        n: LANES,
                        ij: [std::array::from_fn(|l| 2 * l), std::array::from_fn(|l| 2 * l + 1)],
                        e: std::array::from_fn(|l| l),
                        x: &x,
                        v: &v,
                        omega: &w,
                        radius: &rad,
                        rmass: &m,
                        typ: &typ,
                        values: &values,
                        hsize: 3,
                    };
                    let out = p.contact_lanes(&src, update, 1e-4);
                    for l in 0..LANES {
                        let (i, j) = (2 * l, 2 * l + 1);
                        let del = [x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]];
                        let c = Contact {
                            del,
                            rsq: del[0] * del[0] + del[1] * del[1] + del[2] * del[2],
                            radi: rad[i],
                            radj: rad[j],
                            vi: &v[i],
                            vj: &v[j],
                            omegai: &w[i],
                            omegaj: &w[j],
                            mi: m[i],
                            mj: m[j],
                        };
                        let mut h = [values[3 * l], values[3 * l + 1], values[3 * l + 2]];
                        let r = Classic::contact(&p, &c, &mut h, update, 1e-4);
                        for d in 0..3 {
                            assert_eq!(out.f[d][l].to_bits(), r.f[d].to_bits());
                            assert_eq!(out.ti[d][l].to_bits(), r.ti[d].to_bits());
                            assert_eq!(out.tj[d][l].to_bits(), r.tj[d].to_bits());
                            assert_eq!(out.hist[d][l].to_bits(), h[d].to_bits());
                        }
                    }
                }
            }
        }
    }
}
