//! Bonded interactions (bonds, angles, dihedrals): the traits every style implements, the
//! registries that map a LAMMPS style name to a constructor, and the virial each interaction
//! tallies.
//!
//! A style only evaluates one interaction from the displacement vectors the engine hands it
//! (already the closest periodic image, as LAMMPS' bond/angle/dihedral lists guarantee); the
//! engine owns the loops, the force accumulation and the energy/virial sums. Every style
//! reproduces the floating-point operation order of its LAMMPS 2025 counterpart so that
//! forces, energies and virials agree bit for bit (checked against fixtures from real
//! LAMMPS in each style's tests; `testdata/gen_fixtures.py` regenerates them, and
//! `testdata/gen_special.py` / `gen_pair.py` those of `crate::engine::special`).
//!
//! Engine contract (as LAMMPS with newton_bond on): forces are accumulated into zeroed
//! arrays in list order (bond: `f1 += del*fbond`, `f2 -= del*fbond`; angle: `f1 += f1`,
//! `f2 -= f1 + f3` i.e. `+= AngleForces::f2()`, `f3 += f3`; dihedral: `+= f1..f4`), energies and
//! the virials from [`bond_virial`], [`angle_virial`], [`dihedral_virial`] summed per style.

pub mod angle_harmonic;
pub mod bond_bpm_rotational;
pub mod bond_bpm_spring;
pub mod bond_bpm_spring_plastic;
pub mod bond_fene;
pub mod bond_fene_expand;
pub mod bond_harmonic;
pub mod bond_zero;
pub mod bond_morse;
pub mod dihedral_harmonic;
pub mod dihedral_quadratic;
pub mod pass;
pub mod bpm;

use crate::engine::bonded_lists::Entry;
use crate::models::bonded::pass::{BondedTally, Kernels};
use crate::engine::par::AtomsMut;
use dmhs_parser::{Args, DResult};

pub type Vec3 = [f64; 3];
/// Virial in LAMMPS order: xx, yy, zz, xy, xz, yz.
pub type Virial = [f64; 6];

/// LAMMPS `MathConst::MY_PI`.
pub const MY_PI: f64 = std::f64::consts::PI;
/// LAMMPS `MathConst::DEG2RAD` (`MY_PI / 180.0`, rounded once).
pub const DEG2RAD: f64 = MY_PI / 180.0;
/// LAMMPS `MathConst::RAD2DEG` (`180.0 / MY_PI`, rounded once).
pub const RAD2DEG: f64 = 180.0 / MY_PI;

// ---------------------------------------------------------------------------------------
// Style traits

/// A bond style. Types are 1-based as in LAMMPS.
pub trait BondStyle: Send + Sync {
    /// The LAMMPS style name (`harmonic`).
    fn name(&self) -> &'static str;
    /// The arguments of `bond_style NAME ...` (none for most styles).
    fn settings(&mut self, args: &mut Args) -> DResult<()> {
        args.finish()
    }
    /// Number of bond types; clears all coefficients.
    fn set_types(&mut self, n: usize);
    /// Coefficients for types `lo..=hi` from the words after the type (range) of
    /// `bond_coeff`, or of a line of the data file's `Bond Coeffs` section. The style sets
    /// `args.syntax` to its own coefficient syntax, so errors show it as help.
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()>;
    /// `Err` with LAMMPS' message if some type has no coefficients.
    fn check_all_set(&self) -> Result<(), String>;
    /// One bond of type `btype`: `del = x1 - x2`, `rsq = |del|^2` summed as x, y, z.
    /// Returns `(fbond, energy)`: the force on atom 1 is `del * fbond`, on atom 2 its negative.
    fn compute(&self, btype: usize, del: Vec3, rsq: f64) -> (f64, f64);
    /// LAMMPS' `Bond::single` (compute bond/local): `(fbond, energy)` of one bond, by default
    /// as [`BondStyle::compute`] gives them; Err with LAMMPS' message where it stops the run.
    fn single(&self, b: &SingleBond) -> Result<(f64, f64), String> {
        Ok(self.compute(b.typ, b.del, b.rsq))
    }
    /// Apply a batch of bonds (monomorphised per style, so `compute` inlines).
    fn apply(&self, entries: &[Entry<2>], k: &Kernels, f: &mut AtomsMut<Vec3>, t: &mut BondedTally) {
        crate::models::bonded::pass::apply_bonds(self, entries, k, f, t)
    }
    /// The rest length (LAMMPS `equilibrium_distance`, used e.g. by the neighbour-list check).
    fn equilibrium_distance(&self, btype: usize) -> f64;
    /// Spring constant for stability estimates: for E = K (r - r0)^2, the K of the type (0 if
    /// the style has no such notion).
    fn stiffness(&self, _btype: usize) -> f64 {
        0.0
    }
    /// The coefficient words `write_data` prints after the type number.
    fn coeff_words(&self, btype: usize) -> String;
    /// Checks before a run that need the state (special weights, newton, ...); `many_body`:
    /// an angle or dihedral style is defined.
    fn init(&self, _state: &crate::engine::state::State, _many_body: bool) -> Result<(), String> {
        Ok(())
    }
    /// A BPM style runs its own pass (per-bond history, velocities, torques, breaking).
    fn as_bpm(&self) -> Option<&dyn bpm::BpmPass> {
        None
    }
}

/// One bond as `BondStyle::single` sees it: LAMMPS' `single(type, rsq, i, j)`, with the
/// state for the styles that read more (a BPM bond's reference state, the atoms' velocities).
pub struct SingleBond<'a> {
    pub state: &'a crate::engine::state::State,
    /// Its topology record (`state.topo.bonds[rec]`).
    pub rec: usize,
    pub typ: usize,
    /// Local indices: `i` the atom that lists the bond, `j` its partner.
    pub i: usize,
    pub j: usize,
    /// `del = x_i - x_j` (closest image), `rsq = |del|^2`.
    pub del: Vec3,
    pub rsq: f64,
}

/// What one angle contributes. The middle atom gets `-(f1 + f3)` (see [`AngleForces::f2`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngleForces {
    pub f1: Vec3,
    pub f3: Vec3,
    pub energy: f64,
}

impl AngleForces {
    /// The force on the middle atom, as LAMMPS applies it (`f[i2] -= f1 + f3`).
    pub fn f2(&self) -> Vec3 {
        [-(self.f1[0] + self.f3[0]), -(self.f1[1] + self.f3[1]), -(self.f1[2] + self.f3[2])]
    }
}

/// An angle style. Types are 1-based.
pub trait AngleStyle: Send + Sync {
    fn name(&self) -> &'static str;
    fn settings(&mut self, args: &mut Args) -> DResult<()> {
        args.finish()
    }
    fn set_types(&mut self, n: usize);
    /// Coefficients for types `lo..=hi` (words after the type of `angle_coeff` / `Angle Coeffs`).
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()>;
    fn check_all_set(&self) -> Result<(), String>;
    /// One angle 1-2-3 (2 is the vertex): `del1 = x1 - x2`, `del2 = x3 - x2`.
    fn compute(&self, atype: usize, del1: Vec3, del2: Vec3) -> AngleForces;
    /// Apply a batch of angles (monomorphised per style, so `compute` inlines).
    fn apply(&self, entries: &[Entry<3>], k: &Kernels, f: &mut AtomsMut<Vec3>, t: &mut BondedTally) {
        crate::models::bonded::pass::apply_angles(self, entries, k, f, t)
    }
    /// The rest angle in radians (LAMMPS `equilibrium_angle`).
    fn equilibrium_angle(&self, atype: usize) -> f64;
    fn coeff_words(&self, atype: usize) -> String;
}

/// What one dihedral contributes: the force on each of its four atoms (each style computes
/// `f2` and `f3` itself, so they are returned rather than derived), its energy, and whether
/// LAMMPS would print its "Dihedral problem" warning (extreme conformation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DihedralForces {
    pub f1: Vec3,
    pub f2: Vec3,
    pub f3: Vec3,
    pub f4: Vec3,
    pub energy: f64,
    /// LAMMPS `Dihedral::problem()` would warn: the computed cosine left [-1.05, 1.05].
    pub problem: bool,
}

/// A dihedral style. Types are 1-based.
pub trait DihedralStyle: Send + Sync {
    fn name(&self) -> &'static str;
    fn settings(&mut self, args: &mut Args) -> DResult<()> {
        args.finish()
    }
    fn set_types(&mut self, n: usize);
    /// Coefficients for types `lo..=hi` (words after the type of `dihedral_coeff` / `Dihedral Coeffs`).
    fn coeff(&mut self, lo: usize, hi: usize, args: &mut Args) -> DResult<()>;
    fn check_all_set(&self) -> Result<(), String>;
    /// One dihedral 1-2-3-4: `vb1 = x1 - x2`, `vb2 = x3 - x2`, `vb3 = x4 - x3`.
    fn compute(&self, dtype: usize, vb1: Vec3, vb2: Vec3, vb3: Vec3) -> DihedralForces;
    /// Apply a batch of dihedrals (monomorphised per style, so `compute` inlines).
    fn apply(&self, entries: &[Entry<4>], k: &Kernels, f: &mut AtomsMut<Vec3>, t: &mut BondedTally) {
        crate::models::bonded::pass::apply_dihedrals(self, entries, k, f, t)
    }
    fn coeff_words(&self, dtype: usize) -> String;
}

// ---------------------------------------------------------------------------------------
// Virial (LAMMPS Bond/Angle/Dihedral::ev_tally, newton_bond on or all atoms owned)

/// A bond's virial: `del_a * del_b * fbond`.
pub fn bond_virial(del: Vec3, fbond: f64) -> Virial {
    let [x, y, z] = del;
    [x * x * fbond, y * y * fbond, z * z * fbond, x * y * fbond, x * z * fbond, y * z * fbond]
}

/// An angle's virial: `del1 (x) f1 + del2 (x) f3`.
pub fn angle_virial(del1: Vec3, del2: Vec3, f1: Vec3, f3: Vec3) -> Virial {
    [
        del1[0] * f1[0] + del2[0] * f3[0],
        del1[1] * f1[1] + del2[1] * f3[1],
        del1[2] * f1[2] + del2[2] * f3[2],
        del1[0] * f1[1] + del2[0] * f3[1],
        del1[0] * f1[2] + del2[0] * f3[2],
        del1[1] * f1[2] + del2[1] * f3[2],
    ]
}

/// A dihedral's virial: `vb1 (x) f1 + vb2 (x) f3 + (vb3 + vb2) (x) f4`.
pub fn dihedral_virial(vb1: Vec3, vb2: Vec3, vb3: Vec3, f1: Vec3, f3: Vec3, f4: Vec3) -> Virial {
    let t = |a: usize, b: usize| vb1[a] * f1[b] + vb2[a] * f3[b] + (vb3[a] + vb2[a]) * f4[b];
    [t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(0, 2), t(1, 2)]
}

// ---------------------------------------------------------------------------------------
// Registries: adding a style touches one list.

type BondCtor = fn() -> Box<dyn BondStyle>;
type AngleCtor = fn() -> Box<dyn AngleStyle>;
type DihedralCtor = fn() -> Box<dyn DihedralStyle>;

const BOND_STYLES: &[(&str, BondCtor)] = &[
    ("harmonic", || Box::new(bond_harmonic::BondHarmonic::default())),
    ("zero", || Box::new(bond_zero::BondZero::default())),
    ("fene", || Box::new(bond_fene::BondFene::default())),
    ("fene/expand", || Box::new(bond_fene_expand::BondFeneExpand::default())),
    ("morse", || Box::new(bond_morse::BondMorse::default())),
    ("bpm/spring", || Box::new(bond_bpm_spring::BondBpmSpring::default())),
    ("bpm/spring/plastic", || Box::new(bond_bpm_spring_plastic::BondBpmSpringPlastic::default())),
    ("bpm/rotational", || Box::new(bond_bpm_rotational::BondBpmRotational::default())),
];
const ANGLE_STYLES: &[(&str, AngleCtor)] = &[("harmonic", || Box::new(angle_harmonic::AngleHarmonic::default()))];
const DIHEDRAL_STYLES: &[(&str, DihedralCtor)] = &[
    ("harmonic", || Box::new(dihedral_harmonic::DihedralHarmonic::default())),
    ("quadratic", || Box::new(dihedral_quadratic::DihedralQuadratic::default())),
];

pub fn new_bond_style(name: &str) -> Option<Box<dyn BondStyle>> {
    BOND_STYLES.iter().find(|(n, _)| *n == name).map(|(_, c)| c())
}
pub fn new_angle_style(name: &str) -> Option<Box<dyn AngleStyle>> {
    ANGLE_STYLES.iter().find(|(n, _)| *n == name).map(|(_, c)| c())
}
pub fn new_dihedral_style(name: &str) -> Option<Box<dyn DihedralStyle>> {
    DIHEDRAL_STYLES.iter().find(|(n, _)| *n == name).map(|(_, c)| c())
}
/// Names of the supported styles (for "did you mean" and the supported-command table).
pub fn bond_style_names() -> impl Iterator<Item = &'static str> {
    BOND_STYLES.iter().map(|(n, _)| *n)
}
pub fn angle_style_names() -> impl Iterator<Item = &'static str> {
    ANGLE_STYLES.iter().map(|(n, _)| *n)
}
pub fn dihedral_style_names() -> impl Iterator<Item = &'static str> {
    DIHEDRAL_STYLES.iter().map(|(n, _)| *n)
}

// ---------------------------------------------------------------------------------------
// Helpers shared by the styles

/// Per-type parameters with LAMMPS' `setflag`: index 0 is unused, types are `1..=n`.
#[derive(Clone, Debug)]
pub struct TypeTable<P> {
    slots: Vec<Option<P>>,
}

impl<P> Default for TypeTable<P> {
    fn default() -> Self {
        TypeTable { slots: Vec::new() }
    }
}

impl<P: Clone> TypeTable<P> {
    /// `n` types, none set.
    /// Make room for types 1..=n, keeping the coefficients already set.
    pub fn resize(&mut self, n: usize) {
        self.slots.resize(n + 1, None);
    }
    pub fn ntypes(&self) -> usize {
        self.slots.len().saturating_sub(1)
    }
    /// Set types `lo..=hi` (the caller has checked the range against `ntypes`).
    pub fn set(&mut self, lo: usize, hi: usize, p: P) {
        for t in lo..=hi {
            if let Some(slot) = self.slots.get_mut(t) {
                *slot = Some(p.clone());
            }
        }
    }
    /// The parameters of type `t`. The engine only evaluates types whose coefficients are
    /// set (it calls `check_all_set` before a run), so a miss is a bug, not user input.
    pub fn get(&self, t: usize) -> &P {
        match self.slots.get(t) {
            Some(Some(p)) => p,
            _ => panic!("bonded type {t} used without coefficients"),
        }
    }
    pub fn try_get(&self, t: usize) -> Option<&P> {
        self.slots.get(t).and_then(|p| p.as_ref())
    }
    /// LAMMPS' check before a run: every type must be set. `kind` is "Bond", "Angle", ...
    pub fn check_all_set(&self, kind: &str) -> Result<(), String> {
        let missing: Vec<String> =
            (1..self.slots.len()).filter(|&t| self.slots[t].is_none()).map(|t| t.to_string()).collect();
        if missing.is_empty() {
            Ok(())
        } else {
            Err(format!(
                "All {} coeffs are not set (missing for type{} {})",
                kind.to_lowercase(),
                if missing.len() > 1 { "s" } else { "" },
                missing.join(", ")
            ))
        }
    }
}

/// A number as C's `printf("%g")` writes it (what LAMMPS' `write_data` uses for coefficients).
pub fn fmt_g(x: f64) -> String {
    if x.is_nan() {
        return if x.is_sign_negative() { "-nan".into() } else { "nan".into() };
    }
    if x.is_infinite() {
        return if x < 0.0 { "-inf".into() } else { "inf".into() };
    }
    if x == 0.0 {
        return if x.is_sign_negative() { "-0".into() } else { "0".into() };
    }
    const P: i32 = 6;
    // The exponent after rounding to P significant digits decides between %e and %f.
    let e_form = format!("{:.*e}", (P - 1) as usize, x);
    let (mantissa, exp) = e_form.split_once('e').unwrap_or((&e_form, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let strip = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if !(-4..P).contains(&exp) {
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{}e{}{:02}", strip(mantissa), sign, exp.abs())
    } else {
        strip(&format!("{:.*}", (P - 1 - exp) as usize, x))
    }
}

#[cfg(test)]
pub(crate) mod test_util {
    use dmhs_parser::{Span, Word};

    /// The words of a coefficient line, as the parser would hand them over.
    pub fn words(s: &str) -> Vec<Word> {
        let mut out = vec![];
        let mut pos = 0;
        for t in s.split_whitespace() {
            let lo = s[pos..].find(t).unwrap() + pos;
            out.push(Word::new(t, Span::new(Default::default(), lo, lo + t.len())));
            pos = lo + t.len();
        }
        out
    }

    /// A bond style of one type, set up from the words of `bond_style NAME settings...` and
    /// `bond_coeff 1 coeff...`.
    pub fn configured<S: super::BondStyle + Default>(settings: &str, coeff: &str) -> S {
        let mut s = S::default();
        let w = words(settings);
        s.settings(&mut dmhs_parser::Args::from_words(&w, Span::default(), "")).unwrap();
        s.set_types(1);
        let w = words(coeff);
        s.coeff(1, 1, &mut dmhs_parser::Args::from_words(&w, Span::default(), "")).unwrap();
        s
    }

    pub fn bits3(v: [f64; 3]) -> [u64; 3] {
        v.map(f64::to_bits)
    }
    pub fn bits6(v: [f64; 6]) -> [u64; 6] {
        v.map(f64::to_bits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn printf_g_matches_c() {
        // expected strings are what C's printf("%g") prints
        let cases = [
            (100.0, "100"),
            (1.0, "1"),
            (0.5, "0.5"),
            (109.47, "109.47"),
            (123456.0, "123456"),
            (1234567.0, "1.23457e+06"),
            (0.0001, "0.0001"),
            (0.00001234, "1.234e-05"),
            (-2.5e-300, "-2.5e-300"),
            (180.00000000000003, "180"),
            (99999.95, "99999.9"),
            (999999.5, "1e+06"),
            (0.0, "0"),
            (-7.0, "-7"),
        ];
        for (x, s) in cases {
            assert_eq!(fmt_g(x), s, "{x}");
        }
    }

    #[test]
    fn registry_finds_styles() {
        assert_eq!(new_bond_style("harmonic").unwrap().name(), "harmonic");
        assert_eq!(new_angle_style("harmonic").unwrap().name(), "harmonic");
        assert_eq!(new_dihedral_style("quadratic").unwrap().name(), "quadratic");
        assert_eq!(new_bond_style("fene/expand").unwrap().name(), "fene/expand");
        assert!(new_bond_style("fene/nm").is_none());
        assert_eq!(dihedral_style_names().collect::<Vec<_>>(), vec!["harmonic", "quadratic"]);
    }

    #[test]
    fn deg2rad_is_lammps_constant() {
        assert_eq!(DEG2RAD.to_bits(), 0.017453292519943295f64.to_bits());
        assert_eq!(RAD2DEG.to_bits(), 57.29577951308232f64.to_bits());
    }

    #[test]
    fn type_table_reports_missing_types() {
        let mut t: TypeTable<f64> = TypeTable::default();
        t.resize(3);
        t.set(2, 2, 1.0);
        let e = t.check_all_set("Bond").unwrap_err();
        assert_eq!(e, "All bond coeffs are not set (missing for types 1, 3)");
        t.set(1, 3, 2.0);
        assert!(t.check_all_set("Bond").is_ok());
    }
}
