//! Tangential contact laws: one trait, each law with its own parameters and per-contact state.
//! They read the normal law's [`NormalResponse`] (force and contact radius) and never the normal
//! law itself, so a normal law can be swapped without touching the tangential one.

mod mindlin;
mod spring_bed;

pub use mindlin::{Mindlin, MindlinForm, MindlinLaw, MindlinState};
pub use spring_bed::{SpringBedTangential, SpringBedTangentialState};

use crate::error::Result;
use crate::material::ContactPair;
use crate::normal::NormalResponse;
use nalgebra::Vector3;

/// Input of one tangential update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialInput {
    /// Unit contact normal, pointing from body 2 towards body 1.
    pub normal: Vector3<f64>,
    /// Relative displacement of body 1 with respect to body 2 at the contact point during this
    /// step (m): `(v₁ − v₂)_contact · dt`. Its normal part is ignored.
    pub displacement_increment: Vector3<f64>,
    /// The normal law's response at this step.
    pub normal_response: NormalResponse,
}

/// What a tangential law returns.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentialResponse {
    /// Tangential force on body 1 (N), in the contact plane.
    pub force: Vector3<f64>,
    /// Whether the contact slides (the Coulomb cap is active).
    pub sliding: bool,
    /// Work dissipated by friction during this update (J, ≥ 0).
    pub dissipated: f64,
    /// Elastic energy stored in the tangential springs after the update (J).
    pub elastic_energy: f64,
    /// Energy the springs gained in this update without work on the bodies (J; negative when
    /// they lost it): the stored energy changing with the stiffness at a fixed displacement,
    /// the rescale of a shrinking contact, and what the springs held when the contact opened
    /// (docs/theory.md, "Energy books of the incremental springs").
    pub stiffness_energy: f64,
}

/// A tangential law bound to one pair.
pub trait TangentialLaw: Send + Sync {
    /// Per-contact history.
    type State: Clone + Default + std::fmt::Debug + Send + Sync;
    /// Advance the history by one step and return the tangential force.
    fn update(&self, state: &mut Self::State, input: &TangentialInput) -> TangentialResponse;
    /// Elastic energy stored in the tangential springs of `state` (J): what
    /// [`TangentialResponse::elastic_energy`] reported at the update that left `state`.
    fn elastic_energy(&self, state: &Self::State) -> f64;
}

/// Material-level parameters of a tangential law.
pub trait TangentialModel: Clone + Send + Sync {
    /// The law for one pair.
    type Law: TangentialLaw;
    /// Bind to a pair.
    fn bind(&self, pair: &ContactPair) -> Result<Self::Law>;
}

/// No tangential force (frictionless contact).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Frictionless;

impl TangentialModel for Frictionless {
    type Law = Frictionless;
    fn bind(&self, _pair: &ContactPair) -> Result<Frictionless> {
        Ok(Frictionless)
    }
}

impl TangentialLaw for Frictionless {
    type State = ();
    fn update(&self, _state: &mut (), _input: &TangentialInput) -> TangentialResponse {
        // No friction: the contact slides freely (so no tangential dashpot acts either).
        TangentialResponse {
            sliding: true,
            ..TangentialResponse::default()
        }
    }
    fn elastic_energy(&self, _state: &()) -> f64 {
        0.0
    }
}

/// Frictionless: no parameters.
impl crate::params::Declared for Frictionless {
    const DECLARATION: crate::params::LawDeclaration = crate::params::LawDeclaration {
        name: "none",
        kind: crate::params::LawKind::Tangential,
        summary: "frictionless: no tangential force",
        params: &[],
    };
    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Ok(Frictionless)
    }
}
