//! `compute ID all pressure temp-ID`: P = (N_dof kB T + sum r.f) / (dim V) * nktv2p
//! and the pressure tensor (kinetic tensor + virial) / V.

use super::{temp::ke_tensor, Compute};
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID all pressure temp-ID";

pub struct ComputePressure {
    id: String,
    temp_id: String,
}

impl ComputePressure {
    pub fn new(id: String, temp_id: String) -> Self {
        ComputePressure { id, temp_id }
    }
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, sim: &Simulation) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if groupbit != 1 {
            return Err(a.error_at(&cmd.args[1], "compute pressure must use group all", "must be `all`"));
        }
        let w = a.word("temperature compute ID")?;
        match sim.find_compute(&w.text) {
            Some(k) if sim.computes[k].dof(sim).is_some() => {}
            Some(_) => return Err(a.error_at(w, format!("compute `{}` is not a temperature compute", w.text), "not a temperature")),
            None => return Err(a.error_at(w, format!("compute `{}` does not exist", w.text), "unknown compute")),
        }
        a.finish()?;
        Ok(Self::new(id, w.text.clone()))
    }
    fn temp<'a>(&self, sim: &'a Simulation) -> Result<&'a dyn super::Compute, String> {
        let k = sim.find_compute(&self.temp_id).ok_or_else(|| format!("compute `{}` used by pressure does not exist", self.temp_id))?;
        Ok(sim.computes[k].as_ref())
    }
}

impl Compute for ComputePressure {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "pressure"
    }
    fn groupbit(&self) -> u32 {
        1
    }
    fn scalar(&self, sim: &Simulation) -> Result<f64, String> {
        let tc = self.temp(sim)?;
        let t = tc.scalar(sim)?;
        let dof = tc.dof(sim).unwrap_or(0.0);
        let v = &sim.energies.virial;
        let vol = sim.domain()?.volume();
        let inv = 1.0 / vol;
        let u = &sim.units;
        Ok(if sim.dimension == 3 {
            (dof * u.boltz * t + v[0] + v[1] + v[2]) / 3.0 * inv * u.nktv2p
        } else {
            (dof * u.boltz * t + v[0] + v[1]) / 2.0 * inv * u.nktv2p
        })
    }
    fn vector(&self, sim: &Simulation) -> Result<Vec<f64>, String> {
        let tc = self.temp(sim)?;
        let k = ke_tensor(sim, tc.groupbit());
        let v = &sim.energies.virial;
        let inv = 1.0 / sim.domain()?.volume();
        let n = sim.units.nktv2p;
        Ok((0..6).map(|c| (k[c] + v[c]) * inv * n).collect())
    }
}
