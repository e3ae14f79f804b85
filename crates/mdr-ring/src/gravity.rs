//! Optional self-gravity by direct summation over the nearest shear-periodic image of every other
//! particle, with Plummer softening. O(N²) per step: for small boxes (a few thousand particles);
//! off by default, as in the REBOUND comparison (`--grav none`).

use crate::boundary::ShearingBox;
use crate::particles::Particles;
use rapier3d_f64::math::Vector;
use rayon::prelude::*;

/// Newton's constant (m³ kg⁻¹ s⁻²), REBOUND's value.
pub const GRAVITATIONAL_CONSTANT: f64 = 6.67428e-11;

/// Direct-sum self-gravity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfGravity {
    /// Gravitational constant (m³ kg⁻¹ s⁻²).
    pub constant: f64,
    /// Plummer softening length (m).
    pub softening: f64,
}

impl Default for SelfGravity {
    fn default() -> Self {
        Self {
            constant: GRAVITATIONAL_CONSTANT,
            softening: 0.1,
        }
    }
}

impl SelfGravity {
    /// Separation from `a` to the nearest image of `b` at `time`: the radial box offset is chosen
    /// first (it carries the shear offset along y), then the azimuthal one.
    pub fn nearest_image(domain: &ShearingBox, a: Vector, b: Vector, time: f64) -> Vector {
        let mut d = b - a;
        let i = (d.x / domain.lx()).round();
        d.x -= i * domain.lx();
        // The image of b in box −i sits at y_b + i S(t).
        d.y += i * domain.shear_offset(time);
        d.y -= domain.ly() * (d.y / domain.ly()).round();
        d
    }

    /// Accelerations of all particles (m/s²).
    pub fn accelerations(
        &self,
        domain: &ShearingBox,
        particles: &Particles,
        time: f64,
    ) -> Vec<Vector> {
        let eps2 = self.softening * self.softening;
        (0..particles.len())
            .into_par_iter()
            .map(|i| {
                let mut acc = Vector::ZERO;
                for j in 0..particles.len() {
                    if j == i {
                        continue;
                    }
                    let d = Self::nearest_image(
                        domain,
                        particles.position[i],
                        particles.position[j],
                        time,
                    );
                    let r2 = d.length_squared() + eps2;
                    acc += d * (self.constant * particles.mass[j] / (r2 * r2.sqrt()));
                }
                acc
            })
            .collect()
    }
}
