//! Subcommands of the `mdr-dem` program, one module per command group.

pub mod bench;
pub mod impact;
pub mod sim;
pub mod sim_laws;
pub mod sim_ring;
pub mod sim_run;
pub mod sim_run_gpu;
pub mod verify;

use mdr_sim::SimError;

/// Exit status of a finished command.
pub const EXIT_FINISHED: u8 = 0;
/// Exit status of a command that failed while it ran (an output that could not be written).
pub const EXIT_FAILED: u8 = 1;
/// Exit status of refused input: a flag, a scene file, a checkpoint or an output folder.
pub const EXIT_REFUSED: u8 = 2;
/// Exit status of a run stopped by a guard (a non-finite state, the energy guard, a sphere
/// through a wall), with a checkpoint where one could be written.
pub const EXIT_GUARD: u8 = 3;
/// Exit status of a run interrupted by Ctrl-C (SIGINT), with a checkpoint: 128 + SIGINT, as
/// shells report it.
pub const EXIT_INTERRUPTED: u8 = 130;

/// A command that ends with a given exit status, its messages already printed.
#[derive(Debug)]
pub struct Exit(pub u8);

impl std::fmt::Display for Exit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "exit status {}", self.0)
    }
}

impl std::error::Error for Exit {}

/// Input refused with a message (exit status [`EXIT_REFUSED`]).
#[derive(Debug)]
pub struct Refused(pub String);

impl std::fmt::Display for Refused {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Refused {}

/// The exit status for an error that ended a command.
pub fn exit_code(err: &anyhow::Error) -> u8 {
    for cause in err.chain() {
        if let Some(Exit(code)) = cause.downcast_ref::<Exit>() {
            return *code;
        }
        if cause.is::<Refused>() {
            return EXIT_REFUSED;
        }
        match cause.downcast_ref::<mdr_gpu::GpuRunError>() {
            Some(mdr_gpu::GpuRunError::Stopped { .. }) => return EXIT_GUARD,
            Some(mdr_gpu::GpuRunError::Gpu(e)) if gpu_refused_input(e) => return EXIT_REFUSED,
            _ => {}
        }
        if cause
            .downcast_ref::<mdr_gpu::GpuError>()
            .is_some_and(gpu_refused_input)
        {
            return EXIT_REFUSED;
        }
        if let Some(e) = cause.downcast_ref::<SimError>() {
            if e.is_guard() {
                return EXIT_GUARD;
            }
            if e.is_refused_input() {
                return EXIT_REFUSED;
            }
        }
    }
    EXIT_FAILED
}

/// Whether a GPU error refuses the input (a scene the GPU path lacks a part of, a setting out
/// of range) rather than reports a failure.
fn gpu_refused_input(e: &mdr_gpu::GpuError) -> bool {
    matches!(
        e,
        mdr_gpu::GpuError::Unsupported(_) | mdr_gpu::GpuError::OutOfRange { .. }
    )
}

/// The error's message and its causes, each cause once: a cause whose text the message already
/// holds (an I/O error quoted by its wrapper) is not repeated.
pub fn error_text(err: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in err.chain() {
        let part = cause.to_string();
        if !text.contains(&part) {
            if !text.is_empty() {
                text.push_str(": ");
            }
            text.push_str(&part);
        }
    }
    text
}

/// A pool of `threads` worker threads (the `--threads` flag of `bench` and `sim run`, at least 1).
fn rayon_pool(threads: usize) -> anyhow::Result<mdr_rapier::neighbour_list::rayon::ThreadPool> {
    if threads == 0 {
        return Err(
            Refused("--threads = 0 is outside the allowed range [1, inf)".to_owned()).into(),
        );
    }
    if let Ok(cores) = std::thread::available_parallelism() {
        if threads > cores.get() {
            eprintln!(
                "warning: --threads {threads} is more than the {cores} cores this process may use: \
                 the pool's threads wait for each pass busily, so with more threads than cores \
                 they take turns on the cores and a run loses half its speed or more; ask for {cores} \
                 at most"
            );
        }
    }
    Ok(mdr_rapier::neighbour_list::rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?)
}
