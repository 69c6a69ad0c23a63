//! `fix ID group heat N eflux [region R]`: every N steps, at the end of the step, add eflux
//! energy per time (negative: remove it) to the group's atoms (those in the region, if given)
//! by scaling their velocities about their centre-of-mass velocity, so the momentum stays; eflux
//! is a constant, an equal-style variable, or an atom-style variable (each atom its own factor,
//! the momentum change shared out by mass). The HEX algorithm of LAMMPS' fix heat, with the sums
//! in LAMMPS' atom order; f_ID is the velocity scale factor (its average over the atoms for an
//! atom-style eflux).

use super::setforce::{region_keyword, region_now};
use super::value::{Evaluated, FixValue};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group heat N eflux [region region-ID]";

pub struct FixHeat {
    id: String,
    groupbit: u32,
    nevery: i64,
    eflux: FixValue,
    region: Option<String>,
    /// The group's mass (from init; with a region, the mass inside it at each application).
    masstotal: f64,
    /// The velocity scale factor of the last application (for an atom-style eflux, the
    /// average over the atoms it scaled).
    scale: f64,
}

/// The mass, twice the kinetic energy (sum m v^2) and the momentum of the atoms `selected` picks,
/// summed in LAMMPS' atom order over every rank (LAMMPS' Group::mass, ke and vcm).
pub fn group_sums(state: &State, order: &[usize], selected: &dyn Fn(usize) -> bool) -> (f64, f64, [f64; 3]) {
    let a = &state.atoms;
    let mut s = [0.0; 5];
    for &i in order {
        if selected(i) {
            let (m, v) = (state.mass(i), a.v[i]);
            s[0] += m;
            s[1] += (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * m;
            for k in 0..3 {
                s[2 + k] += v[k] * m;
            }
        }
    }
    state.sum_ranks(&mut s);
    (s[0], s[1], [s[2], s[3], s[4]])
}

/// LAMMPS' checks when a run starts of fix heat and fix ehex: the region exists and the group
/// has atoms.
pub fn region_and_atoms(state: &State, style: &str, id: &str, region: &Option<String>, groupbit: u32) -> Result<(), String> {
    region_now(&state.regions, state.step, id, region).map_err(|e| e.message)?;
    if state.group_count(groupbit) == 0 {
        return Err(format!("fix {style} {id}: Fix {style} group has no atoms"));
    }
    Ok(())
}

impl FixHeat {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64_in("N (steps between heat additions)", 1, i64::MAX)?;
        let w = a.word("eflux (energy/time, or v_name)")?;
        let eflux = FixValue::parse(&w, "eflux", false)?;
        let region = region_keyword(&mut a, state)?;
        Ok(FixHeat { id, groupbit, nevery, eflux, region, masstotal: 0.0, scale: 1.0 })
    }
}

impl Fix for FixHeat {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "heat"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        region_and_atoms(state, "heat", &self.id, &self.region, self.groupbit)?;
        let order = state.lammps_order.indices(state.atoms.nlocal);
        let bit = self.groupbit;
        self.masstotal = group_sums(state, &order, &|i| state.atoms.mask[i] & bit != 0).0;
        if self.masstotal <= 0.0 {
            return Err(format!("fix heat {}: Fix heat group has invalid mass", self.id));
        }
        Ok(())
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        let step = state.step;
        let fail = |m: &str| RunError::new(step, format!("fix heat {}: {m}", self.id));
        let eflux = ctx.value_per_atom(state, self, &self.eflux)?;
        let region = region_now(&state.regions, step, &self.id, &self.region)?;
        let order = state.lammps_order.indices(state.atoms.nlocal);
        let a = &state.atoms;
        let bit = self.groupbit;
        let selected: Vec<bool> = (0..a.nlocal).map(|i| a.mask[i] & bit != 0 && region.is_none_or(|r| r.matches(a.x[i]))).collect();
        let (mass, twice_ke, p) = group_sums(state, &order, &|i| selected[i]);
        if region.is_some() {
            if mass == 0.0 {
                return Err(fail("Fix heat group has no atoms"));
            }
            self.masstotal = mass;
        }
        let (units, dt, masstotal) = (&state.units, state.dt, self.masstotal);
        let ke = 0.5 * units.mvv2e * twice_ke * units.ftm2v;
        let vcm = if masstotal > 0.0 { p.map(|x| x / masstotal) } else { p };
        let vcmsq = vcm[0] * vcm[0] + vcm[1] * vcm[1] + vcm[2] * vcm[2];
        let internal = ke - 0.5 * vcmsq * masstotal;
        let energy = |flux: f64| flux * self.nevery as f64 * dt * units.ftm2v;
        match eflux {
            Evaluated::PerAtom(flux) => {
                // each atom's squared scale factor; the momentum change shared out by mass
                let mut vscale = vec![0.0; a.nlocal];
                let mut vsub = [0.0; 5];
                for &i in order.iter().filter(|&&i| selected[i]) {
                    let s = (ke + energy(flux[i]) - 0.5 * vcmsq * masstotal) / internal;
                    if s < 0.0 {
                        return Err(fail("Fix heat kinetic energy of an atom went negative"));
                    }
                    vscale[i] = s;
                    let (scale, m) = (s.sqrt(), state.mass(i));
                    for k in 0..3 {
                        vsub[k] += (scale - 1.0) * a.v[i][k] * m;
                    }
                    vsub[3] += scale;
                    vsub[4] += 1.0;
                }
                // LAMMPS sums the momentum change on each rank alone; over every rank here,
                // so the group's momentum stays on any number of ranks (the same on one)
                state.sum_ranks(&mut vsub);
                self.scale = if vsub[4] == 0.0 { 0.0 } else { vsub[3] / vsub[4] };
                let vsub = [vsub[0] / masstotal, vsub[1] / masstotal, vsub[2] / masstotal];
                let v = &mut state.atoms.v;
                for i in (0..vscale.len()).filter(|&i| selected[i]) {
                    let scale = vscale[i].sqrt();
                    for k in 0..3 {
                        v[i][k] = scale * v[i][k] - vsub[k];
                    }
                }
            }
            Evaluated::One(flux) => {
                let escale = (ke + energy(flux) - 0.5 * vcmsq * masstotal) / internal;
                if escale < 0.0 {
                    return Err(fail("Fix heat kinetic energy went negative"));
                }
                self.scale = escale.sqrt();
                let vsub = vcm.map(|c| (self.scale - 1.0) * c);
                let v = &mut state.atoms.v;
                for i in (0..selected.len()).filter(|&i| selected[i]) {
                    for k in 0..3 {
                        v[i][k] = self.scale * v[i][k] - vsub[k];
                    }
                }
            }
            Evaluated::Null => unreachable!("eflux is never NULL"),
        }
        Ok(())
    }
    /// The velocity scale factor of the last application; for an atom-style eflux the average
    /// over the atoms it scaled (LAMMPS averages over the atoms in the group and region when
    /// asked, with the factors of the last application by local index: the same on the steps
    /// it applies, which thermo output every N steps reads).
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.scale)
    }
}
