//! The demo linear spring `F = k_n δ` against the harmonic oscillator written out: the force,
//! stiffness and geometric contact radius `a = √(R δ)` of two spheres; the stored energy
//! `½ k_n δ²` and no tension, no plasticity, no dissipation, no yield; the largest overlap kept
//! through unloading; an impact lasting half a period `π √(m*/k_n)` to the depth `v √(m*/k_n)` and
//! returning the whole speed; with the demo linear dashpot, the spring–dashpot restitution
//! `exp(−πζ/√(1−ζ²))` (a contact that may pull) and `exp(−β t_e)` at the force's zero (a contact
//! that only pushes). Its parameter: taken by `from_values`, refused outside `(0, inf)` by key.
//! The file's library tests miss 14 mutants of `normal/linear_spring.rs`; these tests catch the
//! 12 that are not equivalent (docs/verification.md §5).
#![cfg(feature = "demo-laws")]

mod common;

use mdr_contact::damping::{DampingLaw, DampingModel, LinearDashpot};
use mdr_contact::normal::{LinearSpring, LinearSpringLaw};
use mdr_contact::params::Declared;
use mdr_contact::prelude::*;

const K: f64 = 2.0e5;

fn law() -> (LinearSpringLaw, ContactPair) {
    let pair = ContactPair::paper_fig2();
    (LinearSpring::new(K).unwrap().bind(&pair).unwrap(), pair)
}

#[test]
fn force_stiffness_and_contact_radius_follow_the_spring_and_the_sphere_geometry() {
    let (law, pair) = law();
    let r = pair.effective_radius();
    let mut state = 0.0;
    for d in [1e-7, 3e-5, 2e-3] {
        let out = law.update(&mut state, d);
        assert_eq!(out.force, K * d);
        assert_eq!(out.stiffness, K);
        // Two spheres that overlap by δ touch on a circle of radius √(R δ) (to O(δ/R)).
        assert!(
            (out.contact_radius - (r * d).sqrt()).abs() <= 1e-15 * (r * d).sqrt(),
            "{}",
            out.contact_radius
        );
    }
    // Apart or just touching: no force, no contact.
    for d in [0.0, -1e-6] {
        assert_eq!(law.update(&mut state, d), NormalResponse::default());
    }
}

#[test]
fn stored_energy_is_half_k_delta_squared_and_nothing_is_lost() {
    let (law, _) = law();
    let mut state = 0.0;
    let d_max = 1e-3;
    law.update(&mut state, d_max);
    law.update(&mut state, 0.4 * d_max);
    // The largest overlap survives unloading; the spring neither yields nor flattens.
    assert_eq!(law.max_overlap(&state), d_max);
    assert_eq!(law.residual_overlap(&state), 0.0);
    assert_eq!(law.dissipated_work(&state), 0.0);
    assert_eq!(law.yield_overlap(), f64::INFINITY);
    for d in [1e-6, 0.4 * d_max, d_max, 3.0 * d_max] {
        let energy = law.elastic_energy(&state, d);
        let expected = 0.5 * K * d * d;
        assert!((energy - expected).abs() <= 1e-15 * expected, "{energy}");
    }
    // A spring does not pull: apart it holds nothing.
    assert_eq!(law.elastic_energy(&state, -1e-4), 0.0);
    assert_eq!(law.elastic_energy(&state, 0.0), 0.0);
    // A new, deeper overlap moves the largest one.
    law.update(&mut state, 1.5 * d_max);
    assert_eq!(law.max_overlap(&state), 1.5 * d_max);
}

/// `m* δ'' = −k_n δ` from `δ = 0`, `δ' = v`: `δ = (v/ω₀) sin ω₀t`, `ω₀ = √(k_n/m*)`, so the
/// contact lasts `π/ω₀`, reaches `v/ω₀` and leaves at `v` (velocity Verlet, 2000 steps per
/// contact: the steps' count within one of 2000, measured 2000; the depth to the sampling error
/// `(ω₀Δt)²/8 = 3.08·10⁻⁷`, measured 3.08·10⁻⁷; the restitution, measured 1 − 1.1·10⁻¹⁵, the
/// scheme being time-reversible).
#[test]
fn an_impact_lasts_half_a_period_and_returns_the_whole_speed() {
    let (law, pair) = law();
    let m = pair.reduced_mass();
    let omega = (K / m).sqrt();
    let v = 0.7;
    let steps_per_contact = 2000;
    let mut state = 0.0;
    let impact = common::impact(
        &law,
        &mut state,
        m,
        v,
        std::f64::consts::PI / omega,
        steps_per_contact,
    );
    assert!(
        impact.steps.abs_diff(steps_per_contact) <= 1,
        "{}",
        impact.steps
    );
    let depth = v / omega;
    assert!(
        (impact.max_overlap / depth - 1.0).abs() < 1e-6,
        "{} vs {depth}",
        impact.max_overlap
    );
    assert_eq!(law.max_overlap(&state), impact.max_overlap);
    assert!(
        (impact.restitution - 1.0).abs() < 1e-13,
        "{}",
        impact.restitution
    );
}

/// One RK4 step of `m* δ'' = −F(δ, δ')` for the state `(δ, δ')`.
fn rk4_step(force: &dyn Fn(f64, f64) -> f64, m: f64, (d, v): (f64, f64), h: f64) -> (f64, f64) {
    let acc = |d: f64, v: f64| -force(d, v) / m;
    let (k1d, k1v) = (v, acc(d, v));
    let (k2d, k2v) = (v + 0.5 * h * k1v, acc(d + 0.5 * h * k1d, v + 0.5 * h * k1v));
    let (k3d, k3v) = (v + 0.5 * h * k2v, acc(d + 0.5 * h * k2d, v + 0.5 * h * k2v));
    let (k4d, k4v) = (v + h * k3v, acc(d + h * k3d, v + h * k3v));
    (
        d + h / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d),
        v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v),
    )
}

/// Integrate from `δ = 0`, `δ' = v` until `ends(δ, δ')` turns true; the exit speed and time are
/// interpolated linearly in `ends`' quantity over the last step (its error `O(Δt²)`).
fn spring_dashpot_exit(
    force: &dyn Fn(f64, f64) -> f64,
    gauge: &dyn Fn(f64, f64) -> f64,
    m: f64,
    v: f64,
    h: f64,
) -> (f64, f64) {
    let (mut x, mut t) = ((0.0, v), 0.0);
    loop {
        let next = rk4_step(force, m, x, h);
        let (g0, g1) = (gauge(x.0, x.1), gauge(next.0, next.1));
        if t > 0.0 && g1 <= 0.0 {
            let tau = g0 / (g0 - g1);
            return (x.1 + tau * (next.1 - x.1), t + tau * h);
        }
        (x, t) = (next, t + h);
        assert!(t < 1e6 * h, "the contact did not end");
    }
}

/// The linear spring–dashpot (docs of `LinearDashpot`): `ω₀ = √(k_n/m*)`, `β = c/(2m*)`,
/// `ζ = β/ω₀`, `ω_d = ω₀√(1−ζ²)`. A contact that may pull ends at `δ = 0`, `t = π/ω_d`, with
/// `e = exp(−πζ/√(1−ζ²))`; one whose total force `k_n δ + c δ'` stays ≥ 0 lets go where it
/// vanishes, at `ω_d t_e = π − 2 arctan(β/ω_d)`, with `e = exp(−β t_e)` (Schwager & Pöschel
/// 2007). RK4 with 20 000 steps per contact, the end interpolated over the last step: measured
/// within 3.2·10⁻¹³ (time) and 7.2·10⁻¹⁵ (restitution) where `δ` ends it, 2.1·10⁻⁹ and
/// 1.5·10⁻⁹ where the force does (its curvature over the step).
#[test]
fn with_a_linear_dashpot_the_restitution_is_the_damped_oscillators() {
    let (law, pair) = law();
    let m = pair.reduced_mass();
    let omega = (K / m).sqrt();
    let v = 0.7;
    for zeta in [0.05, 0.3, 0.6] {
        let c = 2.0 * zeta * (m * K).sqrt();
        let dashpot = LinearDashpot::new(c).unwrap().bind(&pair).unwrap();
        let beta = c / (2.0 * m);
        let omega_d = omega * (1.0 - zeta * zeta).sqrt();
        // The dashpot acts through the whole contact the integration follows: it is asked at an
        // overlap of at least the smallest positive double, so that RK4's stages at δ = 0 (the
        // first) and just past it (the last, for the contact that may pull) do not see it switch
        // on or off, a jump of `c δ'` that would cost the step's accuracy.
        let total = |d: f64, rate: f64| {
            let spring = law.evaluate(&0.0, d);
            spring.force + dashpot.normal_force(&spring, d.max(f64::MIN_POSITIVE), rate)
        };
        let h = std::f64::consts::PI / omega_d / 20_000.0;

        let (exit, t) = spring_dashpot_exit(&total, &|d, _| d, m, v, h);
        let e = (-std::f64::consts::PI * zeta / (1.0 - zeta * zeta).sqrt()).exp();
        let t_c = std::f64::consts::PI / omega_d;
        assert!((t / t_c - 1.0).abs() < 1e-12, "ζ = {zeta}: t {t} vs {t_c}");
        assert!(
            (-exit / v - e).abs() < 1e-13,
            "ζ = {zeta}: e {} vs {e}",
            -exit / v
        );

        let (exit, t) = spring_dashpot_exit(&total, &|d, rate| total(d, rate), m, v, h);
        let t_e = (std::f64::consts::PI - 2.0 * (beta / omega_d).atan()) / omega_d;
        let e = (-beta * t_e).exp();
        assert!((t / t_e - 1.0).abs() < 1e-8, "ζ = {zeta}: t {t} vs {t_e}");
        assert!(
            (-exit / v - e).abs() < 1e-8,
            "ζ = {zeta}: e {} vs {e}",
            -exit / v
        );
    }
}

#[test]
fn the_stiffness_is_its_one_declared_parameter() {
    let spring = LinearSpring::new(K).unwrap();
    assert_eq!(spring.stiffness(), K);
    assert_eq!(LinearSpring::from_values(&[K]).unwrap(), spring);
    assert_eq!(
        LinearSpring::from_values(&[]).unwrap_err().to_string(),
        "invalid table `linear_spring`: 0 parameter values given, the law declares 1"
    );
    assert_eq!(
        LinearSpring::from_values(&[0.0]).unwrap_err().to_string(),
        "parameter `normal_stiffness_n_per_m` = 0 is outside the allowed range (0, inf)"
    );
    assert_eq!(
        LinearSpring::new(f64::INFINITY).unwrap_err().to_string(),
        "parameter `normal_stiffness_n_per_m` must be a finite number, got inf"
    );
    // The smallest positive stiffness is allowed.
    assert_eq!(LinearSpring::new(1e-300).unwrap().stiffness(), 1e-300);
}
