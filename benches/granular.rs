//! Throughput of the rapier coupling on a packed bed of spheres (default 10,140 = 13×13×15 FCC
//! cells) in a box under gravity:
//! - force mode: particle-steps per second and where the time goes (the plugin's force pass,
//!   rapier's collision detection, rapier's integration);
//! - restitution mode: the cost of the hook per contact (the same bed with the hook on every
//!   pair minus plain rapier, and the law's energy route alone);
//! - plain rapier on the same scene (rigid contacts, 1 and 4 solver iterations).
//!
//! Run: `cargo bench --bench granular` (add `-- --cells 13,13,15 --steps 200` to change the
//! size, `--force-only` to time force mode alone, e.g. under `perf record`). A benchmark, not a test: it prints a table and asserts nothing about time.

use mdr_contact::normal::MdrState;
use mdr_rapier::prelude::*;
use mdr_rapier::rapier::prelude::*;
use mdr_rapier::rapier::rayon;
use mdr_rapier::LawPair as ContactPair;
use std::time::Instant;

const RADIUS: f64 = 2.0e-3;

fn material() -> Material {
    Material::new(5.0e6, 0.3, 2500.0).expect("valid material")
}

/// FCC sphere centres (`nx × ny × nz` conventional cells), nearest neighbours slightly
/// overlapping, resting on y = 0; and the box half-widths in x and z.
fn fcc(cells: [usize; 3]) -> (Vec<Vector>, f64, f64) {
    let a = 2.0 * std::f64::consts::SQRT_2 * RADIUS * (1.0 - 1e-4);
    let basis = [
        [0.0, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        [0.5, 0.0, 0.5],
        [0.0, 0.5, 0.5],
    ];
    let (hx, hz) = (0.5 * a * cells[0] as f64, 0.5 * a * cells[2] as f64);
    let mut centres = Vec::new();
    for i in 0..cells[0] {
        for j in 0..cells[1] {
            for k in 0..cells[2] {
                for b in basis {
                    centres.push(Vector::new(
                        -hx + a * (i as f64 + b[0] + 0.25),
                        RADIUS + a * (j as f64 + b[1]),
                        -hz + a * (k as f64 + b[2] + 0.25),
                    ));
                }
            }
        }
    }
    (centres, hx + RADIUS, hz + RADIUS)
}

fn walls(hx: f64, hz: f64) -> Vec<ColliderBuilder> {
    [
        (Vector::Y, Vector::ZERO),
        (Vector::X, Vector::new(-hx, 0.0, 0.0)),
        (-Vector::X, Vector::new(hx, 0.0, 0.0)),
        (Vector::Z, Vector::new(0.0, 0.0, -hz)),
        (-Vector::Z, Vector::new(0.0, 0.0, hz)),
    ]
    .into_iter()
    .map(|(n, p)| ColliderBuilder::new(SharedShape::halfspace(n)).translation(p))
    .collect()
}

fn time_step() -> f64 {
    let pair = ContactPair::sphere_on_sphere(RADIUS, &material(), RADIUS, &material()).unwrap();
    stable_time_step(&pair, 0.5, 50.0).unwrap().time_step
}

fn base_world() -> PhysicsWorld {
    let mut world = PhysicsWorld::default();
    world.integration_parameters.length_unit = 2.0 * RADIUS;
    world.integration_parameters.dt = time_step();
    world
}

/// Accumulated milliseconds.
#[derive(Default)]
struct Split {
    total: f64,
    plugin: f64,
    phases: [f64; 6],
    /// Process CPU time (all threads) over the timed steps, ms.
    cpu: f64,
}

/// CPU time (user + system, all threads) of this process so far, in ms, from `/proc/self/stat`
/// (10 ms resolution). Unlike wall time it does not grow when other processes share the cores.
fn cpu_ms() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|x| x.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    // Fields 14 and 15 of stat (utime, stime) are 11 and 12 after the command name.
    (ticks(11) + ticks(12)) * 10.0
}

fn force_mode(cells: [usize; 3], warmup: usize, steps: usize) -> (usize, usize, Split) {
    let (centres, hx, hz) = fcc(cells);
    let mut world = base_world();
    let model = ContactModel::new(MdrElastoPlastic::new(5.0e2, 0.37).unwrap())
        .with_tangential(Mindlin::new(0.5).unwrap())
        .with_damping(StiffnessViscous::new(0.2).unwrap());
    let mut stepper = ForceModeStepper::new(model);
    let m = stepper.particles_mut().insert_material(material());
    for w in walls(hx, hz) {
        stepper.insert_surface(&mut world, w, None, m).unwrap();
    }
    for c in &centres {
        stepper
            .insert_sphere(&mut world, SphereBuilder::new(RADIUS, m).translation(*c))
            .unwrap();
    }
    let dt = world.integration_parameters.dt;
    stepper
        .configure(&mut world.integration_parameters, dt, 0.2 * RADIUS)
        .unwrap();
    for _ in 0..warmup {
        stepper.step(&mut world).unwrap();
    }
    let mut split = Split::default();
    let mut contacts = 0;
    let cpu0 = cpu_ms();
    for _ in 0..steps {
        let t0 = Instant::now();
        stepper
            .compute_forces(&world.bodies, &world.colliders, &world.narrow_phase, dt)
            .unwrap();
        stepper.apply_forces(&mut world.bodies);
        let t1 = Instant::now();
        world.step();
        let t2 = Instant::now();
        split.plugin += (t1 - t0).as_secs_f64() * 1e3;
        split.total += (t2 - t0).as_secs_f64() * 1e3;
        let t = stepper.last_report().timings;
        for (acc, x) in split.phases.iter_mut().zip([
            t.candidates,
            t.geometry,
            t.merge,
            t.kernel,
            t.reduction,
            t.apply,
        ]) {
            *acc += x * 1e3;
        }
        contacts += stepper.contacts().len();
    }
    split.cpu = cpu_ms() - cpu0;
    (centres.len(), contacts / steps, split)
}

fn rapier_mode(
    cells: [usize; 3],
    hooks_on: bool,
    iterations: usize,
    steps: usize,
) -> (usize, Split) {
    let (centres, hx, hz) = fcc(cells);
    let mut world = base_world();
    world.integration_parameters.num_solver_iterations = iterations;
    let mut hooks =
        RestitutionHooks::new(MdrElastoPlastic::new(5.0e2, 0.37).unwrap(), 0.5).unwrap();
    let m = hooks.particles_mut().insert_material(material());
    for w in walls(hx, hz) {
        if hooks_on {
            hooks.insert_surface(&mut world, w, None, m).unwrap();
        } else {
            world.insert_collider(w, None);
        }
    }
    for c in &centres {
        let sphere = SphereBuilder::new(RADIUS, m).translation(*c);
        if hooks_on {
            hooks.insert_sphere(&mut world, sphere).unwrap();
        } else {
            let body = RigidBodyBuilder::dynamic().translation(*c).can_sleep(false);
            world.insert(body, ColliderBuilder::ball(sphere.radius).density(2500.0));
        }
    }
    for _ in 0..20 {
        hooks.step(&mut world).unwrap();
    }
    let mut split = Split::default();
    let mut contacts = 0;
    let cpu0 = cpu_ms();
    for _ in 0..steps {
        let t0 = Instant::now();
        if hooks_on {
            hooks.step(&mut world).unwrap();
        } else {
            world.step();
        }
        split.total += t0.elapsed().as_secs_f64() * 1e3;
        contacts += world
            .narrow_phase
            .contact_pairs()
            .filter(|p| p.has_any_active_contact())
            .count();
    }
    split.cpu = cpu_ms() - cpu0;
    (contacts / steps, split)
}

/// Cost of the law's energy route alone: a first impact (root solve) and a re-impact that fits
/// in the old elastic branch (the hook's early exit).
fn energy_route_cost() -> (f64, f64) {
    let pair = ContactPair::sphere_on_sphere(RADIUS, &material(), RADIUS, &material()).unwrap();
    let law = MdrElastoPlastic::new(5.0e2, 0.37)
        .unwrap()
        .bind(&pair)
        .unwrap();
    let m = pair.reduced_mass();
    let n = 200_000;
    let t0 = Instant::now();
    let mut acc = 0.0;
    for i in 0..n {
        acc += law
            .impact(&MdrState::default(), m, 0.5 + 1e-6 * i as f64)
            .expect("a finite speed")
            .restitution;
    }
    let fresh = t0.elapsed().as_secs_f64() / n as f64 * 1e9;
    let state = law
        .impact(&MdrState::default(), m, 2.0)
        .expect("a finite speed")
        .state;
    let t0 = Instant::now();
    for i in 0..n {
        let v = 0.5 + 1e-6 * i as f64;
        acc +=
            f64::from(0.5 * m * v * v <= law.stored_energy(state.max_overlap, state.max_overlap));
    }
    let early = t0.elapsed().as_secs_f64() / n as f64 * 1e9;
    std::hint::black_box(acc);
    (fresh, early)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let cells: [usize; 3] = value("--cells").map_or([13, 13, 15], |s| {
        let v: Vec<usize> = s.split(',').map(|x| x.parse().expect("cells")).collect();
        [v[0], v[1], v[2]]
    });
    let steps: usize = value("--steps").map_or(100, |s| s.parse().expect("steps"));
    let threads = rayon::current_num_threads();
    println!("granular bench: {cells:?} FCC cells, {steps} timed steps, {threads} rayon threads");

    let (n, contacts, f) = force_mode(cells, 50, steps);
    let per = |x: f64| x / steps as f64;
    println!("\n{n} spheres, dt = {:.3e} s", time_step());
    println!("| setup | wall ms/step | CPU ms/step (all threads) | particle-steps/s (wall) | touching contacts |");
    println!("|---|---|---|---|---|");
    println!(
        "| force mode (MDR + Mindlin + damping) | {:.2} | {:.1} | {:.3e} | {} |",
        per(f.total),
        per(f.cpu),
        n as f64 / (per(f.total) * 1e-3),
        contacts
    );
    let split = || {
        println!("\nforce mode, where the time goes (ms/step):");
        println!(
            "  rapier step (broad + narrow phase, integration): {:.2}",
            per(f.total - f.plugin)
        );
        println!("  plugin force pass: {:.2}, of which", per(f.plugin));
        let names = [
            "candidates",
            "geometry + sort",
            "history merge",
            "law kernel",
            "reduction",
            "apply",
        ];
        for (name, x) in names.iter().zip(f.phases) {
            println!("    {name}: {:.2}", per(x));
        }
    };
    if args.iter().any(|a| a == "--force-only") {
        split();
        return;
    }
    let (c_hooks, h) = rapier_mode(cells, true, 4, steps);
    println!(
        "| restitution mode (hook on every pair, 4 iterations) | {:.2} | {:.1} | {:.3e} | {} |",
        per(h.total),
        per(h.cpu),
        n as f64 / (per(h.total) * 1e-3),
        c_hooks
    );
    let mut plain_total = 0.0;
    for it in [1, 4] {
        let (c, p) = rapier_mode(cells, false, it, steps);
        if it == 4 {
            plain_total = per(p.cpu);
        }
        println!(
            "| plain rapier, rigid contacts, {it} iteration(s) | {:.2} | {:.1} | {:.3e} | {} |",
            per(p.total),
            per(p.cpu),
            n as f64 / (per(p.total) * 1e-3),
            c
        );
    }
    println!(
        "hook overhead over plain rapier (4 iterations): {:.0} ns CPU per touching contact per step",
        (per(h.cpu) - plain_total) * 1e6 / c_hooks.max(1) as f64
    );
    split();
    let (fresh, early) = energy_route_cost();
    println!("energy route alone: {fresh:.0} ns per first impact, {early:.1} ns per elastic re-impact check");
}
