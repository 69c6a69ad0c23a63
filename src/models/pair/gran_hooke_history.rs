//! `pair_style gran/hooke/history Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]`: the
//! Hookean spring-dashpot contact with a tangential spring (shear history) and Coulomb friction,
//! as LAMMPS 2025 computes it (the formula: [`super::classic`]); `gran/hertz/history` (same
//! arguments) scales both forces by the Hertzian contact radius.
//!
//! Kt NULL = 2/7 Kn, gamma_t NULL = gamma_n/2, dampflag 0 = no tangential damping.
//! Special-bond weights scale the force and torques (LAMMPS 2025).

pub use super::classic::Classic;
use super::contact::{compute_contacts, Contact, ContactForce, ContactModel, LaneSrc, LanesOut};
use super::{PairInput, PairModify, PairOutput, PairSetup, PairStyle, Tally};
use crate::engine::contact_history::ContactHistory;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style gran/hooke/history Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]  (Kt, gamma_t may be NULL)";
pub const HERTZ_SYNTAX: &str = "pair_style gran/hertz/history Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]  (Kt, gamma_t may be NULL)";
pub const COEFF_SYNTAX: &str = "pair_coeff * *  (granular styles take no coefficients)";

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
    /// Alone, every I,I pair must be set (LAMMPS' Pair::init); as a sub-style of a hybrid, only
    /// its own pairs count, and one that pair_coeff did not name is mixed from I,I and J,J, which
    /// must then be set.
    pub fn check(&mut self, ntypes: usize, active: Option<&[bool]>, style: &str) -> Result<(), String> {
        self.grow(ntypes);
        for i in 1..=ntypes {
            let Some(a) = active else {
                if !self.is_set(i, i) {
                    return Err(format!("pair {style} coefficients for types {i} {i} are not set (use pair_coeff * *)"));
                }
                continue;
            };
            for j in i..=ntypes {
                if !a[i * (ntypes + 1) + j] || self.is_set(i, j) {
                    continue;
                }
                if let Some(t) = [i, j].into_iter().find(|&t| !self.is_set(t, t)) {
                    return Err(format!("pair {style} coefficients for types {i} {j} are not set, nor those of {t} {t} to mix them from"));
                }
            }
        }
        Ok(())
    }
    /// Largest radius per type over the owned atoms and the particles fixes will insert.
    pub fn init_radii(&mut self, setup: &PairSetup) {
        self.maxrad = setup.max_radii(self.ntypes.max(setup.ntypes));
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
    /// gran/hooke/history or gran/hertz/history
    style: &'static str,
    pub settings: Classic,
    types: GranTypes,
    history: ContactHistory,
}

impl GranHookeHistory {
    /// gran/hooke/history, or gran/hertz/history with `hertz`.
    pub fn from_lammps(args: &[Word], cmd: &Command, hertz: bool) -> DResult<GranHookeHistory> {
        let (style, syntax) = if hertz { ("gran/hertz/history", HERTZ_SYNTAX) } else { ("gran/hooke/history", SYNTAX) };
        let settings = Classic::from_lammps(args, cmd, syntax, hertz)?;
        Ok(GranHookeHistory { style, settings, types: GranTypes::default(), history: ContactHistory::new(3) })
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
    fn contact(p: &Classic, c: &Contact, hist: &mut [f64], update: bool, dt: f64) -> ContactForce {
        let mut shear = [hist[0], hist[1], hist[2]];
        let r = p.with_history(c, &mut shear, update, dt);
        hist.copy_from_slice(&shear);
        r
    }
    #[inline(always)]
    fn contact_lanes(&self, b: &LaneSrc, update: bool, dt: f64) -> LanesOut {
        let (vi, vj, wi, wj) = (b.v3(b.v, 0), b.v3(b.v, 1), b.v3(b.omega, 0), b.v3(b.omega, 1));
        let mut hist = b.hist::<3>();
        let force = self.with_history(&b.contact(&vi, &vj, &wi, &wj), &mut hist, update, dt);
        LanesOut::new(force, hist)
    }
}

impl PairStyle for GranHookeHistory {
    fn style(&self) -> &str {
        self.style
    }
    /// A Hookean stiffness (the Hertzian one grows with the overlap: no single value).
    fn contact_stiffness(&self) -> Option<f64> {
        (!self.settings.hertz).then_some(self.settings.kn)
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
        self.types.check(ntypes, active, self.style)
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
        compute_contacts(&self.settings, input, out, Some(&mut self.history))
    }
    fn rebuilt(&mut self, input: &PairInput, _order: &[usize]) {
        rebuild_history(&mut self.history, input);
    }
    fn histories(&mut self) -> Vec<&mut ContactHistory> {
        vec![&mut self.history]
    }
    fn describe(&self) -> String {
        self.settings.describe(self.style)
    }
    /// F_t (3), |F_t|, v_n (3), v_t (3): LAMMPS' svector.
    fn single_extra(&self) -> Option<usize> {
        Some(10)
    }
    /// LAMMPS' single: zero apart, else [`Classic::single`] with the stored shear (special
    /// weights are not applied, as in LAMMPS).
    fn single(&self, input: &PairInput, i: usize, j: usize, rsq: f64, _factor_coul: f64, _factor_lj: f64) -> Result<super::Single, String> {
        let mut out = super::Single::default();
        let a = input.atoms;
        let radsum = a.radius[i] + a.radius[j];
        if rsq >= radsum * radsum {
            return Ok(out);
        }
        let shear = self.history.entry(i, j).map_or([0.0; 3], |(_, h)| [h[0], h[1], h[2]]);
        let (ccel, extra) = self.settings.single(&super::contact::contact_of(input, i, j, rsq), shear);
        out.fpair = ccel;
        out.extra[..10].copy_from_slice(&extra);
        Ok(out)
    }
}

/// Carry a history store over a list rebuild: pairs that overlap now keep their contact.
pub fn rebuild_history(history: &mut ContactHistory, input: &PairInput) {
    let a = input.atoms;
    let (x, radius) = (&a.x, &a.radius);
    history.rebuilt(a, input.list, input.sides, |i, j| {
        let del = [x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]];
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        let radsum = radius[i] + radius[j];
        rsq < radsum * radsum
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::par::lanes::LANES;
    use crate::models::pair::contact::LaneSrc;
    use crate::models::pair::gran_hooke::NoHistory;

    /// A small deterministic generator (no dependencies).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    /// The vector kernels (with and without history) give exactly the bits of the one-pair
    /// kernels, in every branch (sticking, sliding, sliding with zero shear, clamped normal
    /// force, setup).
    #[test]
    fn lane_kernel_matches_scalar_kernel_bit_for_bit() {
        let mut rng = Lcg(12345);
        // xmu 0.01: every contact slides; 1000: every contact sticks; 0.3: both
        for (limit_damping, xmu) in [(false, 0.01), (false, 0.3), (false, 1000.0), (true, 0.3)] {
            let p = Classic { kn: 2.0e5, kt: 5.0e4, gamman: 300.0, gammat: 150.0, xmu, dampflag: true, limit_damping, hertz: false };
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
                    let mask = vec![0u32; n];
                    let src = LaneSrc {
                        n: LANES,
                        ij: [std::array::from_fn(|l| 2 * l), std::array::from_fn(|l| 2 * l + 1)],
                        e: std::array::from_fn(|l| l),
                        x: &x,
                        v: &v,
                        omega: &w,
                        radius: &rad,
                        rmass: &m,
                        mask: &mask,
                        freeze_bit: 0,
                        typ: &typ,
                        values: &values,
                        hsize: 3,
                    };
                    let out = p.contact_lanes(&src, update, 1e-4);
                    let out_without = NoHistory(p).contact_lanes(&src, update, 1e-4);
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
                            meff: m[i] * m[j] / (m[i] + m[j]),
                        };
                        let without = NoHistory::contact(&p, &c, &mut [], update, 1e-4);
                        for d in 0..3 {
                            assert_eq!(out_without.force.f[d][l].to_bits(), without.f[d].to_bits());
                            assert_eq!(out_without.force.ti[d][l].to_bits(), without.ti[d].to_bits());
                            assert_eq!(out_without.force.tj[d][l].to_bits(), without.tj[d].to_bits());
                        }
                        let mut h = [values[3 * l], values[3 * l + 1], values[3 * l + 2]];
                        let r = Classic::contact(&p, &c, &mut h, update, 1e-4);
                        for d in 0..3 {
                            assert_eq!(out.force.f[d][l].to_bits(), r.f[d].to_bits());
                            assert_eq!(out.force.ti[d][l].to_bits(), r.ti[d].to_bits());
                            assert_eq!(out.force.tj[d][l].to_bits(), r.tj[d].to_bits());
                            assert_eq!(out.hist[d][l].to_bits(), h[d].to_bits());
                        }
                    }
                }
            }
        }
    }
}
