//! `fix ID group nve`: velocity-Verlet integration (LAMMPS' arithmetic:
//! dtf = dt/2 * ftm2v; v += dtf/m * f; x += dt * v).

use super::{Fix, FixCtx, FixHooks};
use crate::engine::par::{ranges, AtomsMut};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub struct FixNve {
    id: String,
    groupbit: u32,
}

impl FixNve {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        Args::from_words(args, cmd.span, "fix ID group nve").finish()?;
        Ok(FixNve { id, groupbit })
    }

    /// One half step: v += dtf/m f, and in the first half x += dt v. Atoms are independent, so
    /// chunks of atoms run in parallel (same bits).
    fn half_step(&self, state: &mut State, first: bool) {
        let dtv = state.dt;
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let per_atom = state.atoms.features.per_atom_mass();
        let groupbit = self.groupbit;
        let dtfm_of_type = super::dtfm_by_type(dtf, &state.type_mass, per_atom);
        let a = &mut state.atoms;
        let n = a.nlocal;
        let (f, mask, typ, rmass) = (&a.f[..n], &a.mask[..n], &a.typ[..n], &a.rmass[..]);
        ranges(n, 1024, (AtomsMut::new(&mut a.x[..n]), AtomsMut::new(&mut a.v[..n])), |r, (mut x, mut v)| {
            let (x, v) = (x.slice(r.clone()), v.slice(r.clone()));
            let (f, mask, typ) = (&f[r.clone()], &mask[r.clone()], &typ[r.clone()]);
            let rmass = if per_atom { &rmass[r.clone()] } else { &[][..] };
            if first {
                kick_range::<true>(x, v, f, mask, groupbit, dtv, |k| if per_atom { dtf / rmass[k] } else { dtfm_of_type[typ[k]] });
            } else {
                kick_range::<false>(x, v, f, mask, groupbit, dtv, |k| if per_atom { dtf / rmass[k] } else { dtfm_of_type[typ[k]] });
            }
        });
    }
}

/// v += dtfm f for the atoms of a range in the group, and in the first half (`FIRST`) x += dt v;
/// `dtfm(k)` is dtf/m of the range's k-th atom.
#[inline(always)]
fn kick_range<const FIRST: bool>(x: &mut [[f64; 3]], v: &mut [[f64; 3]], f: &[[f64; 3]], mask: &[u32], groupbit: u32, dtv: f64, dtfm: impl Fn(usize) -> f64) {
    let m = x.len();
    let (v, f, mask) = (&mut v[..m], &f[..m], &mask[..m]);
    for k in 0..m {
        if mask[k] & groupbit == 0 {
            continue;
        }
        super::kick(&mut v[k], dtfm(k), &f[k]);
        if FIRST {
            super::drift(&mut x[k], dtv, &v[k]);
        }
    }
}

impl Fix for FixNve {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "nve"
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
    fn initial_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.half_step(state, true);
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.half_step(state, false);
        Ok(())
    }
}
