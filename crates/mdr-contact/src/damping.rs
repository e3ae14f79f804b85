//! Normal damping sub-models (optional; off by default). Kept separate from the normal laws so
//! that plastic dissipation and viscous dissipation are booked separately.

use crate::error::{non_negative, Result};
use crate::material::ContactPair;
use crate::normal::NormalResponse;

/// A damping law bound to one pair.
pub trait DampingLaw: Send + Sync {
    /// Damping force along the normal (N, positive = repulsive) at overlap `overlap` (m) and
    /// approach rate `approach_rate = dδ/dt` (m/s, positive while the bodies approach).
    fn normal_force(&self, response: &NormalResponse, overlap: f64, approach_rate: f64) -> f64;
}

/// Material-level damping parameters.
pub trait DampingModel: Clone + Send + Sync {
    /// The law for one pair.
    type Law: DampingLaw;
    /// Bind to a pair.
    fn bind(&self, pair: &ContactPair) -> Result<Self::Law>;
}

/// No damping.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NoDamping;

impl DampingModel for NoDamping {
    type Law = NoDamping;
    fn bind(&self, _pair: &ContactPair) -> Result<NoDamping> {
        Ok(NoDamping)
    }
}

impl DampingLaw for NoDamping {
    #[inline]
    fn normal_force(&self, _: &NormalResponse, _: f64, _: f64) -> f64 {
        0.0
    }
}

/// LAMMPS `gran/hertz/history` damping: `F_d = m γ_n (dδ/dt) √(R δ)`, with `γ_n` in
/// 1/(time·length) (LAMMPS's `gamman`), `m` the reduced mass and `R` the effective radius.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HertzianViscous {
    gamma_n: f64,
}

impl HertzianViscous {
    /// `γ_n` (finite, ≥ 0).
    pub fn new(gamma_n: f64) -> Result<Self> {
        Ok(Self {
            gamma_n: non_negative("gamma_n", gamma_n)?,
        })
    }
}

/// [`HertzianViscous`] bound to a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzianViscousLaw {
    /// `m γ_n √R`.
    coefficient: f64,
}

impl DampingModel for HertzianViscous {
    type Law = HertzianViscousLaw;
    fn bind(&self, pair: &ContactPair) -> Result<HertzianViscousLaw> {
        Ok(HertzianViscousLaw {
            coefficient: pair.reduced_mass() * self.gamma_n * pair.effective_radius().sqrt(),
        })
    }
}

impl DampingLaw for HertzianViscousLaw {
    #[inline(always)]
    fn normal_force(&self, _: &NormalResponse, overlap: f64, approach_rate: f64) -> f64 {
        // `√δ` written exactly as the normal laws write it, so that the compiler shares one
        // square root between them once the law chain is inlined.
        if overlap > 0.0 {
            self.coefficient * approach_rate * overlap.sqrt()
        } else {
            0.0
        }
    }
}

/// Tsuji-type viscoelastic damping: `F_d = η √(m k_n) (dδ/dt)`, `k_n` the normal law's tangent
/// stiffness; `η` ≥ 0 is dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StiffnessViscous {
    eta: f64,
}

impl StiffnessViscous {
    /// `η` (finite, ≥ 0).
    pub fn new(eta: f64) -> Result<Self> {
        Ok(Self {
            eta: non_negative("eta", eta)?,
        })
    }
}

/// [`StiffnessViscous`] bound to a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessViscousLaw {
    eta: f64,
    mass: f64,
}

impl DampingModel for StiffnessViscous {
    type Law = StiffnessViscousLaw;
    fn bind(&self, pair: &ContactPair) -> Result<StiffnessViscousLaw> {
        Ok(StiffnessViscousLaw {
            eta: self.eta,
            mass: pair.reduced_mass(),
        })
    }
}

impl DampingLaw for StiffnessViscousLaw {
    #[inline]
    fn normal_force(&self, response: &NormalResponse, _overlap: f64, approach_rate: f64) -> f64 {
        self.eta * (self.mass * response.stiffness).sqrt() * approach_rate
    }
}
