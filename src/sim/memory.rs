//! Memory estimate reported before a run ("Per MPI rank memory allocation").

use crate::sim::Simulation;

/// Bytes held by per-atom arrays and neighbour lists.
pub fn bytes_per_rank(sim: &Simulation) -> usize {
    let a = &sim.state.atoms;
    let n = a.x.capacity();
    let mut b = n * (8 + 8 + 4 + 3 * 8 * 3 + 12);
    let ft = a.features;
    if ft.molecule {
        b += n * 8;
    }
    if ft.charge {
        b += n * 8;
    }
    if ft.sphere {
        b += n * (8 + 8 + 24 + 24);
    }
    if ft.sph {
        b += n * (5 * 8 + 24);
    }
    b += a.extra.iter().map(|e| e.data.capacity() * 8).sum::<usize>();
    b += sim.state.neighbor.list.chunks.iter().map(|c| c.neigh.capacity() * 4 + c.offsets.capacity() * 4).sum::<usize>();
    b
}

/// Bytes per owned particle (reported by runs and benchmarks).
pub fn bytes_per_particle(sim: &Simulation) -> f64 {
    let n = sim.state.atoms.nlocal.max(1);
    bytes_per_rank(sim) as f64 / n as f64
}
