//! `fix ID group nve/sphere [disc]`: velocity-Verlet for finite-size spheres, translation and
//! rotation (LAMMPS' arithmetic): dtf = dt/2 ftm2v;
//! v += dtf/m f; x += dt v; omega += dtf/(I_f r^2 m) torque, with I_f = 0.4 (solid sphere) or
//! 0.5 (`disc`, 2d only). Contact forces therefore see the half-step velocities.

use super::{Fix, FixHooks};
use crate::sim::{RunError, Simulation};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group nve/sphere [disc]";

pub struct FixNveSphere {
    id: String,
    groupbit: u32,
    /// Moment of inertia prefactor: 0.4 sphere, 0.5 disc.
    inertia: f64,
}

impl FixNveSphere {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, sim: &Simulation) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if !sim.atoms.features.sphere {
            return Err(a.error_at(&cmd.name, "fix nve/sphere requires atom style sphere", "no radius, rmass, omega").with_help("use atom_style sphere (or hybrid sphere ...)"));
        }
        let mut inertia = 0.4;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "disc" => {
                    if sim.dimension != 2 {
                        return Err(a.error_at(w, "fix nve/sphere disc requires a 2d simulation", "3d"));
                    }
                    inertia = 0.5;
                }
                "update" => return Err(a.error_at(w, "fix nve/sphere update dipole is not supported", "not supported")),
                _ => return Err(a.unknown_keyword(w, &["disc"])),
            }
        }
        Ok(FixNveSphere { id, groupbit, inertia })
    }
}

impl Fix for FixNveSphere {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "nve/sphere"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn init(&mut self, sim: &Simulation) -> Result<(), String> {
        let a = &sim.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 && a.radius[i] == 0.0 {
                return Err(format!("fix nve/sphere requires extended particles (atom {} has radius 0)", a.tag[i]));
            }
        }
        Ok(())
    }
    fn initial_integrate(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        let dtv = sim.dt;
        let dtf = 0.5 * sim.dt * sim.units.ftm2v;
        let dtfrotate = dtf / self.inertia;
        let a = &mut sim.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let m = a.rmass[i];
            let dtfm = dtf / m;
            let f = a.f[i];
            let v = &mut a.v[i];
            v[0] += dtfm * f[0];
            v[1] += dtfm * f[1];
            v[2] += dtfm * f[2];
            let v = *v;
            let x = &mut a.x[i];
            x[0] += dtv * v[0];
            x[1] += dtv * v[1];
            x[2] += dtv * v[2];
            let r = a.radius[i];
            let dtirotate = dtfrotate / (r * r * m);
            let t = a.torque[i];
            let w = &mut a.omega[i];
            w[0] += dtirotate * t[0];
            w[1] += dtirotate * t[1];
            w[2] += dtirotate * t[2];
        }
        Ok(())
    }
    fn final_integrate(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        let dtf = 0.5 * sim.dt * sim.units.ftm2v;
        let dtfrotate = dtf / self.inertia;
        let a = &mut sim.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let m = a.rmass[i];
            let dtfm = dtf / m;
            let f = a.f[i];
            let v = &mut a.v[i];
            v[0] += dtfm * f[0];
            v[1] += dtfm * f[1];
            v[2] += dtfm * f[2];
            let r = a.radius[i];
            let dtirotate = dtfrotate / (r * r * m);
            let t = a.torque[i];
            let w = &mut a.omega[i];
            w[0] += dtirotate * t[0];
            w[1] += dtirotate * t[1];
            w[2] += dtirotate * t[2];
        }
        Ok(())
    }
}
