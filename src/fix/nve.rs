//! `fix ID group nve`: velocity-Verlet integration (LAMMPS' arithmetic:
//! dtf = dt/2 * ftm2v; v += dtf/m * f; x += dt * v).

use super::{Fix, FixHooks};
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
        let dtv = sim.dt;
        let dtf = 0.5 * sim.dt * sim.units.ftm2v;
        let per_atom = sim.atoms.features.per_atom_mass();
        let a = &mut sim.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let m = if per_atom { a.rmass[i] } else { sim.type_mass[a.typ[i]] };
                let dtfm = dtf / m;
                let f = a.f[i];
                let v = &mut a.v[i];
                v[0] += dtfm * f[0];
                v[1] += dtfm * f[1];
                v[2] += dtfm * f[2];
                let x = &mut a.x[i];
                x[0] += dtv * v[0];
                x[1] += dtv * v[1];
                x[2] += dtv * v[2];
            }
        }
        Ok(())
    }
    fn final_integrate(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        let dtf = 0.5 * sim.dt * sim.units.ftm2v;
        let per_atom = sim.atoms.features.per_atom_mass();
        let a = &mut sim.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let m = if per_atom { a.rmass[i] } else { sim.type_mass[a.typ[i]] };
                let dtfm = dtf / m;
                let f = a.f[i];
                let v = &mut a.v[i];
                v[0] += dtfm * f[0];
                v[1] += dtfm * f[1];
                v[2] += dtfm * f[2];
            }
        }
        Ok(())
    }
}
