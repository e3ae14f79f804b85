//! Typed errors of the ring crate.

use thiserror::Error;

/// Everything that can go wrong when setting up or running a ring.
///
/// Parameter errors name the parameter, its value and the allowed range so that the command-line
/// program can pass the message straight to the user.
#[derive(Debug, Error)]
pub enum RingError {
    /// A parameter lies outside its allowed range (or is not finite).
    #[error("parameter `{name}` = {value} is outside the allowed range {range}")]
    OutOfRange {
        /// Parameter name as the user knows it (e.g. `box`).
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// The allowed range in mathematical notation, e.g. `(0, inf)`.
        range: &'static str,
    },
    /// The initial conditions could not be drawn (the box is too full to place the particles
    /// without overlap).
    #[error("could not place particle {index} without overlap after {attempts} attempts: the box is too full")]
    Placement {
        /// Index of the particle that could not be placed.
        index: usize,
        /// Number of attempts made.
        attempts: usize,
    },
    /// A contact-law parameter was rejected by the law crate.
    #[error(transparent)]
    Contact(#[from] mdr_contact::ContactError),
    /// A restitution-law parameter was rejected by the plugin.
    #[error(transparent)]
    Coupling(#[from] mdr_rapier::CouplingError),
    /// Writing an output file failed.
    #[error("cannot write `{path}`: {source}")]
    Io {
        /// The file being written.
        path: String,
        /// The underlying error.
        source: std::io::Error,
    },
    /// Producing an output (CSV, JSON, VTK, SVG) failed.
    #[error("cannot produce `{path}`: {reason}")]
    Output {
        /// The file being produced.
        path: String,
        /// What went wrong.
        reason: String,
    },
}

/// Result alias of this crate.
pub type Result<T, E = RingError> = std::result::Result<T, E>;

/// Check that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(RingError::OutOfRange {
            name,
            value,
            range: "(0, inf)",
        })
    }
}

/// Check that `value` is finite and lies in `[lo, hi]`; `range` is its printed form.
pub(crate) fn in_range(
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    range: &'static str,
) -> Result<f64> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(RingError::OutOfRange { name, value, range })
    }
}
