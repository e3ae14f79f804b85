//! Errors of the verification suite.

use thiserror::Error;

/// Everything that can go wrong while running a verification test.
#[derive(Debug, Error)]
pub enum VerifyError {
    /// A parameter outside its allowed range.
    #[error("invalid {name} = {value}: expected {expected}")]
    Invalid {
        /// Parameter name.
        name: &'static str,
        /// Its value, formatted.
        value: String,
        /// What is allowed.
        expected: &'static str,
    },
    /// The law crate refused a parameter.
    #[error(transparent)]
    Contact(#[from] mdr_contact::ContactError),
    /// The validator failed.
    #[error(transparent)]
    Impact(#[from] mdr_impact::ImpactError),
    /// The rapier coupling failed.
    #[error(transparent)]
    Coupling(#[from] mdr_rapier::CouplingError),
    /// A rapier scene did not separate within its step budget.
    #[error("rapier scene did not separate within {steps} steps")]
    NoSeparation {
        /// Steps run.
        steps: u64,
    },
    /// Writing a figure failed.
    #[error("plot {path}: {message}")]
    Plot {
        /// Output path.
        path: String,
        /// What failed.
        message: String,
    },
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, VerifyError>;

pub(crate) fn invalid(
    name: &'static str,
    value: impl ToString,
    expected: &'static str,
) -> VerifyError {
    VerifyError::Invalid {
        name,
        value: value.to_string(),
        expected,
    }
}
