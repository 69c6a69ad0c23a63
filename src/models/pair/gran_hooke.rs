//! `pair_style gran/hooke Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]`: the Hookean
//! spring-dashpot contact without shear history (LAMMPS 2025 arithmetic). The normal force is
//! Kn delta - m_eff gamma_n v_n (clamped at 0 only with `limit_damping`, as LAMMPS 2025 does);
//! the tangential force is pure damping, -m_eff gamma_t v_tr, limited to xmu |F_n|. Kt is
//! accepted and unused, as in LAMMPS.

use super::classic::Classic;
use super::contact::{compute_contacts, Contact, ContactForce, ContactModel, LaneSrc, LanesOut};
use super::gran_hooke_history::{check_setup, GranTypes};
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
        Ok(GranHooke { model: NoHistory(Classic::from_lammps(args, cmd, SYNTAX, false)?), types: GranTypes::default() })
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
        p.without_history(c)
    }
    #[inline(always)]
    fn contact_lanes(&self, b: &LaneSrc, _update: bool, _dt: f64) -> LanesOut {
        let (vi, vj, wi, wj) = (b.v3(b.v, 0), b.v3(b.v, 1), b.v3(b.omega, 0), b.v3(b.omega, 1));
        LanesOut { force: self.0.without_history(&b.contact(&vi, &vj, &wi, &wj)), hist: Default::default() }
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
    fn size_list(&self) -> bool {
        true
    }
    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        compute_contacts(&self.model, input, out, None)
    }
    fn describe(&self) -> String {
        self.model.0.describe("gran/hooke")
    }
}
