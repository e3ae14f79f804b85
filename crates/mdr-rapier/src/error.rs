//! Typed errors of the coupling.

use mdr_contact::ContactError;
use rapier3d_f64::prelude::ColliderHandle;
use thiserror::Error;

/// Everything that can go wrong when building or stepping a coupled world.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CouplingError {
    /// A law or material parameter was rejected by the law crate.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// A parameter of the coupling lies outside its allowed range.
    #[error("parameter `{name}` = {value} is outside the allowed range {range}")]
    OutOfRange {
        /// Parameter name as the user knows it.
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// The allowed range, e.g. `(0, inf)`.
        range: &'static str,
    },
    /// The collider handle does not name a collider of the collider set.
    #[error("collider {0:?} is not in the collider set")]
    UnknownCollider(ColliderHandle),
    /// A collider registered as a sphere must have a ball shape.
    #[error("collider {0:?} is registered as a sphere but its shape is not a ball")]
    NotABall(ColliderHandle),
    /// A sphere must be attached to a rigid body (the law needs its mass and velocity).
    #[error("sphere collider {0:?} has no parent rigid body")]
    NoParentBody(ColliderHandle),
    /// The material handle does not name a material of the particle set.
    #[error("material handle {0} is not in the particle set (it holds {1} materials)")]
    UnknownMaterial(u32, usize),
    /// A combination of options that the chosen coupling does not support.
    #[error("unsupported: {0}")]
    Unsupported(&'static str),
    /// A saved fast-path state (neighbour lists, histories) does not fit the stepper it is
    /// restored into.
    #[error("the saved neighbour-list state does not fit this stepper: {0}")]
    StateMismatch(String),
}

/// Result alias of this crate.
pub type Result<T, E = CouplingError> = std::result::Result<T, E>;

/// Check that `value` is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CouplingError::OutOfRange {
            name,
            value,
            range: "(0, inf)",
        })
    }
}
