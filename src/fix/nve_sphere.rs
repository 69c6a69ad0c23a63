//! `fix ID group nve/sphere [disc]`: velocity-Verlet for finite-size spheres, translation and
//! rotation (LAMMPS' arithmetic): dtf = dt/2 ftm2v;
//! v += dtf/m f; x += dt v; omega += dtf/(I_f r^2 m) torque, with I_f = 0.4 (solid sphere) or
//! 0.5 (`disc`, 2d only). Contact forces therefore see the half-step velocities.

use super::{Fix, FixHooks};
use crate::sim::{RunError, Simulation};
use crate::pair::SharedMut;
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

impl FixNveSphere {
    /// One half step: v += dtf/m f and omega += dtf/(I_f r^2 m) torque, and in the first half
    /// x += dt v. Atoms are independent, so chunks of atoms run in parallel (same bits).
    fn integrate(&self, sim: &mut Simulation, first: bool) {
        let dtv = sim.dt;
        let dtf = 0.5 * sim.dt * sim.units.ftm2v;
        let dtfrotate = dtf / self.inertia;
        let groupbit = self.groupbit;
        let a = &mut sim.atoms;
        let n = a.nlocal;
        let (f, torque, rmass, radius, mask) = (&a.f[..n], &a.torque[..n], &a.rmass[..n], &a.radius[..n], &a.mask[..n]);
        let (x, v, omega) = (SharedMut::new(&mut a.x[..n]), SharedMut::new(&mut a.v[..n]), SharedMut::new(&mut a.omega[..n]));
        super::for_each_range(n, 1024, |range| {
            for i in range {
                if mask[i] & groupbit == 0 {
                    continue;
                }
                // SAFETY: each index belongs to one range only
                let (xi, vi, wi) = unsafe { (x.get(i), v.get(i), omega.get(i)) };
                let m = rmass[i];
                let dtfm = dtf / m;
                super::kick(vi, dtfm, &f[i]);
                if first {
                    super::drift(xi, dtv, vi);
                }
                let r = radius[i];
                let dtirotate = dtfrotate / (r * r * m);
                super::kick(wi, dtirotate, &torque[i]);
            }
        });
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
        self.integrate(sim, true);
        Ok(())
    }
    fn final_integrate(&mut self, sim: &mut Simulation) -> Result<(), RunError> {
        self.integrate(sim, false);
        Ok(())
    }
}
