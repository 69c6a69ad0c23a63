//! `fix ID group nve`: velocity-Verlet integration (LAMMPS' arithmetic:
//! dtf = dt/2 * ftm2v; v += dtf/m * f; x += dt * v).

use super::{Fix, FixHooks};
use crate::pair::SharedMut;
use crate::sim::{RunError, Simulation};
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
    fn half_step(&self, sim: &mut Simulation, first: bool) {
        let dtv = sim.dt;
        let dtf = 0.5 * sim.dt * sim.units.ftm2v;
        let per_atom = sim.atoms.features.per_atom_mass();
        let groupbit = self.groupbit;
        let dtfm_of_type = super::dtfm_by_type(dtf, &sim.type_mass, per_atom);
        let a = &mut sim.atoms;
        let n = a.nlocal;
        let (f, mask, typ, rmass) = (&a.f[..n], &a.mask[..n], &a.typ[..n], &a.rmass[..]);
        let (x, v) = (SharedMut::new(&mut a.x[..n]), SharedMut::new(&mut a.v[..n]));
        super::for_each_range(n, 1024, |range| {
            for i in range {
                if mask[i] & groupbit == 0 {
                    continue;
                }
                let dtfm = if per_atom { dtf / rmass[i] } else { dtfm_of_type[typ[i]] };
                // SAFETY: each index belongs to one range only
                let (xi, vi) = unsafe { (x.get(i), v.get(i)) };
                super::kick(vi, dtfm, &f[i]);
                if first {
                    super::drift(xi, dtv, vi);
                }
            }
        });
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
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn initial_integrate(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        self.half_step(sim, true);
        Ok(())
    }
    fn final_integrate(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        self.half_step(sim, false);
        Ok(())
    }
}
