//! `compute ID group gyration`: the group's radius of gyration about its centre of mass (the
//! scalar) and the gyration tensor xx yy zz xy xz yz (the vector), both mass-weighted over
//! unwrapped positions and divided by the group's mass, as LAMMPS' compute gyration. The
//! `gyration(group)` group function is the same scalar.

use super::{expect_no_args, Compute};
use crate::engine::state::State;
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Word};

pub struct ComputeGyration {
    id: String,
    groupbit: u32,
}

impl ComputeGyration {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group gyration")?;
        Ok(ComputeGyration { id, groupbit })
    }
}

/// Each member's displacement from the centre `c` (unwrapped) with its mass, in LAMMPS' atom
/// order.
fn about(state: &State, bit: u32, c: [f64; 3]) -> Result<Vec<([f64; 3], f64)>, String> {
    let dom = state.domain()?;
    let a = &state.atoms;
    let order = state.lammps_order.indices(a.nlocal);
    let d = order.iter().filter(|&&i| a.mask[i] & bit != 0).map(|&i| {
        let u = dom.unmap(a.x[i], a.image[i]);
        ([u[0] - c[0], u[1] - c[1], u[2] - c[2]], state.mass(i))
    });
    Ok(d.collect())
}

/// The radius of gyration of group `bit` (0 for a massless group), over the ranks.
pub fn radius(state: &State, bit: u32) -> Result<f64, String> {
    let (c, m) = state.group_xcm(bit);
    radius_about(state, bit, c, m)
}

/// [`radius`] about the group's centre `c` and mass `m` already summed (LAMMPS' gyration with
/// its xcm).
pub fn radius_about(state: &State, bit: u32, c: [f64; 3], m: f64) -> Result<f64, String> {
    let d = about(state, bit, c)?;
    let mut rg = [d.iter().map(|(d, mi)| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * mi).sum::<f64>()];
    state.sum_ranks(&mut rg);
    Ok(if m > 0.0 { (rg[0] / m).sqrt() } else { 0.0 })
}

/// The gyration tensor xx yy zz xy xz yz of group `bit`, over the ranks.
pub fn tensor(state: &State, bit: u32) -> Result<[f64; 6], String> {
    let (c, m) = state.group_xcm(bit);
    let d = about(state, bit, c)?;
    let mut t = [0.0; 6];
    for (d, mi) in d {
        let p = [d[0] * d[0], d[1] * d[1], d[2] * d[2], d[0] * d[1], d[0] * d[2], d[1] * d[2]];
        for k in 0..6 {
            t[k] += p[k] * mi;
        }
    }
    state.sum_ranks(&mut t);
    if m > 0.0 {
        t.iter_mut().for_each(|v| *v /= m);
    }
    Ok(t)
}

impl Compute for ComputeGyration {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "gyration"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        radius(w.state, self.groupbit)
    }
    fn size_vector(&self) -> Option<usize> {
        Some(6)
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        Ok(tensor(w.state, self.groupbit)?.to_vec())
    }
}
