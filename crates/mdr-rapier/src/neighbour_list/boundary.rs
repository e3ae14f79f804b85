//! Boundaries of the neighbour-list path: open space, or a box periodic in x and y.
//!
//! Everything that depends on the kind of boundary goes through two notions, so that a
//! shear-periodic (Lees–Edwards) box only has to supply new ones:
//! - an [`Image`] `(i_x, i_y) ∈ {−1, 0, 1}²` and its [`ImageOffset`]: the position and velocity
//!   added to a particle to obtain that periodic image (periodic box: `(i_x L_x, i_y L_y, 0)` and no
//!   velocity; Lees–Edwards: `(i_x L_x + i_y s(t), i_y L_y, 0)` and `(i_y γ̇ L_y, 0, 0)`);
//! - [`Boundary::wrap`], which maps a particle that left the box back into it (Lees–Edwards would
//!   also shift its velocity).
//!
//! Neighbour lists store the image of each pair; ghosts for binning are made from the offsets, so
//! the neighbour search never looks at the kind of boundary.

use crate::convert::AnyVector;
use crate::error::{positive, CouplingError, Result};
use nalgebra::Vector3;
use rapier3d_f64::math::Vector;

/// A periodic image: shifts by `(x, y)` box lengths, each in `{−1, 0, 1}`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct Image {
    /// Box lengths along x.
    pub x: i8,
    /// Box lengths along y.
    pub y: i8,
}

impl Image {
    /// The image itself (no shift).
    pub const ZERO: Image = Image { x: 0, y: 0 };

    /// Compact code in `0..9` (`(x + 1) · 3 + (y + 1)`), the index into per-step offset tables;
    /// code 4 is [`Image::ZERO`].
    #[inline]
    pub fn code(self) -> u8 {
        ((self.x + 1) * 3 + (self.y + 1)) as u8
    }

    /// The image of a code made by [`Image::code`].
    #[inline]
    pub fn from_code(code: u8) -> Image {
        Image {
            x: (code / 3) as i8 - 1,
            y: (code % 3) as i8 - 1,
        }
    }

    /// The eight non-trivial images.
    pub fn shifted() -> impl Iterator<Item = Image> {
        (0u8..9).filter(|&c| c != 4).map(Image::from_code)
    }
}

/// What is added to a particle's position and velocity to get one of its images.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImageOffset {
    /// Position shift.
    pub position: Vector3<f64>,
    /// Velocity shift (zero in a plain periodic box).
    pub velocity: Vector3<f64>,
}

impl ImageOffset {
    /// Position shift (m), in rapier's vector type.
    pub fn position_shift(&self) -> Vector {
        self.position.glam()
    }

    /// Velocity shift (m/s), in rapier's vector type.
    pub fn velocity_shift(&self) -> Vector {
        self.velocity.glam()
    }
}

/// The box of the neighbour-list path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Boundary {
    /// No periodicity: rapier colliders (walls, floors …) confine the particles.
    Open,
    /// Periodic in x over `[x_lo, x_hi)` and in y over `[y_lo, y_hi)`; open in z.
    PeriodicXY {
        /// Lower corner `(x_lo, y_lo)`.
        lo: [f64; 2],
        /// Upper corner `(x_hi, y_hi)`.
        hi: [f64; 2],
    },
}

impl Boundary {
    /// A box periodic in x over `[x_lo, x_hi)` and in y over `[y_lo, y_hi)`.
    pub fn periodic_xy(x: (f64, f64), y: (f64, f64)) -> Result<Self> {
        for (name, (lo, hi)) in [("box_x_length", x), ("box_y_length", y)] {
            if !(lo.is_finite() && hi.is_finite()) {
                return Err(CouplingError::OutOfRange {
                    name,
                    value: hi - lo,
                    range: "(0, inf) with finite bounds",
                });
            }
            positive(name, hi - lo)?;
        }
        Ok(Boundary::PeriodicXY {
            lo: [x.0, y.0],
            hi: [x.1, y.1],
        })
    }

    /// Whether any direction is periodic.
    pub fn is_periodic(&self) -> bool {
        !matches!(self, Boundary::Open)
    }

    /// Box lengths `(L_x, L_y)`, infinite when open.
    pub fn lengths(&self) -> [f64; 2] {
        match self {
            Boundary::Open => [f64::INFINITY; 2],
            Boundary::PeriodicXY { lo, hi } => [hi[0] - lo[0], hi[1] - lo[1]],
        }
    }

    /// Check that no pair can see two images of the same particle: every periodic length must be
    /// at least twice the neighbour cutoff (largest diameter + skin).
    pub fn check_cutoff(&self, cutoff: f64) -> Result<()> {
        for length in self.lengths() {
            if length < 2.0 * cutoff {
                return Err(CouplingError::OutOfRange {
                    name: "periodic box length",
                    value: length,
                    range: "[2 × (largest diameter + skin), inf)",
                });
            }
        }
        Ok(())
    }

    /// Offset of `image` (the zero image has zero offset).
    #[inline]
    pub fn offset(&self, image: Image) -> ImageOffset {
        match self {
            Boundary::Open => ImageOffset::default(),
            Boundary::PeriodicXY { lo, hi } => ImageOffset {
                position: Vector3::new(
                    f64::from(image.x) * (hi[0] - lo[0]),
                    f64::from(image.y) * (hi[1] - lo[1]),
                    0.0,
                ),
                velocity: Vector3::zeros(),
            },
        }
    }

    /// The nine offsets indexed by [`Image::code`].
    pub fn offsets(&self) -> [ImageOffset; 9] {
        std::array::from_fn(|c| self.offset(Image::from_code(c as u8)))
    }

    /// Map a position (and velocity) back into the box.
    #[inline]
    pub fn wrap(&self, position: &mut Vector3<f64>, _velocity: &mut Vector3<f64>) {
        if let Boundary::PeriodicXY { lo, hi } = self {
            for k in 0..2 {
                let length = hi[k] - lo[k];
                if position[k] < lo[k] || position[k] >= hi[k] {
                    position[k] -= ((position[k] - lo[k]) / length).floor() * length;
                    // Round-off can land exactly on hi.
                    if position[k] >= hi[k] {
                        position[k] = lo[k];
                    }
                }
            }
        }
    }

    /// `position` mapped back into the box, in rapier's vector type.
    pub fn wrapped(&self, position: impl AnyVector) -> Vector {
        let mut x = position.na();
        self.wrap(&mut x, &mut Vector3::zeros());
        x.glam()
    }

    /// Whether the image of `position` by `offset` lies within `margin` of the box in x and y
    /// (then it is a ghost the neighbour search must see).
    #[inline]
    pub fn near_box(&self, position: impl AnyVector, margin: f64) -> bool {
        let position = position.na();
        match self {
            Boundary::Open => true,
            Boundary::PeriodicXY { lo, hi } => {
                (0..2).all(|k| position[k] >= lo[k] - margin && position[k] < hi[k] + margin)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn image_codes_round_trip() {
        for c in 0..9u8 {
            assert_eq!(Image::from_code(c).code(), c);
        }
        assert_eq!(Image::ZERO.code(), 4);
        assert_eq!(Image::shifted().count(), 8);
    }

    #[test]
    fn wrap_and_offsets() {
        let b = Boundary::periodic_xy((0.0, 22.0), (-1.0, 1.0)).unwrap();
        let mut x = Vector3::new(-0.5, 1.5, 7.0);
        let mut v = Vector3::zeros();
        b.wrap(&mut x, &mut v);
        assert!((x - Vector3::new(21.5, -0.5, 7.0)).norm() < 1e-14);
        let o = b.offset(Image { x: -1, y: 1 });
        assert_eq!(o.position, Vector3::new(-22.0, 2.0, 0.0));
        assert!(Boundary::periodic_xy((0.0, 0.0), (0.0, 1.0)).is_err());
        assert!(b.check_cutoff(1.1).is_err());
    }
}
