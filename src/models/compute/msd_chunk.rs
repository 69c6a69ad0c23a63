//! `compute ID group msd/chunk chunkID`: per chunk of a compute chunk/atom, the squared
//! displacement of the chunk's centre of mass (unwrapped with image flags) from where it was at
//! the setup of the first run after the compute was defined, as LAMMPS' compute msd/chunk: a
//! global array of Nchunk rows, dx^2 dy^2 dz^2 and their sum. The number of chunks may not
//! change.

use super::Compute;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID group msd/chunk chunkID";

pub struct ComputeMsdChunk {
    id: String,
    groupbit: u32,
    chunk_id: String,
    /// The centres of mass at the first setup (LAMMPS' fix STORE cominit); None before it.
    cominit: Option<Vec<[f64; 3]>>,
}

impl ComputeMsdChunk {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let cw = a.word("chunkID")?;
        match w.compute(&cw.text) {
            Some(c) if c.as_chunk().is_some() => {}
            Some(c) => return Err(a.error_at(cw, format!("Compute msd/chunk does not use chunk/atom compute: `{}` is compute {}", cw.text, c.style()), "not chunk/atom")),
            None => return Err(a.error_at(cw, format!("Chunk/atom compute `{}` does not exist for compute msd/chunk", cw.text), "unknown compute")),
        }
        a.finish()?;
        Ok(ComputeMsdChunk { id, groupbit, chunk_id: cw.text.clone(), cominit: None })
    }

    /// Each chunk's centre of mass now (LAMMPS' compute_array: mass-weighted unwrapped sums in
    /// the atoms' order, then divided by the chunk's mass).
    fn centres(&self, w: &World) -> Result<Vec<[f64; 3]>, String> {
        let c = w.compute(&self.chunk_id).and_then(|c| c.as_chunk()).ok_or_else(|| format!("chunk/atom compute `{}` for compute msd/chunk {} does not exist", self.chunk_id, self.id))?;
        let s = w.state;
        let ch = c.setup_chunks(s)?;
        let ichunk = c.ichunk(s, &ch)?;
        if let Some(init) = &self.cominit {
            if init.len() != ch.nchunk {
                return Err(format!("compute msd/chunk {}: Compute msd/chunk nchunk is not static ({} chunks now, {} at its setup)", self.id, ch.nchunk, init.len()));
            }
        }
        let d = s.domain()?;
        let at = &s.atoms;
        let mut mass = vec![0.0; ch.nchunk];
        let mut com = vec![[0.0; 3]; ch.nchunk];
        for i in s.lammps_order.indices(at.nlocal).iter().copied() {
            if at.mask[i] & self.groupbit == 0 || ichunk[i] == 0 {
                continue;
            }
            let k = ichunk[i] - 1;
            let m = s.mass(i);
            let u = d.unmap(at.x[i], at.image[i]);
            mass[k] += m;
            com[k][0] += u[0] * m;
            com[k][1] += u[1] * m;
            com[k][2] += u[2] * m;
        }
        s.sum_ranks(&mut mass);
        let mut flat: Vec<f64> = com.iter().flatten().copied().collect();
        s.sum_ranks(&mut flat);
        for (k, c) in com.iter_mut().enumerate() {
            *c = [flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]];
            if mass[k] > 0.0 {
                c[0] /= mass[k];
                c[1] /= mass[k];
                c[2] /= mass[k];
            }
        }
        Ok(com)
    }
}

impl Compute for ComputeMsdChunk {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "msd/chunk"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn array_cols(&self) -> Option<usize> {
        Some(4)
    }
    /// The first setup keeps the centres (LAMMPS' setup with firstflag).
    fn setup_after_build(&mut self, w: &World) {
        if self.cominit.is_none() {
            // an error here (no chunk compute) is reported when the array is read
            self.cominit = self.centres(w).ok();
        }
    }
    fn array(&self, w: &World) -> Result<Vec<Vec<f64>>, String> {
        let now = self.centres(w)?;
        let Some(init) = &self.cominit else {
            return Ok(vec![vec![0.0; 4]; now.len()]);
        };
        Ok(now
            .iter()
            .zip(init)
            .map(|(c, c0)| {
                let (dx, dy, dz) = (c[0] - c0[0], c[1] - c0[1], c[2] - c0[2]);
                vec![dx * dx, dy * dy, dz * dz, dx * dx + dy * dy + dz * dz]
            })
            .collect())
    }
    fn reads(&self) -> Vec<(bool, String)> {
        vec![(false, self.chunk_id.clone())]
    }
}
