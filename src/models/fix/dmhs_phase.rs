//! `fix ID group dmhs/phase Tstar T cvs Cs cvl Cl latent L liquid LT solid ST [bond BT cutoff RC]
//! [mix Tlow Thigh]` — solidification and melting with latent heat (Alexiadis 2015, Eq 24 and
//! the casting example).
//!
//! Equation of state (e = esph/m, the specific internal energy: esph is the particle's energy
//! m e as in LAMMPS' SPH package; e_0 = T_0 = 0):
//!   e_sol = cvs T*,  e_liq = e_sol + L
//!   T = e/cvs                      for e < e_sol          (solid)
//!   T = T*                         for e_sol <= e <= e_liq (transition plateau)
//!   T = T* + (e - e_liq)/cvl       for e > e_liq          (liquid)
//! The temperature of every atom is published in the per-atom field `dmhs/T` (ghosts too), read
//! by `pair_style dmhs/heatconduction` and `fix dmhs/cooling`; atoms outside the group get
//! esph/cv. The particle's heat capacity in its current state (m cvs below e_sol, m cvl above;
//! cv outside the group) goes to `dmhs/c`.
//!
//! Label and switch of models (checked at the end of every step, on group atoms):
//! - a liquid atom whose e falls below e_sol becomes solid: its type becomes ST (so the per-type
//!   pair styles treat it as DEM/CGMD) and, with `bond`, it creates a bond of type BT to every
//!   solid atom within RC. Atoms that solidify on the same step are handled in ID order, so a
//!   later one bonds to an earlier one. An atom that is already solid never creates bonds itself
//!   (it only receives them from newly solidified neighbours), as the paper's rule says.
//! - a solid atom whose e rises above e_liq melts: every bond, angle and dihedral it is part of
//!   is deleted and its type becomes LT (SPH).
//! Initial labels come from the types (ST: solid, LT: liquid). Type and topology changes ask for
//! a neighbour-list rebuild (and a special-list rebuild) on the next step.
//!
//! `mix Tlow Thigh`: the per-atom weight phi(T) = clamp((T - Tlow)/(Thigh - Tlow), 0, 1) of the
//! liquid (SPH) part, published as `dmhs/phi` for `pair_style dmhs/blend` (lava, Fig 13).
//! Without `mix`, phi = 1 for liquid and 0 for solid atoms.
//!
//! Output: f_ID = solid fraction (solid atoms / group atoms); f_ID[1..5] = solid fraction,
//! number of solid atoms, bonds created, bonds deleted (since the fix was defined), and the
//! solid fraction by enthalpy (mean over the group of clamp((e_liq - e)/L, 0, 1)), atoms on the
//! plateau (e_sol <= e <= e_liq: the transition zone), and the numbers of solidification and
//! melting events (since the fix was defined).
//! Per-atom: `compute ID group dmhs/phase/atom` (T, label, melt fraction, phi).

use super::{Fix, FixCtx, FixHooks};
use crate::engine::fields::{Field, HEAT_CAPACITY, LIQUID_WEIGHT, PHASE, TEMPERATURE};
use crate::engine::state::{RunError, State};
use crate::engine::topology::Bond;
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "fix ID group dmhs/phase Tstar T cvs Cs cvl Cl latent L liquid LT solid ST [bond BT cutoff RC] [mix Tlow Thigh]";


/// The phase-change equation of state (Eq 24).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseEos {
    pub tstar: f64,
    pub cvs: f64,
    pub cvl: f64,
    pub esol: f64,
    pub eliq: f64,
}

impl PhaseEos {
    pub fn new(tstar: f64, cvs: f64, cvl: f64, latent: f64) -> PhaseEos {
        let esol = cvs * tstar;
        PhaseEos { tstar, cvs, cvl, esol, eliq: esol + latent }
    }
    pub fn temperature(&self, e: f64) -> f64 {
        if e < self.esol {
            e / self.cvs
        } else if e <= self.eliq {
            self.tstar
        } else {
            self.tstar + (e - self.eliq) / self.cvl
        }
    }
    /// dE/dT of the current state (the liquid's on the plateau).
    pub fn capacity(&self, e: f64) -> f64 {
        if e < self.esol { self.cvs } else { self.cvl }
    }
    /// Inverse of [`PhaseEos::temperature`] off the plateau (for setting initial states).
    pub fn energy(&self, t: f64) -> f64 {
        if t < self.tstar { self.cvs * t } else { self.eliq + self.cvl * (t - self.tstar) }
    }
    /// Melt fraction by enthalpy: 0 below e_sol, 1 above e_liq, linear between.
    pub fn melt_fraction(&self, e: f64) -> f64 {
        let l = self.eliq - self.esol;
        if l <= 0.0 {
            return if e > self.esol { 1.0 } else { 0.0 };
        }
        ((e - self.esol) / l).clamp(0.0, 1.0)
    }
}

pub struct FixDmhsPhase {
    id: String,
    groupbit: u32,
    pub eos: PhaseEos,
    liquid: usize,
    solid: usize,
    bond: Option<(usize, f64)>,
    mix: Option<(f64, f64)>,
    created: u64,
    deleted: u64,
    /// atoms that became solid / liquid (since the fix was defined)
    frozen: u64,
    melted: u64,
}

impl FixDmhsPhase {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if !state.atoms.features.sph {
            return Err(Diagnostic::at(style.span, "fix dmhs/phase needs an atom style with SPH attributes (atom_style sph or hybrid ... sph)", "atom style has no esph").with_help(format!("syntax: {SYNTAX}")));
        }
        let nt = state.ntypes.max(1) as i64;
        let (mut tstar, mut cvs, mut cvl, mut latent, mut liquid, mut solid) = (None, None, None, None, None, None);
        let (mut bond, mut cutoff, mut mix) = (None, None, None);
        let mut bond_word = None;
        const KEYS: &[&str] = &["Tstar", "cvs", "cvl", "latent", "liquid", "solid", "bond", "cutoff", "mix"];
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "Tstar" => tstar = Some(a.f64("T* (transition temperature)")?),
                "cvs" => cvs = Some(a.positive_f64("cvs (heat capacity of the solid)")?),
                "cvl" => cvl = Some(a.positive_f64("cvl (heat capacity of the liquid)")?),
                "latent" => latent = Some(a.non_negative_f64("L (latent heat, e_liq - e_sol)")?),
                "liquid" => liquid = Some(a.i64_in("liquid atom type", 1, nt)? as usize),
                "solid" => solid = Some(a.i64_in("solid atom type", 1, nt)? as usize),
                "bond" => {
                    bond_word = Some(w);
                    bond = Some(a.i64_in("bond type", 1, i64::MAX)? as usize)
                }
                "cutoff" => cutoff = Some(a.positive_f64("bonding cut-off distance")?),
                "mix" => {
                    let lo = a.f64("Tlow (fully solid below)")?;
                    let hi = a.f64_where("Thigh (fully liquid above)", "> Tlow", |x| x > lo)?;
                    mix = Some((lo, hi));
                }
                _ => return Err(a.unknown_keyword(w, KEYS)),
            }
        }
        let need = |v: Option<f64>, k: &str| v.ok_or_else(|| Diagnostic::at(cmd.span, format!("fix dmhs/phase needs the keyword `{k}`"), "missing keyword").with_help(format!("syntax: {SYNTAX}")));
        let eos = PhaseEos::new(need(tstar, "Tstar")?, need(cvs, "cvs")?, need(cvl, "cvl")?, need(latent, "latent")?);
        let liquid = need(liquid.map(|x| x as f64), "liquid")? as usize;
        let solid = need(solid.map(|x| x as f64), "solid")? as usize;
        if liquid == solid {
            return Err(Diagnostic::at(cmd.span, "fix dmhs/phase: the liquid and solid types must differ", "same type").with_help(format!("syntax: {SYNTAX}")));
        }
        let bond = match (bond, cutoff) {
            (Some(b), Some(rc)) => {
                let w = bond_word.unwrap();
                if !state.atoms.features.bonds {
                    return Err(Diagnostic::at(w.span, "fix dmhs/phase bond needs an atom style with bonds (e.g. atom_style hybrid sph bond)", "atom style has no bonds"));
                }
                if b > state.topo.nbondtypes {
                    return Err(Diagnostic::at(w.span, format!("bond type {b} is larger than the number of bond types ({})", state.topo.nbondtypes), "no such bond type"));
                }
                Some((b, rc))
            }
            (None, None) => None,
            _ => return Err(Diagnostic::at(cmd.span, "fix dmhs/phase: `bond BT` and `cutoff RC` go together", "give both or neither").with_help(format!("syntax: {SYNTAX}"))),
        };
        // per-atom fields (registered with no ghosts present)
        state.atoms.clear_ghosts();
        state.lists_valid = false;
        for f in [TEMPERATURE, PHASE, HEAT_CAPACITY] {
            state.atoms.add_field(f);
        }
        if mix.is_some() {
            state.atoms.add_field(LIQUID_WEIGHT);
        }
        Ok(FixDmhsPhase { id, groupbit, eos, liquid, solid, bond, mix, created: 0, deleted: 0, frozen: 0, melted: 0 })
    }

    fn field(state: &State, f: Field) -> usize {
        state.atoms.field(f).expect("dmhs/phase fields are registered at definition")
    }

    /// Labels from the types (1 solid, 0 liquid).
    fn label_from_types(&self, state: &mut State) {
        let kl = Self::field(state, PHASE);
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                a.extra[kl].data[i] = if a.typ[i] == self.solid { 1.0 } else { 0.0 };
            }
        }
    }

    /// T, c (and phi) of owned atoms from their energies.
    fn update_fields(&self, state: &mut State) {
        let (kt, kc, kl) = (Self::field(state, TEMPERATURE), Self::field(state, HEAT_CAPACITY), Self::field(state, PHASE));
        let kp = state.atoms.field(LIQUID_WEIGHT);
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            let (t, c) = if a.mask[i] & self.groupbit != 0 {
                let m = a.mass(i, &state.type_mass);
                let e = a.esph[i] / m;
                (self.eos.temperature(e), m * self.eos.capacity(e))
            } else {
                let e = a.esph[i];
                let cv = a.cv[i];
                (if cv > 0.0 { e / cv } else { 0.0 }, cv)
            };
            a.extra[kt].data[i] = t;
            a.extra[kc].data[i] = c;
            if let Some(kp) = kp {
                let phi = match self.mix {
                    Some((lo, hi)) if a.mask[i] & self.groupbit != 0 => ((t - lo) / (hi - lo)).clamp(0.0, 1.0),
                    _ => 1.0 - a.extra[kl].data[i],
                };
                a.extra[kp].data[i] = phi;
            }
        }
    }

    /// Copy the ghost-carried fields to the existing ghosts (a distributed run: from their
    /// owners on the other ranks, these fields only).
    fn forward(state: &mut State) {
        if let (Some(d), Some(_), Some(domain)) = (&state.decomp, state.distributed, &state.domain) {
            let a = &mut state.atoms;
            d.forward_field(a, domain, |a| a.field_values(TEMPERATURE).unwrap_or(&[]), |a| Self::field_mut(a, TEMPERATURE));
            if a.field(LIQUID_WEIGHT).is_some() {
                d.forward_field(a, domain, |a| a.field_values(LIQUID_WEIGHT).unwrap_or(&[]), |a| Self::field_mut(a, LIQUID_WEIGHT));
            }
            return;
        }
        let a = &mut state.atoms;
        let n = a.nlocal;
        for f in [TEMPERATURE, LIQUID_WEIGHT] {
            if let Some(k) = a.field(f) {
                crate::engine::atoms::Atoms::forward_field(&mut a.extra[k].data, n, &a.ghost_owner);
            }
        }
    }

    fn field_mut(a: &mut crate::engine::atoms::Atoms, f: Field) -> &mut [f64] {
        let k = a.field(f).expect("dmhs/phase fields are registered at definition");
        &mut a.extra[k].data
    }

    /// Apply the solidification and melting rules. A distributed run's ranks each find their
    /// own atoms' events and every rank reads all of them (by ID), so the topology, which every
    /// rank keeps whole, and the counts stay the same on every rank.
    fn transitions(&mut self, state: &mut State) -> Result<(), RunError> {
        let kl = Self::field(state, PHASE);
        let a = &state.atoms;
        let mut freeze = vec![];
        let mut melt = vec![];
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let solid = a.extra[kl].data[i] != 0.0;
            let e = a.esph[i] / a.mass(i, &state.type_mass);
            if !solid && e < self.eos.esol {
                freeze.push(i);
            } else if solid && e > self.eos.eliq {
                melt.push(i);
            }
        }
        freeze.sort_by_key(|&i| a.tag[i]);
        // events by ID: freezing atoms positive, melting ones negative
        let events: Vec<f64> = freeze.iter().map(|&i| a.tag[i] as f64).chain(melt.iter().map(|&i| -a.tag[i] as f64)).collect();
        let events = state.allgather_ranks(events);
        if events.is_empty() {
            return Ok(());
        }
        let frozen: std::collections::HashSet<i64> = events.iter().filter(|&&t| t > 0.0).map(|&t| t as i64).collect();
        let melted: std::collections::HashSet<i64> = events.iter().filter(|&&t| t < 0.0).map(|&t| -t as i64).collect();
        let mut topo_changed = false;
        if !melted.is_empty() {
            let t = &mut state.topo;
            let before = t.bonds.len() + t.angles.len() + t.dihedrals.len();
            let nb = t.bonds.len();
            t.remove_atoms(&melted);
            self.deleted += (nb - t.bonds.len()) as u64;
            topo_changed |= t.bonds.len() + t.angles.len() + t.dihedrals.len() != before;
            self.melted += melted.len() as u64;
            for &i in &melt {
                state.atoms.extra[kl].data[i] = 0.0;
                state.atoms.typ[i] = self.liquid;
            }
        }
        self.frozen += frozen.len() as u64;
        // Newly solid atoms in ID order, each bonding to solid atoms within the cut-off: to the
        // atoms solid before (not melted now) and to those frozen now with a lower ID. Solid
        // means the solid type in the group (the label follows the type); ghosts of a
        // distributed run carry both. Every rank adds the new bonds in rank order.
        let mut new_bonds: Vec<f64> = vec![];
        if let Some((_, rc)) = self.bond {
            let domain = state.domain.as_ref().ok_or_else(|| RunError::new(state.step, "no simulation box"))?;
            let bonded: std::collections::HashSet<(i64, i64)> = state.topo.bonds.iter().map(|b| (b.atoms[0].min(b.atoms[1]), b.atoms[0].max(b.atoms[1]))).collect();
            let a = &state.atoms;
            // serial: the owned atoms at their nearest image; ranks: owned atoms and ghosts as placed
            let (nj, nearest) = if state.distributed.is_some() { (a.nall(), false) } else { (a.nlocal, true) };
            let mut mine: std::collections::HashSet<(i64, i64)> = std::collections::HashSet::new();
            for &i in &freeze {
                let (xi, ti) = (a.x[i], a.tag[i]);
                for j in 0..nj {
                    let tj = a.tag[j];
                    let solid = if melted.contains(&tj) {
                        false
                    } else if frozen.contains(&tj) {
                        tj < ti
                    } else {
                        a.mask[j] & self.groupbit != 0 && a.typ[j] == self.solid
                    };
                    if j == i || tj == ti || !solid {
                        continue;
                    }
                    let mut d = [xi[0] - a.x[j][0], xi[1] - a.x[j][1], xi[2] - a.x[j][2]];
                    if nearest {
                        domain.minimum_image(&mut d);
                    }
                    if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= rc * rc {
                        continue;
                    }
                    let key = (ti.min(tj), ti.max(tj));
                    if !bonded.contains(&key) && mine.insert(key) {
                        new_bonds.extend([ti as f64, tj as f64]);
                    }
                }
            }
        }
        let new_bonds = state.allgather_ranks(new_bonds);
        if let Some((btype, _)) = self.bond {
            // by the freezing atom's ID, then in the order found (the serial run's order of
            // bonds, which the scenes are sensitive to), each once
            let mut seen = std::collections::HashSet::new();
            let mut pairs: Vec<(i64, i64)> = new_bonds.chunks_exact(2).map(|p| (p[0] as i64, p[1] as i64)).filter(|&(p, q)| seen.insert((p.min(q), p.max(q)))).collect();
            pairs.sort_by_key(|p| p.0);
            self.created += pairs.len() as u64;
            topo_changed |= !pairs.is_empty();
            state.topo.bonds.extend(pairs.into_iter().map(|(ti, tj)| Bond::new(btype, [ti, tj])));
        }
        for &i in &freeze {
            state.atoms.extra[kl].data[i] = 1.0;
            state.atoms.typ[i] = self.solid;
        }
        if topo_changed {
            state.topology_changed();
        }
        // new types change cutoffs and ghost types: rebuild the lists on the next step
        state.rebuild_requested = true;
        Ok(())
    }

    /// (group atoms, solid-labelled atoms, solid fraction by enthalpy summed, atoms on the
    /// plateau e_sol <= e <= e_liq).
    fn counts(&self, state: &State) -> (f64, f64, f64, f64) {
        let kl = Self::field(state, PHASE);
        let a = &state.atoms;
        let (mut n, mut ns, mut fs, mut np) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let e = a.esph[i] / a.mass(i, &state.type_mass);
                n += 1.0;
                ns += a.extra[kl].data[i];
                fs += 1.0 - self.eos.melt_fraction(e);
                if e >= self.eos.esol && e <= self.eos.eliq {
                    np += 1.0;
                }
            }
        }
        let mut v = [n, ns, fs, np];
        state.sum_ranks(&mut v);
        (v[0], v[1], v[2], v[3])
    }
}

impl Fix for FixDmhsPhase {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "dmhs/phase"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_integrate: true, end_of_step: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        let a = &state.atoms;
        for t in [self.liquid, self.solid] {
            if t > state.ntypes {
                return Err(format!("atom type {t} does not exist ({} types)", state.ntypes));
            }
        }
        if let Some(i) = (0..a.nlocal).find(|&i| a.mask[i] & self.groupbit != 0 && a.typ[i] != self.liquid && a.typ[i] != self.solid) {
            return Err(format!("atom {} of the group has type {}, neither the liquid type {} nor the solid type {}", a.tag[i], a.typ[i], self.liquid, self.solid));
        }
        if self.bond.is_some() && ctx.bond_style.is_none() {
            return Err("bond needs a bond_style (e.g. bond_style harmonic) with coefficients for the bond type".into());
        }
        Ok(())
    }
    fn setup_pre_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.label_from_types(state);
        self.update_fields(state);
        Self::forward(state);
        Ok(())
    }
    /// After the first half step of e: the temperatures the forces of this step use.
    fn post_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.update_fields(state);
        Ok(())
    }
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.transitions(state)?;
        self.update_fields(state);
        Ok(())
    }
    fn scalar(&self, state: &State) -> Option<f64> {
        let (n, ns, _, _) = self.counts(state);
        Some(if n > 0.0 { ns / n } else { 0.0 })
    }
    fn vector(&self, state: &State, i: usize) -> Option<f64> {
        let (n, ns, fs, np) = self.counts(state);
        match i {
            1 => Some(if n > 0.0 { ns / n } else { 0.0 }),
            2 => Some(ns),
            3 => Some(self.created as f64),
            4 => Some(self.deleted as f64),
            5 => Some(if n > 0.0 { fs / n } else { 0.0 }),
            6 => Some(np),
            7 => Some(self.frozen as f64),
            8 => Some(self.melted as f64),
            _ => None,
        }
    }
    fn phase_eos(&self) -> Option<PhaseEos> {
        Some(self.eos)
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.clear_ghosts();
        state.lists_valid = false;
        for f in [TEMPERATURE, PHASE, HEAT_CAPACITY, LIQUID_WEIGHT] {
            state.atoms.remove_extra(f.name);
        }
    }
    fn describe(&self) -> String {
        let e = &self.eos;
        format!(
            "fix {} dmhs/phase: T* {} cvs {} cvl {} e_sol {} e_liq {}, liquid type {} <-> solid type {}{}{}",
            self.id,
            e.tstar,
            e.cvs,
            e.cvl,
            e.esol,
            e.eliq,
            self.liquid,
            self.solid,
            self.bond.map(|(b, rc)| format!(", bonds of type {b} within {rc}")).unwrap_or_default(),
            self.mix.map(|(l, h)| format!(", SPH weight from T {l} to {h}")).unwrap_or_default()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eos_is_eq24_with_the_paper_numbers() {
        // casting example: e_sol = 50, e_liq = 100, cvs = 2, cvl = 1 -> T* = 25, L = 50
        let eos = PhaseEos::new(25.0, 2.0, 1.0, 50.0);
        assert_eq!((eos.esol, eos.eliq), (50.0, 100.0));
        assert_eq!(eos.temperature(20.0), 10.0);
        assert_eq!(eos.temperature(50.0), 25.0);
        assert_eq!(eos.temperature(75.0), 25.0);
        assert_eq!(eos.temperature(100.0), 25.0);
        assert_eq!(eos.temperature(175.0), 100.0);
        for t in [0.0, 10.0, 24.0, 26.0, 100.0] {
            assert!((eos.temperature(eos.energy(t)) - t).abs() < 1e-12);
        }
        assert_eq!(eos.melt_fraction(75.0), 0.5);
        assert_eq!(eos.capacity(49.0), 2.0);
        assert_eq!(eos.capacity(60.0), 1.0);
    }
}
