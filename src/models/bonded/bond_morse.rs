//! `bond_style morse`: E = D0 [1 - exp(-alpha (r - r0))]^2 (LAMMPS src/MOLECULE/bond_morse.cpp).
//!
//! Coefficients: `bond_coeff N D0 alpha r0`.

use super::{fmt_g, BondStyle, TypeTable, Vec3};
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N D0 alpha r0";

#[derive(Clone, Copy, Debug, PartialEq)]
struct Params {
    d0: f64,
    alpha: f64,
    r0: f64,
}

#[derive(Clone, Debug, Default)]
pub struct BondMorse {
    types: TypeTable<Params>,
}

impl BondStyle for BondMorse {
    fn name(&self) -> &'static str {
        "morse"
    }
    fn set_types(&mut self, n: usize) {
        self.types.resize(n);
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = SYNTAX;
        let d0 = args.f64("D0")?;
        let alpha = args.f64("alpha")?;
        let r0 = args.f64("r0")?;
        args.finish()?;
        self.types.set(lo, hi, Params { d0, alpha, r0 });
        Ok(())
    }
    fn check_all_set(&self) -> Result<(), String> {
        self.types.check_all_set("Bond")
    }
    #[inline(always)]
    fn compute(&self, btype: usize, _del: Vec3, rsq: f64) -> (f64, f64) {
        let p = self.types.get(btype);
        let r = rsq.sqrt();
        let dr = r - p.r0;
        let ralpha = (-p.alpha * dr).exp();
        // a zero-length bond has no direction, hence no force (as LAMMPS)
        let fbond = if r > 0.0 { -2.0 * p.d0 * p.alpha * (1.0 - ralpha) * ralpha / r } else { 0.0 };
        (fbond, p.d0 * (1.0 - ralpha) * (1.0 - ralpha))
    }
    fn equilibrium_distance(&self, btype: usize) -> f64 {
        self.types.get(btype).r0
    }
    fn stiffness(&self, btype: usize) -> f64 {
        // E ~ D0 alpha^2 (r - r0)^2 near r0
        self.types.try_get(btype).map(|p| p.d0 * p.alpha * p.alpha).unwrap_or(0.0)
    }
    fn coeff_words(&self, btype: usize) -> String {
        let p = self.types.get(btype);
        format!("{} {} {}", fmt_g(p.d0), fmt_g(p.alpha), fmt_g(p.r0))
    }
}
