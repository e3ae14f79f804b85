//! How a run of steps uses its pool's threads: kept awake between passes
//! ([`with_workers_awake`]), and each pass's blocks handed to the same threads pass after pass
//! ([`map_tasks`]).
//!
//! A step of the neighbour-list path makes several parallel passes (the surfaces, the two
//! colours of the pair loop, the integration) with short serial parts between them. rayon puts
//! a worker that finds no work to sleep within microseconds, and waking it for the next pass
//! costs that pass tens of microseconds on a virtual machine, whose idle virtual CPU the host has
//! descheduled (measured in docs/performance.md, "The threads wait awake").
//! [`with_workers_awake`] keeps the other threads of the current pool busy-waiting, each taking
//! pool work the moment it appears, for as long as its closure runs: what MPI ranks and
//! OpenMP's active wait policy do. Which thread takes which work does not change any result of
//! the stepper (every sum has an order fixed by the particle count and the lists).
//!
//! A pool of `n ≥ 2` threads runs at most `n − 1` runs at once ([`with_workers_awake`] waits for
//! a free place, running the pool's other work meanwhile). rapier's step hands its tree
//! optimisation to another thread of the pool and blocks its own thread until it is done
//! (`PhysicsPipeline::join_deferred_bvh_optimize` waits on a channel): with as many runs as
//! threads, every thread could block in that wait with the optimisations queued behind them, and
//! the runs would never finish. One thread always left free of runs takes them.
//!
//! A run started from outside the pool ([`run_awake`]: a test, a Python thread, the command
//! line) takes its place on the calling thread, before it enters the pool. Entered first, it
//! could be taken up by a pool thread that is waiting, deep in its stack, for a piece of another
//! run's parallel work (rayon's waiting threads take queued work, injected runs included): that
//! thread would then wait for a place which the other run gives back only when this thread
//! returns, and both runs would stop for good.

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

thread_local! {
    /// How many [`with_workers_awake`] closures run on this thread (nested, or one run that a
    /// waiting thread took up).
    static RUNS: Cell<usize> = const { Cell::new(0) };
}

/// Threads that hold a run, per pool size. rayon does not name a pool, so pools of the same size
/// share a count: runs of two such pools may wait for each other, never for long, and never
/// more than the rule for one pool asks.
static RUNNING_THREADS: Mutex<Vec<(usize, usize)>> = Mutex::new(Vec::new());

/// Take a place among the `pool − 1` threads of a pool of `pool` threads that may hold a run,
/// if one is free.
fn try_take_place(pool: usize) -> bool {
    let mut running = lock(&RUNNING_THREADS);
    let index = match running.iter().position(|&(size, _)| size == pool) {
        Some(index) => index,
        None => {
            running.push((pool, 0));
            running.len() - 1
        }
    };
    let taken = &mut running[index].1;
    if *taken + 1 < pool {
        *taken += 1;
        true
    } else {
        false
    }
}

/// Give back a place taken by [`try_take_place`].
fn give_back_place(pool: usize) {
    let mut running = lock(&RUNNING_THREADS);
    if let Some(entry) = running.iter_mut().find(|(size, _)| *size == pool) {
        entry.1 = entry.1.saturating_sub(1);
    }
}

/// Wait, running the pool's other work (the runs under way need it), until this thread may hold
/// a run. A thread that already holds one (a run started inside a run's wait) keeps its place:
/// the number of threads that can block inside a run does not grow.
fn wait_for_place(pool: usize) -> bool {
    if RUNS.with(Cell::get) > 0 {
        return false;
    }
    while !try_take_place(pool) {
        if rayon::yield_now() != Some(rayon::Yield::Executed) {
            std::thread::sleep(Duration::from_micros(50));
        }
    }
    true
}

/// Run `f` on the current thread with the other threads of the current rayon pool kept awake:
/// each busy-waits, running any of the pool's pending work as soon as it appears (a parallel
/// pass of a step), until `f` returns or unwinds. Outside a pool, or in a pool of one thread,
/// just `f()`. The waiting threads use their cores fully while `f` runs, as MPI ranks do.
///
/// Several runs may share a pool (tests, or Python threads each running a scene): a thread that
/// is running one never waits for another's end (it declines the other's wait), so that no two
/// runs can each hold up the other; a thread that waits for one run takes up the pool's other
/// work as it comes, another run included. At most `n − 1` threads of a pool of `n` hold runs at
/// once (a run started on a thread that holds one shares its place): a further run first waits,
/// running the pool's other work, so that one thread is always free for what a run's step hands
/// off and then waits for (rapier's tree optimisation; the module documentation says why).
pub fn with_workers_awake<R>(f: impl FnOnce() -> R) -> R {
    awake(f, Place::Wait)
}

/// Run `f` as a run of the current rayon pool (the global pool outside one) with the pool's
/// other threads kept awake ([`with_workers_awake`]), the whole of it on one of the pool's
/// threads (a parallel pass started from a thread outside the pool hands its work over and
/// sleeps until it is done; from a pool thread it starts in place).
///
/// From outside the pool, the calling thread first waits (asleep: it is not one of the pool's)
/// for a place among the `n − 1` threads of a pool of `n` that may hold runs, and only then
/// hands the run to the pool, so that no pool thread ever waits for a place (the module
/// documentation says why that matters). From inside the pool, as
/// `rayon::scope(|_| with_workers_awake(f))`.
pub fn run_awake<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    let pool = rayon::current_num_threads();
    if rayon::current_thread_index().is_some() || pool < 2 {
        return rayon::scope(|_| with_workers_awake(f));
    }
    while !try_take_place(pool) {
        std::thread::sleep(Duration::from_micros(200));
    }
    /// Gives back the place when the run returns or unwinds.
    struct GiveBack(usize);
    impl Drop for GiveBack {
        fn drop(&mut self) {
            give_back_place(self.0);
        }
    }
    let _give_back = GiveBack(pool);
    rayon::scope(|_| awake(f, Place::Held))
}

/// Whether a run still has to wait for its place among the pool's threads that hold runs, or
/// holds one taken for it before it entered the pool ([`run_awake`]).
#[derive(Clone, Copy, PartialEq)]
enum Place {
    Wait,
    Held,
}

/// [`with_workers_awake`], with the run's place taken here (`Place::Wait`) or by the caller.
fn awake<R>(f: impl FnOnce() -> R, place: Place) -> R {
    let Some(me) = rayon::current_thread_index() else {
        return f();
    };
    let pool = rayon::current_num_threads();
    if pool < 2 {
        return f();
    }
    let took_place = place == Place::Wait && wait_for_place(pool);
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    // One copy per thread of the pool; the caller's own copy returns at once (it runs when the
    // caller next looks for work, e.g. while waiting for the other half of a join).
    rayon::spawn_broadcast(move |context| {
        // A thread in the middle of a run (this one's caller, or one waiting inside another run
        // for its parallel work) must not wait here: the run it holds could not go on.
        if context.index() == me || RUNS.with(Cell::get) > 0 {
            return;
        }
        while !flag.load(Ordering::Acquire) {
            if rayon::yield_now() != Some(rayon::Yield::Executed) {
                std::hint::spin_loop();
            }
        }
    });
    /// Stops the waiting threads when `f` returns or unwinds, ends this thread's run, and gives
    /// back the place it took (`Some(pool size)`).
    struct Release(Arc<AtomicBool>, Option<usize>);
    impl Drop for Release {
        fn drop(&mut self) {
            self.0.store(true, Ordering::Release);
            RUNS.with(|runs| runs.set(runs.get() - 1));
            if let Some(pool) = self.1 {
                give_back_place(pool);
            }
        }
    }
    RUNS.with(|runs| runs.set(runs.get() + 1));
    let _release = Release(stop, took_place.then_some(pool));
    f()
}

/// Run `f` on every task, spread over the threads of the current rayon pool (outside a pool,
/// the calling thread and the global pool's), and return the results in task order (which
/// thread ran a task changes no result). The parallel passes of the neighbour-list stepper run
/// their blocks of particles and pairs through it.
///
/// The tasks are cut into one part per thread, and each thread takes the tasks of its own part
/// first, one at a time, then what is left of the others'. A thread's part is set by its place
/// in the pool relative to the caller, so in a run of steps (one caller) a thread works on the
/// same particles pass after pass and step after step, and finds their sums, positions and
/// velocities in its own core's cache: handing them from core to core costs more than the work
/// on them. Once no task is left to take, the caller busy-waits for the others to finish theirs
/// (yielding its core after a few thousand spins, in case the thread it waits for needs it),
/// where a rayon `join` would let it sleep after a few dozen yields, and waking it would cost the
/// pass tens of microseconds on a virtual machine. With [`with_workers_awake`] no thread of a
/// run sleeps between its passes. docs/performance.md has the measurements.
///
/// A task must not wait for other pool work (the caller's busy wait runs no other work).
pub fn map_tasks<T: Send, R: Send>(tasks: Vec<T>, f: impl Fn(T) -> R + Sync) -> Vec<R> {
    let n = tasks.len();
    let pool = rayon::current_num_threads();
    let threads = pool.min(n);
    if threads < 2 {
        return tasks.into_iter().map(f).collect();
    }
    let tasks: Vec<Mutex<Option<T>>> = tasks.into_iter().map(|t| Mutex::new(Some(t))).collect();
    let results: Vec<Mutex<Option<R>>> = (0..n).map(|_| Mutex::new(None)).collect();
    // Part `p` of the tasks, `bounds[p]..bounds[p + 1]`, is first taken by the thread `p`
    // places after the caller in the pool (the same thread in every call of a run), so that a
    // thread works on the same particles in pass after pass and finds them in its own cache.
    let bounds: Vec<usize> = (0..=threads).map(|p| p * n / threads).collect();
    let cursors: Vec<AtomicUsize> = bounds[..threads]
        .iter()
        .map(|&b| AtomicUsize::new(b))
        .collect();
    let done = AtomicUsize::new(0);
    let caller = rayon::current_thread_index();
    // A thread's place after the caller (outside a pool, the caller comes first).
    let place = |thread: Option<usize>| match (thread, caller) {
        (Some(t), Some(c)) => (t + pool - c) % pool,
        (Some(t), None) => t + 1,
        (None, _) => 0,
    };
    /// Counts a task as done when it returns or unwinds, so that the caller's wait ends either
    /// way (the scope then passes the panic on).
    struct Done<'a>(&'a AtomicUsize);
    impl Drop for Done<'_> {
        fn drop(&mut self) {
            self.0.fetch_add(1, Ordering::Release);
        }
    }
    let work = || {
        let own = place(rayon::current_thread_index()) % threads;
        // Its own part first, then what is left of the others'.
        for p in (own..threads).chain(0..own) {
            loop {
                let k = cursors[p].fetch_add(1, Ordering::Relaxed);
                if k >= bounds[p + 1] {
                    break;
                }
                let _done = Done(&done);
                let task = lock(&tasks[k]).take().expect("each task is taken once");
                let result = f(task);
                *lock(&results[k]) = Some(result);
            }
        }
    };
    rayon::in_place_scope(|scope| {
        for _ in 1..threads {
            scope.spawn(|_| work());
        }
        work();
        // Spin, then also yield: with more threads than cores, the thread whose task is
        // awaited may need this core.
        let mut spins = 0u32;
        while done.load(Ordering::Acquire) < n {
            if spins < 4096 {
                spins += 1;
                std::hint::spin_loop();
            } else {
                std::thread::yield_now();
            }
        }
    });
    results
        .into_iter()
        .map(|r| {
            r.into_inner()
                .unwrap_or_else(PoisonError::into_inner)
                .expect("every task ran")
        })
        .collect()
}

/// The value behind `m`, also after a task panicked while holding it (the panic is passed on).
fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    }

    /// Every task runs once, its result comes back in its place, and tasks of both halves run
    /// on both threads when they are slow enough for the other thread to join in.
    #[test]
    fn tasks_run_once_each_and_come_back_in_order() {
        let expected: Vec<u64> = (0..1000u64).map(|k| k * k).collect();
        let runs = AtomicUsize::new(0);
        let square = |k: u64| {
            runs.fetch_add(1, Ordering::Relaxed);
            k * k
        };
        // Outside a pool, in pools of one, two and four threads, with the workers awake or not.
        assert_eq!(map_tasks((0..1000).collect(), square), expected);
        for threads in [1, 2, 4] {
            let pool = pool(threads);
            let plain = pool.install(|| map_tasks((0..1000).collect(), square));
            let awake =
                pool.install(|| with_workers_awake(|| map_tasks((0..1000).collect(), square)));
            assert_eq!(plain, expected, "{threads} threads");
            assert_eq!(awake, expected, "{threads} threads, workers awake");
        }
        assert_eq!(runs.load(Ordering::Relaxed), 7 * 1000);
        // Fewer tasks than threads, and none.
        let pool = pool(4);
        assert_eq!(
            pool.install(|| map_tasks(vec![3, 4], |k| k + 1)),
            vec![4, 5]
        );
        assert!(pool
            .install(|| map_tasks(Vec::<u8>::new(), |k| k))
            .is_empty());
        // Tasks that take a while: both threads take part.
        let threads: Vec<usize> = pool.install(|| {
            with_workers_awake(|| {
                map_tasks((0..64).collect(), |_: usize| {
                    std::thread::sleep(std::time::Duration::from_millis(2));
                    rayon::current_thread_index().unwrap()
                })
            })
        });
        let distinct: HashSet<usize> = threads.iter().copied().collect();
        assert!(distinct.len() > 1, "one thread ran every task: {threads:?}");
    }

    /// A task's panic reaches the caller once the other tasks are done, and the pool goes on.
    #[test]
    fn a_panicking_task_panics_the_caller() {
        let pool = pool(2);
        let finished = AtomicUsize::new(0);
        let outcome = pool.install(|| {
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                with_workers_awake(|| {
                    map_tasks((0..200).collect(), |k: usize| {
                        if k == 150 {
                            panic!("task {k}");
                        }
                        finished.fetch_add(1, Ordering::Relaxed);
                    })
                })
            }))
        });
        assert!(outcome.is_err());
        assert!(finished.load(Ordering::Relaxed) <= 199);
        assert_eq!(
            pool.install(|| map_tasks(vec![1, 2, 3], |k| 2 * k)),
            vec![2, 4, 6]
        );
    }
}
