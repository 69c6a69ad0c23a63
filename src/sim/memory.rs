//! Memory: the estimate reported before a run ("Per MPI rank memory allocation"), and the check
//! that refuses a command whose allocation could not fit (a billion atoms from `create_atoms`),
//! before it allocates, instead of an abort on a failed allocation.

use crate::engine::atoms::AtomFeatures;
pub use crate::engine::memory::{available, check_fits, human};
use crate::sim::Simulation;

/// Bytes of the per-atom arrays of one atom with these features and `nextra` extra fields.
pub fn bytes_per_atom(ft: AtomFeatures, nextra: usize) -> usize {
    let mut b = 8 + 8 + 4 + 3 * 8 * 3 + 12;
    if ft.molecule {
        b += 8;
    }
    if ft.charge {
        b += 8;
    }
    if ft.sphere {
        b += 8 + 8 + 24 + 24;
    }
    if ft.sph {
        b += 5 * 8 + 24;
    }
    b + 8 * nextra
}

/// Bytes held by per-atom arrays and neighbour lists.
pub fn bytes_per_rank(sim: &Simulation) -> usize {
    let a = &sim.state.atoms;
    let n = a.x.capacity();
    let mut b = n * bytes_per_atom(a.features, 0);
    b += a.extra.iter().map(|e| e.data.capacity() * 8).sum::<usize>();
    b += sim.state.neighbor.list.chunks.iter().map(|c| c.bytes()).sum::<usize>();
    b
}

/// Bytes per owned particle (reported by runs and benchmarks).
pub fn bytes_per_particle(sim: &Simulation) -> f64 {
    let n = sim.state.atoms.nlocal.max(1);
    bytes_per_rank(sim) as f64 / n as f64
}

/// `N atom types`: every run's neighbour cutoff table (and a pair style's coefficient tables)
/// holds a double per type pair, (N+1)^2.
pub fn check_types(ntypes: usize) -> Result<(), String> {
    let n = ntypes as f64 + 1.0;
    check_fits(n * n * 8.0, &format!("{ntypes} atom types: a table of (N+1)^2 = {:.3e} type pairs x 8 bytes", n * n))
}

/// `n` new atoms with these features; `transient` bytes per atom held while they are made.
pub fn check_atoms(n: f64, ft: AtomFeatures, nextra: usize, transient: usize) -> Result<(), String> {
    let per = (bytes_per_atom(ft, nextra) + transient) as f64;
    check_fits(n * per, &format!("{n:.3e} atoms x {per} bytes"))
}
