//! The law crate's registered laws in their present form against expectations written out here:
//! Thornton's history as the three parts a history kept outside the crate stores (`δ*`, the
//! unloading coefficient `(4/3) E* √R_p` of his eqs. 24–26 and `δ_p`), given back and rebuilt.
//! Each test catches mutants of `normal/thornton.rs` (and the other law files named in
//! docs/verification.md §5) that the crate's other tests miss.

use mdr_contact::normal::NormalLaw;
use mdr_contact::prelude::*;
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
