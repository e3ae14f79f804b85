//! Errors of a run.

use crate::checkpoint::CheckpointError;
use crate::scene::Problems;
use std::path::PathBuf;
use thiserror::Error;

/// Everything that can stop a scene from running.
#[derive(Debug, Error)]
pub enum SimError {
    /// The scene file has errors (each with file, line and key).
    #[error("{0}")]
    Scene(#[from] Problems),
    /// A checkpoint could not be written or was refused.
    #[error(transparent)]
    Checkpoint(#[from] CheckpointError),
    /// A parameter was refused by the law crate.
    #[error("contact law: {0}")]
    Contact(#[from] mdr_contact::ContactError),
    /// The coupling refused something.
    #[error("rapier coupling: {0}")]
    Coupling(#[from] mdr_rapier::CouplingError),
    /// The world could not be built.
    #[error("building the scene: {0}")]
    Build(String),
    /// An output file could not be written.
    #[error("writing {path}: {source}")]
    Output {
        /// File.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// The state became unusable (NaN or a particle far outside the scene).
    #[error("the run went wrong at t = {time:.6e} s (step {step}): {reason}")]
    Diverged {
        /// Simulated time (s).
        time: f64,
        /// Step.
        step: u64,
        /// What happened.
        reason: String,
    },
    /// A guard stopped the run: the energy balance drifted beyond `max_energy_drift`, or a
    /// sphere went through a wall. A checkpoint of the state was written, and the books and plots
    /// up to it.
    #[error("the run was stopped at t = {time:.6e} s (step {step}): {reason}; its state is in {}", checkpoint.display())]
    Stopped {
        /// Simulated time (s) of the check that tripped.
        time: f64,
        /// Step of the check.
        step: u64,
        /// What happened and what to do.
        reason: String,
        /// The checkpoint written.
        checkpoint: PathBuf,
    },
}

impl SimError {
    /// Whether the run was stopped by one of its guards (a non-finite state, the energy guard,
    /// a sphere through a wall) rather than refused before it started or failed to write.
    pub fn is_guard(&self) -> bool {
        matches!(self, SimError::Diverged { .. } | SimError::Stopped { .. })
    }

    /// Whether the input (scene file, checkpoint) was refused before anything ran.
    pub fn is_refused_input(&self) -> bool {
        match self {
            SimError::Scene(_) | SimError::Contact(_) | SimError::Build(_) => true,
            SimError::Checkpoint(e) => !matches!(e, CheckpointError::Encode { .. }),
            _ => false,
        }
    }
}

/// Wrap an I/O error with its file.
pub(crate) fn output(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> SimError + '_ {
    move |source| SimError::Output {
        path: path.to_path_buf(),
        source,
    }
}
