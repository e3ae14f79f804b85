//! Normal contact laws: one trait, one module per law, each law with its own parameters and
//! its own per-contact state (the history).
//!
//! Two levels, as in LAMMPS `pair granular`:
//! - a **model** ([`NormalModel`]) holds material-level parameters (e.g. `q_c`, `Θ/E*`) and is
//!   shared by every pair of a simulation;
//! - a **law** ([`NormalLaw`]) is a model bound to one [`ContactPair`] (its `E*`, `R`), with the
//!   pair-dependent constants precomputed, and maps an overlap history to a force.

mod hertz;
mod mdr;
mod spring_bed;
mod thornton;

pub use hertz::{Hertz, HertzLaw};
pub use mdr::{EnergyRouteImpact, Hardening, MdrElastoPlastic, MdrLaw, MdrState};
pub use spring_bed::{SphereSpringBed, SpringBed, SpringBedState};
pub use thornton::{
    liggghts_thornton_ning_restitution, thornton_restitution, Thornton, ThorntonLaw, ThorntonState,
    ThorntonUnloading,
};

use crate::error::Result;
use crate::material::ContactPair;

/// What a normal law returns for one overlap.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NormalResponse {
    /// Repulsive normal force (N), never negative (no adhesion).
    pub force: f64,
    /// Contact radius `a` (m); zero when the bodies do not touch.
    pub contact_radius: f64,
    /// Tangent stiffness `dF/dδ` (N/m) on the current branch, for time-step estimates and the
    /// tangential law.
    pub stiffness: f64,
}

/// A normal contact law bound to one pair: overlap history → force.
///
/// `update` advances the history (the state) to a new overlap `δ` (m, positive when the bodies
/// interpenetrate). A non-positive overlap means the bodies are apart; the state keeps its
/// plastic memory, so a later re-touch on the same spot sees the flattened profile.
pub trait NormalLaw: Send + Sync {
    /// Per-contact history.
    type State: Clone + Default + std::fmt::Debug + Send + Sync;

    /// Advance the history to `overlap` (m) and return the response there.
    fn update(&self, state: &mut Self::State, overlap: f64) -> NormalResponse;

    /// The response at `overlap` without changing the history.
    fn evaluate(&self, state: &Self::State, overlap: f64) -> NormalResponse {
        let mut trial = state.clone();
        self.update(&mut trial, overlap)
    }

    /// Largest overlap reached so far (m).
    fn max_overlap(&self, state: &Self::State) -> f64;

    /// Overlap at which the force vanishes on unloading: the residual (plastic) indentation (m).
    fn residual_overlap(&self, state: &Self::State) -> f64;

    /// Work dissipated by plasticity so far (J). A function of the largest overlap
    /// ([`NormalLaw::max_overlap`]) alone, as the plastic memory of these laws is: callers that
    /// book it every step recompute it only when that grew.
    fn dissipated_work(&self, state: &Self::State) -> f64;

    /// Elastic energy stored at `overlap` for this history (J): the work the contact returns
    /// when unloaded from `overlap` to separation.
    fn elastic_energy(&self, state: &Self::State, overlap: f64) -> f64;

    /// Indentation at which the law first leaves the elastic branch (m), `inf` if never.
    fn yield_overlap(&self) -> f64;
}

/// Material-level parameters of a normal law; [`NormalModel::bind`] makes the law of one pair.
pub trait NormalModel: Clone + Send + Sync {
    /// The law for one pair.
    type Law: NormalLaw;
    /// Bind to a pair, precomputing what the law needs. Fails when a parameter is incompatible
    /// with the pair (e.g. an absolute hardening modulus above the pair's `E*`).
    fn bind(&self, pair: &ContactPair) -> Result<Self::Law>;
}

/// `F_H(d) = (4/3) E* √R d^{3/2}` written as `c · d^{3/2}` with `c = (4/3) E* √R`: eq. (5).
#[inline]
pub(crate) fn pow3_2(d: f64) -> f64 {
    d * d.sqrt()
}

/// `d^{5/2}`.
#[inline]
pub(crate) fn pow5_2(d: f64) -> f64 {
    d * d * d.sqrt()
}
