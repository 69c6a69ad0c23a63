//! `bond_style zero [nocoeff]` (LAMMPS src/bond_zero.cpp): bonds that exist (for the topology,
//! the special lists, the neighbour exclusions) and exert no force and no energy.
//!
//! Coefficients: `bond_coeff N [r0]` (r0 only reported, as the equilibrium distance and by
//! write_data; default 0); with `nocoeff` any words after the type are accepted and ignored.

use super::{fmt_g, BondStyle, BondedTally, Entry, Kernels, TypeTable, Vec3};
use crate::engine::par::AtomsMut;
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N [r0]";

#[derive(Clone, Debug, Default)]
pub struct BondZero {
    types: TypeTable<f64>,
    /// `nocoeff`: bond_coeff ignores the words after the type.
    nocoeff: bool,
}

impl BondStyle for BondZero {
    fn name(&self) -> &'static str {
        "zero"
    }
    fn settings(&mut self, args: &mut Args) -> DResult<()> {
        args.syntax = "bond_style zero [nocoeff]";
        if args.peek().is_some() {
            args.choice("keyword", &["nocoeff"])?;
            self.nocoeff = true;
        }
        args.finish()
    }
    fn set_types(&mut self, n: usize) {
        self.types.resize(n);
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = SYNTAX;
        let r0 = match self.nocoeff {
            true => {
                args.skip(args.remaining().len());
                0.0
            }
            false if args.peek().is_some() => args.f64("r0")?,
            false => 0.0,
        };
        args.finish()?;
        self.types.set(lo, hi, r0);
        Ok(())
    }
    fn check_all_set(&self) -> Result<(), String> {
        self.types.check_all_set("Bond")
    }
    fn compute(&self, _btype: usize, _del: Vec3, _rsq: f64) -> (f64, f64) {
        (0.0, 0.0)
    }
    /// LAMMPS' compute does nothing: no bond is visited.
    fn apply(&self, _entries: &[Entry<2>], _k: &Kernels, _f: &mut AtomsMut<Vec3>, _t: &mut BondedTally) {}
    fn equilibrium_distance(&self, btype: usize) -> f64 {
        *self.types.get(btype)
    }
    fn coeff_words(&self, btype: usize) -> String {
        fmt_g(*self.types.get(btype))
    }
}
