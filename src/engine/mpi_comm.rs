//! The ranks of `mpiexec -np N dmhs ...`: [`Comm`] over MPI's world communicator (MPICH, through
//! the `mpi` crate; cargo feature `mpi`). One thread of a rank at a time calls MPI (the one that
//! runs the deck, a worker of the rank's pool; the other workers never communicate), so MPI is
//! started with `MPI_THREAD_SERIALIZED`.

use crate::engine::comm::Comm;
use mpi::collective::SystemOperation;
use mpi::datatype::PartitionMut;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

/// MPI, started with [`Mpi::start`] and finalized when the guard it returns is dropped.
pub struct Mpi {
    rank: usize,
    size: usize,
}

impl Mpi {
    /// Start MPI: the communicator, and the guard that finalizes MPI when dropped (None when MPI
    /// cannot start or was started already).
    pub fn start() -> Option<(Mpi, mpi::environment::Universe)> {
        let (universe, _) = mpi::initialize_with_threading(mpi::Threading::Serialized)?;
        let world = universe.world();
        let me = Mpi { rank: world.rank() as usize, size: world.size() as usize };
        Some((me, universe))
    }
    fn world(&self) -> SimpleCommunicator {
        SimpleCommunicator::world()
    }
}

impl Comm for Mpi {
    fn rank(&self) -> usize {
        self.rank
    }
    fn processor_name(&self) -> String {
        mpi::environment::processor_name().unwrap_or_else(|_| crate::engine::comm::host_name())
    }
    fn size(&self) -> usize {
        self.size
    }
    fn sum(&self, v: &mut [f64]) {
        let send = v.to_vec();
        self.world().all_reduce_into(&send[..], v, SystemOperation::sum());
    }
    fn max(&self, v: &mut [f64]) {
        let send = v.to_vec();
        self.world().all_reduce_into(&send[..], v, SystemOperation::max());
    }
    fn exchange(&self, sends: Vec<(usize, Vec<f64>)>, from: &[usize]) -> Vec<Vec<f64>> {
        let world = self.world();
        mpi::request::scope(|scope| {
            // sends start first, so that no pair of ranks waits on each other's receive
            let requests: Vec<_> = sends.iter().map(|(q, buf)| world.process_at_rank(*q as i32).immediate_send(scope, &buf[..])).collect();
            let got: Vec<Vec<f64>> = from.iter().map(|&p| world.process_at_rank(p as i32).receive_vec::<f64>().0).collect();
            for r in requests {
                r.wait();
            }
            got
        })
    }
    fn allgather(&self, data: Vec<f64>) -> Vec<Vec<f64>> {
        let world = self.world();
        let n = data.len() as i32;
        let mut counts = vec![0i32; self.size];
        world.all_gather_into(&n, &mut counts[..]);
        let displs: Vec<i32> = counts.iter().scan(0, |at, &c| {
            let d = *at;
            *at += c;
            Some(d)
        }).collect();
        let total: i32 = counts.iter().sum();
        let mut all = vec![0.0f64; total as usize];
        {
            let mut part = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
            world.all_gather_varcount_into(&data[..], &mut part);
        }
        counts.iter().zip(&displs).map(|(&c, &d)| all[d as usize..(d + c) as usize].to_vec()).collect()
    }
    fn abort(&self, code: i32) -> ! {
        self.world().abort(code)
    }
}
