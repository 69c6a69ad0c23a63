//! `fix ID group dmhs/cooling kT Tair [surface D NC]` — Newton cooling of free-surface particles
//! (Alexiadis 2015, Eq 25): dT/dt = -kT (T - Tair), applied as an energy rate
//!   de_i/dt += -kT c_i (T_i - Tair)
//! where c_i is the heat capacity of the particle's state (`dmhs/c` from fix dmhs/phase: cvs or
//! cvl; else the atom's cv) and T_i its temperature (`dmhs/T`, else esph/cv). Off the latent
//! plateau this is exactly Eq 25; on the plateau T = T* and the energy falls at the constant rate
//! kT cvl (T* - Tair). The rate is added to desph after the forces (post_force), so the SPH
//! integrator (fix sph or sph/stationary) of the atom applies it.
//!
//! `surface D NC`: only atoms with fewer than NC neighbours (atoms of any type within distance
//! D, itself excluded) cool; the paper uses D = h and NC = 5.5. Without it every group atom
//! cools. D must not exceed the neighbour cutoff (ghost atoms must cover it).
//!
//! Output: f_ID = number of cooling atoms on the last step; f_ID[1] the same, f_ID[2] the
//! energy removed so far, sum over steps of dt sum_i kT C_i (T_i - Tair) (trapezoid, as the
//! integrators apply it).

use super::{Fix, FixHooks};
use crate::sim::{RunError, Simulation};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};
use std::collections::HashMap;

pub const SYNTAX: &str = "fix ID group dmhs/cooling kT Tair [surface D NC]";

pub struct FixDmhsCooling {
    id: String,
    groupbit: u32,
    kt: f64,
    tair: f64,
    surface: Option<(f64, f64)>,
    ncool: usize,
    removed: f64,
    /// rate of energy loss at the previous force evaluation
    last_rate: f64,
}

impl FixDmhsCooling {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, sim: &Simulation) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if !sim.atoms.features.sph {
            return Err(Diagnostic::at(style.span, "fix dmhs/cooling needs an atom style with SPH attributes (atom_style sph or hybrid ... sph)", "atom style has no esph"));
        }
        let kt = a.non_negative_f64("kT (cooling rate, 1/time)")?;
        let tair = a.f64("Tair (temperature of the surrounding medium)")?;
        let mut surface = None;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "surface" => {
                    let d = a.positive_f64("D (coordination distance)")?;
                    let nc = a.positive_f64("NC (coordination threshold)")?;
                    surface = Some((d, nc));
                }
                _ => return Err(a.unknown_keyword(w, &["surface"])),
            }
        }
        Ok(FixDmhsCooling { id, groupbit, kt, tair, surface, ncool: 0, removed: 0.0, last_rate: 0.0 })
    }
}

impl FixDmhsCooling {
    /// Add the cooling rates to desph; returns the rate of energy loss sum_i kT C_i (T_i - Tair).
    fn apply(&mut self, sim: &mut Simulation) -> f64 {
        let coord = self.surface.map(|(d, _)| coordination(&sim.atoms, d));
        let kt_field = sim.atoms.find_extra(crate::pair::dmhs_heatconduction::T_FIELD);
        let kc_field = sim.atoms.find_extra(super::dmhs_phase::C_FIELD);
        let a = &mut sim.atoms;
        let mut n = 0;
        let mut rate = 0.0;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            if let (Some(c), Some((_, nc))) = (&coord, self.surface) {
                if c[i] as f64 >= nc {
                    continue;
                }
            }
            let t = crate::pair::dmhs_heatconduction::temperature(a, kt_field, i);
            let c = kc_field.map(|k| a.extra[k].data[i]).unwrap_or(a.cv[i]);
            let de = -self.kt * c * (t - self.tair);
            a.desph[i] += de;
            rate -= de;
            n += 1;
        }
        self.ncool = n;
        rate
    }
}

/// Number of atoms (owned or ghost, any type) within `d` of each owned atom, itself excluded.
pub fn coordination(atoms: &crate::atoms::Atoms, d: f64) -> Vec<u32> {
    let key = |x: &[f64; 3]| [(x[0] / d).floor() as i64, (x[1] / d).floor() as i64, (x[2] / d).floor() as i64];
    let mut bins: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for (k, x) in atoms.x.iter().enumerate() {
        bins.entry(key(x)).or_default().push(k as u32);
    }
    let dsq = d * d;
    (0..atoms.nlocal)
        .map(|i| {
            let xi = atoms.x[i];
            let b = key(&xi);
            let mut n = 0;
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        if let Some(list) = bins.get(&[b[0] + dx, b[1] + dy, b[2] + dz]) {
                            for &j in list {
                                let xj = atoms.x[j as usize];
                                let r = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
                                if j as usize != i && r[0] * r[0] + r[1] * r[1] + r[2] * r[2] < dsq {
                                    n += 1;
                                }
                            }
                        }
                    }
                }
            }
            n
        })
        .collect()
}

impl Fix for FixDmhsCooling {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "dmhs/cooling"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn init(&mut self, sim: &Simulation) -> Result<(), String> {
        if let Some((d, _)) = self.surface {
            let periodic = (0..sim.dimension).any(|k| sim.domain.as_ref().map(|dm| dm.periodic(k)).unwrap_or(false));
            let cut = sim.pair.as_ref().map(|p| (1..=sim.ntypes).flat_map(|i| (1..=sim.ntypes).map(move |j| (i, j))).map(|(i, j)| p.cutoff(i, j)).fold(0.0, f64::max)).unwrap_or(0.0) + sim.neigh_settings.skin;
            if periodic && d > cut {
                return Err(format!("the coordination distance {d} is longer than the neighbour cutoff {cut}: periodic images would be missed"));
            }
        }
        Ok(())
    }
    fn setup(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        self.last_rate = self.apply(sim);
        Ok(())
    }
    fn post_force(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        // the integrators apply each step's rate half before and half after it (trapezoid)
        let rate = self.apply(sim);
        self.removed += 0.5 * sim.dt * (self.last_rate + rate);
        self.last_rate = rate;
        Ok(())
    }
    fn scalar(&self, _sim: &Simulation) -> Option<f64> {
        Some(self.ncool as f64)
    }
    fn vector(&self, _sim: &Simulation, i: usize) -> Option<f64> {
        match i {
            1 => Some(self.ncool as f64),
            2 => Some(self.removed),
            _ => None,
        }
    }
    fn describe(&self) -> String {
        format!(
            "fix {} dmhs/cooling: dT/dt = -{} (T - {}){}",
            self.id,
            self.kt,
            self.tair,
            self.surface.map(|(d, nc)| format!(" on atoms with fewer than {nc} neighbours within {d}")).unwrap_or_default()
        )
    }
}
