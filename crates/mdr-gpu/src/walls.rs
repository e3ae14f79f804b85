//! The walls of a system on the device ([`DeviceWall`]): half-spaces (a plane wall), a box's
//! slabs (axis-aligned cuboids) and exact surfaces of revolution (a cylinder with its end
//! discs, a cone, an orifice plate's faces and rim), fixed or turning about their own axis, each
//! acting until the step its `[[walls]]` entry is removed at. How a scene's walls become device
//! walls ([`scene_walls`]) or are refused with the part named ([`wall_support`]), and the
//! constants of `bed.wgsl` they are written into ([`wall_constants`]).
//!
//! A box's slab touches a sphere as the CPU neighbour-list path's cuboid collider does
//! (`mdr_rapier::geometry::sphere_shape_signed` with parry's projection of the centre on the
//! cuboid): `cuboid_contact` of `bed.wgsl` is that projection and contact written in the same
//! order, inside and outside the slab, on its faces, edges and corners; each slab is one
//! device wall with its own history slot, as each is one surface of the CPU path.
//!
//! A surface of revolution touches a sphere as the CPU neighbour-list path's
//! `mdr_rapier::geometry::SurfaceOfRevolution` does (its doc derives the closed form: the
//! nearest point lies in the meridional half-plane through the centre, so the distance is the
//! planar distance from `(ρ, a)` to the profile polyline); `revolution_contact` of `bed.wgsl`
//! is `SurfaceOfRevolution::nearest` and `sphere_contact_signed` written in the same order.
//! A wall turning at `ω` moves at `ω × (x − c)` at the contact point `x` (`c` on the axis), the
//! velocity the CPU path reads from the wall's kinematic body; a surface of revolution turning
//! about its own axis keeps its shape and place, so the device keeps its geometry fixed.

use crate::device::GpuError;
use mdr_rapier::convert::to_glam;
use mdr_rapier::geometry::{sphere_shape_signed, SurfaceOfRevolution};
use mdr_sim::scene::schema::WallKind;
use mdr_sim::walls::{Revolution, Wall, WallPiece, REMOVED_WALL_DROP_M};
use mdr_sim::Scene;
use nalgebra::Vector3;
use rapier3d_f64::math::Pose;
use rapier3d_f64::parry::shape::Cuboid;

/// A planar wall of a system: the half-space behind the plane through `point` with outward
/// (towards the spheres) unit `normal`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Plane {
    pub normal: Vector3<f64>,
    pub point: Vector3<f64>,
}

impl Plane {
    /// The half-space behind the plane through `point` with outward unit `normal`.
    pub fn infinite(normal: Vector3<f64>, point: Vector3<f64>) -> Self {
        Self { normal, point }
    }
}

/// An axis-aligned cuboid (a box's slab) as the CPU path's collider holds it: its pose's
/// translation `center` (world, m; the wall's origin plus the piece's centre) without rotation,
/// and its half extents (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Slab {
    pub center: Vector3<f64>,
    pub half_extents: Vector3<f64>,
}

/// An exact surface of revolution: the `(radius, axial position)` profile turned about the
/// unit `axis` through `origin + center` (m), as the CPU path's collider at pose `origin`
/// holds it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RevolutionWall {
    /// The wall body's origin (world).
    pub origin: Vector3<f64>,
    /// The axis point of axial position zero, relative to `origin`.
    pub center: Vector3<f64>,
    /// Unit axis.
    pub axis: Vector3<f64>,
    /// The CPU path's surface (the host's overlaps for the energy books).
    pub surface: SurfaceOfRevolution,
}

impl RevolutionWall {
    fn new(origin: Vector3<f64>, revolution: &Revolution) -> Result<Self, GpuError> {
        let surface = SurfaceOfRevolution::new(
            &revolution.center,
            &revolution.axis,
            revolution.profile.clone(),
        )
        .map_err(|e| GpuError::Unsupported(e.to_string()))?;
        Ok(Self {
            origin,
            center: revolution.center,
            axis: revolution.axis.normalize(),
            surface,
        })
    }

    /// The profile points `(radius, axial position)`.
    pub fn profile(&self) -> &[(f64, f64)] {
        self.surface.profile()
    }
}

/// The shape of a device wall.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum WallShape {
    /// A half-space.
    Plane(Plane),
    /// An axis-aligned cuboid: a box's slab.
    Slab(Slab),
    /// An exact surface of revolution.
    Revolution(RevolutionWall),
}

/// One wall of a system on the device, with a history slot per (particle, wall).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DeviceWall {
    /// The scene's `[[walls]]` index it belongs to.
    pub wall: usize,
    /// Its shape.
    pub shape: WallShape,
    /// Angular velocity (rad/s) about an axis through `pivot`; zero for a fixed wall.
    pub angular_velocity: Vector3<f64>,
    /// A point of the rotation axis (world, m).
    pub pivot: Vector3<f64>,
    /// The step from whose force pass on the wall acts no more (removed); `None`: never.
    pub removed_from_step: Option<u64>,
}

impl DeviceWall {
    /// A fixed plane that stays.
    pub fn fixed_plane(wall: usize, plane: Plane) -> Self {
        Self {
            wall,
            shape: WallShape::Plane(plane),
            angular_velocity: Vector3::zeros(),
            pivot: Vector3::zeros(),
            removed_from_step: None,
        }
    }

    /// The half-space that stands for the wall when the laws are bound (they depend on the
    /// materials, not on the shape): a plane's own, or, for a slab or a surface of revolution,
    /// one that no sphere reaches.
    pub fn law_stand_in(&self) -> Plane {
        match &self.shape {
            WallShape::Plane(plane) => *plane,
            WallShape::Slab(_) | WallShape::Revolution(_) => {
                Plane::infinite(Vector3::z(), Vector3::new(0.0, 0.0, -REMOVED_WALL_DROP_M))
            }
        }
    }

    /// The overlap of a sphere at `x` with radius `r`, negative while apart (the contact's
    /// signed overlap, as the force pass takes it); `None` where the contact has no normal (a
    /// centre on a slab's boundary or on a surface of revolution).
    pub fn signed_overlap(&self, x: &Vector3<f64>, r: f64) -> Option<f64> {
        match &self.shape {
            WallShape::Plane(plane) => Some(r - plane.normal.dot(&(x - plane.point))),
            WallShape::Slab(slab) => sphere_shape_signed(
                x,
                r,
                &Cuboid::new(to_glam(&slab.half_extents)),
                &Pose::from_translation(to_glam(&slab.center)),
            )
            .map(|c| c.overlap),
            WallShape::Revolution(rev) => rev
                .surface
                .sphere_contact_signed(x, r, &Pose::from_translation(to_glam(&rev.origin)))
                .map(|c| c.overlap),
        }
    }
}

/// The first step `k` whose time `k · dt` reaches `time`: the step at whose start the CPU run
/// removes a wall due at `time` (its scene events take `step · dt`).
pub(crate) fn removal_step(time: f64, dt: f64) -> u64 {
    let mut k = (time / dt).ceil().max(0.0) as u64;
    while k > 0 && (k - 1) as f64 * dt >= time {
        k -= 1;
    }
    while (k as f64) * dt < time {
        k += 1;
    }
    k
}

/// The steps at which walls are removed, distinct and ascending: the `s`-th (from 1) is the
/// removal stage `s`, and a wall of stage `s` acts no more once `s` stages are reached.
pub(crate) fn removal_steps(walls: &[DeviceWall]) -> Vec<u64> {
    let mut steps: Vec<u64> = walls.iter().filter_map(|w| w.removed_from_step).collect();
    steps.sort_unstable();
    steps.dedup();
    steps
}

/// The removal stages reached at the force pass of `step`: how many of `steps` (ascending) are
/// at or before it.
pub(crate) fn removal_stage(steps: &[u64], step: u64) -> u32 {
    steps.partition_point(|&s| s <= step) as u32
}

/// The scene file's name of a wall kind.
fn kind_name(kind: WallKind) -> &'static str {
    match kind {
        WallKind::Plane => "plane",
        WallKind::Box => "box",
        WallKind::Cylinder => "cylinder",
        WallKind::Mesh => "mesh",
        WallKind::OrificePlate => "orifice_plate",
        WallKind::Cone => "cone",
    }
}

/// Relative tolerance of "parallel" and "on the axis" for a turning surface of revolution.
const AXIS_TOLERANCE: f64 = 1e-9;

/// Whether the device has every wall of `scene`: `Ok`, or the first one it lacks with its
/// `[[walls]]` entry, kind and what is missing. Plane and box walls, and cylinders, cones and
/// orifice plates as exact surfaces (`exact_surface = true`); a turning wall only as a surface
/// of revolution about its own axis; any wall removed at a time.
pub(crate) fn wall_support(scene: &Scene) -> Result<(), String> {
    for wall in &scene.walls {
        let j = wall.index;
        let kind = scene.source.walls.get(j).map(|w| w.kind);
        let name = kind.map_or("unknown", kind_name);
        let entry = format!(
            "wall {j} (`[[walls]]` entry {}, `kind = \"{name}\"`)",
            j + 1
        );
        match kind {
            Some(WallKind::Plane | WallKind::Box) => {}
            Some(WallKind::Cylinder | WallKind::Cone | WallKind::OrificePlate) => {
                if wall.revolution.is_none() {
                    return Err(format!(
                        "{entry} is made of flat pieces (`exact_surface = false`), which have \
                         no GPU kernel: the GPU has its exact surface (`exact_surface = true`)"
                    ));
                }
            }
            _ => {
                return Err(format!(
                    "{entry} has no GPU kernel: the GPU has `plane`, `box`, and `cylinder`, \
                     `cone` and `orifice_plate` walls with `exact_surface = true`"
                ))
            }
        }
        if let Some(omega) = wall.angular_velocity {
            turning_support(wall, &omega)
                .map_err(|why| format!("{entry} turns (`angular_velocity_rad_per_s`) {why}"))?;
        }
    }
    Ok(())
}

/// Whether the device turns `wall` at `omega`: a surface of revolution turning about its own
/// axis keeps its shape and place; anything else moves.
fn turning_support(wall: &Wall, omega: &Vector3<f64>) -> Result<(), String> {
    let Some(rev) = &wall.revolution else {
        return Err(
            "and its faces move: the GPU turns surfaces of revolution about their own \
                    axis only"
                .into(),
        );
    };
    let axis = rev.axis.normalize();
    if omega.cross(&axis).norm() > AXIS_TOLERANCE * omega.norm() {
        return Err(format!(
            "about {omega:?}, not about its own axis {axis:?}: the GPU turns surfaces of \
             revolution about their own axis only"
        ));
    }
    // The rotation centre (the wall's origin, zero in its frame) off the surface's axis.
    let off = -rev.center - axis * axis.dot(&-rev.center);
    let size = rev
        .profile
        .iter()
        .map(|p| p.0.abs().max(p.1.abs()))
        .fold(rev.center.norm(), f64::max);
    if off.norm() > AXIS_TOLERANCE * size {
        return Err(format!(
            "about a centre (`rotation_center_m`) {:.3e} m off its own axis: the GPU turns \
             surfaces of revolution about their own axis only",
            off.norm()
        ));
    }
    Ok(())
}

/// The device walls of `scene` in the CPU path's surface order: per `[[walls]]` entry, its
/// exact surface of revolution (one surface), or each piece (a plane wall's half-space, each
/// of a box's slabs).
pub(crate) fn scene_walls(scene: &Scene) -> Result<Vec<DeviceWall>, GpuError> {
    let mut walls = Vec::new();
    for wall in &scene.walls {
        let angular_velocity = wall.angular_velocity.unwrap_or_else(Vector3::zeros);
        let removed_from_step = wall.removed_at.map(|t| removal_step(t, scene.dt));
        let device = |shape| DeviceWall {
            wall: wall.index,
            shape,
            angular_velocity,
            pivot: wall.origin,
            removed_from_step,
        };
        if let Some(rev) = &wall.revolution {
            walls.push(device(WallShape::Revolution(RevolutionWall::new(
                wall.origin,
                rev,
            )?)));
            continue;
        }
        for piece in &wall.pieces {
            walls.push(device(piece_shape(wall, piece)?));
        }
    }
    Ok(walls)
}

/// The shape of a wall piece: a half-space, or an axis-aligned slab at the pose the CPU path
/// gives its collider (the wall body's translation plus the piece's, no rotation).
fn piece_shape(wall: &Wall, piece: &WallPiece) -> Result<WallShape, GpuError> {
    match piece {
        WallPiece::HalfSpace { point, normal } => Ok(WallShape::Plane(Plane::infinite(
            normal.normalize(),
            wall.origin + point,
        ))),
        WallPiece::Cuboid {
            center,
            rotation,
            half_extents,
        } if *rotation == nalgebra::UnitQuaternion::identity() => Ok(WallShape::Slab(Slab {
            center: wall.origin + center,
            half_extents: *half_extents,
        })),
        _ => Err(GpuError::Unsupported(format!(
            "wall {} has a piece that is neither a half-space nor an axis-aligned slab",
            wall.index
        ))),
    }
}

/// `WALL_KIND` codes of `bed.wgsl`.
const KIND_PLANE: u32 = 0;
const KIND_REVOLUTION: u32 = 1;
const KIND_SLAB: u32 = 2;

/// WGSL constant list of `values` (one `empty` for none: the arrays of `bed.wgsl` have at least
/// one entry).
fn wgsl_list(values: Vec<String>, empty: &str) -> String {
    if values.is_empty() {
        empty.to_owned()
    } else {
        values.join(", ")
    }
}

/// A WGSL `vec3<f64>`. Rust's `{:?}` writes the shortest decimal that reads back as the same
/// double, so the device gets the exact values.
pub(crate) fn wgsl_vector(v: &Vector3<f64>) -> String {
    format!("vec3<f64>({:?}lf, {:?}lf, {:?}lf)", v.x, v.y, v.z)
}

/// The WGSL constants of `walls` (`__WALL_CONSTANTS__` of `bed.wgsl`), one entry per wall in
/// each array: the kind; a plane's normal and point (zero otherwise); the origin (a slab's
/// centre, a surface of revolution's collider pose; zero for a plane); a slab's half extents
/// (zero otherwise); a surface of revolution's centre, axis and profile range in `PROFILE`
/// (zero otherwise); the angular velocity and its pivot; the removal stage (`u32::MAX`: never
/// removed); and whether any wall is a slab (`ANY_SLAB`: without one the slab kernel is
/// compiled out).
pub(crate) fn wall_constants(walls: &[DeviceWall]) -> String {
    let slots = walls.len().max(1);
    let zero = Vector3::zeros();
    let steps = removal_steps(walls);
    let mut profile: Vec<String> = Vec::new();
    let (mut start, mut end) = (Vec::new(), Vec::new());
    let vectors = |f: &dyn Fn(&DeviceWall) -> Vector3<f64>| {
        wgsl_list(
            walls.iter().map(|w| wgsl_vector(&f(w))).collect(),
            "vec3<f64>(0.0lf, 0.0lf, 0.0lf)",
        )
    };
    let plane = |w: &DeviceWall, f: &dyn Fn(&Plane) -> Vector3<f64>| match &w.shape {
        WallShape::Plane(p) => f(p),
        _ => zero,
    };
    let slab = |w: &DeviceWall, f: &dyn Fn(&Slab) -> Vector3<f64>| match &w.shape {
        WallShape::Slab(b) => f(b),
        _ => zero,
    };
    let revolution = |w: &DeviceWall, f: &dyn Fn(&RevolutionWall) -> Vector3<f64>| match &w.shape {
        WallShape::Revolution(r) => f(r),
        _ => zero,
    };
    let origin = |w: &DeviceWall| match &w.shape {
        WallShape::Slab(b) => b.center,
        WallShape::Revolution(r) => r.origin,
        WallShape::Plane(_) => zero,
    };
    for w in walls {
        start.push(format!("{}u", profile.len()));
        if let WallShape::Revolution(r) = &w.shape {
            for &(radius, axial) in r.profile() {
                profile.push(format!("vec2<f64>({radius:?}lf, {axial:?}lf)"));
            }
        }
        end.push(format!("{}u", profile.len()));
    }
    let kinds = walls
        .iter()
        .map(|w| match w.shape {
            WallShape::Plane(_) => format!("{KIND_PLANE}u"),
            WallShape::Revolution(_) => format!("{KIND_REVOLUTION}u"),
            WallShape::Slab(_) => format!("{KIND_SLAB}u"),
        })
        .collect();
    let stages = walls
        .iter()
        .map(|w| {
            let stage = w
                .removed_from_step
                .map_or(u32::MAX, |s| removal_stage(&steps, s));
            format!("{stage}u")
        })
        .collect();
    let points = profile.len().max(1);
    let u32s = |v| wgsl_list(v, "0u");
    [
        format!("const WALL_KIND = array<u32, {slots}>({});", u32s(kinds)),
        format!(
            "const WALL_NORMAL = array<vec3<f64>, {slots}>({});",
            vectors(&|w| plane(w, &|p| p.normal))
        ),
        format!(
            "const WALL_POINT = array<vec3<f64>, {slots}>({});",
            vectors(&|w| plane(w, &|p| p.point))
        ),
        format!(
            "const WALL_ORIGIN = array<vec3<f64>, {slots}>({});",
            vectors(&origin)
        ),
        format!(
            "const WALL_HALF = array<vec3<f64>, {slots}>({});",
            vectors(&|w| slab(w, &|b| b.half_extents))
        ),
        format!(
            "const WALL_CENTER = array<vec3<f64>, {slots}>({});",
            vectors(&|w| revolution(w, &|r| r.center))
        ),
        format!(
            "const WALL_AXIS = array<vec3<f64>, {slots}>({});",
            vectors(&|w| revolution(w, &|r| r.axis))
        ),
        format!(
            "const WALL_PROFILE_START = array<u32, {slots}>({});",
            u32s(start)
        ),
        format!(
            "const WALL_PROFILE_END = array<u32, {slots}>({});",
            u32s(end)
        ),
        format!(
            "const PROFILE = array<vec2<f64>, {points}>({});",
            wgsl_list(profile, "vec2<f64>(0.0lf, 0.0lf)")
        ),
        format!(
            "const WALL_OMEGA = array<vec3<f64>, {slots}>({});",
            vectors(&|w| w.angular_velocity)
        ),
        format!(
            "const WALL_PIVOT = array<vec3<f64>, {slots}>({});",
            vectors(&|w| w.pivot)
        ),
        format!("const WALL_STAGE = array<u32, {slots}>({});", u32s(stages)),
        format!(
            "const ANY_SLAB: bool = {};",
            walls.iter().any(|w| matches!(w.shape, WallShape::Slab(_)))
        ),
    ]
    .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The removal step is the first whose time `k · dt` reaches the removal time, whatever the
    /// rounding of `time / dt`.
    #[test]
    fn the_removal_step_is_the_first_reaching_the_time() {
        for (time, dt) in [
            (0.0, 1e-5),
            (0.002, 2e-5),
            (0.1, 3e-5),
            (1e-3, 1e-4),
            (0.3, 0.1),
        ] {
            let k = removal_step(time, dt);
            assert!(k as f64 * dt >= time, "{time} {dt}: {k}");
            assert!(k == 0 || ((k - 1) as f64) * dt < time, "{time} {dt}: {k}");
        }
        assert_eq!(removal_step(0.0, 1e-5), 0);
        // 0.3 / 0.1 rounds to 2.9999999999999996: step 3 (3 · 0.1 = 0.30000000000000004).
        assert_eq!(removal_step(0.3, 0.1), 3);
    }

    /// Stages count the distinct removal steps at or before a step.
    #[test]
    fn removal_stages_count_the_steps_reached() {
        let steps = [5, 9];
        assert_eq!(removal_stage(&steps, 0), 0);
        assert_eq!(removal_stage(&steps, 4), 0);
        assert_eq!(removal_stage(&steps, 5), 1);
        assert_eq!(removal_stage(&steps, 8), 1);
        assert_eq!(removal_stage(&steps, 9), 2);
        assert_eq!(removal_stage(&[], 100), 0);
    }
}
