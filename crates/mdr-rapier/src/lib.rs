//! # mdr-rapier
//!
//! The MDR elasto-plastic contact law ([`mdr_contact`]) as a per-contact history model in the
//! rapier physics engine (`rapier3d-f64` 0.36, re-exported as [`rapier`]). Two coupling modes,
//! both documented in `docs/coupling.md`:
//!
//! - **force mode** ([`ForceModeStepper`]): soft spheres. The law computes every contact force
//!   from the overlap at the start of the step and the pair's history; rapier detects candidate
//!   pairs, stores the bodies and integrates them (one solver iteration: exact symplectic Euler).
//!   rapier's own contact impulses are switched off between the plugin's colliders only (one
//!   reserved solver group, [`COUPLING_SOLVER_GROUP`]); every other pair stays rapier's.
//! - **restitution mode** ([`RestitutionHooks`]): hard spheres. A `PhysicsHooks` implementation
//!   sets each manifold's restitution from the law's energy route at the approach speed, with the
//!   pair's plastic history kept in a thread-safe store; rapier resolves the contact with
//!   impulses. It composes with a user's hooks ([`RestitutionHooks::with_user`]).
//!
//! Registration adds the coupling's solver group or hook flag to the user's own and never
//! replaces them; a step refuses a world that misses them, or that is not configured, with an
//! error naming the fix. The law itself is never re-implemented here: every force and every
//! restitution comes from `mdr-contact` (re-exported as [`mdr_contact`]).
//!
//! ```
//! use mdr_rapier::prelude::*;
//! use mdr_rapier::rapier::prelude::*;
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

mod added_forces;
pub mod adhesion;
pub mod convert;
pub mod error;
pub mod neighbour_list;
mod pair_models;

/// The neighbour-list path under its former name.
#[deprecated(note = "renamed `neighbour_list`: the module is named after its method")]
pub mod fast {
    #[allow(deprecated)]
    pub use crate::neighbour_list::*;
}
pub mod force_mode;
pub mod geometry;
pub mod kernel;
pub mod particles;
pub mod registration;
pub mod restitution;
pub mod restitution_law;
pub mod scenario;
pub mod store;
pub mod timestep;

/// The rapier crate this coupling is built on (`rapier3d-f64`), re-exported so that programs
/// use the same version.
pub use rapier3d_f64 as rapier;

/// The law crate, re-exported so that programs use the same version (its `ContactPair`, the
/// pair quantities `E*`, `G*`, `R`, `m`, is [`LawPair`] here: rapier's prelude has a
/// `ContactPair` of its own).
pub use mdr_contact;

/// The pair quantities of a contact (`mdr_contact::ContactPair`): `E*` (eq. 3), `G*`,
/// effective radius and reduced mass, under a name that does not clash with rapier's
/// narrow-phase `ContactPair`.
pub use mdr_contact::ContactPair as LawPair;

pub use error::{CouplingError, Result};
pub use force_mode::{ForceModeStepper, PhaseTimings, StepReport, UnhandledPair};
pub use particles::{
    MaterialHandle, Particle, ParticleSet, ParticleShape, SphereBodyOptions, SphereBuilder,
    SphereColliderOptions,
};
pub use registration::COUPLING_SOLVER_GROUP;
pub use restitution::{
    FrictionRule, ImpactHistory, RestitutionHooks, RestitutionReport, WithUserHooks,
};
pub use scenario::{
    CouplingMode, DeclaredSceneLaw, ImpactScene, SceneLaw, SceneLawEntry, SceneOutcome, Target,
};
pub use store::{ContactStore, PairKey};
pub use timestep::{check_time_step, stable_time_step, TimeStepAdvice, TimeStepWarning};

/// The names most programs need: this crate's types and the law crate's prelude, without the
/// law crate's `ContactPair` (rapier's prelude has its own; the law's is [`LawPair`]), so that
/// `use mdr_rapier::prelude::*;` and `use mdr_rapier::rapier::prelude::*;` go together.
pub mod prelude {
    pub use crate::error::{CouplingError, Result};
    pub use crate::force_mode::{ForceModeStepper, StepReport, UnhandledPair};
    pub use crate::particles::{
        MaterialHandle, Particle, ParticleSet, ParticleShape, SphereBuilder,
    };
    pub use crate::registration::COUPLING_SOLVER_GROUP;
    pub use crate::restitution::{
        FrictionRule, ImpactHistory, RestitutionHooks, RestitutionReport, WithUserHooks,
    };
    pub use crate::timestep::{check_time_step, stable_time_step, TimeStepAdvice, TimeStepWarning};
    pub use crate::LawPair;
    pub use mdr_contact::prelude::{
        effective_modulus, effective_shear_modulus, Books, ContactError, ContactInput, ContactLaw,
        ContactModel, ContactOutput, ContactReport, ContactState, Counterpart, DampingLaw,
        DampingModel, Hertz, HertzLaw, HertzianViscous, Material, MdrElastoPlastic, MdrLaw,
        MdrState, NoBooks, NoDamping, NormalLaw, NormalModel, NormalResponse, SphereSpringBed,
        SpringBed, SpringBedState, StiffnessViscous, Thornton, ThorntonLaw, ThorntonState,
        ThorntonUnloading, WorkBooks,
    };
    pub use mdr_contact::prelude::{
        Frictionless, Mindlin, MindlinLaw, MindlinState, SpringBedTangential,
        SpringBedTangentialState, TangentialInput, TangentialLaw, TangentialModel,
        TangentialResponse,
    };
    pub use mdr_contact::rolling::{EpsdRolling, NoRolling, RollingModel};
}
