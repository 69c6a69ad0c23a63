//! Every threading primitive of dmhs: the slab schedule of the pair and bonded passes (chunks
//! of the neighbour list run even/odd so that concurrent tasks never write to the same atom),
//! parallel ranges over atoms, and the lanes of the batched kernels ([`lanes`]).

pub mod lanes;

use crate::engine::neighbor::{ChunkList, NeighList};
use rayon::prelude::*;

/// `s[i]` without a bounds check, for the hot loops. Callers index per-atom arrays with
/// neighbour-list entries (always < the number of owned + ghost atoms, which every per-atom
/// array holds) and per-type tables with atom types (validated to 1..=ntypes when atoms are
/// created or retyped, and tables hold ntypes + 1 entries). Checked in debug builds.
#[inline(always)]
pub fn at<T: Copy>(s: &[T], i: usize) -> T {
    debug_assert!(i < s.len(), "index {i} out of {}", s.len());
    // SAFETY: see above
    unsafe { *s.get_unchecked(i) }
}

/// A raw pointer that chunks of the slab decomposition share; see [`for_each_chunk`]. Copy, so
/// that a task can hold its own copy: through a captured reference the compiler reloaded the
/// pointer after every store made through it.
pub struct SharedMut<T>(*mut T, usize);
impl<T> Clone for SharedMut<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for SharedMut<T> {}
unsafe impl<T> Sync for SharedMut<T> {}
unsafe impl<T> Send for SharedMut<T> {}
impl<T> SharedMut<T> {
    pub fn new(data: &mut [T]) -> SharedMut<T> {
        SharedMut(data.as_mut_ptr(), data.len())
    }
    /// # Safety
    /// Callers must ensure no two threads touch the same index at once.
    #[inline]
    #[allow(clippy::mut_from_ref)]
    pub unsafe fn get(&self, i: usize) -> &mut T {
        debug_assert!(i < self.1);
        &mut *self.0.add(i)
    }
    /// The elements of `range` as a slice (a plain slice lets the compiler keep other data in
    /// registers across writes, which it cannot do for writes through [`SharedMut::get`]).
    /// # Safety
    /// Callers must ensure no other thread touches the range while the slice lives.
    #[inline]
    #[allow(clippy::mut_from_ref)]
    pub unsafe fn slice(&self, range: std::ops::Range<usize>) -> &mut [T] {
        assert!(range.start <= range.end && range.end <= self.1);
        std::slice::from_raw_parts_mut(self.0.add(range.start), range.end - range.start)
    }
}

/// Run `work` on every chunk of the list: first all even-numbered chunks in parallel, then all
/// odd-numbered ones. Chunk `c` may write to its own atoms and to those of chunk `c + 1` only
/// (guaranteed by the list builder), so concurrent chunks never touch the same atom, and every
/// atom receives its contributions in the same order whatever the thread count.
/// Returns the per-chunk results in chunk order.
pub fn for_each_chunk<R: Send + Default + Clone>(list: &NeighList, work: impl Fn(&ChunkList) -> R + Sync) -> Vec<R> {
    for_each_chunk_then(list, work, |_| ())
}

/// [`for_each_chunk`], and `done(chunk)` for every chunk as soon as no task writes to its atoms
/// any more, inside the task that wrote last (while its data are in that core's cache, and
/// without another parallel pass).
pub fn for_each_chunk_then<R: Send + Default + Clone>(list: &NeighList, work: impl Fn(&ChunkList) -> R + Sync, done: impl Fn(&ChunkList) + Sync) -> Vec<R> {
    let atoms = list.chunks.last().map(|c| c.end).unwrap_or(0);
    for_each_slab_then(list.chunks.len(), atoms, |c| work(&list.chunks[c]), |c| done(&list.chunks[c]))
}

/// Below this many owned atoms the slab schedule runs on the calling thread: waking a second
/// thread twice per loop costs more than it saves (the 564-particle Plinko scene ran slower with
/// 2 threads than with 1).
pub const PARALLEL_MIN_ATOMS: usize = 2000;

/// The even/odd schedule of [`for_each_chunk`] over `n` chunks given by index, for a system of
/// `atoms` owned atoms.
pub fn for_each_slab<R: Send + Default + Clone>(n: usize, atoms: usize, work: impl Fn(usize) -> R + Sync) -> Vec<R> {
    for_each_slab_then(n, atoms, work, |_| ())
}

/// [`for_each_slab`] with [`for_each_chunk_then`]'s `done`. Chunk c receives from tasks c - 1
/// and c: an odd c is complete after its own task (in the odd phase), an even c after task
/// c - 1 (chunk 0 after the even phase), so odd task c finishes c and c + 1, and task 1 also 0.
pub fn for_each_slab_then<R: Send + Default + Clone>(n: usize, atoms: usize, work: impl Fn(usize) -> R + Sync, done: impl Fn(usize) + Sync) -> Vec<R> {
    let mut out = vec![R::default(); n];
    let task = |c: usize| {
        let r = work(c);
        if c % 2 == 1 {
            if c == 1 {
                done(0);
            }
            done(c);
            if c + 1 < n {
                done(c + 1);
            }
        }
        r
    };
    if rayon::current_num_threads() == 1 || n < 2 || atoms < PARALLEL_MIN_ATOMS {
        // same order of contributions as the parallel schedule
        for parity in 0..2 {
            for c in (parity..n).step_by(2) {
                out[c] = task(c);
            }
        }
        if n == 1 {
            done(0);
        }
        return out;
    }
    for parity in 0..2 {
        // one task per chunk (with_max_len(1)): work is often concentrated in a few slabs (a
        // water column in a wide tank), and rayon's default splitting would leave them on one thread
        let results: Vec<(usize, R)> = (parity..n).step_by(2).collect::<Vec<_>>().into_par_iter().with_max_len(1).map(|c| (c, task(c))).collect();
        for (c, r) in results {
            out[c] = r;
        }
    }
    out
}

/// Run `work` over index ranges covering `0..n` (`chunk` indices each), in parallel when the
/// pool has several threads: for per-atom loops whose atoms are independent, so the results are
/// the same either way. With one thread it is one plain loop, without the pool's overhead.
pub fn for_each_range(n: usize, chunk: usize, work: impl Fn(std::ops::Range<usize>) + Sync + Send) {
    use rayon::prelude::*;
    if rayon::current_num_threads() == 1 || n <= chunk {
        work(0..n);
    } else {
        (0..n.div_ceil(chunk)).into_par_iter().with_max_len(1).for_each(|c| work(c * chunk..((c + 1) * chunk).min(n)));
    }
}

/// Indices per parallel work item of [`any_index`].
const ANY_CHUNK: usize = 4096;

/// Whether `bad(i)` holds for some i in `0..n`: chunks in parallel, each folded without
/// branches (so it vectorizes). The answer is a boolean, the same for every thread count.
pub fn any_index(n: usize, bad: impl Fn(usize) -> bool + Sync) -> bool {
    use rayon::prelude::*;
    let chunk_bad = |c: usize| (c * ANY_CHUNK..((c + 1) * ANY_CHUNK).min(n)).fold(false, |acc, i| acc | bad(i));
    let chunks = n.div_ceil(ANY_CHUNK);
    if rayon::current_num_threads() == 1 || chunks <= 1 {
        (0..chunks).any(chunk_bad)
    } else {
        (0..chunks).into_par_iter().any(chunk_bad)
    }
}


#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// `done(c)` comes once per chunk, after both tasks that write to the chunk (c - 1 and c),
    /// for any number of chunks and threads.
    #[test]
    fn slab_schedule_finishes_every_chunk_once_after_its_writers() {
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            for n in 0..9 {
                let writes: Vec<AtomicUsize> = (0..n + 1).map(|_| AtomicUsize::new(0)).collect();
                let done: Vec<AtomicUsize> = (0..n).map(|_| AtomicUsize::new(0)).collect();
                let out = pool.install(|| {
                    for_each_slab_then(
                        n,
                        PARALLEL_MIN_ATOMS,
                        |c| {
                            writes[c].fetch_add(1, Ordering::SeqCst);
                            writes[c + 1].fetch_add(1, Ordering::SeqCst);
                            c
                        },
                        |c| {
                            let writers = if c == 0 { 1 } else { 2 };
                            assert_eq!(writes[c].load(Ordering::SeqCst), writers, "chunk {c} of {n} finished early");
                            done[c].fetch_add(1, Ordering::SeqCst);
                        },
                    )
                });
                assert_eq!(out, (0..n).collect::<Vec<_>>());
                assert!(done.iter().all(|d| d.load(Ordering::SeqCst) == 1), "{threads} threads, {n} chunks");
            }
        }
    }
}
