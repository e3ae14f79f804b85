//! Walls and containers as solid convex pieces (half-spaces, cuboids, convex prisms) or a triangle
//! mesh read from STL/OBJ, in the coordinates of the body they are attached to.
//!
//! Containers are built from solid pieces rather than from an open surface mesh so that the
//! side a particle is on is never ambiguous: the plugin measures the overlap with a point
//! projection, which needs a closed shape to tell inside from outside.

use nalgebra::{Point3, Vector3};
use std::f64::consts::PI;
use std::path::Path;

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
    /// A triangle mesh (faces' normals point to the particles' side).
    TriMesh {
        /// Vertices.
        vertices: Vec<Vector3<f64>>,
        /// Triangles.
        indices: Vec<[u32; 3]>,
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

/// Read a triangle mesh from an STL (binary or ASCII) or OBJ file, scale it and move it.
pub fn read_mesh(path: &Path, scale: f64, offset: Vector3<f64>) -> Result<WallPiece, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (vertices, indices): (Vec<Vector3<f64>>, Vec<[u32; 3]>) = match ext.as_deref() {
        Some("stl") => {
            let mut file = std::fs::File::open(path)
                .map_err(|e| format!("cannot open {}: {e}", path.display()))?;
            let mesh = stl_io::read_stl(&mut file)
                .map_err(|e| format!("cannot read STL {}: {e}", path.display()))?;
            let vertices = mesh
                .vertices
                .iter()
                .map(|v| Vector3::new(v[0] as f64, v[1] as f64, v[2] as f64))
                .collect();
            let indices = mesh
                .faces
                .iter()
                .map(|f| {
                    [
                        f.vertices[0] as u32,
                        f.vertices[1] as u32,
                        f.vertices[2] as u32,
                    ]
                })
                .collect();
            (vertices, indices)
        }
        Some("obj") => {
            let (models, _) = tobj::load_obj(
                path,
                &tobj::LoadOptions {
                    triangulate: true,
                    single_index: true,
                    ..Default::default()
                },
            )
            .map_err(|e| format!("cannot read OBJ {}: {e}", path.display()))?;
            let mut vertices = Vec::new();
            let mut indices = Vec::new();
            for m in models {
                let base = vertices.len() as u32;
                for p in m.mesh.positions.chunks_exact(3) {
                    vertices.push(Vector3::new(p[0] as f64, p[1] as f64, p[2] as f64));
                }
                for t in m.mesh.indices.chunks_exact(3) {
                    indices.push([base + t[0], base + t[1], base + t[2]]);
                }
            }
            (vertices, indices)
        }
        _ => {
            return Err(format!(
                "{}: unknown mesh format (allowed: .stl, .obj)",
                path.display()
            ))
        }
    };
    if indices.is_empty() {
        return Err(format!("{}: the mesh has no triangles", path.display()));
    }
    let n = vertices.len() as u32;
    if indices.iter().flatten().any(|&i| i >= n) {
        return Err(format!(
            "{}: a triangle refers to a missing vertex",
            path.display()
        ));
    }
    let vertices: Vec<_> = vertices.into_iter().map(|v| v * scale + offset).collect();
    if vertices.iter().any(|v| !v.iter().all(|c| c.is_finite())) {
        return Err(format!(
            "{}: a vertex is not a finite number",
            path.display()
        ));
    }
    Ok(WallPiece::TriMesh { vertices, indices })
}

impl WallPiece {
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
