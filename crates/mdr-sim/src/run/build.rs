//! Building the rapier world of a scene: materials, wall bodies (fixed or kinematic) with their
//! solid pieces, then the spheres, in the scene's order, so the same scene always gets the same
//! handles (which the checkpoints rely on).
//!
//! Force mode runs on the neighbour-list path ([`NeighbourListScene`]) unless the scene selects
//! `force_path = "rapier"` ([`RapierPipelineScene`]); the scene's normal law picks the stepper
//! compiled for it by name ([`crate::laws::registry`]). On the neighbour-list path the walls are rapier colliders registered as its surfaces, the
//! spheres live in the stepper's own arrays (particle `i` of the scene is its particle `i`),
//! and rapier keeps and moves the wall bodies.

use super::coupling::{NeighbourListScene, RapierPipelineScene};
use crate::error::SimError;
use crate::laws::registry;
use crate::scene::{CouplingMode, ForcePath, Scene};
use crate::walls::WallPiece;
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic};
use mdr_contact::params::Declared;
use mdr_rapier::convert::to_glam;
use mdr_rapier::geometry::SurfaceOfRevolution;
use mdr_rapier::neighbour_list::Boundary;
use mdr_rapier::particles::{MaterialHandle, SphereBuilder};
use mdr_rapier::RestitutionHooks;
use rapier3d_f64::prelude::*;

/// The coupling of a built scene.
pub enum Coupling {
    /// Force mode on rapier's broad and narrow phase (`force_path = "rapier"`).
    RapierPipeline(Box<dyn RapierPipelineScene>),
    /// Force mode on the neighbour-list path (the default).
    NeighbourList(Box<dyn NeighbourListScene>),
    /// Restitution mode.
    Restitution(Box<RestitutionHooks>),
}

/// A built scene.
pub struct Built {
    /// The rapier world.
    pub world: PhysicsWorld,
    /// The coupling.
    pub coupling: Coupling,
    /// Body of particle `i` (empty on the neighbour-list path, whose particles are not rapier
    /// bodies).
    pub particle_bodies: Vec<RigidBodyHandle>,
    /// Collider of particle `i` (empty on the neighbour-list path).
    pub particle_colliders: Vec<ColliderHandle>,
    /// Body of wall `j`.
    pub wall_bodies: Vec<RigidBodyHandle>,
    /// Wall index of each wall collider, by collider arena index (`usize::MAX` when not a wall).
    pub wall_of_collider: Vec<usize>,
    /// Particle index of each particle collider, by collider arena index.
    pub particle_of_collider: Vec<usize>,
    /// Wall index of each surface of the neighbour-list path, in the stepper's surface order
    /// (empty on the other paths).
    pub wall_of_surface: Vec<usize>,
}

fn piece_collider(piece: &WallPiece) -> Result<ColliderBuilder, SimError> {
    Ok(match piece {
        WallPiece::HalfSpace { point, normal } => {
            ColliderBuilder::new(SharedShape::halfspace(to_glam(normal)))
                .translation(to_glam(point))
        }
        WallPiece::Cuboid {
            center,
            rotation,
            half_extents,
        } => {
            let q = rotation.quaternion();
            let rot = rapier3d_f64::math::Rotation::from_xyzw(q.i, q.j, q.k, q.w);
            ColliderBuilder::cuboid(half_extents.x, half_extents.y, half_extents.z)
                .position(Pose::from_parts(to_glam(center), rot))
        }
        WallPiece::ConvexHull { points } => {
            let pts: Vec<Vector> = points.iter().map(to_glam).collect();
            ColliderBuilder::convex_hull(&pts).ok_or_else(|| {
                SimError::Build("a wall piece's convex hull is degenerate".to_owned())
            })?
        }
        WallPiece::TriMesh {
            vertices,
            indices,
            closed,
        } => ColliderBuilder::new(
            crate::walls::trimesh_shape(vertices, indices, *closed).map_err(SimError::Build)?,
        ),
    })
}

/// Prediction distance (m): twice the largest relative displacement in one step, and at least a
/// tenth of the smallest radius.
fn prediction_distance(scene: &Scene) -> f64 {
    let r_min = scene
        .particles
        .iter()
        .map(|p| p.radius)
        .fold(f64::INFINITY, f64::min);
    (4.0 * scene.max_speed * scene.dt).max(0.1 * r_min)
}

/// Neighbour skin (m) of the neighbour-list path: `[run] neighbour_skin_m`, by default a tenth
/// of the mean diameter, the low end of LAMMPS's usual 0.1 d–0.3 d (the lists are rebuilt once
/// something moved half of it).
pub fn skin(scene: &Scene) -> f64 {
    scene.source.run.neighbour_skin_m.unwrap_or_else(|| {
        0.2 * scene.particles.iter().map(|p| p.radius).sum::<f64>() / scene.particles.len() as f64
    })
}

/// Build the world of `scene`.
pub fn build(scene: &Scene) -> Result<Built, SimError> {
    let mut world = PhysicsWorld {
        gravity: to_glam(&scene.gravity),
        ..PhysicsWorld::default()
    };
    let mean_diameter =
        2.0 * scene.particles.iter().map(|p| p.radius).sum::<f64>() / scene.particles.len() as f64;
    world.integration_parameters.length_unit = mean_diameter;

    let mut coupling = match scene.coupling {
        CouplingMode::Force if scene.force_path == ForcePath::Rapier => {
            let (law, parts) = registry::scene_law(&scene.contact)?;
            Coupling::RapierPipeline(law.rapier_pipeline(&scene.contact.normal.values, parts)?)
        }
        CouplingMode::Force => {
            let (law, parts) = registry::scene_law(&scene.contact)?;
            let boundary = match scene.periodic {
                Some([x, y]) => {
                    let boundary = Boundary::periodic_xy(x, y)?;
                    // No sphere may see two images of another: refused here, before the run.
                    let r_max = scene.particles.iter().map(|p| p.radius).fold(0.0, f64::max);
                    boundary.check_cutoff(2.0 * r_max + skin(scene))?;
                    boundary
                }
                None => Boundary::Open,
            };
            Coupling::NeighbourList(law.neighbour_list(
                &scene.contact.normal.values,
                parts,
                boundary,
            )?)
        }
        CouplingMode::Restitution => {
            let law = scene.contact.normal.law;
            let (model, work_of_adhesion) = if law == MdrElastoPlastic::DECLARATION.name {
                (
                    MdrElastoPlastic::from_values(&scene.contact.normal.values)?,
                    0.0,
                )
            } else if law == AdhesiveMdr::DECLARATION.name {
                let adhesive = AdhesiveMdr::from_values(&scene.contact.normal.values)?;
                (*adhesive.params(), adhesive.work_of_adhesion())
            } else {
                return Err(SimError::Build(
                    "restitution mode needs normal = \"mdr\" or \"adhesive_mdr\"".to_owned(),
                ));
            };
            let hooks = RestitutionHooks::new(model, scene.contact.friction())?;
            Coupling::Restitution(Box::new(if work_of_adhesion > 0.0 {
                hooks.with_work_of_adhesion(work_of_adhesion)?
            } else {
                hooks
            }))
        }
    };
    let materials: Vec<MaterialHandle> = scene
        .materials
        .iter()
        .map(|(_, m)| match &mut coupling {
            Coupling::RapierPipeline(s) => s.insert_material(*m),
            Coupling::NeighbourList(s) => s.insert_material(*m),
            Coupling::Restitution(h) => h.particles_mut().insert_material(*m),
        })
        .collect();
    // Each material pair's own normal values (the adhesive law with the pair's mixed work of
    // adhesion), where the scene gives them.
    for a in 0..materials.len() {
        for b in a..materials.len() {
            let Some(values) = scene.contact.pair_normal_values(a, b) else {
                continue;
            };
            let (ma, mb) = (materials[a], materials[b]);
            match &mut coupling {
                Coupling::RapierPipeline(s) => s.set_pair_normal(ma, mb, &values)?,
                Coupling::NeighbourList(s) => s.set_pair_normal(ma, mb, &values)?,
                Coupling::Restitution(h) => {
                    h.set_pair_normal(ma, mb, AdhesiveMdr::from_values(&values)?)?
                }
            }
        }
    }

    let mut wall_bodies = Vec::new();
    let mut wall_of_collider = Vec::new();
    let mut wall_of_surface = Vec::new();
    for (j, wall) in scene.walls.iter().enumerate() {
        let body = match wall.angular_velocity {
            Some(omega) => RigidBodyBuilder::kinematic_velocity_based()
                .translation(to_glam(&wall.origin))
                .angvel(to_glam(&omega))
                .can_sleep(false),
            None => RigidBodyBuilder::fixed().translation(to_glam(&wall.origin)),
        };
        let handle = world.insert_body(body);
        wall_bodies.push(handle);
        if let (Coupling::NeighbourList(s), Some(revolution)) = (&mut coupling, &wall.revolution) {
            // One collider for the whole wall (its pieces as a compound, for rapier's bounding
            // boxes), touching as the exact surface of revolution.
            let shapes = wall
                .pieces
                .iter()
                .map(|piece| piece_collider(piece).map(|b| (b.position, b.shape)))
                .collect::<Result<Vec<_>, _>>()?;
            let surface = SurfaceOfRevolution::new(
                &revolution.center,
                &revolution.axis,
                revolution.profile.clone(),
            )?;
            let c = s.insert_surface_of_revolution(
                &mut world,
                ColliderBuilder::compound(shapes),
                Some(handle),
                materials[wall.material],
                surface,
            )?;
            wall_of_surface.push(j);
            let i = c.into_raw_parts().0 as usize;
            if wall_of_collider.len() <= i {
                wall_of_collider.resize(i + 1, usize::MAX);
            }
            wall_of_collider[i] = j;
            continue;
        }
        for piece in &wall.pieces {
            let collider = piece_collider(piece)?;
            let material = materials[wall.material];
            let c = match &mut coupling {
                Coupling::RapierPipeline(s) => {
                    s.insert_surface(&mut world, collider, Some(handle), material)?
                }
                Coupling::NeighbourList(s) => {
                    wall_of_surface.push(j);
                    s.insert_surface(&mut world, collider, Some(handle), material)?
                }
                Coupling::Restitution(h) => {
                    h.insert_surface(&mut world, collider, Some(handle), material)?
                }
            };
            let i = c.into_raw_parts().0 as usize;
            if wall_of_collider.len() <= i {
                wall_of_collider.resize(i + 1, usize::MAX);
            }
            wall_of_collider[i] = j;
        }
    }

    let mut particle_bodies = Vec::with_capacity(scene.particles.len());
    let mut particle_colliders = Vec::with_capacity(scene.particles.len());
    let mut particle_of_collider = Vec::new();
    for (k, p) in scene.particles.iter().enumerate() {
        let sphere = SphereBuilder::new(p.radius, materials[p.material])
            .translation(to_glam(&p.position))
            .linvel(to_glam(&p.velocity));
        let (b, c) = match &mut coupling {
            Coupling::RapierPipeline(s) => s.insert_sphere(&mut world, sphere)?,
            Coupling::NeighbourList(s) => {
                s.insert_sphere(sphere)?;
                continue;
            }
            Coupling::Restitution(h) => h.insert_sphere(&mut world, sphere)?,
        };
        particle_bodies.push(b);
        particle_colliders.push(c);
        let i = c.into_raw_parts().0 as usize;
        if particle_of_collider.len() <= i {
            particle_of_collider.resize(i + 1, usize::MAX);
        }
        particle_of_collider[i] = k;
    }
    if wall_of_collider.len() < particle_of_collider.len() {
        wall_of_collider.resize(particle_of_collider.len(), usize::MAX);
    }

    let coupling = match coupling {
        Coupling::RapierPipeline(s) => {
            s.configure(
                &mut world.integration_parameters,
                scene.dt,
                prediction_distance(scene),
            )?;
            Coupling::RapierPipeline(s)
        }
        Coupling::NeighbourList(s) => {
            s.configure(&mut world.integration_parameters, scene.dt)?;
            // The walls' broad phase (rapier still detects wall–wall pairs) uses the same
            // prediction distance as the rapier pipeline path.
            world.integration_parameters.normalized_prediction_distance =
                prediction_distance(scene) / world.integration_parameters.length_unit;
            Coupling::NeighbourList(s.with_scene_settings(scene)?)
        }
        Coupling::Restitution(mut h) => {
            world.integration_parameters.dt = scene.dt;
            world.integration_parameters.normalized_max_linear_velocity = f64::MAX;
            world.integration_parameters.normalized_prediction_distance =
                prediction_distance(scene) / world.integration_parameters.length_unit;
            h.set_time_step(scene.dt)?;
            Coupling::Restitution(h)
        }
    };
    Ok(Built {
        world,
        coupling,
        particle_bodies,
        particle_colliders,
        wall_bodies,
        wall_of_collider,
        particle_of_collider,
        wall_of_surface,
    })
}
