//! Typed errors of the validator. Each names the parameter (by its configuration key, which is
//! also the command-line flag without `--`), the offending value and what is allowed.

use mdr_contact::ContactError;
use std::path::PathBuf;
use thiserror::Error;

/// Everything that can go wrong in the validator.
#[derive(Debug, Error)]
pub enum ImpactError {
    /// The law crate rejected a value; `key` is the configuration key it came from.
    #[error("invalid value for `{key}`: {source}")]
    Parameter {
        /// Configuration key (= command-line flag without `--`), e.g. `radius`, `target-youngs`.
        key: &'static str,
        /// The law crate's message (parameter, value and allowed range).
        #[source]
        source: ContactError,
    },
    /// A value outside what the validator accepts.
    #[error("invalid value for `{key}`: {value} ({allowed})")]
    Invalid {
        /// Configuration key (= command-line flag without `--`).
        key: &'static str,
        /// The value as given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// The measured data cannot determine the requested fit parameters.
    #[error("the data cannot determine the fit parameters: {0}")]
    Underdetermined(String),
    /// The optimiser failed.
    #[error("optimiser failed: {0}")]
    Optimiser(String),
    /// The time integration did not reach separation.
    #[error("the contact did not end within {steps} time steps (v0 = {speed} m/s)")]
    NoSeparation {
        /// Steps taken.
        steps: usize,
        /// Impact speed (m/s).
        speed: f64,
    },
    /// Reading or writing a file failed.
    #[error("cannot access `{path}`: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// A CSV file is malformed.
    #[error("bad CSV `{path}`: {reason}")]
    Csv {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// Drawing a plot failed.
    #[error("cannot draw plot `{path}`: {reason}")]
    Plot {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
}

impl ImpactError {
    /// Attach a configuration key to a law-crate error.
    pub fn parameter(key: &'static str) -> impl FnOnce(ContactError) -> Self {
        move |source| Self::Parameter { key, source }
    }

    /// A value the validator does not accept.
    pub fn invalid(key: &'static str, value: impl ToString, allowed: impl ToString) -> Self {
        Self::Invalid {
            key,
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }

    /// The configuration key this error is about, if any.
    pub fn key(&self) -> Option<&'static str> {
        match self {
            Self::Parameter { key, .. } | Self::Invalid { key, .. } => Some(key),
            _ => None,
        }
    }
}

/// Result alias of this crate.
pub type Result<T, E = ImpactError> = std::result::Result<T, E>;
