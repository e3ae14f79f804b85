//! Every invalid parameter gives its typed error, and the message names the parameter.

use mdr_contact::damping::{HertzianViscous, StiffnessViscous};
use mdr_contact::normal::{
    liggghts_thornton_ning_restitution, thornton_restitution, MdrState, SpringBed,
};
use mdr_contact::prelude::*;
use mdr_contact::profile::{Cone, FlatPunch, NumericalProfile, PowerLaw, Sphere};
use mdr_contact::tangential::SpringBedTangential;

/// `result` is an error of the expected kind whose message names `name`.
fn assert_error<T: std::fmt::Debug>(result: Result<T>, name: &str, kind: &str) {
    let error = result.expect_err(&format!("`{name}` should have been rejected"));
    let variant = match &error {
        ContactError::NotFinite { name: n, .. } => ("NotFinite", *n),
        ContactError::OutOfRange { name: n, .. } => ("OutOfRange", *n),
        ContactError::TooFew { name: n, .. } => ("TooFew", *n),
        ContactError::InvalidTable { name: n, .. } => ("InvalidTable", *n),
    };
    assert_eq!(variant, (kind, name), "{error}");
    assert!(
        error.to_string().contains(name),
        "message `{error}` does not name `{name}`"
    );
}

const E: f64 = 2e11;
const NU: f64 = 0.3;
const RHO: f64 = 7800.0;

#[test]
fn non_finite_values() {
    assert_error(
        Material::new(f64::NAN, NU, RHO),
        "youngs_modulus",
        "NotFinite",
    );
    assert_error(
        Material::new(E, f64::INFINITY, RHO),
        "poisson_ratio",
        "NotFinite",
    );
    assert_error(Material::new(E, NU, f64::NAN), "density", "NotFinite");
    let steel = Material::paper_steel();
    assert_error(
        ContactPair::sphere_on_half_space(f64::NAN, &steel, &steel),
        "radius",
        "NotFinite",
    );
    assert_error(
        MdrElastoPlastic::new(f64::INFINITY, 0.3),
        "q_c",
        "NotFinite",
    );
    assert_error(
        MdrElastoPlastic::new(3.8e5, f64::NAN),
        "theta_ratio",
        "NotFinite",
    );
    assert_error(Mindlin::new(f64::NAN), "mu", "NotFinite");
    assert_error(Thornton::new(f64::INFINITY), "yield_stress", "NotFinite");
}

#[test]
fn youngs_modulus_must_be_positive() {
    assert_error(Material::new(0.0, NU, RHO), "youngs_modulus", "OutOfRange");
    assert_error(Material::new(-1.0, NU, RHO), "youngs_modulus", "OutOfRange");
}

#[test]
fn poisson_ratio_must_lie_in_minus_one_to_one_half() {
    assert_error(
        Material::new(E, 0.5000001, RHO),
        "poisson_ratio",
        "OutOfRange",
    );
    assert_error(Material::new(E, -1.0, RHO), "poisson_ratio", "OutOfRange");
    assert!(Material::new(E, 0.5, RHO).is_ok());
    assert!(Material::new(E, -0.999, RHO).is_ok());
}

#[test]
fn density_must_be_positive() {
    assert_error(Material::new(E, NU, 0.0), "density", "OutOfRange");
}

#[test]
fn radius_must_be_positive() {
    let steel = Material::paper_steel();
    assert_error(
        ContactPair::sphere_on_half_space(0.0, &steel, &steel),
        "radius",
        "OutOfRange",
    );
    assert_error(
        ContactPair::sphere_on_sphere(1e-3, &steel, -1e-3, &steel),
        "target_radius",
        "OutOfRange",
    );
    assert_error(
        ContactPair::new(1e11, 4e10, -1.0, 1e-3),
        "effective_radius",
        "OutOfRange",
    );
    assert_error(Sphere::new(0.0), "radius", "OutOfRange");
}

#[test]
fn critical_line_load_must_not_be_negative() {
    assert_error(MdrElastoPlastic::new(-1.0, 0.37), "q_c", "OutOfRange");
    assert_error(
        MdrElastoPlastic::with_hardening_modulus(-1.0, 1e10),
        "q_c",
        "OutOfRange",
    );
    assert_error(
        SpringBed::new(Sphere::new(1e-3).unwrap(), 1e11, -1.0, 0.37, 1e-4, 100),
        "q_c",
        "OutOfRange",
    );
}

#[test]
fn hardening_ratio_must_lie_in_zero_one() {
    assert_error(
        MdrElastoPlastic::new(3.8e5, 1.01),
        "theta_ratio",
        "OutOfRange",
    );
    assert_error(
        MdrElastoPlastic::new(3.8e5, -0.01),
        "theta_ratio",
        "OutOfRange",
    );
    assert_error(
        SpringBed::new(Sphere::new(1e-3).unwrap(), 1e11, 3.8e5, 1.5, 1e-4, 100),
        "theta_ratio",
        "OutOfRange",
    );
}

#[test]
fn absolute_hardening_above_e_star_is_rejected_at_bind() {
    let pair = ContactPair::paper_fig2();
    let params =
        MdrElastoPlastic::with_hardening_modulus(3.8e5, 2.0 * pair.effective_modulus()).unwrap();
    assert_error(params.bind(&pair), "theta", "OutOfRange");
    assert_error(
        SpringBed::sphere(&pair, &params, 100),
        "theta",
        "OutOfRange",
    );
    assert_error(
        MdrElastoPlastic::with_hardening_modulus(3.8e5, -1.0),
        "theta",
        "OutOfRange",
    );
    let fine = MdrElastoPlastic::with_hardening_modulus(3.8e5, 0.37 * pair.effective_modulus());
    assert!(fine.unwrap().bind(&pair).is_ok());
}

#[test]
fn fewer_than_two_springs() {
    let pair = ContactPair::paper_fig2();
    for n in [0, 1] {
        assert_error(
            SpringBed::sphere(&pair, &MdrElastoPlastic::paper(), n),
            "n_springs",
            "TooFew",
        );
    }
    assert!(SpringBed::sphere(&pair, &MdrElastoPlastic::paper(), 2).is_ok());
    let bed = SpringBed::sphere(&pair, &MdrElastoPlastic::paper(), 10).unwrap();
    assert_error(bed.n_springs(1), "n_springs", "TooFew");
}

#[test]
fn spring_bed_geometry() {
    let pair = ContactPair::paper_fig2();
    let bed = SpringBed::sphere(&pair, &MdrElastoPlastic::paper(), 10).unwrap();
    assert_error(bed.clone().half_width(0.0), "half_width", "OutOfRange");
    assert_error(bed.half_width(f64::NAN), "half_width", "NotFinite");
    let sphere = Sphere::new(1e-3).unwrap();
    assert_error(
        SpringBed::new(sphere, 0.0, 3.8e5, 0.3, 1e-4, 10),
        "effective_modulus",
        "OutOfRange",
    );
    assert_error(
        SpringBed::with_spacing(sphere, 1e11, 3.8e5, 0.3, 1e-4, 0.0),
        "spacing",
        "OutOfRange",
    );
    // A table ends at its last radius: the bed may not reach beyond.
    let radii = [0.0, 1e-4, 2e-4, 3e-4];
    let heights: Vec<f64> = radii.iter().map(|r| r * r).collect();
    let table = NumericalProfile::from_table(&radii, &heights).unwrap();
    assert_error(
        SpringBed::new(table, 1e11, 3.8e5, 0.3, 4e-4, 10),
        "half_width",
        "OutOfRange",
    );
}

#[test]
fn friction_coefficient_must_not_be_negative() {
    assert_error(Mindlin::new(-0.1), "mu", "OutOfRange");
    assert_error(
        SpringBedTangential::from_parts(4e10, -0.1),
        "mu",
        "OutOfRange",
    );
    assert_error(
        SpringBedTangential::from_parts(0.0, 0.3),
        "effective_shear_modulus",
        "OutOfRange",
    );
}

#[test]
fn damping_coefficients_must_not_be_negative() {
    assert_error(HertzianViscous::new(-1.0), "gamma_n", "OutOfRange");
    assert_error(StiffnessViscous::new(-1.0), "eta", "OutOfRange");
}

#[test]
fn yield_stress_must_be_positive() {
    assert_error(Thornton::new(0.0), "yield_stress", "OutOfRange");
}

#[test]
fn profile_parameters() {
    assert_error(Cone::new(0.0), "inclination", "OutOfRange");
    assert_error(
        Cone::new(std::f64::consts::FRAC_PI_2),
        "inclination",
        "OutOfRange",
    );
    assert_error(FlatPunch::new(-1.0), "punch_radius", "OutOfRange");
    assert_error(PowerLaw::new(1.0, 0.0), "exponent", "OutOfRange");
    assert_error(PowerLaw::new(-1.0, 2.0), "coefficient", "OutOfRange");
}

#[test]
fn bad_tables() {
    let name = "profile_table";
    let good = [0.0, 1.0, 2.0, 3.0];
    assert!(NumericalProfile::from_table(&good, &good).is_ok());
    // Mismatched lengths.
    assert_error(
        NumericalProfile::from_table(&good, &good[..3]),
        name,
        "InvalidTable",
    );
    // Too few rows.
    assert_error(
        NumericalProfile::from_table(&good[..3], &good[..3]),
        name,
        "TooFew",
    );
    // Unsorted or repeated radii.
    assert_error(
        NumericalProfile::from_table(&[0.0, 2.0, 1.0, 3.0], &good),
        name,
        "InvalidTable",
    );
    assert_error(
        NumericalProfile::from_table(&[0.0, 1.0, 1.0, 3.0], &good),
        name,
        "InvalidTable",
    );
    // Non-finite entries.
    assert_error(
        NumericalProfile::from_table(&good, &[0.0, f64::NAN, 2.0, 3.0]),
        name,
        "InvalidTable",
    );
    // Not starting on the axis.
    assert_error(
        NumericalProfile::from_table(&[0.5, 1.0, 2.0, 3.0], &good),
        name,
        "InvalidTable",
    );
    let message = NumericalProfile::from_table(&[0.0, 2.0, 1.0, 3.0], &good)
        .unwrap_err()
        .to_string();
    assert!(message.contains("increase"), "{message}");
}

/// The energy route (`MdrLaw::impact`) and Thornton's closed forms refuse a speed that is NaN,
/// infinite or negative instead of answering `e = 1`; speed 0 is the elastic limit.
#[test]
fn impact_speed_must_be_finite_and_not_negative() {
    let pair = ContactPair::paper_fig2();
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let m = pair.reduced_mass();
    let fresh = MdrState::default();
    assert_error(law.impact(&fresh, m, f64::NAN), "speed", "NotFinite");
    assert_error(law.impact(&fresh, m, f64::INFINITY), "speed", "NotFinite");
    assert_error(law.impact(&fresh, m, -1.0), "speed", "OutOfRange");
    assert_error(law.impact(&fresh, m, 1.0e-3 - 1.0), "speed", "OutOfRange");
    assert_error(law.impact(&fresh, f64::NAN, 1.0), "mass", "NotFinite");
    assert_error(law.impact(&fresh, 0.0, 1.0), "mass", "OutOfRange");
    let rest = law.impact(&fresh, m, 0.0).unwrap();
    assert_eq!((rest.restitution, rest.max_overlap), (1.0, 0.0));
    assert_eq!(rest.state, fresh);
    for bad in [f64::NAN, f64::NEG_INFINITY, -0.5] {
        let kind = if bad.is_finite() {
            "OutOfRange"
        } else {
            "NotFinite"
        };
        assert_error(thornton_restitution(bad), "speed_over_yield_speed", kind);
        assert_error(
            liggghts_thornton_ning_restitution(bad),
            "speed_over_yield_speed",
            kind,
        );
    }
}
