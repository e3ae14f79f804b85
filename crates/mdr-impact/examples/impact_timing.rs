//! Wall-clock and CPU time of the two validator benchmark workloads (`benches/impact.rs`), for machines where other
//! jobs share the cores (CPU seconds do not depend on how many other processes run):
//! a 200-point curve with the 2,000-spring bed at 2,000 steps per contact, and 100,000
//! closed-form (energy route) velocities.
//!
//! Run: `cargo run --release -p mdr-impact --example impact_timing`

use mdr_impact::{log_spaced, Impact, Method, Sweep, DEFAULT_SPRINGS};
use std::time::Instant;

/// User + system CPU time of this process so far (s), from `/proc/self/stat` (Linux).
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let fields: Vec<&str> = stat.rsplit(')').next()?.split_whitespace().collect();
    // Fields 14 and 15 of stat(5) are utime and stime; after the `)` they are the 12th and 13th.
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

fn measure(label: &str, count: usize, mut work: impl FnMut()) {
    let mut best = f64::INFINITY;
    let mut best_cpu = f64::INFINITY;
    for _ in 0..3 {
        let cpu0 = cpu_seconds();
        let start = Instant::now();
        work();
        let wall = start.elapsed().as_secs_f64();
        if let (Some(a), Some(b)) = (cpu0, cpu_seconds()) {
            best_cpu = best_cpu.min(b - a);
        }
        best = best.min(wall);
    }
    println!(
        "{label}: best wall {best:.3} s ({:.0} per s), CPU {best_cpu:.2} s ({:.0} per CPU-second), {} threads",
        count as f64 / best,
        count as f64 / best_cpu,
        rayon::current_num_threads()
    );
}

fn main() {
    let speeds = log_spaced(0.01, 30.0, 200);
    let springs = Sweep::speeds(
        Impact::paper(1.0).method(Method::Springs {
            springs: DEFAULT_SPRINGS,
        }),
        &speeds,
    );
    measure("springs curve, 200 points", 200, || {
        std::hint::black_box(springs.run().unwrap());
    });
    let many = log_spaced(0.01, 30.0, 100_000);
    let closed = Sweep::speeds(Impact::paper(1.0), &many);
    measure("closed form, 100,000 velocities", 100_000, || {
        std::hint::black_box(closed.run().unwrap());
    });
}
