//! `pair_style gran/hooke Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]`: the Hookean
//! spring-dashpot contact without shear history (LAMMPS 2025 arithmetic). The normal force is
//! Kn delta - m_eff gamma_n v_n (clamped at 0 only with `limit_damping`, as LAMMPS 2025 does);
//! the tangential force is pure damping, -m_eff gamma_t v_tr, limited to xmu |F_n|. Kt is
//! accepted and unused, as in LAMMPS.

use super::contact::{compute_contacts, Contact, ContactForce, ContactModel};
use super::gran_hooke_history::{check_setup, classic_force, Classic, GranTypes};
use super::{PairInput, PairModify, PairOutput, PairSetup, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style gran/hooke Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]  (Kt, gamma_t may be NULL)";

/// The classic settings, evaluated without history.
pub struct NoHistory(pub Classic);

pub struct GranHooke {
    model: NoHistory,
    types: GranTypes,
}

impl GranHooke {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<GranHooke> {
        Ok(GranHooke { model: NoHistory(Classic::from_lammps(args, cmd, SYNTAX)?), types: GranTypes::default() })
    }
}

impl ContactModel for NoHistory {
    type Params = Classic;
    const HISTORY: usize = 0;
    #[inline(always)]
    fn params(&self, _ti: usize, _tj: usize) -> &Classic {
        &self.0
    }
    #[inline(always)]
    fn contact(p: &Classic, c: &Contact, _hist: &mut [f64], _update: bool, _dt: f64) -> ContactForce {
        let [delx, dely, delz] = c.del;
        let rsq = c.rsq;
        let (radi, radj) = (c.radi, c.radj);
        let radsum = radi + radj;
        let r = rsq.sqrt();
        let rinv = 1.0 / r;
        let rsqinv = 1.0 / rsq;

        let vr1 = c.vi[0] - c.vj[0];
        let vr2 = c.vi[1] - c.vj[1];
        let vr3 = c.vi[2] - c.vj[2];
        let vnnr = vr1 * delx + vr2 * dely + vr3 * delz;
        let vt1 = vr1 - delx * vnnr * rsqinv;
        let vt2 = vr2 - dely * vnnr * rsqinv;
        let vt3 = vr3 - delz * vnnr * rsqinv;

        let wr1 = (radi * c.omegai[0] + radj * c.omegaj[0]) * rinv;
        let wr2 = (radi * c.omegai[1] + radj * c.omegaj[1]) * rinv;
        let wr3 = (radi * c.omegai[2] + radj * c.omegaj[2]) * rinv;

        let meff = c.mi * c.mj / (c.mi + c.mj);
        let damp = meff * p.gamman * vnnr * rsqinv;
        let mut ccel = p.kn * (radsum - r) * rinv - damp;
        if p.limit_damping && ccel < 0.0 {
            ccel = 0.0;
        }

        let vtr1 = vt1 - (delz * wr2 - dely * wr3);
        let vtr2 = vt2 - (delx * wr3 - delz * wr1);
        let vtr3 = vt3 - (dely * wr1 - delx * wr2);
        let vrel = (vtr1 * vtr1 + vtr2 * vtr2 + vtr3 * vtr3).sqrt();

        // tangential damping, limited by friction
        let fn_ = p.xmu * (ccel * r).abs();
        let fs = meff * p.gammat * vrel;
        let ft = if vrel != 0.0 { (if fn_ < fs { fn_ } else { fs }) / vrel } else { 0.0 };
        classic_force(c, ccel, rinv, [-ft * vtr1, -ft * vtr2, -ft * vtr3])
    }
}

impl PairStyle for GranHooke {
    fn style(&self) -> &str {
        "gran/hooke"
    }
    fn contact_stiffness(&self) -> Option<f64> {
        Some(self.model.0.kn)
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
        self.types.check(ntypes, active, "gran/hooke")
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.types.cutoff(it, jt)
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        compute_contacts(&self.model, input, out, None)
    }
    fn describe(&self) -> String {
        self.model.0.describe("gran/hooke")
    }
}
