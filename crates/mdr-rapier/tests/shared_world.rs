//! A rapier world shared with the plugin behaves for the user's own bodies as without it: a
//! constant force the user added to a registered body acts at every step on both force-mode
//! paths, the neighbour-list path's surfaces keep rapier's contacts with everything that is
//! not a particle, and a step given to the coupling that differs from rapier's, like every
//! registration or restore mistake, is a named error.

use mdr_rapier::neighbour_list::{Boundary, NeighbourListStepper};
use mdr_rapier::prelude::*;
use mdr_rapier::rapier::prelude::*;
use mdr_rapier::{CouplingMode, ImpactScene, SceneLaw};

const R: f64 = 0.01;
const HALF: f64 = 0.05;
const DT: f64 = 1e-4;
const STEPS: usize = 2000;

fn grain() -> Material {
    Material::builder()
        .youngs(1.0e6)
        .poisson(0.3)
        .density(2500.0)
        .build()
        .unwrap()
}

/// A world with a registered floor `y = 0` on the neighbour-list path, and the grain material.
fn neighbour_list_on_floor() -> (
    PhysicsWorld,
    NeighbourListStepper<MdrElastoPlastic>,
    MaterialHandle,
) {
    let mut world = PhysicsWorld::default();
    let mut stepper =
        NeighbourListStepper::new(ContactModel::new(MdrElastoPlastic::paper()), Boundary::Open);
    let m = stepper.insert_material(grain());
    stepper
        .insert_surface(
            &mut world,
            ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
            None,
            m,
        )
        .unwrap();
    (world, stepper, m)
}

/// The integration parameters force mode's `configure` sets (one solver iteration, no CCD, no
/// speed cap), for the plugin-free reference world.
fn reference_parameters(world: &mut PhysicsWorld) {
    world.integration_parameters.dt = DT;
    world.integration_parameters.num_solver_iterations = 1;
    world.integration_parameters.max_ccd_substeps = 0;
    world.integration_parameters.normalized_max_linear_velocity = f64::MAX;
    world.integration_parameters.normalized_prediction_distance =
        0.2 * R / world.integration_parameters.length_unit;
}

/// The user's bodies: a cuboid resting on the floor, pushed sideways by a constant force the
/// user adds once, and a cuboid in the air held up by a constant force equal to its weight.
struct UserBodies {
    pushed: RigidBodyHandle,
    held: RigidBodyHandle,
    push: Vector,
}

fn cuboid() -> ColliderBuilder {
    ColliderBuilder::cuboid(HALF, HALF, HALF).density(2500.0)
}

/// Insert the two bodies (their colliders through `insert`) and add the user's forces.
fn user_bodies(
    world: &mut PhysicsWorld,
    mut insert: impl FnMut(&mut PhysicsWorld, ColliderBuilder, RigidBodyHandle),
) -> UserBodies {
    let pushed = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, HALF, 0.0))
            .can_sleep(false),
    );
    insert(world, cuboid(), pushed);
    let held = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 1.0, 0.0))
            .can_sleep(false),
    );
    insert(world, cuboid(), held);
    // Sliding friction is 0.5 m g (rapier's default friction); push with 0.9 m g.
    let weight = world.bodies[pushed].mass() * 9.81;
    let push = Vector::new(0.9 * weight, 0.0, 0.0);
    world.bodies[pushed].add_force(push, true);
    world.bodies[held].add_force(Vector::new(0.0, weight, 0.0), true);
    UserBodies { pushed, held, push }
}

/// The same bodies on a plain floor in a world without the plugin, after `STEPS` steps.
fn without_plugin() -> (Vector, Vector) {
    let mut world = PhysicsWorld::default();
    reference_parameters(&mut world);
    world.insert_collider(
        ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
        None,
    );
    let bodies = user_bodies(&mut world, |w, c, b| {
        w.insert_collider(c, Some(b));
    });
    for _ in 0..STEPS {
        world.step();
    }
    (
        world.bodies[bodies.pushed].translation(),
        world.bodies[bodies.held].translation(),
    )
}

fn assert_as_without_plugin(world: &PhysicsWorld, bodies: &UserBodies) {
    let (pushed, held) = without_plugin();
    // The push: a = (0.9 − 0.5) g → x = a t² / 2 = 0.078 m after 0.2 s.
    assert!(
        (pushed.x - 0.0785).abs() < 2e-3,
        "the reference cuboid slid {}",
        pushed.x
    );
    let x = world.bodies[bodies.pushed].translation();
    let y = world.bodies[bodies.held].translation();
    assert!(
        (x - pushed).length() < 1e-9,
        "pushed cuboid at {x:?}, {pushed:?} without the plugin"
    );
    assert!(
        (y - held).length() < 1e-12 && (y.y - 1.0).abs() < 1e-9,
        "held cuboid at {y:?}, {held:?} without the plugin"
    );
    // Between steps the bodies hold exactly the user's forces.
    assert_eq!(world.bodies[bodies.pushed].user_force(), bodies.push);
}

/// Force mode: both cuboids are registered surfaces on dynamic bodies (the spheres would touch
/// them through the law); a sphere rests on the floor away from them.
#[test]
fn a_users_constant_force_on_a_registered_body_acts_as_without_the_plugin() {
    let mut world = PhysicsWorld::default();
    let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::paper()));
    let m = stepper.particles_mut().insert_material(grain());
    stepper
        .insert_surface(
            &mut world,
            ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
            None,
            m,
        )
        .unwrap();
    let bodies = user_bodies(&mut world, |w, c, b| {
        stepper.insert_surface(w, c, Some(b), m).unwrap();
    });
    stepper
        .insert_sphere(
            &mut world,
            SphereBuilder::new(R, m).translation(Vector::new(2.0, R, 0.0)),
        )
        .unwrap();
    stepper
        .configure(&mut world.integration_parameters, DT, 0.2 * R)
        .unwrap();
    for _ in 0..STEPS {
        stepper.step(&mut world).unwrap();
    }
    assert_as_without_plugin(&world, &bodies);
}

/// The neighbour-list path: the floor and both cuboids are its surfaces; one particle rests on
/// the floor away from them. The cuboid on the floor also needs rapier's contact between two
/// registered surfaces.
#[test]
fn a_users_constant_force_acts_as_without_the_plugin_on_the_neighbour_list_path() {
    let (mut world, mut stepper, m) = neighbour_list_on_floor();
    let bodies = user_bodies(&mut world, |w, c, b| {
        stepper.insert_surface(w, c, Some(b), m).unwrap();
    });
    stepper
        .insert_sphere(SphereBuilder::new(R, m).translation(Vector::new(2.0, R, 0.0)))
        .unwrap();
    stepper
        .configure(&mut world.integration_parameters, DT)
        .unwrap();
    world.integration_parameters.normalized_prediction_distance =
        0.2 * R / world.integration_parameters.length_unit;
    for _ in 0..STEPS {
        stepper.step(&mut world).unwrap();
    }
    assert_as_without_plugin(&world, &bodies);
}

/// The user's hook: colliders flagged with `FILTER_CONTACT_PAIRS` touch nothing.
struct PassThrough;

impl PhysicsHooks for PassThrough {
    fn filter_contact_pair(&self, _: &PairFilterContext) -> Option<SolverFlags> {
        None
    }
}

/// The neighbour-list path: a dynamic box the plugin does not know rests on a registered floor
/// (rapier's contact, reported to the user's event handler), a dynamic box falls onto a
/// registered dynamic box resting on it, and a box whose pairs the user's hook rejects falls
/// through the floor.
#[test]
fn unregistered_bodies_rest_on_the_neighbour_list_paths_surfaces() {
    let (mut world, mut stepper, m) = neighbour_list_on_floor();
    let on_floor = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.5, HALF + 0.01, 0.0))
            .can_sleep(false),
    );
    let on_floor_collider = world.insert_collider(
        cuboid().active_events(ActiveEvents::COLLISION_EVENTS),
        Some(on_floor),
    );
    let ghost = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(1.0, HALF + 0.01, 0.0))
            .can_sleep(false),
    );
    world.insert_collider(
        cuboid().active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS),
        Some(ghost),
    );
    let registered = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(-0.5, HALF, 0.0))
            .can_sleep(false),
    );
    stepper
        .insert_surface(&mut world, cuboid(), Some(registered), m)
        .unwrap();
    let on_top = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(-0.5, 3.0 * HALF + 0.01, 0.0))
            .can_sleep(false),
    );
    world.insert_collider(cuboid(), Some(on_top));
    stepper
        .insert_sphere(SphereBuilder::new(R, m).translation(Vector::new(2.0, R, 0.0)))
        .unwrap();
    stepper
        .configure(&mut world.integration_parameters, DT)
        .unwrap();
    let (collisions, received) = std::sync::mpsc::channel();
    let (forces, _) = std::sync::mpsc::channel();
    let (tears, _) = std::sync::mpsc::channel();
    let events = ChannelEventCollector::new(collisions, forces, tears);
    for _ in 0..STEPS {
        stepper
            .step_with(&mut world, &PassThrough, &events)
            .unwrap();
    }
    assert!(
        received.try_iter().any(|e| e.started()),
        "the user's handler saw the box land"
    );
    // Free fall, symplectic Euler: g dt² N (N + 1) / 2 after N steps.
    let fallen = HALF + 0.01 - world.bodies[ghost].translation().y;
    let free_fall = 9.81 * DT * DT * (STEPS * (STEPS + 1)) as f64 / 2.0;
    assert!((fallen - free_fall).abs() < 1e-9, "ghost fell {fallen}");
    let bottom = world.colliders[on_floor_collider].compute_aabb().mins.y;
    assert!(bottom > -2e-3, "unregistered box sank to {bottom}");
    let top = world.bodies[on_top].translation().y;
    assert!(
        (top - 3.0 * HALF).abs() < 3e-3,
        "box on the registered box at {top}"
    );
    assert!(world.bodies[on_floor].linvel().length() < 0.05);
}

/// Force mode, own pipeline: `check_step` refuses a step handed to `compute_forces` that is not
/// rapier's; restitution mode refuses a world whose step is not the declared one.
#[test]
fn a_step_that_is_not_rapiers_is_an_error() {
    let mut world = PhysicsWorld::default();
    let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::paper()));
    let m = stepper.particles_mut().insert_material(grain());
    stepper
        .insert_sphere(&mut world, SphereBuilder::new(R, m))
        .unwrap();
    stepper
        .configure(&mut world.integration_parameters, DT, 0.2 * R)
        .unwrap();
    let (params, colliders) = (&world.integration_parameters, &world.colliders);
    assert_eq!(stepper.check_step(params, colliders, DT), Ok(()));
    let err = stepper.check_step(params, colliders, 2.0 * DT).unwrap_err();
    assert!(
        matches!(err, CouplingError::TimeStepMismatch { coupling, world, .. }
            if coupling == 2.0 * DT && world == DT),
        "{err:?}"
    );
    assert!(err.to_string().contains("compute_forces"), "{err}");

    let mut world = PhysicsWorld::default();
    world.integration_parameters.dt = DT;
    let mut hooks = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.0).unwrap();
    let m = hooks
        .particles_mut()
        .insert_material(Material::paper_steel());
    hooks
        .insert_sphere(&mut world, SphereBuilder::new(R, m))
        .unwrap();
    // Undeclared: the hooks take the world's step, whatever it is.
    hooks.step(&mut world).unwrap();
    world.integration_parameters.dt = 1.0 / 60.0;
    hooks.step(&mut world).unwrap();
    // Declared: a world with another step is refused, the declared one steps.
    hooks.set_time_step(DT).unwrap();
    let err = hooks.step(&mut world).unwrap_err();
    assert!(
        matches!(err, CouplingError::TimeStepMismatch { coupling, world, .. }
            if coupling == DT && world == 1.0 / 60.0),
        "{err:?}"
    );
    assert!(err.to_string().contains("set_time_step"), "{err}");
    world.integration_parameters.dt = DT;
    hooks.step(&mut world).unwrap();
}

/// Every way of registering something that is not there, or not what the coupling needs, is a
/// named error; so are a scene the chosen mode cannot run, bad pair data and a saved
/// neighbour-list state restored into another stepper.
#[test]
fn registration_and_restore_mistakes_are_named_errors() {
    let mut world = PhysicsWorld::default();
    let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::paper()));
    let m = stepper.particles_mut().insert_material(grain());
    let unknown_material = MaterialHandle(7);
    assert_eq!(
        stepper
            .insert_sphere(&mut world, SphereBuilder::new(R, unknown_material))
            .unwrap_err(),
        CouplingError::UnknownMaterial(7, 1)
    );
    let nowhere = ColliderHandle::from_raw_parts(99, 0);
    assert_eq!(
        stepper
            .register_sphere(nowhere, m, &mut world.colliders)
            .unwrap_err(),
        CouplingError::UnknownCollider(nowhere)
    );
    let body = world.insert_body(RigidBodyBuilder::dynamic());
    let cube = world.insert_collider(ColliderBuilder::cuboid(R, R, R), Some(body));
    assert_eq!(
        stepper
            .register_sphere(cube, m, &mut world.colliders)
            .unwrap_err(),
        CouplingError::NotABall(cube)
    );
    let loose = world.insert_collider(ColliderBuilder::ball(R), None);
    assert_eq!(
        stepper
            .register_sphere(loose, m, &mut world.colliders)
            .unwrap_err(),
        CouplingError::NoParentBody(loose)
    );
    let no_body = RigidBodyHandle::from_raw_parts(99, 0);
    assert_eq!(
        stepper
            .insert_surface(&mut world, ColliderBuilder::ball(R), Some(no_body), m)
            .unwrap_err(),
        CouplingError::UnknownBody(no_body)
    );
    // A collider registered and then removed by the user.
    let (ball_body, ball) = stepper
        .insert_sphere(&mut world, SphereBuilder::new(R, m))
        .unwrap();
    world.remove_body(ball_body);
    stepper
        .configure(&mut world.integration_parameters, DT, 0.2 * R)
        .unwrap();
    assert_eq!(
        stepper.step(&mut world).unwrap_err(),
        CouplingError::UnknownCollider(ball)
    );

    // A scene the mode cannot run, and a scene whose pair data the law refuses.
    let mut scene = ImpactScene::paper_drop(1.0);
    scene.model = SceneLaw::Thornton(Thornton::new(1e9).unwrap());
    assert!(matches!(
        scene.run(CouplingMode::Restitution),
        Err(CouplingError::Unsupported(_))
    ));
    let mut scene = ImpactScene::paper_drop(1.0);
    scene.radius = -1.0;
    assert!(matches!(scene.pair(), Err(CouplingError::Contact(_))));

    // Neighbour-list state saved from a stepper of two particles, restored into one of one.
    let fast = |n: usize| {
        let mut world = PhysicsWorld::default();
        let mut s =
            NeighbourListStepper::new(ContactModel::new(MdrElastoPlastic::paper()), Boundary::Open);
        let m = s.insert_material(grain());
        for k in 0..n {
            s.insert_sphere(SphereBuilder::new(R, m).translation(Vector::new(
                3.0 * R * k as f64,
                0.0,
                0.0,
            )))
            .unwrap();
        }
        s.configure(&mut world.integration_parameters, DT).unwrap();
        s.step(&mut world).unwrap();
        (s, world)
    };
    let (two, _) = fast(2);
    let (mut one, world) = fast(1);
    assert!(matches!(
        one.import_lists(&world, two.export_lists()),
        Err(CouplingError::StateMismatch(_))
    ));
}

/// A rapier program passes and reads rapier's own vector type (`Vector`) throughout: the
/// geometry functions give the same contact for rapier's vectors as for the law crate's, and
/// every accessor reads the same numbers as the field behind it.
#[test]
fn vectors_pass_and_read_in_rapiers_type() {
    use mdr_rapier::geometry::{sphere_half_space, sphere_sphere, SurfaceOfRevolution};
    use mdr_rapier::kernel::PairWrench;
    use nalgebra::Vector3;

    let (c1, c2) = (Vector::new(0.0, 0.0, 1.9), Vector::new(0.1, 0.0, 0.0));
    let a = sphere_sphere(c1, 1.0, c2, 1.0).unwrap();
    let b = sphere_sphere(
        &Vector3::new(0.0, 0.0, 1.9),
        1.0,
        &Vector3::new(0.1, 0.0, 0.0),
        1.0,
    )
    .unwrap();
    assert_eq!(a, b);
    // Overlap 2 − |c1 − c2|, normal along c1 − c2, point in the middle of the overlap.
    let d = c1 - c2;
    assert!((a.overlap - (2.0 - d.length())).abs() < 1e-15);
    assert!((a.normal() - d / d.length()).length() < 1e-15);
    assert!((a.point() - (c2 + a.normal() * (1.0 - 0.5 * a.overlap))).length() < 1e-15);
    assert_eq!(a.normal(), Vector::new(a.normal.x, a.normal.y, a.normal.z));

    let pose = Pose::from_translation(Vector::new(0.0, -0.5, 0.0));
    let floor = sphere_half_space(Vector::new(0.3, 0.4, 0.0), 1.0, Vector::Y, &pose).unwrap();
    assert!((floor.overlap - 0.1).abs() < 1e-15 && floor.normal() == Vector::Y);

    let wrench = PairWrench {
        force: Vector3::new(1.0, 2.0, 3.0),
        torque1: Vector3::new(-1.0, 0.0, 0.5),
        torque2: Vector3::new(0.0, 4.0, 0.0),
    };
    assert_eq!(wrench.force(), Vector::new(1.0, 2.0, 3.0));
    assert_eq!(wrench.torque1(), Vector::new(-1.0, 0.0, 0.5));
    assert_eq!(wrench.torque2(), Vector::new(0.0, 4.0, 0.0));

    // A cylinder of radius 2 about z through the origin: a unit sphere at 2.5 from the axis
    // overlaps it by 0.5.
    let cylinder =
        SurfaceOfRevolution::new(Vector::ZERO, Vector::Z, vec![(2.0, -1.0), (2.0, 1.0)]).unwrap();
    let c = cylinder
        .sphere_contact(Vector::new(2.5, 0.0, 0.0), 1.0, &Pose::IDENTITY)
        .unwrap();
    assert!((c.overlap - 0.5).abs() < 1e-15 && (c.normal() - Vector::X).length() < 1e-15);

    let boundary = Boundary::periodic_xy((0.0, 1.0), (0.0, 2.0)).unwrap();
    let wrapped = boundary.wrapped(Vector::new(1.25, -0.5, 3.0));
    assert!((wrapped - Vector::new(0.25, 1.5, 3.0)).length() < 1e-15);
    assert!(boundary.near_box(Vector::new(1.05, 1.0, 0.0), 0.1));
    assert!(!boundary.near_box(Vector::new(1.2, 1.0, 0.0), 0.1));

    let mut stepper =
        NeighbourListStepper::new(ContactModel::new(MdrElastoPlastic::paper()), Boundary::Open);
    let m = stepper.insert_material(grain());
    let i = stepper
        .insert_sphere(
            SphereBuilder::new(R, m)
                .translation(Vector::new(1.0, 2.0, 3.0))
                .linvel(Vector::new(0.0, -1.0, 0.0))
                .angvel(Vector::Z),
        )
        .unwrap();
    let p = stepper.particles_mut();
    assert_eq!(p.position_of(i), Vector::new(1.0, 2.0, 3.0));
    assert_eq!(p.linvel_of(i), Vector::new(0.0, -1.0, 0.0));
    assert_eq!(p.angvel_of(i), Vector::Z);
    p.set_position(i, Vector::X);
    p.set_linvel(i, Vector::Y);
    p.set_angvel(i, Vector::ZERO);
    assert_eq!(p.position[i], Vector3::x());
    assert_eq!(p.linvel[i], Vector3::y());
    assert_eq!(p.angvel_of(i), Vector::ZERO);
}

/// The neighbour-list path refuses, at a build, a step above the stability limit of the
/// fastest contact its particles could make: two grains approaching at 2 m/s each (4 m/s), or
/// one at 3 m/s against the floor; half the limit runs.
#[test]
fn an_unstable_step_on_the_neighbour_list_path_is_an_error() {
    let run = |dt: f64, spheres: &[(Vector, Vector)]| {
        let (mut world, mut stepper, m) = neighbour_list_on_floor();
        for &(x, v) in spheres {
            stepper
                .insert_sphere(SphereBuilder::new(R, m).translation(x).linvel(v))
                .unwrap();
        }
        stepper
            .configure(&mut world.integration_parameters, dt)
            .unwrap();
        stepper.step(&mut world).map(|_| ())
    };
    let head_on = [
        (Vector::new(-0.1, 0.5, 0.0), Vector::new(2.0, 0.0, 0.0)),
        (Vector::new(0.1, 0.5, 0.0), Vector::new(-2.0, 0.0, 0.0)),
    ];
    let pair = LawPair::sphere_on_sphere(R, &grain(), R, &grain()).unwrap();
    let limit = stable_time_step(&pair, 4.0, 1.0).unwrap().stability_limit;
    let err = run(1.01 * limit, &head_on).unwrap_err();
    assert!(
        matches!(err, CouplingError::NeighbourListTimeStepTooLarge { limit: l, speed, kind, .. }
            if (l / limit - 1.0).abs() < 1e-12 && speed == 4.0 && kind == "sphere–sphere"),
        "{err:?}"
    );
    assert!(err.to_string().contains("stable_time_step"), "{err}");
    assert_eq!(run(0.5 * limit, &head_on), Ok(()));

    let falling = [(Vector::new(0.0, 0.5, 0.0), Vector::new(0.0, -3.0, 0.0))];
    let pair = LawPair::sphere_on_half_space(R, &grain(), &grain()).unwrap();
    let limit = stable_time_step(&pair, 3.0, 1.0).unwrap().stability_limit;
    let err = run(1.01 * limit, &falling).unwrap_err();
    assert!(
        matches!(err, CouplingError::NeighbourListTimeStepTooLarge { limit: l, speed, kind, .. }
            if (l / limit - 1.0).abs() < 1e-12 && speed == 3.0 && kind == "sphere–surface"),
        "{err:?}"
    );
    assert_eq!(run(0.5 * limit, &falling), Ok(()));
}
