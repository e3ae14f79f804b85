//! Conversions at the boundary between rapier's glam vectors (`DVec3`, rapier's
//! [`Vector`]) and the law crate's nalgebra vectors (`Vector3<f64>`), and [`AnyVector`]: the
//! coupling's functions accept either.

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

/// A 3-vector argument in rapier's type ([`Vector`], glam's `DVec3`, by value as rapier's own
/// API takes it) or in the law crate's (`&nalgebra::Vector3<f64>`, by reference as the law
/// crate takes it): the geometry functions take either, so that a rapier program passes
/// rapier's vectors and the kernel its own without a conversion at the call.
///
/// ```
/// use mdr_rapier::convert::AnyVector;
/// use mdr_rapier::rapier::math::Vector;
///
/// let v = Vector::new(1.0, 2.0, 3.0);
/// assert_eq!(v.glam(), v);
/// assert_eq!((&v.na()).glam(), v);
/// ```
pub trait AnyVector: Copy {
    /// The vector in the law crate's type.
    fn na(self) -> Vector3<f64>;
    /// The vector in rapier's type.
    fn glam(self) -> Vector;
}

impl AnyVector for Vector {
    #[inline(always)]
    fn na(self) -> Vector3<f64> {
        to_na(self)
    }
    #[inline(always)]
    fn glam(self) -> Vector {
        self
    }
}

impl AnyVector for &Vector3<f64> {
    #[inline(always)]
    fn na(self) -> Vector3<f64> {
        *self
    }
    #[inline(always)]
    fn glam(self) -> Vector {
        to_glam(self)
    }
}
