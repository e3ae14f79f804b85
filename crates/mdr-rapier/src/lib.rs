//! # mdr-rapier
//!
//! The MDR elasto-plastic contact law ([`mdr_contact`]) as a per-contact history model in the
//! rapier physics engine (`rapier3d-f64` 0.36). Two coupling modes, both documented in
//! `docs/coupling.md`:
//!
//! - **force mode** ([`ForceModeStepper`]): soft spheres. The law computes every contact force
//!   from the overlap at the start of the step and the pair's history; rapier detects candidate
//!   pairs, stores the bodies and integrates them (one solver iteration: exact symplectic Euler).
//!   rapier's own contact impulses are switched off for the plugin's colliders.
//! - **restitution mode** ([`RestitutionHooks`]): hard spheres. A `PhysicsHooks` implementation
//!   sets each manifold's restitution from the law's energy route at the approach speed, with the
//!   pair's plastic history kept in a thread-safe store reached through the manifold's
//!   `user_data`; rapier resolves the contact with impulses.
//!
//! The law itself is never re-implemented here: every force and every restitution comes from
//! `mdr-contact`.
//!
//! ```
//! use mdr_rapier::prelude::*;
//! use rapier3d_f64::prelude::*;
//!
//! let mut world = PhysicsWorld::default();
//! world.gravity = Vector::ZERO;
//! let model = ContactModel::new(MdrElastoPlastic::paper());
//! let mut stepper = ForceModeStepper::new(model);
//! let steel = stepper.particles_mut().insert_material(Material::paper_steel());
//! stepper
//!     .insert_surface(&mut world, ColliderBuilder::new(SharedShape::halfspace(Vector::Y)), None, steel)
//!     .unwrap();
//! let ball = SphereBuilder::new(0.00635, steel)
//!     .translation(Vector::new(0.0, 0.00636, 0.0))
//!     .linvel(Vector::new(0.0, -1.0, 0.0));
//! let (body, _) = stepper.insert_sphere(&mut world, ball).unwrap();
//! stepper.configure(&mut world.integration_parameters, 1e-7, 0.002).unwrap();
//! for _ in 0..2000 {
//!     stepper.step(&mut world).unwrap();
//! }
//! // Bounced with a plastic loss: 0 < e < 1.
//! let v = world.bodies[body].linvel().y;
//! assert!(v > 0.0 && v < 1.0);
//! ```
#![warn(missing_docs)]

pub mod convert;
pub mod error;
pub mod fast;
pub mod force_mode;
pub mod geometry;
pub mod kernel;
pub mod particles;
pub mod restitution;
pub mod restitution_law;
pub mod scenario;
pub mod store;
pub mod timestep;

/// The rapier crate this coupling is built on (`rapier3d-f64`), re-exported so that programs
/// use the same version.
pub use rapier3d_f64 as rapier;

pub use error::{CouplingError, Result};
pub use force_mode::{ForceModeStepper, PhaseTimings, StepReport};
pub use particles::{MaterialHandle, Particle, ParticleSet, ParticleShape, SphereBuilder};
pub use restitution::{ImpactHistory, RestitutionHooks};
pub use scenario::{CouplingMode, ImpactScene, SceneLaw, SceneOutcome, Target};
pub use store::{ContactStore, PairKey};
pub use timestep::{check_time_step, stable_time_step, TimeStepAdvice, TimeStepWarning};

/// The names most programs need: this crate's types and the law crate's prelude.
pub mod prelude {
    pub use crate::error::{CouplingError, Result};
    pub use crate::force_mode::{ForceModeStepper, StepReport};
    pub use crate::particles::{
        MaterialHandle, Particle, ParticleSet, ParticleShape, SphereBuilder,
    };
    pub use crate::restitution::{ImpactHistory, RestitutionHooks};
    pub use crate::timestep::{check_time_step, stable_time_step, TimeStepAdvice, TimeStepWarning};
    pub use mdr_contact::prelude::*;
    pub use mdr_contact::rolling::{EpsdRolling, NoRolling, RollingModel};
}
