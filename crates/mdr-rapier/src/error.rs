//! Typed errors of the coupling.

use mdr_contact::ContactError;
use rapier3d_f64::prelude::{ColliderHandle, RigidBodyHandle};
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
    /// An impact scene's bodies were still in contact, or had not met, after its step budget
    /// (200 contact times of its time step).
    #[error(
        "the impact did not end within {steps} steps (200 contact times); the law's contact \
         lasts far longer than its time step resolves"
    )]
    ContactDidNotEnd {
        /// The steps run.
        steps: u64,
    },
    /// The body handle does not name a rigid body of the body set.
    #[error("rigid body {0:?} is not in the rigid-body set")]
    UnknownBody(RigidBodyHandle),
    /// Force mode was stepped on integration parameters that `configure` did not set (or that
    /// were changed since).
    #[error(
        "the world is not configured for force mode: {0}; call \
         `ForceModeStepper::configure(&mut world.integration_parameters, dt, prediction_distance)` \
         before stepping"
    )]
    NotConfigured(String),
    /// A registered collider lacks the flag or group its coupling needs (registered through
    /// `ParticleSet` by hand, or changed since).
    #[error("collider {collider:?} is registered with the coupling but {problem}; {fix}")]
    MissingFlag {
        /// The collider.
        collider: ColliderHandle,
        /// What is missing.
        problem: &'static str,
        /// How to fix it.
        fix: &'static str,
    },
    /// Restitution-mode hooks ran without knowing the step length.
    #[error(
        "the restitution hooks ran without a time step; call \
         `RestitutionHooks::prepare(&integration_parameters, &colliders)` before each \
         `PhysicsPipeline::step` (or step with `RestitutionHooks::step_with`)"
    )]
    TimeStepUnset,
    /// The time step the coupling was given differs from the one rapier integrates with (the
    /// law would advance its histories by one step while rapier moves the bodies by another).
    #[error(
        "the coupling was given dt = {coupling} s but rapier steps with dt = {world} s; {fix}"
    )]
    TimeStepMismatch {
        /// The step the coupling was given (s).
        coupling: f64,
        /// The step of the world's integration parameters (s).
        world: f64,
        /// How to fix it.
        fix: &'static str,
    },
    /// A force-mode step too long for a contact: symplectic Euler is unstable on it.
    #[error(
        "time step {dt:e} s exceeds the stability limit {limit:e} s of the contact between \
         {collider1:?} and {collider2:?} (Hertz contact time {contact_time:e} s at its approach \
         speed); reduce dt, e.g. to `stable_time_step(pair, v_max, 50.0)`"
    )]
    TimeStepTooLarge {
        /// The step (s).
        dt: f64,
        /// Stability limit `2 √(m / k_max)` of the contact (s).
        limit: f64,
        /// Hertz contact time at the approach speed (s).
        contact_time: f64,
        /// The sphere.
        collider1: ColliderHandle,
        /// The other collider.
        collider2: ColliderHandle,
    },
    /// A neighbour-list step too long for the fastest contact its particles could make at the
    /// last build: symplectic Euler is unstable on it.
    #[error(
        "time step {dt:e} s exceeds the stability limit {limit:e} s of a {kind} contact at the \
         approach speed {speed} m/s the particles reach (Hertz contact time {contact_time:e} s); \
         reduce dt, e.g. to `stable_time_step(pair, v_max, 50.0)`"
    )]
    NeighbourListTimeStepTooLarge {
        /// The step (s).
        dt: f64,
        /// Stability limit `2 √(m / k_max)` of that contact (s).
        limit: f64,
        /// Hertz contact time at that approach speed (s).
        contact_time: f64,
        /// The approach speed: twice the largest particle speed between spheres, the largest
        /// particle speed plus the surface's against a surface (m/s).
        speed: f64,
        /// `sphere–sphere` or `sphere–surface`.
        kind: &'static str,
    },
    /// A saved neighbour-list state (neighbour lists, histories) does not fit the stepper it is
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
