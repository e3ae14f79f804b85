//! The elastic–plastic spring rolling resistance (Ai, Chen, Rotter & Ooi 2011, "type C" without
//! dashpot, eqs. 13–16) against its equations, written out here: `k_r = 2.25 k_n μ_r² R²`,
//! `M ← M − k_r Δθ` (the rolling part of the rotation only), `|M| ≤ μ_r R F_N`; on the cap the
//! plastic rotation `(|M_trial| − cap)/k_r` dissipates `cap` times itself, so rolling through a
//! total angle `θ` from rest dissipates exactly `cap (θ − cap/k_r)` (the rigid–plastic loop);
//! the stored energy `|M|²/(2k_r)`. Exact formulas: tolerance 1e-12.

use mdr_contact::nalgebra::Vector3;
use mdr_contact::rolling::{
    EpsdRolling, EpsdRollingState, NoRolling, RollingInput, RollingLaw, RollingModel,
};
use mdr_contact::ContactPair;

const MU_R: f64 = 0.08;
const R: f64 = 0.004;
const K_N: f64 = 3.0e5;

fn pair() -> ContactPair {
    ContactPair::new(1.0e8, 4.0e7, R, 1e-4).unwrap()
}

fn input(rotation: Vector3<f64>, normal_force: f64, normal_stiffness: f64) -> RollingInput {
    RollingInput {
        normal: Vector3::z(),
        rotation_increment: rotation,
        normal_force,
        normal_stiffness,
    }
}

/// Equal to 1e-12, both finite (an infinite value would otherwise pass its own tolerance).
fn close(a: f64, b: f64) -> bool {
    a.is_finite() && b.is_finite() && (a - b).abs() <= 1e-12 * a.abs().max(b.abs()) + 1e-300
}

#[test]
fn spring_stiffness_and_cap_are_ai_et_al() {
    let model = EpsdRolling::new(MU_R).unwrap();
    assert_eq!(model.coefficient(), MU_R);
    let law = model.bind(&pair()).unwrap();
    let k_r = 2.25 * K_N * MU_R * MU_R * R * R;
    let f_n = 2.0;
    let cap = MU_R * R * f_n;
    let mut state = EpsdRollingState::default();
    // Elastic: M = −k_r Δθ, the normal part of the rotation (twist) ignored.
    let small = 0.1 * cap / k_r;
    let r = law.update(&mut state, &input(Vector3::new(small, 0.0, 5.0), f_n, K_N));
    assert!(
        close(r.torque.x, -k_r * small),
        "{} vs {}",
        r.torque.x,
        -k_r * small
    );
    assert_eq!((r.torque.y, r.torque.z), (0.0, 0.0));
    assert!(!r.rolling);
    assert_eq!(r.dissipated, 0.0);
    assert!(close(state.stiffness, k_r));
    let stored = (k_r * small).powi(2) / (2.0 * k_r);
    assert!(close(r.elastic_energy, stored));
    assert!(close(law.elastic_energy(&state), stored));
    assert!(close(state.elastic_energy(), stored));
    // Over the cap: |M| = μ_r R F_N, the excess rotation dissipates cap · excess / k_r.
    let big = 3.0 * cap / k_r;
    let trial = k_r * small + k_r * big;
    let r = law.update(&mut state, &input(Vector3::new(big, 0.0, 0.0), f_n, K_N));
    assert!(r.rolling);
    assert!(close(r.torque.norm(), cap));
    assert!(close(r.torque.x, -cap));
    assert!(close(r.dissipated, cap * (trial - cap) / k_r));
    assert!(close(law.dissipated_work(&state), r.dissipated));
}

#[test]
fn rolling_through_an_angle_dissipates_the_rigid_plastic_work() {
    let law = EpsdRolling::new(MU_R).unwrap().bind(&pair()).unwrap();
    let k_r = 2.25 * K_N * MU_R * MU_R * R * R;
    let f_n = 1.5;
    let cap = MU_R * R * f_n;
    let mut state = EpsdRollingState::default();
    let (steps, theta) = (1000, 40.0 * cap / k_r);
    for _ in 0..steps {
        let step = Vector3::new(0.6, 0.8, 0.0) * (theta / steps as f64);
        law.update(&mut state, &input(step, f_n, K_N));
    }
    let exact = cap * (theta - cap / k_r);
    assert!(
        close(law.dissipated_work(&state), exact),
        "{} vs {exact}",
        law.dissipated_work(&state)
    );
    assert!(close(state.torque.norm(), cap));
    // The torque opposes the rolling direction.
    assert!(close(state.torque.x / state.torque.y, 0.75));
    assert!(state.torque.x < 0.0);
}

#[test]
fn the_torque_follows_the_contact_plane_at_its_length() {
    let law = EpsdRolling::new(MU_R).unwrap().bind(&pair()).unwrap();
    let k_r = 2.25 * K_N * MU_R * MU_R * R * R;
    let f_n = 2.0;
    let cap = MU_R * R * f_n;
    let mut state = EpsdRollingState::default();
    let theta = 0.3 * cap / k_r;
    law.update(&mut state, &input(Vector3::new(theta, 0.0, 0.0), f_n, K_N));
    // The normal tilts by 30° about y: the stored torque is projected onto the new plane and
    // rescaled to its old length; no rotation, no change in stiffness, no energy change.
    let tilt = 30f64.to_radians();
    let normal = Vector3::new(tilt.sin(), 0.0, tilt.cos());
    let r = law.update(
        &mut state,
        &RollingInput {
            normal,
            rotation_increment: Vector3::zeros(),
            normal_force: f_n,
            normal_stiffness: K_N,
        },
    );
    assert!(close(r.torque.norm(), k_r * theta));
    assert!(r.torque.dot(&normal).abs() < 1e-12 * k_r * theta);
    assert!(r.torque.x < 0.0 && r.torque.z > 0.0);
    assert_eq!(r.stiffness_energy, 0.0);
}

#[test]
fn a_softer_contact_changes_the_stored_energy_without_work() {
    let law = EpsdRolling::new(MU_R).unwrap().bind(&pair()).unwrap();
    let f_n = 2.0;
    let mut state = EpsdRollingState::default();
    let k1 = 2.25 * K_N * MU_R * MU_R * R * R;
    let theta = 0.2 * MU_R * R * f_n / k1;
    law.update(&mut state, &input(Vector3::new(theta, 0.0, 0.0), f_n, K_N));
    let m2 = (k1 * theta).powi(2);
    let r = law.update(&mut state, &input(Vector3::zeros(), f_n, 0.5 * K_N));
    let k2 = 0.5 * k1;
    assert!(close(r.stiffness_energy, 0.5 * m2 * (1.0 / k2 - 1.0 / k1)));
    assert!(close(r.elastic_energy, 0.5 * m2 / k2));
    assert!(close(
        EpsdRollingState::stiffness_energy_change(m2, k1, k2),
        0.5 * m2 * (1.0 / k2 - 1.0 / k1)
    ));
    assert_eq!(EpsdRollingState::stiffness_energy_change(m2, 0.0, k2), 0.0);
    assert_eq!(EpsdRollingState::stiffness_energy_change(m2, k1, 0.0), 0.0);
}

#[test]
fn opening_releases_the_spring_as_dissipated_work() {
    let law = EpsdRolling::new(MU_R).unwrap().bind(&pair()).unwrap();
    let f_n = 2.0;
    let mut state = EpsdRollingState::default();
    let k_r = 2.25 * K_N * MU_R * MU_R * R * R;
    let theta = 0.5 * MU_R * R * f_n / k_r;
    law.update(&mut state, &input(Vector3::new(0.0, theta, 0.0), f_n, K_N));
    let stored = 0.5 * k_r * theta * theta;
    let r = law.update(&mut state, &input(Vector3::new(0.0, theta, 0.0), 0.0, K_N));
    assert!(close(r.dissipated, stored));
    assert_eq!(r.torque, Vector3::zeros());
    assert_eq!(state.stiffness, 0.0);
    assert!(close(law.dissipated_work(&state), stored));
    assert_eq!(law.elastic_energy(&state), 0.0);
    // A contact whose normal stiffness vanished keeps its torque but has no spring: when its
    // cap falls below the torque, all rolling at the cap is plastic, `cap |Δθ|`.
    let mut state = EpsdRollingState::default();
    law.update(&mut state, &input(Vector3::new(theta, 0.0, 0.0), f_n, K_N));
    let (quarter, rotation) = (0.25 * f_n, 0.01);
    let r = law.update(
        &mut state,
        &input(Vector3::new(0.0, rotation, 0.0), quarter, 0.0),
    );
    let cap = MU_R * R * quarter;
    assert!(r.rolling);
    assert!(close(r.torque.norm(), cap));
    assert!(close(r.dissipated, cap * rotation));
    assert_eq!(r.elastic_energy, 0.0);
}

#[test]
fn no_rolling_resistance_adds_nothing() {
    let law = NoRolling.bind(&pair()).unwrap();
    let r = law.update(&mut (), &input(Vector3::new(1.0, 2.0, 0.0), 5.0, K_N));
    assert_eq!(r.torque, Vector3::zeros());
    assert_eq!((r.dissipated, r.elastic_energy), (0.0, 0.0));
    assert_eq!(
        (law.elastic_energy(&()), law.dissipated_work(&())),
        (0.0, 0.0)
    );
}

#[test]
fn a_torque_along_the_new_normal_is_dropped_as_twist() {
    // The contact plane turns by 90° about y: the stored rolling torque (about x) now lies along
    // the normal, where it would be a twisting torque, which the model does not resist. It has
    // no part in the new plane, so only this step's rolling remains: M = −k_r Δθ, finite.
    let law = EpsdRolling::new(MU_R).unwrap().bind(&pair()).unwrap();
    let k_r = 2.25 * K_N * MU_R * MU_R * R * R;
    let f_n = 2.0;
    let theta = 0.3 * MU_R * R * f_n / k_r;
    let mut state = EpsdRollingState::default();
    law.update(&mut state, &input(Vector3::new(theta, 0.0, 0.0), f_n, K_N));
    let step = 0.1 * theta;
    let r = law.update(
        &mut state,
        &RollingInput {
            normal: Vector3::x(),
            rotation_increment: Vector3::new(0.0, step, 0.0),
            normal_force: f_n,
            normal_stiffness: K_N,
        },
    );
    assert_eq!(r.torque.x, 0.0);
    assert!(close(r.torque.y, -k_r * step), "{:?}", r.torque);
    assert_eq!(r.torque.z, 0.0);
    assert!(close(r.elastic_energy, 0.5 * k_r * step * step));
}
