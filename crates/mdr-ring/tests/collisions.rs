//! Binary collisions through the rapier restitution hook, inside the box and across the
//! shear-periodic boundaries: the outgoing normal relative velocity is `−e` times the incoming one,
//! momentum is conserved, and each impact is counted once.

use mdr_ring::boundary::ShearingBox;
use mdr_ring::prelude::*;
use mdr_ring::world::CollisionWorld;
use rapier3d_f64::math::Vector;

const OMEGA: f64 = REBOUND_OMEGA;

fn two_particles(p1: Vector, v1: Vector, p2: Vector, v2: Vector) -> Particles {
    let mut particles = Particles::default();
    let mass = |r: f64| 400.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    particles.push(p1, v1, 1.0, mass(1.0));
    particles.push(p2, v2, 2.0, mass(2.0));
    particles
}

/// Step collisions only (positions drift linearly) until the pair has separated again.
fn collide_linear<L: RestitutionLaw>(
    particles: &mut Particles,
    domain: &ShearingBox,
    law: L,
    dt: f64,
    steps: usize,
) -> u64 {
    let mut world = CollisionWorld::new(particles, law, dt, CollisionSettings::default());
    for k in 0..steps {
        world.collide(particles, domain, k as f64 * dt);
        for i in 0..particles.len() {
            let v = particles.velocity[i];
            particles.position[i] += v * dt;
        }
    }
    world.hooks().collisions()
}

fn momentum(p: &Particles) -> Vector {
    p.velocity
        .iter()
        .zip(&p.mass)
        .fold(Vector::ZERO, |acc, (v, m)| acc + *v * *m)
}

#[test]
fn head_on_collision_has_the_requested_restitution() {
    let domain = ShearingBox::new(HillFrame::new(OMEGA).unwrap(), 200.0, 200.0).unwrap();
    let dt = 47.8;
    let u = 1e-3; // approach speed (m/s)
    for e in [0.0, 0.3, 0.9, 1.0] {
        let mut particles = two_particles(
            Vector::new(-1.6, 0.0, 0.0),
            Vector::new(0.5 * u, 0.0, 0.0),
            Vector::new(1.6, 0.3, 0.1),
            Vector::new(-0.5 * u, 0.0, 0.0),
        );
        let p0 = momentum(&particles);
        let law = ConstantRestitution::new(e).unwrap();
        let count = collide_linear(&mut particles, &domain, law, dt, 40);
        assert_eq!(count, 1, "e = {e}");
        // Straight-line approach along x with offsets (0.3, 0.1) m: at contact the line of
        // centres is (√(9 − 0.3² − 0.1²), 0.3, 0.1) / 3 (radii 1 + 2 m).
        let dx = (9.0_f64 - 0.3 * 0.3 - 0.1 * 0.1).sqrt();
        let contact_normal = Vector::new(dx, 0.3, 0.1) / 3.0;
        let u_n = u * contact_normal.x;
        let out = (particles.velocity[1] - particles.velocity[0]).dot(contact_normal);
        assert!(
            (out - e * u_n).abs() < 1e-3 * u_n,
            "e = {e}: outgoing {out}, expected {}",
            e * u_n
        );
        assert!((momentum(&particles) - p0).length() < 1e-9 * p0.length().max(1.0) + 1e-9);
    }
}

#[test]
fn collision_across_the_radial_boundary_is_resolved_once() {
    // Particle 0 near the inner edge, particle 1 near the outer edge: they meet through the
    // shear-periodic boundary. Give them velocities so that, in the frame of the images, they
    // approach radially.
    let frame = HillFrame::new(OMEGA).unwrap();
    let domain = ShearingBox::new(frame, 100.0, 100.0).unwrap();
    let dt = 47.8;
    let u = 1e-3;
    // At t = 0 the image of particle 1 in box −1 is at (x − L, y) moving with vy + (3/2)ΩL.
    let mut particles = two_particles(
        Vector::new(-48.0, 10.0, 0.0),
        Vector::new(-0.5 * u, 0.0, 0.0),
        Vector::new(48.5, 10.0, 0.0),
        Vector::new(0.5 * u, -domain.shear_speed(), 0.0),
    );
    let p0 = momentum(&particles);
    let law = ConstantRestitution::new(0.5).unwrap();
    let count = collide_linear(&mut particles, &domain, law, dt, 30);
    assert_eq!(count, 1);
    // Relative radial velocity reversed and halved; momentum conserved.
    let out = particles.velocity[1].x - particles.velocity[0].x;
    assert!((out + 0.5 * u).abs() < 1e-3 * u, "outgoing {out}");
    assert!((momentum(&particles) - p0).length() < 1e-9 * p0.length());
}

/// Pairs that meet across the azimuthal boundary and across a corner of the box (through both
/// boundaries at once), with either particle on the lower side: one impact each, `e` as set,
/// momentum conserved. Ghosts exist on the lower side of each boundary only, so each such contact
/// is carried by exactly one particle–ghost pair.
#[test]
fn collisions_across_the_azimuthal_boundary_and_a_corner_are_resolved_once() {
    let frame = HillFrame::new(OMEGA).unwrap();
    let domain = ShearingBox::new(frame, 100.0, 100.0).unwrap();
    let (dt, u, e) = (47.8, 1e-3, 0.5);
    // (direction from the lower particle towards the boundary it crosses, whether it crosses
    // the radial boundary too).
    let cases = [
        (Vector::new(0.0, -1.0, 0.0), false),
        (Vector::new(-1.0, -1.0, 0.0).normalize(), true),
    ];
    for (towards, radial) in cases {
        for swap in [false, true] {
            // Gap 0.5 m between the surfaces (radii 1 and 2 m).
            let lower = Vector::new(
                if radial { -48.6 } else { 10.0 },
                if radial { -48.6 } else { -48.0 },
                0.0,
            );
            let upper = Vector::new(
                if radial { 48.9 } else { 10.0 },
                if radial { 48.9 } else { 48.5 },
                0.0,
            );
            // The upper particle's image below (and left of) the box must move towards the lower
            // one: across the radial boundary the image gains the shear speed.
            let v_upper = -towards * (0.5 * u)
                - Vector::new(0.0, if radial { domain.shear_speed() } else { 0.0 }, 0.0);
            let v_lower = towards * (0.5 * u);
            let mut particles = if swap {
                two_particles(upper, v_upper, lower, v_lower)
            } else {
                two_particles(lower, v_lower, upper, v_upper)
            };
            let p0 = momentum(&particles);
            let law = ConstantRestitution::new(e).unwrap();
            let count = collide_linear(&mut particles, &domain, law, dt, 30);
            assert_eq!(count, 1, "radial {radial}, swapped {swap}");
            let (lo, up) = if swap { (1, 0) } else { (0, 1) };
            let shear = if radial { domain.shear_speed() } else { 0.0 };
            let relative =
                particles.velocity[up] + Vector::new(0.0, shear, 0.0) - particles.velocity[lo];
            // Before: the image approached at speed u along −towards; after: it recedes at e u.
            let out = relative.dot(towards);
            assert!(
                (out - e * u).abs() < 1e-3 * u,
                "radial {radial}, swapped {swap}: outgoing {out}"
            );
            assert!((momentum(&particles) - p0).length() < 1e-9 * p0.length());
        }
    }
}

/// The same pair collides again while rapier still holds its manifold (here: velocities reversed
/// by hand three steps after the first impact, gap ≈ 7 cm, inside the 0.5 m prediction
/// distance): the second impact bounces with the law's `e` too. When the hook dropped the
/// contacts of separating pairs, their last impulse stayed on the manifold, rapier took the
/// second impact for a resting contact, and the pair stuck (outgoing speed 0; in a 300-particle
/// ring 27 of ~350 collisions over two orbits were lost that way).
#[test]
fn re_collision_of_the_same_pair_bounces_again() {
    let domain = ShearingBox::new(HillFrame::new(OMEGA).unwrap(), 200.0, 200.0).unwrap();
    let dt = 47.8;
    let u = 1e-3;
    let e = 0.5;
    let mut particles = two_particles(
        Vector::new(-1.6, 0.0, 0.0),
        Vector::new(0.5 * u, 0.0, 0.0),
        Vector::new(1.6, 0.0, 0.0),
        Vector::new(-0.5 * u, 0.0, 0.0),
    );
    let law = ConstantRestitution::new(e).unwrap();
    let mut world = CollisionWorld::new(&particles, law, dt, CollisionSettings::default());
    let mut step = |particles: &mut Particles, k: usize| {
        world.collide(particles, &domain, k as f64 * dt);
        for i in 0..particles.len() {
            let v = particles.velocity[i];
            particles.position[i] += v * dt;
        }
        world.hooks().collisions()
    };
    let mut k = 0;
    while step(&mut particles, k) == 0 {
        k += 1;
        assert!(k < 20, "no first impact");
    }
    for _ in 0..3 {
        k += 1;
        step(&mut particles, k);
    }
    let separating = particles.velocity[1].x - particles.velocity[0].x;
    assert!(
        (separating - e * u).abs() < 1e-3 * u,
        "first impact: {separating}"
    );
    for v in particles.velocity.iter_mut() {
        *v = -*v;
    }
    let mut count = 0;
    for _ in 0..12 {
        k += 1;
        count = step(&mut particles, k);
    }
    assert_eq!(count, 2);
    let out = particles.velocity[1].x - particles.velocity[0].x;
    assert!(
        (out - e * e * u).abs() < 1e-3 * u,
        "second impact: outgoing {out}, expected {}",
        e * e * u
    );
}
