//! Contact geometry at the current poses: overlap, normal and contact point of a sphere against
//! another sphere (closed form) or against any parry shape (point projection of the centre).
//!
//! rapier's manifolds are not used for the overlap: with contact recycling their points can be
//! stale by up to the recycle distance, far more than a micrometre overlap. The narrow phase only
//! provides the candidate pairs.
//!
//! Every function takes its points and directions as rapier's vector type or the law crate's
//! ([`AnyVector`]); a [`SurfaceContact`] reads in either.

use crate::convert::{to_glam, to_na, AnyVector};
use nalgebra::Vector3;
use rapier3d_f64::math::{Pose, Vector};
use rapier3d_f64::parry::shape::Shape;

/// Where and how deep two bodies touch. The fields are in the law crate's vector type (the
/// per-pair kernel hands them to the law as they are); [`SurfaceContact::normal`] and
/// [`SurfaceContact::point`] give them in rapier's.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceContact {
    /// Overlap `δ` (m), > 0.
    pub overlap: f64,
    /// Unit normal from body 2 towards body 1 (the sphere).
    pub normal: Vector3<f64>,
    /// Contact point (m): the middle of the overlap along the normal.
    pub point: Vector3<f64>,
}

impl SurfaceContact {
    /// Unit normal from body 2 towards body 1 (the sphere), in rapier's vector type.
    #[inline]
    pub fn normal(&self) -> Vector {
        to_glam(&self.normal)
    }

    /// Contact point (m), in rapier's vector type.
    #[inline]
    pub fn point(&self) -> Vector {
        to_glam(&self.point)
    }
}

/// Sphere 1 (centre `c1`, radius `r1`) against sphere 2; `None` when they do not overlap.
#[inline]
pub fn sphere_sphere(
    c1: impl AnyVector,
    r1: f64,
    c2: impl AnyVector,
    r2: f64,
) -> Option<SurfaceContact> {
    let (c1, c2) = (c1.na(), c2.na());
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

/// [`sphere_sphere`] at any distance: the overlap is negative by the gap between the spheres
/// while they are apart. An adhesive contact that still holds there
/// ([`mdr_contact::normal::NormalLaw::holds`]) is evaluated at it. `None` only when the centres
/// coincide.
#[inline]
pub fn sphere_sphere_signed(
    c1: impl AnyVector,
    r1: f64,
    c2: impl AnyVector,
    r2: f64,
) -> Option<SurfaceContact> {
    let (c1, c2) = (c1.na(), c2.na());
    let d = c1 - c2;
    let dist2 = d.norm_squared();
    if dist2 == 0.0 {
        return None;
    }
    let dist = dist2.sqrt();
    let overlap = r1 + r2 - dist;
    let normal = d * (1.0 / dist);
    Some(SurfaceContact {
        overlap,
        normal,
        point: c2 + normal * (r2 - 0.5 * overlap),
    })
}

/// [`sphere_shape`] at any distance: the overlap is negative by the gap between the sphere and
/// the shape while they are apart (see [`sphere_sphere_signed`]). `None` only when the centre
/// lies on the shape's boundary.
pub fn sphere_shape_signed(
    c1: impl AnyVector,
    r1: f64,
    shape: &dyn Shape,
    pose: &Pose,
) -> Option<SurfaceContact> {
    let c1 = c1.na();
    let projection = shape.project_point(pose, to_glam(&c1), false);
    let p = to_na(projection.point);
    let d = c1 - p;
    let dist = d.norm();
    if dist == 0.0 {
        return None;
    }
    let (signed, normal) = if projection.is_inside {
        (-dist, -d / dist)
    } else {
        (dist, d / dist)
    };
    let overlap = r1 - signed;
    Some(SurfaceContact {
        overlap,
        normal,
        point: p - normal * (0.5 * overlap),
    })
}

/// [`sphere_half_space`] at any distance (see [`sphere_sphere_signed`]).
#[inline]
pub fn sphere_half_space_signed(
    c1: impl AnyVector,
    r1: f64,
    local_normal: impl AnyVector,
    pose: &Pose,
) -> SurfaceContact {
    let c1 = c1.na();
    let (normal, signed) = half_space_normal_and_distance(&c1, &local_normal.na(), pose);
    let overlap = r1 - signed;
    SurfaceContact {
        overlap,
        normal,
        point: c1 - normal * (signed + 0.5 * overlap),
    }
}

/// [`sphere_convex`] at any distance (see [`sphere_sphere_signed`]).
pub fn sphere_convex_signed(
    c1: impl AnyVector,
    r1: f64,
    faces: &ConvexFaces,
    shape: &dyn Shape,
    pose: &Pose,
) -> Option<SurfaceContact> {
    let c1 = &c1.na();
    let local = to_na(pose.inverse_transform_point(to_glam(c1)));
    match faces.project(&local, f64::INFINITY) {
        ConvexProjection::Nearest(q) => {
            sphere_point_signed(c1, r1, &to_na(pose.transform_point(to_glam(&q))))
        }
        ConvexProjection::Inside | ConvexProjection::Beyond => {
            sphere_shape_signed(c1, r1, shape, pose)
        }
    }
}

/// Sphere 1 (centre `c1`, radius `r1`) against the nearest point `p` of a surface that lies
/// outside the sphere's centre, at any distance; `None` only when the centre is on the surface.
#[inline]
fn sphere_point_signed(c1: &Vector3<f64>, r1: f64, p: &Vector3<f64>) -> Option<SurfaceContact> {
    let d = c1 - p;
    let dist = d.norm();
    if dist == 0.0 {
        return None;
    }
    let overlap = r1 - dist;
    let normal = d / dist;
    Some(SurfaceContact {
        overlap,
        normal,
        point: p - normal * (0.5 * overlap),
    })
}

/// Sphere 1 (centre `c1`, radius `r1`) against any shape at `pose`, through the projection of the
/// centre on the shape's boundary; `None` when they do not overlap.
pub fn sphere_shape(
    c1: impl AnyVector,
    r1: f64,
    shape: &dyn Shape,
    pose: &Pose,
) -> Option<SurfaceContact> {
    sphere_shape_signed(c1, r1, shape, pose).filter(|contact| contact.overlap > 0.0)
}

/// Sphere 1 (centre `c1`, radius `r1`) against a half-space whose boundary plane has the outward
/// unit normal `local_normal` in its collider's frame and passes through the frame's origin (parry's
/// `HalfSpace` at `pose`), in closed form: the signed distance of the centre is `n · (c1 − o)`.
/// `None` when they do not overlap. Agrees with [`sphere_shape`] (parry's projection) to
/// round-off, without its generic projection.
#[inline]
pub fn sphere_half_space(
    c1: impl AnyVector,
    r1: f64,
    local_normal: impl AnyVector,
    pose: &Pose,
) -> Option<SurfaceContact> {
    let c1 = c1.na();
    let (normal, signed) = half_space_normal_and_distance(&c1, &local_normal.na(), pose);
    let overlap = r1 - signed;
    if overlap <= 0.0 {
        return None;
    }
    // The centre's projection on the plane, moved half the overlap into the wall.
    Some(SurfaceContact {
        overlap,
        normal,
        point: c1 - normal * (signed + 0.5 * overlap),
    })
}

/// Signed distance of `x` from the boundary plane of [`sphere_half_space`]'s half-space
/// (negative inside).
#[inline]
pub fn half_space_distance(x: impl AnyVector, local_normal: impl AnyVector, pose: &Pose) -> f64 {
    half_space_normal_and_distance(&x.na(), &local_normal.na(), pose).1
}

/// The half-space's outward normal in the world and the signed distance `n · (x − o)` of `x`.
#[inline(always)]
fn half_space_normal_and_distance(
    x: &Vector3<f64>,
    local_normal: &Vector3<f64>,
    pose: &Pose,
) -> (Vector3<f64>, f64) {
    let normal = to_na(pose.rotation * to_glam(local_normal));
    (normal, normal.dot(&(x - to_na(pose.translation))))
}

/// A convex polyhedron as its planar faces, for an exact sphere contact without GJK: the
/// nearest point of a convex solid to an outside point lies on a face whose plane has the point
/// on its outer side (the point minus the nearest point is a non-negative combination of the
/// normals of the faces through the nearest point, so one of them has a positive distance), so
/// the nearest point is the nearest point of those faces' polygons. A sphere farther than its
/// radius outside any face's plane cannot touch the solid (the solid lies behind every plane).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ConvexFaces {
    /// Outward unit normal of each face.
    normals: Vec<Vector3<f64>>,
    /// `normal · v` for a vertex `v` of each face.
    offsets: Vec<f64>,
    /// `start[f]..start[f + 1]`: the face's vertices, in order around it.
    start: Vec<u32>,
    /// Vertices of every face, face after face.
    vertices: Vec<Vector3<f64>>,
    /// Outward in-plane normal of the edge from each vertex to the next of its face.
    edge_normals: Vec<Vector3<f64>>,
}

/// Where a point is relative to a [`ConvexFaces`] solid, within a reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConvexProjection {
    /// Outside by more than the reach (the point is beyond a face's plane by more).
    Beyond,
    /// Inside the solid (behind every face's plane).
    Inside,
    /// Outside, with this nearest point of the solid.
    Nearest(Vector3<f64>),
}

impl ConvexProjection {
    /// The nearest point of [`ConvexProjection::Nearest`] in rapier's vector type.
    pub fn nearest(&self) -> Option<Vector> {
        match self {
            ConvexProjection::Nearest(q) => Some(to_glam(q)),
            _ => None,
        }
    }
}

impl ConvexFaces {
    /// The faces of a parry convex polyhedron (in its local frame).
    pub fn of(poly: &rapier3d_f64::parry::shape::ConvexPolyhedron) -> Self {
        let points = poly.points();
        let adjacent = poly.vertices_adj_to_face();
        let mut faces = Self::default();
        faces.start.push(0);
        for face in poly.faces() {
            let first = face.first_vertex_or_edge as usize;
            let ring: Vec<Vector3<f64>> = adjacent
                [first..first + face.num_vertices_or_edges as usize]
                .iter()
                .map(|&v| to_na(points[v as usize]))
                .collect();
            let normal = to_na(face.normal).normalize();
            let centroid = ring.iter().sum::<Vector3<f64>>() / ring.len() as f64;
            for (k, v) in ring.iter().enumerate() {
                let next = ring[(k + 1) % ring.len()];
                let mut m = (next - v).cross(&normal);
                // Outward: away from the face's centroid.
                if m.dot(&(centroid - v)) > 0.0 {
                    m = -m;
                }
                let len = m.norm();
                faces.edge_normals.push(if len > 0.0 { m / len } else { m });
            }
            faces.offsets.push(normal.dot(&ring[0]));
            faces.normals.push(normal);
            faces.vertices.extend_from_slice(&ring);
            faces.start.push(faces.vertices.len() as u32);
        }
        faces
    }

    /// Number of faces.
    pub fn len(&self) -> usize {
        self.normals.len()
    }

    /// Whether there are no faces.
    pub fn is_empty(&self) -> bool {
        self.normals.is_empty()
    }

    /// The nearest point of the solid to `x` (local frame), unless `x` is inside it or farther
    /// than `reach` outside one of its faces' planes.
    pub fn project(&self, x: impl AnyVector, reach: f64) -> ConvexProjection {
        let x = &x.na();
        let mut outside = false;
        for (n, &c) in self.normals.iter().zip(&self.offsets) {
            let d = n.dot(x) - c;
            if d > reach {
                return ConvexProjection::Beyond;
            }
            outside |= d > 0.0;
        }
        if !outside {
            return ConvexProjection::Inside;
        }
        let mut best = (f64::INFINITY, Vector3::zeros());
        for (f, (n, &c)) in self.normals.iter().zip(&self.offsets).enumerate() {
            let d = n.dot(x) - c;
            if d <= 0.0 {
                continue;
            }
            let y = x - n * d;
            let (a, b) = (self.start[f] as usize, self.start[f + 1] as usize);
            let ring = &self.vertices[a..b];
            let mut inside = true;
            for (k, v) in ring.iter().enumerate() {
                if (y - v).dot(&self.edge_normals[a + k]) <= 0.0 {
                    continue;
                }
                inside = false;
                // The nearest point of the polygon lies on an edge that `y` is beyond.
                let w = ring[(k + 1) % ring.len()];
                let e = w - v;
                let len2 = e.norm_squared();
                let t = if len2 > 0.0 {
                    ((x - v).dot(&e) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let q = v + e * t;
                let dist2 = (x - q).norm_squared();
                if dist2 < best.0 {
                    best = (dist2, q);
                }
            }
            if inside && d * d < best.0 {
                best = (d * d, y);
            }
        }
        ConvexProjection::Nearest(best.1)
    }
}

/// [`sphere_shape`] for a convex polyhedron given by its [`ConvexFaces`] (exact, no GJK);
/// a centre inside the solid goes to `shape`'s own projection.
#[inline]
pub fn sphere_convex(
    c1: impl AnyVector,
    r1: f64,
    faces: &ConvexFaces,
    shape: &dyn Shape,
    pose: &Pose,
) -> Option<SurfaceContact> {
    let c1 = &c1.na();
    let local = to_na(pose.inverse_transform_point(to_glam(c1)));
    match faces.project(&local, r1) {
        ConvexProjection::Beyond => None,
        ConvexProjection::Inside => sphere_shape(c1, r1, shape, pose),
        ConvexProjection::Nearest(q) => {
            sphere_point_signed(c1, r1, &to_na(pose.transform_point(to_glam(&q))))
                .filter(|contact| contact.overlap > 0.0)
        }
    }
}

/// Distance from `x` to a convex polyhedron given by its [`ConvexFaces`] when it is at most
/// `reach` (`Some(0)` inside); `None` when it is more.
pub fn convex_distance_within(
    x: impl AnyVector,
    faces: &ConvexFaces,
    pose: &Pose,
    reach: f64,
) -> Option<f64> {
    let local = to_na(pose.inverse_transform_point(x.glam()));
    match faces.project(&local, reach) {
        ConvexProjection::Beyond => None,
        ConvexProjection::Inside => Some(0.0),
        ConvexProjection::Nearest(q) => Some((local - q).norm()).filter(|&d| d < reach),
    }
}

/// A thin surface of revolution: a polyline profile of `(radius, axial position)` points turned
/// about an axis through `origin` along the unit `axis`, both in a collider's local frame. A
/// cylinder is one segment at constant radius, a cone frustum one slanted segment, a capped
/// cylinder three. LAMMPS's `region cylinder` and `region cone` walls are such surfaces.
///
/// **Contact.** The point of a surface of revolution nearest to a point `x` off the axis lies in
/// the meridional half-plane through `x` (the surface is symmetric under rotations about the
/// axis, and the distance to a circle of the surface is smallest at the circle's point in that
/// half-plane), so the distance is the planar distance from `(ρ, a)` (`ρ` the distance of `x` from
/// the axis, `a` its axial position) to the profile polyline: exact, with no facets, and a profile
/// vertex gives the exact contact with the circular rim it sweeps (a rim contact). The surface
/// has no thickness: a sphere touches it from either side.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceOfRevolution {
    origin: Vector3<f64>,
    axis: Vector3<f64>,
    profile: Vec<(f64, f64)>,
}

impl SurfaceOfRevolution {
    /// The surface of `profile` (`(radius, axial position)` points, at least two, radius ≥ 0) about
    /// `axis` (normalised here) through `origin`, in the collider's local frame.
    pub fn new(
        origin: impl AnyVector,
        axis: impl AnyVector,
        profile: Vec<(f64, f64)>,
    ) -> Result<Self, crate::CouplingError> {
        let (origin, axis) = (origin.na(), axis.na());
        let out = |name, value: f64, range| crate::CouplingError::OutOfRange { name, value, range };
        let length = axis.norm();
        if !(length.is_finite() && length > 0.0 && origin.iter().all(|c| c.is_finite())) {
            return Err(out("axis", length, "a finite non-zero vector"));
        }
        if profile.len() < 2 {
            return Err(out("profile", profile.len() as f64, "at least 2 points"));
        }
        for &(r, a) in &profile {
            if !(r.is_finite() && r >= 0.0 && a.is_finite()) {
                return Err(out(
                    "profile radius",
                    r,
                    "finite and >= 0, with a finite axial position",
                ));
            }
        }
        Ok(Self {
            origin,
            axis: axis / length,
            profile,
        })
    }

    /// The profile points `(radius, axial position)`.
    pub fn profile(&self) -> &[(f64, f64)] {
        &self.profile
    }

    /// Nearest point of the surface to the local point `x`: `(distance, unit normal from the
    /// surface towards x, surface point)`, all local; the normal is undefined (zero) at distance 0.
    fn nearest(&self, x: &Vector3<f64>) -> (f64, Vector3<f64>, Vector3<f64>) {
        let rel = x - self.origin;
        let a = rel.dot(&self.axis);
        let radial = rel - self.axis * a;
        let rho = radial.norm();
        // On the axis every meridional half-plane is nearest: take any direction across it.
        let e = if rho > 0.0 {
            radial / rho
        } else {
            let t = if self.axis.x.abs() < 0.9 {
                Vector3::x()
            } else {
                Vector3::y()
            };
            (t - self.axis * t.dot(&self.axis)).normalize()
        };
        let (mut best2, mut best) = (f64::INFINITY, (0.0, 0.0));
        for w in self.profile.windows(2) {
            let ((r0, a0), (r1, a1)) = (w[0], w[1]);
            let (dr, da) = (r1 - r0, a1 - a0);
            let len2 = dr * dr + da * da;
            let t = if len2 > 0.0 {
                (((rho - r0) * dr + (a - a0) * da) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (qr, qa) = (r0 + t * dr, a0 + t * da);
            let d2 = (rho - qr).powi(2) + (a - qa).powi(2);
            if d2 < best2 {
                best2 = d2;
                best = (qr, qa);
            }
        }
        let point = self.origin + e * best.0 + self.axis * best.1;
        let d = x - point;
        let dist = best2.sqrt();
        let normal = if dist > 0.0 {
            d / dist
        } else {
            Vector3::zeros()
        };
        (dist, normal, point)
    }

    /// Contact of the sphere (centre `c1` in world coordinates, radius `r1`) with the surface on
    /// a collider at `pose`; `None` when they do not overlap.
    pub fn sphere_contact(
        &self,
        c1: impl AnyVector,
        r1: f64,
        pose: &Pose,
    ) -> Option<SurfaceContact> {
        let c1 = &c1.na();
        let local = to_na(pose.inverse_transform_point(to_glam(c1)));
        let (dist, normal, _) = self.nearest(&local);
        let overlap = r1 - dist;
        if overlap <= 0.0 || dist == 0.0 {
            return None;
        }
        let normal = to_na(pose.rotation * to_glam(&normal));
        let p = c1 - normal * dist;
        Some(SurfaceContact {
            overlap,
            normal,
            point: p - normal * (0.5 * overlap),
        })
    }

    /// [`SurfaceOfRevolution::sphere_contact`] at any distance (see [`sphere_sphere_signed`]).
    pub fn sphere_contact_signed(
        &self,
        c1: impl AnyVector,
        r1: f64,
        pose: &Pose,
    ) -> Option<SurfaceContact> {
        let c1 = &c1.na();
        let local = to_na(pose.inverse_transform_point(to_glam(c1)));
        let (dist, normal, _) = self.nearest(&local);
        if dist == 0.0 {
            return None;
        }
        let overlap = r1 - dist;
        let normal = to_na(pose.rotation * to_glam(&normal));
        let p = c1 - normal * dist;
        Some(SurfaceContact {
            overlap,
            normal,
            point: p - normal * (0.5 * overlap),
        })
    }

    /// Whether the world point `x` is within `reach` of the surface on a collider at `pose`.
    pub fn within(&self, x: impl AnyVector, pose: &Pose, reach: f64) -> bool {
        let local = to_na(pose.inverse_transform_point(x.glam()));
        self.nearest(&local).0 < reach
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapier3d_f64::math::Vector;
    use rapier3d_f64::parry::query::PointQuery;
    use rapier3d_f64::parry::shape::{Cuboid, HalfSpace};

    /// The signed forms agree with the overlapping ones where both give a contact, and give
    /// minus the gap (the distance between the surfaces, computed here from the centres)
    /// where the bodies are apart.
    #[test]
    fn signed_contacts_give_minus_the_gap_when_apart() {
        let c = Vector3::new(0.3, -0.2, 2.5);
        let apart = sphere_sphere_signed(&c, 1.0, &Vector3::zeros(), 1.0).unwrap();
        assert!((apart.overlap - (2.0 - c.norm())).abs() < 1e-15);
        assert!((apart.normal - c / c.norm()).norm() < 1e-15);
        let close = Vector3::new(0.0, 0.0, 1.9);
        assert_eq!(
            sphere_sphere_signed(&close, 1.0, &Vector3::zeros(), 1.0),
            sphere_sphere(&close, 1.0, &Vector3::zeros(), 1.0)
        );
        let pose = Pose::from_translation(Vector::new(0.0, 0.0, -0.5));
        let floor = HalfSpace::new(Vector::Z);
        for z in [0.3, 0.6, 1.2] {
            let centre = Vector3::new(0.2, 0.1, z);
            let gap = z + 0.5 - 1.0;
            let plane = sphere_half_space_signed(&centre, 1.0, &Vector3::z(), &pose);
            let shape = sphere_shape_signed(&centre, 1.0, &floor, &pose).unwrap();
            for contact in [plane, shape] {
                assert!((contact.overlap + gap).abs() < 1e-14, "z = {z}");
                assert!((contact.normal - Vector3::z()).norm() < 1e-14);
            }
            if gap < 0.0 {
                let exact = sphere_half_space(&centre, 1.0, &Vector3::z(), &pose).unwrap();
                assert!((exact.overlap - plane.overlap).abs() < 1e-15);
            }
        }
        let corners: Vec<Vector> = (0..8)
            .map(|k| {
                let side = |bit: usize| if k & bit == 0 { -0.5 } else { 0.5 };
                Vector::new(side(1), side(2), side(4))
            })
            .collect();
        let hull =
            rapier3d_f64::parry::shape::ConvexPolyhedron::from_convex_hull(&corners).unwrap();
        let faces = ConvexFaces::of(&hull);
        let centre = Vector3::new(0.1, 0.0, 1.7);
        let convex = sphere_convex_signed(&centre, 1.0, &faces, &hull, &Pose::IDENTITY).unwrap();
        assert!((convex.overlap - (1.0 - 1.2)).abs() < 1e-14);
        let surface =
            SurfaceOfRevolution::new(Vector::ZERO, Vector::Z, vec![(2.0, -1.0), (2.0, 1.0)])
                .unwrap();
        let inside = Vector3::new(0.5, 0.0, 0.0);
        let wall = surface
            .sphere_contact_signed(&inside, 1.0, &Pose::IDENTITY)
            .unwrap();
        assert!((wall.overlap - (1.0 - 1.5)).abs() < 1e-14);
        assert!((wall.normal + Vector3::x()).norm() < 1e-14);
    }

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

    /// The closed-form half-space against parry's projection on a tilted, shifted plane: same
    /// overlap, normal and point to round-off, the same spheres apart, and the distance that
    /// rebuilds use.
    #[test]
    fn closed_form_half_space_matches_parry_on_a_tilted_plane() {
        use rand::SeedableRng;
        let normal = Vector3::new(0.3, 0.8, -0.2).normalize();
        let plane = HalfSpace::new(to_glam(&Vector3::new(0.3, 0.8, -0.2).normalize()));
        let pose = Pose::from_parts(
            Vector::new(0.1, -0.2, 0.05),
            rapier3d_f64::math::Rotation::from_scaled_axis(Vector::new(0.4, -0.3, 0.7)),
        );
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let (mut touching, mut apart) = (0, 0);
        let mut largest: f64 = 0.0;
        for _ in 0..2000 {
            let (c, r) = random_sphere(&mut rng);
            let exact = sphere_half_space(&c, r, &normal, &pose);
            let parry = sphere_shape(&c, r, &plane, &pose);
            match (exact, parry) {
                (Some(a), Some(b)) => {
                    touching += 1;
                    // parry's normal is the centre minus its projection over their distance,
                    // which loses digits as the centre nears the plane; the closed form's does
                    // not. Its error is compared in proportion.
                    let distance_from_plane = (r - b.overlap).abs();
                    largest = largest
                        .max((a.overlap - b.overlap).abs())
                        .max((a.normal - b.normal).norm() * distance_from_plane)
                        .max((a.point - b.point).norm());
                }
                (None, None) => apart += 1,
                (a, b) => panic!("disagree at {c:?}, r {r}: {a:?} against {b:?}"),
            }
            let distance = plane.distance_to_point(&pose, to_glam(&c), false);
            let signed = half_space_distance(&c, &normal, &pose);
            assert!((signed.max(0.0) - distance.max(0.0)).abs() < 1e-13);
        }
        assert!(
            touching > 200 && apart > 200,
            "{touching} touching, {apart} apart"
        );
        // Measured 2.6e-14 (parry projects in the plane's frame and transforms back).
        assert!(largest < 1e-13, "largest difference {largest:e}");
    }

    /// A sphere of radius 0.05–0.4 centred in the cube of side 2.4 around the origin.
    fn random_sphere(rng: &mut rand_chacha::ChaCha8Rng) -> (Vector3<f64>, f64) {
        use rand::Rng;
        let c = Vector3::new(
            rng.random_range(-1.2..1.2),
            rng.random_range(-1.2..1.2),
            rng.random_range(-1.2..1.2),
        );
        (c, rng.random_range(0.05..0.4))
    }

    /// A hull of a box's corners against parry's closed-form box projection (exact both).
    #[test]
    fn convex_faces_of_a_box_match_the_cuboid_projection() {
        use rand::SeedableRng;
        let half = Vector::new(0.3, 0.5, 0.2);
        let corners: Vec<Vector> = (0..8)
            .map(|k| {
                Vector::new(
                    if k & 1 == 0 { -half.x } else { half.x },
                    if k & 2 == 0 { -half.y } else { half.y },
                    if k & 4 == 0 { -half.z } else { half.z },
                )
            })
            .collect();
        let hull =
            rapier3d_f64::parry::shape::ConvexPolyhedron::from_convex_hull(&corners).unwrap();
        let faces = ConvexFaces::of(&hull);
        assert_eq!(
            faces.len(),
            6,
            "the hull's coplanar triangles merge into the box's faces"
        );
        let cube = Cuboid::new(half);
        let pose = Pose::from_translation(Vector::new(0.1, -0.2, 0.3))
            * Pose::rotation(Vector::new(0.3, -0.4, 0.5));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut touching, mut worst) = (0, 0.0f64);
        for _ in 0..20_000 {
            let (c, r) = random_sphere(&mut rng);
            let exact = sphere_shape(&c, r, &cube, &pose);
            let fast = sphere_convex(&c, r, &faces, &hull, &pose);
            match (exact, fast) {
                (Some(a), Some(b)) => {
                    touching += 1;
                    worst = worst
                        .max((a.overlap - b.overlap).abs())
                        .max((a.normal - b.normal).norm())
                        .max((a.point - b.point).norm());
                }
                (None, None) => {}
                (a, b) => panic!("centre {c:?}, radius {r}: box {a:?}, faces {b:?}"),
            }
        }
        assert!(touching > 1_000, "{touching} touching samples");
        eprintln!("box: {touching} contacts, largest difference {worst:e}");
        assert!(worst < 5e-12, "largest difference {worst:e}");
    }

    /// An irregular hull (a wall piece of a cone) against parry's GJK projection, which
    /// converges to a tolerance: the same contacts to within it (measured: 8e-15 m on a unit-sized
    /// hull; the box against its closed form: 8e-13).
    #[test]
    fn convex_faces_match_parry_on_an_irregular_hull() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let points: Vec<Vector> = (0..14)
            .map(|_| {
                Vector::new(
                    rng.random_range(-0.6..0.6),
                    rng.random_range(-0.3..0.3),
                    rng.random_range(-0.4..0.4),
                )
            })
            .collect();
        let hull = rapier3d_f64::parry::shape::ConvexPolyhedron::from_convex_hull(&points).unwrap();
        let faces = ConvexFaces::of(&hull);
        let pose = Pose::from_translation(Vector::new(-0.3, 0.2, 0.1))
            * Pose::rotation(Vector::new(-0.2, 0.7, 0.1));
        let (mut touching, mut worst) = (0, 0.0f64);
        for _ in 0..20_000 {
            let (c, r) = random_sphere(&mut rng);
            let gjk = sphere_shape(&c, r, &hull, &pose);
            let fast = sphere_convex(&c, r, &faces, &hull, &pose);
            match (gjk, fast) {
                (Some(a), Some(b)) => {
                    touching += 1;
                    worst = worst
                        .max((a.overlap - b.overlap).abs())
                        .max((a.point - b.point).norm());
                }
                (None, None) => {}
                // Grazing contacts may fall either side of the GJK tolerance.
                (Some(a), None) | (None, Some(a)) => {
                    assert!(a.overlap < 1e-9, "centre {c:?}, radius {r}: {a:?}")
                }
            }
            // The rebuild's candidate test: within reach exactly when parry says so.
            let reach = r + 0.01;
            let d = hull.distance_to_point(&pose, to_glam(&c), true);
            let within = convex_distance_within(&c, &faces, &pose, reach);
            if (d - reach).abs() > 1e-9 {
                assert_eq!(within.is_some(), d < reach, "centre {c:?}: parry {d}");
            }
            if let Some(w) = within {
                assert!((w - d).abs() < 1e-9, "centre {c:?}: parry {d}, faces {w}");
            }
        }
        assert!(touching > 500, "{touching} touching samples");
        eprintln!("irregular hull: {touching} contacts, largest difference {worst:e}");
        assert!(worst < 1e-13, "largest difference {worst:e}");
    }

    /// Nearest distance to the surface of revolution by brute force over its points (an
    /// independent reference for the meridional-plane closed form).
    fn sampled_distance(surface: &SurfaceOfRevolution, x: &Vector3<f64>) -> f64 {
        let axis = surface.axis;
        let t = if axis.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let e1 = (t - axis * t.dot(&axis)).normalize();
        let e2 = axis.cross(&e1);
        let mut best = f64::INFINITY;
        for w in surface.profile.windows(2) {
            for k in 0..=400 {
                let s = k as f64 / 400.0;
                let (r, a) = (
                    w[0].0 + s * (w[1].0 - w[0].0),
                    w[0].1 + s * (w[1].1 - w[0].1),
                );
                for m in 0..1440 {
                    let phi = std::f64::consts::TAU * m as f64 / 1440.0;
                    let p = surface.origin + (e1 * phi.cos() + e2 * phi.sin()) * r + axis * a;
                    best = best.min((x - p).norm());
                }
            }
        }
        best
    }

    #[test]
    fn surface_of_revolution_distance_matches_sampling() {
        // A funnel: cone from radius 2 at a = 0 to 20 at a = 40, tilted axis, off origin.
        let cone = SurfaceOfRevolution::new(
            &Vector3::new(1.0, -2.0, 0.5),
            &Vector3::new(0.2, 0.1, 1.0),
            vec![(2.0, 0.0), (20.0, 40.0)],
        )
        .unwrap();
        let capped = SurfaceOfRevolution::new(
            &Vector3::zeros(),
            &Vector3::z(),
            vec![(0.0, -1.0), (3.0, -1.0), (3.0, 1.0), (0.0, 1.0)],
        )
        .unwrap();
        let points = [
            Vector3::new(4.0, 3.0, 12.0),
            Vector3::new(-1.0, 0.5, -3.0),
            Vector3::new(12.0, -9.0, 41.0),
            Vector3::new(1.3, -1.6, 20.0),
        ];
        for x in points {
            let (d, n, q) = cone.nearest(&x);
            let reference = sampled_distance(&cone, &x);
            // Sampling resolution: 40 m / 400 along, 2π 20 m / 1440 around.
            assert!((d - reference).abs() < 0.1, "{x:?}: {d} vs {reference}");
            assert!(
                d <= reference + 1e-9,
                "{x:?}: the closed form is the minimum"
            );
            assert!((q + n * d - x).norm() < 1e-9);
        }
        for x in [
            Vector3::new(1.0, 2.0, 0.7),
            Vector3::new(3.5, 0.0, 1.4),
            Vector3::new(0.0, 0.0, 0.2),
        ] {
            let d = capped.nearest(&x).0;
            let reference = sampled_distance(&capped, &x);
            assert!((d - reference).abs() < 0.02, "{x:?}: {d} vs {reference}");
        }
    }

    #[test]
    fn sphere_inside_an_exact_cylinder_touches_at_its_radius_in_every_direction() {
        // Inner radius 2, open ends at z = ±5; a sphere of radius 0.5 whose centre is 1.6 from
        // the axis overlaps by 0.1 whatever its azimuth (no facets), with the normal pointing to
        // the axis; above the rim (z = 5.3) it touches the rim circle.
        let cylinder = SurfaceOfRevolution::new(
            &Vector3::zeros(),
            &Vector3::z(),
            vec![(2.0, -5.0), (2.0, 5.0)],
        )
        .unwrap();
        let pose = Pose::from_translation(Vector::new(10.0, 0.0, 0.0));
        for k in 0..7 {
            let phi = 0.37 * k as f64;
            let radial = Vector3::new(phi.cos(), phi.sin(), 0.0);
            let c = Vector3::new(10.0, 0.0, 0.0) + radial * 1.6 + Vector3::new(0.0, 0.0, 0.3);
            let contact = cylinder.sphere_contact(&c, 0.5, &pose).unwrap();
            assert!((contact.overlap - 0.1).abs() < 1e-12, "{}", contact.overlap);
            assert!((contact.normal + radial).norm() < 1e-12);
            assert!((contact.point - (c + radial * 0.45)).norm() < 1e-12);
        }
        let c = Vector3::new(10.0 + 1.8, 0.0, 5.3);
        let contact = cylinder.sphere_contact(&c, 0.5, &pose).unwrap();
        let expected = 0.5 - (0.2f64.powi(2) + 0.3f64.powi(2)).sqrt();
        assert!((contact.overlap - expected).abs() < 1e-12);
        assert!(cylinder.within(&c, &pose, 0.37) && !cylinder.within(&c, &pose, 0.36));
        assert!(cylinder
            .sphere_contact(&Vector3::new(10.0, 0.0, 0.0), 0.5, &pose)
            .is_none());
    }

    #[test]
    fn surface_of_revolution_rejects_bad_input() {
        let ok = vec![(1.0, 0.0), (1.0, 1.0)];
        assert!(
            SurfaceOfRevolution::new(&Vector3::zeros(), &Vector3::zeros(), ok.clone()).is_err()
        );
        assert!(
            SurfaceOfRevolution::new(&Vector3::zeros(), &Vector3::z(), vec![(1.0, 0.0)]).is_err()
        );
        assert!(SurfaceOfRevolution::new(
            &Vector3::zeros(),
            &Vector3::z(),
            vec![(-1.0, 0.0), (1.0, 1.0)]
        )
        .is_err());
        assert!(SurfaceOfRevolution::new(
            &Vector3::zeros(),
            &Vector3::z(),
            vec![(f64::NAN, 0.0), (1.0, 1.0)]
        )
        .is_err());
        assert!(SurfaceOfRevolution::new(&Vector3::zeros(), &Vector3::z(), ok).is_ok());
    }
}
