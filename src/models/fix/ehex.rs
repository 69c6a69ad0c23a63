//! `fix ID group ehex N F [region R] [hex] [constrain] [com]`: every N steps, at the end of the
//! step, add the heat flux F (energy per time; negative removes it) to the group's atoms in the
//! region by scaling their velocities about their centre-of-mass velocity (Wirnsberger, Frenkel
//! and Dellago's eHEX/a algorithm, J. Chem. Phys. 143, 124104 (2015), as LAMMPS' fix ehex):
//! besides the rescaling of HEX, each position gets the third-order correction of the paper's
//! Eq. (20), which removes HEX's drift of the total energy. `hex` leaves the correction out
//! (plain HEX). Positions are tested against the region after mapping them into the periodic
//! box. The sums run in LAMMPS' atom order; f_ID is the velocity scale factor. `constrain` and
//! `com` need fix shake or rattle, which dmhs does not have: they are located errors.

use super::setforce::{find_region, region_now};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::args::word_f64;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group ehex N F [region region-ID] [hex]";

pub struct FixEhex {
    id: String,
    groupbit: u32,
    nevery: i64,
    heat_input: f64,
    region: Option<String>,
    hex: bool,
    scale: f64,
}

impl FixEhex {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64_in("N (steps between heat additions)", 1, i64::MAX)?;
        let w = a.word("F (heat flux, energy/time)")?;
        let heat_input = word_f64(&w, "F")?;
        let (mut region, mut hex) = (None, false);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "region" => region = Some(find_region(&mut a, state)?),
                "hex" => hex = true,
                "constrain" | "com" => return Err(a.error_at(w, format!("fix ehex `{}` corrects constrained clusters through fix shake or fix rattle, which dmhs does not have", w.text), "needs fix shake/rattle")),
                _ => return Err(a.unknown_keyword(w, &["region", "hex", "constrain", "com"])),
            }
        }
        Ok(FixEhex { id, groupbit, nevery, heat_input, region, hex, scale: 1.0 })
    }
}

impl Fix for FixEhex {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "ehex"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        super::heat::region_and_atoms(state, "ehex", &self.id, &self.region, self.groupbit)
    }
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        let step = state.step;
        let region = region_now(&state.regions, step, &self.id, &self.region)?;
        let Some(domain) = state.domain.as_ref() else { return Ok(()) };
        let a = &state.atoms;
        let selected: Vec<bool> = (0..a.nlocal)
            .map(|i| {
                a.mask[i] & self.groupbit != 0
                    && region.is_none_or(|r| {
                        let (mut x, mut image) = (a.x[i], [0; 3]);
                        domain.remap(&mut x, &mut image);
                        r.matches(x)
                    })
            })
            .collect();
        // the reservoir's momentum, kinetic energy, mass, force sum and sum of f.v (LAMMPS'
        // com_properties)
        let order = state.lammps_order.indices(a.nlocal);
        let mut s = [0.0; 9];
        for &i in order.iter().filter(|&&i| selected[i]) {
            let (m, v, f) = (state.mass(i), a.v[i], a.f[i]);
            s[4] += m;
            s[3] += m / 2.0 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            s[8] += f[0] * v[0] + f[1] * v[1] + f[2] * v[2];
            for k in 0..3 {
                s[k] += m * v[k];
                s[5 + k] += f[k];
            }
        }
        state.sum_ranks(&mut s);
        let mr = s[4];
        if mr < 1e-14 {
            return Err(RunError::new(step, format!("fix ehex {}: Fix ehex error mass of region is close to zero", self.id)));
        }
        let vcm = [s[0] / mr, s[1] / mr, s[2] / mr];
        let sfr = [s[5], s[6], s[7]];
        let kr = s[3] - 0.5 * mr * (vcm[0] * vcm[0] + vcm[1] * vcm[1] + vcm[2] * vcm[2]);
        let sfvr = s[8] - (vcm[0] * sfr[0] + vcm[1] * sfr[1] + vcm[2] * sfr[2]);
        let (ftm2v, dt) = (state.units.ftm2v, state.dt);
        let flux = self.heat_input * ftm2v * self.nevery as f64;
        let escale = 1.0 + (flux * dt) / kr;
        if escale < 0.0 {
            return Err(RunError::new(step, format!("fix ehex {}: Fix ehex kinetic energy went negative", self.id)));
        }
        self.scale = escale.sqrt();
        let vsub = vcm.map(|c| (self.scale - 1.0) * c);
        let (a, type_mass) = (&mut state.atoms, &state.type_mass);
        for i in (0..selected.len()).filter(|&i| selected[i]) {
            let mi = a.mass(i, type_mass);
            for k in 0..3 {
                if !self.hex {
                    // Eq. (20) of the paper: the position correction of eHEX
                    let eta = mi * flux / (2.0 * kr) * (a.v[i][k] - vcm[k]);
                    let eps = eta / (mi * kr) * (flux / 48.0 + sfvr / 6.0 * ftm2v) - flux / (12.0 * kr) * (a.f[i][k] / mi - sfr[k] / mr) * ftm2v;
                    a.x[i][k] -= dt * dt * dt * eps;
                }
                a.v[i][k] = self.scale * a.v[i][k] - vsub[k];
            }
        }
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.scale)
    }
}
