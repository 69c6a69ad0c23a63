//! The team: threads that stay awake between the parallel loops of a run, as an OpenMP team
//! does. A step runs a dozen short loops (integrators, the pair and bonded phases, the list
//! build); handed to a pool whose idle threads had gone to sleep, and whose tasks landed on
//! whichever thread stole them, a short loop took longer on two threads than on one (fix nve of
//! a 10,000-atom melt: 0.070 s on one thread, 0.157 s on two; docs/performance.md).
//!
//! - The calling thread is thread 0 of its team and takes part in every loop.
//! - A loop of `n` tasks is cut into one contiguous block per thread; a thread runs its own
//!   block first (so a thread meets the same atoms in every loop of the step, in its cache),
//!   then helps with the others' blocks. Which thread runs a task never changes a result: tasks
//!   write disjoint windows (see [`super::slab_phase`]).
//! - An idle worker spins for [`SPIN`] before it parks, so the next loop of a step finds it
//!   awake, and a finished run leaves no thread busy.
//!
//! A team belongs to the thread that made it ([`with_threads`]); a loop started on any other
//! thread, or from inside a task, runs on the calling thread alone.

use std::any::Any;
use std::cell::{Cell, RefCell};
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::rc::Rc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long an idle worker spins before it parks.
pub const SPIN: Duration = Duration::from_micros(200);

/// One loop: the task to run for each index, the blocks of indices and what is left.
struct Job {
    /// The caller's closure, its lifetime erased: it is called only for an index claimed from
    /// a block, and the caller returns only when every index has been claimed and finished.
    task: *const (dyn Fn(usize) + Sync),
    /// Per thread: the next unclaimed index of its block and the block's end.
    next: Vec<Cursor>,
    end: Vec<usize>,
    /// Indices not finished yet.
    left: AtomicUsize,
    /// The first panic of a task, raised again on the calling thread.
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

/// A block's next index, alone on its cache line (each thread claims from its own block).
#[repr(align(64))]
struct Cursor(AtomicUsize);

// SAFETY: the task is `Sync` (called from several threads at once) and outlived by the caller,
// which waits for `left == 0` before it returns (see `Job::task`).
unsafe impl Send for Job {}
unsafe impl Sync for Job {}

impl Job {
    /// Claim and run indices, own block first, until none is left unclaimed.
    fn work(&self, me: usize) {
        let blocks = self.next.len();
        for b in (0..blocks).map(|k| (me + k) % blocks) {
            loop {
                let k = self.next[b].0.fetch_add(1, Ordering::Relaxed);
                if k >= self.end[b] {
                    break;
                }
                // SAFETY: index k was claimed, so the caller is still waiting (left > 0)
                let task = unsafe { &*self.task };
                if let Err(p) = catch_unwind(AssertUnwindSafe(|| task(k))) {
                    self.panic.lock().unwrap_or_else(|e| e.into_inner()).get_or_insert(p);
                }
                self.left.fetch_sub(1, Ordering::Release);
            }
        }
    }
}

/// What the calling thread and its workers share.
struct Shared {
    /// Bumped once per loop (and at the end of the team).
    epoch: AtomicUsize,
    job: Mutex<Option<Arc<Job>>>,
    quit: AtomicBool,
    /// Workers parked or about to park, and what wakes them.
    sleepers: AtomicUsize,
    sleep: Mutex<()>,
    wake: Condvar,
}

struct Team {
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
    /// A loop is running (a loop started from one of its tasks runs serially).
    busy: Cell<bool>,
}

thread_local! {
    static TEAM: RefCell<Option<Rc<Team>>> = const { RefCell::new(None) };
}

fn worker(shared: Arc<Shared>, me: usize) {
    let mut seen = 0usize;
    loop {
        // spin, then park until the epoch moves
        let start = Instant::now();
        let mut spins = 0u32;
        while shared.epoch.load(Ordering::Acquire) == seen {
            std::hint::spin_loop();
            spins = spins.wrapping_add(1);
            if spins % 256 == 0 {
                // more threads than free cores: let a thread that holds a task run
                std::thread::yield_now();
            }
            if spins % 64 == 0 && start.elapsed() > SPIN {
                let mut g = shared.sleep.lock().unwrap_or_else(|e| e.into_inner());
                shared.sleepers.fetch_add(1, Ordering::SeqCst);
                while shared.epoch.load(Ordering::SeqCst) == seen {
                    g = shared.wake.wait(g).unwrap_or_else(|e| e.into_inner());
                }
                shared.sleepers.fetch_sub(1, Ordering::SeqCst);
                break;
            }
        }
        seen = shared.epoch.load(Ordering::Acquire);
        if shared.quit.load(Ordering::Acquire) {
            return;
        }
        let job = shared.job.lock().unwrap_or_else(|e| e.into_inner()).clone();
        if let Some(job) = job {
            if me < job.next.len() {
                job.work(me);
            }
        }
    }
}

impl Team {
    fn new(threads: usize) -> Team {
        let shared = Arc::new(Shared {
            epoch: AtomicUsize::new(0),
            job: Mutex::new(None),
            quit: AtomicBool::new(false),
            sleepers: AtomicUsize::new(0),
            sleep: Mutex::new(()),
            wake: Condvar::new(),
        });
        let mut workers = Vec::new();
        for me in 1..threads {
            let s = shared.clone();
            // a worker that cannot start leaves a smaller team
            match std::thread::Builder::new().name(format!("dmhs-{me}")).stack_size(8 << 20).spawn(move || worker(s, me)) {
                Ok(h) => workers.push(h),
                Err(_) => break,
            }
        }
        Team { shared, workers, busy: Cell::new(false) }
    }

    fn threads(&self) -> usize {
        self.workers.len() + 1
    }

    fn bump(&self) {
        self.shared.epoch.fetch_add(1, Ordering::SeqCst);
        if self.shared.sleepers.load(Ordering::SeqCst) > 0 {
            let _g = self.shared.sleep.lock().unwrap_or_else(|e| e.into_inner());
            self.shared.wake.notify_all();
        }
    }

    fn run(&self, n: usize, task: &(dyn Fn(usize) + Sync)) {
        let blocks = self.threads().min(n);
        let bound = |b: usize| b * n / blocks;
        // SAFETY (of the erased lifetime): this function returns only after `left` reached 0,
        // and a task is called only for a claimed index below its block's end
        let task: *const (dyn Fn(usize) + Sync + '_) = task;
        let task: *const (dyn Fn(usize) + Sync) = unsafe { std::mem::transmute(task) };
        let job = Arc::new(Job {
            task,
            next: (0..blocks).map(|b| Cursor(AtomicUsize::new(bound(b)))).collect(),
            end: (0..blocks).map(|b| bound(b + 1)).collect(),
            left: AtomicUsize::new(n),
            panic: Mutex::new(None),
        });
        *self.shared.job.lock().unwrap_or_else(|e| e.into_inner()) = Some(job.clone());
        self.busy.set(true);
        self.bump();
        job.work(0);
        let mut spins = 0u32;
        while job.left.load(Ordering::Acquire) > 0 {
            std::hint::spin_loop();
            spins = spins.wrapping_add(1);
            if spins % 256 == 0 {
                // a worker descheduled (more threads than cores): give it the core
                std::thread::yield_now();
            }
        }
        self.busy.set(false);
        *self.shared.job.lock().unwrap_or_else(|e| e.into_inner()) = None;
        let panic = job.panic.lock().unwrap_or_else(|e| e.into_inner()).take();
        if let Some(p) = panic {
            resume_unwind(p);
        }
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        self.shared.quit.store(true, Ordering::SeqCst);
        self.bump();
        for h in self.workers.drain(..) {
            let _ = h.join();
        }
    }
}

/// Run `f` with a team of `threads` threads (the calling thread and `threads - 1` workers) for
/// the loops it starts on this thread; the previous team (if any) comes back afterwards.
pub fn with_threads<R>(threads: usize, f: impl FnOnce() -> R) -> R {
    let team = Some(Rc::new(Team::new(threads.max(1))));
    let before = TEAM.with(|t| std::mem::replace(&mut *t.borrow_mut(), team));
    struct Restore(Option<Option<Rc<Team>>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let before = self.0.take().flatten();
            TEAM.with(|t| *t.borrow_mut() = before);
        }
    }
    let _restore = Restore(Some(before));
    f()
}

/// The team of the calling thread, unless a loop of it is running.
fn current() -> Option<Rc<Team>> {
    TEAM.with(|t| t.borrow().as_ref().filter(|team| !team.busy.get()).cloned())
}

/// Threads a loop started here would use.
pub fn threads() -> usize {
    current().map_or(1, |t| t.threads())
}

/// Run `task(k)` for every `k` in `0..n`, on the calling thread's team when it has one (each
/// index exactly once, in no particular order across threads), in index order otherwise. A
/// panic of a task is raised here once every task has finished.
pub fn run(n: usize, task: &(dyn Fn(usize) + Sync)) {
    match current() {
        Some(team) if n > 1 && team.threads() > 1 => team.run(n, task),
        _ => (0..n).for_each(task),
    }
}

/// `f` of every item, in the items' order, computed as [`run`] runs its tasks.
pub fn map<T: Send, R: Send>(items: Vec<T>, f: impl Fn(T) -> R + Sync) -> Vec<R> {
    if threads() == 1 || items.len() < 2 {
        return items.into_iter().map(f).collect();
    }
    let slots: Vec<Mutex<(Option<T>, Option<R>)>> = items.into_iter().map(|t| Mutex::new((Some(t), None))).collect();
    run(slots.len(), &|k| {
        let mut slot = slots[k].lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = slot.0.take() {
            slot.1 = Some(f(t));
        }
    });
    slots.into_iter().map(|s| s.into_inner().unwrap_or_else(|e| e.into_inner()).1.expect("every task ran")).collect()
}

/// Run `f` with the calling thread's team set aside: its loops run on this thread alone (a
/// pass with too little work to share).
pub fn alone<R>(f: impl FnOnce() -> R) -> R {
    let team = TEAM.with(|t| t.borrow().clone());
    let Some(team) = team.filter(|t| !t.busy.get()) else { return f() };
    team.busy.set(true);
    struct Free(Rc<Team>);
    impl Drop for Free {
        fn drop(&mut self) {
            self.0.busy.set(false);
        }
    }
    let _free = Free(team);
    f()
}

/// Whether the calling thread has a team of its own (made by [`with_threads`]).
pub fn installed() -> bool {
    TEAM.with(|t| t.borrow().is_some())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_index_runs_once_on_any_team() {
        for threads in [1, 2, 3, 5] {
            with_threads(threads, || {
                assert_eq!(super::threads(), threads);
                for n in [0, 1, 2, 3, 7, 100] {
                    let hits: Vec<AtomicUsize> = (0..n).map(|_| AtomicUsize::new(0)).collect();
                    for _ in 0..50 {
                        run(n, &|k| {
                            hits[k].fetch_add(1, Ordering::Relaxed);
                        });
                    }
                    assert!(hits.iter().all(|h| h.load(Ordering::Relaxed) == 50), "{threads} threads, {n} tasks");
                }
            });
            assert_eq!(super::threads(), 1);
        }
    }

    #[test]
    fn a_loop_inside_a_task_runs_on_its_thread() {
        with_threads(2, || {
            let total = AtomicUsize::new(0);
            run(4, &|_| {
                assert_eq!(super::threads(), 1);
                run(3, &|_| {
                    total.fetch_add(1, Ordering::Relaxed);
                });
            });
            assert_eq!(total.load(Ordering::Relaxed), 12);
        });
    }

    #[test]
    fn a_panicking_task_panics_the_caller_after_the_others_finish() {
        with_threads(2, || {
            let done = AtomicUsize::new(0);
            let r = catch_unwind(AssertUnwindSafe(|| {
                run(8, &|k| {
                    if k == 5 {
                        panic!("task 5");
                    }
                    done.fetch_add(1, Ordering::Relaxed);
                })
            }));
            assert!(r.is_err());
            assert_eq!(done.load(Ordering::Relaxed), 7);
            // the team still works
            let n = AtomicUsize::new(0);
            run(10, &|_| {
                n.fetch_add(1, Ordering::Relaxed);
            });
            assert_eq!(n.load(Ordering::Relaxed), 10);
        });
    }

    #[test]
    fn a_parked_worker_wakes_for_the_next_loop() {
        with_threads(2, || {
            std::thread::sleep(SPIN * 5);
            let n = AtomicUsize::new(0);
            run(64, &|_| {
                n.fetch_add(1, Ordering::Relaxed);
            });
            assert_eq!(n.load(Ordering::Relaxed), 64);
        });
    }
}
