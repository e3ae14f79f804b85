//! A normal law declared outside the impact scene's built-in laws (the demo linear spring,
//! `F = k_n δ`) runs in the scene through its entry ([`SceneLawEntry::of`]), in force mode, at a
//! half-space and at a free sphere, as its analytic solution: an undamped spring returns the
//! whole approach speed (`e_n = 1`, to the integrator's step error) after half a period,
//! `t_c = π √(m*/k_n)`.

use mdr_contact::normal::LinearSpring;
use mdr_contact::Material;
use mdr_rapier::scenario::{CouplingMode, ImpactScene, SceneLawEntry, Target};
use mdr_rapier::CouplingError;

static SPRING: SceneLawEntry = SceneLawEntry::of::<LinearSpring>();

/// The paper's steel ball on `target`, the spring `stiffness` (N/m), without friction.
fn spring_scene(stiffness: f64, target: Target, speed: f64) -> ImpactScene {
    ImpactScene {
        target,
        model: SPRING.with_values(&[stiffness]).unwrap().into(),
        ..ImpactScene::paper_drop(speed)
    }
}

/// `4/3 π r³ ρ`, written out rather than taken from the law crate.
fn ball_mass(radius: f64, material: &Material) -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * radius.powi(3) * material.density()
}

/// `e_n` and the contact time (steps × dt) against the spring's, for the reduced mass `mass`.
fn check_spring(scene: &ImpactScene, mass: f64, stiffness: f64) {
    let outcome = scene.run(CouplingMode::Force).unwrap();
    let contact_time = std::f64::consts::PI * (mass / stiffness).sqrt();
    let measured = outcome.steps as f64 * outcome.time_step;
    // Symplectic Euler conserves the spring's energy but for the phases at which the contact
    // begins and ends inside a step: an error of order `(ω dt)²`, `ω = π / t_c` (measured at
    // most 0.1 of it; round-off alone where both phases match).
    let step_error = (std::f64::consts::PI * outcome.time_step / contact_time).powi(2);
    assert!(
        (outcome.normal_restitution - 1.0).abs() < 0.5 * step_error + 1e-12,
        "e_n = {} at {} m/s",
        outcome.normal_restitution,
        scene.speed
    );
    // The contact begins and ends inside a step: one step either way.
    assert!(
        (measured - contact_time).abs() <= 1.01 * outcome.time_step,
        "contact time {measured} vs {contact_time} (dt {})",
        outcome.time_step
    );
    assert!(!outcome.stuck);
}

#[test]
fn linear_spring_drop_returns_every_impact_after_half_a_period() {
    let scene = ImpactScene::paper_drop(1.0);
    let mass = ball_mass(scene.radius, &scene.material);
    // Softer than the steel Hertz contact (longer contact), and stiffer (shorter).
    for (stiffness, speed) in [(1.0e6, 1.0), (1.0e6, 0.1), (1.0e9, 1.0)] {
        let scene = spring_scene(stiffness, scene.target, speed);
        check_spring(&scene, mass, stiffness);
    }
}

#[test]
fn linear_spring_pair_takes_the_reduced_mass() {
    let paper = ImpactScene::paper_drop(1.0);
    let (radius, material) = (0.01, Material::paper_steel());
    let target = Target::Sphere { radius, material };
    let (m1, m2) = (
        ball_mass(paper.radius, &paper.material),
        ball_mass(radius, &material),
    );
    let stiffness = 1.0e7;
    check_spring(
        &spring_scene(stiffness, target, 0.5),
        m1 * m2 / (m1 + m2),
        stiffness,
    );
    // Negative control: the ball's own mass gives a contact time 1.3 times longer.
    let outcome = spring_scene(stiffness, target, 0.5)
        .run(CouplingMode::Force)
        .unwrap();
    let with_ball_mass = std::f64::consts::PI * (m1 / stiffness).sqrt();
    assert!(
        (outcome.steps as f64 * outcome.time_step - with_ball_mass).abs()
            > 100.0 * outcome.time_step
    );
}

#[test]
fn declared_law_is_refused_in_restitution_mode_and_out_of_its_range() {
    let scene = spring_scene(1.0e6, ImpactScene::paper_drop(1.0).target, 1.0);
    assert!(matches!(
        scene.run(CouplingMode::Restitution),
        Err(CouplingError::Unsupported(_))
    ));
    let err = SPRING.with_values(&[-1.0]).unwrap_err().to_string();
    assert!(
        err.contains("normal_stiffness_n_per_m") && err.contains("(0, inf)"),
        "{err}"
    );
    let name = SPRING.with_values(&[1.0]).unwrap();
    assert_eq!(name.name(), "linear_spring");
    assert_eq!(name.values(), &[1.0]);
}
