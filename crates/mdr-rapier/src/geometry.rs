//! Contact geometry at the current poses: overlap, normal and contact point of a sphere against
//! another sphere (closed form) or against any parry shape (point projection of the centre).
//!
//! rapier's manifolds are not used for the overlap: with contact recycling their points can be
//! stale by up to the recycle distance, far more than a micrometre overlap. The narrow phase only
//! provides the candidate pairs.

use crate::convert::{to_glam, to_na};
use nalgebra::Vector3;
use rapier3d_f64::math::Pose;
use rapier3d_f64::parry::shape::Shape;

/// Where and how deep two bodies touch.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceContact {
    /// Overlap `δ` (m), > 0.
    pub overlap: f64,
    /// Unit normal from body 2 towards body 1 (the sphere).
    pub normal: Vector3<f64>,
    /// Contact point (m): the middle of the overlap along the normal.
    pub point: Vector3<f64>,
}

/// Sphere 1 (centre `c1`, radius `r1`) against sphere 2; `None` when they do not overlap.
#[inline]
pub fn sphere_sphere(
    c1: &Vector3<f64>,
    r1: f64,
    c2: &Vector3<f64>,
    r2: f64,
) -> Option<SurfaceContact> {
    let d = c1 - c2;
    let dist2 = d.norm_squared();
    let reach = r1 + r2;
    if dist2 >= reach * reach || dist2 == 0.0 {
        return None;
    }
    let dist = dist2.sqrt();
    let overlap = reach - dist;
    // One division and three products (as LAMMPS forms `rinv`), not three divisions.
    let normal = d * (1.0 / dist);
    Some(SurfaceContact {
        overlap,
        normal,
        point: c2 + normal * (r2 - 0.5 * overlap),
    })
}

/// Sphere 1 (centre `c1`, radius `r1`) against any shape at `pose`, through the projection of the
/// centre on the shape's boundary; `None` when they do not overlap.
pub fn sphere_shape(
    c1: &Vector3<f64>,
    r1: f64,
    shape: &dyn Shape,
    pose: &Pose,
) -> Option<SurfaceContact> {
    let projection = shape.project_point(pose, to_glam(c1), false);
    let p = to_na(projection.point);
    let d = c1 - p;
    let dist = d.norm();
    if dist == 0.0 {
        return None;
    }
    // Signed distance of the centre from the surface (negative inside the shape).
    let (signed, normal) = if projection.is_inside {
        (-dist, -d / dist)
    } else {
        (dist, d / dist)
    };
    let overlap = r1 - signed;
    if overlap <= 0.0 {
        return None;
    }
    Some(SurfaceContact {
        overlap,
        normal,
        point: p - normal * (0.5 * overlap),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapier3d_f64::math::Vector;
    use rapier3d_f64::parry::shape::{Cuboid, HalfSpace};

    #[test]
    fn sphere_sphere_overlap_and_normal() {
        let c = sphere_sphere(&Vector3::new(0.0, 0.0, 1.9), 1.0, &Vector3::zeros(), 1.0).unwrap();
        assert!((c.overlap - 0.1).abs() < 1e-15);
        assert!((c.normal - Vector3::z()).norm() < 1e-15);
        assert!((c.point.z - 0.95).abs() < 1e-15);
        assert!(sphere_sphere(&Vector3::new(0.0, 0.0, 2.0), 1.0, &Vector3::zeros(), 1.0).is_none());
    }

    #[test]
    fn sphere_on_half_space_and_cuboid_agree() {
        let c1 = Vector3::new(0.3, 0.999, -0.2);
        let plane = HalfSpace::new(Vector::Y);
        let a = sphere_shape(&c1, 1.0, &plane, &Pose::IDENTITY).unwrap();
        assert!((a.overlap - 1e-3).abs() < 1e-14);
        assert!((a.normal - Vector3::y()).norm() < 1e-15);
        // A big box whose top face is y = 0.
        let cube = Cuboid::new(Vector::new(10.0, 1.0, 10.0));
        let pose = Pose::from_translation(Vector::new(0.0, -1.0, 0.0));
        let b = sphere_shape(&c1, 1.0, &cube, &pose).unwrap();
        assert!((a.overlap - b.overlap).abs() < 1e-14);
        assert!((a.point - b.point).norm() < 1e-14);
        // Centre inside the half-space: overlap larger than the radius.
        let deep =
            sphere_shape(&Vector3::new(0.0, -0.5, 0.0), 1.0, &plane, &Pose::IDENTITY).unwrap();
        assert!((deep.overlap - 1.5).abs() < 1e-15);
        assert!((deep.normal - Vector3::y()).norm() < 1e-15);
    }
}
