//! The numerical MDR transform (eq. 1) against the closed forms: 1e-6 relative away from the
//! singular point x = 0 (the required accuracy; the achieved error is far smaller).

use mdr_contact::profile::{
    power_law_factor, Cone, FlatPunch, NumericalProfile, PowerLaw, Profile, Sphere,
};
use std::f64::consts::{FRAC_PI_2, PI};

const TOLERANCE: f64 = 1e-6;

/// Sample points from 1 % to 100 % of `half_width`.
fn sample(half_width: f64) -> impl Iterator<Item = f64> {
    (1..=100).map(move |k| half_width * k as f64 / 100.0)
}

fn assert_close(numeric: &dyn Profile, exact: &dyn Profile, half_width: f64, what: &str) {
    for x in sample(half_width) {
        for x in [x, -x] {
            let (got, want) = (numeric.mdr_height(x), exact.mdr_height(x));
            assert!(
                ((got - want) / want).abs() < TOLERANCE,
                "{what}: g({x}) = {got}, closed form {want}"
            );
        }
    }
}

#[test]
fn gamma_factor_has_its_known_values() {
    // κ(1) = π/2 (cone), κ(2) = 2 (paraboloid), κ(3) = 8/3, κ(4) = 8/3 · 6/5 · ... = 16/5·... :
    // κ(n) = √π Γ(n/2+1)/Γ(n/2+1/2): κ(3) = √π (3√π/4) / 1 = 3π/4, κ(4) = √π · 2 / (3√π/4) = 8/3.
    let cases = [
        (1.0, FRAC_PI_2),
        (2.0, 2.0),
        (3.0, 0.75 * PI),
        (4.0, 8.0 / 3.0),
    ];
    for (n, kappa) in cases {
        assert!(
            (power_law_factor(n) / kappa - 1.0).abs() < 1e-13,
            "κ({n}) = {} ≠ {kappa}",
            power_law_factor(n)
        );
    }
    assert!(power_law_factor(0.0).is_nan());
}

#[test]
fn closed_forms_agree_with_each_other() {
    let radius = 0.01;
    let sphere = Sphere::new(radius).unwrap();
    let parabola = PowerLaw::new(1.0 / (2.0 * radius), 2.0).unwrap();
    let beta: f64 = 0.1;
    let cone = Cone::new(beta).unwrap();
    let linear = PowerLaw::new(beta.tan(), 1.0).unwrap();
    for x in sample(1e-3) {
        assert!((sphere.mdr_height(x) / parabola.mdr_height(x) - 1.0).abs() < 1e-13);
        assert!((sphere.height(x) / parabola.height(x) - 1.0).abs() < 1e-13);
        assert!((cone.mdr_height(x) / linear.mdr_height(x) - 1.0).abs() < 1e-13);
    }
    let punch = FlatPunch::new(1e-3).unwrap();
    assert_eq!(punch.mdr_height(0.999e-3), 0.0);
    assert_eq!(punch.mdr_height(-0.5e-3), 0.0);
    assert!(punch.mdr_height(1.001e-3).is_infinite());
}

#[test]
fn numerical_sphere_matches_closed_form() {
    let radius = 6.35e-3;
    let numeric = NumericalProfile::from_height(move |r| r * r / (2.0 * radius));
    assert_close(&numeric, &Sphere::new(radius).unwrap(), 1e-3, "sphere");
    let with_slope = NumericalProfile::from_height_and_slope(
        move |r| r * r / (2.0 * radius),
        move |r| r / radius,
    );
    assert_close(
        &with_slope,
        &Sphere::new(radius).unwrap(),
        1e-3,
        "sphere, exact slope",
    );
}

#[test]
fn numerical_cone_matches_closed_form() {
    let beta: f64 = 0.2;
    let slope = beta.tan();
    let numeric = NumericalProfile::from_height(move |r| r * slope);
    assert_close(&numeric, &Cone::new(beta).unwrap(), 1e-3, "cone");
}

#[test]
fn numerical_power_laws_match_closed_form() {
    for n in [1.5, 3.0, 4.0] {
        let c = 1e3;
        let numeric = NumericalProfile::from_height(move |r: f64| c * r.powf(n));
        assert_close(
            &numeric,
            &PowerLaw::new(c, n).unwrap(),
            1e-3,
            &format!("power law n = {n}"),
        );
    }
}

#[test]
fn tabulated_profiles_match_closed_form() {
    let radius = 6.35e-3;
    let rows = 201;
    let max_radius = 1e-3;
    let radii: Vec<f64> = (0..rows)
        .map(|i| max_radius * i as f64 / (rows - 1) as f64)
        .collect();
    let sphere: Vec<f64> = radii.iter().map(|r| r * r / (2.0 * radius)).collect();
    let table = NumericalProfile::from_table(&radii, &sphere).unwrap();
    assert_close(
        &table,
        &Sphere::new(radius).unwrap(),
        max_radius,
        "tabulated sphere",
    );
    assert_eq!(table.max_radius(), max_radius);
    assert!(table.mdr_height(1.01 * max_radius).is_infinite());
    // A quartic is not reproduced exactly by the spline: this checks the interpolation error
    // (relative to f' ~ r³ it is largest near the axis, so start at 10 % of the table).
    let c = 1e9;
    let quartic: Vec<f64> = radii.iter().map(|r| c * r.powi(4)).collect();
    let table = NumericalProfile::from_table(&radii, &quartic).unwrap();
    let exact = PowerLaw::new(c, 4.0).unwrap();
    for x in sample(max_radius).skip(9) {
        let (got, want) = (table.mdr_height(x), exact.mdr_height(x));
        assert!(
            ((got - want) / want).abs() < TOLERANCE,
            "quartic table at {x}: {got} vs {want}"
        );
    }
}

#[test]
fn a_wrong_slope_is_detected() {
    // Guard against a transform that ignores its input: a sphere's slope with a cone's
    // height must give the sphere's g, not the cone's.
    let radius = 0.01;
    let numeric = NumericalProfile::from_height_and_slope(|r| r, move |r| r / radius);
    let x = 1e-3;
    assert!((numeric.mdr_height(x) / (x * x / radius) - 1.0).abs() < 1e-9);
    assert!((numeric.mdr_height(x) / (FRAC_PI_2 * x) - 1.0).abs() > 0.5);
}
