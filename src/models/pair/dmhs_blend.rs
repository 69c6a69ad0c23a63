//! `pair_style dmhs/blend Kn Kt gamma_n gamma_t xmu dampflag [limit_damping] [history]` with
//! `pair_coeff I J rho0 c0 mu h` — gradual SPH-to-DEM mixing with temperature (Alexiadis 2015,
//! lava flow, Fig 13B): each pair force is a weighted sum of an SPH force and a DEM contact force,
//!   F_ij = w_ij F_SPH,ij + (1 - w_ij) F_DEM,ij,   w_ij = (phi_i + phi_j)/2,
//! where phi is the per-atom liquid weight `dmhs/phi` published by `fix dmhs/phase ... mix Tlow
//! Thigh` (phi = 1 above Thigh: SPH only; 0 below Tlow: DEM only; linear in T between; without
//! the field phi = 1). The pair weight is symmetric, so Newton's third law and momentum hold.
//!
//! F_SPH is sph/taitwater/morris with the pair_coeff values (Tait EOS + Morris viscosity, per-type
//! mass, velocity estimates; drho and de are weighted by w_ij too). F_DEM is gran/hooke with the
//! pair_style values (Hookean normal spring-dashpot, tangential damping limited by friction,
//! contact when r < R_i + R_j; per-atom rmass and radius), torques weighted by 1 - w_ij. With
//! `history` it is gran/hooke/history instead: a tangential spring Kt on the accumulated shear
//! displacement, capped by Coulomb friction (the paper's Eq 17; the formula: [`super::classic`]),
//! kept per contact while the pair overlaps and has a DEM part (w_ij < 1), forgotten when either
//! ends. Kt must then be positive.
//! Needs atom_style hybrid sph sphere. Pairs are evaluated one at a time (no lanes): this style
//! is for the blended particles; pure-SPH and pure-DEM pairs run faster with their own styles
//! under hybrid/overlay. No special-bond weights apply.

use super::contact::{effective_mass, Contact, ContactModel};
use super::classic::Classic;
use super::gran_hooke_history::rebuild_history;
use crate::engine::contact_history::ContactHistory;
use super::sph::{Batch, SphKernel, L};
use super::sph_taitwater_morris::SphTaitwaterMorris;
use super::{compute_pairs, PairInput, PairKernel, PairModify, PairOutput, PairResult, PairSetup, PairStyle, Tally};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style dmhs/blend Kn Kt gamma_n gamma_t xmu dampflag [limit_damping] [history] [kernel K] [pmin P]";

pub struct DmhsBlend {
    sph: SphTaitwaterMorris,
    dem: Classic,
    /// The tangential springs of the contacts (`history`: gran/hooke/history's three values).
    history: Option<ContactHistory>,
    /// Largest radius per type (index 0 unused), for the contact cutoff.
    maxrad: Vec<f64>,
    n: usize,
}

impl DmhsBlend {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Self> {
        // `kernel K` and `pmin P` (dmhs extensions of the SPH part) may follow the DEM values
        let k = args.iter().position(|w| w.text == "kernel" || w.text == "pmin").unwrap_or(args.len());
        // `history` (like limit_damping, after the six numbers) selects the tangential spring
        let located = Args::from_words(args, cmd.span, SYNTAX);
        if let Some(w) = args.get(6..k).into_iter().flatten().find(|w| w.text != "history" && w.text != "limit_damping") {
            return Err(located.unknown_keyword(w, &["limit_damping", "history", "kernel", "pmin"]));
        }
        let hist_at: Vec<usize> = (6..k).filter(|&n| args[n].text == "history").collect();
        if let Some(&second) = hist_at.get(1) {
            return Err(located.error_at(&args[second], "`history` given twice", "second `history`"));
        }
        let words: Vec<Word> = args[..k].iter().enumerate().filter(|(n, _)| !hist_at.contains(n)).map(|(_, w)| w.clone()).collect();
        let dem = Classic::from_lammps(&words, cmd, SYNTAX, false)?;
        let history = (!hist_at.is_empty()).then(|| ContactHistory::new(3));
        if history.is_some() && !(dem.kt > 0.0) {
            // the Coulomb cap sets the spring back by dividing by Kt (LAMMPS' gran/hooke/history)
            return Err(located.error_at(&args[1], format!("Kt must be > 0 with `history` (the tangential spring), got {}", dem.kt), "Kt"));
        }
        let sph = SphTaitwaterMorris::from_lammps(&args[k..], cmd)?;
        Ok(DmhsBlend { sph, dem, history, maxrad: vec![], n: 0 })
    }
}

/// The blended pair kernel of one force evaluation: the two models and the liquid weights.
struct Blended<'a> {
    sph: &'a SphTaitwaterMorris,
    dem: &'a Classic,
    phi: Option<&'a [f64]>,
}

impl Blended<'_> {
    /// The pair; `hist` (with `history`) is the contact's shear displacement, `touch` whether it
    /// is in DEM contact.
    fn blend(&self, input: &PairInput, i: usize, j: usize, del: [f64; 3], rsq: f64, hist: Option<&mut [f64]>, touch: &mut bool) -> Option<PairResult> {
        let (sph, dem) = (self.sph, self.dem);
        let a = input.atoms;
        let (ti, tj) = (a.typ[i], a.typ[j]);
        let weight = |k: usize| self.phi.map(|p| p[k]).unwrap_or(1.0);
        let w = 0.5 * (weight(i) + weight(j));
        let fluid = w > 0.0 && rsq < sph.cutsq_row(ti)[tj];
        let (ri, rj) = (a.radius[i], a.radius[j]);
        let solid = w < 1.0 && rsq < (ri + rj) * (ri + rj);
        *touch = solid;
        if !fluid && !solid {
            return None;
        }
        let mut r = PairResult::default();
        if fluid {
            let (pi, pj) = (sph.pack(input, i), sph.pack(input, j));
            let b: Batch<3> = Batch {
                i,
                j: [j; 4],
                tj: [tj; 4],
                m: L::splat(input.type_mass[tj]),
                del: [L::splat(del[0]), L::splat(del[1]), L::splat(del[2])],
                rsq: L::splat(rsq),
                r: L::splat(rsq.sqrt()),
                v: [L::splat(pj.v[0]), L::splat(pj.v[1]), L::splat(pj.v[2])],
                a: L::splat(pj.a),
                b: L::splat(pj.b),
            };
            let c = sph.pair_lanes(input, &pi, ti, &b);
            for k in 0..3 {
                r.f[k] += w * c.f[k][0];
            }
            r.rate_i = [w * c.drho_i[0], w * c.de_i[0]];
            r.rate_j = [w * c.drho_j[0], w * c.de_j[0]];
        }
        if solid {
            let c = Contact { del, rsq, radi: ri, radj: rj, vi: &a.v[i], vj: &a.v[j], omegai: &a.omega[i], omegaj: &a.omega[j], meff: effective_mass(a.rmass[i], a.rmass[j], input.frozen(i), input.frozen(j)) };
            let cf = match hist {
                Some(h) => <Classic as ContactModel>::contact(dem, &c, h, input.advance, input.dt),
                None => dem.without_history(&c),
            };
            let u = 1.0 - w;
            for k in 0..3 {
                r.f[k] += u * cf.f[k];
                r.ti[k] = u * cf.ti[k];
                r.tj[k] = u * cf.tj[k];
            }
        }
        Some(r)
    }
}

impl PairKernel for Blended<'_> {
    fn pair(&self, input: &PairInput, i: usize, j: usize, del: [f64; 3], rsq: f64, _factor: f64) -> Option<PairResult> {
        self.blend(input, i, j, del, rsq, None, &mut false)
    }
    fn pair_with_history(&self, input: &PairInput, i: usize, j: usize, del: [f64; 3], rsq: f64, _factor: f64, hist: &mut [f64], touch: &mut bool) -> Option<PairResult> {
        self.blend(input, i, j, del, rsq, Some(hist), touch)
    }
}

impl PairStyle for DmhsBlend {
    fn style(&self) -> &str {
        "dmhs/blend"
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        self.sph.coeff(ilo, ihi, jlo, jhi, args)
    }
    fn init_sim(&mut self, setup: &PairSetup) -> Result<(), String> {
        let a = setup.atoms;
        if !a.features.sphere || !a.features.sph {
            return Err("pair dmhs/blend needs SPH and sphere attributes (atom_style hybrid sph sphere)".into());
        }
        self.maxrad = setup.max_radii(setup.ntypes);
        Ok(())
    }
    fn init(&mut self, ntypes: usize, modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.n = ntypes;
        self.maxrad.resize(ntypes + 1, 0.0);
        self.sph.init(ntypes, modify, active).map_err(|e| e.replace("sph/taitwater/morris", "dmhs/blend"))
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        let contact = self.maxrad.get(it).copied().unwrap_or(0.0) + self.maxrad.get(jt).copied().unwrap_or(0.0);
        self.sph.cutoff(it, jt).max(contact)
    }
    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        self.sph.set_dim3(input.dimension == 3);
        let a = input.atoms;
        let phi = a.field(crate::engine::fields::LIQUID_WEIGHT).map(|k| &a.extra[k].data[..]);
        compute_pairs(&Blended { sph: &self.sph, dem: &self.dem, phi }, input, out, self.history.as_mut())
    }
    fn rebuilt(&mut self, input: &PairInput, _order: &[usize]) {
        if let Some(h) = &mut self.history {
            rebuild_history(h, input);
        }
    }
    fn histories(&mut self) -> Vec<&mut ContactHistory> {
        self.history.iter_mut().collect()
    }
    fn needs_type_mass(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        let dem = if self.history.is_some() { "gran/hooke/history" } else { "gran/hooke" };
        format!("dmhs/blend: w sph/taitwater/morris + (1 - w) {}", self.dem.describe(dem))
    }
}
