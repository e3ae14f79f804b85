//! Limits and invariants of the MDR law (`docs/theory.md` §4): Hertz limits,
//! no tension, continuity across branch changes, energy balance of closed cycles.

use mdr_contact::normal::{SpringBed, SpringBedState};
use mdr_contact::prelude::*;
use proptest::prelude::*;

fn pair() -> ContactPair {
    ContactPair::paper_fig2()
}

fn bed(params: &MdrElastoPlastic, max_overlap: f64) -> SpringBed {
    let pair = pair();
    SpringBed::sphere(&pair, params, 2001)
        .unwrap()
        .half_width(1.02 * (pair.effective_radius() * max_overlap).sqrt())
        .unwrap()
}

/// A history with loading, unloading, reloading past the old maximum, separation, re-touch.
const HISTORY: [f64; 9] = [
    1.0e-5, 0.2e-5, 1.5e-5, -1e-6, 0.8e-5, 2.5e-5, 0.5e-5, 2.0e-5, 0.0,
];

fn ramp(targets: &[f64], per_segment: usize) -> Vec<f64> {
    let mut path = vec![0.0];
    let mut current = 0.0;
    for &t in targets {
        for k in 1..=per_segment {
            path.push(current + (t - current) * k as f64 / per_segment as f64);
        }
        current = t;
    }
    path
}

#[test]
fn elastic_limits_reproduce_hertz_exactly() {
    let pair = pair();
    let hertz = Hertz.bind(&pair).unwrap();
    // q_c so large that u_c is far beyond every overlap of the history.
    let q_c_huge = 1e15;
    for params in [
        MdrElastoPlastic::elastic(),
        MdrElastoPlastic::new(3.8e5, 1.0).unwrap(), // Θ = E*
        MdrElastoPlastic::new(q_c_huge, 0.37).unwrap(),
    ] {
        let law = params.bind(&pair).unwrap();
        let mut state = MdrState::default();
        let mut hertz_state = 0.0;
        for d in ramp(&HISTORY, 50) {
            let got = law.update(&mut state, d);
            let want = hertz.update(&mut hertz_state, d);
            assert!(
                (got.force - want.force).abs() <= 1e-12 * want.force,
                "{params:?} at {d}: {} vs Hertz {}",
                got.force,
                want.force
            );
            assert!(
                (got.contact_radius - want.contact_radius).abs() <= 1e-12 * want.contact_radius
            );
        }
        assert_eq!(law.residual_overlap(&state), 0.0);
        assert!(law.dissipated_work(&state).abs() < 1e-12 * hertz.work(2.5e-5));
    }
}

#[test]
fn elastic_spring_bed_reproduces_hertz() {
    let pair = pair();
    let hertz = Hertz.bind(&pair).unwrap();
    for params in [
        MdrElastoPlastic::elastic(),
        MdrElastoPlastic::new(3.8e5, 1.0).unwrap(),
    ] {
        let bed = bed(&params, 2.5e-5);
        let mut state = SpringBedState::default();
        let peak = hertz.force(2.5e-5);
        for d in ramp(&HISTORY, 20) {
            let got = bed.update(&mut state, d).force;
            assert!(
                (got - hertz.force(d)).abs() <= 2e-3 * peak,
                "{params:?} at {d}"
            );
        }
        assert_eq!(bed.dissipated_work(&state), 0.0);
    }
}

#[test]
fn plasticity_actually_changes_the_force() {
    // Guard for the Hertz-limit tests: with the paper's parameters the law is not Hertz.
    let pair = pair();
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let hertz = Hertz.bind(&pair).unwrap();
    let f = law.update(&mut MdrState::default(), 2.5e-5).force;
    assert!(f < 0.9 * hertz.force(2.5e-5));
}

/// Left and right limits of the force at `at`, evaluated with the history `state`.
fn jump(law: &MdrLaw, state: &MdrState, at: f64) -> f64 {
    let eps = 1e-10 * at;
    let left = law.evaluate(state, at - eps).force;
    let right = law.evaluate(state, at + eps).force;
    (right - left).abs()
}

#[test]
fn force_is_continuous_across_branch_changes() {
    let pair = pair();
    for theta in [0.0, 0.1, 0.37, 0.9] {
        let law = MdrElastoPlastic::new(3.8e5, theta)
            .unwrap()
            .bind(&pair)
            .unwrap();
        let u_c = law.yield_overlap();
        let d_max = 4.0 * u_c;
        let s = d_max - u_c;
        let peak = law.evaluate(&MdrState::default(), d_max).force;
        let tolerance = 1e-7 * peak;
        // Onset of plasticity on first loading.
        assert!(
            jump(&law, &MdrState::default(), u_c) < tolerance,
            "θ = {theta}: at u_c"
        );
        let mut state = MdrState::default();
        law.update(&mut state, d_max);
        // Branch changes of the unloading curve, and the turning point d = d_max (the left side
        // unloads, the right side loads further).
        for (name, at) in [("s", s), ("(1-θ)s", (1.0 - theta) * s), ("d_max", d_max)] {
            if at > 0.0 {
                assert!(
                    jump(&law, &state, at) < tolerance,
                    "θ = {theta}: jump at {name}"
                );
            }
        }
        // At d_max the unloading branch meets the loading branch.
        let loading = law.evaluate(&MdrState::default(), d_max).force;
        let unloading = law.evaluate(&state, d_max * (1.0 - 1e-12)).force;
        assert!((loading - unloading).abs() < tolerance);
    }
}

#[test]
fn continuity_check_detects_a_jump() {
    // Guard: a law with a force jump must fail `jump`: compare the loading branch at d_max with
    // the unloading branch of another history.
    let pair = pair();
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let mut a = MdrState::default();
    law.update(&mut a, 3e-5);
    let mut b = MdrState::default();
    law.update(&mut b, 2e-5);
    let d = 1.9e-5;
    assert!((law.evaluate(&a, d).force - law.evaluate(&b, d).force).abs() > 1e-3);
}

/// `∮ F dδ` along `path` with the trapezoid rule (J), updating the history.
fn work_along<L: NormalLaw>(law: &L, state: &mut L::State, path: &[f64]) -> f64 {
    let mut work = 0.0;
    let mut previous = (path[0], law.update(state, path[0]).force);
    for &d in &path[1..] {
        let f = law.update(state, d).force;
        work += 0.5 * (f + previous.1) * (d - previous.0);
        previous = (d, f);
    }
    work
}

/// Bound on the trapezoid-rule error of `work_along` over `segments` ramps of at most 3e-5 m,
/// each cut into `per_segment` steps, for curves no stiffer than Hertz at 3e-5 m
/// (`scale` = the Hertz loading work there). Per segment the error is `h²/12 · Δ(dF/dδ)` with
/// `dF/dδ ≤ 1.5 F/δ = 3.75 W/δ²`, i.e. `0.31 (h/δ)² W`; a factor ~3 covers the stiffer elastic
/// unloading of a flattened (plastic) contact. An elastic load–unload cycle on unequal grids
/// returns exactly this quadrature error, of either sign (proptest found one at −1e-8 W).
fn quadrature_error(segments: usize, per_segment: usize, scale: f64) -> f64 {
    segments as f64 / (per_segment as f64).powi(2) * scale
}

fn cycles() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(0.0f64..1.0, 1..8).prop_map(|v| {
        let mut path: Vec<f64> = v.into_iter().map(|t| t * 3e-5).collect();
        path.push(0.0); // a closed cycle ends where it started, apart
        path
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    /// A closed cycle never returns more work than was put in, and the net work equals the
    /// law's `dissipated_work` (the plastic loop area), for the closed form and the bed.
    #[test]
    fn closed_cycles_dissipate_exactly_the_plastic_work(
        targets in cycles(),
        theta in 0.0f64..=1.0,
    ) {
        let pair = pair();
        let params = MdrElastoPlastic::new(3.8e5, theta).unwrap();
        let closed = params.bind(&pair).unwrap();
        let path = ramp(&targets, 4000);
        let mut state = MdrState::default();
        let net = work_along(&closed, &mut state, &path);
        let scale = closed.loading_work(3e-5);
        prop_assert!(net >= -quadrature_error(targets.len(), 4000, scale), "net work {net} < 0");
        let dissipated = closed.dissipated_work(&state);
        prop_assert!((net - dissipated).abs() <= 1e-5 * scale + 1e-4 * dissipated,
            "closed form: loop area {net} vs dissipated_work {dissipated}");

        let bed = bed(&params, 3e-5);
        let mut bed_state = SpringBedState::default();
        let path = ramp(&targets, 400);
        let net = work_along(&bed, &mut bed_state, &path);
        prop_assert!(net >= -quadrature_error(targets.len(), 400, scale), "spring bed: net work {net} < 0");
        let dissipated = bed.dissipated_work(&bed_state);
        prop_assert!((net - dissipated).abs() <= 1e-4 * scale + 1e-3 * dissipated,
            "spring bed: loop area {net} vs dissipated_work {dissipated}");
    }

    /// No tension, for any history and hardening.
    #[test]
    fn force_is_never_negative(
        targets in prop::collection::vec(-0.3f64..1.0, 1..10),
        theta in 0.0f64..=1.0,
    ) {
        let pair = pair();
        let params = MdrElastoPlastic::new(3.8e5, theta).unwrap();
        let closed = params.bind(&pair).unwrap();
        let bed = bed(&params, 3e-5);
        let targets: Vec<f64> = targets.into_iter().map(|t| t * 3e-5).collect();
        let (mut s1, mut s2) = (MdrState::default(), SpringBedState::default());
        for d in ramp(&targets, 20) {
            prop_assert!(closed.update(&mut s1, d).force >= 0.0);
            prop_assert!(bed.update(&mut s2, d).force >= 0.0);
        }
    }
}

#[test]
fn stored_energy_is_the_work_returned_on_unloading() {
    let pair = pair();
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let mut state = MdrState::default();
    law.update(&mut state, 2.5e-5);
    // Residual depth is (1 − θ)(d_max − u_c) ≈ 1.2e-5: start above it.
    for start in [2.5e-5, 1.8e-5, 1.4e-5] {
        let mut trial = state;
        let path: Vec<f64> = (0..=20000)
            .map(|k| start * (1.0 - k as f64 / 20000.0))
            .collect();
        let returned = -work_along(&law, &mut trial, &path);
        let stored = law.elastic_energy(&state, start);
        assert!(stored > 0.0);
        assert!(
            (returned - stored).abs() < 1e-6 * stored,
            "from {start}: returned {returned} vs stored {stored}"
        );
    }
}

/// Numerical `dF/dδ` on the branch the law reports: forward difference on loading (`d = d_max`),
/// central difference below `d_max`.
fn numerical_stiffness<L: NormalLaw>(law: &L, state: &L::State, d: f64, loading: bool) -> f64 {
    let h = 1e-7 * d;
    if loading {
        (law.evaluate(state, d + h).force - law.evaluate(state, d).force) / h
    } else {
        (law.evaluate(state, d + h).force - law.evaluate(state, d - h).force) / (2.0 * h)
    }
}

#[test]
fn reported_stiffness_is_the_slope_of_the_force() {
    let pair = pair();
    for theta in [0.0, 0.37, 1.0] {
        let params = MdrElastoPlastic::new(3.8e5, theta).unwrap();
        let law = params.bind(&pair).unwrap();
        let u_c = law.yield_overlap();
        // Loading: elastic (0.5 u_c) and plastic (3 u_c).
        for d in [0.5 * u_c, 3.0 * u_c] {
            let mut state = MdrState::default();
            let reported = law.update(&mut state, d).stiffness;
            let slope = numerical_stiffness(&law, &state, d, true);
            assert!(
                (reported / slope - 1.0).abs() < 1e-5,
                "θ = {theta}, loading at {d}"
            );
        }
        // Unloading from 4 u_c: above s and on the flattened branch.
        let mut state = MdrState::default();
        law.update(&mut state, 4.0 * u_c);
        let s = 3.0 * u_c;
        for d in [3.5 * u_c, (1.0 - 0.5 * theta) * s] {
            let response = law.evaluate(&state, d);
            if response.force > 0.0 {
                let slope = numerical_stiffness(&law, &state, d, false);
                assert!(
                    (response.stiffness / slope - 1.0).abs() < 1e-5,
                    "θ = {theta}, unloading at {d}: {} vs {slope}",
                    response.stiffness
                );
            }
        }
    }
}
