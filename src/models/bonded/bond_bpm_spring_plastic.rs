//! `bond_style bpm/spring/plastic` (LAMMPS BPM package, src/BPM/bond_bpm_spring_plastic.cpp):
//! bpm/spring with a plastic strain ep kept per bond (its second history value, 0 when the
//! reference length r0 is stored). With e = (r - r0) / r0 the bond first breaks as bpm/spring
//! does (|e| > ecrit, `break yes`); then ep follows e once e leaves [ep - eplastic, ep + eplastic]
//! (ep = e -/+ eplastic), and
//!
//!   F = [-k (r - (1 + ep) r0) - gamma (del . dv) / r] / r * del * s
//!
//! (`normalize yes`: -k (e - ep)), s the smoothing of bpm/spring (from e, not e - ep). LAMMPS
//! tallies no energy for this style (ebond 0); the virial is the force's.

use super::bond_bpm_spring::damped;
use super::bpm::{Bpm, BondOut, BpmAtoms, BpmStyle};
use super::{bond_virial, fmt_g, BondStyle, SingleBond, TypeTable, Vec3};
use crate::engine::state::State;
use crate::engine::topology::BOND_HISTORY;
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N k ecrit gamma eplastic";
pub const SETTINGS_SYNTAX: &str =
    "bond_style bpm/spring/plastic [store/local fixID N id1|id2|time|x|y|z|x/ref|y/ref|z/ref ...] [overlay/pair yes/no] [break yes/no] [smooth yes/no] [normalize yes/no]";

#[derive(Clone, Copy, Debug, PartialEq)]
struct Params {
    k: f64,
    ecrit: f64,
    gamma: f64,
    eplastic: f64,
}

#[derive(Debug, Default)]
pub struct BondBpmSpringPlastic {
    types: TypeTable<Params>,
    pub bpm: Bpm,
}

impl BondBpmSpringPlastic {
    /// One intact bond of type `btype` with reference length `r0` and plastic strain `ep`:
    /// `del = x1 - x2`, `dv = v1 - v2` (atom 1 the lower ID). `None`: the bond breaks.
    /// Otherwise `(fbond, ep)`: the force on atom 1 is `del * fbond`, `ep` the new plastic strain.
    #[inline(always)]
    pub fn kernel(&self, btype: usize, r0: f64, mut ep: f64, del: Vec3, dv: Vec3) -> Option<(f64, f64)> {
        let p = self.types.get(btype);
        let r = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
        let e = (r - r0) / r0;
        if e.abs() > p.ecrit && self.bpm.break_bonds {
            return None;
        }
        if e > ep + p.eplastic {
            ep = e - p.eplastic;
        }
        if e < ep - p.eplastic {
            ep = e + p.eplastic;
        }
        Some((self.spring(p, r, r0, e, ep, del, dv), ep))
    }

    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn spring(&self, p: &Params, r: f64, r0: f64, e: f64, ep: f64, del: Vec3, dv: Vec3) -> f64 {
        let fbond = if self.bpm.normalize { -p.k * (e - ep) } else { -p.k * (r - (1.0 + ep) * r0) };
        damped(p.gamma, p.ecrit, self.bpm.smooth, r, r0, fbond, del, dv)
    }
}

impl BondStyle for BondBpmSpringPlastic {
    crate::bpm_bond_style_common!();
    fn name(&self) -> &'static str {
        "bpm/spring/plastic"
    }
    fn settings(&mut self, a: &mut Args) -> DResult<()> {
        a.syntax = SETTINGS_SYNTAX;
        self.bpm.settings(a, &[], |_, _| Ok(false))
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = SYNTAX;
        let k = args.f64("k")?;
        let ecrit = args.f64("ecrit")?;
        let gamma = args.f64("gamma")?;
        let eplastic = args.f64("eplastic")?;
        args.finish()?;
        self.types.set(lo, hi, Params { k, ecrit, gamma, eplastic });
        Ok(())
    }
    /// LAMMPS' single: the stored r0 and ep, never breaking nor yielding; no energy.
    fn single(&self, b: &SingleBond) -> Result<(f64, f64), String> {
        let p = self.types.get(b.typ);
        let h = b.state.topo.bonds[b.rec].history;
        let (r0, ep) = (h[0], h[1]);
        let r = b.rsq.sqrt();
        let e = if r0 != 0.0 { (r - r0) / r0 } else { 0.0 };
        let v = &b.state.atoms.v;
        let dv = [v[b.i][0] - v[b.j][0], v[b.i][1] - v[b.j][1], v[b.i][2] - v[b.j][2]];
        Ok((self.spring(p, r, r0, e, ep, b.del, dv), 0.0))
    }
    fn stiffness(&self, btype: usize) -> f64 {
        self.types.try_get(btype).map(|p| 0.5 * p.k).unwrap_or(0.0)
    }
    fn coeff_words(&self, btype: usize) -> String {
        let p = self.types.get(btype);
        format!("{} {} {} {}", fmt_g(p.k), fmt_g(p.ecrit), fmt_g(p.gamma), fmt_g(p.eplastic))
    }
}

impl BondBpmSpringPlastic {
    /// LAMMPS' BondBPM::init_style and BondBPMSpringPlastic::init_style checks.
    fn check(&self, state: &State, many_body: bool) -> Result<(), String> {
        self.bpm.check(state, many_body)?;
        if !state.comm_vel {
            return Err("Bond bpm/spring requires ghost atoms store velocity (comm_modify vel yes)".into());
        }
        Ok(())
    }
}

impl BpmStyle for BondBpmSpringPlastic {
    const TORQUES: bool = false;
    fn bpm(&self) -> &Bpm {
        &self.bpm
    }
    fn reference(&self, del: Vec3) -> [f64; BOND_HISTORY] {
        [(del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt(), 0.0, 0.0, 0.0]
    }
    #[inline(always)]
    fn bond(&self, btype: usize, hist: &[f64; BOND_HISTORY], i1: usize, i2: usize, del: Vec3, atoms: &BpmAtoms) -> Option<BondOut> {
        let (v1, v2) = (atoms.v[i1], atoms.v[i2]);
        let dv = [v1[0] - v2[0], v1[1] - v2[1], v1[2] - v2[2]];
        let (fbond, ep) = self.kernel(btype, hist[0], hist[1], del, dv)?;
        let history = (ep != hist[1]).then(|| [hist[0], ep, hist[2], hist[3]]);
        Some(BondOut { f1: del.map(|d| d * fbond), virial: bond_virial(del, fbond), history, ..Default::default() })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::bonded::test_util::words;
    use dmhs_parser::Span;

    fn style(settings: &str, coeff: &str) -> BondBpmSpringPlastic {
        crate::models::bonded::test_util::configured(settings, coeff)
    }

    /// Within the yield band the plastic strain stays; beyond it it trails e by eplastic, and
    /// the spring's rest length becomes (1 + ep) r0.
    #[test]
    fn yields_beyond_the_plastic_strain() {
        let s = style("break no smooth no", "2.0 0.5 0.0 0.1");
        let (f, ep) = s.kernel(1, 1.0, 0.0, [1.05, 0.0, 0.0], [0.0; 3]).unwrap();
        assert_eq!(ep, 0.0);
        assert!((f - -2.0 * 0.05 / 1.05).abs() < 1e-15);
        let (f, ep) = s.kernel(1, 1.0, 0.0, [1.25, 0.0, 0.0], [0.0; 3]).unwrap();
        assert!((ep - 0.15).abs() < 1e-15);
        assert!((f - -2.0 * 0.1 / 1.25).abs() < 1e-15);
        // back inside the band around ep = 0.15: unchanged; below it, ep follows down
        assert_eq!(s.kernel(1, 1.0, 0.15, [1.1, 0.0, 0.0], [0.0; 3]).unwrap().1, 0.15);
        let (_, ep) = s.kernel(1, 1.0, 0.15, [0.9, 0.0, 0.0], [0.0; 3]).unwrap();
        assert!((ep - 0.0).abs() < 1e-15);
        let s = style("", "2.0 0.3 0.0 0.1");
        assert!(s.kernel(1, 1.0, 0.0, [1.31, 0.0, 0.0], [0.0; 3]).is_none());
    }

    #[test]
    fn settings_and_coeff_errors_are_located() {
        let mut s = BondBpmSpringPlastic::default();
        let w = words("break no smooth no volume/factor yes");
        let e = s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert_eq!(e.primary_span().unwrap().lo, 19, "{e}");
        let mut s = BondBpmSpringPlastic::default();
        s.set_types(1);
        let w = words("1.0 0.1 1.0");
        let e = s.coeff(1, 1, &mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert!(e.to_string().contains("eplastic"), "{e}");
    }
}
