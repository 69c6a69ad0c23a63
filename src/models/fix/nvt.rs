//! `fix ID group nvt temp Tstart Tstop Tdamp [tchain N] [tloop N] [drag f] [mtk yes|no]`:
//! Nose-Hoover chain thermostat with velocity-Verlet (LAMMPS' fix_nh.cpp without a barostat,
//! same operations and order): a half step of the chain and velocity scaling, then the NVE
//! half kick and drift; after the forces the second kick, the new temperature, and the chain's
//! second half step. Defaults as LAMMPS: a chain of 3, one loop, no drag. The scalar is the
//! chain's energy. `fix npt`/`nph` (barostats) are refused.

use super::thermostat::{run_fraction, GroupTemp};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group nvt temp Tstart Tstop Tdamp [tchain N] [tloop N] [drag factor] [mtk yes|no]";

pub struct FixNvt {
    id: String,
    groupbit: u32,
    t_start: f64,
    t_stop: f64,
    t_freq: f64,
    mtchain: usize,
    nc_tchain: i64,
    drag: f64,
    temp: GroupTemp,
    // chain state (eta_dot has one extra zero entry, as LAMMPS')
    eta: Vec<f64>,
    eta_dot: Vec<f64>,
    eta_dotdot: Vec<f64>,
    eta_mass: Vec<f64>,
    t_target: f64,
    ke_target: f64,
    t_current: f64,
    tdof: f64,
    tdrag_factor: f64,
}

impl FixNvt {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mut temp: Option<(f64, f64, f64)> = None;
        let (mut mtchain, mut nc_tchain, mut drag) = (3usize, 1i64, 0.0);
        let barostat = ["iso", "aniso", "tri", "x", "y", "z", "xy", "yz", "xz", "couple", "dilate", "pchain", "ploop", "nreset", "scalexy", "scalexz", "scaleyz", "flip", "fixedpoint", "update", "ptemp", "disc"];
        if a.is_empty() {
            return Err(a.missing("the keyword `temp`"));
        }
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "temp" => {
                    let t0w = a.peek();
                    let t0 = a.f64("Tstart")?;
                    let t1 = a.f64("Tstop")?;
                    if t0 <= 0.0 || t1 <= 0.0 {
                        return Err(a.error_at(t0w.unwrap_or(w), "target temperature for fix nvt must be > 0.0", "Tstart and Tstop must be positive"));
                    }
                    let period = a.positive_f64("Tdamp")?;
                    temp = Some((t0, t1, period));
                }
                "tchain" => mtchain = a.i64_in("tchain (chain length)", 1, 10_000)? as usize,
                // LAMMPS takes any count; a bound keeps a typo from hanging the run
                "tloop" => nc_tchain = a.i64_in("tloop (sub-cycles)", 0, 10_000)?,
                "drag" => drag = a.non_negative_f64("drag factor")?,
                // the MTK terms act on the barostat only
                "mtk" => {
                    a.yes_no("mtk")?;
                }
                k if barostat.contains(&k) => {
                    return Err(a.error_at(w, format!("pressure control (`{k}`) cannot be used with fix nvt, and barostats (fix npt, nph) are not supported"), "not supported"));
                }
                _ => return Err(a.unknown_keyword(w, &["temp", "tchain", "tloop", "drag", "mtk"])),
            }
        }
        let Some((t_start, t_stop, period)) = temp else {
            return Err(a.error_at(&args[0], "fix nvt needs temperature control: `temp Tstart Tstop Tdamp`", "no `temp` keyword"));
        };
        let n = mtchain;
        Ok(FixNvt {
            id,
            groupbit,
            t_start,
            t_stop,
            t_freq: 1.0 / period,
            mtchain,
            nc_tchain,
            drag,
            temp: GroupTemp::new(groupbit),
            eta: vec![0.0; n],
            eta_dot: vec![0.0; n + 1],
            eta_dotdot: vec![0.0; n],
            eta_mass: vec![0.0; n],
            t_target: 0.0,
            ke_target: 0.0,
            t_current: 0.0,
            tdof: 0.0,
            tdrag_factor: 1.0,
        })
    }

    fn compute_temp_target(&mut self, state: &State) {
        let delta = run_fraction(state);
        self.t_target = self.t_start + delta * (self.t_stop - self.t_start);
        self.ke_target = self.tdof * state.units.boltz * self.t_target;
    }

    /// Half step of the chain; scales the group's velocities (LAMMPS' nhc_temp_integrate).
    fn nhc_temp_integrate(&mut self, state: &mut State) -> Result<(), RunError> {
        let boltz = state.units.boltz;
        let (dthalf, dt4, dt8) = (0.5 * state.dt, 0.25 * state.dt, 0.125 * state.dt);
        let m = self.mtchain;
        let mut kecurrent = self.tdof * boltz * self.t_current;
        // masses follow the target, so the chain keeps its frequency
        self.eta_mass[0] = self.tdof * boltz * self.t_target / (self.t_freq * self.t_freq);
        for ich in 1..m {
            self.eta_mass[ich] = boltz * self.t_target / (self.t_freq * self.t_freq);
        }
        self.eta_dotdot[0] = if self.eta_mass[0] > 0.0 { (kecurrent - self.ke_target) / self.eta_mass[0] } else { 0.0 };
        let ncfac = 1.0 / self.nc_tchain as f64;
        for _ in 0..self.nc_tchain {
            for ich in (1..m).rev() {
                let expfac = (-ncfac * dt8 * self.eta_dot[ich + 1]).exp();
                self.eta_dot[ich] *= expfac;
                self.eta_dot[ich] += self.eta_dotdot[ich] * ncfac * dt4;
                self.eta_dot[ich] *= self.tdrag_factor;
                self.eta_dot[ich] *= expfac;
            }
            let expfac = (-ncfac * dt8 * self.eta_dot[1]).exp();
            self.eta_dot[0] *= expfac;
            self.eta_dot[0] += self.eta_dotdot[0] * ncfac * dt4;
            self.eta_dot[0] *= self.tdrag_factor;
            self.eta_dot[0] *= expfac;

            let factor_eta = (-ncfac * dthalf * self.eta_dot[0]).exp();
            self.temp.scale(state, self.groupbit, factor_eta)?;

            // the temperature scales with the velocities; LAMMPS does not recompute it
            self.t_current *= factor_eta * factor_eta;
            kecurrent = self.tdof * boltz * self.t_current;
            self.eta_dotdot[0] = if self.eta_mass[0] > 0.0 { (kecurrent - self.ke_target) / self.eta_mass[0] } else { 0.0 };

            for ich in 0..m {
                self.eta[ich] += ncfac * dthalf * self.eta_dot[ich];
            }
            self.eta_dot[0] *= expfac;
            self.eta_dot[0] += self.eta_dotdot[0] * ncfac * dt4;
            self.eta_dot[0] *= expfac;
            for ich in 1..m {
                let expfac = (-ncfac * dt8 * self.eta_dot[ich + 1]).exp();
                self.eta_dot[ich] *= expfac;
                self.eta_dotdot[ich] = (self.eta_mass[ich - 1] * self.eta_dot[ich - 1] * self.eta_dot[ich - 1] - boltz * self.t_target) / self.eta_mass[ich];
                self.eta_dot[ich] += self.eta_dotdot[ich] * ncfac * dt4;
                self.eta_dot[ich] *= expfac;
            }
        }
        Ok(())
    }

    /// v += dtf/m f for the group, and in the first half x += dt v (LAMMPS' nve_v, nve_x).
    fn nve(&self, state: &mut State, first: bool) {
        let dtv = state.dt;
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let per_atom = state.atoms.features.per_atom_mass();
        let type_mass = &state.type_mass;
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let m = if per_atom { a.rmass[i] } else { type_mass[a.typ[i]] };
                super::kick(&mut a.v[i], dtf / m, &a.f[i]);
            }
        }
        if first {
            for i in 0..a.nlocal {
                if a.mask[i] & self.groupbit != 0 {
                    super::drift(&mut a.x[i], dtv, &a.v[i]);
                }
            }
        }
    }
}

impl Fix for FixNvt {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "nvt"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, final_integrate: true, ..FixHooks::default() }
    }
    fn modify_temp(&mut self, spec: crate::models::compute::temp_bias::TempSpec) -> Result<(), String> {
        self.temp.replace(spec);
        Ok(())
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        self.temp.count_dof(state, ctx);
        self.tdrag_factor = 1.0 - (state.dt * self.t_freq * self.drag / self.nc_tchain as f64);
        Ok(())
    }
    /// The drag factor depends on dt (LAMMPS' FixNH::reset_dt).
    fn reset_dt(&mut self, state: &State) -> Result<(), String> {
        self.tdrag_factor = 1.0 - (state.dt * self.t_freq * self.drag / self.nc_tchain as f64);
        Ok(())
    }
    fn setup(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.t_current = self.temp.compute(state)?;
        self.tdof = self.temp.dof;
        self.compute_temp_target(state);
        let boltz = state.units.boltz;
        let f2 = self.t_freq * self.t_freq;
        self.eta_mass[0] = self.tdof * boltz * self.t_target / f2;
        for ich in 1..self.mtchain {
            self.eta_mass[ich] = boltz * self.t_target / f2;
        }
        for ich in 1..self.mtchain {
            self.eta_dotdot[ich] = (self.eta_mass[ich - 1] * self.eta_dot[ich - 1] * self.eta_dot[ich - 1] - boltz * self.t_target) / self.eta_mass[ich];
        }
        Ok(())
    }
    fn initial_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.compute_temp_target(state);
        self.nhc_temp_integrate(state)?;
        self.nve(state, true);
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        self.nve(state, false);
        self.t_current = self.temp.compute(state)?;
        self.tdof = self.temp.dof;
        self.nhc_temp_integrate(state)?;
        Ok(())
    }
    /// The chain's energy: L kT eta_1 + sum_k>1 kT eta_k + sum 0.5 Q_k eta_dot_k^2.
    fn scalar(&self, state: &State) -> Option<f64> {
        let kt = state.units.boltz * self.t_target;
        let mut energy = self.ke_target * self.eta[0] + 0.5 * self.eta_mass[0] * self.eta_dot[0] * self.eta_dot[0];
        for ich in 1..self.mtchain {
            energy += kt * self.eta[ich] + 0.5 * self.eta_mass[ich] * self.eta_dot[ich] * self.eta_dot[ich];
        }
        Some(energy)
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
    /// LAMMPS' FixNH::pack_restart_data without a barostat: tstat_flag, the chain length,
    /// eta, eta_dot, pstat_flag.
    fn write_restart(&self) -> Option<Vec<f64>> {
        let m = self.mtchain;
        let mut list = vec![1.0, m as f64];
        list.extend_from_slice(&self.eta[..m]);
        list.extend_from_slice(&self.eta_dot[..m]);
        list.push(0.0);
        Some(list)
    }
    /// LAMMPS' FixNH::restart: the chain only when its length is this fix's.
    fn restart(&mut self, list: &[f64]) {
        let m = self.mtchain;
        if let [tstat, len, rest @ ..] = list {
            if *tstat != 0.0 && *len == m as f64 && rest.len() >= 2 * m {
                self.eta[..m].copy_from_slice(&rest[..m]);
                self.eta_dot[..m].copy_from_slice(&rest[m..2 * m]);
            }
        }
    }
}
