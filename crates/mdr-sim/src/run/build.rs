//! Building the rapier world of a scene: materials, wall bodies (fixed or kinematic) with their
//! solid pieces, then the spheres, in the scene's order, so the same scene always gets the same
//! handles (which the checkpoints rely on).
//!
//! Force mode runs on the neighbour-list path ([`NeighbourListStepper`]) unless the scene selects
//! `force_path = "rapier"`: the walls are rapier colliders registered as its surfaces, the
//! spheres live in the stepper's own arrays (particle `i` of the scene is its particle `i`),
//! and rapier keeps and moves the wall bodies.

use crate::error::SimError;
use crate::laws::{scene_model, AnyDamping, AnyNormal, AnyRolling, SceneNormal, SceneRolling};
use crate::scene::{CouplingMode, ForcePath, NormalSpec, Scene};
use crate::walls::WallPiece;
use mdr_contact::model::ContactModel;
use mdr_contact::normal::{Hertz, MdrElastoPlastic, Thornton};
use mdr_contact::rolling::{EpsdRolling, NoRolling};
use mdr_contact::tangential::Mindlin;
use mdr_rapier::convert::to_glam;
use mdr_rapier::geometry::SurfaceOfRevolution;
use mdr_rapier::neighbour_list::particles::NeighbourListParticles;
use mdr_rapier::neighbour_list::{
    Boundary, NeighbourListStepReport, NeighbourListStepper, StepTimings,
};
use mdr_rapier::particles::{MaterialHandle, SphereBuilder};
use mdr_rapier::{ForceModeStepper, RestitutionHooks};
use rapier3d_f64::prelude::*;

/// The force-mode stepper type every scene uses.
pub type SceneStepper = ForceModeStepper<AnyNormal, Mindlin, AnyDamping, AnyRolling>;

/// The neighbour-list force-mode stepper of a scene, with normal model `N` and rolling model
/// `R`.
pub type FastSceneStepper<N, R> = NeighbourListStepper<N, Mindlin, AnyDamping, R>;

/// The neighbour-list stepper of a scene (the default force path), compiled for each normal law
/// and for rolling resistance on or off: a contact carries only the history its laws keep (a
/// scene without rolling resistance runs with [`NoRolling`]: no rolling history, no rolling
/// branch), and the pair loop takes no branch on the law (docs/performance.md).
pub enum FastScene {
    /// MDR, no rolling resistance (`rolling_friction = 0`).
    MdrSliding(Box<FastSceneStepper<MdrElastoPlastic, NoRolling>>),
    /// MDR with the elastic–plastic spring rolling resistance.
    MdrRolling(Box<FastSceneStepper<MdrElastoPlastic, EpsdRolling>>),
    /// Hertz, no rolling resistance.
    HertzSliding(Box<FastSceneStepper<Hertz, NoRolling>>),
    /// Hertz with rolling resistance.
    HertzRolling(Box<FastSceneStepper<Hertz, EpsdRolling>>),
    /// Thornton, no rolling resistance.
    ThorntonSliding(Box<FastSceneStepper<Thornton, NoRolling>>),
    /// Thornton with rolling resistance.
    ThorntonRolling(Box<FastSceneStepper<Thornton, EpsdRolling>>),
}

/// `$body` with `$s` bound to the stepper of a [`FastScene`] (a reference to it when `$scene`
/// is one), whichever its laws: for code generic over [`SceneNormal`] and [`SceneRolling`].
macro_rules! with_fast {
    ($scene:expr, $s:ident => $body:expr) => {
        match $scene {
            $crate::run::build::FastScene::MdrSliding($s) => $body,
            $crate::run::build::FastScene::MdrRolling($s) => $body,
            $crate::run::build::FastScene::HertzSliding($s) => $body,
            $crate::run::build::FastScene::HertzRolling($s) => $body,
            $crate::run::build::FastScene::ThorntonSliding($s) => $body,
            $crate::run::build::FastScene::ThorntonRolling($s) => $body,
        }
    };
}
pub(crate) use with_fast;

impl FastScene {
    /// The spheres.
    pub fn particles(&self) -> &NeighbourListParticles {
        with_fast!(self, s => s.particles())
    }

    /// The spheres, to change.
    pub fn particles_mut(&mut self) -> &mut NeighbourListParticles {
        with_fast!(self, s => s.particles_mut())
    }

    /// Neighbour-list builds so far.
    pub fn rebuilds(&self) -> u64 {
        with_fast!(self, s => s.rebuilds())
    }

    /// Sphere pairs in the neighbour list.
    pub fn listed_pairs(&self) -> usize {
        with_fast!(self, s => s.pairs().len())
    }

    /// What the last step did.
    pub fn last_report(&self) -> NeighbourListStepReport {
        with_fast!(self, s => s.last_report())
    }

    /// Build the neighbour lists at the next step (after particles jumped).
    pub fn request_rebuild(&mut self) {
        with_fast!(self, s => s.request_rebuild())
    }

    /// Time each part of the steps from now on, or stop ([`NeighbourListStepper::time_steps`]).
    pub fn time_steps(&mut self, on: bool) {
        with_fast!(self, s => s.time_steps(on))
    }

    /// Time per part of the steps while timed.
    pub fn step_timings(&self) -> Option<StepTimings> {
        with_fast!(self, s => s.step_timings().copied())
    }
}

/// A neighbour-list stepper's settings for scenes: the skin, energy books that take each
/// contact's works once, when its history ends, and no orientations (no output reads a sphere's
/// orientation and no sphere contact depends on it, as LAMMPS's `atom_style sphere`; spins are
/// integrated).
fn scene_settings<N: SceneNormal, R: SceneRolling>(
    stepper: FastSceneStepper<N, R>,
    scene: &Scene,
) -> Result<Box<FastSceneStepper<N, R>>, SimError> {
    Ok(Box::new(
        stepper
            .skin(skin(scene))?
            .record_ended_contacts(true)
            .track_orientation(false),
    ))
}

impl FastScene {
    /// The stepper for `model` with normal law `N` and the scene's rolling model, as the variant
    /// `sliding` or `rolling` of its normal law.
    fn new<N: SceneNormal>(
        model: ContactModel<N, Mindlin, AnyDamping>,
        rolling: AnyRolling,
        boundary: Boundary,
        sliding: fn(Box<FastSceneStepper<N, NoRolling>>) -> FastScene,
        with_rolling: fn(Box<FastSceneStepper<N, EpsdRolling>>) -> FastScene,
    ) -> FastScene {
        let stepper = NeighbourListStepper::new(model, boundary);
        match rolling {
            AnyRolling(Some(rolling)) => with_rolling(Box::new(stepper.with_rolling(rolling))),
            AnyRolling(None) => sliding(Box::new(stepper)),
        }
    }

    /// The same stepper with the settings of [`scene_settings`].
    fn with_scene_settings(self, scene: &Scene) -> Result<FastScene, SimError> {
        Ok(match self {
            FastScene::MdrSliding(s) => FastScene::MdrSliding(scene_settings(*s, scene)?),
            FastScene::MdrRolling(s) => FastScene::MdrRolling(scene_settings(*s, scene)?),
            FastScene::HertzSliding(s) => FastScene::HertzSliding(scene_settings(*s, scene)?),
            FastScene::HertzRolling(s) => FastScene::HertzRolling(scene_settings(*s, scene)?),
            FastScene::ThorntonSliding(s) => FastScene::ThorntonSliding(scene_settings(*s, scene)?),
            FastScene::ThorntonRolling(s) => FastScene::ThorntonRolling(scene_settings(*s, scene)?),
        })
    }
}

/// The coupling of a built scene.
pub enum Coupling {
    /// Force mode on rapier's broad and narrow phase (`force_path = "rapier"`).
    Force(Box<SceneStepper>),
    /// Force mode on the neighbour-list path (the default).
    Fast(FastScene),
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

    enum Inserter {
        Force(Box<SceneStepper>),
        Fast(FastScene),
        Restitution(Box<RestitutionHooks>),
    }
    let mut inserter = match scene.coupling {
        CouplingMode::Force if scene.force_path == ForcePath::Rapier => {
            let (model, rolling) = scene_model(&scene.contact)?;
            Inserter::Force(Box::new(ForceModeStepper::new(model).with_rolling(rolling)))
        }
        CouplingMode::Force => {
            let (model, rolling) = scene_model(&scene.contact)?;
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
            Inserter::Fast(match model.normal {
                AnyNormal::Mdr(normal) => FastScene::new(
                    model.with_normal(normal),
                    rolling,
                    boundary,
                    FastScene::MdrSliding,
                    FastScene::MdrRolling,
                ),
                AnyNormal::Hertz(normal) => FastScene::new(
                    model.with_normal(normal),
                    rolling,
                    boundary,
                    FastScene::HertzSliding,
                    FastScene::HertzRolling,
                ),
                AnyNormal::Thornton(normal) => FastScene::new(
                    model.with_normal(normal),
                    rolling,
                    boundary,
                    FastScene::ThorntonSliding,
                    FastScene::ThorntonRolling,
                ),
            })
        }
        CouplingMode::Restitution => {
            let NormalSpec::Mdr {
                critical_line_load,
                hardening_ratio,
            } = scene.contact.normal
            else {
                return Err(SimError::Build(
                    "restitution mode needs normal = \"mdr\"".to_owned(),
                ));
            };
            let model = MdrElastoPlastic::new(critical_line_load, hardening_ratio)?;
            Inserter::Restitution(Box::new(RestitutionHooks::new(
                model,
                scene.contact.friction,
            )?))
        }
    };
    let materials: Vec<MaterialHandle> = scene
        .materials
        .iter()
        .map(|(_, m)| match &mut inserter {
            Inserter::Force(s) => s.particles_mut().insert_material(*m),
            Inserter::Fast(s) => with_fast!(s, s => s.insert_material(*m)),
            Inserter::Restitution(h) => h.particles_mut().insert_material(*m),
        })
        .collect();

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
        if let (Inserter::Fast(s), Some(revolution)) = (&mut inserter, &wall.revolution) {
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
            let c = with_fast!(s, s => s.insert_surface_of_revolution(
                &mut world,
                ColliderBuilder::compound(shapes),
                Some(handle),
                materials[wall.material],
                surface,
            ))?;
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
            let c = match &mut inserter {
                Inserter::Force(s) => {
                    s.insert_surface(&mut world, collider, Some(handle), material)?
                }
                Inserter::Fast(s) => {
                    wall_of_surface.push(j);
                    with_fast!(s, s => {
                        s.insert_surface(&mut world, collider, Some(handle), material)
                    })?
                }
                Inserter::Restitution(h) => {
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
        let (b, c) = match &mut inserter {
            Inserter::Force(s) => s.insert_sphere(&mut world, sphere)?,
            Inserter::Fast(s) => {
                with_fast!(s, s => s.insert_sphere(sphere))?;
                continue;
            }
            Inserter::Restitution(h) => h.insert_sphere(&mut world, sphere)?,
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

    let coupling = match inserter {
        Inserter::Force(s) => {
            s.configure(
                &mut world.integration_parameters,
                scene.dt,
                prediction_distance(scene),
            )?;
            Coupling::Force(s)
        }
        Inserter::Fast(s) => {
            with_fast!(&s, s => s.configure(&mut world.integration_parameters, scene.dt))?;
            // The walls' broad phase (rapier still detects wall–wall pairs) uses the same
            // prediction distance as the rapier pipeline path.
            world.integration_parameters.normalized_prediction_distance =
                prediction_distance(scene) / world.integration_parameters.length_unit;
            Coupling::Fast(s.with_scene_settings(scene)?)
        }
        Inserter::Restitution(mut h) => {
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
