//! A game-style rapier world with MDR spheres in it (restitution mode, the game's 60 Hz step):
//! a walled floor, two dynamic crates and a convex rock (registered as surfaces: the spheres bounce off
//! them with the law's restitution; they rest on the floor and on each other through rapier),
//! a fixed ledge the user left unregistered (rapier's own contact), plain rapier balls of the
//! user's, a user hook that lets "ghost" colliders pass through the ledge, and collision events
//! collected through rapier's channel collector.
//!
//! Run: `cargo run --release -p mdr-rapier --example game_world`.
use mdr_rapier::prelude::*;
use mdr_rapier::rapier::prelude::*;
use std::sync::mpsc::channel;

/// User data of the colliders the user's hook lets through the ledge.
pub const GHOST: u128 = 0x6057;

/// The user's hooks: ghosts pass through the ledge.
pub struct GhostThroughLedge {
    /// The ledge collider.
    pub ledge: ColliderHandle,
}

impl PhysicsHooks for GhostThroughLedge {
    fn filter_contact_pair(&self, ctx: &PairFilterContext) -> Option<SolverFlags> {
        let ghost = |c: ColliderHandle| ctx.colliders[c].user_data == GHOST;
        let ledge = ctx.collider1 == self.ledge || ctx.collider2 == self.ledge;
        if ledge && (ghost(ctx.collider1) || ghost(ctx.collider2)) {
            None
        } else {
            Some(SolverFlags::COMPUTE_RIGID_IMPULSES)
        }
    }
}

/// What a run ends with.
#[derive(Debug, Clone, PartialEq)]
pub struct GameSummary {
    /// Lowest point of any crate or the rock (m): they stand on the floor at 0.
    pub lowest_surface_body: f64,
    /// Lowest MDR sphere centre (m).
    pub lowest_sphere: f64,
    /// Heights of the user's plain balls (m), the ghost last.
    pub plain_balls: Vec<f64>,
    /// Impacts resolved with the law's restitution.
    pub law_impacts: u64,
    /// Largest number of other pairs rapier solved in one step.
    pub rapier_pairs: usize,
    /// Collision-started events seen by the user's channel.
    pub collisions_started: usize,
}

/// Build the world and run it for `steps` frames of 1/60 s.
pub fn run(steps: usize) -> Result<GameSummary, CouplingError> {
    let mut world = PhysicsWorld::default();
    world.integration_parameters.dt = 1.0 / 60.0;
    world.integration_parameters.length_unit = 0.2;
    let mut mdr =
        RestitutionHooks::with_friction_rule(MdrElastoPlastic::paper(), FrictionRule::Colliders)?;
    let rubberish = Material::builder()
        .youngs(5.0e7)
        .poisson(0.45)
        .density(1100.0)
        .build()?;
    let m = mdr.particles_mut().insert_material(rubberish);

    mdr.insert_surface(
        &mut world,
        ColliderBuilder::cuboid(5.0, 0.5, 5.0).translation(Vector::new(0.0, -0.5, 0.0)),
        None,
        m,
    )?;
    // The arena's walls, 3 m from the centre.
    for (centre, half) in [
        (Vector::new(3.0, 0.5, 0.0), Vector::new(0.1, 0.5, 3.0)),
        (Vector::new(-3.0, 0.5, 0.0), Vector::new(0.1, 0.5, 3.0)),
        (Vector::new(0.0, 0.5, 3.0), Vector::new(3.0, 0.5, 0.1)),
        (Vector::new(0.0, 0.5, -3.0), Vector::new(3.0, 0.5, 0.1)),
    ] {
        let wall = ColliderBuilder::cuboid(half.x, half.y, half.z).translation(centre);
        mdr.insert_surface(&mut world, wall, None, m)?;
    }
    let mut surface_bodies = Vec::new();
    for (x, half) in [(-1.0, 0.25), (1.2, 0.2)] {
        let body =
            world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(x, 1.0, 0.0)));
        surface_bodies.push(mdr.insert_surface(
            &mut world,
            ColliderBuilder::cuboid(half, half, half).density(400.0),
            Some(body),
            m,
        )?);
    }
    let rock_points = [
        Vector::new(0.3, 0.0, 0.0),
        Vector::new(-0.25, 0.0, 0.1),
        Vector::new(0.0, 0.25, 0.0),
        Vector::new(0.05, -0.2, 0.0),
        Vector::new(0.0, 0.0, 0.3),
        Vector::new(0.1, 0.0, -0.25),
    ];
    let rock =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.5, 1.0)));
    let rock_shape = ColliderBuilder::convex_hull(&rock_points)
        .ok_or(CouplingError::Unsupported("the rock's points have no hull"))?
        .density(2500.0);
    surface_bodies.push(mdr.insert_surface(&mut world, rock_shape, Some(rock), m)?);

    // The user's own ledge (not registered) and its filter hook.
    let ledge = world.insert_collider(
        ColliderBuilder::cuboid(0.6, 0.05, 0.6)
            .translation(Vector::new(0.0, 0.8, -1.5))
            .active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS),
        None,
    );
    let user_hooks = GhostThroughLedge { ledge };

    // MDR spheres rain down, reporting their collisions.
    let mut spheres = Vec::new();
    for i in 0..12 {
        let x = -1.2 + 0.22 * i as f64;
        let sphere = SphereBuilder::new(0.08, m)
            .translation(Vector::new(x, 2.5 + 0.1 * (i % 3) as f64, 0.0))
            .active_events(ActiveEvents::COLLISION_EVENTS)
            .ccd_enabled(true)
            .friction(0.6);
        spheres.push(mdr.insert_sphere(&mut world, sphere)?.0);
    }
    // The user's plain rapier balls: one lands on the ledge, the ghost falls through it.
    let mut plain = Vec::new();
    for (x, tag) in [(-0.2, 0), (0.2, GHOST)] {
        let (b, _) = world.insert(
            RigidBodyBuilder::dynamic().translation(Vector::new(x, 1.5, -1.5)),
            ColliderBuilder::ball(0.1).user_data(tag),
        );
        plain.push(b);
    }

    let (collision_send, collision_recv) = channel();
    let (force_send, _force_recv) = channel();
    let (tear_send, _tear_recv) = channel();
    let events = ChannelEventCollector::new(collision_send, force_send, tear_send);
    let (mut law_impacts, mut rapier_pairs, mut collisions_started) = (0, 0, 0);
    for _ in 0..steps {
        let report = mdr.step_with(&mut world, &user_hooks, &events)?;
        law_impacts += report.impacts;
        rapier_pairs = rapier_pairs.max(report.rapier_pairs);
        collisions_started += collision_recv.try_iter().filter(|e| e.started()).count();
    }
    let lowest_surface_body = surface_bodies
        .iter()
        .map(|&c| world.colliders[c].compute_aabb().mins.y)
        .fold(f64::INFINITY, f64::min);
    let lowest_sphere = spheres
        .iter()
        .map(|&b| world.bodies[b].translation().y)
        .fold(f64::INFINITY, f64::min);
    Ok(GameSummary {
        lowest_surface_body,
        lowest_sphere,
        plain_balls: plain
            .iter()
            .map(|&b| world.bodies[b].translation().y)
            .collect(),
        law_impacts,
        rapier_pairs,
        collisions_started,
    })
}

#[allow(dead_code)]
fn main() -> Result<(), CouplingError> {
    let summary = run(300)?;
    println!("after 5 s of game time: {summary:#?}");
    Ok(())
}
