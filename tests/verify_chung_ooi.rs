//! The Chung & Ooi (2011) benchmark tests at CI resolution (coarse sweeps; the full sweeps run
//! with `mdr-dem verify`). Each test's checks carry their tolerances (`mdr_verify::chung_ooi`
//! constants, listed in `docs/verification.md` with the measured errors): Hertz contact time and
//! peak force within 2·10⁻⁵, elastic `e_n` within 10⁻⁷ (rapier's oblique impacts 2·10⁻³), the
//! gross-sliding impulse theory within 5·10⁻³ of `μ J_n`, rapier against the validator within
//! 10⁻² of `μ J_n` (plus computed geometric allowances), restitution from plasticity within
//! 2·10⁻⁵, and test 4 against the Kharaz, Gorham & Salman (2001) experiment in gross sliding
//! (e_t 0.02, spin 8 %, rebound angles 1.5°/3°).

use mdr_verify::chung_ooi::{self, Resolution};

fn assert_passes(number: u8) {
    let report = chung_ooi::run(number, Resolution::ci()).expect("test runs");
    assert!(!report.checks.is_empty(), "test {number} made no checks");
    assert!(report.passed(), "{report}");
}

#[test]
fn verify_test1_two_identical_spheres_hertz() {
    assert_passes(1);
}

#[test]
fn verify_test2_sphere_on_rigid_plane_hertz() {
    assert_passes(2);
}

#[test]
fn verify_test3_restitution_from_plasticity() {
    assert_passes(3);
}

#[test]
fn verify_test4_oblique_constant_speed_varying_angle() {
    assert_passes(4);
}

/// Test 4 is compared with the experiment: every experimental point at θ ≥ 28° is a check, for
/// both validator laws (e_t 4, spin 4, centre angle 4, contact-point angle 7 points).
#[test]
fn verify_test4_checks_the_experiment() {
    let report = chung_ooi::run(4, Resolution::ci()).expect("test runs");
    let experimental = report
        .checks
        .iter()
        .filter(|c| c.name.contains("experiment (Kharaz"))
        .count();
    assert_eq!(experimental, 2 * (4 + 4 + 4 + 7), "{report}");
}

#[test]
fn verify_test5_oblique_varying_tangential_speed() {
    assert_passes(5);
}

#[test]
fn verify_test6_spinning_sphere_on_plane() {
    assert_passes(6);
}

#[test]
fn verify_test7_identical_spheres_varying_spin() {
    assert_passes(7);
}

#[test]
fn verify_test8_different_spheres_varying_spin() {
    assert_passes(8);
}

/// The checks must fail when the physics is wrong: a law with the wrong modulus (a plane that is
/// not rigid, E* halved) misses Hertz's contact time for the rigid plane.
#[test]
fn verify_detects_a_wrong_modulus() {
    use mdr_verify::{materials, Backend, Collision, Target};
    let m = materials::aluminium_alloy();
    let right = Collision::head_on(
        0.1,
        m,
        Target::Plane {
            material: materials::rigid_for(&m),
        },
        0.2,
    );
    let wrong = Collision {
        target: Target::Plane { material: m },
        ..right
    };
    let hertz = mdr_verify::reference::HertzImpact::new(&right.pair().unwrap(), 0.2);
    let out = wrong.run(Backend::ValidatorMindlin).unwrap();
    let check = mdr_verify::Check::new(
        "contact time",
        out.contact_time,
        hertz.contact_time,
        mdr_verify::Tolerance::Relative(chung_ooi::HERTZ_TOLERANCE),
    );
    assert!(!check.passed(), "{check}");
}

/// A wrong friction coefficient fails the gross-sliding theory.
#[test]
fn verify_detects_a_wrong_friction_coefficient() {
    use mdr_verify::{materials, Backend, Collision, Target};
    let m = materials::aluminium_alloy();
    let c = Collision {
        tangential_speed: 14.0 * 0.4 * 0.2,
        friction: 0.4,
        ..Collision::head_on(
            0.1,
            m,
            Target::Plane {
                material: materials::rigid_for(&m),
            },
            0.2,
        )
    };
    let theory = mdr_verify::reference::sliding_tangential_impulse(
        c.pair().unwrap().reduced_mass(),
        0.4,
        1.0,
        0.2,
        c.slip_velocity(),
    );
    let out = Collision {
        friction: 0.41,
        ..c
    }
    .run(Backend::ValidatorMindlin)
    .unwrap();
    let scale = 0.4 * c.mass() * 2.0 * 0.2;
    let check = mdr_verify::Check::new(
        "J_t",
        out.tangential_impulse / scale,
        theory / scale,
        mdr_verify::Tolerance::Absolute(chung_ooi::SLIDING_TOLERANCE),
    );
    assert!(!check.passed(), "{check}");
}
