//! The pool's other threads kept awake through a run of steps.
//!
//! A step of the neighbour-list path makes several parallel passes (the surfaces, the two
//! colours of the pair loop, the integration) with short serial parts between them. rayon puts
//! a worker that finds no work to sleep within microseconds, and waking it for the next pass
//! costs that pass tens of microseconds on a virtual machine, whose idle virtual CPU the host has
//! descheduled: on the 2-core virtual machine of docs/performance.md a `join` of two 20 µs halves
//! took 21 µs right after another one, 45 µs after 10 µs of serial work and 89 µs after 50 µs.
//! [`with_workers_awake`] keeps the other threads of the current pool busy-waiting, each taking
//! pool work the moment it appears, for as long as its closure runs: what MPI ranks and
//! OpenMP's active wait policy do. Which thread takes which work does not change any result of
//! the stepper (every sum has an order fixed by the particle count and the lists).

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

thread_local! {
    /// How many [`with_workers_awake`] closures run on this thread (nested, or one run that a
    /// waiting thread took up).
    static RUNS: Cell<usize> = const { Cell::new(0) };
}

/// Run `f` on the current thread with the other threads of the current rayon pool kept awake:
/// each busy-waits, running any of the pool's pending work as soon as it appears (a parallel
/// pass of a step), until `f` returns or unwinds. Outside a pool, or in a pool of one thread,
/// just `f()`. The waiting threads use their cores fully while `f` runs, as MPI ranks do.
///
/// Several runs may share a pool (tests, or Python threads each running a scene): a thread that
/// is running one never waits for another's end (it declines the other's wait), so that no two
/// runs can each hold up the other; a thread that waits for one run takes up the pool's other
/// work as it comes, another run included.
pub fn with_workers_awake<R>(f: impl FnOnce() -> R) -> R {
    let Some(me) = rayon::current_thread_index() else {
        return f();
    };
    if rayon::current_num_threads() < 2 {
        return f();
    }
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
    /// Stops the waiting threads when `f` returns or unwinds, and ends this thread's run.
    struct Release(Arc<AtomicBool>);
    impl Drop for Release {
        fn drop(&mut self) {
            self.0.store(true, Ordering::Release);
            RUNS.with(|runs| runs.set(runs.get() - 1));
        }
    }
    RUNS.with(|runs| runs.set(runs.get() + 1));
    let _release = Release(stop);
    f()
}
