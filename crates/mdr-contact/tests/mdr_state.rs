//! The `NormalLaw` view of the closed-form MDR law on every branch, against the formulas of
//! docs/theory.md §4 written out here from `E*`, `R`, `u_c = π q_c/(2E*)` (eq. 11) and
//! `θ = Θ/E*`: force, contact radius and tangent stiffness on plastic loading, on elastic
//! unloading with every spring in contact, on the flattened residual profile and inside the
//! crater; the history, residual depth, stored and dissipated work; and the parameters as given.

use mdr_contact::normal::Hardening;
use mdr_contact::prelude::*;
use std::f64::consts::PI;

/// `E*`, `R` of the pair and `u_c` of the law's `q_c`.
struct Reference {
    e: f64,
    r: f64,
    u_c: f64,
}

impl Reference {
    fn new(pair: &ContactPair, q_c: f64) -> Self {
        let e = pair.effective_modulus();
        Self {
            e,
            r: pair.effective_radius(),
            u_c: PI * q_c / (2.0 * e),
        }
    }
    /// Hertz `F_H(d) = (4/3) E* √R d^{3/2}`.
    fn hertz(&self, d: f64) -> f64 {
        4.0 / 3.0 * self.e * self.r.sqrt() * d.max(0.0).powf(1.5)
    }
    /// Hertz work `(8/15) E* √R d^{5/2}`.
    fn hertz_work(&self, d: f64) -> f64 {
        8.0 / 15.0 * self.e * self.r.sqrt() * d.max(0.0).powf(2.5)
    }
}

fn close(x: f64, y: f64, tol: f64) -> bool {
    (x - y).abs() <= tol * y.abs().max(f64::MIN_POSITIVE)
}

fn assert_close(what: &str, x: f64, y: f64) {
    assert!(close(x, y, 1e-12), "{what}: {x:e} vs {y:e}");
}

/// One loading–unloading cycle through every branch, θ = 0.37 (the paper) and θ = 0.1.
#[test]
fn every_branch_reports_the_closed_form_quantities() {
    let pair = ContactPair::paper_fig2();
    for theta in [0.37, 0.1] {
        let q_c = 3.8e5;
        let law = MdrElastoPlastic::new(q_c, theta)
            .unwrap()
            .bind(&pair)
            .unwrap();
        let x = Reference::new(&pair, q_c);
        assert_close("u_c", law.yield_overlap(), x.u_c);
        assert_close("theta", law.hardening_ratio(), theta);
        assert_eq!(law.effective_modulus(), x.e);
        assert_eq!(law.effective_radius(), x.r);
        let mut state = MdrState::default();

        // Elastic loading below u_c: Hertz, a = √(R d), k = 2E* a.
        let d = 0.6 * x.u_c;
        let resp = law.update(&mut state, d);
        let a = (x.r * d).sqrt();
        assert_close("elastic F", resp.force, x.hertz(d));
        assert_close("elastic a", resp.contact_radius, a);
        assert_close("elastic k", resp.stiffness, 2.0 * x.e * a);
        assert_eq!(law.max_overlap(&state), d);
        assert_eq!(law.residual_overlap(&state), 0.0);
        assert_eq!(law.dissipated_work(&state), 0.0);
        // Below u_c the stored energy is Hertz's, on loading and on unloading.
        assert_close(
            "stored, elastic",
            law.elastic_energy(&state, d),
            x.hertz_work(d),
        );
        assert_close(
            "stored, elastic unloading",
            law.stored_energy(d, 0.5 * d),
            x.hertz_work(0.5 * d),
        );
        assert_eq!(law.stored_energy(d, 0.0), 0.0);

        // Plastic loading to d_max = 3 u_c: F = F_H(d) − (1 − θ) F_H(d − u_c),
        // k = 2E*√R(√d − (1 − θ)√(d − u_c)).
        let d_max = 3.0 * x.u_c;
        let s = d_max - x.u_c;
        let resp = law.update(&mut state, d_max);
        assert_close(
            "loading F",
            resp.force,
            x.hertz(d_max) - (1.0 - theta) * x.hertz(s),
        );
        assert_close("loading a", resp.contact_radius, (x.r * d_max).sqrt());
        assert_close(
            "loading k",
            resp.stiffness,
            2.0 * x.e * x.r.sqrt() * (d_max.sqrt() - (1.0 - theta) * s.sqrt()),
        );
        assert_eq!(law.max_overlap(&state), d_max);
        let residual = (1.0 - theta) * s;
        assert_close("residual", law.residual_overlap(&state), residual);
        assert_close("residual_depth", law.residual_depth(d_max), residual);
        let w_load = x.hertz_work(d_max) - (1.0 - theta) * x.hertz_work(s);
        assert_close("loading work", law.loading_work(d_max), w_load);
        // Stored at d_max: flattened part (2/5)c θ^{-1/2}(s − e_r)^{5/2} plus the outer part.
        let c = 4.0 / 3.0 * x.e * x.r.sqrt();
        let stored = 0.4 * c / theta.sqrt() * (s - residual).powf(2.5)
            + 0.4 * c * (d_max.powf(2.5) - s.powf(2.5))
            - (1.0 - theta) * c * s.powf(1.5) * (d_max - s);
        assert_close("stored", law.elastic_energy(&state, d_max), stored);
        assert_close("dissipated", law.dissipated_work(&state), w_load - stored);

        // Unloading with d ≥ s: F = F_H(d) − (1 − θ) F_H(s), a = √(R d), k = 2E* a; the
        // history stays at d_max.
        let d = s + 0.5 * x.u_c;
        let resp = law.update(&mut state, d);
        let a = (x.r * d).sqrt();
        assert_close(
            "unloading F",
            resp.force,
            x.hertz(d) - (1.0 - theta) * x.hertz(s),
        );
        assert_close("unloading a", resp.contact_radius, a);
        assert_close("unloading k", resp.stiffness, 2.0 * x.e * a);
        assert_eq!(law.max_overlap(&state), d_max);
        let stored_d = 0.4 * c / theta.sqrt() * (s - residual).powf(2.5)
            + 0.4 * c * (d.powf(2.5) - s.powf(2.5))
            - (1.0 - theta) * c * s.powf(1.5) * (d - s);
        assert_close("stored at d", law.elastic_energy(&state, d), stored_d);

        // The flattened residual profile, (1 − θ)s < d < s: Hertz of radius R/θ about the
        // residual depth.
        let d = residual + 0.5 * (s - residual);
        let resp = law.update(&mut state, d);
        let excess = d - residual;
        let a = (x.r * excess / theta).sqrt();
        assert_close(
            "flattened F",
            resp.force,
            4.0 / 3.0 * x.e * (x.r / theta).sqrt() * excess.powf(1.5),
        );
        assert_close("flattened a", resp.contact_radius, a);
        assert_close("flattened k", resp.stiffness, 2.0 * x.e * a);
        assert_eq!(law.max_overlap(&state), d_max);
        assert_close(
            "stored on the flattened profile",
            law.elastic_energy(&state, d),
            0.4 * c / theta.sqrt() * excess.powf(2.5),
        );

        // Inside the crater, and apart: nothing, and the history is kept.
        for d in [0.5 * residual, 0.0, -1e-6] {
            let resp = law.update(&mut state, d);
            assert_eq!(resp.force, 0.0, "d = {d}");
            assert_eq!(resp.contact_radius, 0.0);
            assert_eq!(resp.stiffness, 0.0);
            assert_eq!(law.max_overlap(&state), d_max);
            assert_eq!(law.elastic_energy(&state, d.max(0.0)), 0.0);
        }

        // Reloading past d_max loads plastically again from the new maximum.
        let d = 4.0 * x.u_c;
        let resp = law.update(&mut state, d);
        assert_close(
            "reloading F",
            resp.force,
            x.hertz(d) - (1.0 - theta) * x.hertz(d - x.u_c),
        );
        assert_eq!(law.max_overlap(&state), d);
    }
}

/// Without hardening (θ = 0) the force drops to zero at `d = s`: no flattened branch.
#[test]
fn without_hardening_unloading_ends_at_s() {
    let pair = ContactPair::paper_fig2();
    let law = MdrElastoPlastic::new(3.8e5, 0.0)
        .unwrap()
        .bind(&pair)
        .unwrap();
    let x = Reference::new(&pair, 3.8e5);
    let mut state = MdrState::default();
    let d_max = 3.0 * x.u_c;
    let s = d_max - x.u_c;
    law.update(&mut state, d_max);
    assert_close("residual", law.residual_overlap(&state), s);
    let at_s = law.update(&mut state, s * (1.0 + 1e-9));
    assert!(at_s.force < 1e-6 * x.hertz(s), "{}", at_s.force);
    for d in [0.99 * s, 0.5 * s] {
        assert_eq!(law.update(&mut state, d).force, 0.0, "d = {d}");
    }
    assert_eq!(law.elastic_energy(&state, 0.99 * s), 0.0);
    // Only the outer part, s < d' < d_max, stores energy; the rest of the loading work is
    // dissipated.
    let w_load = x.hertz_work(d_max) - x.hertz_work(s);
    assert_close("loading work", law.loading_work(d_max), w_load);
    let c = 4.0 / 3.0 * x.e * x.r.sqrt();
    let outer = 0.4 * c * (d_max.powf(2.5) - s.powf(2.5)) - c * s.powf(1.5) * (d_max - s);
    assert_close("stored", law.stored_energy(d_max, d_max), outer);
    assert_close("dissipated", law.dissipated_work(&state), w_load - outer);
}

/// `v_y` from `m v_y²/2 = (8/15) E* √R u_c^{5/2}` (docs/theory.md §4) and the loading work
/// below `u_c` is Hertz's.
#[test]
fn yield_speed_and_elastic_work_are_hertz_at_u_c() {
    let pair = ContactPair::paper_fig2();
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let x = Reference::new(&pair, 3.8e5);
    let m = pair.reduced_mass();
    let v_y = (2.0 * x.hertz_work(x.u_c) / m).sqrt();
    assert_close("v_y", law.yield_speed(m), v_y);
    assert_close(
        "W below u_c",
        law.loading_work(0.5 * x.u_c),
        x.hertz_work(0.5 * x.u_c),
    );
    assert_eq!(law.loading_work(0.0), 0.0);
    assert_eq!(law.loading_work(-1e-6), 0.0);
    assert_eq!(law.residual_depth(0.5 * x.u_c), 0.0);
}

/// The parameters as given, and an absolute hardening modulus `Θ` bound to a pair gives the
/// ratio `Θ/E*` of that pair (the same law as [`MdrElastoPlastic::new`] with that ratio).
#[test]
fn parameters_and_an_absolute_hardening_modulus() {
    let pair = ContactPair::paper_fig2();
    let e = pair.effective_modulus();
    let paper = MdrElastoPlastic::paper();
    assert_eq!(paper.critical_line_load(), 3.8e5);
    assert_eq!(paper.hardening(), Hardening::Ratio(0.37));
    let elastic = MdrElastoPlastic::elastic();
    assert_eq!(elastic.critical_line_load(), f64::INFINITY);
    assert_eq!(elastic.hardening(), Hardening::Ratio(1.0));
    assert_eq!(elastic.bind(&pair).unwrap().yield_overlap(), f64::INFINITY);

    let by_modulus = MdrElastoPlastic::with_hardening_modulus(3.8e5, 0.37 * e).unwrap();
    assert_eq!(by_modulus.hardening(), Hardening::Modulus(0.37 * e));
    assert_eq!(by_modulus.critical_line_load(), 3.8e5);
    let law = by_modulus.bind(&pair).unwrap();
    assert_close("θ from Θ", law.hardening_ratio(), 0.37);
    let by_ratio = paper.bind(&pair).unwrap();
    let (mut s1, mut s2) = (MdrState::default(), MdrState::default());
    for d in [2e-6, 1.5e-5, 8e-6] {
        let (f1, f2) = (
            law.update(&mut s1, d).force,
            by_ratio.update(&mut s2, d).force,
        );
        assert!(close(f1, f2, 1e-14), "d = {d}: {f1} vs {f2}");
    }
    // Θ = E* is Hertz; Θ above E* of the pair is refused by name.
    let hertz = MdrElastoPlastic::with_hardening_modulus(3.8e5, e)
        .unwrap()
        .bind(&pair)
        .unwrap();
    assert_eq!(hertz.hardening_ratio(), 1.0);
    let err = MdrElastoPlastic::with_hardening_modulus(3.8e5, 1.01 * e)
        .unwrap()
        .bind(&pair)
        .unwrap_err();
    assert!(err.to_string().contains("theta"), "{err}");
}

/// A re-impact on a flattened contact within the energy it can store is elastic, and its
/// deepest overlap is where the flattened profile (Hertz of radius `R/θ` about the residual
/// depth) has stored the kinetic energy: `(8/15) E* √(R/θ) (D − e_r)^{5/2} = m v²/2`; one that
/// reaches past `s` stores the outer part as well. Both against the closed form written out.
#[test]
fn elastic_re_impact_reaches_the_depth_that_stores_its_energy() {
    let pair = ContactPair::paper_fig2();
    let theta = 0.37;
    let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    let x = Reference::new(&pair, 3.8e5);
    let m = pair.reduced_mass();
    let d_max = 4.0 * x.u_c;
    let s = d_max - x.u_c;
    let residual = (1.0 - theta) * s;
    let state = MdrState { max_overlap: d_max };
    let c = 4.0 / 3.0 * x.e * x.r.sqrt();
    // On the flattened profile: choose D, give the energy it stores.
    let depth = residual + 0.6 * (s - residual);
    let kinetic = 0.4 * c / theta.sqrt() * (depth - residual).powf(2.5);
    let speed = (2.0 * kinetic / m).sqrt();
    let impact = law.impact(&state, m, speed).unwrap();
    assert_eq!(impact.restitution, 1.0);
    assert_eq!(impact.state, state);
    assert!(
        close(impact.max_overlap, depth, 1e-12),
        "{} vs {depth}",
        impact.max_overlap
    );
    // Past s, still below d_max: the flattened part up to s plus the outer part.
    let depth = s + 0.5 * x.u_c;
    let kinetic = 0.4 * c / theta.sqrt() * (s - residual).powf(2.5)
        + 0.4 * c * (depth.powf(2.5) - s.powf(2.5))
        - (1.0 - theta) * c * s.powf(1.5) * (depth - s);
    let impact = law.impact(&state, m, (2.0 * kinetic / m).sqrt()).unwrap();
    assert_eq!(impact.restitution, 1.0);
    assert!(
        close(impact.max_overlap, depth, 1e-12),
        "{} vs {depth}",
        impact.max_overlap
    );
}

/// The energy route of a plastic impact against the closed form written out: for a chosen
/// deepest overlap `D`, the speed whose kinetic energy is the loading work
/// `(8/15) E* √R [D^{5/2} − (1 − θ)(D − u_c)^{5/2}]` gives back `D` to 1e-13 and
/// `e_n² = W_stored(D)/W_load(D)` (docs/theory.md §4), on a virgin contact and on one loaded
/// before (where only the work past the old `d_max` is new).
#[test]
fn energy_route_finds_the_overlap_that_spends_the_kinetic_energy() {
    let pair = ContactPair::paper_fig2();
    let m = pair.reduced_mass();
    for theta in [0.37, 0.1] {
        let law = MdrElastoPlastic::new(3.8e5, theta)
            .unwrap()
            .bind(&pair)
            .unwrap();
        let x = Reference::new(&pair, 3.8e5);
        let c = 4.0 / 3.0 * x.e * x.r.sqrt();
        let w_load = |d: f64| x.hertz_work(d) - (1.0 - theta) * x.hertz_work(d - x.u_c);
        let w_stored = |d_max: f64, d: f64| {
            let s = d_max - x.u_c;
            if s <= 0.0 {
                return x.hertz_work(d);
            }
            let residual = (1.0 - theta) * s;
            0.4 * c / theta.sqrt() * (d.min(s) - residual).max(0.0).powf(2.5)
                + if d > s {
                    0.4 * c * (d.powf(2.5) - s.powf(2.5))
                        - (1.0 - theta) * c * s.powf(1.5) * (d - s)
                } else {
                    0.0
                }
        };
        for ratio in [1.5, 4.0, 30.0, 1000.0] {
            let depth = ratio * x.u_c;
            let kinetic = w_load(depth);
            let impact = law
                .impact(&MdrState::default(), m, (2.0 * kinetic / m).sqrt())
                .unwrap();
            assert!(
                close(impact.max_overlap, depth, 1e-13),
                "θ = {theta}, D = {ratio} u_c: {} vs {depth}",
                impact.max_overlap
            );
            assert_eq!(impact.state.max_overlap, impact.max_overlap);
            let e = (w_stored(depth, depth) / kinetic).sqrt();
            assert!(
                close(impact.restitution, e, 1e-12),
                "θ = {theta}, D = {ratio} u_c: e = {} vs {e}",
                impact.restitution
            );
            // Again on a contact already loaded to D/2: reloading absorbs W_stored(D/2) first.
            let before = MdrState {
                max_overlap: 0.5 * depth,
            };
            let kinetic = w_stored(0.5 * depth, 0.5 * depth) + w_load(depth) - w_load(0.5 * depth);
            let impact = law.impact(&before, m, (2.0 * kinetic / m).sqrt()).unwrap();
            assert!(
                close(impact.max_overlap, depth, 1e-13),
                "θ = {theta}, D = {ratio} u_c after D/2: {} vs {depth}",
                impact.max_overlap
            );
            let e = (w_stored(depth, depth) / kinetic).sqrt();
            assert!(
                close(impact.restitution, e, 1e-12),
                "θ = {theta}, D = {ratio} u_c after D/2: e = {} vs {e}",
                impact.restitution
            );
        }
    }
}
