//! The law crate's registered laws in their present form against expectations written out here:
//! Thornton's history as the three parts a history kept outside the crate stores (`δ*`, the
//! unloading coefficient `(4/3) E* √R_p` of his eqs. 24–26 and `δ_p`), given back and rebuilt;
//! what a law without adhesion says through the normal law's defaults (it never holds and lets go
//! where its force vanishes, at its residual overlap); the frictionless law's free sliding; which
//! rolling models resist rolling; the parameter-free laws built by name from no values. Each test
//! catches mutants of `normal/hertz.rs`, `normal/mod.rs`, `tangential/mod.rs`, `damping.rs`,
//! `rolling.rs` or `normal/thornton.rs` that the crate's other tests miss (docs/verification.md
//! §5).

use mdr_contact::nalgebra::Vector3;
use mdr_contact::normal::{NormalLaw, NormalResponse};
use mdr_contact::prelude::*;
use mdr_contact::rolling::{EpsdRolling, NoRolling, RollingModel};
use std::f64::consts::PI;

const P_Y: f64 = 1.0e9;

/// `a` equals `b` to a relative `tol`.
fn close(a: f64, b: f64, tol: f64) -> bool {
    a.is_finite() && b.is_finite() && (a - b).abs() <= tol * b.abs()
}

#[test]
fn a_thornton_history_gives_back_its_parts_and_is_rebuilt_from_them() {
    let pair = ContactPair::paper_fig2();
    let (e, r) = (pair.effective_modulus(), pair.effective_radius());
    let law = Thornton::new(P_Y).unwrap().bind(&pair).unwrap();
    // δ_y = R (π p_y / (2E*))² (his eq. 27's yield overlap).
    let d_y = r * (PI * P_Y / (2.0 * e)).powi(2);

    // Elastic: the largest overlap alone, no unloading curve yet.
    let mut state = ThorntonState::default();
    law.update(&mut state, 0.5 * d_y);
    assert_eq!(state.parts(), [0.5 * d_y, 0.0, 0.0]);

    // Plastic to δ* = 4 δ_y: F* = F_y + π p_y R (δ* − δ_y) (eq. 22), a*² = R δ*,
    // R_p = 4E* a*³/(3F*), δ_p = δ* − (3F*/(4E*√R_p))^{2/3} (eqs. 24–26).
    let d_max = 4.0 * d_y;
    law.update(&mut state, d_max);
    let f_y = 4.0 / 3.0 * e * r.sqrt() * d_y.powf(1.5);
    let f_max = f_y + PI * P_Y * r * (d_max - d_y);
    let a_max = (r * d_max).sqrt();
    let r_p = 4.0 * e * a_max.powi(3) / (3.0 * f_max);
    let coefficient = 4.0 / 3.0 * e * r_p.sqrt();
    let d_p = d_max - (3.0 * f_max / (4.0 * e * r_p.sqrt())).powf(2.0 / 3.0);
    let [max_overlap, unloading_coefficient, residual_overlap] = state.parts();
    assert_eq!(max_overlap, d_max);
    assert!(close(unloading_coefficient, coefficient, 1e-12));
    assert!(close(residual_overlap, d_p, 1e-12));
    assert!(d_p > 0.0 && d_p < d_max);

    // Rebuilt from its parts: the same history, unloading on the same curve
    // F = (4/3) E* √R_p (δ − δ_p)^{3/2}, and not the Hertz curve of a fresh contact.
    let mut rebuilt =
        ThorntonState::from_parts(max_overlap, unloading_coefficient, residual_overlap);
    assert_eq!(rebuilt, state);
    let d = 0.5 * (d_p + d_max);
    let unloading = law.update(&mut rebuilt, d);
    assert!(close(
        unloading.force,
        coefficient * (d - d_p).powf(1.5),
        1e-12
    ));
    assert_eq!(law.residual_overlap(&rebuilt), residual_overlap);

    // Any three values come back in their order.
    assert_eq!(
        ThorntonState::from_parts(1.5, 2.5, 0.25).parts(),
        [1.5, 2.5, 0.25]
    );
}

#[test]
fn a_law_without_adhesion_never_holds_and_lets_go_at_its_residual_overlap() {
    let pair = ContactPair::paper_fig2();
    let (e, r) = (pair.effective_modulus(), pair.effective_radius());
    // Hertz: elastic, the force vanishes at δ = 0 on unloading.
    let hertz = Hertz.bind(&pair).unwrap();
    let mut state = 0.0;
    hertz.update(&mut state, 1e-6);
    assert!(!hertz.holds(&state));
    assert_eq!(hertz.detachment_overlap(&state), 0.0);
    assert_eq!(hertz.pull_off_force(), 0.0);
    // Thornton past yield: the force vanishes at δ_p = δ* − (3F*/(4E*√R_p))^{2/3} (eqs. 24–26).
    let law = Thornton::new(P_Y).unwrap().bind(&pair).unwrap();
    let d_y = r * (PI * P_Y / (2.0 * e)).powi(2);
    let d_max = 4.0 * d_y;
    let mut state = ThorntonState::default();
    law.update(&mut state, d_max);
    let f_max = 4.0 / 3.0 * e * r.sqrt() * d_y.powf(1.5) + PI * P_Y * r * (d_max - d_y);
    let r_p = 4.0 * e * (r * d_max).powf(1.5) / (3.0 * f_max);
    let d_p = d_max - (3.0 * f_max / (4.0 * e * r_p.sqrt())).powf(2.0 / 3.0);
    assert!(!law.holds(&state));
    assert!(close(law.detachment_overlap(&state), d_p, 1e-12));
    // Unloaded to just above δ_p it still pushes and does not hold.
    law.update(&mut state, 1.001 * d_p);
    assert!(!law.holds(&state));
}

#[test]
fn a_frictionless_contact_slides_freely_and_stores_nothing() {
    let law = Frictionless.bind(&ContactPair::paper_fig2()).unwrap();
    let input = TangentialInput {
        normal: Vector3::z(),
        displacement_increment: Vector3::new(1e-6, -2e-6, 0.0),
        normal_response: NormalResponse {
            force: 10.0,
            contact_radius: 1e-4,
            stiffness: 1e6,
        },
    };
    let response = law.update(&mut (), &input);
    assert_eq!(
        response,
        TangentialResponse {
            force: Vector3::zeros(),
            sliding: true,
            dissipated: 0.0,
            elastic_energy: 0.0,
            stiffness_energy: 0.0,
        }
    );
    assert_eq!(law.elastic_energy(&()), 0.0);
}

/// A rolling model that keeps the trait's default for `resists`.
#[derive(Clone)]
struct AlwaysRolling;

impl RollingModel for AlwaysRolling {
    type Law = NoRolling;
    fn bind(&self, _pair: &ContactPair) -> mdr_contact::Result<NoRolling> {
        Ok(NoRolling)
    }
}

#[test]
fn only_a_positive_rolling_coefficient_resists_rolling() {
    // `|M_r| ≤ μ_r R F_N`: no torque at all without the model or at μ_r = 0; a model that does
    // not say otherwise may give one.
    assert!(!NoRolling.resists());
    assert!(!EpsdRolling::new(0.0).unwrap().resists());
    assert!(EpsdRolling::new(1e-300).unwrap().resists());
    assert!(EpsdRolling::new(0.3).unwrap().resists());
    assert!(AlwaysRolling.resists());
}

#[test]
fn a_law_without_parameters_is_built_from_no_values_and_refuses_any() {
    use mdr_contact::params::Declared;
    fn refused<L: Declared>(name: &str) {
        assert_eq!(
            L::from_values(&[1.0]).err().unwrap().to_string(),
            format!("invalid table `{name}`: 1 parameter values given, the law declares 0")
        );
    }
    assert_eq!(Hertz::from_values(&[]).unwrap(), Hertz);
    assert_eq!(Frictionless::from_values(&[]).unwrap(), Frictionless);
    assert_eq!(NoDamping::from_values(&[]).unwrap(), NoDamping);
    assert_eq!(NoRolling::from_values(&[]).unwrap(), NoRolling);
    refused::<Hertz>("hertz");
    refused::<Frictionless>("none");
    refused::<NoDamping>("none");
    refused::<NoRolling>("none");
}
