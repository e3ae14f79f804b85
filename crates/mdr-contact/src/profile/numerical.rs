//! The numerical MDR transform, eq. (1), for a profile given as a function or a table.
//!
//! With `r = x sin φ` the singular kernel disappears (`docs/theory.md` §2):
//! `g(x) = |x| ∫_0^{π/2} f'(|x| sin φ) dφ`, a smooth integral evaluated by adaptive
//! Gauss–Kronrod quadrature; for tables the integral is split at the knots, where the
//! interpolant's second derivative jumps.

use super::spline::CubicSpline;
use super::Profile;
use crate::error::{ContactError, Result};
use crate::quadrature::integrate_relative;
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

type RealFn = Arc<dyn Fn(f64) -> f64 + Send + Sync>;

/// Relative accuracy requested from the quadrature (the achieved error is usually far smaller,
/// the Gauss–Kronrod estimate being pessimistic).
const RELATIVE_TOLERANCE: f64 = 1e-12;

/// How the slope `f'(r)` is obtained.
#[derive(Clone)]
enum Slope {
    /// Given by the user.
    Exact(RealFn),
    /// Fourth-order central difference of `f` with step `1e-3 r`.
    Differenced,
    /// Derivative of the interpolating spline.
    Table(CubicSpline),
}

/// Any axisymmetric profile, transformed numerically with eq. (1).
///
/// ```
/// use mdr_contact::profile::{NumericalProfile, Profile, Sphere};
/// let radius = 0.01;
/// let numeric = NumericalProfile::from_height(move |r| r * r / (2.0 * radius));
/// let exact = Sphere::new(radius).unwrap();
/// let x = 1e-3;
/// assert!((numeric.mdr_height(x) / exact.mdr_height(x) - 1.0).abs() < 1e-9);
/// ```
#[derive(Clone)]
pub struct NumericalProfile {
    height: RealFn,
    slope: Slope,
    max_radius: f64,
}

impl std::fmt::Debug for NumericalProfile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let kind = match &self.slope {
            Slope::Exact(_) => "function with exact slope",
            Slope::Differenced => "function, slope by finite differences",
            Slope::Table(spline) => {
                return write!(
                    f,
                    "NumericalProfile(table of {} rows)",
                    spline.knots().len()
                )
            }
        };
        write!(f, "NumericalProfile({kind})")
    }
}

impl NumericalProfile {
    /// A profile from its height function `f(r)` (m, with `f(0) = 0`, defined for `r ≥ 0`).
    /// The slope is taken by a fourth-order central difference with step `10⁻³ r`, accurate to
    /// about 1e-10 relative for smooth profiles; give the slope with
    /// [`NumericalProfile::from_height_and_slope`] when it is known.
    pub fn from_height<F>(height: F) -> Self
    where
        F: Fn(f64) -> f64 + Send + Sync + 'static,
    {
        Self {
            height: Arc::new(height),
            slope: Slope::Differenced,
            max_radius: f64::INFINITY,
        }
    }

    /// A profile from its height `f(r)` and slope `f'(r)` (both for `r ≥ 0`).
    pub fn from_height_and_slope<F, G>(height: F, slope: G) -> Self
    where
        F: Fn(f64) -> f64 + Send + Sync + 'static,
        G: Fn(f64) -> f64 + Send + Sync + 'static,
    {
        Self {
            height: Arc::new(height),
            slope: Slope::Exact(Arc::new(slope)),
            max_radius: f64::INFINITY,
        }
    }

    /// A tabulated profile: rows `(radii[i], heights[i])` with `radii[0] = 0`, strictly
    /// increasing radii, at least four rows, finite entries. It is interpolated by a cubic
    /// spline ([`CubicSpline`], exact for polynomials up to degree 3) and defined up to the last
    /// radius ([`Profile::max_radius`]); beyond it `g = +∞` (no spring there can touch).
    pub fn from_table(radii: &[f64], heights: &[f64]) -> Result<Self> {
        let spline = CubicSpline::new("profile_table", radii, heights)?;
        if radii[0] != 0.0 {
            return Err(ContactError::InvalidTable {
                name: "profile_table",
                reason: format!("the first radius must be 0 (the axis), got {}", radii[0]),
            });
        }
        let max_radius = radii[radii.len() - 1];
        let for_height = spline.clone();
        Ok(Self {
            height: Arc::new(move |r| for_height.value(r)),
            slope: Slope::Table(spline),
            max_radius,
        })
    }

    /// `f'(r)` for `r > 0`.
    pub fn slope(&self, r: f64) -> f64 {
        match &self.slope {
            Slope::Exact(slope) => slope(r),
            Slope::Table(spline) => spline.derivative(r),
            Slope::Differenced => {
                let h = 1e-3 * r;
                let f = &self.height;
                (f(r - 2.0 * h) - 8.0 * f(r - h) + 8.0 * f(r + h) - f(r + 2.0 * h)) / (12.0 * h)
            }
        }
    }
}

impl Profile for NumericalProfile {
    fn height(&self, r: f64) -> f64 {
        if r.abs() > self.max_radius {
            return f64::INFINITY;
        }
        (self.height)(r.abs())
    }

    /// `g(x) = |x| ∫_0^{π/2} f'(|x| sin φ) dφ`, eq. (1) after `r = x sin φ`.
    fn mdr_height(&self, x: f64) -> f64 {
        let x = x.abs();
        if x == 0.0 {
            return 0.0;
        }
        if x > self.max_radius {
            return f64::INFINITY;
        }
        let integrand = |phi: f64| self.slope(x * phi.sin());
        // Split at the knots of a table: the spline's second derivative jumps there.
        let mut breaks = vec![0.0];
        if let Slope::Table(spline) = &self.slope {
            breaks.extend(
                spline
                    .knots()
                    .iter()
                    .filter(|&&r| r > 0.0 && r < x)
                    .map(|&r| (r / x).asin()),
            );
        }
        breaks.push(FRAC_PI_2);
        let integral: f64 = breaks
            .windows(2)
            .map(|w| integrate_relative(&integrand, w[0], w[1], RELATIVE_TOLERANCE, 1e-300))
            .sum();
        x * integral
    }

    fn max_radius(&self) -> f64 {
        self.max_radius
    }
}
