//! Axisymmetric profiles `z = f(r)` and their MDR 1D profiles `g(x)`, eq. (1):
//!
//! `g(x) = |x| ∫_0^|x| f'(r) / sqrt(x² − r²) dr`.
//!
//! Closed forms for the sphere (parabolic), cone, flat punch and power law; a numerical
//! transform ([`NumericalProfile`]) for any profile given as a function or a table
//! (`docs/theory.md` §2).

mod numerical;
mod spline;

pub use numerical::NumericalProfile;
pub use spline::CubicSpline;

use crate::error::{finite, positive, ContactError, Result};
use crate::quadrature::ln_gamma;
use std::f64::consts::{FRAC_PI_2, PI};

/// An axisymmetric indenter profile and its MDR equivalent.
///
/// Implementors give the height `f(r)` of the surface above its lowest point at distance `r`
/// from the axis, and the 1D MDR profile `g(x)` of eq. (1). Both are even: only `|r|`, `|x|`
/// matter.
pub trait Profile: std::fmt::Debug + Send + Sync {
    /// Height `f(r)` (m) at distance `r` (m) from the axis; `+∞` where the body ends in a
    /// vertical wall (flat punch).
    fn height(&self, r: f64) -> f64;

    /// The MDR 1D profile `g(x)` (m), eq. (1).
    fn mdr_height(&self, x: f64) -> f64;

    /// Largest `|x|` (m) at which [`Profile::mdr_height`] is defined (a table ends there);
    /// `+∞` for analytic profiles.
    fn max_radius(&self) -> f64 {
        f64::INFINITY
    }
}

/// A sphere of radius `R` in the parabolic approximation: `f = r²/(2R)`, `g = x²/R`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Sphere {
    radius: f64,
}

impl Sphere {
    /// Radius `R` (m, > 0).
    pub fn new(radius: f64) -> Result<Self> {
        Ok(Self {
            radius: positive("radius", radius)?,
        })
    }

    /// Radius `R` (m).
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

impl Profile for Sphere {
    fn height(&self, r: f64) -> f64 {
        r * r / (2.0 * self.radius)
    }

    fn mdr_height(&self, x: f64) -> f64 {
        x * x / self.radius
    }
}

/// A cone `f = r tan β` (β the angle between the surface and the plane):
/// `g = (π/2) |x| tan β`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Cone {
    slope: f64,
}

impl Cone {
    /// Inclination `β` of the surface against the contact plane (rad, in `(0, π/2)`).
    pub fn new(inclination: f64) -> Result<Self> {
        finite("inclination", inclination)?;
        if !(inclination > 0.0 && inclination < FRAC_PI_2) {
            return Err(ContactError::OutOfRange {
                name: "inclination",
                value: inclination,
                range: "(0, pi/2)",
            });
        }
        Ok(Self {
            slope: inclination.tan(),
        })
    }

    /// `tan β` (> 0).
    pub fn slope(&self) -> f64 {
        self.slope
    }
}

impl Profile for Cone {
    fn height(&self, r: f64) -> f64 {
        r.abs() * self.slope
    }

    fn mdr_height(&self, x: f64) -> f64 {
        FRAC_PI_2 * x.abs() * self.slope
    }
}

/// A cylindrical flat punch of radius `a₀`: `f = 0` for `r ≤ a₀`, a vertical wall beyond;
/// `g = 0` for `|x| ≤ a₀`, `+∞` beyond.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FlatPunch {
    radius: f64,
}

impl FlatPunch {
    /// Punch radius `a₀` (m, > 0).
    pub fn new(radius: f64) -> Result<Self> {
        Ok(Self {
            radius: positive("punch_radius", radius)?,
        })
    }

    /// Punch radius `a₀` (m).
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

impl Profile for FlatPunch {
    fn height(&self, r: f64) -> f64 {
        if r.abs() <= self.radius {
            0.0
        } else {
            f64::INFINITY
        }
    }

    fn mdr_height(&self, x: f64) -> f64 {
        self.height(x)
    }
}

/// A power-law profile `f = c rⁿ`: `g = κ(n) c |x|ⁿ` with
/// `κ(n) = √π Γ(n/2 + 1) / Γ(n/2 + 1/2)` ([`power_law_factor`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PowerLaw {
    coefficient: f64,
    exponent: f64,
    /// `κ(n) c`.
    mdr_coefficient: f64,
}

impl PowerLaw {
    /// `c` (m^{1−n}, > 0) and `n` (> 0).
    pub fn new(coefficient: f64, exponent: f64) -> Result<Self> {
        positive("coefficient", coefficient)?;
        positive("exponent", exponent)?;
        Ok(Self {
            coefficient,
            exponent,
            mdr_coefficient: power_law_factor(exponent) * coefficient,
        })
    }

    /// `c`.
    pub fn coefficient(&self) -> f64 {
        self.coefficient
    }

    /// `n`.
    pub fn exponent(&self) -> f64 {
        self.exponent
    }
}

impl Profile for PowerLaw {
    fn height(&self, r: f64) -> f64 {
        self.coefficient * r.abs().powf(self.exponent)
    }

    fn mdr_height(&self, x: f64) -> f64 {
        self.mdr_coefficient * x.abs().powf(self.exponent)
    }
}

/// `κ(n) = √π Γ(n/2 + 1) / Γ(n/2 + 1/2)`, the factor of the MDR image of `f = c rⁿ`
/// (`κ(1) = π/2` for the cone, `κ(2) = 2` for the paraboloid). Returns NaN for `n ≤ 0`.
pub fn power_law_factor(exponent: f64) -> f64 {
    if exponent.is_nan() || exponent <= 0.0 {
        return f64::NAN;
    }
    let half = 0.5 * exponent;
    PI.sqrt() * (ln_gamma(half + 1.0) - ln_gamma(half + 0.5)).exp()
}
