//! Several scenes run at once on one pool all finish. Each step of a run on the rapier pipeline
//! hands rapier's tree optimisation to another thread of the pool and blocks until it is done; with
//! as many runs as the pool has threads, every thread could block so and the runs would hang. The
//! runs here are bounded by a watchdog, so a hang fails the test instead of stalling the suite.

use mdr_sim::scene::validate::parse_scene;
use mdr_sim::{run_scene, RunOptions};
use std::path::PathBuf;
use std::sync::{mpsc, Arc};
use std::time::Duration;

/// Two scenes whose every step runs rapier's pipeline: the drum, shortened (the neighbour-list
/// path, its walls turning as rapier bodies), and the drop scene in restitution mode.
fn scenes() -> Vec<(String, String)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let read = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
    let drum_text = read("drum.toml");
    let drum = drum_text.replace("duration_s = 2.0", "duration_s = 0.02");
    assert_ne!(drum, drum_text, "drum.toml's duration key moved");
    let drop_text = read("drop.toml");
    let restitution = drop_text
        .replace("duration_s = 0.2 ", "duration_s = 0.11 ")
        .replace("dt_s = \"auto\"", "dt_s = 1e-4")
        .replace("steps_per_contact = 200", "")
        .replace(
            "headline = \"drop\"",
            "headline = \"drop\"\ncoupling = \"restitution\"",
        );
    assert_ne!(restitution, drop_text, "drop.toml's keys moved");
    vec![
        ("drum".to_owned(), drum),
        ("restitution".to_owned(), restitution),
    ]
}

/// Four callers share a pool of two threads, each running the two scenes three times: every run
/// finishes (before the pool kept a thread free of runs, this hung in about one try of ten).
#[test]
fn runs_sharing_a_pool_of_two_threads_all_finish() {
    let pool = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap(),
    );
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path().to_path_buf();
    let (done, finished) = mpsc::channel();
    let callers = 4;
    for caller in 0..callers {
        let pool = Arc::clone(&pool);
        let root = root.clone();
        let done = done.clone();
        std::thread::spawn(move || {
            for round in 0..3 {
                for (mode, text) in scenes() {
                    let path = root.join(format!("{mode}_{caller}_{round}.toml"));
                    let scene = parse_scene(&path, &text).unwrap_or_else(|p| panic!("{p}"));
                    let options = RunOptions::new(root.join(format!("{mode}_{caller}_{round}")))
                        .quiet(true)
                        .no_frames(true);
                    pool.install(|| run_scene(&scene, &options))
                        .unwrap_or_else(|e| panic!("{mode}: {e}"));
                }
            }
            done.send(caller).unwrap();
        });
    }
    drop(done);
    for _ in 0..callers {
        match finished.recv_timeout(Duration::from_secs(600)) {
            Ok(_) => {}
            Err(mpsc::RecvTimeoutError::Timeout) => {
                panic!("the runs sharing one pool did not finish within 600 s: they hang")
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => panic!("a run failed (see its panic)"),
        }
    }
}
