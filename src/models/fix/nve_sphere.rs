//! `fix ID group nve/sphere [disc]`: velocity-Verlet for finite-size spheres, translation and
//! rotation (LAMMPS' arithmetic): dtf = dt/2 ftm2v;
//! v += dtf/m f; x += dt v; omega += dtf/(I_f r^2 m) torque, with I_f = 0.4 (solid sphere) or
//! 0.5 (`disc`, 2d only). Contact forces therefore see the half-step velocities.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use crate::engine::par::lanes::{lanes, L, LANES};
use crate::engine::par::{ranges, AtomsMut};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group nve/sphere [disc]";

pub struct FixNveSphere {
    id: String,
    groupbit: u32,
    /// Moment of inertia prefactor: 0.4 sphere, 0.5 disc.
    inertia: f64,
}

impl FixNveSphere {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if !state.atoms.features.sphere {
            return Err(a.error_at(&cmd.name, "fix nve/sphere requires atom style sphere", "no radius, rmass, omega").with_help("use atom_style sphere (or hybrid sphere ...)"));
        }
        let mut inertia = 0.4;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "disc" => {
                    if state.dimension != 2 {
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
    fn integrate(&self, state: &mut State, first: bool) {
        let dtv = state.dt;
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let dtfrotate = dtf / self.inertia;
        let groupbit = self.groupbit;
        let a = &mut state.atoms;
        let n = a.nlocal;
        let (f, torque, rmass, radius, mask) = (&a.f[..n], &a.torque[..n], &a.rmass[..n], &a.radius[..n], &a.mask[..n]);
        let windows = (AtomsMut::new(&mut a.x[..n]), AtomsMut::new(&mut a.v[..n]), AtomsMut::new(&mut a.omega[..n]));
        ranges(n, 1024, windows, |r, (mut x, mut v, mut omega)| {
            let s = HalfStep { x: x.slice(r.clone()), v: v.slice(r.clone()), omega: omega.slice(r.clone()) };
            let input = (&f[r.clone()], &torque[r.clone()], &rmass[r.clone()], &radius[r.clone()], &mask[r.clone()]);
            if first {
                s.run::<true>(input, groupbit, dtf, dtfrotate, dtv);
            } else {
                s.run::<false>(input, groupbit, dtf, dtfrotate, dtv);
            }
        });
    }
}

/// The per-atom arrays one task of a half step writes (one range of atoms), as plain slices.
struct HalfStep<'a> {
    x: &'a mut [[f64; 3]],
    v: &'a mut [[f64; 3]],
    omega: &'a mut [[f64; 3]],
}

/// Forces, torques, masses, radii and group masks of a range.
type HalfStepInput<'a> = (&'a [[f64; 3]], &'a [[f64; 3]], &'a [f64], &'a [f64], &'a [u32]);

impl HalfStep<'_> {
    /// The half step of the range's atoms in the group (`FIRST`: the one that also moves them).
    /// The two divisions per atom are made for four atoms at once, as lane vectors (the same
    /// IEEE division per lane, so the same bits): one at a time, their latency bounded the loop.
    #[inline(always)]
    fn run<const FIRST: bool>(self, (f, torque, rmass, radius, mask): HalfStepInput, groupbit: u32, dtf: f64, dtfrotate: f64, dtv: f64) {
        let m = self.x.len();
        let (x, v, omega) = (&mut self.x[..m], &mut self.v[..m], &mut self.omega[..m]);
        let (f, torque, rmass, radius, mask) = (&f[..m], &torque[..m], &rmass[..m], &radius[..m], &mask[..m]);
        let mut one = |i: usize, dtfm: f64, dtirotate: f64| {
            if mask[i] & groupbit != 0 {
                super::kick(&mut v[i], dtfm, &f[i]);
                if FIRST {
                    super::drift(&mut x[i], dtv, &v[i]);
                }
                super::kick(&mut omega[i], dtirotate, &torque[i]);
            }
        };
        let quads = m / LANES * LANES;
        for i0 in (0..quads).step_by(LANES) {
            // atoms outside the group get quotients too (unused; a zero mass gives inf, no trap)
            let mass = lanes(|l| rmass[i0 + l]);
            let r = lanes(|l| radius[i0 + l]);
            let dtfm = L::splat(dtf) / mass;
            let dtirotate = L::splat(dtfrotate) / (r * r * mass);
            for l in 0..LANES {
                one(i0 + l, dtfm[l], dtirotate[l]);
            }
        }
        for i in quads..m {
            let (mass, r) = (rmass[i], radius[i]);
            one(i, dtf / mass, dtfrotate / (r * r * mass));
        }
    }
}

/// LAMMPS' init check of the sphere integrators: no point particles in the group.
pub fn require_extended(state: &State, groupbit: u32, style: &str) -> Result<(), String> {
    let a = &state.atoms;
    match (0..a.nlocal).find(|&i| a.mask[i] & groupbit != 0 && a.radius[i] == 0.0) {
        Some(i) => Err(format!("fix {style} requires extended particles (atom {} has radius 0)", a.tag[i])),
        None => Ok(()),
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
    fn time_integrate(&self) -> bool {
        true
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        require_extended(state, self.groupbit, "nve/sphere")
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
