//! Walls and containers as solid convex pieces (half-spaces, cuboids, convex prisms) or a triangle
//! mesh read from STL/OBJ, in the coordinates of the body they are attached to.
//!
//! Containers are built from solid pieces rather than from an open surface mesh so that the
//! side a particle is on is never ambiguous: the plugin measures the overlap with a point
//! projection, which needs a closed shape to tell inside from outside.
//!
//! One job per module: the pieces and containers (here), the sink that takes spheres out of a
//! run and the removal of walls ([`sink`]), and triangle meshes read from files ([`mesh_file`]).

pub mod mesh_file;
pub mod sink;

pub use mesh_file::{read_mesh, read_mesh_with_notes, trimesh_shape};
pub use sink::{remove_due_walls, Parking, Sink, REMOVED_WALL_DROP_M};

use nalgebra::{Point3, Vector3};
use std::f64::consts::PI;

/// One solid piece of a wall, in the wall body's frame (m).
#[derive(Debug, Clone, PartialEq)]
pub enum WallPiece {
    /// Half-space bounded by the plane through `point` with outward unit `normal`.
    HalfSpace {
        /// A point on the plane.
        point: Vector3<f64>,
        /// Outward unit normal (the side the particles are on).
        normal: Vector3<f64>,
    },
    /// An oriented box.
    Cuboid {
        /// Centre.
        center: Vector3<f64>,
        /// Rotation of the box axes.
        rotation: nalgebra::UnitQuaternion<f64>,
        /// Half extents along the box axes.
        half_extents: Vector3<f64>,
    },
    /// The convex hull of a point set.
    ConvexHull {
        /// Points.
        points: Vec<Vector3<f64>>,
    },
    /// A triangle mesh ([`crate::mesh`]): closed, a solid whose faces' normals point to the
    /// particles' side; open, a sheet touched from either face.
    TriMesh {
        /// Vertices.
        vertices: Vec<Vector3<f64>>,
        /// Triangles.
        indices: Vec<[u32; 3]>,
        /// Closed and consistently wound (one-sided); open meshes are two-sided.
        closed: bool,
    },
}

/// A wall: its pieces and, for a kinematic wall, its rotation.
#[derive(Debug, Clone, PartialEq)]
pub struct Wall {
    /// Index of the `[[walls]]` entry.
    pub index: usize,
    /// Material index into the scene's materials.
    pub material: usize,
    /// Pieces, relative to `origin`.
    pub pieces: Vec<WallPiece>,
    /// Origin of the wall body (the rotation centre) in world coordinates (m).
    pub origin: Vector3<f64>,
    /// Constant angular velocity (rad/s) of a kinematic wall; `None` for a fixed wall.
    pub angular_velocity: Option<Vector3<f64>>,
    /// Simulated time (s) at which the wall is removed (a plug that opens); `None`: never.
    pub removed_at: Option<f64>,
    /// The exact surface a cylinder, cone or orifice-plate wall stands for (`exact_surface =
    /// true`), relative to `origin`: on the neighbour-list path the spheres touch it instead of
    /// `pieces`.
    pub revolution: Option<Revolution>,
}

/// A surface of revolution in the wall body's frame: the `(radius, axial position)` profile
/// turned about `axis` (unit) through `center` (m).
#[derive(Debug, Clone, PartialEq)]
pub struct Revolution {
    /// A point on the axis, where the axial position is zero.
    pub center: Vector3<f64>,
    /// Unit axis.
    pub axis: Vector3<f64>,
    /// Profile points `(radius, axial position)` (m).
    pub profile: Vec<(f64, f64)>,
}

impl Revolution {
    /// The inner surface of `cylinder_container` with the same arguments: the side at `radius`
    /// from `-length/2` to `length/2` about `center`, and the end discs when `capped`.
    pub fn cylinder(
        center: Vector3<f64>,
        axis: Vector3<f64>,
        radius: f64,
        length: f64,
        capped: bool,
    ) -> Self {
        let h = length / 2.0;
        let profile = if capped {
            vec![(0.0, -h), (radius, -h), (radius, h), (0.0, h)]
        } else {
            vec![(radius, -h), (radius, h)]
        };
        Self {
            center,
            axis,
            profile,
        }
    }

    /// The surface of `orifice_plate` with the same arguments, axis `z`: the top face from
    /// `outer_radius` in to the hole's rim, the hole's side down to the bottom face, and the
    /// bottom face back out (the outer rim, which no sphere reaches inside a container, is left
    /// open).
    pub fn orifice_plate(
        center: Vector3<f64>,
        outer_radius: f64,
        orifice_diameter: f64,
        thickness: f64,
    ) -> Self {
        let hole = orifice_diameter / 2.0;
        Self {
            center,
            axis: Vector3::z(),
            profile: vec![
                (outer_radius, 0.0),
                (hole, 0.0),
                (hole, -thickness),
                (outer_radius, -thickness),
            ],
        }
    }

    /// The inner surface of `cone_container` with the same arguments: radius `bottom_radius` at
    /// `center`, `top_radius` at `length` along `axis`.
    pub fn cone(
        center: Vector3<f64>,
        axis: Vector3<f64>,
        bottom_radius: f64,
        top_radius: f64,
        length: f64,
    ) -> Self {
        Self {
            center,
            axis,
            profile: vec![(bottom_radius, 0.0), (top_radius, length)],
        }
    }
}

/// The rotation taking `z` to `axis`.
fn rotation_from_z(axis: &Vector3<f64>) -> nalgebra::UnitQuaternion<f64> {
    nalgebra::UnitQuaternion::rotation_between(&Vector3::z(), axis).unwrap_or_else(|| {
        // axis = −z
        nalgebra::UnitQuaternion::from_axis_angle(&Vector3::x_axis(), PI)
    })
}

/// An open-top (or closed) box container whose inside is `[min, max]`, walls `thickness` thick.
pub fn box_container(
    min: Vector3<f64>,
    max: Vector3<f64>,
    thickness: f64,
    open_top: bool,
) -> Vec<WallPiece> {
    let c = (min + max) / 2.0;
    let h = (max - min) / 2.0;
    let t = thickness / 2.0;
    let id = nalgebra::UnitQuaternion::identity();
    let mut pieces = Vec::new();
    // Slabs overlap at the edges (extended by the thickness) so corners are closed.
    for axis in 0..3 {
        for side in [-1.0, 1.0] {
            if axis == 2 && side > 0.0 && open_top {
                continue;
            }
            let mut center = c;
            center[axis] += side * (h[axis] + t);
            let mut half = h.add_scalar(2.0 * t);
            half[axis] = t;
            pieces.push(WallPiece::Cuboid {
                center,
                rotation: id,
                half_extents: half,
            });
        }
    }
    pieces
}

/// A cylindrical container: `segments` slabs whose inner faces are tangent to the circle of
/// radius `radius` around `axis` through `center`, `length` long, optionally closed at both ends.
pub fn cylinder_container(
    center: Vector3<f64>,
    axis: Vector3<f64>,
    radius: f64,
    length: f64,
    thickness: f64,
    segments: u32,
    capped: bool,
) -> Vec<WallPiece> {
    let q = rotation_from_z(&axis);
    let n = segments.max(3) as f64;
    // Inner faces of width 2 r tan(π/n) meet at the polygon's corners.
    let half_width = radius * (PI / n).tan() + thickness;
    let mut pieces = Vec::new();
    for i in 0..segments.max(3) {
        let phi = 2.0 * PI * i as f64 / n;
        let radial = Vector3::new(phi.cos(), phi.sin(), 0.0);
        let local_center = radial * (radius + thickness / 2.0);
        let rot = q * nalgebra::UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi);
        pieces.push(WallPiece::Cuboid {
            center: center + q * local_center,
            rotation: rot,
            half_extents: Vector3::new(thickness / 2.0, half_width, length / 2.0),
        });
    }
    if capped {
        let r = radius + thickness;
        for side in [-1.0, 1.0] {
            pieces.push(WallPiece::Cuboid {
                center: center
                    + q * Vector3::new(0.0, 0.0, side * (length / 2.0 + thickness / 2.0)),
                rotation: q,
                half_extents: Vector3::new(r, r, thickness / 2.0),
            });
        }
    }
    pieces
}

/// A flat disc of radius `outer_radius` in the plane normal to `z` whose top face is at
/// `center.z`, with a circular hole of diameter `orifice_diameter`, built from `segments`
/// convex prisms around the hole.
pub fn orifice_plate(
    center: Vector3<f64>,
    outer_radius: f64,
    orifice_diameter: f64,
    thickness: f64,
    segments: u32,
) -> Vec<WallPiece> {
    let n = segments.max(3);
    let r_in = orifice_diameter / 2.0;
    let mut pieces = Vec::new();
    for i in 0..n {
        let a0 = 2.0 * PI * i as f64 / n as f64;
        let a1 = 2.0 * PI * (i + 1) as f64 / n as f64;
        let mut points = Vec::with_capacity(8);
        for z in [0.0, -thickness] {
            for (r, a) in [
                (r_in, a0),
                (r_in, a1),
                (outer_radius, a0),
                (outer_radius, a1),
            ] {
                points.push(center + Vector3::new(r * a.cos(), r * a.sin(), z));
            }
        }
        pieces.push(WallPiece::ConvexHull { points });
    }
    pieces
}

/// A conical container (a frustum, open at both ends): `segments` solid convex pieces whose
/// inner faces are tangent, at their mid-line, to the cone of radius `bottom_radius` at `center`
/// and `top_radius` a distance `length` along the unit `axis`; each piece is `thickness` thick
/// (measured across the axis). With `bottom_radius == top_radius` it is the open cylinder.
///
/// Each piece is the convex hull of two trapezoids, the inner one (the face the particles touch)
/// and the outer one; the four corners of a trapezoid are coplanar because its bottom and top
/// edges are parallel (both along `u(φ₁) − u(φ₀)`), so the inner face is one plane.
pub fn cone_container(
    center: Vector3<f64>,
    axis: Vector3<f64>,
    bottom_radius: f64,
    top_radius: f64,
    length: f64,
    thickness: f64,
    segments: u32,
) -> Vec<WallPiece> {
    let q = rotation_from_z(&axis);
    let n = segments.max(3);
    // Corners at r / cos(π/n): the faces' mid-lines lie on the cone (circumscribed polygon),
    // face centres at φ = 2π i / n as in `cylinder_container`.
    let corner = 1.0 / (PI / n as f64).cos();
    let mut pieces = Vec::with_capacity(n as usize);
    for i in 0..n {
        let phi = 2.0 * PI * i as f64 / n as f64;
        let (a0, a1) = (phi - PI / n as f64, phi + PI / n as f64);
        let mut points = Vec::with_capacity(8);
        for (z, r) in [(0.0, bottom_radius), (length, top_radius)] {
            for extra in [0.0, thickness] {
                for a in [a0, a1] {
                    let local = Vector3::new(a.cos(), a.sin(), 0.0) * ((r + extra) * corner)
                        + Vector3::new(0.0, 0.0, z);
                    points.push(center + q * local);
                }
            }
        }
        pieces.push(WallPiece::ConvexHull { points });
    }
    pieces
}

/// A signed-distance function of a wall piece (m, negative inside).
pub type DistanceFn<'a> = Box<dyn Fn(&Vector3<f64>) -> f64 + 'a>;

impl WallPiece {
    /// A signed-distance function of the piece (m, negative inside) for the placement check:
    /// exact for convex hulls (parry's point projection on the hull, built once here), as
    /// [`WallPiece::signed_distance`] otherwise. A slanted hull (a cone's piece) has a bounding
    /// box that reaches deep into the container, so the box bound would refuse valid placements.
    pub fn distance_fn(&self) -> DistanceFn<'_> {
        if let WallPiece::TriMesh {
            vertices,
            indices,
            closed,
        } = self
        {
            if let Ok(shape) = trimesh_shape(vertices, indices, *closed) {
                return Box::new(move |p: &Vector3<f64>| {
                    let q = mdr_rapier::convert::to_glam(p);
                    let proj = shape.project_local_point(q, false);
                    let d = mdr_rapier::convert::to_na(proj.point - q).norm();
                    if proj.is_inside {
                        -d
                    } else {
                        d
                    }
                });
            }
        }
        if let WallPiece::ConvexHull { points } = self {
            let pts: Vec<_> = points.iter().map(mdr_rapier::convert::to_glam).collect();
            if let Some(shape) = rapier3d_f64::prelude::SharedShape::convex_hull(&pts) {
                return Box::new(move |p: &Vector3<f64>| {
                    let q = mdr_rapier::convert::to_glam(p);
                    let proj = shape.project_local_point(q, false);
                    let d = mdr_rapier::convert::to_na(proj.point - q).norm();
                    if proj.is_inside {
                        -d
                    } else {
                        d
                    }
                });
            }
        }
        Box::new(move |p: &Vector3<f64>| self.signed_distance(p))
    }

    /// Signed distance (m) from `p` to the piece's surface, negative inside, approximately for
    /// meshes and convex hulls (used only to check the initial placement).
    pub fn signed_distance(&self, p: &Vector3<f64>) -> f64 {
        match self {
            WallPiece::HalfSpace { point, normal } => (p - point).dot(normal),
            WallPiece::Cuboid {
                center,
                rotation,
                half_extents,
            } => {
                let local = rotation.inverse() * (p - center);
                let q = local.abs() - half_extents;
                let outside = q.sup(&Vector3::zeros()).norm();
                outside + q.max().min(0.0)
            }
            WallPiece::ConvexHull { points }
            | WallPiece::TriMesh {
                vertices: points, ..
            } => {
                // Conservative: distance to the bounding box (placement check only).
                let mut lo = Point3::from(points[0]);
                let mut hi = lo;
                for q in points {
                    lo = lo.inf(&Point3::from(*q));
                    hi = hi.sup(&Point3::from(*q));
                }
                let c = (lo.coords + hi.coords) / 2.0;
                let h = (hi.coords - lo.coords) / 2.0;
                let q = (p - c).abs() - h;
                if matches!(self, WallPiece::TriMesh { .. }) {
                    // A mesh may be a hollow container: never call its inside overlapping.
                    return f64::INFINITY;
                }
                q.sup(&Vector3::zeros()).norm() + q.max().min(0.0)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cone's inner faces touch the cone at their mid-lines: a point on the axis is
    /// `r(z)` from the nearest piece at every height, and a point a little beyond the cone's
    /// surface (between two pieces' corners, where the polygon reaches farthest) is inside a piece.
    #[test]
    fn cone_pieces_are_tangent_to_the_cone() {
        let center = Vector3::new(25.0, 25.0, 10.0);
        let pieces = cone_container(center, Vector3::z(), 2.0, 20.0, 40.0, 1.0, 64);
        assert_eq!(pieces.len(), 64);
        let distances: Vec<_> = pieces.iter().map(WallPiece::distance_fn).collect();
        // Heights where the foot of the perpendicular from the axis lies on the pieces.
        for z in [5.0, 10.0, 20.0, 39.5] {
            let r = 2.0 + (20.0 - 2.0) * z / 40.0;
            // The slant shortens the distance from the axis to the face by cos(slant).
            let slant = ((20.0_f64 - 2.0) / 40.0).atan();
            let p = center + Vector3::new(0.0, 0.0, z);
            let nearest = distances
                .iter()
                .map(|d| d(&p))
                .fold(f64::INFINITY, f64::min);
            assert!(
                (nearest - r * slant.cos()).abs() < 1e-9 * r,
                "z = {z}: {nearest} vs {}",
                r * slant.cos()
            );
            // Straight out at a face centre (φ = 0): on the surface at r, inside beyond it.
            let on = center + Vector3::new(r, 0.0, z);
            assert!(distances[0](&on).abs() < 1e-9, "{}", distances[0](&on));
            let beyond = center + Vector3::new(r + 0.1, 0.0, z);
            assert!(distances[0](&beyond) < 0.0);
        }
    }
}
