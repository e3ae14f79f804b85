//! Hertz (elastic) normal contact, eq. (5): `F = (4/3) E* √R δ^{3/2}`.

use super::{pow3_2, pow5_2, NormalLaw, NormalModel, NormalResponse};
use crate::error::Result;
use crate::material::ContactPair;
use crate::params::{Declared, LawDeclaration, LawKind};

/// The Hertz law as a model: no parameters beyond the pair's.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Hertz;

/// Hertz has no parameters beyond the pair's.
impl Declared for Hertz {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "hertz",
        kind: LawKind::Normal,
        summary: "Hertz elastic sphere contact, F = (4/3) E* √R δ^{3/2}, eq. (5)",
        params: &[],
    };

    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Ok(Hertz)
    }
}

impl NormalModel for Hertz {
    type Law = HertzLaw;
    fn bind(&self, pair: &ContactPair) -> Result<HertzLaw> {
        Ok(HertzLaw::new(pair))
    }
}

/// The Hertz law of one pair. Its state only records the largest overlap (for reports).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzLaw {
    effective_modulus: f64,
    effective_radius: f64,
    /// `√R`, so that the contact radius `√(R δ)` reuses `√δ`.
    sqrt_radius: f64,
    /// `(4/3) E* √R`.
    force_coefficient: f64,
}

impl HertzLaw {
    /// The Hertz law for `pair`.
    pub fn new(pair: &ContactPair) -> Self {
        let e = pair.effective_modulus();
        let r = pair.effective_radius();
        Self {
            effective_modulus: e,
            effective_radius: r,
            sqrt_radius: r.sqrt(),
            force_coefficient: 4.0 / 3.0 * e * r.sqrt(),
        }
    }

    /// Hertz force at overlap `d` (N), eq. (5).
    #[inline]
    pub fn force(&self, d: f64) -> f64 {
        if d > 0.0 {
            self.force_coefficient * pow3_2(d)
        } else {
            0.0
        }
    }

    /// `∫₀^d F dδ = (8/15) E* √R d^{5/2}` (J).
    #[inline]
    pub fn work(&self, d: f64) -> f64 {
        if d > 0.0 {
            0.4 * self.force_coefficient * pow5_2(d)
        } else {
            0.0
        }
    }
}

impl NormalLaw for HertzLaw {
    /// Largest overlap so far (m).
    type State = f64;

    #[inline(always)]
    fn update(&self, state: &mut f64, overlap: f64) -> NormalResponse {
        // One square root: a = √R √δ, F = c δ √δ. Taken before the apart test (unused, NaN, when
        // δ < 0) so that it dominates the rest of an inlined contact update, where the damping
        // law's √δ then reuses it.
        let sqrt_overlap = overlap.sqrt();
        if overlap <= 0.0 {
            return NormalResponse::default();
        }
        if overlap > *state {
            *state = overlap;
        }
        let a = self.sqrt_radius * sqrt_overlap;
        NormalResponse {
            force: self.force_coefficient * overlap * sqrt_overlap,
            contact_radius: a,
            stiffness: 2.0 * self.effective_modulus * a,
        }
    }

    fn max_overlap(&self, state: &f64) -> f64 {
        *state
    }

    fn residual_overlap(&self, _state: &f64) -> f64 {
        0.0
    }

    fn dissipated_work(&self, _state: &f64) -> f64 {
        0.0
    }

    fn elastic_energy(&self, _state: &f64, overlap: f64) -> f64 {
        self.work(overlap)
    }

    fn yield_overlap(&self) -> f64 {
        f64::INFINITY
    }
}
