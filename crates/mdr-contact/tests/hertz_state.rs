//! The Hertz law's history is the largest overlap so far (what the scenes report as `d_max`
//! for a Hertz contact): it grows with the overlap and never shrinks on unloading. Written for
//! the mutants of `HertzLaw::update` that a restitution or force check cannot see (Hertz is
//! elastic, so its force does not depend on the history).

use mdr_contact::prelude::*;

#[test]
fn hertz_state_is_the_largest_overlap_so_far() {
    let pair = ContactPair::paper_fig2();
    let law = Hertz.bind(&pair).unwrap();
    let mut state = 0.0;
    for (overlap, largest) in [
        (1.0e-6, 1.0e-6),
        (3.0e-6, 3.0e-6),
        (2.0e-6, 3.0e-6),
        (3.0e-6, 3.0e-6),
        (4.0e-6, 4.0e-6),
        (-1.0e-6, 4.0e-6),
    ] {
        let response = law.update(&mut state, overlap);
        assert_eq!(state, largest, "after overlap {overlap}");
        // The force is Hertz's at the current overlap whatever the history.
        let hertz = law.force(overlap);
        assert!(
            (response.force - hertz).abs() <= 1e-14 * hertz,
            "{} vs {hertz}",
            response.force
        );
    }
}

/// The rest of the `NormalLaw` view of Hertz, against Hertz's formulas written out: contact
/// radius `a = √(R d)`, tangent stiffness `2E* a`, stored energy `(8/15) E* √R d^{5/2}`, no
/// residual overlap, no dissipation, no yield.
#[test]
fn hertz_law_reports_the_hertz_quantities() {
    let pair = ContactPair::paper_fig2();
    let law = Hertz.bind(&pair).unwrap();
    let (r, e_star) = (pair.effective_radius(), pair.effective_modulus());
    let mut state = 0.0;
    let d = 5.0e-6;
    let response = law.update(&mut state, d);
    let a = (r * d).sqrt();
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-14 * y.abs();
    assert!(
        close(response.contact_radius, a),
        "a = {}",
        response.contact_radius
    );
    assert!(
        close(response.stiffness, 2.0 * e_star * a),
        "k = {}",
        response.stiffness
    );
    assert!(close(
        response.force,
        4.0 / 3.0 * e_star * r.sqrt() * d.powf(1.5)
    ));
    assert_eq!(law.max_overlap(&state), d);
    let stored = 8.0 / 15.0 * e_star * r.sqrt() * d.powf(2.5);
    assert!(close(law.elastic_energy(&state, d), stored));
    assert!(close(
        law.elastic_energy(&state, 0.5 * d),
        stored * 0.5f64.powf(2.5)
    ));
    assert_eq!(law.residual_overlap(&state), 0.0);
    assert_eq!(law.dissipated_work(&state), 0.0);
    assert_eq!(law.yield_overlap(), f64::INFINITY);
}
