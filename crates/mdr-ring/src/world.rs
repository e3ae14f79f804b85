//! Collisions of the ring particles in rapier: one dynamic ball per particle plus ghost balls for
//! the periodic images near the box edges, stepped by rapier with no gravity so that the step
//! only applies contact impulses (restitution mode through [`RingHooks`]).
//!
//! The ring crate integrates free motion itself ([`crate::hill::Sei`]); rapier's position update
//! is discarded: before each step the bodies are placed at the particles' positions and
//! velocities, after it only the velocities are read back (docs/rings.md §4). A ghost's velocity
//! change is added to the particle it images.
//!
//! Ghosts exist on the lower side of each boundary only: the images from the radially outer
//! neighbour box (`i = −1`, left of the box, any azimuthal shift) and from the azimuthally upper
//! one (`i = 0, n = −1`, below the box) ([`ImageLabel::is_lower_side`]). A pair that touches
//! across a boundary then meets exactly once, as one particle against the other's ghost: of the
//! two images that could carry the contact, the one shifted by `+L_x` (or by `+L_y`) has no ghost.
//! Ghosts do not collide with ghosts (collision groups).

use crate::boundary::{Image, ImageLabel, ShearingBox};
use crate::hooks::{decode, identity, RingHooks};
use crate::law::RestitutionLaw;
use crate::particles::Particles;
use rapier3d_f64::prelude::*;
use std::collections::BTreeMap;

/// Collision group of the particles' colliders.
const PARTICLES: Group = Group::GROUP_1;
/// Collision group of the ghosts' colliders.
const GHOSTS: Group = Group::GROUP_2;

/// A ghost ball: the rapier body of one periodic image of a particle.
#[derive(Debug, Clone, Copy)]
struct Ghost {
    body: RigidBodyHandle,
    source: usize,
    velocity: Vector,
    seen: bool,
}

/// Numerical settings of the collision step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionSettings {
    /// Distance below which rapier builds speculative contacts (m); must exceed the largest
    /// relative displacement of two particles in one step.
    pub prediction_distance: f64,
    /// rapier solver iterations per step.
    pub solver_iterations: usize,
}

impl Default for CollisionSettings {
    fn default() -> Self {
        Self {
            prediction_distance: 0.5,
            solver_iterations: 1,
        }
    }
}

/// The rapier side of a ring run.
pub struct CollisionWorld<L: RestitutionLaw> {
    world: PhysicsWorld,
    hooks: RingHooks<L>,
    real: Vec<RigidBodyHandle>,
    /// Ordered by key, so that ghosts are created, removed and summed in the same order in every
    /// run (a `HashMap`'s random order made runs differ: rapier's body slots, and the rounding of
    /// the ghost velocity sums).
    ghosts: BTreeMap<(usize, ImageLabel), Ghost>,
    margin: f64,
    images: Vec<Image>,
}

impl<L: RestitutionLaw> CollisionWorld<L> {
    /// Bodies for `particles`, stepping by `dt` (s) with `law`.
    pub fn new(particles: &Particles, law: L, dt: f64, settings: CollisionSettings) -> Self {
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::ZERO;
        let params = &mut world.integration_parameters;
        params.dt = dt;
        params.length_unit = 1.0;
        params.normalized_prediction_distance = settings.prediction_distance;
        params.num_solver_iterations = settings.solver_iterations.max(1);
        // No CCD: the speculative contacts cover the step, and positions are not rapier's.
        params.max_ccd_substeps = 0;
        let mut this = Self {
            world,
            hooks: RingHooks::new(law, dt),
            real: Vec::with_capacity(particles.len()),
            ghosts: BTreeMap::new(),
            margin: 2.0 * particles.max_radius() + 2.0 * settings.prediction_distance,
            images: Vec::new(),
        };
        for i in 0..particles.len() {
            let body = this.insert_ball(
                particles.position[i],
                particles.velocity[i],
                particles.radius[i],
                particles.mass[i],
                identity(i, false),
            );
            this.real.push(body);
        }
        this
    }

    fn insert_ball(
        &mut self,
        position: Vector,
        velocity: Vector,
        radius: f64,
        mass: f64,
        user_data: u128,
    ) -> RigidBodyHandle {
        let body = RigidBodyBuilder::dynamic()
            .translation(position)
            .linvel(velocity)
            .lock_rotations()
            .can_sleep(false)
            .build();
        // Ghosts meet particles only: two ghosts image a pair that meets elsewhere, as particles
        // or as a particle and a ghost (module documentation).
        let groups = if decode(user_data).1 {
            InteractionGroups::new(GHOSTS, PARTICLES, InteractionTestMode::And)
        } else {
            InteractionGroups::new(PARTICLES, PARTICLES | GHOSTS, InteractionTestMode::And)
        };
        let collider = ColliderBuilder::ball(radius)
            .mass(mass)
            .friction(0.0)
            .restitution(0.0)
            .user_data(user_data)
            .collision_groups(groups)
            .active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS)
            .build();
        self.world.insert(body, collider).0
    }

    /// The hooks (law, collision counter).
    pub fn hooks(&self) -> &RingHooks<L> {
        &self.hooks
    }

    /// Number of ghost bodies currently alive.
    pub fn ghost_count(&self) -> usize {
        self.ghosts.len()
    }

    /// Margin around the box within which images get a ghost (m).
    pub fn ghost_margin(&self) -> f64 {
        self.margin
    }

    /// One collision step at time `time`: place bodies and ghosts, let rapier resolve the
    /// contacts that close within `dt`, and write the post-impulse velocities back to
    /// `particles` (positions are left untouched).
    pub fn collide(&mut self, particles: &mut Particles, domain: &ShearingBox, time: f64) {
        for (i, &handle) in self.real.iter().enumerate() {
            let body = &mut self.world.bodies[handle];
            body.set_translation(particles.position[i], false);
            body.set_linvel(particles.velocity[i], false);
        }
        self.sync_ghosts(particles, domain, time);
        self.world.step_with_events(&self.hooks, &());
        self.hooks.end_step();
        for (i, &handle) in self.real.iter().enumerate() {
            particles.velocity[i] = self.world.bodies[handle].linvel();
        }
        for ghost in self.ghosts.values() {
            let delta = self.world.bodies[ghost.body].linvel() - ghost.velocity;
            particles.velocity[ghost.source] += delta;
        }
    }

    /// Create, move or remove ghost bodies so that every image within the margin of the box has
    /// exactly one, keyed by (particle, image label) so a ghost keeps its contacts while the
    /// boxes slide.
    fn sync_ghosts(&mut self, particles: &Particles, domain: &ShearingBox, time: f64) {
        for ghost in self.ghosts.values_mut() {
            ghost.seen = false;
        }
        for i in 0..particles.len() {
            self.images.clear();
            domain.lower_side_images_near_box(
                particles.position[i],
                particles.velocity[i],
                time,
                self.margin,
                &mut self.images,
            );
            for k in 0..self.images.len() {
                let image = self.images[k];
                let key = (i, image.label);
                if let Some(ghost) = self.ghosts.get_mut(&key) {
                    let body = &mut self.world.bodies[ghost.body];
                    body.set_translation(image.position, false);
                    body.set_linvel(image.velocity, false);
                    ghost.velocity = image.velocity;
                    ghost.seen = true;
                } else {
                    let body = self.insert_ball(
                        image.position,
                        image.velocity,
                        particles.radius[i],
                        particles.mass[i],
                        identity(i, true),
                    );
                    self.ghosts.insert(
                        key,
                        Ghost {
                            body,
                            source: i,
                            velocity: image.velocity,
                            seen: true,
                        },
                    );
                }
            }
        }
        let world = &mut self.world;
        self.ghosts.retain(|_, ghost| {
            if !ghost.seen {
                world.remove_body_with_colliders(ghost.body, true);
            }
            ghost.seen
        });
    }
}
