//! Spheres leaving the scene (the sink and its parking lattice) and walls leaving it (removed
//! plugs).

use super::Wall;
use nalgebra::Vector3;

/// Spheres leaving the scene: a sphere whose centre falls below `height` (measured along `up`,
/// the direction against gravity) is removed from the run, as LAMMPS removes atoms that leave a
/// fixed boundary. The neighbour-list path keeps its particle arrays fixed in size, so a removed sphere is
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

    /// How far (m) a sphere moved onto its spot for [`Parking::jumped`]: a quarter of the
    /// largest radius.
    pub fn jump_distance(&self) -> f64 {
        0.25 * self.r_max
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
                parking.jumped |= (*x - spot).norm_squared() > self.jump_distance().powi(2);
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
                    parking.jumped |= (x - spot).norm_squared() > self.jump_distance().powi(2);
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

/// How far a removed wall is moved (m), against `up`: far below anything of the scene, so that no
/// sphere can reach it again (a removed half-space still bounds the space below it).
pub const REMOVED_WALL_DROP_M: f64 = 1.0e6;

/// Remove every wall due at `time` (s) that is still in place: its body is moved
/// [`REMOVED_WALL_DROP_M`] against `up` (a plane wall: against its own outward normal) and its
/// colliders follow at once. Idempotent (a wall
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
        // A lone half-space is moved along its own normal: moved along `up`, a side wall
        // (normal across `up`) would stay where it is and go on acting.
        let away = match wall.pieces.as_slice() {
            [super::WallPiece::HalfSpace { normal, .. }] => *normal,
            _ => *up,
        };
        let target = wall.origin - away * REMOVED_WALL_DROP_M;
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

#[cfg(test)]
mod tests {
    use super::*;

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
