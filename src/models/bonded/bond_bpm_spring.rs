//! `bond_style bpm/spring` (LAMMPS BPM package, src/BPM/bond_bpm_spring.cpp): a breakable
//! central spring whose rest length r0 is each bond's own reference length (stored as
//! `crate::models::bonded::bpm` describes, with the keywords, checks and breaking all BPM
//! styles share).
//!
//! With e = (r - r0) / r0, a bond breaks when |e| > ecrit (with `break yes`); otherwise
//!
//!   F = [k (r0 - r) - gamma (del . dv) / r] / r * del * s,   s = 1 - (e / ecrit)^8 with `smooth yes`
//!
//! (`normalize yes` uses -k e for the spring term) and the energy is 1/2 k (r - r0)^2 (divided by
//! r0 with `normalize yes`; the damping and the smoothing carry none).
//!
//! `volume/factor yes` (Clemmer, Monti and Lechman, Soft Matter 20, 1702 (2024)) adds
//! av ([(V_1 + V_2) / (V0_1 + V0_2)]^(1/dim) - 1 - e) to the spring term, where V_i sums the
//! current lengths of atom i's bonds to the power dim and V0_i their reference lengths (see
//! `bpm::VOL`); bond_coeff then takes a fifth coefficient av. The energy ignores it.

use super::bpm::{logical, Bpm, BondOut, BpmAtoms, BpmStyle, VolSums, VOL, VOL0};
use super::{bond_virial, fmt_g, BondStyle, SingleBond, TypeTable, Vec3};
use crate::engine::state::State;
use crate::engine::topology::BOND_HISTORY;
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "bond_coeff N k ecrit gamma";
const SYNTAX_VOLUME: &str = "bond_coeff N k ecrit gamma av (with volume/factor yes)";
pub const SETTINGS_SYNTAX: &str =
    "bond_style bpm/spring [store/local fixID N id1|id2|time|x|y|z|x/ref|y/ref|z/ref ...] [overlay/pair yes/no] [break yes/no] [smooth yes/no] [normalize yes/no] [volume/factor yes/no]";
#[derive(Clone, Copy, Debug, PartialEq)]
struct Params {
    k: f64,
    ecrit: f64,
    gamma: f64,
    /// The volume factor's coefficient (0 without `volume/factor yes`).
    av: f64,
}

#[derive(Debug, Default)]
pub struct BondBpmSpring {
    types: TypeTable<Params>,
    pub bpm: Bpm,
}

impl BondBpmSpring {
    /// The kernel of one intact bond of type `btype` with reference length `r0`:
    /// `del = x1 - x2`, `dv = v1 - v2` (atom 1 has the lower ID). `None`: the bond breaks.
    /// Otherwise `(fbond, energy)`: the force on atom 1 is `del * fbond`.
    #[inline(always)]
    /// `vol`: the volume sums of the bond's atoms with `volume/factor yes`.
    pub fn kernel(&self, btype: usize, r0: f64, del: Vec3, dv: Vec3, vol: Option<VolSums>) -> Option<(f64, f64)> {
        let p = self.types.get(btype);
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        let r = rsq.sqrt();
        let e = (r - r0) / r0;
        if e.abs() > p.ecrit && self.bpm.break_bonds {
            return None;
        }
        let mut fbond = if self.bpm.normalize { -p.k * e } else { p.k * (r0 - r) };
        if let Some(v) = vol {
            fbond += volume_term(p.av, v, e);
        }
        let energy = if self.bpm.normalize { 0.5 * p.k * e * (r - r0) } else { 0.5 * p.k * (r - r0) * (r - r0) };
        Some((self.damped(p, r, r0, fbond, del, dv), energy))
    }

    #[inline(always)]
    fn bond_out(&self, btype: usize, r0: f64, [i1, i2]: [usize; 2], del: Vec3, atoms: &BpmAtoms, vol: Option<VolSums>) -> Option<BondOut> {
        let (v1, v2) = (atoms.v[i1], atoms.v[i2]);
        let dv = [v1[0] - v2[0], v1[1] - v2[1], v1[2] - v2[2]];
        let (fbond, energy) = self.kernel(btype, r0, del, dv, vol)?;
        Some(BondOut { f1: del.map(|d| d * fbond), energy, virial: bond_virial(del, fbond), ..Default::default() })
    }

    #[inline(always)]
    fn damped(&self, p: &Params, r: f64, r0: f64, fbond: f64, del: Vec3, dv: Vec3) -> f64 {
        damped(p.gamma, p.ecrit, self.bpm.smooth, r, r0, fbond, del, dv)
    }

    /// LAMMPS' BondBPM::init_style and BondBPMSpring::init_style checks.
    fn check(&self, state: &State, many_body: bool) -> Result<(), String> {
        self.bpm.check(state, many_body)?;
        if !state.comm_vel {
            return Err("Bond bpm/spring requires ghost atoms store velocity (comm_modify vel yes)".into());
        }
        Ok(())
    }
}

/// The volume factor's addition to the spring term (LAMMPS' order).
#[inline(always)]
fn volume_term(av: f64, v: VolSums, e: f64) -> f64 {
    av * ((v.vol / v.vol0).powf(v.invdim) - 1.0 - e)
}

/// The spring force `fbond` (k (r0 - r) or -k e) with the damping and smoothing, over r (LAMMPS'
/// order, shared with bpm/spring/plastic).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn damped(gamma: f64, ecrit: f64, smooth: bool, r: f64, r0: f64, mut fbond: f64, del: Vec3, dv: Vec3) -> f64 {
    let rinv = 1.0 / r;
    let dot = del[0] * dv[0] + del[1] * dv[1] + del[2] * dv[2];
    fbond -= gamma * dot * rinv;
    fbond *= rinv;
    if smooth {
        let mut s = (r - r0) / (r0 * ecrit);
        s *= s;
        s *= s;
        s *= s;
        fbond *= 1.0 - s;
    }
    fbond
}

impl BondStyle for BondBpmSpring {
    crate::bpm_bond_style_common!();
    fn name(&self) -> &'static str {
        "bpm/spring"
    }
    fn settings(&mut self, a: &mut Args) -> DResult<()> {
        a.syntax = SETTINGS_SYNTAX;
        let mut volume = false;
        self.bpm.settings(a, &["volume/factor"], |w, a| {
            if w.text != "volume/factor" {
                return Ok(false);
            }
            volume = logical(a, "volume/factor")?;
            Ok(true)
        })?;
        self.bpm.volume = volume;
        Ok(())
    }
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = if self.bpm.volume { SYNTAX_VOLUME } else { SYNTAX };
        let k = args.f64("k")?;
        let ecrit = args.f64("ecrit")?;
        let gamma = args.f64("gamma")?;
        let av = if self.bpm.volume { args.f64("av")? } else { 0.0 };
        args.finish()?;
        self.types.set(lo, hi, Params { k, ecrit, gamma, av });
        Ok(())
    }
    /// LAMMPS' single: the bond's stored r0, the atoms' velocities and volumes of the last
    /// force evaluation, never breaking; its normalized spring is k (r0 - r) / r0 (compute's
    /// -k e may differ in the last bit).
    fn single(&self, b: &SingleBond) -> Result<(f64, f64), String> {
        let p = self.types.get(b.typ);
        let r0 = b.state.topo.bonds[b.rec].history[0];
        let r = b.rsq.sqrt();
        let mut fbond = if self.bpm.normalize { p.k * (r0 - r) / r0 } else { p.k * (r0 - r) };
        if self.bpm.volume {
            fbond += volume_term(p.av, single_volumes(b)?, (r - r0) / r0);
        }
        let v = &b.state.atoms.v;
        let dv = [v[b.i][0] - v[b.j][0], v[b.i][1] - v[b.j][1], v[b.i][2] - v[b.j][2]];
        let energy = if self.bpm.normalize { 0.5 * p.k * ((r - r0) / r0) * (r - r0) } else { 0.5 * p.k * (r - r0) * (r - r0) };
        Ok((self.damped(p, r, r0, fbond, b.del, dv), energy))
    }
    fn stiffness(&self, btype: usize) -> f64 {
        self.types.try_get(btype).map(|p| 0.5 * p.k).unwrap_or(0.0)
    }
    fn coeff_words(&self, btype: usize) -> String {
        let p = self.types.get(btype);
        let av = if self.bpm.volume { format!(" {}", fmt_g(p.av)) } else { String::new() };
        format!("{} {} {}{av}", fmt_g(p.k), fmt_g(p.ecrit), fmt_g(p.gamma))
    }
}

/// The volume sums of a bond's atoms for `single` (a ghost reads its owner's values).
fn single_volumes(b: &SingleBond) -> Result<VolSums, String> {
    let a = &b.state.atoms;
    let (Some(vol), Some(vol0)) = (a.field_values(VOL), a.field_values(VOL0)) else {
        return Err("bond bpm/spring volumes are made by the first force evaluation".into());
    };
    let owner = |i: usize| if i < a.nlocal { i } else { a.ghost_owner[i - a.nlocal] as usize };
    let (i, j) = (owner(b.i), owner(b.j));
    Ok(VolSums { vol: vol[i] + vol[j], vol0: vol0[i] + vol0[j], invdim: 1.0 / b.state.dimension as f64 })
}

impl BpmStyle for BondBpmSpring {
    const TORQUES: bool = false;
    fn bpm(&self) -> &Bpm {
        &self.bpm
    }
    fn reference(&self, del: Vec3) -> [f64; BOND_HISTORY] {
        [(del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt(), 0.0, 0.0, 0.0]
    }
    #[inline(always)]
    fn bond(&self, btype: usize, hist: &[f64; BOND_HISTORY], i1: usize, i2: usize, del: Vec3, atoms: &BpmAtoms) -> Option<BondOut> {
        self.bond_out(btype, hist[0], [i1, i2], del, atoms, None)
    }
    #[inline(always)]
    fn bond_volume(&self, btype: usize, hist: &[f64; BOND_HISTORY], i1: usize, i2: usize, del: Vec3, atoms: &BpmAtoms, vol: VolSums) -> Option<BondOut> {
        self.bond_out(btype, hist[0], [i1, i2], del, atoms, Some(vol))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::bonded::bpm::LocalValue;
    use crate::models::bonded::test_util::words;
    use dmhs_parser::Span;

    fn style(settings: &str, coeff: &str) -> BondBpmSpring {
        crate::models::bonded::test_util::configured(settings, coeff)
    }

    /// One bond in real LAMMPS 22 Jul 2025 (`newton on off`, pair_style zero): atoms at (0,0,0)
    /// and (1, 0.1, 0) for the first `run 0` (which stores r0), then atom 2 moved to `x2`,
    /// v1 = (0.1, 0.2, -0.1), v2 = (0.3, -0.1, 0.05) and `run 0` again: the force on atom 1 and
    /// ebond (normalised by the 2 atoms, lj units), printed with %.17g. bond_coeff 1 2.0 0.3 0.5.
    #[test]
    fn matches_lammps_bit_for_bit() {
        #[rustfmt::skip]
        let cases: [(&str, Vec3, Vec3, f64); 6] = [
            ("smooth yes", [1.1, 0.15, 0.02], [0.28812122379427496, 0.039289257790128394, 0.0052385677053504529], 0.0055517071435228858),
            ("smooth yes", [0.85, -0.05, 0.1], [-0.17657731312415673, 0.01038690077200922, -0.020773801544018439], 0.010902646243618046),
            ("smooth no", [1.1, 0.15, 0.02], [0.28818538057892013, 0.039298006442580018, 0.0052397341923440021], 0.0055517071435228858),
            ("smooth no", [0.85, -0.05, 0.1], [-0.17716394746374067, 0.010421408674337688, -0.020842817348675376], 0.010902646243618046),
            ("normalize yes", [1.1, 0.15, 0.02], [0.28708532348637011, 0.039147998657232279, 0.0052197331542976379], 0.0055241550769597374),
            ("normalize yes", [0.85, -0.05, 0.1], [-0.17512896354970317, 0.010301703738217835, -0.020603407476435669], 0.010848538484103195),
        ];
        let r0 = {
            let d: Vec3 = [0.0 - 1.0, 0.0 - 0.1, 0.0 - 0.0];
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        };
        for (settings, x2, f1, e) in cases {
            let s = style(settings, "2.0 0.3 0.5");
            let del = [0.0 - x2[0], 0.0 - x2[1], 0.0 - x2[2]];
            let dv = [0.1 - 0.3, 0.2 - -0.1, -0.1 - 0.05];
            let (fbond, energy) = s.kernel(1, r0, del, dv, None).unwrap();
            let f = del.map(|d| 0.0 + d * fbond);
            assert_eq!(f.map(f64::to_bits), f1.map(f64::to_bits), "{settings} {x2:?}: {f:?} vs {f1:?}");
            assert_eq!((energy / 2.0).to_bits(), e.to_bits(), "{settings} {x2:?}: energy {energy} vs 2 x {e}");
        }
    }

    #[test]
    fn breaks_beyond_the_critical_strain_only() {
        let s = style("", "2.0 0.3 0.5");
        assert!(s.kernel(1, 1.0, [1.29, 0.0, 0.0], [0.0; 3], None).is_some());
        assert!(s.kernel(1, 1.0, [1.31, 0.0, 0.0], [0.0; 3], None).is_none());
        assert!(s.kernel(1, 1.0, [0.69, 0.0, 0.0], [0.0; 3], None).is_none());
        let s = style("break no smooth no", "2.0 0.3 0.5");
        assert!(s.kernel(1, 1.0, [1.5, 0.0, 0.0], [0.0; 3], None).is_some());
    }

    #[test]
    fn settings_errors_are_located() {
        let mut s = BondBpmSpring::default();
        let w = words("break no");
        let e = s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert!(e.message.contains("must turn off smoothing"), "{e}");
        let mut s = BondBpmSpring::default();
        let w = words("store/local brk 100 bogus");
        let e = s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert!(e.message.contains("at least one value"), "{e}");
        let mut s = BondBpmSpring::default();
        let w = words("smooth maybe");
        let e = s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap_err();
        assert_eq!(e.primary_span().unwrap().lo, 7);
        let mut s = BondBpmSpring::default();
        let w = words("store/local brk 100 time id1 id2 overlay/pair yes");
        s.settings(&mut Args::from_words(&w, Span::default(), "")).unwrap();
        let sl = s.bpm.store_local.as_ref().unwrap();
        assert_eq!((sl.fix_id.as_str(), sl.every), ("brk", 100));
        assert_eq!(sl.values, vec![LocalValue::Time, LocalValue::Id1, LocalValue::Id2]);
        assert!(s.bpm.overlay);
    }
}
