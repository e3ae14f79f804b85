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
}

/// Wrap an I/O error with its file.
pub(crate) fn output(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> SimError + '_ {
    move |source| SimError::Output {
        path: path.to_path_buf(),
        source,
    }
}
