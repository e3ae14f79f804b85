//! Many-contact behaviour of force mode: energy conservation over repeated elastic bounces,
//! history bookkeeping, determinism across runs and thread counts, and settling of a pile.

use mdr_rapier::prelude::*;
use mdr_rapier::LawPair as ContactPair;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rapier3d_f64::prelude::*;

fn halfspace(normal: Vector, point: Vector) -> ColliderBuilder {
    ColliderBuilder::new(SharedShape::halfspace(normal)).translation(point)
}

/// A steel ball bouncing between two parallel steel walls (no gravity, elastic law): after 100
/// bounces its kinetic energy equals the initial one within 2e-5 (measured 5.6e-6: the elastic law
/// conserves energy up to the integrator's error at 200 steps per contact), and the history store holds
/// an entry only while the ball touches a wall.
#[test]
fn hundred_elastic_bounces_conserve_energy_and_free_history() {
    let radius = 0.635e-2;
    let gap = 2.0e-4;
    let mut world = PhysicsWorld {
        gravity: Vector::ZERO,
        ..PhysicsWorld::default()
    };
    world.integration_parameters.length_unit = 2.0 * radius;
    let mut stepper = ForceModeStepper::new(ContactModel::new(MdrElastoPlastic::elastic()));
    let steel = stepper
        .particles_mut()
        .insert_material(Material::paper_steel());
    stepper
        .insert_surface(&mut world, halfspace(Vector::Y, Vector::ZERO), None, steel)
        .unwrap();
    stepper
        .insert_surface(
            &mut world,
            halfspace(-Vector::Y, Vector::new(0.0, 2.0 * radius + gap, 0.0)),
            None,
            steel,
        )
        .unwrap();
    let v0 = 1.0;
    let (ball, _) = stepper
        .insert_sphere(
            &mut world,
            SphereBuilder::new(radius, steel)
                .translation(Vector::new(0.0, radius + 0.5 * gap, 0.0))
                .linvel(Vector::new(0.0, -v0, 0.0)),
        )
        .unwrap();
    let pair = ContactPair::sphere_on_half_space(
        radius,
        &Material::paper_steel(),
        &Material::paper_steel(),
    )
    .unwrap();
    let advice = stable_time_step(&pair, v0, 200.0).unwrap();
    stepper
        .configure(
            &mut world.integration_parameters,
            advice.time_step,
            0.1 * radius,
        )
        .unwrap();
    let mut max_entries = 0;
    let mut steps = 0u64;
    while stepper.contacts().created() < 100 || !stepper.contacts().is_empty() {
        let report = stepper.step(&mut world).unwrap();
        max_entries = max_entries.max(report.contacts);
        steps += 1;
        assert!(steps < 2_000_000, "the ball stopped bouncing");
    }
    let v = world.bodies[ball].linvel();
    let energy_ratio = v.length_squared() / (v0 * v0);
    assert!(
        (energy_ratio - 1.0).abs() < 2e-5,
        "kinetic energy after 100 bounces / initial = {energy_ratio}"
    );
    assert_eq!(stepper.contacts().created(), 100);
    assert_eq!(stepper.contacts().removed(), 100);
    assert_eq!(max_entries, 1);
    assert!(stepper.contacts().capacity() <= 4);
}

/// A soft, light test material so that piles settle in few steps.
fn soft_material() -> Material {
    Material::new(1.0e6, 0.3, 2500.0).unwrap()
}

type PileStepper = ForceModeStepper<MdrElastoPlastic, Mindlin, StiffnessViscous, EpsdRolling>;

struct Pile {
    world: PhysicsWorld,
    stepper: PileStepper,
    bodies: Vec<RigidBodyHandle>,
    radius: f64,
    half_width: f64,
}

/// `side × side × layers` spheres (radius 2 mm, slightly polydisperse, random velocities) in a
/// lattice of spacing `spacing` radii above the floor of a square box, with friction
/// coefficient `mu` (and rolling resistance when `mu > 0`).
fn pile(side: usize, layers: usize, seed: u64, spacing: f64, mu: f64) -> Pile {
    pile_with(side, layers, seed, spacing, mu, 0.0, true)
}

/// [`pile`] with a tangential dashpot `tangential_damping` × the normal one, and rolling
/// resistance (with friction) only if `rolling`.
fn pile_with(
    side: usize,
    layers: usize,
    seed: u64,
    spacing: f64,
    mu: f64,
    tangential_damping: f64,
    rolling: bool,
) -> Pile {
    let radius = 2.0e-3;
    let spacing = spacing * radius;
    let half_width = 0.5 * side as f64 * spacing + radius;
    let mut world = PhysicsWorld::default();
    world.integration_parameters.length_unit = 2.0 * radius;
    let model = ContactModel::new(MdrElastoPlastic::new(5.0e2, 0.37).unwrap())
        .with_tangential(Mindlin::new(mu).unwrap())
        .with_damping(
            StiffnessViscous::new(0.5)
                .unwrap()
                .with_tangential_ratio(tangential_damping)
                .unwrap(),
        );
    let mu_r = if mu > 0.0 && rolling { 0.05 } else { 0.0 };
    let mut stepper = ForceModeStepper::new(model).with_rolling(EpsdRolling::new(mu_r).unwrap());
    let glass = stepper.particles_mut().insert_material(soft_material());
    let walls = [
        (Vector::Y, Vector::ZERO),
        (Vector::X, Vector::new(-half_width, 0.0, 0.0)),
        (-Vector::X, Vector::new(half_width, 0.0, 0.0)),
        (Vector::Z, Vector::new(0.0, 0.0, -half_width)),
        (-Vector::Z, Vector::new(0.0, 0.0, half_width)),
    ];
    for (n, p) in walls {
        stepper
            .insert_surface(&mut world, halfspace(n, p), None, glass)
            .unwrap();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut bodies = Vec::new();
    for layer in 0..layers {
        for i in 0..side {
            for k in 0..side {
                let r = radius * rng.random_range(0.9..1.0);
                let centre = Vector::new(
                    -half_width + radius + spacing * (i as f64 + 0.5),
                    radius + spacing * (layer as f64 + 0.5),
                    -half_width + radius + spacing * (k as f64 + 0.5),
                );
                let v = Vector::new(
                    rng.random_range(-0.1..0.1),
                    rng.random_range(-0.1..0.1),
                    rng.random_range(-0.1..0.1),
                );
                let (b, _) = stepper
                    .insert_sphere(
                        &mut world,
                        SphereBuilder::new(r, glass).translation(centre).linvel(v),
                    )
                    .unwrap();
                bodies.push(b);
            }
        }
    }
    let pair =
        ContactPair::sphere_on_sphere(radius, &soft_material(), radius, &soft_material()).unwrap();
    // Fastest expected impact: the fall from the top of the column.
    let top = spacing * layers as f64;
    let v_max = (2.0 * 9.81 * top).sqrt();
    let dt = stable_time_step(&pair, v_max, 50.0).unwrap().time_step;
    stepper
        .configure(&mut world.integration_parameters, dt, 0.5 * radius)
        .unwrap();
    Pile {
        world,
        stepper,
        bodies,
        radius,
        half_width,
    }
}

fn kinetic_energy(world: &PhysicsWorld, bodies: &[RigidBodyHandle]) -> f64 {
    bodies
        .iter()
        .map(|&h| {
            let b = &world.bodies[h];
            let r = b.mass_properties().local_mprops.principal_inertia();
            let w = b.angvel();
            0.5 * b.mass() * b.linvel().length_squared()
                + 0.5 * (r.x * w.x * w.x + r.y * w.y * w.y + r.z * w.z * w.z)
        })
        .sum()
}

fn snapshot(p: &Pile) -> Vec<[u64; 6]> {
    p.bodies
        .iter()
        .map(|&h| {
            let b = &p.world.bodies[h];
            let (x, v) = (b.translation(), b.linvel());
            [x.x, x.y, x.z, v.x, v.y, v.z].map(f64::to_bits)
        })
        .collect()
}

fn run_in_pool(threads: usize, steps: usize) -> Vec<[u64; 6]> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        // A dense, frictional, rolling-resistant pile: every code path of the kernel runs.
        let mut p = pile(5, 4, 7, 1.9, 0.3);
        let mut max_contacts = 0;
        for _ in 0..steps {
            let report = p.stepper.step(&mut p.world).unwrap();
            max_contacts = max_contacts.max(report.contacts);
        }
        assert!(
            max_contacts > 100,
            "the test must have contacts ({max_contacts})"
        );
        snapshot(&p)
    })
}

#[test]
fn bit_identical_across_runs_and_thread_counts() {
    let steps = 600;
    let one = run_in_pool(1, steps);
    let two = run_in_pool(2, steps);
    let two_again = run_in_pool(2, steps);
    assert_eq!(two, two_again, "two runs with 2 threads differ");
    assert_eq!(one, two, "1 thread and 2 threads differ");
}

fn settle(side: usize, layers: usize, max_time: f64) {
    settle_with(side, layers, max_time, 0.0, 0.0);
}

/// Pour and wait until the kinetic energy is 10⁻⁶ of its peak. Frictionless by default; with
/// friction `mu` the Mindlin (and rolling) springs need the tangential dashpot, or the pile keeps
/// undamped rocking vibrations (docs/coupling.md).
fn settle_with(side: usize, layers: usize, max_time: f64, mu: f64, tangential_damping: f64) {
    let mut p = pile_with(side, layers, 11, 2.1, mu, tangential_damping, false);
    let dt = p.world.integration_parameters.dt;
    let n = p.bodies.len();
    let mut peak: f64 = 0.0;
    let mut t = 0.0;
    let mut max_store = 0;
    let mut ratio = f64::INFINITY;
    while t < max_time {
        p.stepper.step(&mut p.world).unwrap();
        t += dt;
        max_store = max_store.max(p.stepper.contacts().len());
        let ke = kinetic_energy(&p.world, &p.bodies);
        assert!(ke.is_finite(), "NaN kinetic energy at t = {t}");
        peak = peak.max(ke);
        ratio = ke / peak;
        if t > 0.05 && ratio < 1e-6 {
            break;
        }
    }
    eprintln!("{n} spheres: kinetic energy / peak = {ratio:.2e} at t = {t:.3} s");
    assert!(
        ratio < 1e-6,
        "{n} spheres: kinetic energy only decayed to {ratio:.2e} of its peak in {t:.3} s"
    );
    for &h in &p.bodies {
        let x = p.world.bodies[h].translation();
        assert!(x.is_finite(), "NaN position");
        let reach = p.half_width - 0.5 * p.radius;
        assert!(
            x.y > 0.5 * p.radius && x.x.abs() < reach && x.z.abs() < reach,
            "a sphere escaped the box: {x:?}"
        );
    }
    // Memory proportional to the contacts: at most ~6 contacts per sphere plus the walls.
    assert!(
        max_store < 8 * n,
        "{max_store} history entries for {n} spheres"
    );
}

/// CI-sized settling: 200 spheres.
#[test]
fn pile_of_200_spheres_settles_with_damping() {
    settle(10, 2, 1.5);
}

/// A frictional pile (μ = 0.3) comes to rest once the Mindlin springs have a tangential dashpot
/// (ratio 1 of the normal one): measured 10⁻⁶ of the peak kinetic energy at t = 0.39 s, against
/// 1.48 s without the dashpot (same pile, same seed), so the 0.6 s bound fails without it.
#[test]
fn frictional_pile_settles_with_the_tangential_dashpot() {
    settle_with(10, 2, 0.6, 0.3, 1.0);
}

/// The full settling test: 1,000 spheres (`cargo test --release -- --ignored`).
#[test]
#[ignore]
fn pile_of_1000_spheres_settles_with_damping() {
    settle(10, 10, 5.0);
}
