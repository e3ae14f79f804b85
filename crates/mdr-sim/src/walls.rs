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

/// Spheres leaving the scene: a sphere whose centre falls below `height` (measured along `up`,
/// the direction against gravity) is removed from the run, as LAMMPS removes atoms that leave a
/// fixed boundary. The fast path keeps its particle arrays fixed in size, so a removed sphere is
/// parked instead: held at rest at its own spot of a simple cubic lattice below the height,
/// `4 r_max` under it and with spacing `2.5 r_max`, so that it touches nothing (parked spheres are
/// farther apart than the neighbour cut-off `2 r_max + skin` for any skin below `r_max / 2`, and
/// live spheres, whose centres are above `height`, are farther than `4 r_max` away). The lattice
/// is a compact block under the particles' initial centroid, so it enlarges the neighbour grid's
/// bounding box only a little. A sphere counts as removed while its centre is below `height`.
#[derive(Debug, Clone, PartialEq)]
pub struct Sink {
    /// Height (m) along `up` below which a sphere is removed.
    pub height: f64,
    /// Unit vector against gravity.
    pub up: Vector3<f64>,
    /// Magnitude of gravity (m/s²), for the gravitational energy a parked sphere gives up.
    pub gravity: f64,
    spots: Vec<Vector3<f64>>,
    r_max: f64,
}

/// What one [`Sink::apply`] did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Parking {
    /// A sphere was moved by more than a quarter radius (a newly removed one: the neighbour
    /// lists need a rebuild).
    pub jumped: bool,
    /// Kinetic and gravitational energy the parked spheres lost (J): what they take out of the
    /// run.
    pub energy: f64,
}

impl Sink {
    /// A sink at `height` along `up` (unit) under gravity of magnitude `gravity`, for spheres
    /// with the given initial centres and radii.
    pub fn new(
        height: f64,
        up: Vector3<f64>,
        gravity: f64,
        centres: &[Vector3<f64>],
        radii: &[f64],
    ) -> Self {
        let n = centres.len();
        let r_max = radii.iter().copied().fold(0.0, f64::max);
        let spacing = 2.5 * r_max;
        let side = (n as f64).cbrt().ceil().max(1.0) as usize;
        // Horizontal frame (e1, e2) perpendicular to `up`.
        let e1 = if up.x.abs() < 0.9 {
            up.cross(&Vector3::x()).normalize()
        } else {
            up.cross(&Vector3::y()).normalize()
        };
        let e2 = up.cross(&e1);
        let centroid = centres.iter().sum::<Vector3<f64>>() / n.max(1) as f64;
        let horizontal = centroid - up * centroid.dot(&up);
        let half = 0.5 * (side as f64 - 1.0);
        let spots = (0..n)
            .map(|i| {
                let (ix, iy, iz) = (i % side, (i / side) % side, i / (side * side));
                horizontal
                    + e1 * (spacing * (ix as f64 - half))
                    + e2 * (spacing * (iy as f64 - half))
                    + up * (height - 4.0 * r_max - spacing * iz as f64)
            })
            .collect();
        Self {
            height,
            up,
            gravity,
            spots,
            r_max,
        }
    }

    /// Whether a sphere centred at `p` has been removed.
    pub fn is_removed(&self, p: &Vector3<f64>) -> bool {
        p.dot(&self.up) < self.height
    }

    /// The parking spot of sphere `i`.
    pub fn spot(&self, i: usize) -> Vector3<f64> {
        self.spots[i]
    }

    /// Hold every sphere below the height at rest on its spot; `inertia(i)` gives sphere `i`'s
    /// mass and moment of inertia.
    pub fn apply(
        &self,
        position: &mut [Vector3<f64>],
        linvel: &mut [Vector3<f64>],
        angvel: &mut [Vector3<f64>],
        inertia: impl Fn(usize) -> (f64, f64),
    ) -> Parking {
        let mut parking = Parking::default();
        for (i, ((x, v), w)) in position
            .iter_mut()
            .zip(linvel.iter_mut())
            .zip(angvel.iter_mut())
            .enumerate()
        {
            if x.dot(&self.up) < self.height {
                let (m, moment) = inertia(i);
                parking.energy += self.lost_energy(i, m, moment, x, v, w);
                let spot = self.spots[i];
                parking.jumped |= (*x - spot).norm_squared() > (0.25 * self.r_max).powi(2);
                *x = spot;
                *v = Vector3::zeros();
                *w = Vector3::zeros();
            }
        }
        parking
    }

    /// [`Sink::apply`] on particles held as rapier bodies (`handles[i]` is sphere `i`, of radius
    /// `radii[i]`).
    pub fn apply_to_bodies(
        &self,
        bodies: &mut rapier3d_f64::prelude::RigidBodySet,
        handles: &[rapier3d_f64::prelude::RigidBodyHandle],
        radii: impl Fn(usize) -> f64,
    ) -> Parking {
        use mdr_rapier::convert::{to_glam, to_na};
        let mut parking = Parking::default();
        for (i, h) in handles.iter().enumerate() {
            let Some(body) = bodies.get_mut(*h) else {
                continue;
            };
            let x = to_na(body.translation());
            if x.dot(&self.up) < self.height {
                let (m, r) = (body.mass(), radii(i));
                let (v, w) = (to_na(body.linvel()), to_na(body.angvel()));
                parking.energy += self.lost_energy(i, m, 0.4 * m * r * r, &x, &v, &w);
                let spot = self.spots[i];
                if x != spot {
                    parking.jumped |= (x - spot).norm_squared() > (0.25 * self.r_max).powi(2);
                    body.set_translation(to_glam(&spot), true);
                }
                body.set_linvel(to_glam(&Vector3::zeros()), true);
                body.set_angvel(to_glam(&Vector3::zeros()), true);
            }
        }
        parking
    }

    /// Kinetic energy plus the gravitational energy above its spot of sphere `i` (mass `m`,
    /// moment of inertia `moment`) at `x` moving with `v`, `w`: what parking it takes away.
    fn lost_energy(
        &self,
        i: usize,
        m: f64,
        moment: f64,
        x: &Vector3<f64>,
        v: &Vector3<f64>,
        w: &Vector3<f64>,
    ) -> f64 {
        0.5 * m * v.norm_squared()
            + 0.5 * moment * w.norm_squared()
            + m * self.gravity * self.up.dot(&(x - self.spots[i]))
    }

    /// Number of removed spheres among `position`.
    pub fn removed(&self, position: &[Vector3<f64>]) -> usize {
        position.iter().filter(|p| self.is_removed(p)).count()
    }
}

/// The scene's sink (`[run] delete_below_m`), if it has one.
pub fn scene_sink(scene: &crate::scene::Scene) -> Option<Sink> {
    let height = scene.source.run.delete_below_m?;
    let g = scene.gravity.norm();
    let up = if g > 0.0 {
        -scene.gravity / g
    } else {
        Vector3::z()
    };
    let centres: Vec<_> = scene.particles.iter().map(|p| p.position).collect();
    let radii: Vec<_> = scene.particles.iter().map(|p| p.radius).collect();
    Some(Sink::new(height, up, g, &centres, &radii))
}

/// How far a removed wall is moved (m), against `up`: far below anything of the scene, so that no
/// sphere can reach it again (a removed half-space still bounds the space below it).
pub const REMOVED_WALL_DROP_M: f64 = 1.0e6;

/// Remove every wall due at `time` (s) that is still in place: its body is moved
/// [`REMOVED_WALL_DROP_M`] against `up` and its colliders follow at once. Idempotent (a wall
/// already moved stays where it is), so a run resumed from a checkpoint removes it again at its
/// first step. Returns whether a wall was removed now.
pub fn remove_due_walls(
    walls: &[Wall],
    time: f64,
    up: &Vector3<f64>,
    world: &mut rapier3d_f64::prelude::PhysicsWorld,
    wall_bodies: &[rapier3d_f64::prelude::RigidBodyHandle],
) -> bool {
    let mut removed = false;
    for (wall, handle) in walls.iter().zip(wall_bodies) {
        let Some(at) = wall.removed_at else { continue };
        if time < at {
            continue;
        }
        let target = wall.origin - up * REMOVED_WALL_DROP_M;
        let Some(body) = world.bodies.get_mut(*handle) else {
            continue;
        };
        let now = mdr_rapier::convert::to_na(body.translation());
        if (now - target).norm() > 1.0 {
            body.set_translation(mdr_rapier::convert::to_glam(&target), true);
            removed = true;
        }
    }
    if removed {
        world
            .bodies
            .propagate_modified_body_positions_to_colliders(&mut world.colliders);
    }
    removed
}

/// Read a triangle mesh from an STL (binary or ASCII) or OBJ file, scale it and move it.
pub fn read_mesh(path: &Path, scale: f64, offset: Vector3<f64>) -> Result<WallPiece, String> {
    read_mesh_with_notes(path, scale, offset).map(|(piece, _)| piece)
}

/// [`read_mesh`], with what the user should know about the mesh: STL facet normals that point
/// against the winding (the winding decides), and whether the mesh is a closed solid or an open,
/// two-sided sheet. A closed mesh wound inconsistently is refused ([`crate::mesh::topology`]).
pub fn read_mesh_with_notes(
    path: &Path,
    scale: f64,
    offset: Vector3<f64>,
) -> Result<(WallPiece, Vec<String>), String> {
    if std::fs::metadata(path).is_ok_and(|m| m.len() == 0) {
        return Err(format!("{}: the file is empty (0 bytes)", path.display()));
    }
    let mut stored_normals = Vec::new();
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
            stored_normals = mesh
                .faces
                .iter()
                .map(|f| Vector3::new(f.normal[0] as f64, f.normal[1] as f64, f.normal[2] as f64))
                .collect();
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
    let topology = crate::mesh::topology(&vertices, &indices)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut notes = Vec::new();
    // A negative scale mirrors the mesh and turns its winding round with it.
    if let Some((count, first)) = crate::mesh::facet_normal_disagreements(
        &vertices,
        &indices,
        &stored_normals
            .iter()
            .map(|n| n * scale.signum())
            .collect::<Vec<_>>(),
    ) {
        notes.push(format!(
            "{}: {count} of {} facet normals (the first: facet {first}) point against their \
             triangle's winding; the winding decides (the normal of corners a, b, c is \
             (b − a) × (c − a)){}",
            path.display(),
            indices.len(),
            if topology.closed {
                ", and this closed mesh's particle side is the side its windings' normals point to"
            } else {
                "; this open mesh is two-sided, so neither changes the contacts"
            }
        ));
    }
    Ok((
        WallPiece::TriMesh {
            vertices,
            indices,
            closed: topology.closed,
        },
        notes,
    ))
}

/// The collision shape of a mesh: a closed mesh is oriented (parry's pseudo-normals tell its
/// inside from its outside, the outside being the side its faces' normals point to); an open
/// one is not, so a point's projection is never inside it and a sphere is pushed away from the
/// face its centre is in front of (two-sided).
pub fn trimesh_shape(
    vertices: &[Vector3<f64>],
    indices: &[[u32; 3]],
    closed: bool,
) -> Result<rapier3d_f64::prelude::SharedShape, String> {
    use rapier3d_f64::parry::shape::TriMeshFlags;
    let flags = if closed {
        TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES
    } else {
        TriMeshFlags::MERGE_DUPLICATE_VERTICES
    };
    rapier3d_f64::prelude::SharedShape::trimesh_with_flags(
        vertices.iter().map(mdr_rapier::convert::to_glam).collect(),
        indices.to_vec(),
        flags,
    )
    .map_err(|e| format!("triangle mesh: {e}"))
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

    /// Spheres below the sink are held at rest on distinct spots far enough apart that they do
    /// not touch, and farther than `4 r_max` below the sink height; spheres above are untouched.
    #[test]
    fn sink_parks_removed_spheres_apart_and_below() {
        let n = 30;
        let centres: Vec<_> = (0..n)
            .map(|i| Vector3::new(i as f64 * 0.01, 0.0, 1.0))
            .collect();
        let radii = vec![0.004; n];
        let sink = Sink::new(-0.5, Vector3::z(), 9.81, &centres, &radii);
        let mut x = centres.clone();
        let mut v = vec![Vector3::new(0.0, 0.0, -3.0); n];
        let mut w = vec![Vector3::new(1.0, 0.0, 0.0); n];
        for xi in x.iter_mut().take(10) {
            xi.z = -0.6;
        }
        let (m, moment) = (2.0, 0.4 * 2.0 * 0.004 * 0.004);
        let parking = sink.apply(&mut x, &mut v, &mut w, |_| (m, moment));
        assert!(parking.jumped, "ten spheres jumped to their spots");
        // Each took its kinetic energy and its fall from z = −0.6 to its spot with it.
        let expected: f64 = (0..10)
            .map(|i| 0.5 * m * 9.0 + 0.5 * moment + m * 9.81 * (-0.6 - sink.spot(i).z))
            .sum();
        assert!(
            (parking.energy - expected).abs() < 1e-12 * expected,
            "{parking:?}"
        );
        assert_eq!(sink.removed(&x), 10);
        for i in 0..10 {
            assert_eq!(x[i], sink.spot(i));
            assert!(x[i].z <= -0.5 - 4.0 * 0.004 + 1e-12);
            assert_eq!((v[i], w[i]), (Vector3::zeros(), Vector3::zeros()));
            for j in 0..i {
                assert!((x[i] - x[j]).norm() >= 2.5 * 0.004 - 1e-12);
            }
        }
        for i in 10..n {
            assert_eq!(x[i], centres[i]);
            assert_eq!(v[i].z, -3.0);
        }
        // Held again after a small drift: no jump, back on the spot.
        x[3].z -= 1e-6;
        assert!(!sink.apply(&mut x, &mut v, &mut w, |_| (m, moment)).jumped);
        assert_eq!(x[3], sink.spot(3));
    }
}
