//! `fix ID group nve/bpm/sphere [disc]` (LAMMPS BPM package): velocity-Verlet for the
//! finite-size spheres of atom_style bpm/sphere, which also carries each sphere's orientation.
//! First half: v += dtf/m f; x += dt v; omega += dtf/I torque with I = I_f (r^2 m), I_f = 0.4
//! (solid sphere) or 0.5 (`disc`, 2d only); then the quaternion is advanced by
//! dq/dt = 1/2 omega q over dt/2 with Richardson's scheme (MathExtra::richardson_sphere, with the
//! half-step omega). Second half: the two kicks again. LAMMPS' order of operations per atom.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::par::{ranges, AtomsMut};
use crate::engine::quat::richardson_sphere;
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group nve/bpm/sphere [disc]";

pub struct FixNveBpmSphere {
    id: String,
    groupbit: u32,
    /// Moment of inertia prefactor: 0.4 sphere, 0.5 disc.
    inertia: f64,
}

impl FixNveBpmSphere {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mut inertia = 0.4;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "disc" => {
                    if state.dimension != 2 {
                        return Err(a.error_at(w, "fix nve/bpm/sphere disc requires a 2d simulation", "3d"));
                    }
                    inertia = 0.5;
                }
                _ => return Err(a.unknown_keyword(w, &["disc"])),
            }
        }
        if !state.atoms.features.quat {
            return Err(a.error_at(&cmd.name, "fix nve/bpm/sphere requires atom style bpm/sphere", "no quaternion, radius, omega").with_help("use atom_style bpm/sphere"));
        }
        Ok(FixNveBpmSphere { id, groupbit, inertia })
    }

    /// One half step of every atom of the group (`first`: the one that also moves and turns).
    fn integrate(&self, state: &mut State, first: bool) {
        let dtv = state.dt;
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let dtq = 0.5 * dtv;
        let (groupbit, inertia) = (self.groupbit, self.inertia);
        let a = &mut state.atoms;
        let n = a.nlocal;
        let (f, torque, rmass, radius, mask) = (&a.f[..n], &a.torque[..n], &a.rmass[..n], &a.radius[..n], &a.mask[..n]);
        let windows = (AtomsMut::new(&mut a.x[..n]), AtomsMut::new(&mut a.v[..n]), AtomsMut::new(&mut a.omega[..n]), AtomsMut::new(&mut a.quat[..n]));
        // atoms are independent: ranges of them on the team
        ranges(n, 1024, windows, |r, (mut x, mut v, mut omega, mut quat)| {
            for i in r {
                if mask[i] & groupbit == 0 {
                    continue;
                }
                let dtfm = dtf / rmass[i];
                super::kick(&mut v[i], dtfm, &f[i]);
                if first {
                    super::drift(&mut x[i], dtv, &v[i]);
                }
                let particle_inertia = inertia * (radius[i] * radius[i] * rmass[i]);
                let dtirotate = dtf / particle_inertia;
                super::kick(&mut omega[i], dtirotate, &torque[i]);
                if first {
                    richardson_sphere(&mut quat[i], &omega[i], dtq);
                }
            }
        });
    }
}

impl Fix for FixNveBpmSphere {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "nve/bpm/sphere"
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
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        super::nve_sphere::require_extended(state, self.groupbit, "nve/bpm/sphere")
    }
    fn initial_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.integrate(state, true);
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.integrate(state, false);
        Ok(())
    }
}
