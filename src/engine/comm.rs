//! Communication between the ranks of a distributed run: the few collective and point-to-point
//! operations domain decomposition needs, behind one trait. `Serial` is the one-rank world of an
//! ordinary run; `Threads` runs ranks as threads of one process (tests of the decomposition in
//! the default build); `mpi_comm::Mpi` (cargo feature `mpi`) is MPICH through the `mpi` crate.
//!
//! Every rank calls the collective operations in the same order; a rank that fails stops the
//! others with [`Comm::abort`] rather than leave them waiting.

use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex};

pub trait Comm: Send + Sync {
    fn rank(&self) -> usize;
    fn size(&self) -> usize;
    /// Element-wise sum over the ranks, in rank order (so every rank gets the same bits).
    fn sum(&self, v: &mut [f64]);
    /// Element-wise maximum over the ranks.
    fn max(&self, v: &mut [f64]);
    /// Element-wise minimum over the ranks.
    fn min(&self, v: &mut [f64]) {
        let mut neg: Vec<f64> = v.iter().map(|x| -x).collect();
        self.max(&mut neg);
        for (x, n) in v.iter_mut().zip(neg) {
            *x = -n;
        }
    }
    /// Send `sends[k].1` to rank `sends[k].0` and receive one buffer from each rank in `from`
    /// (in that order). The ranks must agree: rank p lists q in its sends iff q lists p in `from`.
    fn exchange(&self, sends: Vec<(usize, Vec<f64>)>, from: &[usize]) -> Vec<Vec<f64>>;
    /// Every rank's buffer, in rank order, on every rank.
    fn allgather(&self, data: Vec<f64>) -> Vec<Vec<f64>>;
    /// Stop every rank: the error was printed by the caller.
    fn abort(&self, code: i32) -> !;

    /// The sum over ranks of one value.
    fn sum1(&self, x: f64) -> f64 {
        let mut v = [x];
        self.sum(&mut v);
        v[0]
    }
    /// Whether any rank says yes.
    fn any(&self, yes: bool) -> bool {
        let mut v = [if yes { 1.0 } else { 0.0 }];
        self.max(&mut v);
        v[0] > 0.0
    }
    /// The name of the machine this rank runs on (MPI's processor name).
    fn processor_name(&self) -> String {
        host_name()
    }
    /// Every rank's [`Comm::processor_name`], in rank order.
    fn processor_names(&self) -> Vec<String> {
        let mine = self.processor_name().bytes().map(|b| b as f64).collect();
        self.allgather(mine).into_iter().map(|v| v.into_iter().map(|b| b as u8 as char).collect()).collect()
    }
}

/// This machine's host name (Linux' kernel record; "localhost" where there is none).
pub fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname").map(|s| s.trim().to_string()).ok().filter(|s| !s.is_empty()).unwrap_or_else(|| "localhost".into())
}

/// One rank: every operation is the identity.
pub struct Serial;

impl Comm for Serial {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn sum(&self, _: &mut [f64]) {}
    fn max(&self, _: &mut [f64]) {}
    fn exchange(&self, sends: Vec<(usize, Vec<f64>)>, from: &[usize]) -> Vec<Vec<f64>> {
        // the only partner is this rank: what it sent, in order
        let mut sent = sends.into_iter().map(|s| s.1);
        from.iter().map(|_| sent.next().unwrap_or_default()).collect()
    }
    fn allgather(&self, data: Vec<f64>) -> Vec<Vec<f64>> {
        vec![data]
    }
    fn abort(&self, code: i32) -> ! {
        std::process::exit(code)
    }
}

/// Ranks as threads of one process, connected by channels: `Threads::world(n)` gives the n
/// communicators, one for each thread to run a rank with.
pub struct Threads {
    rank: usize,
    /// `to[q]` sends to rank q.
    to: Vec<Sender<Vec<f64>>>,
    /// `from[p]` receives what rank p sent here, in the order it was sent.
    from: Vec<Mutex<Receiver<Vec<f64>>>>,
    aborted: Arc<std::sync::atomic::AtomicBool>,
}

impl Threads {
    pub fn world(n: usize) -> Vec<Threads> {
        // channel[p][q]: from p to q
        let mut senders: Vec<Vec<Option<Sender<Vec<f64>>>>> = (0..n).map(|_| (0..n).map(|_| None).collect()).collect();
        let mut receivers: Vec<Vec<Option<Receiver<Vec<f64>>>>> = (0..n).map(|_| (0..n).map(|_| None).collect()).collect();
        for p in 0..n {
            for q in 0..n {
                let (s, r) = channel();
                senders[p][q] = Some(s);
                receivers[q][p] = Some(r);
            }
        }
        let aborted = Arc::new(std::sync::atomic::AtomicBool::new(false));
        (0..n)
            .map(|rank| Threads {
                rank,
                to: senders[rank].iter_mut().map(|s| s.take().unwrap()).collect(),
                from: receivers[rank].iter_mut().map(|r| Mutex::new(r.take().unwrap())).collect(),
                aborted: aborted.clone(),
            })
            .collect()
    }

    fn send(&self, q: usize, data: Vec<f64>) {
        // a peer that has gone (its thread ended after an error) cannot receive: nothing to do
        let _ = self.to[q].send(data);
    }
    fn recv(&self, p: usize) -> Vec<f64> {
        match self.from[p].lock().map(|r| r.recv()) {
            Ok(Ok(v)) => v,
            // the sender ended (it failed): this rank stops too
            _ => {
                self.aborted.store(true, std::sync::atomic::Ordering::Relaxed);
                panic!("rank {p} stopped: rank {} cannot go on", self.rank)
            }
        }
    }
    /// Everyone's buffer, in rank order.
    fn gather_all(&self, data: &[f64]) -> Vec<Vec<f64>> {
        for q in 0..self.to.len() {
            if q != self.rank {
                self.send(q, data.to_vec());
            }
        }
        (0..self.to.len()).map(|p| if p == self.rank { data.to_vec() } else { self.recv(p) }).collect()
    }
}

impl Comm for Threads {
    fn rank(&self) -> usize {
        self.rank
    }
    fn size(&self) -> usize {
        self.to.len()
    }
    fn sum(&self, v: &mut [f64]) {
        let all = self.gather_all(v);
        for (k, x) in v.iter_mut().enumerate() {
            *x = all.iter().fold(0.0, |s, b| s + b[k]);
        }
    }
    fn max(&self, v: &mut [f64]) {
        let all = self.gather_all(v);
        for (k, x) in v.iter_mut().enumerate() {
            *x = all.iter().map(|b| b[k]).fold(f64::NEG_INFINITY, f64::max);
        }
    }
    fn exchange(&self, sends: Vec<(usize, Vec<f64>)>, from: &[usize]) -> Vec<Vec<f64>> {
        for (q, data) in sends {
            self.send(q, data);
        }
        from.iter().map(|&p| self.recv(p)).collect()
    }
    fn allgather(&self, data: Vec<f64>) -> Vec<Vec<f64>> {
        self.gather_all(&data)
    }
    fn abort(&self, code: i32) -> ! {
        self.aborted.store(true, std::sync::atomic::Ordering::Relaxed);
        panic!("rank {} aborted with code {code}", self.rank)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thread_ranks_sum_exchange_and_gather() {
        let world = Threads::world(3);
        let results: Vec<(f64, Vec<Vec<f64>>, Vec<Vec<f64>>)> = std::thread::scope(|s| {
            let handles: Vec<_> = world
                .iter()
                .map(|c| {
                    s.spawn(move || {
                        let r = c.rank() as f64;
                        let total = c.sum1(r + 1.0);
                        // a ring: send to the next rank, receive from the previous one
                        let n = c.size();
                        let got = c.exchange(vec![((c.rank() + 1) % n, vec![r; 2])], &[(c.rank() + n - 1) % n]);
                        (total, got, c.allgather(vec![r]))
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        for (rank, (total, got, all)) in results.into_iter().enumerate() {
            assert_eq!(total, 6.0);
            assert_eq!(got, vec![vec![((rank + 2) % 3) as f64; 2]]);
            assert_eq!(all, vec![vec![0.0], vec![1.0], vec![2.0]]);
        }
    }
}
