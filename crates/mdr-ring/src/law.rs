//! The restitution laws a ring can run with: the trait and the MDR and constant laws of
//! `mdr-rapier` ([`mdr_rapier::restitution_law`]), and the empirical law of Bridges, Hatzes &
//! Lin (1984, Nature 309, 333) for frost-covered ice at 165 K, which belongs to ring dynamics
//! rather than to contact mechanics: [`BridgesLaw`], REBOUND's default.

pub use mdr_rapier::restitution_law::*;

/// The Bridges et al. (1984) law `ε(v) = min(1, a (v / v₀)^−b)` with `a = 0.32`, `b = 0.234`,
/// `v₀ = 1 cm/s` (as in REBOUND's shearing-sheet example).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BridgesLaw {
    prefactor: f64,
    exponent: f64,
    reference_speed: f64,
}

impl Default for BridgesLaw {
    fn default() -> Self {
        Self {
            prefactor: 0.32,
            exponent: 0.234,
            reference_speed: 0.01,
        }
    }
}

impl BridgesLaw {
    /// `ε(v)` for speed `v` (m/s).
    pub fn at(&self, speed: f64) -> f64 {
        (self.prefactor * (speed.abs() / self.reference_speed).powf(-self.exponent)).clamp(0.0, 1.0)
    }

    /// Speed below which `ε = 1`: `v₀ a^{1/b}` (m/s).
    pub fn elastic_speed(&self) -> f64 {
        self.reference_speed * self.prefactor.powf(1.0 / self.exponent)
    }
}

impl RestitutionLaw for BridgesLaw {
    type History = ();

    fn restitution(&self, _: &ImpactPair, _: &mut (), approach_speed: f64) -> f64 {
        self.at(approach_speed)
    }

    fn name(&self) -> &'static str {
        "bridges"
    }
}
