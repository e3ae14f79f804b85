//! Typed errors for every user-supplied number.

use thiserror::Error;

/// Everything that can go wrong when building a material, a pair or a law from user input.
///
/// Each variant names the parameter, the offending value and the allowed range, so that a
/// command-line program or a scene parser can pass the message straight to the user.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ContactError {
    /// A parameter is NaN or infinite where a finite number is required.
    #[error("parameter `{name}` must be a finite number, got {value}")]
    NotFinite {
        /// Parameter name as the user knows it (e.g. `youngs_modulus`).
        name: &'static str,
        /// The value that was given.
        value: f64,
    },
    /// A parameter lies outside its allowed range.
    #[error("parameter `{name}` = {value} is outside the allowed range {range}")]
    OutOfRange {
        /// Parameter name as the user knows it.
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// The allowed range in mathematical notation, e.g. `(-1, 0.5]`.
        range: &'static str,
    },
    /// A count (springs, table rows, …) is too small.
    #[error("parameter `{name}` = {value} is too small: at least {min} required")]
    TooFew {
        /// Parameter name.
        name: &'static str,
        /// The value that was given.
        value: usize,
        /// The smallest allowed value.
        min: usize,
    },
    /// A tabulated profile is not usable (unsorted abscissae, mismatched lengths, …).
    #[error("invalid table `{name}`: {reason}")]
    InvalidTable {
        /// Name of the table.
        name: &'static str,
        /// What is wrong with it.
        reason: String,
    },
}

/// Result alias of this crate.
pub type Result<T, E = ContactError> = std::result::Result<T, E>;

/// Check that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ContactError::NotFinite { name, value })
    }
}

/// Check that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(ContactError::OutOfRange {
            name,
            value,
            range: "(0, inf)",
        })
    }
}

/// Check that `value` is finite and not negative.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64> {
    finite(name, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(ContactError::OutOfRange {
            name,
            value,
            range: "[0, inf)",
        })
    }
}

/// Check that `value` is finite and lies in `[lo, hi]`; `range` is its printed form.
pub(crate) fn in_closed_range(
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    range: &'static str,
) -> Result<f64> {
    finite(name, value)?;
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(ContactError::OutOfRange { name, value, range })
    }
}
