//! The neighbour-list path against the rapier pipeline path (rapier narrow phase + rapier integration):
//! same trajectories to round-off on a small bed in a box of rapier colliders with a dynamic lid;
//! determinism for 1 and 2 threads; periodic images; LAMMPS data files.

use mdr_rapier::geometry::SurfaceOfRevolution;
use mdr_rapier::kernel::ContactWorks;
use mdr_rapier::neighbour_list::bed::{lattice_bed, Bed, BedSpec};
use mdr_rapier::neighbour_list::particles::NeighbourListParticles;
use mdr_rapier::neighbour_list::rayon::ThreadPoolBuilder;
use mdr_rapier::neighbour_list::{Boundary, ContactPartner, NeighbourListStepper};
use mdr_rapier::prelude::*;
use mdr_rapier::rapier::prelude::*;

/// Bench units: E* = 1.5e5 for two grains (E = 2.73e5, ν = 0.3), density 1, diameter 1.
fn grain() -> Material {
    let nu: f64 = 0.3;
    Material::new(1.5e5 * 2.0 * (1.0 - nu * nu), nu, 1.0).unwrap()
}

fn model() -> ContactModel<Hertz, Mindlin, HertzianViscous> {
    ContactModel::new(Hertz)
        .with_tangential(Mindlin::new(0.5).unwrap())
        .with_damping(HertzianViscous::new(50.0).unwrap())
}

/// Floor, four walls and a dynamic lid (in this collider order), then 4 × 4 × 4 spheres on a
/// jittered lattice with random velocities.
struct Scene {
    surfaces: Vec<(ColliderBuilder, Option<usize>)>,
    spheres: Vec<SphereBuilder>,
}

fn scene(material: MaterialHandle) -> Scene {
    let side = 4.4;
    let wall = |x: f64, y: f64, hx: f64, hy: f64| {
        ColliderBuilder::cuboid(hx, hy, 3.0).translation(Vector::new(x, y, 3.0))
    };
    let surfaces = vec![
        (
            ColliderBuilder::new(SharedShape::halfspace(Vector::Z)),
            None,
        ),
        (wall(-0.5, side / 2.0, 0.5, side), None),
        (wall(side + 0.5, side / 2.0, 0.5, side), None),
        (wall(side / 2.0, -0.5, side, 0.5), None),
        (wall(side / 2.0, side + 0.5, side, 0.5), None),
        (ColliderBuilder::cuboid(0.6, 0.6, 0.1).density(1.0), Some(0)),
    ];
    let mut seed = 7u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut spheres = Vec::new();
    for k in 0..64 {
        let (ix, iy, iz) = (k % 4, (k / 4) % 4, k / 16);
        spheres.push(
            SphereBuilder::new(0.5, material)
                .translation(Vector::new(
                    0.6 + 1.07 * ix as f64 + 0.04 * rnd(),
                    0.6 + 1.07 * iy as f64 + 0.04 * rnd(),
                    0.52 + 1.03 * iz as f64 + 0.02 * rnd(),
                ))
                .linvel(Vector::new(rnd(), rnd(), rnd()))
                .angvel(Vector::new(rnd(), rnd(), rnd())),
        );
    }
    Scene { surfaces, spheres }
}

fn lid_body() -> RigidBodyBuilder {
    RigidBodyBuilder::dynamic()
        .translation(Vector::new(2.2, 2.2, 4.25))
        .linvel(Vector::new(0.0, 0.0, -1.0))
        .can_sleep(false)
}

/// How far the neighbour-list path strayed from the rapier pipeline path over a run of the box scene.
struct Comparison {
    max_dx: f64,
    max_dv: f64,
    lid_dz: f64,
    sphere_contacts_per_step: f64,
    surface_contacts_per_step: f64,
    rebuilds: u64,
    lid_vz: f64,
    /// Largest `d_max / u_c` (normal law's largest overlap over its yield overlap) of the
    /// rapier pipeline path's sphere contacts at any step: > 1 when plasticity was reached.
    max_plastic_ratio: f64,
}

/// The box scene run `steps` steps on both paths with `model` and `rolling`.
fn compare_paths<N, D, R>(
    model: ContactModel<N, Mindlin, D>,
    rolling: R,
    steps: usize,
) -> Comparison
where
    N: NormalModel + Clone,
    N::Law: Clone,
    D: DampingModel + Clone,
    D::Law: Clone,
    R: RollingModel + Clone,
    R::Law: Clone,
{
    let dt = 1e-4;
    // Plain path: spheres are rapier bodies, candidates from the narrow phase.
    let mut plain_world = PhysicsWorld {
        gravity: Vector::new(0.0, 0.0, -1.0),
        ..PhysicsWorld::default()
    };
    let mut plain = ForceModeStepper::new(model.clone()).with_rolling(rolling.clone());
    let m = plain.particles_mut().insert_material(grain());
    plain
        .configure(&mut plain_world.integration_parameters, dt, 0.05)
        .unwrap();
    let sc = scene(m);
    let plain_lid = plain_world.insert_body(lid_body());
    for (c, parent) in &sc.surfaces {
        plain
            .insert_surface(&mut plain_world, c.clone(), parent.map(|_| plain_lid), m)
            .unwrap();
    }
    let plain_bodies: Vec<_> = sc
        .spheres
        .iter()
        .map(|s| plain.insert_sphere(&mut plain_world, *s).unwrap().0)
        .collect();

    // Neighbour-list path: spheres in the plugin's arrays, the same rapier colliders and lid.
    let mut fast_world = PhysicsWorld {
        gravity: Vector::new(0.0, 0.0, -1.0),
        ..PhysicsWorld::default()
    };
    let mut fast = NeighbourListStepper::new(model, Boundary::Open)
        .with_rolling(rolling)
        .skin(0.1)
        .unwrap();
    let fm = fast.insert_material(grain());
    fast.configure(&mut fast_world.integration_parameters, dt)
        .unwrap();
    let fast_lid = fast_world.insert_body(lid_body());
    for (c, parent) in &sc.surfaces {
        fast.insert_surface(&mut fast_world, c.clone(), parent.map(|_| fast_lid), fm)
            .unwrap();
    }
    for s in &sc.spheres {
        fast.insert_sphere(*s).unwrap();
    }

    let (mut max_dx, mut max_dv, mut max_plastic_ratio) = (0.0f64, 0.0f64, 0.0f64);
    let (mut sphere_contacts, mut surface_contacts) = (0, 0);
    for _ in 0..steps {
        plain.step(&mut plain_world).unwrap();
        for e in plain.contacts().entries() {
            let ratio =
                e.law.normal.max_overlap(&e.history.contact.normal) / e.law.normal.yield_overlap();
            max_plastic_ratio = max_plastic_ratio.max(ratio);
        }
        let report = fast.step(&mut fast_world).unwrap();
        sphere_contacts += report.sphere_contacts;
        surface_contacts += report.surface_contacts;
        let p = fast.particles();
        for (k, h) in plain_bodies.iter().enumerate() {
            let b = &plain_world.bodies[*h];
            let x = b.translation();
            let v = b.linvel();
            max_dx = max_dx.max(
                (x.x - p.position[k].x)
                    .abs()
                    .max((x.y - p.position[k].y).abs())
                    .max((x.z - p.position[k].z).abs()),
            );
            max_dv = max_dv.max(
                (v.x - p.linvel[k].x)
                    .abs()
                    .max((v.y - p.linvel[k].y).abs())
                    .max((v.z - p.linvel[k].z).abs()),
            );
        }
    }
    let lid_dz = (plain_world.bodies[plain_lid].translation().z
        - fast_world.bodies[fast_lid].translation().z)
        .abs();
    let c = Comparison {
        max_dx,
        max_dv,
        lid_dz,
        sphere_contacts_per_step: sphere_contacts as f64 / steps as f64,
        surface_contacts_per_step: surface_contacts as f64 / steps as f64,
        rebuilds: fast.rebuilds(),
        lid_vz: fast_world.bodies[fast_lid].linvel().z,
        max_plastic_ratio,
    };
    println!(
        "max |Δx| = {:e}, max |Δv| = {:e}, lid |Δz| = {:e}, rebuilds {}, sphere contacts/step \
         {:.1}, surface contacts/step {:.1}, max d_max/u_c {:.2}",
        c.max_dx,
        c.max_dv,
        c.lid_dz,
        c.rebuilds,
        c.sphere_contacts_per_step,
        c.surface_contacts_per_step,
        c.max_plastic_ratio
    );
    c
}

/// The comparison is not vacuous (contacts of both kinds, several list rebuilds, the lid came
/// down onto the spheres), and the paths agree to round-off: rapier applies the torque through
/// its world inverse-inertia matrix and a gyroscopic correction that are exact only up to
/// rounding for a sphere; nothing else differs. Positions are of order 1.
fn assert_round_off(c: &Comparison) {
    assert!(c.sphere_contacts_per_step > 3.0);
    assert!(c.surface_contacts_per_step > 1.0);
    assert!(c.rebuilds > 2);
    // Free fall would end at v_z = −1 − g t = −1.3: the spheres pushed the lid back.
    assert!(c.lid_vz > -1.2);
    assert!(c.max_dx < 1e-9, "positions differ by {:e}", c.max_dx);
    assert!(c.max_dv < 1e-7, "velocities differ by {:e}", c.max_dv);
    assert!(c.lid_dz < 1e-9, "lid differs by {:e}", c.lid_dz);
}

#[test]
fn neighbour_list_path_reproduces_rapier_pipeline_path() {
    assert_round_off(&compare_paths(model(), NoRolling, 3000));
}

/// MDR normal law (plastic: the largest overlaps pass the yield overlap), Mindlin, Hertzian
/// damping with a tangential dashpot, rolling resistance.
#[test]
fn neighbour_list_path_reproduces_rapier_pipeline_path_with_mdr_damping_and_rolling() {
    let model = ContactModel::new(MdrElastoPlastic::new(10.0, 0.37).unwrap())
        .with_tangential(Mindlin::new(0.5).unwrap())
        .with_damping(
            HertzianViscous::new(50.0)
                .unwrap()
                .with_tangential_ratio(0.5)
                .unwrap(),
        );
    let c = compare_paths(model, EpsdRolling::new(0.1).unwrap(), 3000);
    assert_round_off(&c);
    assert!(c.max_plastic_ratio > 1.0, "no plastic contact");
}

/// Thornton's normal law (plastic) with the stiffness-proportional dashpot and a tangential
/// dashpot.
#[test]
fn neighbour_list_path_reproduces_rapier_pipeline_path_with_thornton_and_stiffness_damping() {
    let model = ContactModel::new(Thornton::new(3000.0).unwrap())
        .with_tangential(Mindlin::new(0.3).unwrap())
        .with_damping(
            StiffnessViscous::new(0.2)
                .unwrap()
                .with_tangential_ratio(1.0)
                .unwrap(),
        );
    let c = compare_paths(model, NoRolling, 3000);
    assert_round_off(&c);
    assert!(c.max_plastic_ratio > 1.0, "no plastic contact");
}

/// Hertz without damping, with rolling resistance.
#[test]
fn neighbour_list_path_reproduces_rapier_pipeline_path_with_hertz_and_rolling() {
    let model = ContactModel::new(Hertz)
        .with_tangential(Mindlin::new(0.5).unwrap())
        .with_damping(NoDamping);
    assert_round_off(&compare_paths(model, EpsdRolling::new(0.2).unwrap(), 3000));
}

/// Two runs' spheres are in the same place with the same velocities and spins, to the bit.
fn assert_same_motion(a: &NeighbourListParticles, b: &NeighbourListParticles) {
    assert_eq!(a.position, b.position);
    assert_eq!(a.linvel, b.linvel);
    assert_eq!(a.angvel, b.angvel);
}

fn periodic_run(bed: &Bed, steps: usize) -> NeighbourListStepper<Hertz, Mindlin, HertzianViscous> {
    let (mut fast, mut world) = periodic_setup(bed);
    for _ in 0..steps {
        fast.step(&mut world).unwrap();
    }
    fast
}

fn periodic_setup(
    bed: &Bed,
) -> (
    NeighbourListStepper<Hertz, Mindlin, HertzianViscous>,
    PhysicsWorld,
) {
    periodic_setup_with(bed, kick)
}

/// The starting velocity of sphere `k` in the beds of these tests: down at 0.5, and sideways
/// by up to 0.15 each way, varying from sphere to sphere; no spin.
fn kick(k: usize) -> (Vector, Vector) {
    let linvel = Vector::new(
        0.3 * ((k * 7919) % 13) as f64 / 13.0 - 0.15,
        0.3 * ((k * 104729) % 11) as f64 / 11.0 - 0.15,
        -0.5,
    );
    (linvel, Vector::ZERO)
}

/// The periodic bed of [`periodic_setup`] with sphere `k` starting at the velocity and angular
/// velocity `kick(k)`.
fn periodic_setup_with(
    bed: &Bed,
    kick: impl Fn(usize) -> (Vector, Vector),
) -> (
    NeighbourListStepper<Hertz, Mindlin, HertzianViscous>,
    PhysicsWorld,
) {
    let boundary = Boundary::periodic_xy((bed.lo[0], bed.hi[0]), (bed.lo[1], bed.hi[1])).unwrap();
    bed_setup(bed, boundary, 0.1, kick)
}

/// The spheres of `bed` in `boundary` on a floor, with neighbour skin `skin`, sphere `k`
/// starting at the velocity and angular velocity `kick(k)`.
fn bed_setup(
    bed: &Bed,
    boundary: Boundary,
    skin: f64,
    kick: impl Fn(usize) -> (Vector, Vector),
) -> (
    NeighbourListStepper<Hertz, Mindlin, HertzianViscous>,
    PhysicsWorld,
) {
    let mut fast = NeighbourListStepper::new(model(), boundary)
        .skin(skin)
        .unwrap();
    let m = fast.insert_material(grain());
    let mut world = PhysicsWorld {
        gravity: Vector::new(0.0, 0.0, -1.0),
        ..PhysicsWorld::default()
    };
    fast.configure(&mut world.integration_parameters, 1e-4)
        .unwrap();
    fast.insert_surface(
        &mut world,
        ColliderBuilder::new(SharedShape::halfspace(Vector::Z)),
        None,
        m,
    )
    .unwrap();
    for (k, p) in bed.position.iter().enumerate() {
        let (linvel, angvel) = kick(k);
        fast.insert_sphere(
            SphereBuilder::new(0.5, m)
                // Layers squeezed to 0.99 apart, the bottom one on the floor: contacts at once.
                .translation(Vector::new(p.x, p.y, 0.49 + (p.z - 0.55) * 0.9))
                .linvel(linvel)
                .angvel(angvel),
        )
        .unwrap();
    }
    (fast, world)
}

/// `bed` with its spheres in a scrambled order: neighbours in space far apart in index.
fn scrambled(bed: &Bed) -> Bed {
    let n = bed.len();
    // A fixed permutation: i -> (i * 7919) mod n, with n prime to 7919.
    assert_ne!(n % 7919, 0);
    let order: Vec<usize> = (0..n).map(|i| (i * 7919) % n).collect();
    Bed {
        position: order.iter().map(|&k| bed.position[k]).collect(),
        diameter: order.iter().map(|&k| bed.diameter[k]).collect(),
        density: order.iter().map(|&k| bed.density[k]).collect(),
        ..bed.clone()
    }
}

/// The same run with 1, 2 and 3 threads gives the same bits, with the spheres in lattice order
/// and in a scrambled one (each particle's partners then spread over the whole list, and over
/// the chunks of the parallel pair loop).
#[test]
fn neighbour_list_path_is_deterministic_for_one_and_two_threads() {
    let lattice = lattice_bed(&BedSpec {
        count: 3000,
        ..BedSpec::default()
    })
    .unwrap();
    for bed in [lattice.clone(), scrambled(&lattice)] {
        let run = |threads| {
            ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| periodic_run(&bed, 400))
        };
        let one = run(1);
        assert!(one.last_report().sphere_contacts > 50);
        assert!(one.last_report().surface_contacts > 20);
        assert!(
            bed.len() > 4 * 512 && one.pairs().len() > 2048,
            "the pair loop must split into several particle blocks and chunks"
        );
        for threads in [2, 3] {
            let other = run(threads);
            assert_same_motion(one.particles(), other.particles());
        }
    }
}

/// The pair loop sums each particle's wrenches per block of particles, and a pair whose second
/// particle lies beyond the next block has that particle's share deferred. The same bed with its
/// spheres scrambled (most shares deferred) and in lattice order (almost none) is the same
/// physical system, summed in another order: it must move the same to round-off.
#[test]
fn scrambled_order_moves_like_lattice_order() {
    let lattice = lattice_bed(&BedSpec {
        count: 3000,
        ..BedSpec::default()
    })
    .unwrap();
    let n = lattice.len();
    // `scrambled` puts lattice sphere (k * 7919) mod n at index k.
    let order: Vec<usize> = (0..n).map(|k| (k * 7919) % n).collect();
    // A kick that depends on the sphere's place, not on its index.
    let kick = |x: &nalgebra::Vector3<f64>| {
        let h = |a: f64| ((a * 12.9898).sin() * 43758.5453).rem_euclid(1.0) - 0.5;
        Vector::new(0.3 * h(x.x + 2.0 * x.z), 0.3 * h(x.y - 3.0 * x.z), -0.5)
    };
    let run = |bed: &Bed| {
        let (mut fast, mut world) =
            periodic_setup_with(bed, |k| (kick(&bed.position[k]), Vector::ZERO));
        for _ in 0..400 {
            fast.step(&mut world).unwrap();
        }
        fast
    };
    let (a, b) = (run(&lattice), run(&scrambled(&lattice)));
    assert!(a.last_report().sphere_contacts > 1000);
    let (pa, pb) = (a.particles(), b.particles());
    let (mut dv, mut dw) = (0.0f64, 0.0f64);
    for (k, &l) in order.iter().enumerate() {
        dv = dv.max((pb.linvel[k] - pa.linvel[l]).amax());
        dw = dw.max((pb.angvel[k] - pa.angvel[l]).amax());
    }
    println!("max |Δv| = {dv:e}, max |Δω| = {dw:e}");
    assert!(dv < 1e-9, "velocities differ by {dv:e}");
    assert!(dw < 1e-8, "angular velocities differ by {dw:e}");
    assert_eq!(
        a.last_report().sphere_contacts,
        b.last_report().sphere_contacts
    );
}

/// Steps run with the pool's other threads kept awake move exactly as steps whose workers sleep
/// between the passes, on one and two threads.
#[test]
fn workers_kept_awake_change_no_trajectory() {
    let bed = lattice_bed(&BedSpec {
        count: 3000,
        ..BedSpec::default()
    })
    .unwrap();
    let run = |threads: usize, awake: bool| {
        ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let steps = || periodic_run(&bed, 200);
                if awake {
                    mdr_rapier::neighbour_list::with_workers_awake(steps)
                } else {
                    steps()
                }
            })
    };
    let reference = run(1, false);
    assert!(reference.last_report().sphere_contacts > 1000);
    for (threads, awake) in [(1, true), (2, false), (2, true)] {
        let other = run(threads, awake);
        assert_same_motion(reference.particles(), other.particles());
    }
}

/// The skin decides only how often the lists are rebuilt and how many pairs they hold beyond the
/// touching ones: in open space (no periodic wrap at a rebuild) the touching pairs, their order in
/// the list and so every sum are the same for any skin, and so is every bit of the trajectory.
#[test]
fn the_skin_changes_no_trajectory_in_open_space() {
    let bed = lattice_bed(&BedSpec {
        count: 2000,
        ..BedSpec::default()
    })
    .unwrap();
    let run = |skin: f64| {
        let (mut fast, mut world) = bed_setup(&bed, Boundary::Open, skin, kick);
        for _ in 0..300 {
            fast.step(&mut world).unwrap();
        }
        fast
    };
    let (thin, thick) = (run(0.02), run(0.2));
    assert!(thin.last_report().sphere_contacts > 1000);
    assert!(
        thin.rebuilds() > thick.rebuilds(),
        "{} vs {}",
        thin.rebuilds(),
        thick.rebuilds()
    );
    assert!(thin.pairs().len() < thick.pairs().len());
    assert_same_motion(thin.particles(), thick.particles());
}

/// Switching the number of threads mid-run (and rebuilding the list with either) must not
/// change a bit; no step stores a per-pair wrench unless asked to.
#[test]
fn switching_thread_counts_mid_run_changes_nothing() {
    let bed = lattice_bed(&BedSpec {
        count: 3000,
        ..BedSpec::default()
    })
    .unwrap();
    let one_thread = ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let two_threads = ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let reference = one_thread.install(|| periodic_run(&bed, 400));
    let (mut fast, mut world) = periodic_setup(&bed);
    let mut rebuilds_in = [0u64; 2];
    for step in 0..400 {
        let parallel = (step / 37) % 2 == 1;
        let pool = if parallel { &two_threads } else { &one_thread };
        let report = pool.install(|| fast.step(&mut world).unwrap());
        rebuilds_in[usize::from(parallel)] += u64::from(report.rebuilt);
        assert_eq!(fast.pairs().wrench.len(), 0, "a step stores no wrench");
    }
    assert!(
        rebuilds_in[0] > 1 && rebuilds_in[1] > 1,
        "rebuilds in both modes: {rebuilds_in:?}"
    );
    assert_same_motion(reference.particles(), fast.particles());
}

#[test]
fn periodic_images_push_like_open_neighbours() {
    // Two spheres overlapping by 0.05 across the x boundary of a 6 × 6 box, and the same two
    // spheres side by side in open space: the same forces (round-off of the image shift).
    let run = |boundary: Boundary, x2: f64| {
        let mut fast = NeighbourListStepper::new(model(), boundary)
            .skin(0.1)
            .unwrap();
        let m = fast.insert_material(grain());
        let mut world = PhysicsWorld {
            gravity: Vector::ZERO,
            ..PhysicsWorld::default()
        };
        fast.configure(&mut world.integration_parameters, 1e-4)
            .unwrap();
        fast.insert_sphere(SphereBuilder::new(0.5, m).translation(Vector::new(0.2, 3.0, 3.0)))
            .unwrap();
        fast.insert_sphere(SphereBuilder::new(0.5, m).translation(Vector::new(x2, 3.0, 3.0)))
            .unwrap();
        fast.step(&mut world).unwrap();
        assert_eq!(fast.last_report().sphere_contacts, 1);
        fast.particles().linvel[0]
    };
    let periodic = run(
        Boundary::periodic_xy((0.0, 6.0), (0.0, 6.0)).unwrap(),
        6.0 - 0.75,
    );
    let open = run(Boundary::Open, -0.75);
    // Hertz: F = (4/3) E* √R δ^{3/2}, R = 1/4, δ = 0.05; Δv = F dt / m.
    let mass = std::f64::consts::PI / 6.0;
    let expected = 4.0 / 3.0 * 1.5e5 * 0.5 * 0.05f64.powf(1.5) * 1e-4 / mass;
    assert!(
        (periodic.x - expected).abs() < 1e-9 * expected,
        "{periodic:?} vs {expected}"
    );
    assert!((periodic - open).norm() < 1e-12 * expected);
}

#[test]
fn lammps_data_round_trip_and_tiling() {
    let bed = lattice_bed(&BedSpec {
        count: 50,
        ..BedSpec::default()
    })
    .unwrap();
    let dir_guard = tempfile::tempdir().unwrap();
    let dir = dir_guard.path().to_path_buf();
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bed.data");
    bed.write_lammps(&path).unwrap();
    let back = Bed::read_lammps(&path).unwrap();
    assert_eq!(back.len(), 50);
    for (a, b) in bed.position.iter().zip(&back.position) {
        assert_eq!(a, b, "positions must round-trip exactly");
    }
    let tiled = back.tiled(2, 3).unwrap();
    assert_eq!(tiled.len(), 300);
    assert!((tiled.hi[0] - 2.0 * bed.hi[0]).abs() < 1e-12);
    assert!((tiled.hi[1] - 3.0 * bed.hi[1]).abs() < 1e-12);
    std::fs::write(&path, "x\n\n5 atoms\n").unwrap();
    assert!(Bed::read_lammps(&path).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn orientation_tracking_does_not_change_sphere_trajectories() {
    // Spheres: contact forces and torques do not depend on orientation, so switching its
    // integration off must leave positions and velocities bit for bit the same, on the serial
    // (one-thread) and the parallel path alike.
    let bed = lattice_bed(&BedSpec {
        count: 300,
        ..BedSpec::default()
    })
    .unwrap();
    let run = |threads: usize, orientation: bool| {
        ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let (fast, mut world) = periodic_setup_with(&bed, |k| {
                    (Vector::ZERO, Vector::new(0.0, 0.0, 0.1 * (k % 5) as f64))
                });
                let mut fast = fast.track_orientation(orientation);
                for _ in 0..300 {
                    fast.step(&mut world).unwrap();
                }
                fast
            })
    };
    for threads in [1, 2] {
        let on = run(threads, true);
        let off = run(threads, false);
        assert!(on.last_report().sphere_contacts > 50);
        assert_same_motion(on.particles(), off.particles());
        // The tracked orientations turned; the untracked ones did not.
        let turned = |f: &NeighbourListStepper<Hertz, Mindlin, HertzianViscous>| {
            f.particles()
                .rotation
                .iter()
                .filter(|q| q.w < 1.0 - 1e-12)
                .count()
        };
        assert!(turned(&on) > 100);
        assert_eq!(turned(&off), 0);
    }
}

/// Timing the parts of the steps reads the clock and changes no bit of the trajectory; every
/// step is counted once, every part that ran has time, and the parts add up to no more than the
/// steps took.
#[test]
fn timing_the_steps_changes_no_trajectory_and_accounts_for_every_part() {
    let bed = lattice_bed(&BedSpec {
        count: 300,
        ..BedSpec::default()
    })
    .unwrap();
    let plain = periodic_run(&bed, 300);
    let (mut timed, mut world) = periodic_setup(&bed);
    assert!(timed.step_timings().is_none(), "timing is off by default");
    timed.time_steps(true);
    let start = std::time::Instant::now();
    for _ in 0..300 {
        timed.step(&mut world).unwrap();
    }
    let elapsed = start.elapsed();
    assert_same_motion(plain.particles(), timed.particles());
    let t = *timed.step_timings().unwrap();
    assert_eq!(t.steps, 300);
    assert!(timed.rebuilds() >= 2, "the first step and later ones build");
    for (part, d) in [
        ("builds", t.builds),
        ("surfaces", t.surfaces),
        ("pairs", t.pairs),
        ("integration", t.integration),
        ("rapier", t.rapier),
    ] {
        assert!(d > std::time::Duration::ZERO, "no time for {part}: {t:?}");
    }
    assert!(t.total() <= elapsed, "{t:?} against {elapsed:?}");
    timed.time_steps(false);
    assert!(timed.step_timings().is_none());
}

#[test]
fn dropping_the_work_books_mid_run_changes_no_trajectory() {
    // The friction and damping books are diagnostics: a stepper that drops them halfway keeps
    // every pair's normal and tangential history and follows the same trajectory bit for bit,
    // on the serial and the parallel path alike; its reports then give NaN for those works.
    let bed = lattice_bed(&BedSpec {
        count: 1000,
        ..BedSpec::default()
    })
    .unwrap();
    for threads in [1, 2] {
        let pool = ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let reference = pool.install(|| periodic_run(&bed, 300));
        let (mut fast, mut world) = periodic_setup(&bed);
        pool.install(|| {
            for _ in 0..150 {
                fast.step(&mut world).unwrap();
            }
        });
        let booked = fast.pairs().history.clone();
        let booked_bytes = fast.memory_bytes();
        let damped = booked
            .iter()
            .filter(|h| h.contact.books.damping_work > 0.0)
            .count();
        let sheared = booked
            .iter()
            .filter(|h| h.contact.tangential.displacement.norm() > 0.0)
            .count();
        assert!(
            damped > 100 && sheared > 100,
            "{damped} damped, {sheared} sheared"
        );
        let mut fast = fast.without_work_books();
        assert!(fast.memory_bytes() < booked_bytes);
        for (before, after) in booked.iter().zip(&fast.pairs().history) {
            assert_eq!(before.contact.normal, after.contact.normal);
            assert_eq!(before.contact.tangential, after.contact.tangential);
        }
        pool.install(|| {
            for _ in 150..300 {
                fast.step(&mut world).unwrap();
            }
        });
        assert_same_motion(reference.particles(), fast.particles());
        let pairs = fast.pairs();
        let q = (0..pairs.len()).find(|&q| pairs.active[q]).unwrap();
        let law = fast.sphere_law(pairs.i[q] as usize, pairs.j[q] as usize);
        let report = law.report(&pairs.history[q].contact, 1e-3);
        assert!(report.friction_work.is_nan() && report.damping_work.is_nan());
        assert!(report.max_overlap > 0.0);
    }
}

#[test]
fn rolling_resistance_can_be_added_to_a_filled_stepper() {
    // `with_rolling` after the spheres are in: the laws are bound again and the lists found again
    // at the next step. With μ_r = 0 the run is the one without rolling resistance, bit for bit;
    // with μ_r > 0 the rolling springs load and the spinning spheres turn differently.
    let bed = lattice_bed(&BedSpec {
        count: 300,
        ..BedSpec::default()
    })
    .unwrap();
    let spin = |k: usize| (Vector::ZERO, Vector::new(0.3 * (k % 7) as f64, 0.0, 0.0));
    let (mut plain, mut world) = periodic_setup_with(&bed, spin);
    for _ in 0..200 {
        plain.step(&mut world).unwrap();
    }
    let run = |mu_r: f64| {
        let (fast, mut world) = periodic_setup_with(&bed, spin);
        let mut fast = fast.with_rolling(EpsdRolling::new(mu_r).unwrap());
        for _ in 0..200 {
            fast.step(&mut world).unwrap();
        }
        fast
    };
    let free = run(0.0);
    assert_eq!(free.particles().position, plain.particles().position);
    assert_eq!(free.particles().angvel, plain.particles().angvel);
    let resisted = run(0.1);
    let loaded = resisted
        .pairs()
        .history
        .iter()
        .filter(|h| h.rolling.torque.norm() > 0.0)
        .count();
    assert!(loaded > 50, "{loaded} loaded rolling springs");
    assert_ne!(resisted.particles().angvel, plain.particles().angvel);
}

#[test]
fn ended_contacts_carry_their_whole_books_once() {
    // Two spheres in an oblique, damped, frictional collision in zero gravity, then apart: the
    // stepper hands over the pair once, when it separates, with the works its history had
    // booked at its last update (friction and damping dissipated, and the spring's stiffness
    // energy, released when the contact opened: all non-zero here).
    let run = |record: bool| {
        let mut fast = NeighbourListStepper::new(model(), Boundary::Open)
            .skin(0.1)
            .unwrap()
            .record_ended_contacts(record);
        let m = fast.insert_material(grain());
        let mut world = PhysicsWorld {
            gravity: Vector::ZERO,
            ..PhysicsWorld::default()
        };
        fast.configure(&mut world.integration_parameters, 1e-4)
            .unwrap();
        fast.insert_sphere(SphereBuilder::new(0.5, m)).unwrap();
        fast.insert_sphere(
            SphereBuilder::new(0.5, m)
                .translation(Vector::new(1.005, 0.3, 0.0))
                .linvel(Vector::new(-1.0, 0.4, 0.0)),
        )
        .unwrap();
        let mut live = None;
        let mut ended = Vec::new();
        let mut steps_in_contact = 0;
        for _ in 0..4000 {
            fast.step(&mut world).unwrap();
            fast.take_ended_contacts(&mut ended);
            let pairs = fast.pairs();
            if let Some(q) = (0..pairs.len()).find(|&q| pairs.active[q]) {
                let (law, rolling) = fast.sphere_pair_laws(0, 1);
                live = Some(ContactWorks::of(law, rolling, &pairs.history[q]));
                steps_in_contact += 1;
            }
        }
        (live, ended, steps_in_contact)
    };
    let (live, ended, steps_in_contact) = run(true);
    let live = live.expect("the spheres touched");
    assert!(steps_in_contact > 20, "{steps_in_contact} steps in contact");
    assert_eq!(ended.len(), 1, "{ended:?}");
    let e = ended[0];
    assert_eq!((e.particle, e.partner), (0, ContactPartner::Sphere(1)));
    assert_eq!(e.works, live);
    assert!(
        e.works.friction > 0.0 && e.works.damping > 0.0,
        "{:?}",
        e.works
    );
    assert!(e.works.tangential_stiffness != 0.0, "{:?}", e.works);
    // Not recorded unless asked.
    assert!(run(false).1.is_empty());
}

/// A surface of revolution registered on the neighbour-list path: spheres inside an exact cylinder (a
/// bounding cuboid as the rapier collider) touch it at its radius whatever their azimuth, also at
/// the corners of a polygon that flat pieces would leave there; the stepper's candidate search
/// and contacts both go through the closed form.
#[test]
fn spheres_touch_an_exact_cylinder_at_its_radius_in_every_direction() {
    let mut world = PhysicsWorld {
        gravity: Vector::ZERO,
        ..PhysicsWorld::default()
    };
    let mut fast = NeighbourListStepper::new(model(), Boundary::Open)
        .skin(0.1)
        .unwrap();
    let m = fast.insert_material(grain());
    fast.configure(&mut world.integration_parameters, 1e-4)
        .unwrap();
    let body = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(5.0, 0.0, 0.0)));
    let cylinder =
        SurfaceOfRevolution::new(Vector::ZERO, Vector::Z, vec![(2.0, -5.0), (2.0, 5.0)]).unwrap();
    fast.insert_surface_of_revolution(
        &mut world,
        ColliderBuilder::cuboid(2.5, 2.5, 5.0),
        Some(body),
        m,
        cylinder,
    )
    .unwrap();
    // Azimuths at the corners of a 32-gon (odd multiples of π/32), 1.6 from the axis.
    let n = 8;
    for k in 0..n {
        let phi = std::f64::consts::PI / 32.0 * (8 * k + 1) as f64;
        let at = Vector::new(5.0 + 1.6 * phi.cos(), 1.6 * phi.sin(), -4.0 + k as f64);
        fast.insert_sphere(SphereBuilder::new(0.5, m).translation(at))
            .unwrap();
    }
    fast.compute_forces(&world, false).unwrap();
    let pairs = fast.surface_pairs();
    let touching: Vec<usize> = (0..pairs.len()).filter(|&q| pairs.active[q]).collect();
    assert_eq!(touching.len(), n, "one contact per sphere");
    for q in touching {
        let c = pairs.contact[q];
        assert!((c.overlap - 0.1).abs() < 1e-12, "overlap {}", c.overlap);
        assert!(c.normal.z.abs() < 1e-12, "{:?}", c.normal);
    }
}
