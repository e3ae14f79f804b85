//! The spring-bed tangential law (`SpringBedTangential`, `docs/theory.md` §5) held to its
//! springs worked out by hand: each spring in contact follows the tangential displacement
//! while `G* |u| ≤ μ q_z` (`q_z = f_z/Δx`), slips back to `|u| = μ f_z/(G* Δx)` past it,
//! dissipating `μ f_z` times the slip, and forgets its displacement when its normal force
//! vanishes; the force is `G* Δx Σ w u`.
//!
//! The normal bed: a sphere of radius 1 m (`g = x²`), elastic, `E* = 4 Pa`, `L = 1 m`, `n = 4`
//! (`Δx = 0.5 m`, springs at `x = 0.25, 0.75 m`, weight 2); at `d = 1 m` they carry
//! `f_z = 2 (1 − g) = 1.875, 0.875 N`. `G* = 3 Pa` (`k_x = G* Δx = 1.5 N/m`), `μ = 0.3`: slip
//! limits `μ f_z/k_x = 0.375, 0.175 m`. Tolerance 1e-12 (relative).

use mdr_contact::nalgebra::Vector2;
use mdr_contact::prelude::*;
use mdr_contact::profile::Sphere;

fn assert_close(what: &str, got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-12 * want.abs().max(got.abs()),
        "{what}: {got} vs {want}"
    );
}

const MU: f64 = 0.3;
const K_X: f64 = 1.5;

fn normal_bed() -> SpringBed {
    SpringBed::new(Sphere::new(1.0).unwrap(), 4.0, f64::INFINITY, 1.0, 1.0, 4).unwrap()
}

#[test]
fn springs_stick_slip_from_the_outside_in_and_reach_coulomb() {
    let bed = normal_bed();
    let law = SpringBedTangential::from_parts(3.0, MU).unwrap();
    assert_eq!(
        (law.effective_shear_modulus(), law.friction_coefficient()),
        (3.0, MU)
    );
    let mut normal = SpringBedState::default();
    let normal_force = bed.update(&mut normal, 1.0).force;
    assert_close("F_N", normal_force, 2.0 * (1.875 + 0.875));
    let mut state = SpringBedTangentialState::default();

    // Both springs stick: u = 0.125 m each.
    let f = law.update(&bed, &normal, &mut state, 0.125);
    assert_close("stick", f, K_X * 2.0 * (0.125 + 0.125));
    assert_eq!(state.dissipated_work, 0.0);
    assert_eq!(law.stick_radius(&bed, &normal, &state), 0.75);
    assert_close(
        "stored energy",
        law.elastic_energy(&bed, &state),
        0.5 * 2.0 * K_X * (0.125f64.powi(2) * 2.0),
    );

    // u = 0.25: the outer spring slips back to its limit 0.175 m (slip 0.075 m).
    let f = law.update(&bed, &normal, &mut state, 0.125);
    assert_close("partial slip", f, K_X * 2.0 * (0.25 + 0.175));
    let outer_slip = 2.0 * MU * 0.875 * 0.075;
    assert_close("partial-slip work", state.dissipated_work, outer_slip);
    // The spring at its limit slips: the stick zone ends at the inner spring.
    assert_eq!(law.stick_radius(&bed, &normal, &state), 0.25);

    // Another 0.25 m: both slip, the force is μ F_N (Coulomb).
    let f = law.update(&bed, &normal, &mut state, 0.25);
    assert_close("gross slip", f, MU * normal_force);
    let work = outer_slip + 2.0 * MU * 1.875 * 0.125 + 2.0 * MU * 0.875 * 0.25;
    assert_close("gross-slip work", state.dissipated_work, work);
    assert_eq!(law.stick_radius(&bed, &normal, &state), 0.0);
    assert_close(
        "stored energy at the limits",
        law.elastic_energy(&bed, &state),
        0.5 * 2.0 * K_X * (0.375f64.powi(2) + 0.175f64.powi(2)),
    );

    // Reversing by 0.125 m: both stick again, nothing dissipated.
    let f = law.update(&bed, &normal, &mut state, -0.125);
    assert_close("reversed", f, K_X * 2.0 * (0.25 + 0.05));
    assert_close("no work on reversal", state.dissipated_work, work);
    assert_eq!(law.stick_radius(&bed, &normal, &state), 0.75);

    // Unloaded to d = 0.5 the outer spring leaves the contact and forgets its displacement;
    // the inner one (f_z = 0.875 N, limit 0.175 m) slips back from 0.25 m.
    bed.update(&mut normal, 0.5);
    let f = law.update(&bed, &normal, &mut state, 0.0);
    assert_close("after unloading", f, K_X * 2.0 * 0.175);
    assert_eq!(state.displacements[1], Vector2::zeros());
    let work = work + 2.0 * MU * 0.875 * 0.075;
    assert_close("unloading slip work", state.dissipated_work, work);

    // A sideways step: the displacement (0.175, 0.1) m slips back to the circle of radius
    // 0.175 m along itself (isotropic criterion).
    let f = law.update_vector(&bed, &normal, &mut state, Vector2::new(0.0, 0.1));
    let length = (0.175f64.powi(2) + 0.01).sqrt();
    let direction = Vector2::new(0.175, 0.1) / length;
    assert_close("sideways |F|", f.norm(), K_X * 2.0 * 0.175);
    assert_close("sideways direction", f.dot(&direction), f.norm());
    assert_close(
        "sideways slip work",
        state.dissipated_work,
        work + 2.0 * MU * 0.875 * (length - 0.175),
    );
    assert_close(
        "stored energy",
        law.elastic_energy(&bed, &state),
        0.5 * 2.0 * K_X * 0.175f64.powi(2),
    );

    // Out of contact every spring forgets.
    bed.update(&mut normal, 0.0);
    let f = law.update(&bed, &normal, &mut state, 0.1);
    assert_eq!(f, 0.0);
    assert_eq!(law.elastic_energy(&bed, &state), 0.0);
    assert_eq!(law.stick_radius(&bed, &normal, &state), 0.0);
}

#[test]
fn parameters_are_checked() {
    let pair = ContactPair::new(4.0, 3.0, 1.0, 1.0).unwrap();
    let law = SpringBedTangential::new(&pair, MU).unwrap();
    assert_eq!(law.effective_shear_modulus(), 3.0);
    assert_eq!(law.friction_coefficient(), MU);
    assert!(SpringBedTangential::from_parts(3.0, 0.0).is_ok());
    assert!(matches!(
        SpringBedTangential::from_parts(3.0, -0.1),
        Err(ContactError::OutOfRange { name: "mu", .. })
    ));
    assert!(matches!(
        SpringBedTangential::from_parts(0.0, MU),
        Err(ContactError::OutOfRange {
            name: "effective_shear_modulus",
            ..
        })
    ));
}

#[test]
fn a_spring_within_the_round_off_guard_of_its_limit_is_not_in_the_stick_zone() {
    // The stick zone takes the springs whose |u| is below their slip limit by more than the
    // 1e-12 relative guard that tells a spring slipped back to its limit (to round-off) from a
    // sticking one. The inner spring's limit is μ f_z/(G* Δx) = 0.375 m; the outer spring
    // (limit 0.175 m) slips.
    let bed = normal_bed();
    let law = SpringBedTangential::from_parts(3.0, MU).unwrap();
    let mut normal = SpringBedState::default();
    bed.update(&mut normal, 1.0);
    let limit = MU * 1.875 / (0.5 * 3.0);
    let mut state = SpringBedTangentialState::default();
    law.update(&bed, &normal, &mut state, limit * (1.0 - 1e-12));
    assert_eq!(law.stick_radius(&bed, &normal, &state), 0.0);
    let mut state = SpringBedTangentialState::default();
    law.update(&bed, &normal, &mut state, limit * (1.0 - 2e-12));
    assert_eq!(law.stick_radius(&bed, &normal, &state), 0.25);
}
