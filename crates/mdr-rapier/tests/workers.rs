//! The pool's other threads kept awake ([`with_workers_awake`]): they wait busily while the
//! closure runs and stop when it returns or unwinds. Alone in its test binary, so that the
//! process's CPU time is this test's.

use mdr_rapier::neighbour_list::bed::process_cpu_seconds;
use mdr_rapier::neighbour_list::rayon::ThreadPoolBuilder;
use mdr_rapier::neighbour_list::with_workers_awake;
use std::time::Duration;

/// CPU seconds the process uses while the current thread sleeps for `ms` milliseconds.
fn cpu_while_sleeping(ms: u64) -> Option<f64> {
    let before = process_cpu_seconds()?;
    std::thread::sleep(Duration::from_millis(ms));
    Some(process_cpu_seconds()? - before)
}

/// CPU seconds the process uses while the current thread sleeps until it has used `cpu_s` or
/// `limit_ms` milliseconds have passed: a spinning thread reaches `cpu_s` however loaded the
/// machine is, a sleeping one never does.
fn cpu_while_sleeping_until(cpu_s: f64, limit_ms: u64) -> Option<f64> {
    let before = process_cpu_seconds()?;
    let start = std::time::Instant::now();
    loop {
        std::thread::sleep(Duration::from_millis(20));
        let used = process_cpu_seconds()? - before;
        if used > cpu_s || start.elapsed() >= Duration::from_millis(limit_ms) {
            return Some(used);
        }
    }
}

#[test]
fn workers_wait_busily_while_the_closure_runs_and_stop_after() {
    let pool = ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let (during, value) =
        pool.install(|| with_workers_awake(|| (cpu_while_sleeping_until(0.1, 10_000), 42)));
    assert_eq!(value, 42, "the closure's value comes back");
    let after = pool.install(|| cpu_while_sleeping(200));
    // A panic inside stops the waiting threads too, and the pool stays usable.
    let unwound = pool.install(|| {
        std::panic::catch_unwind(|| with_workers_awake(|| panic!("inside the closure")))
    });
    assert!(unwound.is_err());
    let after_panic = pool.install(|| cpu_while_sleeping(200));
    let sum: u64 = pool.install(|| {
        use mdr_rapier::neighbour_list::rayon::prelude::*;
        (0..1000u64).into_par_iter().sum()
    });
    assert_eq!(sum, 499_500);
    // Outside a pool, and in a pool of one thread, only the closure runs.
    assert_eq!(with_workers_awake(|| 7), 7);
    let one = ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let lone = one.install(|| with_workers_awake(|| cpu_while_sleeping(200)));
    let (Some(during), Some(after), Some(after_panic), Some(lone)) =
        (during, after, after_panic, lone)
    else {
        eprintln!("no process CPU clock here: the CPU checks are skipped");
        return;
    };
    println!("CPU s: awake {during:.3} (until 0.1 or 10 s), in 0.2 s after {after:.3}, after a panic {after_panic:.3}, one thread {lone:.3}");
    // The other thread spins through the sleep, so the process gathers 0.1 CPU s however
    // loaded the machine is; asleep, a pool uses none in 0.2 s.
    assert!(
        during > 0.1,
        "the other thread did not wait busily: {during} CPU s"
    );
    assert!(
        after < 0.05,
        "the other thread still spins after the closure: {after} CPU s"
    );
    assert!(
        after_panic < 0.05,
        "the other thread still spins after a panic: {after_panic} CPU s"
    );
    assert!(lone < 0.05, "a one-thread pool spun: {lone} CPU s");
}
