//! Shear-periodic (Lees–Edwards) boundaries of the shearing box: periodic in y, periodic in x with
//! the neighbouring boxes sliding along y at the shear velocity jump `(3/2) Ω L_x`, free in z.
//!
//! The image of a particle in the box `i` steps out radially (`i ∈ {−1, 0, 1}`) and `n` steps along
//! y sits at `(x + i L_x, y − i S(t) + n L_y, z)` and moves with `ẏ − i (3/2) Ω L_x`, where
//! `S(t) = (3/2) Ω L_x t` is the accumulated shear offset (docs/rings.md §3).

use crate::error::{positive, Result};
use crate::hill::HillFrame;
use rapier3d_f64::math::Vector;

/// Label of one periodic image of a particle: the box offset `i` in x and the lattice offset `n`
/// in y, counted against the *unwrapped* shear offset so that the label of a given image does not
/// change while the boxes slide.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ImageLabel {
    /// Box offset in x, −1, 0 or 1.
    pub radial: i8,
    /// Lattice offset in y.
    pub azimuthal: i64,
}

impl ImageLabel {
    /// Whether the image lies on the lower side of a boundary: shifted by `−L_x` (left of the
    /// box, any azimuthal offset) or, in the same radial column, by `−L_y` (below the box). Of the
    /// two images through which a pair can touch across a boundary, exactly one is on the lower
    /// side, so ghosts for these images alone see every such contact once.
    pub fn is_lower_side(&self) -> bool {
        self.radial == -1 || (self.radial == 0 && self.azimuthal == -1)
    }
}

/// One periodic image: its label, position and velocity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Image {
    /// Which image this is.
    pub label: ImageLabel,
    /// Its position (m).
    pub position: Vector,
    /// Its velocity (m/s).
    pub velocity: Vector,
}

/// The shearing box: side lengths `L_x` (radial) and `L_y` (azimuthal), centred on the origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearingBox {
    frame: HillFrame,
    lx: f64,
    ly: f64,
}

impl ShearingBox {
    /// A box of sides `lx` × `ly` (m, > 0) in `frame`.
    pub fn new(frame: HillFrame, lx: f64, ly: f64) -> Result<Self> {
        Ok(Self {
            frame,
            lx: positive("box_x", lx)?,
            ly: positive("box_y", ly)?,
        })
    }

    /// Radial side `L_x` (m).
    pub fn lx(&self) -> f64 {
        self.lx
    }

    /// Azimuthal side `L_y` (m).
    pub fn ly(&self) -> f64 {
        self.ly
    }

    /// Area `L_x L_y` (m²).
    pub fn area(&self) -> f64 {
        self.lx * self.ly
    }

    /// The rotating frame.
    pub fn frame(&self) -> HillFrame {
        self.frame
    }

    /// Velocity jump between neighbouring boxes, `(3/2) Ω L_x` (m/s).
    pub fn shear_speed(&self) -> f64 {
        1.5 * self.frame.omega() * self.lx
    }

    /// Accumulated shear offset `S(t) = (3/2) Ω L_x t` (m), not reduced modulo `L_y`.
    pub fn shear_offset(&self, time: f64) -> f64 {
        self.shear_speed() * time
    }

    /// Bring a particle that left the box back in through the opposite side: across x it becomes
    /// its image from the neighbouring box (shifted along y by the shear offset and with the
    /// velocity jump), across y it is shifted by `L_y`. Returns whether it was moved.
    pub fn wrap(&self, position: &mut Vector, velocity: &mut Vector, time: f64) -> bool {
        let (hx, hy) = (0.5 * self.lx, 0.5 * self.ly);
        let mut moved = false;
        if position.x >= hx || position.x < -hx {
            let i = if position.x >= hx { -1.0 } else { 1.0 };
            position.x += i * self.lx;
            position.y -= i * self.shear_offset(time);
            velocity.y -= i * self.shear_speed();
            moved = true;
        }
        if position.y >= hy || position.y < -hy {
            position.y -= self.ly * ((position.y + hy) / self.ly).floor();
            // Round-off can leave y at +L_y/2 exactly.
            if position.y >= hy {
                position.y -= self.ly;
            }
            moved = true;
        }
        moved
    }

    /// The images of [`Self::images_near_box`] that lie on the lower side of a boundary
    /// ([`ImageLabel::is_lower_side`]). Only a particle within `margin` of the outer (`+x`) or
    /// upper (`+y`) edge has one, so the others return at once.
    pub fn lower_side_images_near_box(
        &self,
        position: Vector,
        velocity: Vector,
        time: f64,
        margin: f64,
        out: &mut Vec<Image>,
    ) {
        if position.x < 0.5 * self.lx - margin && position.y < 0.5 * self.ly - margin {
            return;
        }
        let start = out.len();
        self.images_near_box(position, velocity, time, margin, out);
        let mut kept = start;
        for k in start..out.len() {
            if out[k].label.is_lower_side() {
                out[kept] = out[k];
                kept += 1;
            }
        }
        out.truncate(kept);
    }

    /// Every image of a particle at `position` with `velocity` (inside the box), other than the
    /// particle itself, that lies within `margin` (m) of the box, at `time`.
    pub fn images_near_box(
        &self,
        position: Vector,
        velocity: Vector,
        time: f64,
        margin: f64,
        out: &mut Vec<Image>,
    ) {
        let (hx, hy) = (0.5 * self.lx + margin, 0.5 * self.ly + margin);
        let offset = self.shear_offset(time);
        // Split the unwrapped offset into whole boxes and a remainder for round-off.
        let whole = (offset / self.ly).floor();
        let rest = offset - whole * self.ly;
        for i in -1i8..=1 {
            let x = position.x + f64::from(i) * self.lx;
            if x.abs() > hx {
                continue;
            }
            let fi = f64::from(i);
            // y' = y − i S + n L_y = (y − i rest) + (n − i whole) L_y.
            let y0 = position.y - fi * rest;
            let m_lo = ((-hy - y0) / self.ly).ceil() as i64;
            let m_hi = ((hy - y0) / self.ly).floor() as i64;
            for m in m_lo..=m_hi {
                let n = m + i64::from(i) * whole as i64;
                if i == 0 && n == 0 {
                    continue;
                }
                out.push(Image {
                    label: ImageLabel {
                        radial: i,
                        azimuthal: n,
                    },
                    position: Vector::new(x, y0 + m as f64 * self.ly, position.z),
                    velocity: Vector::new(
                        velocity.x,
                        velocity.y - fi * self.shear_speed(),
                        velocity.z,
                    ),
                });
            }
        }
    }
}
