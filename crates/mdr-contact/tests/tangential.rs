//! Tangential laws (`docs/theory.md` §5): the MDR spring bed with per-spring
//! stick/slip reproduces Cattaneo–Mindlin partial slip, `F_x = μ F_N (1 − (c/a)³)` with
//! `F_x = μ F_N (1 − (1 − δ_x/δ_slip)^{3/2})`, `δ_slip = μ E* d / G*`, within 1e-6 μ F_N; without slip
//! the O(1) Mindlin law equals the spring bed (`F = 2 G* a δ_x`).

use mdr_contact::normal::{SpringBed, SpringBedState};
use mdr_contact::prelude::*;
use mdr_contact::tangential::{SpringBedTangential, SpringBedTangentialState};
use nalgebra::Vector3;

const MU: f64 = 0.3;

fn pair() -> ContactPair {
    ContactPair::paper_fig2()
}

fn bed(params: &MdrElastoPlastic, max_overlap: f64) -> SpringBed {
    let pair = pair();
    SpringBed::sphere(&pair, params, 4001)
        .unwrap()
        .half_width(1.02 * (pair.effective_radius() * max_overlap).sqrt())
        .unwrap()
}

/// Cattaneo–Mindlin force of a Hertzian pressure at `F_N` with slip displacement `δ_slip`.
fn cattaneo_mindlin(normal_force: f64, slip_displacement: f64, displacement: f64) -> f64 {
    let ratio = (displacement / slip_displacement).min(1.0);
    MU * normal_force * (1.0 - (1.0 - ratio).powf(1.5))
}

/// Load tangentially in `steps` equal increments up to `1.2 δ_slip` at constant normal overlap
/// and compare with Cattaneo–Mindlin at every step: within 1e-6 μ F_N (measured 1.7e-7 with 4,001
/// springs); through the stick radius `c` within 5e-3 μ F_N (measured 2.4e-3: `c` moves from
/// spring to spring).
fn check_partial_slip(
    bed: &SpringBed,
    normal_state: &SpringBedState,
    normal_force: f64,
    contact_radius: f64,
    slip_displacement: f64,
) {
    let pair = pair();
    let law = SpringBedTangential::new(&pair, MU).unwrap();
    let mut state = SpringBedTangentialState::default();
    let steps = 600;
    let increment = 1.2 * slip_displacement / steps as f64;
    for k in 1..=steps {
        let force = law.update(bed, normal_state, &mut state, increment);
        let displacement = k as f64 * increment;
        let expected = cattaneo_mindlin(normal_force, slip_displacement, displacement);
        assert!(
            (force - expected).abs() <= 1e-6 * MU * normal_force,
            "δ_x/δ_slip = {}: spring bed {force}, Cattaneo–Mindlin {expected}",
            displacement / slip_displacement
        );
        // The same in terms of the stick radius c: F_x = μ F_N (1 − (c/a)³).
        if displacement < 0.95 * slip_displacement {
            let c = law.stick_radius(bed, normal_state, &state);
            let from_stick = MU * normal_force * (1.0 - (c / contact_radius).powi(3));
            assert!(
                (force - from_stick).abs() <= 5e-3 * MU * normal_force,
                "stick radius {c}: {force} vs {from_stick}"
            );
        }
    }
}

#[test]
fn elastic_spring_bed_reproduces_cattaneo_mindlin() {
    let pair = pair();
    let d = 2e-5;
    let bed = bed(&MdrElastoPlastic::elastic(), d);
    let mut normal_state = SpringBedState::default();
    bed.update(&mut normal_state, d);
    let hertz = Hertz.bind(&pair).unwrap();
    let slip = MU * pair.effective_modulus() * d / pair.effective_shear_modulus();
    let a = (pair.effective_radius() * d).sqrt();
    check_partial_slip(&bed, &normal_state, hertz.force(d), a, slip);
}

#[test]
fn flattened_plastic_contact_is_cattaneo_mindlin_with_radius_r_over_theta() {
    // After plastic loading to d_max and unloading to (1 − θ)s < d < s, the normal pressure is
    // Hertzian with radius R/θ about the residual depth (docs/theory.md §4), so partial slip follows
    // Cattaneo–Mindlin with that contact: F_N, a = sqrt(R e/θ), δ_slip = μ E* e / G*,
    // e = d − (1 − θ)s.
    let pair = pair();
    let params = MdrElastoPlastic::paper();
    let closed = params.bind(&pair).unwrap();
    let d_max = 3e-5;
    let bed = bed(&params, d_max);
    let mut normal_state = SpringBedState::default();
    let mut closed_state = MdrState::default();
    bed.update(&mut normal_state, d_max);
    closed.update(&mut closed_state, d_max);
    let s = d_max - closed.yield_overlap();
    let theta = closed.hardening_ratio();
    let d = (1.0 - theta) * s + 0.5 * theta * s;
    bed.update(&mut normal_state, d);
    let response = closed.update(&mut closed_state, d);
    let excess = d - (1.0 - theta) * s;
    let slip = MU * pair.effective_modulus() * excess / pair.effective_shear_modulus();
    check_partial_slip(
        &bed,
        &normal_state,
        response.force,
        response.contact_radius,
        slip,
    );
}

#[test]
fn without_slip_mindlin_equals_the_spring_bed() {
    let pair = pair();
    let no_slip = 1e6;
    let mindlin = Mindlin::new(no_slip).unwrap().bind(&pair).unwrap();
    let bed_tangential = SpringBedTangential::new(&pair, no_slip).unwrap();
    for (params, overlaps) in [
        (MdrElastoPlastic::elastic(), vec![2e-5]),
        // Plastic loading, then unloading on the flattened branch.
        (MdrElastoPlastic::paper(), vec![3e-5]),
        (MdrElastoPlastic::paper(), vec![3e-5, 1.6e-5]),
    ] {
        let bed = bed(&params, 3e-5);
        let closed = params.bind(&pair).unwrap();
        let (mut bed_state, mut closed_state) = (SpringBedState::default(), MdrState::default());
        let mut response = NormalResponse::default();
        for &d in &overlaps {
            bed.update(&mut bed_state, d);
            response = closed.update(&mut closed_state, d);
        }
        let mut state = SpringBedTangentialState::default();
        let mut mindlin_state = MindlinState::default();
        let increment = 1e-8;
        for k in 1..=10 {
            let f_bed = bed_tangential.update(&bed, &bed_state, &mut state, increment);
            let f_mindlin = -mindlin
                .update(
                    &mut mindlin_state,
                    &TangentialInput {
                        normal: Vector3::z(),
                        displacement_increment: Vector3::new(increment, 0.0, 0.0),
                        normal_response: response,
                    },
                )
                .force
                .x;
            let exact = 2.0
                * pair.effective_shear_modulus()
                * response.contact_radius
                * k as f64
                * increment;
            assert!((f_mindlin - exact).abs() < 1e-12 * exact);
            assert!(
                (f_bed - f_mindlin).abs() < 2e-3 * f_mindlin,
                "{overlaps:?}: bed {f_bed} vs Mindlin {f_mindlin}"
            );
        }
    }
}

#[test]
fn gross_slip_caps_at_coulomb_and_dissipates_mu_f_n_per_slip_length() {
    let pair = pair();
    let d = 2e-5;
    let bed = bed(&MdrElastoPlastic::paper(), d);
    let mut normal_state = SpringBedState::default();
    let normal_force = bed.update(&mut normal_state, d).force;
    let law = SpringBedTangential::new(&pair, MU).unwrap();
    let mut state = SpringBedTangentialState::default();
    let slip = MU * pair.effective_modulus() * d / pair.effective_shear_modulus();
    // Past full slip every spring sits at its limit.
    let mut force = 0.0;
    for _ in 0..200 {
        force = law.update(&bed, &normal_state, &mut state, 2.0 * slip / 200.0);
    }
    assert!((force - MU * normal_force).abs() < 1e-9 * normal_force);
    let before = state.dissipated_work;
    let energy = law.elastic_energy(&bed, &state);
    law.update(&bed, &normal_state, &mut state, 1e-7);
    assert!((state.dissipated_work - before - MU * normal_force * 1e-7).abs() < 1e-9 * before);
    assert!((law.elastic_energy(&bed, &state) - energy).abs() < 1e-12 * energy);
    // Reversing: the springs first stick (the force falls with stiffness 2 G* a).
    let back = law.update(&bed, &normal_state, &mut state, -1e-9);
    let a = (pair.effective_radius() * d).sqrt();
    let drop = force - back;
    // Measured 1.1e-4 (the bed's discrete stiffness against 2 G* a).
    assert!((drop / (2.0 * pair.effective_shear_modulus() * a * 1e-9) - 1.0).abs() < 5e-4);
}

#[test]
fn springs_leaving_the_contact_forget_their_displacement() {
    let pair = pair();
    let bed = bed(&MdrElastoPlastic::elastic(), 2e-5);
    let law = SpringBedTangential::new(&pair, MU).unwrap();
    let mut normal_state = SpringBedState::default();
    let mut state = SpringBedTangentialState::default();
    bed.update(&mut normal_state, 2e-5);
    let stuck = law.update(&bed, &normal_state, &mut state, 1e-8);
    assert!(stuck > 0.0);
    // Separate: no spring touches, all forget.
    bed.update(&mut normal_state, -1e-6);
    assert_eq!(law.update(&bed, &normal_state, &mut state, 0.0), 0.0);
    assert!(state.displacements.iter().all(|u| u.norm() == 0.0));
    // Re-touch: the tangential force starts from zero again.
    bed.update(&mut normal_state, 2e-5);
    let again = law.update(&bed, &normal_state, &mut state, 1e-8);
    assert!((again - stuck).abs() < 1e-12 * stuck);
}

#[test]
fn vector_update_is_isotropic() {
    let pair = pair();
    let bed = bed(&MdrElastoPlastic::elastic(), 2e-5);
    let law = SpringBedTangential::new(&pair, MU).unwrap();
    let mut normal_state = SpringBedState::default();
    bed.update(&mut normal_state, 2e-5);
    let (mut along_x, mut diagonal) = (
        SpringBedTangentialState::default(),
        SpringBedTangentialState::default(),
    );
    let step = 2e-8;
    let direction = nalgebra::Vector2::new(0.6, 0.8);
    for _ in 0..50 {
        let fx = law.update(&bed, &normal_state, &mut along_x, step);
        let f = law.update_vector(&bed, &normal_state, &mut diagonal, direction * step);
        assert!((f.norm() - fx).abs() < 1e-12 * fx);
        assert!((f.normalize() - direction).norm() < 1e-12);
    }
}
