//! Adhesive contacts (the adhesive MDR law, docs/theory.md §9) in every rapier coupling, against
//! references that are not this code: the pull-off force `(3/2) π Δγ R` and the snap-off
//! separation `(3/4) (π² Δγ² R / E*²)^{1/3}` of JKR theory (Johnson, Kendall & Roberts 1971;
//! the law is JKR exactly in its elastic limit), and the single-impact validator (`mdr-impact`,
//! an independent time integration of the law without rapier).
//!
//! A micron glass sphere (R = 5 µm, E = 63 GPa, ν = 0.22, Δγ = 0.2 J/m²) sticks below about
//! 0.1 m/s and rebounds above it.

use mdr_contact::model::ContactModel;
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic};
use mdr_contact::{ContactPair, Material};
use mdr_impact::{Impact, NormalSpec, Route};
use mdr_rapier::neighbour_list::{Boundary, EndedContact, NeighbourListStepper};
use mdr_rapier::prelude::*;
use mdr_rapier::rapier::prelude::*;
use mdr_rapier::scenario::{CouplingMode, ImpactScene, SceneLaw, Target};
use mdr_rapier::timestep::stable_time_step;
use std::f64::consts::PI;

const RADIUS: f64 = 5e-6;
const ADHESION: f64 = 0.2;

fn glass() -> Material {
    Material::new(63e9, 0.22, 2500.0).unwrap()
}

fn model() -> AdhesiveMdr {
    AdhesiveMdr::new(MdrElastoPlastic::elastic(), ADHESION).unwrap()
}

/// JKR's pull-off force `(3/2) π Δγ R` and snap-off separation under displacement control
/// `(3/4) (π² Δγ² R / E*²)^{1/3}` of `pair`.
fn jkr(pair: &ContactPair) -> (f64, f64) {
    let (r, e) = (pair.effective_radius(), pair.effective_modulus());
    (
        1.5 * PI * ADHESION * r,
        0.75 * (PI * PI * ADHESION * ADHESION * r / (e * e)).cbrt(),
    )
}

/// What one pull-off run recorded: per step, the overlap and the normal force on the sphere
/// (from its velocity change, `m Δv / dt`, exact for symplectic Euler without gravity).
struct PullOff {
    /// Largest tensile force (N).
    tension: f64,
    /// Overlap at the first step with no force after the tension (m; negative when apart).
    release: f64,
    /// Largest overlap step `|Δδ|` on the way out (m): the resolution of `release`.
    resolution: f64,
}

impl PullOff {
    /// From `(overlap, force)` samples of one impact.
    fn of(samples: &[(f64, f64)]) -> Self {
        let tension = samples.iter().map(|s| -s.1).fold(0.0, f64::max);
        let first_tension = samples.iter().position(|s| s.1 < 0.0).expect("tension");
        let release_at = first_tension
            + samples[first_tension..]
                .iter()
                .position(|s| s.1 == 0.0)
                .expect("the contact lets go");
        let resolution = samples[first_tension..=release_at]
            .windows(2)
            .map(|w| (w[1].0 - w[0].0).abs())
            .fold(0.0, f64::max);
        Self {
            tension,
            release: samples[release_at].0,
            resolution,
        }
    }

    /// The JKR checks: the largest tension is the pull-off force to the sampling of the force
    /// minimum (where `dF/dδ = 0`, so second order in the step: measured 2e-5 at 1000 steps per
    /// contact and 0.5 m/s), and the contact lets go within one step of the snap-off
    /// separation.
    fn check(&self, pair: &ContactPair, what: &str) {
        let (pull_off, snap_off) = jkr(pair);
        let error = (self.tension - pull_off).abs() / pull_off;
        assert!(
            error < 1e-4,
            "{what}: tension {} vs JKR {pull_off} ({error:.1e})",
            self.tension
        );
        assert!(
            (self.release + snap_off).abs() <= self.resolution * 1.001,
            "{what}: let go at {} vs JKR −{snap_off} (step {})",
            self.release,
            self.resolution
        );
        assert!(self.resolution < 0.1 * snap_off, "{what}: resolved");
    }
}

/// A sphere at `speed` on a glass half-space in force mode's rapier pipeline path.
fn rapier_pipeline_pull_off(speed: f64) -> (PullOff, ContactPair) {
    let pair = ContactPair::sphere_on_half_space(RADIUS, &glass(), &glass()).unwrap();
    let dt = stable_time_step(&pair, speed, 1000.0).unwrap().time_step;
    let mut world = PhysicsWorld {
        gravity: Vector::ZERO,
        ..PhysicsWorld::default()
    };
    world.integration_parameters.length_unit = 2.0 * RADIUS;
    let mut stepper = ForceModeStepper::new(ContactModel::new(model()));
    // A prediction distance far below the snap-off separation: the narrow phase drops the pair
    // while its neck still holds, so the coupling must keep it by itself.
    stepper
        .configure(&mut world.integration_parameters, dt, 1e-12)
        .unwrap();
    let m = stepper.particles_mut().insert_material(glass());
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
            SphereBuilder::new(RADIUS, m)
                .translation(Vector::new(0.0, RADIUS + 2.5 * speed * dt, 0.0))
                .linvel(Vector::new(0.0, -speed, 0.0)),
        )
        .unwrap();
    let mass = world.bodies[ball].mass();
    let mut samples = Vec::new();
    for _ in 0..20_000 {
        let overlap = RADIUS - world.bodies[ball].translation().y;
        let v = world.bodies[ball].linvel().y;
        stepper.step(&mut world).unwrap();
        samples.push((overlap, mass * (world.bodies[ball].linvel().y - v) / dt));
        if overlap < -2.0 * jkr(&pair).1 {
            break;
        }
    }
    (PullOff::of(&samples), pair)
}

/// Two spheres approaching head-on at relative speed `speed` in the neighbour-list path, with a
/// skin of 2 % of the snap-off separation (a neck outlives its pair's listing unless the cut-off
/// covers it), the cut-off rule on or off; also returns the ended contacts.
fn neighbour_list_pair(speed: f64, cover_necks: bool) -> (PullOff, ContactPair, Energy) {
    let pair = ContactPair::sphere_on_sphere(RADIUS, &glass(), RADIUS, &glass()).unwrap();
    let dt = stable_time_step(&pair, speed, 1000.0).unwrap().time_step;
    let mut world = PhysicsWorld {
        gravity: Vector::ZERO,
        ..PhysicsWorld::default()
    };
    let mut stepper = NeighbourListStepper::new(ContactModel::new(model()), Boundary::Open)
        .skin(0.02 * jkr(&pair).1)
        .unwrap()
        .cover_necks(cover_necks)
        .record_ended_contacts(true);
    stepper
        .configure(&mut world.integration_parameters, dt)
        .unwrap();
    let m = stepper.insert_material(glass());
    let gap = 2.5 * speed * dt;
    for side in [-1.0, 1.0] {
        stepper
            .insert_sphere(
                SphereBuilder::new(RADIUS, m)
                    .translation(Vector::new(side * (RADIUS + 0.5 * gap), 0.0, 0.0))
                    .linvel(Vector::new(-side * 0.5 * speed, 0.0, 0.0)),
            )
            .unwrap();
    }
    let mass = glass().density() * 4.0 / 3.0 * PI * RADIUS.powi(3);
    let kinetic = |s: &NeighbourListStepper<AdhesiveMdr>| {
        s.particles()
            .linvel
            .iter()
            .map(|v| 0.5 * mass * v.norm_squared())
            .sum::<f64>()
    };
    let before = kinetic(&stepper);
    let mut samples = Vec::new();
    for _ in 0..20_000 {
        let p = stepper.particles();
        let overlap = 2.0 * RADIUS - (p.position[1] - p.position[0]).norm();
        let v = p.linvel[1].x;
        stepper.step(&mut world).unwrap();
        samples.push((overlap, mass * (stepper.particles().linvel[1].x - v) / dt));
        if overlap < -2.0 * jkr(&pair).1 {
            break;
        }
    }
    let mut ended: Vec<EndedContact> = Vec::new();
    stepper.take_ended_contacts(&mut ended);
    let energy = Energy {
        before,
        after: kinetic(&stepper),
        dissipated: ended.iter().map(|c| c.works.plastic).sum(),
        contacts: ended.len(),
    };
    (PullOff::of(&samples), pair, energy)
}

/// The energy books of one run.
struct Energy {
    before: f64,
    after: f64,
    /// The ended contacts' dissipated normal work (plastic and adhesive).
    dissipated: f64,
    contacts: usize,
}

#[test]
fn rapier_pipeline_path_pulls_off_at_the_jkr_force_and_snaps_off_at_its_separation() {
    for speed in [0.2, 0.5] {
        let (pull, pair) = rapier_pipeline_pull_off(speed);
        pull.check(&pair, &format!("rapier pipeline at {speed} m/s"));
    }
}

#[test]
fn neighbour_list_path_pulls_off_at_the_jkr_force_and_books_the_adhesive_work() {
    let (pull, pair, energy) = neighbour_list_pair(0.5, true);
    pull.check(&pair, "neighbour list");
    // The books close: what the spheres lost is what the contact dissipated (the adhesive
    // hysteresis of an elastic contact), to the error of the step in which the neck lets go
    // (the law books the springs' energy at the let-go overlap, the step's force acts over the
    // whole step: first order in the step, measured 1.3e-4 of the impact energy).
    assert_eq!(energy.contacts, 1);
    let lost = energy.before - energy.after;
    assert!(lost > 0.05 * energy.before, "adhesion takes energy: {lost}");
    let error = (lost - energy.dissipated).abs() / energy.before;
    assert!(
        error < 5e-4,
        "lost {lost} vs booked {} ({error:.1e})",
        energy.dissipated
    );
}

/// The negative control of the cut-off rule: with a skin far below the snap-off separation and
/// the rule off, a rebuild drops the held pair long before its neck lets go.
#[test]
fn neighbour_list_cut_off_must_cover_the_neck() {
    let (pull, pair, _) = neighbour_list_pair(0.5, false);
    let (_, snap_off) = jkr(&pair);
    assert!(
        pull.release > -0.5 * snap_off,
        "without the rule the contact is lost early: {} vs −{snap_off}",
        pull.release
    );
}

/// The single-impact validator's `e_n` of `scene` and whether it stuck.
fn validator(scene: &ImpactScene) -> (f64, bool) {
    let outcome = Impact::new(
        scene.pair().unwrap(),
        NormalSpec::Mdr(MdrElastoPlastic::elastic()),
        scene.speed,
    )
    .work_of_adhesion(ADHESION)
    .route(Route::TimeIntegration)
    .run()
    .unwrap();
    (outcome.normal_restitution, outcome.stuck)
}

fn drop(speed: f64) -> ImpactScene {
    ImpactScene {
        radius: RADIUS,
        material: glass(),
        target: Target::HalfSpace { material: glass() },
        model: SceneLaw::AdhesiveMdr(model()),
        friction: 0.0,
        speed,
        angle_degrees: 0.0,
        steps_per_contact: 1000.0,
    }
}

/// Force mode (1000 steps per contact) and restitution mode (the energy route in one impulse)
/// against the validator (2000 steps per contact): a slow impact sticks in all three, a fast one
/// rebounds with the validator's `e_n` to the integrators' step errors (measured: force mode
/// 1.3e-4 at 0.2 m/s and 4.5e-5 at 0.5 m/s, restitution mode 1.1e-5 and 8.9e-6, the
/// validator's own step error).
#[test]
fn slow_impacts_stick_and_fast_ones_rebound_with_the_validators_restitution() {
    for (speed, tolerance) in [(0.02, 0.0), (0.2, 5e-4), (0.5, 2e-4)] {
        let scene = drop(speed);
        let (reference, stuck) = validator(&scene);
        assert_eq!(stuck, speed < 0.1, "validator at {speed} m/s");
        for mode in [CouplingMode::Force, CouplingMode::Restitution] {
            let outcome = scene.run(mode).unwrap();
            assert_eq!(outcome.stuck, stuck, "{mode:?} at {speed} m/s");
            let error = (outcome.normal_restitution - reference).abs();
            assert!(
                error <= tolerance,
                "{mode:?} at {speed} m/s: e_n = {} vs validator {reference} ({error:.1e})",
                outcome.normal_restitution
            );
        }
    }
}

/// Bad input is refused with the parameter's name.
#[test]
fn negative_or_nan_work_of_adhesion_is_refused_by_name() {
    for bad in [-0.1, f64::NAN, f64::INFINITY] {
        let error = RestitutionHooks::new(MdrElastoPlastic::paper(), 0.0)
            .unwrap()
            .with_work_of_adhesion(bad)
            .unwrap_err();
        assert!(error.to_string().contains("work_of_adhesion"), "{error}");
    }
}

/// The validator's `e_n` of `pair` at `speed` with work of adhesion `gamma`, and whether it
/// stuck.
fn validator_of(pair: ContactPair, speed: f64, gamma: f64) -> (f64, bool) {
    let outcome = Impact::new(pair, NormalSpec::Mdr(MdrElastoPlastic::elastic()), speed)
        .work_of_adhesion(gamma)
        .route(Route::TimeIntegration)
        .run()
        .unwrap();
    (outcome.normal_restitution, outcome.stuck)
}

/// Speeds (m/s) of the per-pair throws: slow onto the floor, fast at the ceiling, head on.
const FLOOR_SPEED: f64 = 0.1;
const CEILING_SPEED: f64 = 1.0;
const PAIR_SPEED: f64 = 0.5;

/// Restitution-mode throws in one world of three materials: powder spheres (`Δγ`), a steel
/// floor (`Δγ_ij = 0` with the powder) and a sticky ceiling (`2Δγ` with the powder), the hooks'
/// own work of adhesion the largest (`2Δγ`). With `per_pair`, the powder–steel and
/// powder–powder pairs are bound with their own laws ([`RestitutionHooks::set_pair_normal`]);
/// without, every pair runs `2Δγ`. Returns the measured `e_n` of the floor, ceiling and
/// sphere-pair impacts.
fn restitution_throws(per_pair: bool) -> [f64; 3] {
    let law = |gamma: f64| AdhesiveMdr::new(MdrElastoPlastic::elastic(), gamma).unwrap();
    let mut hooks = RestitutionHooks::new(MdrElastoPlastic::elastic(), 0.0)
        .unwrap()
        .with_work_of_adhesion(2.0 * ADHESION)
        .unwrap();
    let powder = hooks.particles_mut().insert_material(glass());
    let steel = hooks.particles_mut().insert_material(glass());
    let sticky = hooks.particles_mut().insert_material(glass());
    if per_pair {
        hooks.set_pair_normal(powder, steel, law(0.0)).unwrap();
        hooks
            .set_pair_normal(powder, powder, law(ADHESION))
            .unwrap();
        hooks
            .set_pair_normal(sticky, powder, law(2.0 * ADHESION))
            .unwrap();
        assert_eq!(hooks.pair_normal(steel, powder).work_of_adhesion(), 0.0);
        assert_eq!(
            hooks.pair_normal(steel, steel).work_of_adhesion(),
            2.0 * ADHESION
        );
    }
    let wall = ContactPair::sphere_on_half_space(RADIUS, &glass(), &glass()).unwrap();
    let dt = wall.hertz_contact_time(FLOOR_SPEED);
    let mut world = PhysicsWorld {
        gravity: Vector::ZERO,
        ..PhysicsWorld::default()
    };
    world.integration_parameters.length_unit = 2.0 * RADIUS;
    world.integration_parameters.dt = dt;
    world.integration_parameters.normalized_max_linear_velocity = f64::MAX;
    let ceiling = 200.0 * RADIUS;
    hooks
        .insert_surface(
            &mut world,
            ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
            None,
            steel,
        )
        .unwrap();
    hooks
        .insert_surface(
            &mut world,
            ColliderBuilder::new(SharedShape::halfspace(-Vector::Y))
                .translation(Vector::new(0.0, ceiling, 0.0)),
            None,
            sticky,
        )
        .unwrap();
    let mut ball = |x: f64, y: f64, v: Vector| {
        let sphere = SphereBuilder::new(RADIUS, powder)
            .translation(Vector::new(x, y, 0.0))
            .linvel(v);
        hooks.insert_sphere(&mut world, sphere).unwrap().0
    };
    // Each starts 2.5 steps of flight from what it hits.
    let down = ball(
        0.0,
        RADIUS + 2.5 * FLOOR_SPEED * dt,
        Vector::new(0.0, -FLOOR_SPEED, 0.0),
    );
    let up = ball(
        10.0 * RADIUS,
        ceiling - RADIUS - 2.5 * CEILING_SPEED * dt,
        Vector::new(0.0, CEILING_SPEED, 0.0),
    );
    let mid = 0.5 * ceiling;
    let left = ball(20.0 * RADIUS, mid, Vector::new(0.5 * PAIR_SPEED, 0.0, 0.0));
    let right = ball(
        22.0 * RADIUS + 2.5 * PAIR_SPEED * dt,
        mid,
        Vector::new(-0.5 * PAIR_SPEED, 0.0, 0.0),
    );
    let mut impacts = 0;
    for _ in 0..20 {
        impacts += hooks.step_with(&mut world, &(), &()).unwrap().impacts;
    }
    assert_eq!(impacts, 3, "one impact per throw");
    let v = |h: RigidBodyHandle| world.bodies[h].linvel();
    [
        v(down).y / FLOOR_SPEED,
        -v(up).y / CEILING_SPEED,
        (v(right).x - v(left).x) / PAIR_SPEED,
    ]
}

/// Largest relative difference of the per-pair restitution-mode rebounds from the validator's
/// (the energy route against the validator's time integration; measured 3.3e-5, the ceiling's
/// and the sphere pair's).
const PAIR_TOLERANCE: f64 = 1e-4;

/// Restitution mode binds each material pair's own law: in one world, a powder sphere thrown
/// slowly onto a steel floor (`Δγ_ij = 0`) rebounds with the validator's non-adhesive `e_n`
/// where the sticky pair (`2Δγ`) sticks, one thrown fast at the sticky ceiling rebounds with
/// the validator's `e_n` at `2Δγ`, and two powder spheres thrown at each other with the
/// validator's sphere–sphere `e_n` at `Δγ`, each to [`PAIR_TOLERANCE`]. Negative control: the
/// same hooks with one `Δγ` (`2Δγ`) for every pair miss the references by far more (the
/// floor's sphere sticks).
#[test]
fn restitution_hooks_bind_each_material_pairs_own_work_of_adhesion() {
    let wall = ContactPair::sphere_on_half_space(RADIUS, &glass(), &glass()).unwrap();
    let spheres = ContactPair::sphere_on_sphere(RADIUS, &glass(), RADIUS, &glass()).unwrap();
    let (e_floor, stuck_floor) = validator_of(wall, FLOOR_SPEED, 0.0);
    let (e_ceiling, stuck_ceiling) = validator_of(wall, CEILING_SPEED, 2.0 * ADHESION);
    let (e_pair, stuck_pair) = validator_of(spheres, PAIR_SPEED, ADHESION);
    // The references tell the pairs' values apart: the floor throw sticks at the largest Δγ,
    // the sphere pair's rebound at 2Δγ differs from its own.
    assert!(!stuck_floor && !stuck_ceiling && !stuck_pair);
    assert!(validator_of(wall, FLOOR_SPEED, 2.0 * ADHESION).1);
    let (e_pair_wrong, _) = validator_of(spheres, PAIR_SPEED, 2.0 * ADHESION);
    assert!((e_pair_wrong / e_pair - 1.0).abs() > 100.0 * PAIR_TOLERANCE);
    let reference = [e_floor, e_ceiling, e_pair];
    let worst = |e: [f64; 3]| {
        e.iter()
            .zip(reference)
            .map(|(e, r)| (e / r - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let bound = restitution_throws(true);
    eprintln!("per pair: e_n {bound:?}, validator {reference:?}");
    assert!(worst(bound) < PAIR_TOLERANCE, "{bound:?} vs {reference:?}");
    let one = restitution_throws(false);
    eprintln!("one Δγ: e_n {one:?}");
    assert!(worst(one) > 100.0 * PAIR_TOLERANCE, "{one:?}");
    assert_eq!(one[0], 0.0, "the floor's sphere sticks at the largest Δγ");
}
