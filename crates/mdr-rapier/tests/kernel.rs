//! The per-pair kernel (`mdr_rapier::kernel`) against its mechanics written out by hand: the
//! contact-point velocity `v₁ − v₂ + ω₁ × r₁ − ω₂ × r₂`, the torques `r₁ × F` on body 1 and
//! `r₂ × (−F)` on body 2 (for two spheres `r₁ = −l₁ n`, `r₂ = l₂ n`), Hertz's force
//! `(4/3) E* √R δ^{3/2}` along the normal, the rolling spring's torque `−k_r Δθ_⊥` with
//! `Δθ = (ω₁ − ω₂) Δt` and `k_r = 2.25 (μ_r R)² · 2E* √(Rδ)` (Ai et al. 2011, eqs. 13–16) on
//! body 1 and its opposite on body 2, and the works booked part by part. The cross products are
//! worked out in the comments with binary-exact numbers; tolerance 1e-12 (relative).

use mdr_contact::prelude::*;
use mdr_contact::rolling::{EpsdRolling, EpsdRollingState, RollingModel};
use mdr_rapier::kernel::{
    evaluate_pair, Arms, ContactKinematics, ContactWorks, LeverArms, PairHistory, SphereArms,
};
use nalgebra::Vector3;

fn assert_vec(what: &str, got: Vector3<f64>, want: Vector3<f64>) {
    let scale = want.norm().max(got.norm()).max(1e-300);
    assert!(
        (got - want).norm() <= 1e-12 * scale,
        "{what}: {got:?} vs {want:?}"
    );
}

fn assert_close(what: &str, got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-12 * want.abs().max(got.abs()),
        "{what}: {got} vs {want}"
    );
}

const NORMAL: Vector3<f64> = Vector3::new(0.0, 0.0, 1.0);

fn omega1() -> Vector3<f64> {
    Vector3::new(1.0, 2.0, 3.0)
}

fn omega2() -> Vector3<f64> {
    Vector3::new(-2.0, 0.5, 1.0)
}

#[test]
fn sphere_arms_give_the_contact_point_velocity_and_torques() {
    let arms = SphereArms {
        lever1: 0.75,
        lever2: 0.25,
    };
    // r₁ = −0.75 n = (0, 0, −0.75): ω₁ × r₁ = (2·(−0.75), −1·(−0.75), 0) = (−1.5, 0.75, 0).
    // r₂ = 0.25 n = (0, 0, 0.25): ω₂ × r₂ = (0.5·0.25, 2·0.25, 0) = (0.125, 0.5, 0).
    assert_vec(
        "ω₁ × r₁ − ω₂ × r₂",
        arms.rotational_velocity(&NORMAL, &omega1(), &omega2()),
        Vector3::new(-1.625, 0.25, 0.0),
    );
    // F = (1, −2, 0.5): r₁ × F = (−(−0.75)(−2), −0.75·1, 0) = (−1.5, −0.75, 0);
    // r₂ × (−F) = (−0.25·2, 0.25·(−1), 0) = (−0.5, −0.25, 0).
    let (t1, t2) = arms.torques(&NORMAL, &Vector3::new(1.0, -2.0, 0.5));
    assert_vec("r₁ × F", t1, Vector3::new(-1.5, -0.75, 0.0));
    assert_vec("r₂ × (−F)", t2, Vector3::new(-0.5, -0.25, 0.0));
}

#[test]
fn general_arms_give_the_contact_point_velocity_and_torques() {
    let arms = Arms {
        arm1: Vector3::new(0.5, -1.0, 2.0),
        arm2: Vector3::new(-0.25, 0.5, 1.0),
    };
    // ω₁ × r₁ = (2·2 − 3·(−1), 3·0.5 − 1·2, 1·(−1) − 2·0.5) = (7, −0.5, −2);
    // ω₂ × r₂ = (0.5·1 − 1·0.5, 1·(−0.25) − (−2)·1, (−2)·0.5 − 0.5·(−0.25)) = (0, 1.75, −0.875).
    assert_vec(
        "ω₁ × r₁ − ω₂ × r₂",
        arms.rotational_velocity(&NORMAL, &omega1(), &omega2()),
        Vector3::new(7.0, -2.25, -1.125),
    );
    // F = (1, −2, 0.5): r₁ × F = (−1·0.5 − 2·(−2), 2·1 − 0.5·0.5, 0.5·(−2) − (−1)·1)
    // = (3.5, 1.75, 0); r₂ × (−F) with −F = (−1, 2, −0.5):
    // (0.5·(−0.5) − 1·2, 1·(−1) − (−0.25)(−0.5), (−0.25)·2 − 0.5·(−1)) = (−2.25, −1.125, 0).
    let (t1, t2) = arms.torques(&NORMAL, &Vector3::new(1.0, -2.0, 0.5));
    assert_vec("r₁ × F", t1, Vector3::new(3.5, 1.75, 0.0));
    assert_vec("r₂ × (−F)", t2, Vector3::new(-2.25, -1.125, 0.0));
    // The contact point's relative velocity adds v₁ − v₂ = (3, 0, −1) − (1, 1, 1) = (2, −1, −2).
    let kinematics = ContactKinematics {
        overlap: 1e-4,
        normal: NORMAL,
        arms,
        linvel1: Vector3::new(3.0, 0.0, -1.0),
        angvel1: omega1(),
        linvel2: Vector3::new(1.0, 1.0, 1.0),
        angvel2: omega2(),
    };
    assert_vec(
        "relative velocity",
        kinematics.relative_velocity(),
        Vector3::new(9.0, -3.25, -3.125),
    );
}

/// `E* = 7.5·10⁸ Pa`, `R = 10⁻² m`: `(4/3) E* √R = 10⁸`, so at `δ = 10⁻⁴` Hertz gives
/// `F = 100 N`, `a = √(Rδ) = 10⁻³ m`, `k_n = 2E* a = 1.5·10⁶ N/m`; with `μ_r = 0.1` the rolling
/// arm is `μ_r R = 10⁻³ m`, `k_r = 2.25·10⁻⁶ k_n = 3.375 N·m/rad` and the cap `μ_r R F = 0.1 N·m`.
const E_STAR: f64 = 7.5e8;
const RADIUS: f64 = 1e-2;
const MU_R: f64 = 0.1;

fn hertz_force(overlap: f64) -> f64 {
    4.0 / 3.0 * E_STAR * RADIUS.sqrt() * overlap.powf(1.5)
}

fn rolling_stiffness(overlap: f64) -> f64 {
    2.25 * (MU_R * RADIUS).powi(2) * 2.0 * E_STAR * (RADIUS * overlap).sqrt()
}

#[test]
fn evaluate_pair_turns_the_laws_into_a_force_and_two_torques() {
    let pair = ContactPair::new(E_STAR, 3e8, RADIUS, 1e-3).unwrap();
    let law = ContactModel::new(Hertz).bind(&pair).unwrap();
    let rolling = EpsdRolling::new(MU_R).unwrap().bind(&pair).unwrap();
    let mut history: PairHistory<_, EpsdRollingState> = PairHistory {
        contact: law.new_state(),
        rolling: EpsdRollingState::default(),
    };
    let arm1 = Vector3::new(0.5e-3, -1e-3, 2e-3);
    let arm2 = Vector3::new(-0.25e-3, 0.5e-3, 1e-3);
    let dt = 1e-3;
    let overlap = 1e-4;
    let kinematics = ContactKinematics {
        overlap,
        normal: NORMAL,
        arms: Arms { arm1, arm2 },
        linvel1: Vector3::new(0.0, 0.0, -0.1),
        angvel1: omega1(),
        linvel2: Vector3::zeros(),
        angvel2: omega2(),
    };
    let wrench = evaluate_pair(&law, &rolling, &mut history, &kinematics, dt);
    let force = hertz_force(overlap);
    assert_close("Hertz force", force, 100.0);
    assert_vec("force on body 1", wrench.force, NORMAL * force);
    // Δθ = (ω₁ − ω₂) Δt = (3, 1.5, 2)·10⁻³, in the contact plane (3, 1.5, 0)·10⁻³;
    // the spring's torque on body 1 is −k_r Δθ_⊥ (|M| = 0.0113 N·m, under the 0.1 N·m cap).
    let k_r = rolling_stiffness(overlap);
    assert_close("k_r", k_r, 3.375);
    let spring = -k_r * Vector3::new(3e-3, 1.5e-3, 0.0);
    // r₁ × F n = 100 (−1e-3, −0.5e-3, 0); r₂ × (−F n) = 100 (−0.5e-3, −0.25e-3, 0).
    assert_vec(
        "torque on body 1",
        wrench.torque1,
        Vector3::new(-0.1, -0.05, 0.0) + spring,
    );
    assert_vec(
        "torque on body 2",
        wrench.torque2,
        Vector3::new(-0.05, -0.025, 0.0) - spring,
    );
    // rapier's vector type carries the same numbers.
    let (f, t1, t2) = (wrench.force(), wrench.torque1(), wrench.torque2());
    assert_eq!(
        [f.x, f.y, f.z],
        [wrench.force.x, wrench.force.y, wrench.force.z]
    );
    assert!(f.z > 0.0);
    assert_eq!(
        [t1.x, t1.y, t1.z],
        [wrench.torque1.x, wrench.torque1.y, wrench.torque1.z]
    );
    assert_eq!(
        [t2.x, t2.y, t2.z],
        [wrench.torque2.x, wrench.torque2.y, wrench.torque2.z]
    );

    // A deeper, still step: the spring keeps its torque while k_r follows k_n, which changes its
    // stored energy by ½|M|² (1/k_r' − 1/k_r) without work (booked as rolling stiffness energy).
    let deeper = 4e-4;
    let still = ContactKinematics {
        overlap: deeper,
        angvel1: Vector3::zeros(),
        angvel2: Vector3::zeros(),
        linvel1: Vector3::zeros(),
        ..kinematics
    };
    let wrench = evaluate_pair(&law, &rolling, &mut history, &still, dt);
    assert_vec("force deeper", wrench.force, NORMAL * hertz_force(deeper));
    let k_r2 = rolling_stiffness(deeper);
    assert_close("k_r deeper", k_r2, 6.75);
    let m2 = spring.norm_squared();
    let works = ContactWorks::of(&law, &rolling, &history);
    assert_close(
        "rolling stiffness energy",
        works.rolling_stiffness,
        0.5 * m2 * (1.0 / k_r2 - 1.0 / k_r),
    );
    assert_eq!(works.rolling, 0.0);
    // Opening releases what the spring held, |M|²/(2 k_r'), as dissipated rolling work.
    let open = ContactKinematics {
        overlap: 0.0,
        ..still
    };
    let wrench = evaluate_pair(&law, &rolling, &mut history, &open, dt);
    assert_eq!(wrench.force, Vector3::zeros());
    let works = ContactWorks::of(&law, &rolling, &history);
    assert_close("released", works.rolling, 0.5 * m2 / k_r2);
    assert_eq!(
        (works.plastic, works.friction, works.damping),
        (0.0, 0.0, 0.0)
    );
}

#[test]
fn contact_works_add_part_by_part() {
    let mut total = ContactWorks {
        plastic: 1.0,
        friction: 2.0,
        damping: 3.0,
        rolling: 4.0,
        tangential_stiffness: 5.0,
        rolling_stiffness: -6.0,
    };
    total.add(&ContactWorks {
        plastic: 10.0,
        friction: 20.0,
        damping: 30.0,
        rolling: 40.0,
        tangential_stiffness: -50.0,
        rolling_stiffness: 60.0,
    });
    assert_eq!(
        total,
        ContactWorks {
            plastic: 11.0,
            friction: 22.0,
            damping: 33.0,
            rolling: 44.0,
            tangential_stiffness: -45.0,
            rolling_stiffness: 54.0,
        }
    );
}
