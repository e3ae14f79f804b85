//! Oblique impacts of a sphere on a half-space with friction and rotation (`I = (2/5) m R²`).
//!
//! In gross sliding the tangential force is `μ F_n` throughout, so the tangential impulse is
//! `μ m v_n (1 + e_n)`: with the angle θ measured from the normal (`tan θ = v_t / v_n`),
//! `e_t = 1 − μ (1 + e_n) cot θ` and `ω = (5/2) μ (1 + e_n) v_n / R`. Gross sliding holds for the
//! whole contact when the slip velocity `v_t − R ω` never reaches zero:
//! `tan θ > (7/2) μ (1 + e_n)`.

use mdr_contact::ContactPair;
use mdr_impact::{Impact, Method, Sweep, TangentialSpec};

/// The MDR spring bed with the spring-bed tangential law (per-spring stick/slip).
fn spring_bed(speed: f64) -> Impact {
    Impact::paper(speed)
        .method(Method::Springs { springs: 400 })
        .tangential(TangentialSpec::SpringBed)
}

const MU: f64 = 0.2;

/// Both tangential laws (the O(1) Mindlin law and the MDR spring bed) against the impulse
/// formulas, and against each other: under gross sliding the Coulomb cap decides, so the
/// formulas hold to rounding (measured ≤ 1e-14: tolerance 1e-12). The two laws differ by up to
/// 1.5e-7 in `e_t` and 1.1e-6 in the spin (measured), from their normal laws: the closed form
/// for Mindlin, 400 springs for the bed.
#[test]
fn gross_sliding_matches_impulse_theory() {
    let pair = ContactPair::paper_fig2();
    let radius = pair.effective_radius();
    for angle in [60.0, 70.0, 80.0, 85.0] {
        let speed = 1.0;
        let mindlin = Impact::paper(speed)
            .angle_degrees(angle)
            .friction(MU)
            .run()
            .unwrap();
        let bed = spring_bed(speed)
            .angle_degrees(angle)
            .friction(MU)
            .run()
            .unwrap();
        let theta = f64::to_radians(angle);
        for (law, outcome) in [("Mindlin", &mindlin), ("spring bed", &bed)] {
            let e_n = outcome.normal_restitution;
            assert!(
                theta.tan() > 3.5 * MU * (1.0 + e_n),
                "{law}, θ = {angle}°: not gross sliding"
            );
            let v_n = speed * theta.cos();
            let e_t = 1.0 - MU * (1.0 + e_n) / theta.tan();
            let omega = 2.5 * MU * (1.0 + e_n) * v_n / radius;
            let measured_e_t = outcome.tangential_restitution.unwrap();
            assert!(
                (measured_e_t / e_t - 1.0).abs() < 1e-12,
                "{law}, θ = {angle}°: e_t {measured_e_t} vs {e_t}"
            );
            assert!(
                (outcome.spin / omega - 1.0).abs() < 1e-12,
                "{law}, θ = {angle}°: ω {} vs {omega}",
                outcome.spin
            );
        }
        let (a, b) = (
            mindlin.tangential_restitution.unwrap(),
            bed.tangential_restitution.unwrap(),
        );
        assert!(
            (a - b).abs() < 5e-7 && (mindlin.spin / bed.spin - 1.0).abs() < 5e-6,
            "θ = {angle}°: Mindlin e_t {a}, ω {} vs spring bed e_t {b}, ω {}",
            mindlin.spin,
            bed.spin
        );
    }
}

/// Below the gross-sliding angle the sphere ends up rolling or with its slip reversed, and
/// `e_t` lies above the sliding formula (friction cannot take more than `μ` times the normal
/// impulse).
#[test]
fn small_angles_do_not_slide_throughout() {
    let outcome = Impact::paper(1.0)
        .angle_degrees(10.0)
        .friction(MU)
        .run()
        .unwrap();
    let theta = f64::to_radians(10.0);
    let sliding = 1.0 - MU * (1.0 + outcome.normal_restitution) / theta.tan();
    assert!(outcome.tangential_restitution.unwrap() > sliding);
}

/// No angle creates energy: translational plus rotational kinetic energy after the impact never
/// exceeds the energy before, with or without initial spin, with the Mindlin law at every degree
/// and the spring bed at every 8th; head-on impacts match the normal validator.
#[test]
fn no_angle_creates_energy() {
    let every_degree: Vec<f64> = (1..90).map(f64::from).collect();
    let every_8th: Vec<f64> = (1..90).step_by(8).map(f64::from).collect();
    for (speed, spin) in [
        (0.1, 0.0),
        (1.0, 0.0),
        (5.0, 0.0),
        (1.0, 300.0),
        (1.0, -300.0),
    ] {
        let mindlin = Impact::paper(speed)
            .friction(MU)
            .spin(spin)
            .steps_per_contact(500);
        let bed = spring_bed(speed)
            .friction(MU)
            .spin(spin)
            .steps_per_contact(500);
        for (law, template, angles) in [
            ("Mindlin", mindlin, &every_degree),
            ("spring bed", bed, &every_8th),
        ] {
            for outcome in Sweep::angles(template, angles).run().unwrap() {
                assert!(
                    outcome.kinetic_energy_out <= outcome.kinetic_energy_in * (1.0 + 1e-6),
                    "{law}, v = {speed}, ω0 = {spin}, θ = {}: {} > {}",
                    outcome.angle_degrees,
                    outcome.kinetic_energy_out,
                    outcome.kinetic_energy_in
                );
            }
        }
    }
    let head_on = Impact::paper(1.0).run().unwrap().normal_restitution;
    let tiny = Impact::paper(1.0)
        .angle_degrees(1e-9)
        .friction(MU)
        .run()
        .unwrap();
    // Measured 3.2e-8: the time integration of the oblique route against the head-on closed form.
    assert!((tiny.normal_restitution - head_on).abs() < 1e-7);
}

/// Without friction the tangential velocity is untouched and no spin appears.
#[test]
fn frictionless_keeps_tangential_velocity() {
    let outcome = Impact::paper(1.0)
        .angle_degrees(45.0)
        .friction(0.0)
        .run()
        .unwrap();
    assert!((outcome.tangential_restitution.unwrap() - 1.0).abs() < 1e-12);
    assert_eq!(outcome.spin, 0.0);
}

/// Both tangential laws agree on the partial-slip regime to within a few per cent (the Mindlin
/// law is the incremental no-micro-slip approximation of the spring bed), and the spring bed
/// needs the spring-bed normal law.
#[test]
fn spring_bed_and_mindlin_are_close_at_small_angles() {
    let mindlin = Impact::paper(1.0)
        .angle_degrees(20.0)
        .friction(MU)
        .run()
        .unwrap();
    let bed = spring_bed(1.0)
        .angle_degrees(20.0)
        .friction(MU)
        .run()
        .unwrap();
    let (a, b) = (
        mindlin.tangential_restitution.unwrap(),
        bed.tangential_restitution.unwrap(),
    );
    assert!((a - b).abs() < 0.1, "mindlin {a} vs spring bed {b}");
    let error = Impact::paper(1.0)
        .angle_degrees(20.0)
        .tangential(TangentialSpec::SpringBed)
        .run()
        .unwrap_err();
    assert_eq!(error.key(), Some("tangential"));
}
