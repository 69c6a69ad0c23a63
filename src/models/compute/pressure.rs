//! `compute ID all pressure temp-ID`: P = (N_dof kB T + sum r.f) / (dim V) * nktv2p
//! and the pressure tensor (the temperature compute's kinetic tensor + virial) / V.

use super::Compute;
use crate::models::world::World;
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
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, world: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if groupbit != 1 {
            return Err(a.error_at(&cmd.args[1], "compute pressure must use group all", "must be `all`"));
        }
        let w = a.word("temperature compute ID")?;
        match world.compute(&w.text) {
            Some(c) if c.dof(world).is_some() => {}
            Some(_) => return Err(a.error_at(w, format!("compute `{}` is not a temperature compute", w.text), "not a temperature")),
            None => return Err(a.error_at(w, format!("compute `{}` does not exist", w.text), "unknown compute")),
        }
        a.finish()?;
        Ok(Self::new(id, w.text.clone()))
    }
    fn temp<'a>(&self, w: &World<'a>) -> Result<&'a dyn super::Compute, String> {
        w.compute(&self.temp_id).ok_or_else(|| format!("compute `{}` used by pressure does not exist", self.temp_id))
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
    fn reset_temperature(&mut self, temp_id: &str) -> bool {
        self.temp_id = temp_id.to_string();
        true
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        let tc = self.temp(w)?;
        let t = tc.scalar(w)?;
        let dof = tc.dof(w).unwrap_or(0.0);
        let u = &w.state.units;
        Ok(scalar_pressure(w.state.dimension, dof * u.boltz * t, &w.virial(), w.state.domain()?.volume(), u.nktv2p))
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        let tc = self.temp(w)?;
        // the temperature compute's kinetic tensor (temp/sphere's has the rotational part)
        let k = tc.vector(w)?;
        Ok(tensor_pressure(&k, &w.virial(), w.state.domain()?.volume(), w.state.units.nktv2p).to_vec())
    }
}

/// P = (N_dof kB T + the virial's trace) / (dim V) * nktv2p, `dof_kt` = N_dof kB T, `volume` the
/// area in 2D (LAMMPS' ComputePressure::compute_scalar, its order of operations).
pub fn scalar_pressure(dimension: usize, dof_kt: f64, v: &[f64; 6], volume: f64, nktv2p: f64) -> f64 {
    let inv = 1.0 / volume;
    if dimension == 3 {
        (dof_kt + v[0] + v[1] + v[2]) / 3.0 * inv * nktv2p
    } else {
        (dof_kt + v[0] + v[1]) / 2.0 * inv * nktv2p
    }
}

/// The pressure tensor (kinetic tensor `k` + virial) / V * nktv2p (xx yy zz xy xz yz).
pub fn tensor_pressure(k: &[f64], v: &[f64; 6], volume: f64, nktv2p: f64) -> [f64; 6] {
    let inv = 1.0 / volume;
    std::array::from_fn(|c| (k[c] + v[c]) * inv * nktv2p)
}
