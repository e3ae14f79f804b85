//! Subcommands of the `mdr-dem` program, one module per command group.

pub mod bench;
pub mod impact;
pub mod sim;
pub mod sim_ring;
pub mod sim_run;
pub mod verify;

/// A pool of `threads` worker threads (the `--threads` flag of `bench` and `sim run`, at least 1).
fn rayon_pool(threads: usize) -> anyhow::Result<mdr_rapier::fast::rayon::ThreadPool> {
    if threads == 0 {
        anyhow::bail!("--threads = 0 is outside the allowed range [1, inf)");
    }
    Ok(mdr_rapier::fast::rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
}
