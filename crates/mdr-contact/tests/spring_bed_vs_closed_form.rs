//! The discrete spring bed (eqs. 2, 6, 9–13, 2,001 springs) against the continuum closed form
//! (docs/theory.md §4, `MdrLaw`) on random load/unload/reload histories with separation and re-touch:
//! the force must agree within 0.2 % of the peak force of the history at every point.
//!
//! The two implementations share nothing but the parameters: the bed integrates eq. (10)–(13)
//! spring by spring with its own per-spring history; the closed form uses `d_max` only.

use mdr_contact::normal::{SpringBed, SpringBedState};
use mdr_contact::prelude::*;
use proptest::prelude::*;

const SPRINGS: usize = 2001;
const TOLERANCE: f64 = 2e-3;

/// Largest overlap a history may reach (m); the bed covers its contact radius.
const MAX_OVERLAP: f64 = 3e-5;

fn laws(critical_over_max: f64, theta: f64) -> (SpringBed, MdrLaw) {
    let pair = ContactPair::paper_fig2();
    // q_c such that u_c = critical_over_max · MAX_OVERLAP.
    let u_c = critical_over_max * MAX_OVERLAP;
    let q_c = 2.0 * pair.effective_modulus() * u_c / std::f64::consts::PI;
    let params = MdrElastoPlastic::new(q_c, theta).unwrap();
    let half_width = 1.02 * (pair.effective_radius() * MAX_OVERLAP).sqrt();
    let bed = SpringBed::sphere(&pair, &params, SPRINGS)
        .unwrap()
        .half_width(half_width)
        .unwrap();
    (bed, params.bind(&pair).unwrap())
}

/// Compare both laws along piecewise-linear ramps through `targets` (m), 8 points per ramp.
fn compare(bed: &SpringBed, closed: &MdrLaw, targets: &[f64]) -> Result<(), TestCaseError> {
    let mut bed_state = SpringBedState::default();
    let mut closed_state = MdrState::default();
    let mut forces = Vec::new();
    let mut current = 0.0;
    for &target in targets {
        for k in 1..=8 {
            let d = current + (target - current) * k as f64 / 8.0;
            let f_bed = bed.update(&mut bed_state, d).force;
            let f_closed = closed.update(&mut closed_state, d).force;
            forces.push((d, f_bed, f_closed));
        }
        current = target;
    }
    let peak = forces.iter().map(|f| f.2).fold(0.0, f64::max);
    for &(d, f_bed, f_closed) in &forces {
        prop_assert!(
            (f_bed - f_closed).abs() <= TOLERANCE * peak,
            "at d = {d:e}: bed {f_bed} vs closed form {f_closed} (peak {peak})"
        );
    }
    // The histories agree too.
    prop_assert!((bed.max_overlap(&bed_state) - closed.max_overlap(&closed_state)).abs() < 1e-15);
    Ok(())
}

/// Random targets in `[−0.2, 1] · MAX_OVERLAP`: negative ones separate the bodies.
fn history() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-0.2f64..1.0, 2..12)
        .prop_map(|v| v.into_iter().map(|t| t * MAX_OVERLAP).collect())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn spring_bed_matches_closed_form(
        critical_over_max in 0.02f64..1.5,
        theta in 0.0f64..=1.0,
        targets in history(),
    ) {
        let (bed, closed) = laws(critical_over_max, theta);
        compare(&bed, &closed, &targets)?;
    }
}

#[test]
fn spring_bed_matches_closed_form_for_the_paper_parameters() {
    let pair = ContactPair::paper_fig2();
    let params = MdrElastoPlastic::paper();
    let bed = SpringBed::sphere(&pair, &params, SPRINGS)
        .unwrap()
        .half_width(1.02 * (pair.effective_radius() * MAX_OVERLAP).sqrt())
        .unwrap();
    let closed = params.bind(&pair).unwrap();
    let targets = [
        1.0e-5, 0.3e-5, 1.6e-5, -1e-6, 0.9e-5, 2.9e-5, 1.2e-5, 2.0e-5, 0.0,
    ];
    compare(&bed, &closed, &targets).unwrap();
}

#[test]
fn the_comparison_detects_a_wrong_hardening() {
    // Guard: a closed form with another Θ must fail the same comparison.
    let (bed, _) = laws(0.2, 0.37);
    let (_, wrong) = laws(0.2, 0.5);
    assert!(compare(&bed, &wrong, &[2.5e-5, 1.0e-5]).is_err());
}
