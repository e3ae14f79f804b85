//! Normal contact laws: one trait, one module per law, each law with its own parameters and
//! its own per-contact state (the history).
//!
//! Two levels, as in LAMMPS `pair granular`:
//! - a **model** ([`NormalModel`]) holds material-level parameters (e.g. `q_c`, `Θ/E*`) and is
//!   shared by every pair of a simulation;
//! - a **law** ([`NormalLaw`]) is a model bound to one [`ContactPair`] (its `E*`, `R`), with the
//!   pair-dependent constants precomputed, and maps an overlap history to a force.

mod adhesive_mdr;
mod adhesive_spring_bed;
mod hertz;
#[cfg(feature = "demo-laws")]
mod linear_spring;
mod mdr;
mod spring_bed;
mod thornton;

pub use adhesive_mdr::{AdhesiveMdr, AdhesiveMdrLaw, AdhesiveMdrState};
pub use adhesive_spring_bed::{AdhesiveSpringBed, AdhesiveSpringBedState, SphereAdhesiveSpringBed};
pub use hertz::{Hertz, HertzLaw};
#[cfg(feature = "demo-laws")]
pub use linear_spring::{LinearSpring, LinearSpringLaw};
pub(crate) use mdr::{AfterTouching, Touching};
pub use mdr::{EnergyRouteImpact, Hardening, MdrElastoPlastic, MdrLaw, MdrState};
pub use spring_bed::{SphereSpringBed, SpringBed, SpringBedState};
pub use thornton::{
    liggghts_thornton_ning_restitution, thornton_restitution, Thornton, ThorntonLaw, ThorntonState,
    ThorntonUnloading,
};

use crate::error::Result;
use crate::material::ContactPair;
use crate::params::{Declared, LawDeclaration, LawKind, Param, Range};

/// The adhesive MDR law's parameters: the MDR law's, and the work of adhesion `Δγ` of Heß's
/// rule. Declared here so that a layer can carry it by name; the rapier paths do not register it
/// (they apply compressive forces only).
impl Declared for AdhesiveMdr {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "adhesive_mdr",
        kind: LawKind::Normal,
        summary: "MDR elasto-plastic with Heß's adhesion rule on the plastic springs (closed form)",
        params: &[
            MdrElastoPlastic::DECLARATION.params[0],
            MdrElastoPlastic::DECLARATION.params[1],
            Param::new(
                "work_of_adhesion_j_per_m2",
                "Δγ",
                "J/m²",
                Range::NON_NEGATIVE,
                "work of adhesion: a spring lets go at its critical elongation √(2 π a Δγ / E*)",
            )
            .flag("work-of-adhesion")
            .python("work_of_adhesion")
            .lammps("adhesion"),
        ],
    };

    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        AdhesiveMdr::new(MdrElastoPlastic::new(values[0], values[1])?, values[2])
    }
}

/// What a normal law returns for one overlap.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NormalResponse {
    /// Normal force (N): positive pushes the bodies apart; negative (adhesive laws only, while
    /// [`NormalLaw::holds`]) pulls them together.
    pub force: f64,
    /// Contact radius `a` (m): the radius of the springs in contact (for adhesive laws, of the
    /// attached springs, which may be stretched); zero when the bodies do not touch.
    pub contact_radius: f64,
    /// Tangent stiffness `dF/dδ` (N/m) on the current branch, for time-step estimates and the
    /// tangential law. For adhesive laws it is the stiffness `2E* a` of the attached springs,
    /// an upper bound of `|dF/dδ|` while the contact's edge retreats.
    pub stiffness: f64,
}

/// A normal contact law bound to one pair: overlap history → force.
///
/// `update` advances the history (the state) to a new overlap `δ` (m, positive when the bodies
/// interpenetrate). The state keeps its plastic memory, so a later re-touch on the same spot sees
/// the flattened profile.
///
/// Without adhesion the force is never negative and a contact ends where the force vanishes
/// (at [`NormalLaw::residual_overlap`]). An adhesive law ([`AdhesiveMdrLaw`],
/// [`AdhesiveSpringBed`]) may return a negative (tensile) force, also at negative overlaps,
/// while [`NormalLaw::holds`] is true; the contact lets go at the latest when the overlap falls
/// below [`NormalLaw::detachment_overlap`], so a caller keeps updating a held contact (and keeps
/// the pair in its neighbour list) until then. The work the let-go springs held is part of
/// [`NormalLaw::dissipated_work`].
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

    /// Work dissipated so far (J): by plasticity and, for adhesive laws, the energy the springs
    /// held when they let go (the adhesive hysteresis). Without adhesion it is a function of the
    /// largest overlap ([`NormalLaw::max_overlap`]) alone; with adhesion it also grows while the
    /// contact [`NormalLaw::holds`]: callers that cache it recompute it when the largest overlap
    /// grew or the contact held at the previous step.
    fn dissipated_work(&self, state: &Self::State) -> f64;

    /// Elastic energy stored at `overlap` for this history (J): the work the contact returns
    /// when unloaded from `overlap` to separation.
    fn elastic_energy(&self, state: &Self::State, overlap: f64) -> f64;

    /// Indentation at which the law first leaves the elastic branch (m), `inf` if never.
    fn yield_overlap(&self) -> f64;

    /// Whether the contact holds adhesively after the last update: springs are attached and the
    /// law gives a force (possibly tensile) below the residual overlap, down to
    /// [`NormalLaw::detachment_overlap`]. Always false without adhesion.
    #[inline(always)]
    fn holds(&self, _state: &Self::State) -> bool {
        false
    }

    /// The overlap (m) below which the contact, as it stands, has let go: for a held adhesive
    /// contact the smallest overlap it reaches while unloading (typically negative, a
    /// separation); otherwise the residual overlap, where the force vanishes.
    fn detachment_overlap(&self, state: &Self::State) -> f64 {
        self.residual_overlap(state)
    }

    /// The elastic (JKR) pull-off force `(3/2) π Δγ R` (N) of an adhesive law, zero without
    /// adhesion. The tangential Coulomb limit uses the load `F_n + 2 F_c` with this `F_c`
    /// (Thornton & Yin 1991; LAMMPS `jkr`), so an adhesive contact resists sliding under zero
    /// or tensile load.
    #[inline(always)]
    fn pull_off_force(&self) -> f64 {
        0.0
    }
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
