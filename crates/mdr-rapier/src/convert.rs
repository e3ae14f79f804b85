//! Conversions at the boundary between rapier's glam vectors (`DVec3`) and the law crate's
//! nalgebra vectors (`Vector3<f64>`).

use nalgebra::Vector3;
use rapier3d_f64::math::Vector;

/// glam → nalgebra.
#[inline]
pub fn to_na(v: Vector) -> Vector3<f64> {
    Vector3::new(v.x, v.y, v.z)
}

/// nalgebra → glam.
#[inline]
pub fn to_glam(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x, v.y, v.z)
}
