//! `fix ID group langevin Tstart Tstop damp seed [scale type ratio] [tally yes|no]
//! [zero yes|no] [omega yes|no]`: Langevin thermostat. After the forces of every step (and of
//! the run setup) each atom of the group gets a drag -m v / damp and a random force
//! sqrt(24 kB T m / (damp dt)) (u - 1/2) per component, u uniform from LAMMPS' Marsaglia
//! generator seeded with `seed` (+ the rank, 0 in serial). The atoms draw in LAMMPS' local order
//! (engine/lammps_order.rs), so with the same trajectory the forces are LAMMPS' bits. The
//! operations follow LAMMPS' fix_langevin.cpp (the non-GJF path).

use super::thermostat::Target;
use crate::models::compute::temp_bias::{Bias, TempSpec};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::random_mars::{RanMars, SEED_RANGE};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group langevin Tstart Tstop damp seed [scale type ratio] [tally yes|no] [zero yes|no] [omega yes|no]";

/// Moment of inertia prefactor of a solid sphere.
const SINERTIA: f64 = 0.4;

pub struct FixLangevin {
    id: String,
    groupbit: u32,
    target: Target,
    period: f64,
    /// Per type (index 0 unused): the damping of the type is damp * ratio.
    ratio: Vec<f64>,
    tally: bool,
    zero: bool,
    omega: bool,
    random: RanMars,
    /// Per-type drag and random-force prefactors (LAMMPS' gfactor1, gfactor2).
    gfactor1: Vec<f64>,
    gfactor2: Vec<f64>,
    /// Drag plus random force of each owned atom (dmhs' index), kept for the energy tally.
    flangevin: Vec<[f64; 3]>,
    tallied: bool,
    energy: f64,
    energy_onestep: f64,
    /// `fix_modify temp CID` with a bias compute: the drag acts on the thermal velocity.
    temp: Option<TempSpec>,
}

impl FixLangevin {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let target = Target::parse(&mut a)?;
        let period = a.positive_f64("damp")?;
        let seed = a.i64_in("seed", *SEED_RANGE.start(), *SEED_RANGE.end())?;
        let mut ratio = vec![1.0; state.ntypes + 1];
        let (mut tally, mut zero, mut omega) = (false, false, false);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "scale" => {
                    let t = a.i64_in("atom type", 1, state.ntypes as i64)? as usize;
                    ratio[t] = a.f64("scale ratio")?;
                }
                "tally" => tally = a.yes_no("tally")?,
                "zero" => zero = a.yes_no("zero")?,
                "omega" => omega = a.yes_no("omega")?,
                "angmom" => {
                    let v = a.word("angmom value")?;
                    if v.text != "no" {
                        return Err(a.error_at(v, "fix langevin angmom needs ellipsoidal particles, which dmhs does not have", "only `angmom no` is supported"));
                    }
                }
                "gjf" => {
                    let v = a.word("gjf value")?;
                    if v.text != "no" {
                        return Err(a.error_at(v, "fix langevin gjf (the Gronbech-Jensen/Farago integrator) is not supported", "only `gjf no` is supported"));
                    }
                }
                _ => return Err(a.unknown_keyword(w, &["scale", "tally", "zero", "omega", "angmom", "gjf"])),
            }
        }
        Ok(FixLangevin {
            id,
            groupbit,
            target,
            period,
            ratio,
            tally,
            zero,
            omega,
            // LAMMPS: seed + comm->me, each rank its own stream
            random: RanMars::new(seed as i32 + state.decomp.as_ref().map_or(0, |d| d.rank()) as i32),
            gfactor1: Vec::new(),
            gfactor2: Vec::new(),
            flangevin: Vec::new(),
            tallied: false,
            energy: 0.0,
            energy_onestep: 0.0,
            temp: None,
        })
    }

    /// sum of flangevin . v over the group, in LAMMPS' order.
    fn power(&self, state: &State) -> f64 {
        let a = &state.atoms;
        let mut e = 0.0;
        for &i in state.lammps_order.indices(a.nlocal).iter() {
            if a.mask[i] & self.groupbit != 0 {
                let (fl, v) = (self.flangevin[i], a.v[i]);
                e += fl[0] * v[0] + fl[1] * v[1] + fl[2] * v[2];
            }
        }
        let mut e = [e];
        state.sum_ranks(&mut e);
        e[0]
    }

    fn apply(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let t_target = self.target.now(state, self, ctx, "langevin")?;
        let tsqrt = t_target.sqrt();
        let (boltz, mvv2e, ftm2v, dt) = (state.units.boltz, state.units.mvv2e, state.units.ftm2v, state.dt);
        let per_atom = state.atoms.features.per_atom_mass();
        let count = if self.zero {
            let c = state.group_count(self.groupbit);
            if c == 0 {
                return Err(RunError::new(state.step, "cannot zero the Langevin force of 0 atoms (fix langevin zero yes on an empty group)"));
            }
            c
        } else {
            0
        };
        let order = state.lammps_order.indices(state.atoms.nlocal).into_owned();
        let bias = match &self.temp {
            Some(spec) => spec.field(state, self.groupbit).map_err(|e| RunError::new(state.step, e))?,
            None => None,
        };
        let a = &mut state.atoms;
        if self.tally {
            self.flangevin.resize(a.nlocal, [0.0; 3]);
            self.tallied = true;
        }
        let mut fsum = [0.0; 3];
        for &i in &order {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let t = a.typ[i];
            let (gamma1, gamma2) = if per_atom {
                let m = a.rmass[i];
                let g1 = -m / self.period / ftm2v;
                let g2 = m.sqrt() * (24.0 * boltz / self.period / dt / mvv2e).sqrt() / ftm2v;
                (g1 * (1.0 / self.ratio[t]), g2 * (1.0 / self.ratio[t].sqrt() * tsqrt))
            } else {
                (self.gfactor1[t], self.gfactor2[t] * tsqrt)
            };
            let mut fran = [0.0; 3];
            for r in &mut fran {
                *r = gamma2 * (self.random.uniform() - 0.5);
            }
            let mut v = a.v[i];
            if let Some(b) = &bias {
                // LAMMPS' remove_bias: drag on the thermal velocity, no noise on a removed component
                for k in 0..3 {
                    v[k] -= b[i][k];
                    if v[k] == 0.0 {
                        fran[k] = 0.0;
                    }
                }
            }
            let fdrag = [gamma1 * v[0], gamma1 * v[1], gamma1 * v[2]];
            let f = &mut a.f[i];
            for k in 0..3 {
                f[k] += fdrag[k] + fran[k];
                fsum[k] += fran[k];
            }
            if self.tally {
                self.flangevin[i] = [fdrag[0] + fran[0], fdrag[1] + fran[1], fdrag[2] + fran[2]];
            }
        }
        if self.zero {
            state.sum_ranks(&mut fsum);
            let a = &mut state.atoms;
            for s in &mut fsum {
                *s /= count as f64;
            }
            for i in 0..a.nlocal {
                if a.mask[i] & self.groupbit != 0 {
                    for k in 0..3 {
                        a.f[i][k] -= fsum[k];
                    }
                    if self.tally {
                        for k in 0..3 {
                            self.flangevin[i][k] -= fsum[k];
                        }
                    }
                }
            }
        }
        if self.omega {
            // rotational drag and noise, gamma scaled by 10/3 for spheres (LAMMPS' omega_thermostat)
            let tendivthree = 10.0 / 3.0;
            let a = &mut state.atoms;
            for &i in &order {
                if a.mask[i] & self.groupbit == 0 || a.radius[i] <= 0.0 {
                    continue;
                }
                let t = a.typ[i];
                let inertiaone = SINERTIA * a.radius[i] * a.radius[i] * a.rmass[i];
                let g1 = -tendivthree * inertiaone / self.period / ftm2v;
                let g2 = inertiaone.sqrt() * (80.0 * boltz / self.period / dt / mvv2e).sqrt() / ftm2v;
                let gamma1 = g1 * (1.0 / self.ratio[t]);
                let gamma2 = g2 * (1.0 / self.ratio[t].sqrt() * tsqrt);
                let mut tran = [0.0; 3];
                for r in &mut tran {
                    *r = gamma2 * (self.random.uniform() - 0.5);
                }
                let w = a.omega[i];
                for k in 0..3 {
                    a.torque[i][k] += gamma1 * w[k] + tran[k];
                }
            }
        }
        Ok(())
    }
    /// The random force's factor of type `t` (type masses), from the current dt.
    fn gfactor2_of(&self, state: &State, t: usize) -> f64 {
        let u = &state.units;
        let g = state.type_mass[t].sqrt() * (24.0 * u.boltz / self.period / state.dt / u.mvv2e).sqrt() / u.ftm2v;
        g * (1.0 / self.ratio[t].sqrt())
    }
}

impl Fix for FixLangevin {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "langevin"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, end_of_step: self.tally, ..FixHooks::default() }
    }
    /// LAMMPS' fix langevin has no minimization hook.
    fn min_role(&self) -> super::MinRole {
        super::MinRole::Inert
    }
    /// LAMMPS' fix langevin reads its temperature compute only to remove a bias; a plain
    /// compute temp has none, so the forces do not change.
    fn modify_temp(&mut self, spec: TempSpec) -> Result<(), String> {
        self.temp = (spec.bias != Bias::None).then_some(spec);
        Ok(())
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        if self.omega {
            if !state.atoms.features.sphere {
                return Err("fix langevin omega requires atom style sphere".into());
            }
            let a = &state.atoms;
            if (0..a.nlocal).any(|i| a.mask[i] & self.groupbit != 0 && a.radius[i] == 0.0) {
                return Err("fix langevin omega requires extended particles (an atom of the group has radius 0)".into());
            }
        }
        let u = &state.units;
        let n = state.ntypes + 1;
        (self.gfactor1, self.gfactor2) = (vec![0.0; n], vec![0.0; n]);
        if !state.atoms.features.per_atom_mass() {
            for t in 1..n {
                let m = state.type_mass[t];
                self.gfactor1[t] = -m / self.period / u.ftm2v;
                self.gfactor1[t] *= 1.0 / self.ratio[t];
                self.gfactor2[t] = self.gfactor2_of(state, t);
            }
        }
        Ok(())
    }
    /// The random force's factor depends on dt (LAMMPS' reset_dt renews it).
    fn reset_dt(&mut self, state: &State) -> Result<(), String> {
        if !state.atoms.features.per_atom_mass() && self.gfactor2.len() == state.ntypes + 1 {
            for t in 1..=state.ntypes {
                self.gfactor2[t] = self.gfactor2_of(state, t);
            }
        }
        Ok(())
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.apply(state, ctx)?;
        if self.tally {
            // LAMMPS restarts the tally when its scalar is read at the first step of a run (thermo
            // output at setup): half a step of the power at that step
            self.energy_onestep = self.power(state);
            self.energy = 0.5 * self.energy_onestep * state.dt;
        }
        Ok(())
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.apply(state, ctx)
    }
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if self.tally {
            self.energy_onestep = self.power(state);
            self.energy += self.energy_onestep * state.dt;
        }
        Ok(())
    }
    /// Energy added to the group by the thermostat, with the sign LAMMPS reports (minus the
    /// energy given to the reservoir), at the last full step.
    fn couples_energy(&self) -> bool {
        true
    }
    fn scalar(&self, state: &State) -> Option<f64> {
        if !self.tally || !self.tallied {
            return Some(0.0);
        }
        Some(-(self.energy - 0.5 * self.energy_onestep * state.dt))
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
