//! Hill's equations of a small patch of a ring, in the frame rotating at the local orbital
//! frequency `Ω` (x radial outwards, y along the orbit, z vertical):
//!
//! ```text
//! ẍ = 2Ω ẏ + 3Ω² x        (Coriolis + tidal)
//! ÿ = −2Ω ẋ               (Coriolis)
//! z̈ = −Ω² z               (vertical restoring force of the planet)
//! ```
//!
//! Free motion is an epicycle about a guiding centre that moves with the Keplerian shear
//! `ẏ_g = −(3/2) Ω x_g` (derivation in `docs/rings.md` §2). [`Sei`] advances it exactly: the
//! symplectic epicycle integrator of Rein & Tremaine (2011, MNRAS 415, 3168), whose free-motion
//! operator is the exact solution written as a rotation of the epicycle phasor (implemented as three
//! shears so that it preserves phase-space area to round-off).

use crate::error::{positive, Result};
use rapier3d_f64::math::Vector;

/// The rotating frame of Hill's approximation: the orbital frequency `Ω` (1/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HillFrame {
    omega: f64,
}

impl HillFrame {
    /// A frame rotating at `omega` (1/s, > 0).
    pub fn new(omega: f64) -> Result<Self> {
        Ok(Self {
            omega: positive("omega", omega)?,
        })
    }

    /// The orbital frequency `Ω` (1/s).
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// The orbital period `2π/Ω` (s).
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.omega
    }

    /// Azimuthal velocity of the Keplerian shear flow at radial offset `x`: `−(3/2) Ω x` (m/s).
    pub fn shear_velocity(&self, x: f64) -> f64 {
        -1.5 * self.omega * x
    }

    /// Acceleration of a free particle: Coriolis, tidal and vertical terms of Hill's equations.
    pub fn acceleration(&self, position: Vector, velocity: Vector) -> Vector {
        let w = self.omega;
        Vector::new(
            2.0 * w * velocity.y + 3.0 * w * w * position.x,
            -2.0 * w * velocity.x,
            -w * w * position.z,
        )
    }

    /// Radial position of the guiding centre, `x_g = 4x + 2ẏ/Ω`: a constant of free motion
    /// (from `ẏ + 2Ωx = const`).
    pub fn guiding_centre_x(&self, position: Vector, velocity: Vector) -> f64 {
        4.0 * position.x + 2.0 * velocity.y / self.omega
    }

    /// Azimuthal position of the guiding centre, `y_g = y − 2ẋ/Ω`; it moves at `−(3/2) Ω x_g`.
    pub fn guiding_centre_y(&self, position: Vector, velocity: Vector) -> f64 {
        position.y - 2.0 * velocity.x / self.omega
    }

    /// Radial amplitude of the epicycle, `√((x − x_g)² + (ẋ/Ω)²)` (m): a constant of free motion.
    pub fn epicycle_amplitude(&self, position: Vector, velocity: Vector) -> f64 {
        let dx = position.x - self.guiding_centre_x(position, velocity);
        dx.hypot(velocity.x / self.omega)
    }

    /// Amplitude of the vertical oscillation, `√(z² + (ż/Ω)²)` (m): a constant of free motion.
    pub fn vertical_amplitude(&self, position: Vector, velocity: Vector) -> f64 {
        position.z.hypot(velocity.z / self.omega)
    }
}

/// A rotation of the phasor `(a, b)` by the angle `Ωτ`, written as three shears
/// (`a += t b; b −= s a; a += t b` with `t = tan(Ωτ/2)`, `s = sin(Ωτ)`), which is exactly
/// area-preserving in floating point (Rein & Tremaine 2011, §3.2).
#[derive(Debug, Clone, Copy, PartialEq)]
struct ShearRotation {
    tan_half: f64,
    sin: f64,
}

impl ShearRotation {
    fn new(angle: f64) -> Self {
        Self {
            tan_half: (0.5 * angle).tan(),
            sin: angle.sin(),
        }
    }

    /// `(a, b) → (a cos φ + b sin φ, −a sin φ + b cos φ)`.
    #[inline]
    fn apply(&self, a: f64, b: f64) -> (f64, f64) {
        let a1 = a + self.tan_half * b;
        let b1 = b - self.sin * a1;
        (a1 + self.tan_half * b1, b1)
    }
}

/// The free-motion operator of the symplectic epicycle integrator (SEI) for a fixed time step:
/// the exact solution of Hill's equations without other forces.
///
/// ```
/// use mdr_ring::hill::{HillFrame, Sei};
/// use rapier3d_f64::math::Vector;
/// let frame = HillFrame::new(1.3143527e-4).unwrap();
/// let sei = Sei::new(frame, frame.period() * 1e-3).unwrap();
/// let (mut p, mut v) = (Vector::new(10.0, 0.0, 1.0), Vector::new(0.001, 0.0, 0.0));
/// let xg = frame.guiding_centre_x(p, v);
/// for _ in 0..1000 {
///     sei.advance(&mut p, &mut v);
/// }
/// assert!((frame.guiding_centre_x(p, v) - xg).abs() < 1e-9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sei {
    frame: HillFrame,
    dt: f64,
    rotation: ShearRotation,
}

impl Sei {
    /// The operator advancing by `dt` (s, > 0) in `frame`.
    pub fn new(frame: HillFrame, dt: f64) -> Result<Self> {
        positive("dt", dt)?;
        Ok(Self {
            frame,
            dt,
            rotation: ShearRotation::new(frame.omega() * dt),
        })
    }

    /// The time step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The frame.
    pub fn frame(&self) -> HillFrame {
        self.frame
    }

    /// Advance one free particle by `dt` exactly (up to round-off).
    ///
    /// Radially, `(Ω(x − x_g), ẋ)` rotates at `Ω` about the guiding centre `x_g` (constant); the
    /// azimuthal position is `y = y_g + 2ẋ/Ω` with `y_g` moving at `−(3/2) Ω x_g`, and
    /// `ẏ = −(3/2) Ω x_g − 2Ω(x − x_g)`. Vertically `(Ωz, ż)` rotates at `Ω`.
    #[inline]
    pub fn advance(&self, position: &mut Vector, velocity: &mut Vector) {
        let w = self.frame.omega();
        // Vertical harmonic oscillation.
        let (wz, vz) = self.rotation.apply(w * position.z, velocity.z);
        position.z = wz / w;
        velocity.z = vz;
        // Epicycle about the guiding centre.
        let xg = self.frame.guiding_centre_x(*position, *velocity);
        let yg = self.frame.guiding_centre_y(*position, *velocity) - 1.5 * w * xg * self.dt;
        let (wx, vx) = self.rotation.apply(w * (position.x - xg), velocity.x);
        position.x = xg + wx / w;
        position.y = yg + 2.0 * vx / w;
        velocity.x = vx;
        velocity.y = -1.5 * w * xg - 2.0 * wx;
    }
}
