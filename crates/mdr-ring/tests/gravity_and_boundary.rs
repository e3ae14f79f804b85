//! Shear-periodic images and the optional self-gravity: the nearest image used by the gravity sum
//! is one of the boundary's images; mutual accelerations conserve momentum and point at the
//! nearest image; wrapping a particle keeps its epicycle (guiding centre relative to the box).

use mdr_ring::boundary::ShearingBox;
use mdr_ring::prelude::*;
use rapier3d_f64::math::Vector;

fn domain() -> ShearingBox {
    ShearingBox::new(HillFrame::new(REBOUND_OMEGA).unwrap(), 100.0, 80.0).unwrap()
}

#[test]
fn nearest_image_is_one_of_the_boundary_images() {
    let d = domain();
    let t = 3.7e4; // shear offset S = (3/2) Ω L t ≈ 729 m, many box lengths
    let a = Vector::new(-48.0, 30.0, 0.5);
    let b = Vector::new(47.0, -35.0, -0.5);
    let sep = SelfGravity::nearest_image(&d, a, b, t);
    let mut images = Vec::new();
    d.images_near_box(b, Vector::ZERO, t, 60.0, &mut images);
    let closest = images
        .iter()
        .map(|im| im.position - a)
        .min_by(|p, q| p.length().total_cmp(&q.length()))
        .unwrap();
    assert!((closest - sep).length() < 1e-9, "{closest:?} vs {sep:?}");
    assert!(sep.length() < 0.5 * (100f64.hypot(80.0)));
}

#[test]
fn pair_gravity_conserves_momentum_and_attracts() {
    let d = domain();
    let mut p = Particles::default();
    p.push(Vector::new(-49.0, 0.0, 0.0), Vector::ZERO, 1.0, 2.0e6);
    p.push(Vector::new(49.0, 1.0, 0.0), Vector::ZERO, 2.0, 5.0e6);
    let g = SelfGravity::default();
    let acc = g.accelerations(&d, &p, 0.0);
    let momentum = acc[0] * p.mass[0] + acc[1] * p.mass[1];
    assert!(momentum.length() < 1e-12 * (acc[0].length() * p.mass[0]));
    // Across the radial boundary the nearest image of particle 1 is at x = −51: pull towards −x.
    assert!(acc[0].x < 0.0 && acc[1].x > 0.0);
    // Plummer softening: |a| = G m |d| / (|d|² + ε²)^{3/2}, |d|² = 2² + 1².
    let r2 = 2.0f64 * 2.0 + 1.0 + g.softening * g.softening;
    let expected = g.constant * p.mass[1] * 5f64.sqrt() / r2.powf(1.5);
    assert!((acc[0].length() - expected).abs() < 1e-9 * expected);
}

#[test]
fn wrapping_keeps_the_epicycle_of_a_free_particle() {
    // A particle leaving through x and its re-entered image have the same epicycle amplitude and
    // guiding centre relative to their boxes: x_g shifts by −L_x, ρ is unchanged.
    let d = domain();
    let f = d.frame();
    let (mut pos, mut vel) = (
        Vector::new(50.5, 10.0, 0.3),
        Vector::new(1e-3, -0.0099, 2e-4),
    );
    let (xg, rho) = (f.guiding_centre_x(pos, vel), f.epicycle_amplitude(pos, vel));
    assert!(d.wrap(&mut pos, &mut vel, 1.0e4));
    assert!(pos.x < 0.0 && pos.y >= -40.0 && pos.y < 40.0);
    assert!((f.guiding_centre_x(pos, vel) - (xg - d.lx())).abs() < 1e-9);
    assert!((f.epicycle_amplitude(pos, vel) - rho).abs() < 1e-9);
}

/// The ghosts' images: exactly the boundary images on the lower side, for particles anywhere in
/// the box (the early return for particles away from the outer and upper edges loses none), and
/// every image on the lower side lies left of or below the box.
#[test]
fn lower_side_images_are_the_lower_side_boundary_images() {
    let d = domain();
    let margin = 9.0;
    let mut found = 0;
    for k in 0..400 {
        let f = |m: u64| ((k * m) % 397) as f64 / 397.0 - 0.5;
        let p = Vector::new(f(131) * 99.9, f(277) * 79.9, f(53));
        let t = 1.3e3 * k as f64;
        let (mut all, mut lower) = (Vec::new(), Vec::new());
        d.images_near_box(p, Vector::ZERO, t, margin, &mut all);
        d.lower_side_images_near_box(p, Vector::ZERO, t, margin, &mut lower);
        all.retain(|im| im.label.is_lower_side());
        assert_eq!(all, lower, "particle {p:?} at t = {t}");
        for im in &lower {
            assert!(im.position.x < -50.0 || im.position.y < -40.0, "{im:?}");
        }
        found += lower.len();
    }
    assert!(found > 20, "{found}");
}
