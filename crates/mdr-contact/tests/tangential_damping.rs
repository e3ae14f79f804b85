//! The tangential dashpot of the damping sub-models (LAMMPS `gammat`): `−η_t v_t` on top of the
//! Mindlin spring while it sticks, off on gross slip and without friction, booked as damping
//! work; `η_t = ratio · m γ_n √(R δ)` for `HertzianViscous`.

use mdr_contact::nalgebra::Vector3;
use mdr_contact::prelude::*;

const GAMMA_N: f64 = 50.0;
const MU: f64 = 0.5;

/// The settled-bed pair of `benches/lammps` (E* = 1.5e5, R = 0.25, m = π/12).
fn pair() -> ContactPair {
    ContactPair::new(1.5e5, 28_571.0, 0.25, std::f64::consts::PI / 12.0).unwrap()
}

fn input(overlap: f64, tangential_speed: f64) -> ContactInput {
    ContactInput {
        overlap,
        normal: Vector3::z(),
        // No normal motion: the normal dashpot does no work, only the tangential one.
        relative_velocity: Vector3::new(tangential_speed, 0.5 * tangential_speed, 0.0),
        dt: 1e-4,
    }
}

#[test]
fn sticking_contact_gets_the_dashpot_force_and_books_its_work() {
    let pair = pair();
    let plain = ContactModel::new(Hertz)
        .with_tangential(Mindlin::new(MU).unwrap())
        .with_damping(HertzianViscous::new(GAMMA_N).unwrap())
        .bind(&pair)
        .unwrap();
    let damped = ContactModel::new(Hertz)
        .with_tangential(Mindlin::new(MU).unwrap())
        .with_damping(
            HertzianViscous::new(GAMMA_N)
                .unwrap()
                .with_tangential_ratio(0.5)
                .unwrap(),
        )
        .bind(&pair)
        .unwrap();
    let (mut s_plain, mut s_damped) = (plain.new_state(), damped.new_state());
    let delta = 1e-3;
    let eta_t = 0.5 * pair.reduced_mass() * GAMMA_N * (pair.effective_radius() * delta).sqrt();
    for step in 0..20 {
        // A slow tangential oscillation: the spring sticks.
        let v = 1e-3 * (0.3 * step as f64).sin();
        let (a, b) = (input(delta, v), input(delta, v));
        let out_plain = plain.update(&mut s_plain, &a);
        let work_before = s_damped.books.damping_work;
        let out_damped = damped.update(&mut s_damped, &b);
        assert!(!out_damped.tangential.sliding);
        let v_t = b.relative_velocity;
        let expected = out_plain.force - v_t * eta_t;
        assert!(
            (out_damped.force - expected).norm() <= 1e-12 * expected.norm().max(1e-12),
            "step {step}: {:?} vs {:?}",
            out_damped.force,
            expected
        );
        let booked = s_damped.books.damping_work - work_before;
        let dissipated = eta_t * v_t.norm_squared() * b.dt;
        assert!((booked - dissipated).abs() <= 1e-12 * dissipated.max(1e-30));
        // The spring itself is the same law either way.
        assert_eq!(out_plain.tangential, out_damped.tangential);
    }
    assert!(s_damped.books.damping_work > 0.0);
}

#[test]
fn sliding_and_frictionless_contacts_feel_no_dashpot() {
    let pair = pair();
    let damping = HertzianViscous::new(GAMMA_N)
        .unwrap()
        .with_tangential_ratio(0.5)
        .unwrap();
    let law = ContactModel::new(Hertz)
        .with_tangential(Mindlin::new(MU).unwrap())
        .with_damping(damping)
        .bind(&pair)
        .unwrap();
    let mut state = law.new_state();
    // 100 m/s over 1e-4 s: a tangential displacement of 1.1e-2, far beyond μ F_N / k_t ≈ 1.7e-3.
    let out = law.update(&mut state, &input(1e-3, 100.0));
    assert!(out.tangential.sliding);
    let tangential = out.force - Vector3::z() * out.force.z;
    assert!((tangential.norm() - MU * out.normal_force).abs() <= 1e-12 * out.normal_force);
    assert_eq!(state.books.damping_work, 0.0);

    let frictionless = ContactModel::new(Hertz)
        .with_damping(damping)
        .bind(&pair)
        .unwrap();
    let mut state = frictionless.new_state();
    let out = frictionless.update(&mut state, &input(1e-3, 0.01));
    assert_eq!(out.force.x, 0.0);
    assert_eq!(out.force.y, 0.0);
    assert_eq!(state.books.damping_work, 0.0);
}

#[test]
fn stiffness_viscous_dashpot_follows_the_normal_stiffness() {
    let pair = pair();
    let eta = 0.3;
    let law = ContactModel::new(Hertz)
        .with_tangential(Mindlin::new(MU).unwrap())
        .with_damping(
            StiffnessViscous::new(eta)
                .unwrap()
                .with_tangential_ratio(2.0)
                .unwrap(),
        )
        .bind(&pair)
        .unwrap();
    let response = law.normal.update(&mut 0.0, 1e-3);
    let expected = 2.0 * eta * (pair.reduced_mass() * response.stiffness).sqrt();
    let got = law.damping.tangential_coefficient(&response, 1e-3);
    assert!((got - expected).abs() <= 1e-12 * expected);
}

#[test]
fn negative_or_non_finite_ratios_are_refused_by_name() {
    for bad in [-0.1, f64::NAN, f64::INFINITY] {
        let err = HertzianViscous::new(GAMMA_N)
            .unwrap()
            .with_tangential_ratio(bad)
            .unwrap_err();
        assert!(
            err.to_string().contains("tangential_damping_ratio"),
            "{err}"
        );
        let err = StiffnessViscous::new(0.1)
            .unwrap()
            .with_tangential_ratio(bad)
            .unwrap_err();
        assert!(
            err.to_string().contains("tangential_damping_ratio"),
            "{err}"
        );
    }
}
