//! The adhesive MDR law on the plastic crater against the crater written out here: the
//! profile `h(x) = θx²/R + (1 − θ)s` inside the plastic radius `b = √(R s)` and `x²/R` outside
//! (docs/theory.md, eq. A1), integrated by Gauss–Legendre quadrature (exact for the
//! polynomials of each branch), and the let-go overlap (A7) found by a search over the
//! attached disc. A law in round units (`E* = 1 Pa`, `R = 1 m`) keeps every branch of the
//! crater in reach: the edge's `ε` runs from below `1/16` to far above `1/2`, the neck is held
//! by adhesion alone below the residual depth, and the weakest edge lies on either branch or
//! at the plastic radius.

#[path = "common/crater.rs"]
mod crater;

use crater::Crater;
use mdr_contact::prelude::*;
use std::f64::consts::PI;

const MODULUS: f64 = 1.0;
const RADIUS: f64 = 1.0;
const YIELD: f64 = 1e-3;
const THETA: f64 = 0.25;

/// `Δγ` for the let-go coefficient `c = √(2πΔγ/E*)`.
fn gamma_for(c: f64) -> f64 {
    c * c * MODULUS / (2.0 * PI)
}

fn law(c: f64) -> AdhesiveMdrLaw {
    scaled_law(c, 1.0)
}

/// The law with every length times `scale`: `R`, `u_c`, and `c = √(2πΔγ/E*)` (m^{1/2}) times
/// `√scale`, so that every overlap and radius of the unit law scales alike.
fn scaled_law(c: f64, scale: f64) -> AdhesiveMdrLaw {
    AdhesiveMdrLaw::new(
        MdrLaw::from_parts(MODULUS, RADIUS * scale, YIELD * scale, THETA),
        gamma_for(c * scale.sqrt()),
    )
}

/// The crater of the law with every length times `scale` after loading to `max_overlap`:
/// `R`, `u_c`, and the let-go coefficient `c` (already scaled, m^½).
fn crater_of(max_overlap: f64, c: f64, scale: f64) -> Crater {
    Crater::new(
        MODULUS,
        RADIUS * scale,
        YIELD * scale,
        THETA,
        c,
        max_overlap,
    )
}

/// Walks `law` quasi-statically through the turning points `turns` in steps of at most
/// `step`, checking at every step against the crater written out: the force is (A3) on the
/// attached disc, the stored energy (A6), the attached edge within its limit (A5) and at it
/// where it retreated, a contact that lets go below its weakest edge (A7) with the work (A6)
/// the springs held, and the books of the work done. Returns how many steps had a stretched
/// edge, a retreated edge, and how many let-gos.
fn walk(law: &AdhesiveMdrLaw, c: f64, turns: &[f64], step: f64) -> (usize, usize, usize) {
    walk_scaled(law, c, 1.0, turns, step)
}

/// [`walk`] for the law with every length times `scale` ([`scaled_law`]): `c` is the unit
/// law's, `turns` and `step` are in the scaled law's metres.
fn walk_scaled(
    law: &AdhesiveMdrLaw,
    c: f64,
    scale: f64,
    turns: &[f64],
    step: f64,
) -> (usize, usize, usize) {
    let c = c * scale.sqrt();
    let mut state = AdhesiveMdrState::default();
    let (mut d, mut force, mut work) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut previous_overlap;
    let (mut stretched, mut retreated, mut let_go) = (0, 0, 0);
    for &target in turns {
        let n = ((target - d).abs() / step).ceil().max(1.0) as usize;
        let start = d;
        for i in 1..=n {
            let next = start + (target - start) * i as f64 / n as f64;
            let before = state;
            previous_overlap = d;
            let response = law.update(&mut state, next);
            let mut step_work = 0.5 * (response.force + force) * (next - d);
            let previous_force = force;
            force = response.force;
            d = next;
            let crater = crater_of(state.max_overlap, c, scale);
            assert_eq!(state.max_overlap, before.max_overlap.max(d));
            let a = state.contact_radius;
            assert_eq!(response.contact_radius, a);
            // Scales: the force and energy of the attached disc at the deepest overlap.
            let force_scale = 2.0 * MODULUS * a.max(1e-6 * scale) * state.max_overlap;
            let energy_scale = force_scale * state.max_overlap;
            if a > 0.0 {
                let expected = crater.force(d, a);
                assert!(
                    (response.force - expected).abs() < 1e-12 * force_scale,
                    "d={d} a={a}: force {} (A3) {expected}",
                    response.force
                );
                let stored = law.elastic_energy(&state, d);
                let expected = crater.energy(d, a);
                assert!(
                    (stored - expected).abs() < 1e-12 * energy_scale,
                    "d={d} a={a}: energy {stored} (A6) {expected}"
                );
                let elongation = crater.h(a) - d;
                let limit = c * a.sqrt();
                assert!(
                    elongation <= limit + 1e-12 * state.max_overlap,
                    "d={d} a={a}: {elongation} > {limit}"
                );
                if elongation > 1e-9 * state.max_overlap {
                    stretched += 1;
                }
                if a < before.contact_radius {
                    assert!(
                        (elongation - limit).abs() < 1e-11 * state.max_overlap,
                        "d={d} a={a}: retreated to {elongation}, limit {limit}"
                    );
                    let released = PI * gamma_for(c) * (before.contact_radius.powi(2) - a * a);
                    let booked = state.adhesive_work - before.adhesive_work;
                    // The sum booked so far carries its own rounding.
                    assert!(
                        (booked - released).abs() < 1e-12 * released + 1e-15 * state.adhesive_work,
                        "d={d}: {booked} {released}"
                    );
                    retreated += 1;
                }
            } else {
                assert_eq!(response.force, 0.0);
                assert!(!law.holds(&state));
                assert_eq!(law.elastic_energy(&state, d), 0.0);
            }
            if a == 0.0 && before.contact_radius > 0.0 {
                // Let go: below the weakest edge of the disc that was attached, which the
                // previous overlap was not, with the energy (A6) the springs held.
                let (weakest, weakest_overlap) = crater.weakest_edge(before.contact_radius);
                assert!(d < weakest_overlap + 1e-12 * state.max_overlap, "d={d}");
                assert!(previous_overlap >= weakest_overlap - 1e-12 * state.max_overlap);
                let held = PI * gamma_for(c) * (before.contact_radius.powi(2) - weakest * weakest)
                    + crater.energy(weakest_overlap, weakest);
                let booked = state.adhesive_work - before.adhesive_work;
                assert!(
                    (booked - held).abs() < 1e-9 * held,
                    "d={d}: let-go work {booked}, (A6) {held}"
                );
                // The force drops to zero at the weakest edge's overlap within the step.
                step_work = previous_force * (weakest_overlap - previous_overlap);
                let_go += 1;
            }
            work += step_work;
            // The let-go overlap (A7) of the disc as it stands: at every turn and every 1009th
            // step.
            if state.contact_radius > 0.0 && (i == n || i % 1009 == 0) {
                let expected = crater.weakest_edge(state.contact_radius).1;
                let got = law.detachment_overlap(&state);
                assert!(
                    (got - expected).abs() < 1e-13 * state.max_overlap,
                    "d={d} a={}: δ_off {got}, (A7) {expected}",
                    state.contact_radius
                );
            }
        }
    }
    // The books: work done (the trapezoid rule, and at a let-go the force up to the weakest
    // edge's overlap) = stored + plastic + adhesive.
    let stored = law.elastic_energy(&state, d);
    let dissipated = law.dissipated_work(&state);
    let plain = MdrLaw::from_parts(MODULUS, RADIUS * scale, YIELD * scale, THETA);
    let plastic = plain.dissipated_work(&MdrState {
        max_overlap: state.max_overlap,
    });
    assert!(
        (dissipated - plastic - state.adhesive_work).abs() < 1e-15 * dissipated,
        "{dissipated} {plastic} {}",
        state.adhesive_work
    );
    assert!(
        (work - stored - dissipated).abs() < 1e-5 * work,
        "work {work}, stored {stored} + dissipated {dissipated}"
    );
    (stretched, retreated, let_go)
}

#[test]
fn elastic_unloading_to_let_go_follows_the_crater_written_out() {
    // d_max below u_c: no crater, h = x²/R; the edge's ε at the deepest overlap is about 0.8.
    let c = 0.004;
    let (stretched, retreated, let_go) = walk(&law(c), c, &[8e-4, -0.01], 1e-7);
    assert!(
        stretched > 1000 && retreated > 1000,
        "{stretched} {retreated}"
    );
    assert_eq!(let_go, 1);
}

#[test]
fn plastic_unloading_through_the_neck_follows_the_crater_written_out() {
    // s = 0.9 mm: b = 30 mm; the residual depth (1 − θ)s = 0.675 mm, below which no spring
    // touches and the neck is held by adhesion alone; reloading and a second let-go.
    let c = 0.004;
    let turns = [1.9e-3, 1.2e-3, 1.6e-3, 5e-4, 1.0e-3, -0.01];
    let (stretched, retreated, let_go) = walk(&law(c), c, &turns, 1e-7);
    assert!(
        stretched > 1000 && retreated > 1000,
        "{stretched} {retreated}"
    );
    assert_eq!(let_go, 1);
}

#[test]
fn large_plastic_contact_follows_the_crater_written_out() {
    // s = 29 mm, b = 0.17 m: ε = (c/κ) a_t^{−3/2} from below 1/16 (the series) on the
    // sphere's branch and on the flattened one to far above 1/2 near let-go. The contact lets
    // go on the way down to 20 mm (below the residual depth 21.75 mm, at its weakest edge's
    // 21.3 mm), re-touches, and lets go twice more.
    let c = 0.004;
    let turns = [3e-2, 2e-2, 2.5e-2, -0.01, 3.1e-2, -0.01];
    let (stretched, retreated, let_go) = walk(&law(c), c, &turns, 1e-6);
    assert!(
        stretched > 1000 && retreated > 1000,
        "{stretched} {retreated}"
    );
    assert_eq!(let_go, 3);
}

#[test]
fn the_walks_hold_in_other_units() {
    // The plastic walk with every length 10³ and 10⁻³ times as large (R ≠ 1: no factor of R
    // may go missing).
    for scale in [1e3, 1e-3] {
        let turns = [1.9e-3, 1.2e-3, 1.6e-3, 5e-4, 1.0e-3, -0.01].map(|d| d * scale);
        let law = scaled_law(0.004, scale);
        let (stretched, retreated, let_go) = walk_scaled(&law, 0.004, scale, &turns, 1e-6 * scale);
        assert!(
            stretched > 100 && retreated > 100,
            "{stretched} {retreated}"
        );
        assert_eq!(let_go, 1);
    }
}

#[test]
fn strong_adhesion_on_a_small_crater_follows_the_crater_written_out() {
    // c = 0.04: the weakest edge (cR/4)^{2/3} = 46 mm lies outside the plastic radius 20 mm.
    let c = 0.04;
    let turns = [1.4e-3, 0.0, 1.2e-3, -0.05];
    let (stretched, retreated, let_go) = walk(&law(c), c, &turns, 1e-7);
    // The disc of 37 mm lies inside the weakest edge: every smaller edge is weaker (δ falls
    // with a' up to a*), so the neck holds to δ(a) and lets go at once, without retreating.
    assert!(stretched > 1000, "{stretched}");
    assert_eq!(retreated, 0);
    assert_eq!(let_go, 1);
}

#[test]
fn a_small_disc_re_touching_inside_the_plastic_radius_lets_go_at_its_edge() {
    // After a let-go the contact re-touches just above the residual depth (1 − θ)s: a small
    // disc on the flattened branch, inside its stationary point, whose weakest edge is its own
    // edge, not the plastic radius b or the stationary point beyond the disc. s = 0.4 mm:
    // b = 20 mm inside the stationary point (25.2 mm), δ falls all the way out to b; re-touch
    // at 0.32 mm (residual depth 0.3 mm), a disc of 8.9 mm. s = 0.9 mm: b = 30 mm beyond the
    // stationary point; re-touch at 0.7 mm (residual depth 0.675 mm), a disc of 10 mm.
    let c = 0.004;
    for (s, retouch) in [(4e-4, 3.2e-4), (9e-4, 7e-4)] {
        let turns = [YIELD + s, -0.01, retouch, -0.01];
        let (stretched, retreated, let_go) = walk(&law(c), c, &turns, 1e-7);
        assert!(
            stretched > 1000 && retreated > 100,
            "{stretched} {retreated}"
        );
        assert_eq!(let_go, 2);
        let law = law(c);
        let mut state = AdhesiveMdrState::default();
        for d in [YIELD + s, -0.01, retouch] {
            law.update(&mut state, d);
        }
        let residual = (1.0 - THETA) * s;
        let a = state.contact_radius;
        assert!(
            (a - ((retouch - residual) / THETA).sqrt()).abs() < 1e-12,
            "{a}"
        );
        let expected = THETA * a * a + residual - c * a.sqrt();
        assert!((law.detachment_overlap(&state) - expected).abs() < 1e-16);
    }
}

/// The let-go overlap of the disc attached on loading to `d_max`, against the search, and
/// where its weakest edge lies.
fn detachment_after_loading(c: f64, max_overlap: f64) -> f64 {
    detachment_after_loading_scaled(c, max_overlap, 1.0)
}

/// The same for the law with every length times `scale` ([`scaled_law`]); lengths in and out
/// are those of the unit law.
fn detachment_after_loading_scaled(c: f64, max_overlap: f64, scale: f64) -> f64 {
    let law = scaled_law(c, scale);
    let mut state = AdhesiveMdrState::default();
    law.update(&mut state, max_overlap * scale);
    let crater = crater_of(max_overlap * scale, c * scale.sqrt(), scale);
    let (weakest, expected) = crater.weakest_edge(state.contact_radius);
    let got = law.detachment_overlap(&state);
    assert!(
        (got - expected).abs() < 1e-13 * max_overlap * scale,
        "d_max={max_overlap} scale={scale}: {got} (A7) {expected}"
    );
    weakest / scale
}

#[test]
fn detachment_overlap_is_the_weakest_edge_on_every_branch() {
    let c = 0.004;
    // The sphere's branch: a* = (cR/4)^{2/3} = 10 mm, elastic and with b = 6.3 mm.
    for d_max in [8e-4, YIELD + 4e-5] {
        let a = detachment_after_loading(c, d_max);
        assert!((a - 0.01).abs() < 1e-6, "{a}");
    }
    // The flattened branch: a* = (cR/(4θ))^{2/3} = 25.2 mm inside b = 30 mm.
    let a = detachment_after_loading(c, YIELD + 9e-4);
    assert!((a - 0.004f64.powf(2.0 / 3.0)).abs() < 1e-6, "{a}");
    // The kink at b = 20 mm, between the two stationary points.
    let a = detachment_after_loading(c, YIELD + 4e-4);
    assert!((a - 0.02).abs() < 1e-9, "{a}");
    // The edge itself: a disc of radius 7.1 mm, inside the stationary point.
    let a = detachment_after_loading(c, 5e-5);
    assert!((a - 5e-5f64.sqrt()).abs() < 1e-9, "{a}");
    // Strong adhesion: a* = 46 mm on the sphere's branch outside b = 39 mm and inside the
    // edge at 50 mm; the flattened branch's stationary point (117 mm) lies beyond b.
    let a = detachment_after_loading(0.04, YIELD + 1.5e-3);
    assert!((a - 0.01f64.powf(2.0 / 3.0)).abs() < 1e-6, "{a}");
    // The same contacts with every length 10⁴ and 10⁻⁴ times as large: which branch holds the
    // weakest edge does not depend on the unit (b² against a or a², here above and below 1).
    for scale in [1e4, 1e-4] {
        for (c, d_max, weakest) in [
            (0.04, YIELD + 1.5e-3, 0.01f64.powf(2.0 / 3.0)),
            (c, YIELD + 9e-4, 0.004f64.powf(2.0 / 3.0)),
            (c, YIELD + 4e-4, 0.02),
        ] {
            let a = detachment_after_loading_scaled(c, d_max, scale);
            assert!((a - weakest).abs() < 1e-6, "scale {scale}: {a} {weakest}");
        }
    }
    // A contact that does not hold lets go at its residual overlap (1 − θ)s.
    let law = law(c);
    let state = AdhesiveMdrState {
        max_overlap: YIELD + 4e-4,
        contact_radius: 0.0,
        adhesive_work: 0.0,
    };
    assert!(!law.holds(&state));
    assert!((law.detachment_overlap(&state) - (1.0 - THETA) * 4e-4).abs() < 1e-18);
}

#[test]
fn accessors_give_the_parameters() {
    let c = 0.004;
    let law = law(c);
    let gamma = gamma_for(c);
    assert_eq!(law.work_of_adhesion(), gamma);
    assert!(
        (law.pull_off_force() - 1.5 * PI * gamma * RADIUS).abs() < 1e-15 * law.pull_off_force()
    );
    assert_eq!(law.jkr_pull_off_force(), law.pull_off_force());
    assert!((law.critical_elongation(0.01) - c * 0.1).abs() < 1e-16);
    assert_eq!(law.yield_overlap(), YIELD);
    assert_eq!(law.mdr().yield_overlap(), YIELD);
    let mut state = AdhesiveMdrState::default();
    law.update(&mut state, 2e-3);
    assert_eq!(law.max_overlap(&state), 2e-3);
    assert!((law.residual_overlap(&state) - (1.0 - THETA) * (2e-3 - YIELD)).abs() < 1e-18);
    let model = AdhesiveMdr::new(MdrElastoPlastic::paper(), 0.3).unwrap();
    assert_eq!(model.work_of_adhesion(), 0.3);
    assert_eq!(model.params(), &MdrElastoPlastic::paper());
}
