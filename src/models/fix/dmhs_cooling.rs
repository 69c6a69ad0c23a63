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

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
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
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if !state.atoms.features.sph {
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
    fn apply(&mut self, state: &mut State) -> f64 {
        let coord = self.surface.map(|(d, _)| coordination(&state.atoms, d));
        let kt_field = state.atoms.field(crate::engine::fields::TEMPERATURE);
        let kc_field = state.atoms.field(crate::engine::fields::HEAT_CAPACITY);
        let a = &mut state.atoms;
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
            let t = crate::models::pair::dmhs_heatconduction::temperature(a, kt_field, i);
            let c = kc_field.map(|k| a.extra[k].data[i]).unwrap_or(a.cv[i]);
            let de = -self.kt * c * (t - self.tair);
            a.desph[i] += de;
            rate -= de;
            n += 1;
        }
        // a distributed run: the count and the rate of every rank
        let mut v = [n as f64, rate];
        state.sum_ranks(&mut v);
        self.ncool = v[0] as usize;
        v[1]
    }
}

/// Number of atoms (owned or ghost, any type) within `d` of each owned atom, itself excluded.
/// Atoms are binned in cells of side `d` (so neighbours lie in the 27 cells around an atom's own):
/// a dense grid over the atoms' bounding box (counting sort, no allocation per cell), or a hash map
/// of cells when a stray atom far away would make that grid large. Called every step, so speed
/// matters: the hash map alone took half of the lava scene's run time.
pub fn coordination(atoms: &crate::engine::atoms::Atoms, d: f64) -> Vec<u32> {
    let x = &atoms.x;
    if x.is_empty() {
        return vec![];
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in x {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let dims: Vec<f64> = (0..3).map(|k| ((hi[k] - lo[k]) / d).floor() + 1.0).collect();
    let ncell = dims[0] * dims[1] * dims[2];
    if !ncell.is_finite() || ncell > (8 * x.len() + 4096) as f64 {
        return coordination_hashed(atoms, d);
    }
    let n = [dims[0] as usize, dims[1] as usize, dims[2] as usize];
    let cell = |p: &[f64; 3]| -> [usize; 3] { [0, 1, 2].map(|k| (((p[k] - lo[k]) / d).floor() as usize).min(n[k] - 1)) };
    let flat = |c: [usize; 3]| (c[2] * n[1] + c[1]) * n[0] + c[0];
    // counting sort of atom indices by cell
    let mut start = vec![0u32; n[0] * n[1] * n[2] + 1];
    let cells: Vec<usize> = x.iter().map(|p| flat(cell(p))).collect();
    for &c in &cells {
        start[c + 1] += 1;
    }
    for c in 0..start.len() - 1 {
        start[c + 1] += start[c];
    }
    let mut fill = start.clone();
    let mut sorted = vec![0u32; x.len()];
    for (k, &c) in cells.iter().enumerate() {
        sorted[fill[c] as usize] = k as u32;
        fill[c] += 1;
    }
    let dsq = d * d;
    (0..atoms.nlocal)
        .map(|i| {
            let xi = x[i];
            let c = cell(&xi);
            let range = |k: usize| c[k].saturating_sub(1)..=(c[k] + 1).min(n[k] - 1);
            let mut count = 0;
            for cz in range(2) {
                for cy in range(1) {
                    for cx in range(0) {
                        let f = flat([cx, cy, cz]);
                        for &j in &sorted[start[f] as usize..start[f + 1] as usize] {
                            let xj = x[j as usize];
                            let r = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
                            if j as usize != i && r[0] * r[0] + r[1] * r[1] + r[2] * r[2] < dsq {
                                count += 1;
                            }
                        }
                    }
                }
            }
            count
        })
        .collect()
}

/// [`coordination`] with cells in a hash map (any spread of positions).
fn coordination_hashed(atoms: &crate::engine::atoms::Atoms, d: f64) -> Vec<u32> {
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
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        if let Some((d, _)) = self.surface {
            let periodic = (0..state.dimension).any(|k| state.domain.as_ref().map(|dm| dm.periodic(k)).unwrap_or(false));
            let cut = ctx.pair.map(|p| (1..=state.ntypes).flat_map(|i| (1..=state.ntypes).map(move |j| (i, j))).map(|(i, j)| p.cutoff(i, j)).fold(0.0, f64::max)).unwrap_or(0.0) + state.neigh_settings.skin;
            // periodic images, or a distributed run's ghosts, reach only as far as the cutoff
            if (periodic || state.decomp.is_some()) && d > cut {
                return Err(format!("the coordination distance {d} is longer than the neighbour cutoff {cut}: periodic images or other ranks' atoms would be missed"));
            }
        }
        Ok(())
    }
    fn setup(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.last_rate = self.apply(state);
        Ok(())
    }
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        // the integrators apply each step's rate half before and half after it (trapezoid)
        let rate = self.apply(state);
        self.removed += 0.5 * state.dt * (self.last_rate + rate);
        self.last_rate = rate;
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.ncool as f64)
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        match i {
            1 => Some(self.ncool as f64),
            2 => Some(self.removed),
            _ => None,
        }
    }
    /// The heat removed is extensive; the count of cooling atoms is not (as LAMMPS' counts).
    fn extensive(&self, index: Option<usize>) -> bool {
        index == Some(2)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Positions from a small linear congruential generator (reproducible, no crate).
    fn atoms(n: usize, nlocal: usize, spread: f64, stray: Option<[f64; 3]>) -> crate::engine::atoms::Atoms {
        let mut a = crate::engine::atoms::Atoms::default();
        let mut s: u64 = 12345;
        let mut next = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..n {
            a.x.push([spread * next(), spread * next(), 0.2 * spread * next()]);
        }
        if let Some(p) = stray {
            a.x.push(p);
        }
        a.nlocal = nlocal;
        a
    }

    fn brute(a: &crate::engine::atoms::Atoms, d: f64) -> Vec<u32> {
        (0..a.nlocal)
            .map(|i| (0..a.x.len()).filter(|&j| j != i && (0..3).map(|k| (a.x[i][k] - a.x[j][k]).powi(2)).sum::<f64>() < d * d).count() as u32)
            .collect()
    }

    #[test]
    fn grid_and_hash_count_the_same_neighbours_as_a_direct_count() {
        // 400 atoms in a 2 x 2 x 0.4 box, the last 100 of them ghosts; d = 0.2: about 2.5 each
        let a = atoms(400, 300, 2.0, None);
        let want = brute(&a, 0.2);
        assert!(want.iter().sum::<u32>() > 300, "the test needs neighbours");
        assert_eq!(coordination(&a, 0.2), want);
        assert_eq!(coordination_hashed(&a, 0.2), want);
        // an atom 1e6 away would need a huge grid: the hash map takes over, same counts
        let b = atoms(400, 300, 2.0, Some([1.0e6, 0.0, 0.0]));
        assert_eq!(coordination(&b, 0.2), brute(&b, 0.2));
        // atoms exactly on cell faces and a single atom
        let mut c = crate::engine::atoms::Atoms::default();
        c.x = vec![[0.0, 0.0, 0.0], [0.2, 0.0, 0.0], [0.1999, 0.0, 0.0], [0.4, 0.4, 0.0]];
        c.nlocal = 4;
        assert_eq!(coordination(&c, 0.2), vec![1, 1, 2, 0]);
        c.x.truncate(1);
        c.nlocal = 1;
        assert_eq!(coordination(&c, 0.2), vec![0]);
    }
}
