//! # mdr-contact
//!
//! The MDR (method of dimensionality reduction) elasto-plastic normal contact law with nonlocal
//! plasticity and linear strain hardening of Lyashenko & Popov (2018), packaged as per-contact
//! history models with no engine dependency. Equation numbers in the docs are the paper's; the
//! derivations are in `docs/theory.md`.
//!
//! - [`material`]: materials and pair quantities (`E*`, eq. 3; `G*`; effective radius; reduced mass).
//! - [`profile`]: axisymmetric profiles and their MDR 1D profiles (eq. 1), closed form and numerical.
//! - [`normal`]: normal laws — [`normal::Hertz`], the MDR closed form
//!   [`normal::MdrElastoPlastic`] (O(1)), the discrete MDR spring bed [`normal::SpringBed`]
//!   (eqs. 2, 6, 9–13, any profile), [`normal::Thornton`]; with adhesion (Heß's rule on the
//!   plastic springs), the closed form [`normal::AdhesiveMdrLaw`] and the spring bed
//!   [`normal::AdhesiveSpringBed`].
//! - [`tangential`]: the O(1) Mindlin law with a Coulomb cap, and the MDR spring-bed law with
//!   per-spring stick/slip [`tangential::SpringBedTangential`].
//! - [`damping`]: optional viscous damping.
//! - [`model`]: composition of the sub-models into one contact model.
//!
//! ```
//! use mdr_contact::prelude::*;
//! let pair = ContactPair::paper_fig2();
//! let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
//! let mut state = MdrState::default();
//! let loaded = law.update(&mut state, 8e-6); // past u_c = π q_c / (2 E*) ≈ 5.5 µm
//! let unloaded = law.update(&mut state, 7e-6);
//! assert!(unloaded.force < loaded.force);
//! assert!(law.residual_overlap(&state) > 0.0);
//! ```
#![warn(missing_docs)]

pub mod damping;
pub mod error;
pub mod material;
pub mod model;
pub mod normal;
pub mod params;
pub mod profile;
mod quadrature;
pub mod rolling;
pub mod tangential;

pub use error::{ContactError, Result};
pub use material::{ContactPair, Counterpart, Material};
/// The linear-algebra crate of the vector types in this API (`Vector3`, `Vector2`).
pub use nalgebra;

/// The names most programs need.
pub mod prelude {
    pub use crate::damping::{
        DampingLaw, DampingModel, HertzianViscous, NoDamping, StiffnessViscous,
    };
    pub use crate::error::{ContactError, Result};
    pub use crate::material::{
        effective_modulus, effective_shear_modulus, ContactPair, Counterpart, Material,
    };
    pub use crate::model::{
        Books, ContactInput, ContactLaw, ContactModel, ContactOutput, ContactReport, ContactState,
        NoBooks, WorkBooks,
    };
    pub use crate::normal::{
        AdhesiveMdr, AdhesiveMdrLaw, AdhesiveMdrState, AdhesiveSpringBed, AdhesiveSpringBedState,
        Hertz, HertzLaw, MdrElastoPlastic, MdrLaw, MdrState, NormalLaw, NormalModel,
        NormalResponse, SphereSpringBed, SpringBed, SpringBedState, Thornton, ThorntonLaw,
        ThorntonState, ThorntonUnloading,
    };
    pub use crate::tangential::{
        Frictionless, Mindlin, MindlinLaw, MindlinState, SpringBedTangential,
        SpringBedTangentialState, TangentialInput, TangentialLaw, TangentialModel,
        TangentialResponse,
    };
}
