//! The MDR closed form (docs/theory.md §4): yield onset at `u_c = π q_c / (2 E*)` (eq. 11, closed form
//! and spring bed), and the time-free energy route of `MdrLaw::impact` against time stepping and
//! its limits.

mod common;

use mdr_contact::normal::{SpringBed, SpringBedState};
use mdr_contact::prelude::*;
use std::f64::consts::PI;

fn pair() -> ContactPair {
    ContactPair::paper_fig2()
}

fn critical_displacement(pair: &ContactPair, q_c: f64) -> f64 {
    PI * q_c / (2.0 * pair.effective_modulus())
}

#[test]
fn closed_form_yields_at_pi_q_c_over_two_e_star() {
    let pair = pair();
    for q_c in [1e4, 3.8e5, 2e6] {
        let law = MdrElastoPlastic::new(q_c, 0.37)
            .unwrap()
            .bind(&pair)
            .unwrap();
        let u_c = critical_displacement(&pair, q_c);
        assert!((law.yield_overlap() / u_c - 1.0).abs() < 1e-14);
        // Loaded to just below u_c and unloaded: no plastic trace.
        let mut below = MdrState::default();
        law.update(&mut below, u_c * (1.0 - 1e-9));
        law.update(&mut below, 0.0);
        assert_eq!(law.residual_overlap(&below), 0.0);
        assert_eq!(law.dissipated_work(&below), 0.0);
        // Just above: a residual depth (1 − θ)(d_max − u_c) and dissipation.
        let mut above = MdrState::default();
        law.update(&mut above, u_c * 1.001);
        let residual = law.residual_overlap(&above);
        assert!((residual / (0.63 * 0.001 * u_c) - 1.0).abs() < 1e-9);
        assert!(law.dissipated_work(&above) > 0.0);
    }
}

#[test]
fn spring_bed_yields_at_pi_q_c_over_two_e_star_for_any_spacing() {
    let pair = pair();
    let params = MdrElastoPlastic::paper();
    let u_c = critical_displacement(&pair, params.critical_line_load());
    // Odd counts put a spring on the axis (g = 0), which yields first, exactly at u_c.
    for n in [3, 101, 2001] {
        let bed = SpringBed::sphere(&pair, &params, n)
            .unwrap()
            .half_width(2e-4)
            .unwrap();
        assert!((bed.yield_overlap() / u_c - 1.0).abs() < 1e-14, "n = {n}");
        assert!((bed.critical_displacement() / u_c - 1.0).abs() < 1e-14);
        let mut below = SpringBedState::default();
        bed.update(&mut below, u_c * (1.0 - 1e-9));
        assert_eq!(bed.dissipated_work(&below), 0.0, "n = {n}");
        assert_eq!(bed.residual_overlap(&below), 0.0);
        let mut above = SpringBedState::default();
        bed.update(&mut above, u_c * (1.0 + 1e-6));
        assert!(bed.dissipated_work(&above) > 0.0, "n = {n}");
        assert!(bed.residual_overlap(&above) > 0.0);
    }
}

#[test]
fn energy_route_matches_time_stepping() {
    let pair = pair();
    let mass = pair.reduced_mass();
    for theta in [0.0, 0.37, 0.8] {
        let law = MdrElastoPlastic::new(3.8e5, theta)
            .unwrap()
            .bind(&pair)
            .unwrap();
        let v_y = law.yield_speed(mass);
        for ratio in [0.5, 1.5, 4.0, 30.0] {
            let speed = ratio * v_y;
            let route = law.impact(&MdrState::default(), mass, speed).unwrap();
            let mut state = MdrState::default();
            let run = common::impact(
                &law,
                &mut state,
                mass,
                speed,
                pair.hertz_contact_time(speed),
                20_000,
            );
            // 20,000 steps per contact: measured ≤ 1.2e-9 in e_n, ≤ 1.8e-9 in d_max.
            assert!(
                (route.restitution - run.restitution).abs() < 5e-9,
                "θ = {theta}, v/v_y = {ratio}: energy route {} vs time stepping {}",
                route.restitution,
                run.restitution
            );
            assert!((route.max_overlap / run.max_overlap - 1.0).abs() < 1e-8);
            assert!((route.state.max_overlap / state.max_overlap - 1.0).abs() < 1e-8);
        }
    }
}

#[test]
fn restitution_tends_to_sqrt_theta_at_high_speed() {
    let pair = pair();
    let mass = pair.reduced_mass();
    for theta in [0.1, 0.37, 0.8] {
        let law = MdrElastoPlastic::new(3.8e5, theta)
            .unwrap()
            .bind(&pair)
            .unwrap();
        let v_y = law.yield_speed(mass);
        // Corrections are O((u_c / d_max)) ~ (v_y / v)^{4/5}.
        let e = law
            .impact(&MdrState::default(), mass, 1e8 * v_y)
            .unwrap()
            .restitution;
        assert!(
            (e / theta.sqrt() - 1.0).abs() < 1e-4,
            "θ = {theta}: e = {e}, sqrt θ = {}",
            theta.sqrt()
        );
        // And it approaches from above (the elastic core returns more).
        let slower = law
            .impact(&MdrState::default(), mass, 1e3 * v_y)
            .unwrap()
            .restitution;
        assert!(slower > e);
    }
}

#[test]
fn restitution_is_one_below_the_yield_speed() {
    let pair = pair();
    let mass = pair.reduced_mass();
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let v_y = law.yield_speed(mass);
    // v_y is where the Hertz work up to u_c equals the kinetic energy.
    let hertz = Hertz.bind(&pair).unwrap();
    assert!((0.5 * mass * v_y * v_y / hertz.work(law.yield_overlap()) - 1.0).abs() < 1e-12);
    for ratio in [0.1, 0.5, 0.999] {
        let impact = law.impact(&MdrState::default(), mass, ratio * v_y).unwrap();
        assert!((impact.restitution - 1.0).abs() < 1e-12);
        assert_eq!(law.residual_overlap(&impact.state), 0.0);
    }
    assert!(
        law.impact(&MdrState::default(), mass, 1.01 * v_y)
            .unwrap()
            .restitution
            < 1.0
    );
}

#[test]
fn a_slower_second_impact_on_the_same_spot_is_elastic() {
    let pair = pair();
    let mass = pair.reduced_mass();
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let v_y = law.yield_speed(mass);
    let first = law.impact(&MdrState::default(), mass, 10.0 * v_y).unwrap();
    assert!(first.restitution < 0.9);
    // The flattened contact stores at most e₁² of the first kinetic energy elastically, so a
    // second impact is elastic up to v₂ = e₁ v₁ (and plastic again beyond).
    let slower = 0.95 * first.restitution * 10.0 * v_y;
    let second = law.impact(&first.state, mass, slower).unwrap();
    assert_eq!(second.restitution, 1.0);
    assert_eq!(second.state, first.state);
    assert!(second.max_overlap < first.max_overlap);
    // The same by time stepping on the flattened contact.
    let mut state = first.state;
    let run = common::impact(
        &law,
        &mut state,
        mass,
        slower,
        pair.hertz_contact_time(slower),
        20_000,
    );
    // Measured 2.8e-11.
    assert!(
        (run.restitution - 1.0).abs() < 1e-10,
        "e = {}",
        run.restitution
    );
    // A second impact just above e₁ v₁ loads further and dissipates again.
    let third = law
        .impact(&first.state, mass, 1.05 * first.restitution * 10.0 * v_y)
        .unwrap();
    assert!(third.restitution < 1.0);
    assert!(third.state.max_overlap > first.state.max_overlap);
}

#[test]
fn a_law_without_strength_reports_no_rebound() {
    // q_c = 0 and Θ = 0 carry no force at all: the energy route must not report e = 1.
    let pair = pair();
    let law = MdrElastoPlastic::new(0.0, 0.0)
        .unwrap()
        .bind(&pair)
        .unwrap();
    let impact = law
        .impact(&MdrState::default(), pair.reduced_mass(), 1.0)
        .unwrap();
    assert_eq!(impact.restitution, 0.0);
}
