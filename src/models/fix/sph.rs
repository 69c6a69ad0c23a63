//! `fix ID group sph` and `fix ID group sph/stationary` (LAMMPS SPH package).
//!
//! sph: velocity Verlet for x and v, half steps for density and internal energy, and the
//! velocity estimate the SPH pair styles use:
//!   setup: vest = v
//!   initial: e += dtf de; rho += dtf drho; vest = v + 2 dtf/m f; v += dtf/m f; x += dt v
//!   final:   v += dtf/m f; rho += dtf drho; e += dtf de
//! sph/stationary: only the density and energy half steps (x and v stay; vest is never set, so
//! such particles look at rest to the SPH styles even if v != 0, as in LAMMPS).
//! m is the per-atom mass if the atom style has one, else the per-type mass.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::par::{ranges, AtomsMut};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub struct FixSph {
    id: String,
    groupbit: u32,
    stationary: bool,
}

impl FixSph {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let stationary = style.text == "sph/stationary";
        Args::from_words(args, cmd.span, if stationary { "fix ID group sph/stationary" } else { "fix ID group sph" }).finish()?;
        if !state.atoms.features.sph {
            return Err(Diagnostic::at(style.span, format!("fix {} needs an atom style with SPH attributes (atom_style sph or hybrid ... sph)", style.text), "atom style has no rho/esph/vest"));
        }
        Ok(FixSph { id, groupbit, stationary })
    }

    /// One half step of LAMMPS' fix sph (in its order of operations). First half: esph and rho
    /// by dtf times their rates; for moving particles the velocity estimate
    /// vest = v + 2 dtfm f, then v += dtfm f and x += dt v. Second half: v += dtfm f, then esph
    /// and rho. Atoms are independent, so chunks run in parallel (same bits).
    fn half_step(&self, state: &mut State, first: bool) {
        let dtv = state.dt;
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let per_atom = state.atoms.features.per_atom_mass();
        let groupbit = self.groupbit;
        let dtfm_of_type = super::dtfm_by_type(dtf, &state.type_mass, per_atom);
        let a = &mut state.atoms;
        let n = a.nlocal;
        let (f, drho, desph, mask, typ) = (&a.f[..n], &a.drho[..n], &a.desph[..n], &a.mask[..n], &a.typ[..n]);
        let rmass = if per_atom { &a.rmass[..n] } else { &[][..] };
        let windows = (AtomsMut::new(&mut a.x[..n]), AtomsMut::new(&mut a.v[..n]), AtomsMut::new(&mut a.vest[..n]), AtomsMut::new(&mut a.rho[..n]), AtomsMut::new(&mut a.esph[..n]));
        ranges(n, 1024, windows, |r, (mut x, mut v, mut vest, mut rho, mut esph)| {
            let s = HalfStep { x: x.slice(r.clone()), v: v.slice(r.clone()), vest: vest.slice(r.clone()), rho: rho.slice(r.clone()), esph: esph.slice(r.clone()) };
            let (f, drho, desph, mask) = (&f[r.clone()], &drho[r.clone()], &desph[r.clone()], &mask[r.clone()]);
            // dtf/m of the range's k-th atom
            let dtfm_r = |k: usize| {
                let i = r.start + k;
                if per_atom { dtf / rmass[i] } else { dtfm_of_type[typ[i]] }
            };
            match (first, self.stationary) {
                (true, false) => s.run::<true, true>(f, drho, desph, mask, groupbit, dtf, dtv, dtfm_r),
                (false, false) => s.run::<false, true>(f, drho, desph, mask, groupbit, dtf, dtv, dtfm_r),
                (true, true) => s.run::<true, false>(f, drho, desph, mask, groupbit, dtf, dtv, dtfm_r),
                (false, true) => s.run::<false, false>(f, drho, desph, mask, groupbit, dtf, dtv, dtfm_r),
            }
        });
    }
}

/// The per-atom arrays one task of a half step writes (one range of atoms).
struct HalfStep<'a> {
    x: &'a mut [[f64; 3]],
    v: &'a mut [[f64; 3]],
    vest: &'a mut [[f64; 3]],
    rho: &'a mut [f64],
    esph: &'a mut [f64],
}

impl HalfStep<'_> {
    /// One half step (`FIRST`: the initial one) of the atoms in the group, in LAMMPS' order;
    /// `MOVING`: fix sph (x, v and vest move), else sph/stationary.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn run<const FIRST: bool, const MOVING: bool>(self, f: &[[f64; 3]], drho: &[f64], desph: &[f64], mask: &[u32], groupbit: u32, dtf: f64, dtv: f64, dtfm: impl Fn(usize) -> f64) {
        let m = self.x.len();
        let (x, v, vest, rho, esph) = (&mut self.x[..m], &mut self.v[..m], &mut self.vest[..m], &mut self.rho[..m], &mut self.esph[..m]);
        let (f, drho, desph, mask) = (&f[..m], &drho[..m], &desph[..m], &mask[..m]);
        for i in 0..m {
            if mask[i] & groupbit == 0 {
                continue;
            }
            if FIRST {
                esph[i] += dtf * desph[i];
                rho[i] += dtf * drho[i];
            }
            if MOVING {
                let dtfm = dtfm(i);
                let fi = f[i];
                if FIRST {
                    let vi = v[i];
                    vest[i] = [vi[0] + 2.0 * dtfm * fi[0], vi[1] + 2.0 * dtfm * fi[1], vi[2] + 2.0 * dtfm * fi[2]];
                }
                super::kick(&mut v[i], dtfm, &fi);
                if FIRST {
                    super::drift(&mut x[i], dtv, &v[i]);
                }
            }
            if !FIRST {
                esph[i] += dtf * desph[i];
                rho[i] += dtf * drho[i];
            }
        }
    }
}

impl Fix for FixSph {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        if self.stationary { "sph/stationary" } else { "sph" }
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn time_integrate(&self) -> bool {
        true
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn setup_pre_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if !self.stationary {
            let a = &mut state.atoms;
            for i in 0..a.nlocal {
                if a.mask[i] & self.groupbit != 0 {
                    a.vest[i] = a.v[i];
                }
            }
        }
        Ok(())
    }
    fn initial_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.half_step(state, true);
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.half_step(state, false);
        Ok(())
    }
}
