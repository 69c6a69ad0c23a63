//! `bond_style fene/expand`: fene of the shifted distance r - delta (LAMMPS
//! src/MOLECULE/bond_fene_expand.cpp), for beads of different sizes.
//!
//! Coefficients: `bond_coeff N K R0 epsilon sigma delta`; the log-argument cap and the "Bad FENE
//! bond" stop are fene's.

use super::bond_fene::{FeneParams, MY_CUBEROOT2};
use super::{fmt_g, BondStyle, SingleBond, TypeTable, Vec3};
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N K R0 epsilon sigma delta";

#[derive(Clone, Copy, Debug, PartialEq)]
struct Params {
    fene: FeneParams,
    shift: f64,
}

#[derive(Clone, Debug, Default)]
pub struct BondFeneExpand {
    types: TypeTable<Params>,
}

impl BondFeneExpand {
    /// The log argument 1 - (r - delta)^2 / R0^2 before the cap, and r - delta.
    fn logarg(p: &Params, rsq: f64) -> (f64, f64) {
        let rshift = rsq.sqrt() - p.shift;
        (1.0 - rshift * rshift / (p.fene.r0 * p.fene.r0), rshift)
    }
}

impl BondStyle for BondFeneExpand {
    fn name(&self) -> &'static str {
        "fene/expand"
    }
    fn set_types(&mut self, n: usize) {
        self.types.resize(n);
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = SYNTAX;
        let fene = FeneParams::parse(args)?;
        let shift = args.f64("delta")?;
        args.finish()?;
        self.types.set(lo, hi, Params { fene, shift });
        Ok(())
    }
    fn check_all_set(&self) -> Result<(), String> {
        self.types.check_all_set("Bond")
    }
    #[inline(always)]
    fn compute(&self, btype: usize, _del: Vec3, rsq: f64) -> (f64, f64) {
        let p = self.types.get(btype);
        let f = &p.fene;
        let r = rsq.sqrt();
        let rshift = r - p.shift;
        let rshiftsq = rshift * rshift;
        let r0sq = f.r0 * f.r0;
        let rlogarg = FeneParams::capped(1.0 - rshiftsq / r0sq);
        let mut fbond = -f.k * rshift / rlogarg / r;
        let mut ebond = -0.5 * f.k * r0sq * rlogarg.ln();
        if rshiftsq < MY_CUBEROOT2 * f.sigma * f.sigma {
            let sr2 = f.sigma * f.sigma / rshiftsq;
            let sr6 = sr2 * sr2 * sr2;
            fbond += 48.0 * f.epsilon * sr6 * (sr6 - 0.5) / rshift / r;
            ebond += 4.0 * f.epsilon * sr6 * (sr6 - 1.0) + f.epsilon;
        }
        (fbond, ebond)
    }
    fn single(&self, b: &SingleBond) -> Result<(f64, f64), String> {
        FeneParams::check(Self::logarg(self.types.get(b.typ), b.rsq).0)?;
        Ok(self.compute(b.typ, b.del, b.rsq))
    }
    fn equilibrium_distance(&self, btype: usize) -> f64 {
        let p = self.types.get(btype);
        0.97 * p.fene.sigma + p.shift
    }
    fn coeff_words(&self, btype: usize) -> String {
        let p = self.types.get(btype);
        format!("{} {}", p.fene.words(), fmt_g(p.shift))
    }
}
