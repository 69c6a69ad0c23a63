//! LAMMPS' SPH setup with stale ghost velocity estimates. `Verlet::setup` makes the ghosts
//! (borders, or a forward communication when `pre no`) before fix sph's `setup_pre_force` sets
//! vest = v on owned atoms, so each ghost keeps the vest its owner had before (zero after
//! create_atoms or read_data, the last step's estimate after a run). With `newton on`, LAMMPS'
//! half list holds a pair across a periodic face once, at the owned atom whose partner image
//! lies in the upper half of its bin stencil, and the pair's force goes to both atoms: it sees
//! the fresh vest of that atom and the stale vest of the other. dmhs lists such a pair at both
//! owned atoms, each with the other's (stale) ghost, so for the setup forces the pairs LAMMPS
//! holds at the other atom are computed apart with the estimates swapped (owned stale, ghosts
//! fresh): each atom then gets the mirror image of LAMMPS' pair.
//!
//! A distributed run reproduces the serial run: only periodic images (ghosts with a shift) are
//! the serial run's ghosts; a ghost from a neighbouring rank stands for an owned atom of the
//! serial run and is given its owner's fresh estimate.

use crate::engine::domain::Domain;
use crate::models::pair::Tally;
use crate::sim::{RunError, Simulation};

/// LAMMPS' global bins of a neighbour build (NBinStandard: half the largest list cutoff, or
/// `neigh_modify binsize`, stretched to fit the box a whole number of times).
struct LammpsBins {
    /// The half list is made from a full one (a sub-style such as sph/rhosum asks for a full
    /// list: LAMMPS' halffull/newton), which keeps a ghost partner by its coordinates alone.
    from_full: bool,
    lo: [f64; 3],
    hi: [f64; 3],
    inv: [f64; 3],
    n: [i64; 3],
}

impl LammpsBins {
    fn new(domain: &Domain, cutneighmax: f64, binsize_user: f64, from_full: bool) -> LammpsBins {
        let prd = domain.prd();
        let optimal = if binsize_user > 0.0 { binsize_user } else { 0.5 * cutneighmax };
        let optimal = if optimal == 0.0 { prd[0] } else { optimal };
        let inv_opt = 1.0 / optimal;
        let mut n = [1i64; 3];
        let mut inv = [0.0; 3];
        for d in 0..3 {
            if d < domain.dimension {
                n[d] = ((prd[d] * inv_opt) as i64).max(1);
            }
            inv[d] = 1.0 / (prd[d] / n[d] as f64);
        }
        LammpsBins { from_full, lo: domain.lo, hi: domain.hi, inv, n }
    }

    /// LAMMPS' `coord2bin`, as global bin coordinates.
    fn bin(&self, x: &[f64; 3]) -> [i64; 3] {
        std::array::from_fn(|d| {
            if x[d] >= self.hi[d] {
                ((x[d] - self.hi[d]) * self.inv[d]) as i64 + self.n[d]
            } else if x[d] >= self.lo[d] {
                (((x[d] - self.lo[d]) * self.inv[d]) as i64).min(self.n[d] - 1)
            } else {
                ((x[d] - self.lo[d]) * self.inv[d]) as i64 - 1
            }
        })
    }

    /// Whether LAMMPS' half/bin/newton list holds the pair of owned atom `xi` and ghost `xj`
    /// at the owned atom: the ghost's bin in the upper half stencil (z, then y, then x
    /// positive), or the same bin (any bin for a list made from a full one) and the ghost not
    /// below and left of the atom.
    fn held_at_owned(&self, xi: &[f64; 3], xj: &[f64; 3]) -> bool {
        let (bi, bj) = (self.bin(xi), self.bin(xj));
        for d in (0..3).rev().filter(|_| !self.from_full) {
            if bj[d] != bi[d] {
                return bj[d] > bi[d];
            }
        }
        for d in (0..3).rev() {
            if xj[d] != xi[d] {
                return xj[d] > xi[d];
            }
        }
        true
    }
}

impl Simulation {
    /// The owned atoms' vest before fixes' `setup_pre_force`, when the setup forces may need
    /// [`Simulation::setup_forces_stale_vest`]: an SPH run with `newton on`.
    pub(crate) fn vest_before_setup(&self) -> Option<Vec<[f64; 3]>> {
        let s = &self.state;
        let wanted = s.atoms.features.sph && s.newton_pair && self.pair.is_some() && s.domain.is_some();
        wanted.then(|| s.atoms.vest[..s.atoms.nlocal].to_vec())
    }

    /// The setup forces with LAMMPS' stale ghost estimates: `old` is the owned atoms' vest
    /// the ghosts were made with. Pair forces of the list minus the pairs LAMMPS holds at the
    /// other atom, then those pairs alone with owned vest = `old` and ghost vest fresh.
    pub(crate) fn setup_forces_stale_vest(&mut self, old: Option<Vec<[f64; 3]>>) -> Result<(), RunError> {
        let Some(old) = old else {
            return self.compute_forces(true, false);
        };
        let (nlocal, step) = (self.state.atoms.nlocal, self.state.step);
        let fresh_ghosts = self.state.owners_vectors(|a| &a.vest);
        let image = |a: &crate::engine::atoms::Atoms, k: usize| a.ghost_shift[k] != [0; 3];
        // ghosts from other ranks stand for the serial run's owned atoms: fresh
        let a = &mut self.state.atoms;
        for k in 0..a.nghost() {
            if !image(a, k) {
                a.vest[nlocal + k] = fresh_ghosts[k];
            }
        }
        // whether some periodic image holds an estimate its owner no longer has (on any rank)
        let mut stale = [(0..a.nghost()).any(|k| image(a, k) && a.vest[nlocal + k] != fresh_ghosts[k]) as u8 as f64];
        self.state.max_ranks(&mut stale);
        if stale[0] == 0.0 {
            // the copy is as large as the velocities: not held through the forces
            drop(old);
            return self.compute_forces(true, false);
        }
        if self.computes.iter().any(|c| c.uses_peratom_tally()) {
            return Err(RunError::new(step, "per-atom energies and virials (compute pe/atom, stress/atom) of an SPH run setup whose ghosts hold old velocity estimates are not made yet (LAMMPS splits those pairs by its newton list)"));
        }
        let domain = self.state.domain.as_ref().expect("a box");
        let from_full = self.pair.as_deref().is_some_and(|p| p.sub_styles().contains(&"sph/rhosum"));
        let bins = LammpsBins::new(domain, self.state.neighbor.cutneighmax, self.state.neigh_settings.binsize, from_full);
        let a = &self.state.atoms;
        let here = |i: usize, j: usize| j < nlocal || !image(a, j - nlocal) || bins.held_at_owned(&a.x[i], &a.x[j]);
        let full = &self.state.neighbor.list;
        let (near, far) = (full.retained(here), full.retained(|i, j| !here(i, j)));
        let ghosts_old = self.state.atoms.vest[nlocal..].to_vec();
        // the density summation (sph/rhosum) sees every pair
        self.compute_forces_listed(true, false, Some(near))?;
        // the far pairs alone, on zeroed accumulators, with the estimates swapped
        let a = &mut self.state.atoms;
        let near_out = (std::mem::take(&mut a.f), std::mem::take(&mut a.drho), std::mem::take(&mut a.desph));
        (a.f, a.drho, a.desph) = (vec![[0.0; 3]; near_out.0.len()], vec![0.0; near_out.1.len()], vec![0.0; near_out.2.len()]);
        let fresh = a.vest[..nlocal].to_vec();
        a.vest[..nlocal].copy_from_slice(&old);
        a.vest[nlocal..].copy_from_slice(&fresh_ghosts);
        let full = std::mem::replace(&mut self.state.neighbor.list, far);
        let mut tally: Tally = self.with_pair(|p, input, out| p.compute(input, out), true, false);
        self.state.neighbor.list = full;
        let a = &mut self.state.atoms;
        a.vest[..nlocal].copy_from_slice(&fresh);
        a.vest[nlocal..].copy_from_slice(&ghosts_old);
        let far_out = (std::mem::replace(&mut a.f, near_out.0), std::mem::replace(&mut a.drho, near_out.1), std::mem::replace(&mut a.desph, near_out.2));
        for (f, g) in a.f.iter_mut().zip(&far_out.0) {
            *f = [f[0] + g[0], f[1] + g[1], f[2] + g[2]];
        }
        for (r, g) in a.drho.iter_mut().zip(&far_out.1) {
            *r += g;
        }
        for (e, g) in a.desph.iter_mut().zip(&far_out.2) {
            *e += g;
        }
        // the near pass's energies are already summed over the ranks
        let mut v = [tally.evdwl, tally.ecoul, tally.virial[0], tally.virial[1], tally.virial[2], tally.virial[3], tally.virial[4], tally.virial[5]];
        self.state.sum_ranks(&mut v);
        (tally.evdwl, tally.ecoul) = (v[0], v[1]);
        tally.virial.copy_from_slice(&v[2..8]);
        let e = &mut self.state.energies;
        e.pair.evdwl += tally.evdwl;
        e.pair.ecoul += tally.ecoul;
        for k in 0..6 {
            e.pair.virial[k] += tally.virial[k];
            e.virial[k] += tally.virial[k];
        }
        Ok(())
    }
}
