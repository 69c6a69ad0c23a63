//! `pair_style dmhs/heatconduction [kernel K]` — the paper's SPH heat conduction (Alexiadis 2015,
//! Eq 22), driven by temperature differences with a conductivity per particle kind:
//!
//!   m_i de_i/dt = sum_j m_i m_j/(rho_i rho_j) (kappa_i + kappa_j) (T_i - T_j) wfd_ij
//!
//! (wfd = (1/r) dW/dr < 0, so heat flows from hot to cold; `r_ij . grad_j W / r^2` of the paper
//! is `-wfd`). As in LAMMPS' SPH package `esph` is the particle's internal energy E = m e
//! (extensive; e is the paper's specific energy), so the style adds dE_i/dt = m_i de_i/dt to
//! desph; the exchange is antisymmetric, so sum_i esph_i is conserved to round-off (and the
//! work of LAMMPS' SPH momentum styles, added to esph in the same units, keeps KE + sum esph
//! conserved).
//!
//! `pair_coeff I J kappa h`: kappa is the pair's mean conductivity (kappa_i + kappa_j)/2, h the
//! kernel support. Unset I != J pairs mix arithmetically from I I and J J (kappa and h), which
//! gives exactly the paper's kappa_i + kappa_j; give I J explicitly for another rule (e.g. the
//! harmonic mean 2 kappa_i kappa_j/(kappa_i + kappa_j) of Cleary and Monaghan).
//!
//! T_i: the per-atom field `dmhs/T` when a `fix dmhs/phase` publishes it (Eq 24 with latent
//! heat), else esph/cv (Eq 23 with e_0 = T_0 = 0; cv is the particle's heat capacity m c_v, as
//! compute sph/t/atom reads it). m is the atom's mass (rmass with sphere).
//! Relation to LAMMPS' sph/heatconduction: for one material with constant c_v and equal masses
//! both give the same rates when D = kappa/(rho c_v) (c_v specific); LAMMPS drives the flux by esph
//! differences, which is wrong across a latent-heat plateau and between materials of different
//! c_v, hence this style.

use super::sph::{compute_sph, lanes, parse_kernel, Batch, Kernel, Packed, PairTable, SphContribution, SphKernel, Support, SupportLanes, LANES};
use super::{PairInput, PairModify, PairOutput, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style dmhs/heatconduction [kernel lucy|cubic|wendland2]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J kappa h   (kappa: conductivity, mean of the pair; h: kernel support)";

pub struct DmhsHeatConduction {
    kernel: Kernel,
    /// (kappa, h) per pair as given
    given: PairTable<(f64, f64)>,
    /// after mixing
    pairs: PairTable<(f64, f64)>,
    cutsq: Vec<f64>,
    n: usize,
    dim3: bool,
}

impl DmhsHeatConduction {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let kernel = parse_kernel(&mut a)?;
        Ok(DmhsHeatConduction { kernel, given: PairTable::empty(), pairs: PairTable::empty(), cutsq: vec![], n: 0, dim3: true })
    }
}

/// Temperature of atom `i`: the published field, else esph/cv (0 where cv = 0).
#[inline(always)]
pub fn temperature(atoms: &crate::engine::atoms::Atoms, field: Option<usize>, i: usize) -> f64 {
    match field {
        Some(k) => atoms.extra[k].data[i],
        None => {
            let cv = atoms.cv[i];
            if cv > 0.0 { atoms.esph[i] / cv } else { 0.0 }
        }
    }
}

impl SphKernel for DmhsHeatConduction {
    /// a = rho, b = T, v[0] = mass.
    #[inline(always)]
    fn pack(&self, input: &PairInput, i: usize) -> Packed {
        let a = input.atoms;
        let field = a.field(crate::engine::fields::TEMPERATURE);
        Packed { x: a.x[i], v: [a.mass(i, input.type_mass), 0.0, 0.0], a: a.rho[i], b: temperature(a, field, i) }
    }
    #[inline(always)]
    fn cutsq_row(&self, ti: usize) -> &[f64] {
        &self.cutsq[ti * (self.n + 1)..(ti + 1) * (self.n + 1)]
    }
    #[inline(always)]
    fn pair_lanes<const D: usize>(&self, _input: &PairInput, pi: &Packed, ti: usize, b: &Batch<D>) -> SphContribution<D> {
        let kh: [(f64, f64); LANES] = std::array::from_fn(|l| *self.pairs.get(ti, b.tj[l]));
        let sup = SupportLanes::gather(|l| Support::new(kh[l].1));
        let wfd = self.kernel.wfd_lanes(&b.r, &sup, self.dim3);
        // dE_i = m_i m_j (kappa_i + kappa_j)(T_i - T_j) wfd / (rho_i rho_j) = -dE_j
        let de = lanes(|l| pi.v[0] * b.v[0][l] * (2.0 * kh[l].0 * (pi.b - b.b[l]) * wfd[l] / (pi.a * b.a[l])));
        SphContribution { de_i: de, de_j: lanes(|l| -de[l]), ..SphContribution::default() }
    }
}

impl PairStyle for DmhsHeatConduction {
    fn style(&self) -> &str {
        "dmhs/heatconduction"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = COEFF_SYNTAX;
        let k = args.f64("kappa (thermal conductivity)")?;
        let h = args.positive_f64("h (kernel support)")?;
        args.finish()?;
        self.given.put_range(ilo, ihi, jlo, jhi, (k, h)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        Ok(())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.given.grow(ntypes)?;
        let mut p = PairTable::new(ntypes)?;
        for i in 1..=ntypes {
            for j in i..=ntypes {
                if active.map(|a| !a[i * (ntypes + 1) + j]).unwrap_or(false) {
                    continue;
                }
                if self.given.is_set(i, j) {
                    p.put(i, j, *self.given.get(i, j));
                } else if self.given.is_set(i, i) && self.given.is_set(j, j) {
                    let (a, b) = (self.given.get(i, i), self.given.get(j, j));
                    p.put(i, j, (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1)));
                } else {
                    return Err(format!("pair dmhs/heatconduction coefficients for types {i} {j} are not set (give I J, or I I and J J to mix)"));
                }
            }
        }
        self.pairs = p;
        self.n = ntypes;
        self.cutsq = super::sph_cutsq(&self.pairs, ntypes, active, |p| p.1)?;
        Ok(())
    }
    fn init_sim(&mut self, setup: &super::PairSetup) -> Result<(), String> {
        super::sph::check_setup(setup, self.style())
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        self.cutsq.get(it * (self.n + 1) + jt).map(|c| c.sqrt()).unwrap_or(0.0)
    }
    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        self.dim3 = input.dimension == 3;
        compute_sph(self, input, out);
        Tally::default()
    }
    fn describe(&self) -> String {
        format!("dmhs/heatconduction (kernel {})", self.kernel.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::atoms::{AtomFeatures, Atoms, NewAtom};

    /// Two particles: the rate follows Eq 22 term by term and m e is exchanged antisymmetrically.
    #[test]
    fn two_particles_follow_eq22() {
        let mut atoms = Atoms::new(AtomFeatures { sph: true, ..Default::default() });
        for (k, (t, x, e, cv)) in [(1usize, 0.0, 300.0, 2.0), (2, 0.3, 50.0, 1.0)].into_iter().enumerate() {
            let mut n = NewAtom::at(k as i64 + 1, t, [x, 0.0, 0.0]);
            n.rho = [1000.0, 1500.0][k];
            n.esph = e;
            n.cv = cv;
            atoms.push(&n);
        }
        let type_mass = vec![0.0, 2.0, 5.0];
        let mut hc = DmhsHeatConduction { kernel: Kernel::Lucy, given: PairTable::empty(), pairs: PairTable::empty(), cutsq: vec![], n: 0, dim3: true };
        hc.given.grow(2).unwrap();
        hc.given.put(1, 1, (1.0, 1.0));
        hc.given.put(2, 2, (3.0, 0.6));
        hc.init(2, &PairModify::default(), None).unwrap();
        // mixed: kappa 2, h 0.8
        assert_eq!(*hc.pairs.get(1, 2), (2.0, 0.8));
        let mut nb = crate::engine::neighbor::Neighbor::default();
        let dom = crate::engine::domain::Domain::new(3, [-5.0; 3], [5.0; 3], [[crate::engine::domain::BoundaryKind::Fixed; 2]; 3]);
        let settings = crate::engine::neighbor::NeighborSettings::new(0.1);
        let cut = |i: usize, j: usize| hc.cutoff(i, j);
        nb.build(&mut atoms, &dom, &settings, 2, &cut, false, &Default::default()).unwrap();
        let (mut f, mut tq, mut drho, mut de) = (vec![[0.0; 3]; 2], vec![], vec![0.0; 2], vec![0.0; 2]);
        let input = PairInput {
            atoms: &atoms,
            list: &nb.list,
            special_lj: [1.0; 4],
            special_coul: [1.0; 4],
            eflag: false,
            ntypes: 2,
            type_filter: None,
            type_mass: &type_mass,
            dt: 1.0,
            step: 0,
            advance: true,
            dimension: 3,
            newton_pair: true,
            sides: None,
            rigid_mass: None,
            freeze_bit: 0,
        };
        let mut out = PairOutput { f: &mut f, torque: &mut tq, drho: &mut drho, desph: &mut de, fields: vec![], peratom: None };
        hc.compute(&input, &mut out);
        // T1 = 150, T2 = 50; wfd for Lucy 3D at r = 0.3, h = 0.8
        let wfd = Kernel::Lucy.wfd(0.09, 0.8, true);
        let q = 2.0 * 5.0 * (1.0 + 3.0) * (150.0 - 50.0) * wfd / (1000.0 * 1500.0);
        let i0 = atoms.tag.iter().position(|&t| t == 1).unwrap();
        let i1 = 1 - i0;
        assert!((de[i0] - q).abs() <= 1e-14 * q.abs(), "{} vs {}", de[i0], q);
        assert!(de[i0] < 0.0, "the hot particle cools");
        assert_eq!(de[i0], -de[i1], "sum of dE = 0");
        assert_eq!(f[0], [0.0; 3]);
    }
}
