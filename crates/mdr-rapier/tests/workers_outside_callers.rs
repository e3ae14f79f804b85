//! A run started from outside the pool ([`run_awake`]) waits outside it for its place: a pool
//! thread that waits inside another run's parallel work never takes it up.

use mdr_rapier::neighbour_list::rayon;
use mdr_rapier::neighbour_list::run_awake;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

static A2_TAKEN: AtomicBool = AtomicBool::new(false);
static B2_TAKEN: AtomicBool = AtomicBool::new(false);
static SECOND_CALLED: AtomicBool = AtomicBool::new(false);

/// Spin until `flag` is set; a schedule the test did not arrange fails it instead of hanging.
fn wait_for(flag: &AtomicBool, what: &str) {
    let start = Instant::now();
    while !flag.load(Ordering::Acquire) {
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "{what} never happened"
        );
        std::hint::spin_loop();
    }
}

/// Two runs from two outside threads on a pool of two threads, which has one place for a run.
/// The first run's pool thread T_a and the awake thread T_b share its parallel work so that T_b
/// ends up waiting for a piece T_a took (`b2`) while the second run is handed over. Had the
/// second run entered the pool at once, T_b, waiting, would take it up and wait there for the
/// place the first run gives back only when T_b returns: both runs would stop for good (as
/// `rayon::scope(|_| with_workers_awake(…))` from the second thread does; it fails this test
/// with the message below). Waiting outside the pool, the second runs after the first.
#[test]
fn a_run_from_outside_the_pool_waits_there_for_its_place() {
    rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build_global()
        .expect("the global pool is built once, here");
    let (done, finished) = mpsc::channel();
    let first = done.clone();
    std::thread::spawn(move || {
        let value = run_awake(|| {
            rayon::join(
                // a1 on T_a, until T_b has taken a2; T_a then waits for a2 and takes b2.
                || wait_for(&A2_TAKEN, "T_b taking a2"),
                || {
                    A2_TAKEN.store(true, Ordering::Release);
                    rayon::join(
                        // b1 on T_b: returns after the second run was handed over, so that
                        // T_b then waits for b2 with that run queued.
                        || {
                            wait_for(&B2_TAKEN, "T_a taking b2");
                            wait_for(&SECOND_CALLED, "the second run's call");
                            std::thread::sleep(Duration::from_millis(50));
                        },
                        || {
                            B2_TAKEN.store(true, Ordering::Release);
                            std::thread::sleep(Duration::from_millis(300));
                        },
                    )
                },
            );
            1
        });
        first.send(value).unwrap();
    });
    std::thread::spawn(move || {
        wait_for(&B2_TAKEN, "T_a taking b2");
        SECOND_CALLED.store(true, Ordering::Release);
        done.send(run_awake(|| 2)).unwrap();
    });
    let mut values = Vec::new();
    for _ in 0..2 {
        match finished.recv_timeout(Duration::from_secs(60)) {
            Ok(v) => values.push(v),
            Err(_) => panic!("the two runs did not both finish within 60 s: {values:?}"),
        }
    }
    values.sort();
    assert_eq!(values, vec![1, 2]);
}
