//! The profiles of eq. (1) against results written out here: the closed forms of the sphere,
//! cone, flat punch and power law (heights, MDR images, accessors, the parameter errors a user
//! sees, word for word); the factor `κ(n) = √π Γ(n/2 + 1)/Γ(n/2 + 1/2)` from tabulated values of
//! `Γ`; the numerical transform where it is exact up to round-off (exact slopes, smooth or with
//! an integrable singularity at the axis, a fourth-order difference of a quartic, a spline table
//! of a cubic), and
//! the spline's and the table's errors word for word. Tolerances are a few times the round-off
//! measured; each test fails on mutants of `profile/` and `quadrature.rs` that the older tests
//! let through (docs/verification.md §5).

use mdr_contact::profile::{
    power_law_factor, Cone, CubicSpline, FlatPunch, NumericalProfile, PowerLaw, Profile, Sphere,
};
use std::f64::consts::{FRAC_PI_2, PI};

/// `|got − want| ≤ tolerance · |want|`.
fn assert_relative(got: f64, want: f64, tolerance: f64, what: &str) {
    assert!(
        (got - want).abs() <= tolerance * want.abs(),
        "{what}: {got} vs {want} (relative {:e})",
        (got - want).abs() / want.abs()
    );
}

/// The message of an error, which a user reads.
fn message<T: std::fmt::Debug>(result: mdr_contact::Result<T>) -> String {
    result.expect_err("should have been refused").to_string()
}

/// `Γ(1/4)` and `Γ(3/4)` (Abramowitz & Stegun, table 6.1 and 6.1.17 with `Γ(1/4)Γ(3/4) = π√2`).
const GAMMA_QUARTER: f64 = 3.625_609_908_221_908;
const GAMMA_THREE_QUARTERS: f64 = 1.225_416_702_465_177_6;

#[test]
fn closed_form_profiles_have_their_heights_images_and_parameters() {
    let r = 1e-3;
    let sphere = Sphere::new(0.01).unwrap();
    assert_eq!(sphere.radius(), 0.01);
    assert_eq!(sphere.max_radius(), f64::INFINITY);
    for x in [r, -r] {
        assert_relative(sphere.height(x), 5e-5, 1e-15, "sphere r²/2R");
        assert_relative(sphere.mdr_height(x), 1e-4, 1e-15, "sphere x²/R");
    }

    let beta: f64 = 0.3;
    let cone = Cone::new(beta).unwrap();
    assert_relative(cone.slope(), 0.309_336_249_609_623_3, 1e-15, "tan 0.3");
    assert_eq!(cone.max_radius(), f64::INFINITY);
    for x in [r, -r] {
        assert_relative(
            cone.height(x),
            3.093_362_496_096_233e-4,
            1e-15,
            "cone r tan β",
        );
        assert_relative(
            cone.mdr_height(x),
            FRAC_PI_2 * 3.093_362_496_096_233e-4,
            1e-15,
            "cone (π/2) |x| tan β",
        );
    }

    let punch = FlatPunch::new(r).unwrap();
    assert_eq!(punch.radius(), r);
    assert_eq!(punch.max_radius(), f64::INFINITY);
    // The face reaches its edge `|r| = a₀` inclusive; the wall stands beyond.
    for x in [0.0, r, -r, 0.5 * r] {
        assert_eq!(punch.height(x), 0.0, "punch face at {x}");
        assert_eq!(punch.mdr_height(x), 0.0, "punch image at {x}");
    }
    for x in [1.000_001 * r, -1.000_001 * r] {
        assert_eq!(punch.height(x), f64::INFINITY, "punch wall at {x}");
        assert_eq!(punch.mdr_height(x), f64::INFINITY, "punch image at {x}");
    }

    // f = 2 r³: g = κ(3) 2 |x|³ with κ(3) = 3π/4.
    let cubic = PowerLaw::new(2.0, 3.0).unwrap();
    assert_eq!(cubic.coefficient(), 2.0);
    assert_eq!(cubic.exponent(), 3.0);
    assert_eq!(cubic.max_radius(), f64::INFINITY);
    for x in [r, -r] {
        assert_relative(cubic.height(x), 2e-9, 1e-15, "2 |r|³");
        assert_relative(cubic.mdr_height(x), 1.5 * PI * 1e-9, 1e-14, "(3π/4) 2 |x|³");
    }
}

#[test]
fn profile_parameters_are_refused_with_their_name_value_and_range() {
    assert_eq!(
        message(Sphere::new(0.0)),
        "parameter `radius` = 0 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        message(Sphere::new(f64::NAN)),
        "parameter `radius` must be a finite number, got NaN"
    );
    for bad in [0.0, -0.1, FRAC_PI_2, 2.0] {
        assert_eq!(
            message(Cone::new(bad)),
            format!("parameter `inclination` = {bad} is outside the allowed range (0, pi/2)")
        );
    }
    assert_eq!(
        message(Cone::new(f64::INFINITY)),
        "parameter `inclination` must be a finite number, got inf"
    );
    // Just inside both ends of (0, π/2).
    assert!(Cone::new(1e-300).is_ok());
    assert!(Cone::new(FRAC_PI_2 - 4.0 * f64::EPSILON).is_ok());
    assert_eq!(
        message(FlatPunch::new(-1.0)),
        "parameter `punch_radius` = -1 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        message(PowerLaw::new(0.0, 2.0)),
        "parameter `coefficient` = 0 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        message(PowerLaw::new(1.0, -1.0)),
        "parameter `exponent` = -1 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        message(PowerLaw::new(1.0, f64::NAN)),
        "parameter `exponent` must be a finite number, got NaN"
    );
}

#[test]
fn power_law_factor_matches_tabulated_gamma_values() {
    let sqrt_pi = PI.sqrt();
    // κ(1/2) = √π Γ(5/4)/Γ(3/4), Γ(5/4) = Γ(1/4)/4.
    let half = sqrt_pi * 0.25 * GAMMA_QUARTER / GAMMA_THREE_QUARTERS;
    // κ(3/2) = √π Γ(7/4)/Γ(5/4) = 3√π Γ(3/4)/Γ(1/4).
    let three_halves = 3.0 * sqrt_pi * GAMMA_THREE_QUARTERS / GAMMA_QUARTER;
    // κ(9) = √π Γ(11/2)/Γ(5) = √π (945√π/32)/24; κ(10) = √π Γ(6)/Γ(11/2) = 120·32/945.
    let cases = [
        (0.5, half),
        (1.5, three_halves),
        (9.0, 945.0 * PI / 768.0),
        (10.0, 256.0 / 63.0),
    ];
    for (n, kappa) in cases {
        assert_relative(power_law_factor(n), kappa, 1e-14, &format!("κ({n})"));
    }
    for n in [f64::NAN, 0.0, -1.0, -2.5] {
        assert!(
            power_law_factor(n).is_nan(),
            "κ({n}) = {}",
            power_law_factor(n)
        );
    }
}

#[test]
fn numerical_transform_is_exact_where_its_integrand_is_smooth() {
    let c = 3.0e3;
    let half_width = 1e-3;
    // f = c r²: f'(x sin φ) = 2c x sin φ, g = 2c x² (the quadrature of sin φ over [0, π/2]).
    let parabola =
        NumericalProfile::from_height_and_slope(move |r| c * r * r, move |r| 2.0 * c * r);
    // f = c r⁴: the fourth-order central difference is exact for a quartic; g = (8/3) c x⁴.
    let quartic = NumericalProfile::from_height(move |r: f64| c * r.powi(4));
    // f = c r^{3/2} with its exact slope: √(sin φ) has an endpoint singularity in its
    // derivative, which the adaptive bisection resolves; g = κ(3/2) c |x|^{3/2}.
    let kappa = 3.0 * PI.sqrt() * GAMMA_THREE_QUARTERS / GAMMA_QUARTER;
    let root = |c: f64| {
        NumericalProfile::from_height_and_slope(
            move |r: f64| c * r.powf(1.5),
            move |r: f64| 1.5 * c * r.sqrt(),
        )
    };
    // The tolerance is relative to the integral: a small one (c = 10⁻⁶) is resolved as well.
    let (root, small_root) = (root(c), root(1e-6));
    // f = c r^{1/2}: the integrand ∝ 1/√(sin φ) is singular at φ = 0 and takes the bisection
    // far towards it; g = κ(1/2) c |x|^{1/2} (the error measured: 1.6·10⁻¹³).
    let kappa_half = PI.sqrt() * 0.25 * GAMMA_QUARTER / GAMMA_THREE_QUARTERS;
    let sqrt_profile = NumericalProfile::from_height_and_slope(
        move |r: f64| c * r.sqrt(),
        move |r: f64| 0.5 * c / r.sqrt(),
    );
    assert_eq!(parabola.max_radius(), f64::INFINITY);
    assert_eq!(parabola.mdr_height(0.0), 0.0);
    for k in 1..=20 {
        let x = half_width * k as f64 / 20.0;
        for x in [x, -x] {
            let a = x.abs();
            assert_relative(parabola.mdr_height(x), 2.0 * c * a * a, 1e-15, "2c x²");
            assert_relative(parabola.height(x), c * a * a, 1e-15, "c r²");
            assert_relative(
                quartic.mdr_height(x),
                8.0 / 3.0 * c * a.powi(4),
                1e-13,
                "(8/3) c x⁴",
            );
            assert_relative(
                root.mdr_height(x),
                kappa * c * a.powf(1.5),
                1e-13,
                "κ c x^1.5",
            );
            assert_relative(
                sqrt_profile.mdr_height(x),
                kappa_half * c * a.sqrt(),
                5e-13,
                "κ(1/2) c x^0.5",
            );
            assert_relative(
                small_root.mdr_height(x),
                kappa * 1e-6 * a.powf(1.5),
                1e-13,
                "κ 10⁻⁶ x^1.5",
            );
        }
    }
    // The slopes the transform integrates.
    assert_relative(
        quartic.slope(0.5),
        4.0 * c * 0.125,
        3e-13,
        "4c r³ by differences",
    );
    assert_relative(parabola.slope(0.5), c, 1e-15, "2c r given");
}

#[test]
fn a_table_of_a_cubic_is_transformed_exactly_up_to_its_last_radius() {
    // f = c r³ + r²/(2R) on an uneven grid: the clamped spline with four-point end slopes
    // reproduces every cubic, so g = κ(3) c x³ + x²/R to round-off.
    let (c, radius) = (2e4, 0.01);
    let f = move |r: f64| c * r * r * r + r * r / (2.0 * radius);
    let radii = [0.0, 1e-4, 2.5e-4, 3e-4, 5e-4, 7.5e-4, 7.6e-4, 1e-3];
    let heights: Vec<f64> = radii.iter().map(|&r| f(r)).collect();
    let table = NumericalProfile::from_table(&radii, &heights).unwrap();
    assert_eq!(table.max_radius(), 1e-3);
    assert_eq!(format!("{table:?}"), "NumericalProfile(table of 8 rows)");
    assert_eq!(table.mdr_height(0.0), 0.0);
    for k in 1..=40 {
        let x = 1e-3 * k as f64 / 40.0;
        let want = 0.75 * PI * c * x * x * x + x * x / radius;
        for x in [x, -x] {
            assert_relative(table.mdr_height(x), want, 2e-14, "table g(x)");
            assert_relative(table.height(x), f(x.abs()), 3e-14, "table f(r)");
        }
    }
    // Beyond the last radius no spring can touch.
    for x in [1.000_001e-3, -1.000_001e-3] {
        assert_eq!(table.height(x), f64::INFINITY);
        assert_eq!(table.mdr_height(x), f64::INFINITY);
    }
    assert_eq!(
        format!("{:?}", NumericalProfile::from_height(|r| r)),
        "NumericalProfile(function, slope by finite differences)"
    );
    assert_eq!(
        format!(
            "{:?}",
            NumericalProfile::from_height_and_slope(|r| r, |_| 1.0)
        ),
        "NumericalProfile(function with exact slope)"
    );
}

#[test]
fn a_spline_reproduces_a_cubic_inside_and_beyond_its_knots() {
    let cubic = |x: f64| 0.7 - 1.3 * x + 2.1 * x * x - 0.4 * x * x * x;
    let slope = |x: f64| -1.3 + 4.2 * x - 1.2 * x * x;
    let knots = [-1.0, -0.2, 0.0, 0.9, 1.0, 2.5, 4.0];
    let values: Vec<f64> = knots.iter().map(|&x| cubic(x)).collect();
    let spline = CubicSpline::new("t", &knots, &values).unwrap();
    assert_eq!(spline.knots(), &knots);
    for k in 0..=120 {
        // From −2 to 5: the end pieces extend the cubic beyond both ends.
        let x = -2.0 + 7.0 * k as f64 / 120.0;
        assert!((spline.value(x) - cubic(x)).abs() < 1e-13, "y({x})");
        assert!((spline.derivative(x) - slope(x)).abs() < 2e-13, "y'({x})");
    }
}

#[test]
fn bad_tables_are_refused_with_the_row_at_fault() {
    let good = [0.0, 1.0, 2.0, 3.0];
    assert_eq!(
        message(NumericalProfile::from_table(&good, &good[..3])),
        "invalid table `profile_table`: 4 abscissae but 3 values: the columns must have equal length"
    );
    assert_eq!(
        message(NumericalProfile::from_table(&good[..3], &good[..3])),
        "parameter `profile_table` = 3 is too small: at least 4 required"
    );
    assert_eq!(
        message(NumericalProfile::from_table(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0, f64::NAN, 3.0])),
        "invalid table `profile_table`: row 2 = (2, NaN) is not finite: every entry must be a finite number"
    );
    assert_eq!(
        message(NumericalProfile::from_table(&[0.0, 1.0, 2.0, f64::INFINITY], &good)),
        "invalid table `profile_table`: row 3 = (inf, 3) is not finite: every entry must be a finite number"
    );
    assert_eq!(
        message(NumericalProfile::from_table(&[0.0, 1.0, 1.0, 3.0], &good)),
        "invalid table `profile_table`: abscissae must increase strictly, but row 2 has 1 after 1"
    );
    assert_eq!(
        message(NumericalProfile::from_table(&[0.0, 2.0, 1.0, 3.0], &good)),
        "invalid table `profile_table`: abscissae must increase strictly, but row 2 has 1 after 2"
    );
    assert_eq!(
        message(NumericalProfile::from_table(&[0.5, 1.0, 2.0, 3.0], &good)),
        "invalid table `profile_table`: the first radius must be 0 (the axis), got 0.5"
    );
    assert_eq!(
        message(CubicSpline::new("knots", &good[..2], &good[..2])),
        "parameter `knots` = 2 is too small: at least 4 required"
    );
}
