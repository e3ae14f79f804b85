//! The plugin in a rapier user's own world: non-spherical bodies keep rapier's contacts, the
//! user's hooks, filters and flags survive registration, misuse is an error, and a
//! restitution-mode crater lives by the law's distance rule whatever rapier's margins.

use mdr_rapier::prelude::*;
use mdr_rapier::rapier::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

const R: f64 = 0.01;
const HALF: f64 = 0.05;

/// A soft granular material (E = 1 MPa) so that force mode runs with a coarse step.
fn grain() -> Material {
    Material::builder()
        .youngs(1.0e6)
        .poisson(0.3)
        .density(2500.0)
        .build()
        .unwrap()
}

/// Force-mode step resolving a 2 m/s impact of two grains with 50 steps.
fn grain_dt() -> f64 {
    let pair = LawPair::sphere_on_sphere(R, &grain(), R, &grain()).unwrap();
    stable_time_step(&pair, 2.0, 50.0).unwrap().time_step
}

fn hull_points() -> Vec<Vector> {
    // An irregular octahedron-like hull about 8 cm across.
    vec![
        Vector::new(0.04, 0.0, 0.0),
        Vector::new(-0.035, 0.0, 0.01),
        Vector::new(0.0, 0.03, 0.0),
        Vector::new(0.005, -0.03, 0.0),
        Vector::new(0.0, 0.0, 0.04),
        Vector::new(0.01, 0.0, -0.035),
    ]
}

/// Lowest point of a collider's AABB (m).
fn bottom(world: &PhysicsWorld, collider: ColliderHandle) -> f64 {
    world.colliders[collider].compute_aabb().mins.y
}

/// A mixed world: MDR spheres, a dynamic cuboid and a convex hull on a floor, in
/// force mode. The cuboid and the hull are registered surfaces (the spheres touch them through
/// the law); their contacts with the floor and with each other are rapier's.
#[test]
fn cuboid_and_hull_stay_on_the_floor_in_force_mode() {
    let mut world = PhysicsWorld::default();
    world.integration_parameters.length_unit = 2.0 * R;
    // Damped, so that the spheres come to rest within the run.
    let model = ContactModel::new(MdrElastoPlastic::paper())
        .with_damping(StiffnessViscous::new(0.5).unwrap());
    let mut stepper = ForceModeStepper::new(model);
    let m = stepper.particles_mut().insert_material(grain());
    stepper
        .insert_surface(
            &mut world,
            ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
            None,
            m,
        )
        .unwrap();
    let cuboid_body = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, HALF + 0.02, 0.0))
            .can_sleep(false),
    );
    let cuboid = stepper
        .insert_surface(
            &mut world,
            ColliderBuilder::cuboid(HALF, HALF, HALF).density(2500.0),
            Some(cuboid_body),
            m,
        )
        .unwrap();
    let hull_body = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.2, 0.06, 0.0))
            .can_sleep(false),
    );
    let hull = stepper
        .insert_surface_with_parent(
            ColliderBuilder::convex_hull(&hull_points())
                .unwrap()
                .density(2500.0),
            Some(hull_body),
            m,
            &mut world.colliders,
            &mut world.bodies,
        )
        .unwrap();
    // Three spheres dropped on the cuboid, one on the hull, two side by side on the floor.
    let mut spheres = Vec::new();
    for x in [-0.03, 0.0, 0.03] {
        let (b, _) = stepper
            .insert_sphere(
                &mut world,
                SphereBuilder::new(R, m).translation(Vector::new(x, 2.0 * HALF + 0.05, 0.0)),
            )
            .unwrap();
        spheres.push(b);
    }
    for c in [
        Vector::new(0.2, 0.12, 0.0),
        Vector::new(-0.2, R + 0.01, 0.0),
        Vector::new(-0.2 + 2.0 * R - 1e-4, R + 0.01, 0.0),
    ] {
        spheres.push(
            stepper
                .insert_sphere(&mut world, SphereBuilder::new(R, m).translation(c))
                .unwrap()
                .0,
        );
    }
    stepper
        .configure(&mut world.integration_parameters, grain_dt(), 0.2 * R)
        .unwrap();
    let steps = (0.4 / grain_dt()) as usize;
    let (mut rapier_pairs, mut sphere_surface, mut sphere_sphere) = (0, 0, 0);
    for _ in 0..steps {
        let report = stepper.step(&mut world).unwrap();
        rapier_pairs = rapier_pairs.max(report.rapier_pairs);
        sphere_surface = sphere_surface.max(report.sphere_surface);
        sphere_sphere = sphere_sphere.max(report.sphere_sphere);
        assert_eq!(report.unhandled, 0);
        assert_eq!(
            report.contacts,
            report.sphere_sphere + report.sphere_surface
        );
    }
    // rapier holds the cuboid and the hull on the floor (to its penetration allowance).
    assert!(
        bottom(&world, cuboid) > -2e-3,
        "cuboid sank to {}",
        bottom(&world, cuboid)
    );
    assert!(
        bottom(&world, hull) > -2e-3,
        "hull sank to {}",
        bottom(&world, hull)
    );
    assert!(world.bodies[cuboid_body].linvel().length() < 0.05);
    assert!(world.bodies[hull_body].linvel().length() < 0.05);
    // The spheres rest on the cuboid's top, the hull and the floor (law contacts).
    for &s in &spheres[..3] {
        let y = world.bodies[s].translation().y;
        assert!(
            y > 2.0 * HALF + 0.9 * R && y < 2.0 * HALF + R,
            "sphere on the cuboid at {y}"
        );
    }
    // The one dropped on the hull's apex rolls off it, onto the floor at worst.
    assert!(world.bodies[spheres[3]].translation().y > 0.9 * R);
    for &s in &spheres[4..] {
        let y = world.bodies[s].translation().y;
        assert!(y > 0.9 * R && y < R, "sphere on the floor at {y}");
    }
    assert!(
        rapier_pairs >= 2,
        "cuboid–floor and hull–floor: {rapier_pairs}"
    );
    assert!(
        sphere_surface >= 6,
        "{sphere_surface} sphere–surface contacts"
    );
    assert!(sphere_sphere >= 1, "{sphere_sphere} sphere–sphere contacts");
}

/// The same bodies in restitution mode: the hull and the cuboid stay on the floor, and the
/// sphere dropped on the cuboid bounces off it with the law's restitution.
#[test]
fn cuboid_and_hull_stay_on_the_floor_in_restitution_mode() {
    let mut world = PhysicsWorld::default();
    world.integration_parameters.length_unit = 2.0 * R;
    world.integration_parameters.dt = 1e-3;
    let mut hooks = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.3).unwrap();
    let m = hooks.particles_mut().insert_material(grain());
    hooks
        .insert_surface(
            &mut world,
            ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
            None,
            m,
        )
        .unwrap();
    let cuboid_body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
        0.0,
        HALF + 0.02,
        0.0,
    )));
    let cuboid = hooks
        .insert_surface(
            &mut world,
            ColliderBuilder::cuboid(HALF, HALF, HALF).density(2500.0),
            Some(cuboid_body),
            m,
        )
        .unwrap();
    let hull_body =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.2, 0.06, 0.0)));
    let hull = hooks
        .insert_surface(
            &mut world,
            ColliderBuilder::convex_hull(&hull_points())
                .unwrap()
                .density(2500.0),
            Some(hull_body),
            m,
        )
        .unwrap();
    let (ball, _) = hooks
        .insert_sphere(
            &mut world,
            SphereBuilder::new(R, m).translation(Vector::new(0.0, 0.3, 0.0)),
        )
        .unwrap();
    let mut impacts = 0;
    for _ in 0..1000 {
        impacts += hooks.step_with(&mut world, &(), &()).unwrap().impacts;
    }
    assert!(bottom(&world, cuboid) > -2e-3 && bottom(&world, hull) > -2e-3);
    assert!(world.bodies[ball].translation().y > 2.0 * HALF);
    assert!(impacts >= 1);
}

/// A user's filter that rejects every pair involving a collider whose user data is 7.
struct RejectTagged;

impl PhysicsHooks for RejectTagged {
    fn filter_contact_pair(&self, ctx: &PairFilterContext) -> Option<SolverFlags> {
        let tagged = |c: ColliderHandle| ctx.colliders[c].user_data == 7;
        (!tagged(ctx.collider1) && !tagged(ctx.collider2))
            .then_some(SolverFlags::COMPUTE_RIGID_IMPULSES)
    }
}

/// Drop a tagged and an untagged ball on a registered floor in `mode` with the user's filter:
/// the tagged one falls through, the other bounces.
fn filter_run(force: bool) -> (f64, f64, usize) {
    let mut world = PhysicsWorld {
        gravity: Vector::ZERO,
        ..PhysicsWorld::default()
    };
    world.integration_parameters.length_unit = 2.0 * R;
    let floor = ColliderBuilder::new(SharedShape::halfspace(Vector::Y));
    let ball = |x: f64, tag: u128, m| {
        SphereBuilder::new(R, m)
            .translation(Vector::new(x, R + 1e-3, 0.0))
            .linvel(Vector::new(0.0, -1.0, 0.0))
            .user_data(tag)
            .active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS)
    };
    let mut filtered = 0;
    let (tagged, plain);
    if force {
        let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::paper()));
        let m = stepper.particles_mut().insert_material(grain());
        stepper.insert_surface(&mut world, floor, None, m).unwrap();
        tagged = stepper
            .insert_sphere(&mut world, ball(0.0, 7, m))
            .unwrap()
            .0;
        plain = stepper
            .insert_sphere(&mut world, ball(0.1, 0, m))
            .unwrap()
            .0;
        stepper
            .configure(&mut world.integration_parameters, grain_dt(), 0.2 * R)
            .unwrap();
        for _ in 0..(0.05 / grain_dt()) as usize {
            filtered = filtered.max(
                stepper
                    .step_with(&mut world, &RejectTagged, &())
                    .unwrap()
                    .filtered,
            );
        }
    } else {
        world.integration_parameters.dt = 1e-4;
        let mut hooks = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.0).unwrap();
        let m = hooks.particles_mut().insert_material(grain());
        hooks.insert_surface(&mut world, floor, None, m).unwrap();
        tagged = hooks.insert_sphere(&mut world, ball(0.0, 7, m)).unwrap().0;
        plain = hooks.insert_sphere(&mut world, ball(0.1, 0, m)).unwrap().0;
        for _ in 0..500 {
            hooks.step_with(&mut world, &RejectTagged, &()).unwrap();
        }
    }
    (
        world.bodies[tagged].translation().y,
        world.bodies[plain].linvel().y,
        filtered,
    )
}

#[test]
fn the_users_filter_is_honoured_in_both_modes() {
    for force in [true, false] {
        let (tagged_y, plain_vy, filtered) = filter_run(force);
        assert!(
            tagged_y < -R,
            "force {force}: the rejected ball is at {tagged_y}"
        );
        assert!(
            plain_vy > 0.1,
            "force {force}: the accepted ball bounced at {plain_vy}"
        );
        if force {
            assert!(filtered >= 1, "the report counts the rejected pair");
        }
    }
}

/// A user's contact modifier that counts its calls.
#[derive(Default)]
struct CountingModifier {
    calls: AtomicUsize,
}

impl PhysicsHooks for CountingModifier {
    fn modify_solver_contacts(&self, _: &mut ContactModificationContext) {
        self.calls.fetch_add(1, Ordering::Relaxed);
    }
}

#[test]
fn the_users_hook_flags_and_groups_survive_registration() {
    let collision = InteractionGroups::new(
        Group::GROUP_3,
        Group::GROUP_1 | Group::GROUP_3,
        InteractionTestMode::And,
    );
    let solver = InteractionGroups::new(
        Group::GROUP_2,
        Group::GROUP_1 | Group::GROUP_2,
        InteractionTestMode::And,
    );
    let user_hooks = ActiveHooks::FILTER_CONTACT_PAIRS;
    let describe = |m| {
        SphereBuilder::new(R, m)
            .translation(Vector::new(0.0, 1.0, 0.0))
            .rotation(Vector::new(0.0, 0.3, 0.0))
            .collision_groups(collision)
            .solver_groups(solver)
            .active_hooks(user_hooks)
            .user_data(42)
            .body_user_data(43)
            .friction(0.7)
            .can_sleep(true)
    };
    // Restitution mode adds its flag to the user's hooks and leaves everything else.
    let mut world = PhysicsWorld::default();
    let mut hooks = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.0).unwrap();
    let m = hooks.particles_mut().insert_material(grain());
    let (b, c) = hooks.insert_sphere(&mut world, describe(m)).unwrap();
    let co = &world.colliders[c];
    assert_eq!(
        co.active_hooks(),
        user_hooks | ActiveHooks::MODIFY_SOLVER_CONTACTS
    );
    assert_eq!(co.collision_groups(), collision);
    assert_eq!(co.solver_groups(), solver);
    assert_eq!((co.user_data, co.friction()), (42, 0.7));
    let body = &world.bodies[b];
    assert_eq!(body.user_data, 43);
    assert!(
        body.activation().normalized_linear_threshold > 0.0,
        "can sleep"
    );
    assert!((body.rotation().to_scaled_axis() - Vector::new(0.0, 0.3, 0.0)).length() < 1e-12);
    assert_eq!(hooks.particles().get(c).unwrap().user_hooks, user_hooks);

    // Force mode: the same, with the coupling's group added to the solver groups only.
    let mut world = PhysicsWorld::default();
    let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::paper()));
    let m = stepper.particles_mut().insert_material(grain());
    let (_, c) = stepper.insert_sphere(&mut world, describe(m)).unwrap();
    let co = &world.colliders[c];
    assert_eq!(co.active_hooks(), user_hooks);
    assert_eq!(co.collision_groups(), collision);
    assert_eq!(co.solver_groups().filter, solver.filter);
    assert_eq!(co.solver_groups().memberships, COUPLING_SOLVER_GROUP);
    // A surface built by the user and registered afterwards keeps its flags too.
    let wall = world.insert_collider(
        ColliderBuilder::cuboid(1.0, 0.1, 1.0)
            .active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS)
            .solver_groups(solver),
        None,
    );
    stepper
        .register_surface(wall, m, &mut world.colliders)
        .unwrap();
    let co = &world.colliders[wall];
    assert_eq!(co.active_hooks(), ActiveHooks::MODIFY_SOLVER_CONTACTS);
    assert_eq!(co.solver_groups().memberships, solver.memberships);
    assert_eq!(co.solver_groups().filter, solver.filter);
}

/// The composed hooks call the user's contact modifier exactly where the user's own flags ask
/// for it, and the law's on the registered pairs.
#[test]
fn composed_hooks_call_the_users_modifier_where_the_user_asked() {
    let run = |user_flag: bool| {
        let mut world = PhysicsWorld {
            gravity: Vector::ZERO,
            ..PhysicsWorld::default()
        };
        world.integration_parameters.length_unit = 2.0 * R;
        world.integration_parameters.dt = 1e-4;
        let mut hooks = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.0).unwrap();
        let m = hooks.particles_mut().insert_material(grain());
        hooks
            .insert_surface(
                &mut world,
                ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
                None,
                m,
            )
            .unwrap();
        let mut ball = SphereBuilder::new(R, m)
            .translation(Vector::new(0.0, R + 2e-4, 0.0))
            .linvel(Vector::new(0.0, -1.0, 0.0));
        if user_flag {
            ball = ball.active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
        }
        let (b, _) = hooks.insert_sphere(&mut world, ball).unwrap();
        let user = CountingModifier::default();
        let mut impacts = 0;
        for _ in 0..20 {
            impacts += hooks.step_with(&mut world, &user, &()).unwrap().impacts;
        }
        (
            user.calls.load(Ordering::Relaxed),
            impacts,
            world.bodies[b].linvel().y,
        )
    };
    let (calls, impacts, vy) = run(true);
    assert!(
        calls > 0 && impacts == 1 && vy > 0.0,
        "{calls} {impacts} {vy}"
    );
    let (calls, impacts, vy) = run(false);
    assert!(
        calls == 0 && impacts == 1 && vy > 0.0,
        "{calls} {impacts} {vy}"
    );
}

fn steel_world() -> PhysicsWorld {
    let mut world = PhysicsWorld {
        gravity: Vector::ZERO,
        ..PhysicsWorld::default()
    };
    world.integration_parameters.length_unit = 0.0127;
    world
}

#[test]
fn a_forgotten_hook_flag_is_an_error() {
    // Restitution mode: a ball inserted by hand and registered through the particle set only.
    let mut world = steel_world();
    let mut hooks = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.0).unwrap();
    let m = hooks
        .particles_mut()
        .insert_material(Material::paper_steel());
    let (_, c) = world.insert(
        RigidBodyBuilder::dynamic(),
        ColliderBuilder::ball(0.00635).density(7800.0),
    );
    hooks
        .particles_mut()
        .register_sphere(&world.colliders, c, m)
        .unwrap();
    let err = hooks.step(&mut world).unwrap_err();
    assert!(
        matches!(err, CouplingError::MissingFlag { collider, .. } if collider == c),
        "{err}"
    );
    assert!(err.to_string().contains("MODIFY_SOLVER_CONTACTS"), "{err}");
    // Registering through the hooks adds the flag, and the step runs.
    hooks.register_sphere(c, m, &mut world.colliders).unwrap();
    hooks.step(&mut world).unwrap();

    // Force mode: the same ball without the coupling's solver group.
    let mut world = steel_world();
    let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::paper()));
    let m = stepper
        .particles_mut()
        .insert_material(Material::paper_steel());
    let (_, c) = world.insert(
        RigidBodyBuilder::dynamic(),
        ColliderBuilder::ball(0.00635).density(7800.0),
    );
    stepper
        .particles_mut()
        .register_sphere(&world.colliders, c, m)
        .unwrap();
    stepper
        .configure(&mut world.integration_parameters, 1e-7, 1e-3)
        .unwrap();
    let err = stepper.step(&mut world).unwrap_err();
    assert!(matches!(err, CouplingError::MissingFlag { .. }), "{err}");
    stepper.register_sphere(c, m, &mut world.colliders).unwrap();
    stepper.step(&mut world).unwrap();
}

/// Restitution mode inside the user's own `PhysicsPipeline::step`
/// loop. Without `prepare` the hooks do not know the step; `maintain` says so.
#[test]
fn a_forgotten_time_step_is_an_error() {
    let mut world = steel_world();
    world.integration_parameters.dt = 1e-4;
    let mut hooks = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.0).unwrap();
    let m = hooks
        .particles_mut()
        .insert_material(Material::paper_steel());
    let PhysicsWorld {
        bodies,
        colliders,
        integration_parameters: params,
        physics_pipeline: pipeline,
        islands,
        broad_phase,
        narrow_phase,
        impulse_joints,
        multibody_joints,
        soft_bodies,
        ccd_solver,
        ..
    } = &mut world;
    hooks
        .insert_surface_with_parent(
            ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
            None,
            m,
            colliders,
            bodies,
        )
        .unwrap();
    let (ball, _) = hooks
        .insert_sphere_into(
            SphereBuilder::new(0.00635, m)
                .translation(Vector::new(0.0, 0.00635 + 1e-4, 0.0))
                .linvel(Vector::new(0.0, -1.0, 0.0)),
            bodies,
            colliders,
        )
        .unwrap();
    let mut step =
        |hooks: &RestitutionHooks, bodies: &mut RigidBodySet, colliders: &mut ColliderSet| {
            pipeline.step(
                Vector::ZERO,
                params,
                islands,
                broad_phase,
                narrow_phase,
                bodies,
                colliders,
                impulse_joints,
                multibody_joints,
                soft_bodies,
                ccd_solver,
                hooks,
                &(),
            )
        };
    let mut error = None;
    for _ in 0..5 {
        step(&hooks, bodies, colliders);
        if let Err(e) = hooks.maintain(colliders) {
            error = Some(e);
            break;
        }
    }
    let err = error.expect("the hooks ran without a time step");
    assert_eq!(err, CouplingError::TimeStepUnset);
    assert!(err.to_string().contains("prepare"), "{err}");
    // With `prepare` each step, the same loop bounces the ball with the law's restitution.
    bodies[ball].set_translation(Vector::new(0.0, 0.00635 + 1e-4, 0.0), true);
    bodies[ball].set_linvel(Vector::new(0.0, -1.0, 0.0), true);
    for _ in 0..5 {
        hooks.prepare(params, colliders).unwrap();
        step(&hooks, bodies, colliders);
        hooks.maintain(colliders).unwrap();
    }
    let pair =
        LawPair::sphere_on_half_space(0.00635, &Material::paper_steel(), &Material::paper_steel())
            .unwrap();
    let e = MdrElastoPlastic::paper()
        .bind(&pair)
        .unwrap()
        .impact(&MdrState::default(), pair.reduced_mass(), 1.0)
        .unwrap()
        .restitution;
    let vy = bodies[ball].linvel().y;
    assert!((vy - e).abs() < 5e-3 * e, "bounced at {vy}, law {e}");
}

/// Force mode on a world that `configure` never saw, and a step far above the contact's
/// stability limit.
#[test]
fn an_unconfigured_world_and_an_unstable_step_are_errors() {
    let build = || {
        let mut world = steel_world();
        let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::paper()));
        let m = stepper
            .particles_mut()
            .insert_material(Material::paper_steel());
        stepper
            .insert_surface(
                &mut world,
                ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
                None,
                m,
            )
            .unwrap();
        let (ball, _) = stepper
            .insert_sphere(
                &mut world,
                SphereBuilder::new(0.00635, m)
                    .translation(Vector::new(0.0, 0.00635 + 1e-5, 0.0))
                    .linvel(Vector::new(0.0, -1.0, 0.0)),
            )
            .unwrap();
        (world, stepper, ball)
    };
    let (mut world, mut stepper, _) = build();
    let err = stepper.step(&mut world).unwrap_err();
    assert!(matches!(err, CouplingError::NotConfigured(_)), "{err}");
    assert!(err.to_string().contains("configure"), "{err}");

    // 1e-4 s against a contact of about 4e-5 s at 1 m/s.
    let (mut world, mut stepper, _) = build();
    stepper
        .configure(&mut world.integration_parameters, 1e-4, 1e-3)
        .unwrap();
    let err = (0..10)
        .find_map(|_| stepper.step(&mut world).err())
        .expect("the contact begins within ten steps");
    assert!(
        matches!(err, CouplingError::TimeStepTooLarge { .. }),
        "{err}"
    );

    // The step of `stable_time_step` passes.
    let (mut world, mut stepper, ball) = build();
    let pair =
        LawPair::sphere_on_half_space(0.00635, &Material::paper_steel(), &Material::paper_steel())
            .unwrap();
    let dt = stable_time_step(&pair, 1.0, 50.0).unwrap().time_step;
    stepper
        .configure(&mut world.integration_parameters, dt, 1e-3)
        .unwrap();
    while world.bodies[ball].linvel().y < 0.0 {
        stepper.step(&mut world).unwrap();
    }
}

/// A sphere touching an unregistered collider that keeps out of the coupling's solver group
/// gets no response at all: the report names the pair. On an unregistered collider of default
/// groups, rapier holds it.
#[test]
fn a_pair_nobody_handles_is_named() {
    let mut world = PhysicsWorld::default();
    world.integration_parameters.length_unit = 2.0 * R;
    let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::paper()));
    let m = stepper.particles_mut().insert_material(grain());
    let aloof = world.insert_collider(
        ColliderBuilder::cuboid(0.1, 0.01, 0.1)
            .translation(Vector::new(0.0, -0.01, 0.0))
            .solver_groups(InteractionGroups::new(
                Group::GROUP_1,
                Group::GROUP_1,
                InteractionTestMode::And,
            )),
        None,
    );
    world.insert_collider(
        ColliderBuilder::cuboid(0.1, 0.01, 0.1).translation(Vector::new(0.5, -0.01, 0.0)),
        None,
    );
    let (sinking, c) = stepper
        .insert_sphere(
            &mut world,
            SphereBuilder::new(R, m).translation(Vector::new(0.0, R + 1e-3, 0.0)),
        )
        .unwrap();
    let (held, _) = stepper
        .insert_sphere(
            &mut world,
            SphereBuilder::new(R, m).translation(Vector::new(0.5, R + 1e-3, 0.0)),
        )
        .unwrap();
    stepper
        .configure(&mut world.integration_parameters, grain_dt(), 0.2 * R)
        .unwrap();
    let mut named = None;
    let mut rapier_pairs = 0;
    for _ in 0..(0.1 / grain_dt()) as usize {
        let report = stepper.step(&mut world).unwrap();
        rapier_pairs = rapier_pairs.max(report.rapier_pairs);
        if report.unhandled > 0 {
            named = stepper.unhandled_pairs().first().copied();
        }
    }
    let named = named.expect("the sinking sphere's pair is reported");
    assert_eq!((named.sphere, named.other), (c, aloof));
    assert!(named.to_string().contains("register it as a surface"));
    assert!(world.bodies[sinking].translation().y < R);
    assert!(world.bodies[held].translation().y > 0.9 * R);
    assert!(rapier_pairs >= 1);
}

/// Restitution mode: the crater of a ball–floor pair lives while the ball is within the
/// history reach (one effective radius) of the floor, whatever the prediction distance that
/// keeps rapier's pair alive: within it a slower second impact is elastic, beyond it a second
/// impact is a fresh one.
#[test]
fn the_second_bounce_follows_the_laws_rule_at_two_margins() {
    let r = 0.00635;
    let dt = 1e-5;
    let pair = LawPair::sphere_on_half_space(r, &Material::paper_steel(), &Material::paper_steel())
        .unwrap();
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let fresh = |v: f64| {
        law.impact(&MdrState::default(), pair.reduced_mass(), v)
            .unwrap()
            .restitution
    };
    for normalized_prediction in [0.002, 3.0] {
        let mut world = steel_world();
        world.integration_parameters.dt = dt;
        world.integration_parameters.normalized_max_linear_velocity = f64::MAX;
        world.integration_parameters.normalized_prediction_distance = normalized_prediction;
        let mut hooks = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.0).unwrap();
        let steel = hooks
            .particles_mut()
            .insert_material(Material::paper_steel());
        hooks
            .insert_surface(
                &mut world,
                ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
                None,
                steel,
            )
            .unwrap();
        let (ball, _) = hooks
            .insert_sphere(&mut world, SphereBuilder::new(r, steel))
            .unwrap();
        // Launch from `gap` above the floor at `speed`; v_out / v_in.
        let mut bounce = |gap: f64, speed: f64| {
            let b = &mut world.bodies[ball];
            b.set_translation(Vector::new(0.0, r + gap, 0.0), true);
            b.set_linvel(Vector::new(0.0, -speed, 0.0), true);
            let steps = if speed > 0.0 {
                (gap / (speed * dt)) as usize + 20
            } else {
                1
            };
            for _ in 0..steps {
                hooks.step(&mut world).unwrap();
                if world.bodies[ball].linvel().y > 0.0 {
                    break;
                }
            }
            world.bodies[ball].linvel().y / speed
        };
        let e1 = bounce(2.5 * 3.0 * dt, 3.0);
        assert!((e1 - fresh(3.0)).abs() < 5e-3 * e1, "first impact {e1}");
        // Within reach (half a radius above the floor): the crater holds the slower impact.
        let e2 = bounce(0.5 * r, 1.0);
        assert!(
            (e2 - 1.0).abs() < 1e-3,
            "margin {normalized_prediction}: second impact from within reach {e2}"
        );
        // Two radii above the floor for a step: the crater is gone, the next impact is fresh.
        bounce(2.0 * r, 0.0);
        let e3 = bounce(2.5 * 3.0 * dt, 3.0);
        assert!(
            (e3 - fresh(3.0)).abs() < 5e-3 * e3,
            "margin {normalized_prediction}: impact after leaving the reach {e3} vs {}",
            fresh(3.0)
        );
    }
}

/// Restitution mode with `FrictionRule::Colliders`: an oblique impact keeps more of its
/// tangential speed on a slippery collider than on a rough one; a uniform μ ignores them.
#[test]
fn friction_comes_from_the_colliders() {
    let slide = |rule: FrictionRule, floor_friction: f64| {
        let mut world = steel_world();
        world.integration_parameters.dt = 1e-5;
        let mut hooks =
            RestitutionHooks::with_friction_rule(MdrElastoPlastic::paper(), rule).unwrap();
        let steel = hooks
            .particles_mut()
            .insert_material(Material::paper_steel());
        hooks
            .insert_surface(
                &mut world,
                ColliderBuilder::new(SharedShape::halfspace(Vector::Y)).friction(floor_friction),
                None,
                steel,
            )
            .unwrap();
        let (ball, _) = hooks
            .insert_sphere(
                &mut world,
                SphereBuilder::new(0.00635, steel)
                    .friction(floor_friction)
                    .translation(Vector::new(0.0, 0.00635 + 2e-5, 0.0))
                    .linvel(Vector::new(1.0, -1.0, 0.0)),
            )
            .unwrap();
        for _ in 0..10 {
            hooks.step(&mut world).unwrap();
        }
        world.bodies[ball].linvel().x
    };
    let (slippery, rough) = (
        slide(FrictionRule::Colliders, 0.0),
        slide(FrictionRule::Colliders, 0.5),
    );
    assert!((slippery - 1.0).abs() < 1e-9, "frictionless: {slippery}");
    assert!(rough < 0.9, "rough: {rough}");
    let (a, b) = (
        slide(FrictionRule::Uniform(0.2), 0.0),
        slide(FrictionRule::Uniform(0.2), 0.5),
    );
    assert_eq!(a, b);
    assert!(a < 1.0);
}
