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

use super::{Fix, FixHooks};
use crate::sim::{RunError, Simulation};
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub struct FixSph {
    id: String,
    groupbit: u32,
    stationary: bool,
}

impl FixSph {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, sim: &Simulation) -> DResult<Self> {
        let stationary = style.text == "sph/stationary";
        Args::from_words(args, cmd.span, if stationary { "fix ID group sph/stationary" } else { "fix ID group sph" }).finish()?;
        if !sim.atoms.features.sph {
            return Err(Diagnostic::at(style.span, format!("fix {} needs an atom style with SPH attributes (atom_style sph or hybrid ... sph)", style.text), "atom style has no rho/esph/vest"));
        }
        Ok(FixSph { id, groupbit, stationary })
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
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn setup_pre_force(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        if !self.stationary {
            let a = &mut sim.atoms;
            for i in 0..a.nlocal {
                if a.mask[i] & self.groupbit != 0 {
                    a.vest[i] = a.v[i];
                }
            }
        }
        Ok(())
    }
    fn initial_integrate(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        let dtv = sim.dt;
        let dtf = 0.5 * sim.dt * sim.units.ftm2v;
        let per_atom = sim.atoms.features.per_atom_mass();
        let a = &mut sim.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            a.esph[i] += dtf * a.desph[i];
            a.rho[i] += dtf * a.drho[i];
            if self.stationary {
                continue;
            }
            let m = if per_atom { a.rmass[i] } else { sim.type_mass[a.typ[i]] };
            let dtfm = dtf / m;
            let f = a.f[i];
            let v = a.v[i];
            a.vest[i] = [v[0] + 2.0 * dtfm * f[0], v[1] + 2.0 * dtfm * f[1], v[2] + 2.0 * dtfm * f[2]];
            let v = &mut a.v[i];
            v[0] += dtfm * f[0];
            v[1] += dtfm * f[1];
            v[2] += dtfm * f[2];
            let x = &mut a.x[i];
            x[0] += dtv * v[0];
            x[1] += dtv * v[1];
            x[2] += dtv * v[2];
        }
        Ok(())
    }
    fn final_integrate(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        let dtf = 0.5 * sim.dt * sim.units.ftm2v;
        let per_atom = sim.atoms.features.per_atom_mass();
        let a = &mut sim.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            if !self.stationary {
                let m = if per_atom { a.rmass[i] } else { sim.type_mass[a.typ[i]] };
                let dtfm = dtf / m;
                let f = a.f[i];
                let v = &mut a.v[i];
                v[0] += dtfm * f[0];
                v[1] += dtfm * f[1];
                v[2] += dtfm * f[2];
            }
            a.esph[i] += dtf * a.desph[i];
            a.rho[i] += dtf * a.drho[i];
        }
        Ok(())
    }
}
