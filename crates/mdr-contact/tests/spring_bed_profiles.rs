//! The spring bed with profiles other than the sphere, against analytic results:
//! flat punch (elastic stiffness `2 E* a₀`; at yield every spring yields at once and the force is
//! `π q_c a₀`, the nonlocal criterion eq. 7), cone (Sneddon, `F = 2 E* d² / (π tan β)`), and a
//! numerically transformed sphere (eq. 1) against the closed-form sphere.

use mdr_contact::normal::{NormalLaw, SpringBed, SpringBedState};
use mdr_contact::profile::{Cone, FlatPunch, NumericalProfile, Sphere};
use std::f64::consts::PI;

const E_STAR: f64 = 1.1e11;
const Q_C: f64 = 3.8e5;

#[test]
fn flat_punch_is_linear_then_yields_at_pi_q_c_a() {
    let a0 = 1e-4;
    let theta = 0.37;
    let bed = SpringBed::new(FlatPunch::new(a0).unwrap(), E_STAR, Q_C, theta, a0, 400).unwrap();
    let u_c = PI * Q_C / (2.0 * E_STAR);
    let mut state = SpringBedState::default();
    // Elastic: F = 2 a₀ E* d.
    let d = 0.5 * u_c;
    let response = bed.update(&mut state, d);
    assert!((response.force / (2.0 * a0 * E_STAR * d) - 1.0).abs() < 1e-12);
    assert!((response.stiffness / (2.0 * a0 * E_STAR) - 1.0).abs() < 1e-12);
    // At yield every spring carries f_c: F = 2a₀/Δx · (π/2) q_c Δx = π q_c a₀ (eq. 7).
    let at_yield = bed.update(&mut state, u_c).force;
    assert!((at_yield / (PI * Q_C * a0) - 1.0).abs() < 1e-12);
    // Plastic loading with hardening Θ: F = π q_c a₀ + 2 a₀ Θ (d − u_c); stiffness 2 a₀ Θ.
    let d = 3.0 * u_c;
    let plastic = bed.update(&mut state, d);
    let expected = PI * Q_C * a0 + 2.0 * a0 * theta * E_STAR * (d - u_c);
    assert!((plastic.force / expected - 1.0).abs() < 1e-12);
    assert!((plastic.stiffness / (2.0 * a0 * theta * E_STAR) - 1.0).abs() < 1e-12);
    // Unloading elastically to the residual depth (1 − θ)(d − u_c).
    let residual = (1.0 - theta) * (d - u_c);
    assert!((bed.residual_overlap(&state) / residual - 1.0).abs() < 1e-12);
    let unloaded = bed.update(&mut state, residual + 0.1 * u_c).force;
    assert!((unloaded / (2.0 * a0 * E_STAR * 0.1 * u_c) - 1.0).abs() < 1e-9);
    assert_eq!(bed.update(&mut state, 0.99 * residual).force, 0.0);
}

#[test]
fn elastic_cone_follows_sneddon() {
    let beta: f64 = 0.1;
    let cone = Cone::new(beta).unwrap();
    let d_max = 2e-6;
    let half_width = 1.05 * 2.0 * d_max / (PI * beta.tan());
    let bed = SpringBed::new(cone, E_STAR, f64::INFINITY, 1.0, half_width, 4001).unwrap();
    let mut state = SpringBedState::default();
    for k in 1..=20 {
        let d = d_max * k as f64 / 20.0;
        let force = bed.update(&mut state, d).force;
        let sneddon = 2.0 * E_STAR * d * d / (PI * beta.tan());
        assert!(
            (force / sneddon - 1.0).abs() < 2e-3,
            "d = {d}: {force} vs {sneddon}"
        );
    }
}

#[test]
fn numerically_transformed_sphere_gives_the_same_bed() {
    let radius = 6.35e-3;
    let numeric = NumericalProfile::from_height(move |r| r * r / (2.0 * radius));
    let exact = Sphere::new(radius).unwrap();
    let half_width = 2e-4;
    let a = SpringBed::new(numeric, E_STAR, Q_C, 0.37, half_width, 1001).unwrap();
    let b = SpringBed::new(exact, E_STAR, Q_C, 0.37, half_width, 1001).unwrap();
    let (mut sa, mut sb) = (SpringBedState::default(), SpringBedState::default());
    for d in [3e-6, 1e-6, 5e-6, 2e-6, -1e-7, 5.5e-6] {
        let (fa, fb) = (a.update(&mut sa, d).force, b.update(&mut sb, d).force);
        assert!(
            (fa - fb).abs() <= 1e-8 * fb.abs().max(1.0),
            "d = {d}: {fa} vs {fb}"
        );
    }
}
