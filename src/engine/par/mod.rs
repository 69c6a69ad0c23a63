//! Every threading primitive of dmhs and every `unsafe` block of the engine crate (the others
//! are in [`lanes`], the vector type of the batched kernels, [`bounded`], neighbour entries
//! that read per-atom arrays and write a task's window without bounds checks, [`cmath`],
//! the C library's cube root, and [`team`], the threads every loop below runs on).
//!
//! - The slab schedule ([`slab_phase`]): the pair and bonded passes split the owned atoms into chunks
//!   along one axis (the neighbour list's chunks); task `c` writes only to the atoms of chunks
//!   `c` and `c + 1`, so all even tasks run at once, then all odd ones. Each task receives its
//!   own window of every array it writes ([`AtomsMut`], indexed by atom index), split off with
//!   safe slice splitting: no two tasks can touch the same atom, and a write outside the
//!   window panics instead of racing. Every atom receives its contributions in the same order
//!   whatever the thread count, so results do not depend on it. [`window_phase`] is the same
//!   schedule with wider windows (bonded interactions reaching further).
//! - Parallel ranges over independent atoms ([`ranges`]) for the integrators and other per-atom
//!   loops, and a parallel "any" ([`any_index`]).
//!
//! The invariant the slab schedule rests on (a listed owned partner of an atom in chunk `c` lies
//! in chunk `c` or `c + 1`) is established by the neighbour-list builder and checked there with
//! [`check_slab_invariant`] in debug builds.

pub mod bounded;
pub mod cmath;
pub mod lanes;
pub mod team;

pub use team::{alone, threads, with_threads};
use std::ops::{Index, IndexMut, Range};

/// Below this many owned atoms the slab schedule runs on the calling thread.
pub const PARALLEL_MIN_ATOMS: usize = 200;

/// Below this much work (the entries of a pair pass's neighbour list, the interactions of a
/// bonded pass) a pass runs on the calling thread ([`alone`]): 564 ring-cell particles with
/// 1,100 bonds and angles and almost no contacts (the Plinko scene) ran slower on two threads,
/// a 216-particle SPH channel with 3,100 pairs faster (docs/performance.md).
pub const PARALLEL_MIN_WORK: usize = 2500;

/// A mutable window on per-atom values, indexed by atom index: the atoms `start..start + len`.
/// An array a model does not have (empty) stays empty in every window.
pub struct AtomsMut<'a, T> {
    start: usize,
    data: &'a mut [T],
}

impl<'a, T> AtomsMut<'a, T> {
    /// The whole array, atom 0 first.
    pub fn new(data: &'a mut [T]) -> AtomsMut<'a, T> {
        AtomsMut { start: 0, data }
    }
    /// The atoms of the window.
    pub fn range(&self) -> Range<usize> {
        self.start..self.start + self.data.len()
    }
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }
    /// The values of atoms `r` as a plain slice (its first element is atom `r.start`).
    pub fn slice(&mut self, r: Range<usize>) -> &mut [T] {
        &mut self.data[r.start - self.start..r.end - self.start]
    }
}

impl<T> Index<usize> for AtomsMut<'_, T> {
    type Output = T;
    #[inline(always)]
    fn index(&self, i: usize) -> &T {
        &self.data[i.wrapping_sub(self.start)]
    }
}

impl<T> IndexMut<usize> for AtomsMut<'_, T> {
    #[inline(always)]
    fn index_mut(&mut self, i: usize) -> &mut T {
        &mut self.data[i.wrapping_sub(self.start)]
    }
}

/// A mutable window on per-chunk items (e.g. the contact histories of a list's chunks), indexed
/// by chunk index.
pub struct ChunksMut<'a, T> {
    start: usize,
    data: &'a mut [T],
}

impl<'a, T> ChunksMut<'a, T> {
    pub fn new(data: &'a mut [T]) -> ChunksMut<'a, T> {
        ChunksMut { start: 0, data }
    }
}

impl<T> Index<usize> for ChunksMut<'_, T> {
    type Output = T;
    fn index(&self, c: usize) -> &T {
        &self.data[c.wrapping_sub(self.start)]
    }
}

impl<T> IndexMut<usize> for ChunksMut<'_, T> {
    fn index_mut(&mut self, c: usize) -> &mut T {
        &mut self.data[c.wrapping_sub(self.start)]
    }
}

/// Data a schedule splits among its tasks.
pub trait Split: Sized + Send {
    /// The part before atom `atom` (which starts chunk `chunk`) and the rest.
    fn split(self, atom: usize, chunk: usize) -> (Self, Self);
}

impl<T: Send> Split for AtomsMut<'_, T> {
    fn split(self, atom: usize, _chunk: usize) -> (Self, Self) {
        let at = (atom - self.start).min(self.data.len());
        let (a, b) = self.data.split_at_mut(at);
        (AtomsMut { start: self.start, data: a }, AtomsMut { start: self.start + at, data: b })
    }
}

impl<T: Send> Split for ChunksMut<'_, T> {
    fn split(self, _atom: usize, chunk: usize) -> (Self, Self) {
        let at = (chunk - self.start).min(self.data.len());
        let (a, b) = self.data.split_at_mut(at);
        (ChunksMut { start: self.start, data: a }, ChunksMut { start: self.start + at, data: b })
    }
}

macro_rules! tuples {
    ($($name:ident)+) => {
        impl<$($name: Split),+> Split for ($($name,)+) {
            #[allow(non_snake_case)]
            fn split(self, atom: usize, chunk: usize) -> (Self, Self) {
                let ($($name,)+) = self;
                $(let $name = $name.split(atom, chunk);)+
                (($($name.0,)+), ($($name.1,)+))
            }
        }
    };
}
tuples!(A);
tuples!(A B);
tuples!(A B C);
tuples!(A B C D);
tuples!(A B C D E);
tuples!(A B C D E F);

/// Whether a schedule over `atoms` owned atoms should use the team.
fn parallel(atoms: usize) -> bool {
    atoms >= PARALLEL_MIN_ATOMS && threads() > 1
}

/// One phase of the slab schedule: chunk `c` holds atoms `bounds[c]..bounds[c + 1]`; every task
/// `c` of the phase (`c % 2 == parity`) runs `work(c, window)` with the window of `data` on
/// chunks `c` and `c + 1`, and its result goes to `out[c]`. Run the even phase (0), then the odd
/// one (1), each with a fresh borrow of the arrays:
///
/// ```ignore
/// let mut parts = vec![Tally::default(); nchunks];
/// for parity in 0..2 {
///     slab_phase(&bounds, parity, AtomsMut::new(&mut f), &mut parts, |c, mut f| { ... });
/// }
/// ```
///
/// Tasks run in parallel when the team has several threads and there are enough atoms, in
/// chunk order otherwise; every atom receives its contributions in the same order either way.
pub fn slab_phase<S: Split, R: Send>(bounds: &[usize], parity: usize, data: S, out: &mut [R], work: impl Fn(usize, S) -> R + Sync) {
    window_phase(bounds, 2, parity, data, out, work)
}

/// One phase of a schedule of `width`-chunk windows, the slab schedule's generalisation: every
/// task `c` with `c % width == phase` runs `work(c, window)` with the window of `data` on chunks
/// `c..c + width`, its result going to `out[c]`. Run phases `0..width` in turn. Tasks of one
/// phase are `width` chunks apart, so their windows do not overlap.
pub fn window_phase<S: Split, R: Send>(bounds: &[usize], width: usize, phase: usize, data: S, out: &mut [R], work: impl Fn(usize, S) -> R + Sync) {
    let n = bounds.len().saturating_sub(1);
    if phase >= n {
        return;
    }
    let mut rest = data.split(bounds[phase], phase).1;
    if !(n >= 2 && parallel(bounds[n])) {
        // serial: each window as it is split off, no task list to allocate
        for c in (phase..n).step_by(width) {
            let end = (c + width).min(n);
            let (window, tail) = rest.split(bounds[end], end);
            out[c] = work(c, window);
            rest = tail;
        }
        return;
    }
    let mut tasks = Vec::with_capacity(n / width + 1);
    for c in (phase..n).step_by(width) {
        let end = (c + width).min(n);
        let (window, tail) = rest.split(bounds[end], end);
        tasks.push((c, window));
        rest = tail;
    }
    // one task per chunk: work is often concentrated in a few slabs (a water column in a wide
    // tank), which the team's threads share once their own blocks are done
    let results = team::map(tasks, |(c, w)| (c, work(c, w)));
    for (c, r) in results {
        out[c] = r;
    }
}

/// The chunks no task of the slab schedule writes to any more once task `c` (of `n`) is done:
/// chunk `c` receives from tasks `c - 1` and `c`, so chunk 0 is complete after task 0, an odd
/// chunk after its own task and an even one after the odd task before it. Both lie in task
/// `c`'s window.
pub fn completed_after(c: usize, n: usize) -> Range<usize> {
    if c == 0 {
        0..1.min(n)
    } else if c % 2 == 1 {
        c..(c + 2).min(n)
    } else {
        0..0
    }
}

/// Check the slab invariant for the chunks `bounds` of a list whose chunk `c` holds, for each of
/// its atoms, the partner indices `partners(c)`: every owned partner (index < the owned count
/// `bounds[n]`) of an atom of chunk `c` lies in chunks `c` or `c + 1`.
pub fn check_slab_invariant<'a>(bounds: &[usize], partners: impl Fn(usize) -> &'a [u32], index: impl Fn(u32) -> usize) -> Result<(), String> {
    let n = bounds.len().saturating_sub(1);
    let nlocal = bounds.last().copied().unwrap_or(0);
    for c in 0..n {
        let hi = bounds[(c + 2).min(n)];
        for &raw in partners(c) {
            let j = index(raw);
            if j < nlocal && !(bounds[c] <= j && j < hi) {
                return Err(format!("chunk {c} lists owned atom {j}, outside its chunks {}..{hi}", bounds[c]));
            }
        }
    }
    Ok(())
}

/// Run `work(range, window)` over ranges of `chunk` atoms covering `0..n`, with the window of
/// `data` on that range, in parallel when the team has several threads and there are at least
/// four ranges (`chunk` says how much work is worth handing to another thread): for per-atom
/// loops whose atoms are independent, so the results are the same either way. Otherwise one
/// plain loop: a few thousand atoms of an integrator fit in one core's cache, and splitting
/// them moves them between caches every step.
pub fn ranges<S: Split>(n: usize, chunk: usize, data: S, work: impl Fn(Range<usize>, S) + Sync) {
    if threads() == 1 || n < 4 * chunk {
        work(0..n, data);
        return;
    }
    let mut tasks = Vec::with_capacity(n.div_ceil(chunk));
    let mut rest = data;
    for k in 0..n.div_ceil(chunk) {
        let end = ((k + 1) * chunk).min(n);
        let (window, tail) = rest.split(end, k + 1);
        tasks.push((k * chunk..end, window));
        rest = tail;
    }
    team::map(tasks, |(r, w)| work(r, w));
}

/// Indices per parallel work item of [`any_index`].
const ANY_CHUNK: usize = 4096;

/// Whether `bad(i)` holds for some i in `0..n`: chunks in parallel, each folded without
/// branches (so it vectorizes). The answer is a boolean, the same for every thread count.
pub fn any_index(n: usize, bad: impl Fn(usize) -> bool + Sync) -> bool {
    let chunk_bad = |c: usize| (c * ANY_CHUNK..((c + 1) * ANY_CHUNK).min(n)).fold(false, |acc, i| acc | bad(i));
    let chunks = n.div_ceil(ANY_CHUNK);
    if threads() == 1 || chunks <= 1 {
        (0..chunks).any(chunk_bad)
    } else {
        team::map((0..chunks).collect(), chunk_bad).into_iter().any(|b| b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every task writes its own and the next chunk's atoms through its window; chunks are
    /// complete exactly when `completed_after` says, and the sums do not depend on the thread
    /// count.
    #[test]
    fn slab_windows_cover_two_chunks_and_complete_in_order() {
        for threads in [1, 2, 3] {
            with_threads(threads, || {
                for n in 0..9usize {
                    // chunks of 3000 atoms, so the team is used
                    let bounds: Vec<usize> = (0..=n).map(|c| c * 3000).collect();
                    let natoms = n * 3000;
                    let mut writes = vec![0u32; natoms + 5];
                    let mut done = vec![0u32; n];
                    let mut out = vec![usize::MAX; n];
                    for parity in 0..2 {
                        slab_phase(&bounds, parity, (AtomsMut::new(&mut writes), ChunksMut::new(&mut done)), &mut out, |c, (mut w, mut d)| {
                            for i in bounds[c]..bounds[(c + 2).min(n)] {
                                w[i] += 1;
                            }
                            for k in completed_after(c, n) {
                                let writers = if k == 0 || n == 1 { 1 } else { 2 };
                                assert!((bounds[k]..bounds[k + 1]).all(|i| w[i] == writers), "chunk {k} of {n} complete too early");
                                d[k] += 1;
                            }
                            c
                        });
                    }
                    assert_eq!(out, (0..n).collect::<Vec<_>>());
                    assert!(done.iter().all(|&d| d == 1), "{threads} threads, {n} chunks: {done:?}");
                    assert!(writes[natoms..].iter().all(|&w| w == 0), "no task writes beyond the owned atoms");
                }
            });
        }
    }

    #[test]
    #[should_panic]
    fn a_write_outside_the_window_panics() {
        let bounds = [0, 10, 20, 30];
        let mut f = vec![0.0; 30];
        slab_phase(&bounds, 0, AtomsMut::new(&mut f), &mut [(), (), ()], |c, mut w| {
            if c == 0 {
                w[25] = 1.0;
            }
        });
    }

    #[test]
    fn the_invariant_check_names_a_partner_two_chunks_away() {
        let bounds = [0, 2, 4, 6];
        let ok: [&[u32]; 3] = [&[1, 3], &[5, 7], &[4, 9]];
        assert!(check_slab_invariant(&bounds, |c| ok[c], |j| j as usize).is_ok());
        let bad: [&[u32]; 3] = [&[5], &[], &[]];
        let e = check_slab_invariant(&bounds, |c| bad[c], |j| j as usize).unwrap_err();
        assert!(e.contains("chunk 0 lists owned atom 5"), "{e}");
    }

    /// Windows of four chunks: each atom is written once by every task whose window holds its
    /// chunk, on any number of threads.
    #[test]
    fn wide_windows_cover_four_chunks() {
        for threads in [1, 2, 3] {
            with_threads(threads, || {
                for n in 0..11usize {
                    let bounds: Vec<usize> = (0..=n).map(|c| c * 300).collect();
                    let mut writes = vec![0u32; n * 300];
                    let mut out = vec![usize::MAX; n];
                    for phase in 0..4 {
                        window_phase(&bounds, 4, phase, AtomsMut::new(&mut writes), &mut out, |c, mut w| {
                            for i in bounds[c]..bounds[(c + 4).min(n)] {
                                w[i] += 1;
                            }
                            c
                        });
                    }
                    assert_eq!(out, (0..n).collect::<Vec<_>>());
                    for (i, &w) in writes.iter().enumerate() {
                        assert_eq!(w as usize, (i / 300 + 1).min(4), "{threads} threads, {n} chunks, atom {i}");
                    }
                }
            });
        }
    }

    #[test]
    fn ranges_give_each_task_its_own_atoms() {
        let mut x = vec![0usize; 10_000];
        with_threads(2, || {
            ranges(x.len(), 1024, AtomsMut::new(&mut x), |r, mut w| {
                for i in r {
                    w[i] = i;
                }
            })
        });
        assert!(x.iter().enumerate().all(|(i, &v)| v == i));
    }
}
