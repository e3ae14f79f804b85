//! Several runs sharing one pool, each keeping the pool's other threads awake
//! ([`with_workers_awake`]): all finish.

use mdr_rapier::neighbour_list::rayon::ThreadPoolBuilder;
use mdr_rapier::neighbour_list::with_workers_awake;
use std::sync::mpsc;
use std::time::Duration;

/// Several runs share one pool, each keeping the others' threads awake: a thread that runs one of
/// them must never be caught waiting for another one's end (each would wait for the other). Two
/// callers start their runs on the pool's two threads at once (a barrier), then four more join;
/// each runs serial gaps and parallel loops inside `with_workers_awake`, and all must finish.
#[test]
fn concurrent_runs_in_one_pool_all_finish() {
    use mdr_rapier::neighbour_list::rayon::prelude::*;
    use std::sync::{Arc, Barrier};
    let pool = Arc::new(ThreadPoolBuilder::new().num_threads(2).build().unwrap());
    let both_started = Arc::new(Barrier::new(2));
    let (done, finished) = mpsc::channel();
    let callers = 6u64;
    for caller in 0..callers {
        let (pool, done, both_started) = (pool.clone(), done.clone(), both_started.clone());
        std::thread::spawn(move || {
            let total: u64 = pool.install(|| {
                if caller < 2 {
                    both_started.wait();
                }
                with_workers_awake(|| {
                    (0..300)
                        .map(|round| {
                            // A serial gap, then a parallel pass, as in a step.
                            std::thread::sleep(Duration::from_micros(50));
                            (0..2000u64)
                                .into_par_iter()
                                .map(|k| k * caller + round)
                                .sum::<u64>()
                        })
                        .sum()
                })
            });
            done.send((caller, total)).unwrap();
        });
    }
    let mut totals = Vec::new();
    for _ in 0..callers {
        match finished.recv_timeout(Duration::from_secs(60)) {
            Ok(t) => totals.push(t),
            Err(_) => panic!("runs sharing a pool did not all finish within 60 s: {totals:?}"),
        }
    }
    totals.sort();
    for (caller, total) in totals {
        let expected: u64 = (0..300u64).map(|r| caller * 1999 * 1000 + 2000 * r).sum();
        assert_eq!(total, expected, "caller {caller}");
    }
}
