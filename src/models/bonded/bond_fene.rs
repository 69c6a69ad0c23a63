//! `bond_style fene`: the finitely extensible nonlinear elastic bond of Kremer & Grest,
//! E = -1/2 K R0^2 ln(1 - (r/R0)^2) + 4 eps [(sigma/r)^12 - (sigma/r)^6] + eps, the LJ term only
//! below 2^(1/6) sigma (LAMMPS src/MOLECULE/bond_fene.cpp).
//!
//! Coefficients: `bond_coeff N K R0 epsilon sigma`. As in LAMMPS, a bond stretched so far that
//! 1 - (r/R0)^2 < 0.1 is computed with 0.1 ("FENE bond too long"), and one with 1 - (r/R0)^2 <=
//! -3 stops compute bond/local with "Bad FENE bond".

use super::{fmt_g, BondStyle, SingleBond, TypeTable, Vec3};
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N K R0 epsilon sigma";
/// LAMMPS `MathConst::MY_CUBEROOT2`: the LJ term acts below r^2 = 2^(1/3) sigma^2.
pub(super) const MY_CUBEROOT2: f64 = 1.259_921_049_894_873_2;

/// The four coefficients fene and fene/expand share (fene/expand adds its shift).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct FeneParams {
    pub k: f64,
    pub r0: f64,
    pub epsilon: f64,
    pub sigma: f64,
}

impl FeneParams {
    /// `K R0 epsilon sigma` (LAMMPS: numbers, no range checks).
    pub fn parse(args: &mut Args) -> DResult<Self> {
        Ok(FeneParams { k: args.f64("K")?, r0: args.f64("R0")?, epsilon: args.f64("epsilon")?, sigma: args.f64("sigma")? })
    }
    pub fn words(&self) -> String {
        format!("{} {} {} {}", fmt_g(self.k), fmt_g(self.r0), fmt_g(self.epsilon), fmt_g(self.sigma))
    }
    /// LAMMPS' cap of the log argument of an overstretched bond (its warning aside).
    pub fn capped(rlogarg: f64) -> f64 {
        if rlogarg < 0.1 { 0.1 } else { rlogarg }
    }
    /// The argument at which LAMMPS stops ("Bad FENE bond").
    pub fn check(rlogarg: f64) -> Result<(), String> {
        if rlogarg <= -3.0 { Err("Bad FENE bond".into()) } else { Ok(()) }
    }
}

#[derive(Clone, Debug, Default)]
pub struct BondFene {
    types: TypeTable<FeneParams>,
}

impl BondStyle for BondFene {
    fn name(&self) -> &'static str {
        "fene"
    }
    fn set_types(&mut self, n: usize) {
        self.types.resize(n);
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = SYNTAX;
        let p = FeneParams::parse(args)?;
        args.finish()?;
        self.types.set(lo, hi, p);
        Ok(())
    }
    fn check_all_set(&self) -> Result<(), String> {
        self.types.check_all_set("Bond")
    }
    #[inline(always)]
    fn compute(&self, btype: usize, _del: Vec3, rsq: f64) -> (f64, f64) {
        let p = self.types.get(btype);
        let r0sq = p.r0 * p.r0;
        let rlogarg = FeneParams::capped(1.0 - rsq / r0sq);
        let mut fbond = -p.k / rlogarg;
        let mut ebond = -0.5 * p.k * r0sq * rlogarg.ln();
        if rsq < MY_CUBEROOT2 * p.sigma * p.sigma {
            let sr2 = p.sigma * p.sigma / rsq;
            let sr6 = sr2 * sr2 * sr2;
            fbond += 48.0 * p.epsilon * sr6 * (sr6 - 0.5) / rsq;
            ebond += 4.0 * p.epsilon * sr6 * (sr6 - 1.0) + p.epsilon;
        }
        (fbond, ebond)
    }
    fn single(&self, b: &SingleBond) -> Result<(f64, f64), String> {
        let p = self.types.get(b.typ);
        FeneParams::check(1.0 - b.rsq / (p.r0 * p.r0))?;
        // LAMMPS' single sums the same terms in the same order as its compute
        Ok(self.compute(b.typ, b.del, b.rsq))
    }
    fn equilibrium_distance(&self, btype: usize) -> f64 {
        0.97 * self.types.get(btype).sigma
    }
    fn coeff_words(&self, btype: usize) -> String {
        self.types.get(btype).words()
    }
}
