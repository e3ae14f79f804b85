//! The adhesive MDR law's held and retreating edge (docs/theory.md, eqs. A3–A7) where the walks
//! of `adhesive_crater.rs` do not look: the tangent stiffness `2E* a` of an edge placed by
//! Halley's iteration or on the sphere's branch; the held edge's test `(h(a) − d)² ≤ c² a` in
//! units where `c² a` is above 1 (a test with the elongation's square replaced by a sum or a
//! ratio declines every edge in small units, leaving it to the iteration, which holds it
//! itself, but holds an edge past its limit in large ones); and a contact pulled far apart in
//! one step. Expectations from the crater written out here (eq. A1): the force (A3) by
//! Gauss–Legendre quadrature, the edge (A5) by bisection, and the let-go work (A6) at the
//! weakest edge (A7) in closed form. `E* = 4 Pa`, so that a factor of `E*` cannot go missing.
//! Tolerances are a few times the round-off measured: the edge within `5·10⁻¹⁶` of the root,
//! the force within `10⁻¹⁶` of `2E* a d_max`, the works to the last bit.

#[path = "common/crater.rs"]
mod crater;

use crater::Crater;
use mdr_contact::prelude::*;
use std::f64::consts::PI;

const MODULUS: f64 = 4.0;
const RADIUS: f64 = 1.0;
const YIELD: f64 = 1e-3;
const THETA: f64 = 0.25;
/// The let-go coefficient `c = √(2πΔγ/E*)` (m^½) of the law in metres.
const C: f64 = 0.004;

/// `Δγ` of the law with every length times `scale` (`c` times `√scale`).
fn gamma(scale: f64) -> f64 {
    C * C * scale * MODULUS / (2.0 * PI)
}

/// The law with every length times `scale`: `R`, `u_c`, and `c` times `√scale`.
fn law(scale: f64) -> AdhesiveMdrLaw {
    AdhesiveMdrLaw::new(
        MdrLaw::from_parts(MODULUS, RADIUS * scale, YIELD * scale, THETA),
        gamma(scale),
    )
}

/// The crater of the history `d_max` (eq. A1), written out, for the law with every length
/// times `scale`.
fn crater_of(max_overlap: f64, scale: f64) -> Crater {
    Crater::new(
        MODULUS,
        RADIUS * scale,
        YIELD * scale,
        THETA,
        C * scale.sqrt(),
        max_overlap,
    )
}

/// One update from an attached edge at `previous` after loading to `max_overlap`.
fn unload(
    law: &AdhesiveMdrLaw,
    max_overlap: f64,
    previous: f64,
    d: f64,
) -> (NormalResponse, AdhesiveMdrState) {
    let mut state = AdhesiveMdrState {
        max_overlap,
        contact_radius: previous,
        adhesive_work: 0.0,
    };
    let response = law.update(&mut state, d);
    assert_eq!(state.max_overlap, max_overlap);
    assert_eq!(response.contact_radius, state.contact_radius);
    (response, state)
}

/// Where the edge retreats in the cases the branch's own root does not settle, the edge is the
/// root of (A5) on the crater and the law reports the tangent stiffness of the attached springs,
/// `2E* a` (docs/theory.md §9), the force (A3) on the attached disc and the work
/// `π Δγ (a₀² − a²)` of the released annulus: a neck held by adhesion alone (no spring
/// touching, Halley's iteration), springs touching on the flattened branch with the root beyond
/// the plastic radius (the sphere's branch), and springs touching on the sphere's branch with
/// `ε = (cR) a_t^{−3/2} > 2` (Halley's iteration from the touching radius). Kills the
/// iteration's stiffness `2E* · a` with `+` or `/` (the walks check force and energy only).
#[test]
fn an_edge_placed_by_the_iteration_has_the_stiffness_of_its_springs() {
    let law = law(1.0);
    // (d_max, a₀, d): b = 30 mm, residual depth 0.675 mm. The neck: a₀ = 36 mm beyond b, d
    // half-way between the disc's smallest δ and δ(a₀), below the residual depth. The flattened
    // branch: d = 0.89 mm, touching out to 29.3 mm inside b, ε = 3.2 there; the loaded edge
    // 43.6 mm retreats to about 41 mm, beyond b. The sphere's branch: no crater, d = 0.1 mm,
    // touching out to 10 mm, ε = 4.
    let neck = {
        let crater = crater_of(1.9e-3, 1.0);
        let lowest = (1..=20_000)
            .map(|i| crater.edge_overlap((0.036f64.sqrt() * i as f64 / 2e4).powi(2)))
            .fold(f64::INFINITY, f64::min);
        let d = 0.5 * (lowest + crater.edge_overlap(0.036));
        assert!(d > 0.0 && d < crater.depth(), "{d}");
        (1.9e-3, 0.036, d)
    };
    let cases = [
        ("neck", neck),
        ("flattened", (1.9e-3, 1.9e-3f64.sqrt(), 0.89e-3)),
        ("sphere", (8e-4, 8e-4f64.sqrt(), 1e-4)),
    ];
    for (what, (max_overlap, previous, d)) in cases {
        let crater = crater_of(max_overlap, 1.0);
        let (response, state) = unload(&law, max_overlap, previous, d);
        let a = state.contact_radius;
        let root = crater.retreated_edge(previous, d);
        assert!(
            (a - root).abs() <= 1e-14 * root,
            "{what}: edge {a}, root of (A5) {root}"
        );
        match what {
            "flattened" => {
                let touching = ((d - crater.depth()) * RADIUS / THETA).sqrt();
                assert!(touching < crater.plastic_radius() && a > crater.plastic_radius());
                assert!(C * RADIUS / THETA * touching.powf(-1.5) > 2.0);
            }
            "sphere" => assert!(C * RADIUS * (RADIUS * d).powf(-0.75) > 2.0),
            _ => {}
        }
        let stiffness = 2.0 * MODULUS * a;
        assert!(
            (response.stiffness - stiffness).abs() <= 1e-15 * stiffness,
            "{what}: stiffness {} for 2E* a = {stiffness}",
            response.stiffness
        );
        let force = crater.force(d, a);
        assert!(
            (response.force - force).abs() <= 1e-15 * 2.0 * MODULUS * a * max_overlap,
            "{what}: force {} (A3) {force}",
            response.force
        );
        let work = PI * gamma(1.0) * (previous * previous - a * a);
        assert!(
            (state.adhesive_work - work).abs() <= 1e-13 * work,
            "{what}: work {} for {work}",
            state.adhesive_work
        );
    }
}

/// A neck held by adhesion alone (no spring touching) holds its edge `a₀` just inside its
/// limit `δ(a₀)` (A5), with the force (A3), `2E* a₀` and no work, and retreats to the root of
/// (A5) just past it, in metres and with every length 10⁻⁴ and 10⁴ times as large. At 10⁴,
/// `c² a₀ = 58 m²` against the limit's elongation `c√a₀ = 7.6 m`: kills the test
/// `(h(a) − d)² ≤ c² a` with the square as `e + e` or `e / e`, or the elongation `h − d` as
/// `h / d`, each of which holds the edge past its limit there (in metres each declines, and the
/// iteration holds or retreats the edge itself).
#[test]
fn a_neck_holds_to_its_limit_in_any_unit() {
    for scale in [1e-4, 1.0, 1e4] {
        let law = law(scale);
        let max_overlap = 1.9e-3 * scale;
        let crater = crater_of(max_overlap, scale);
        // Beyond b = 30 mm (scaled), its limit overlap below the residual depth.
        let previous = 0.036 * scale;
        let limit = crater.c * previous.sqrt();
        let at_limit = crater.edge_overlap(previous);
        assert!(at_limit > 0.0 && at_limit < crater.depth());
        let d = at_limit + 1e-9 * limit;
        let (response, state) = unload(&law, max_overlap, previous, d);
        assert_eq!(state.contact_radius, previous, "scale {scale}: held");
        let force = crater.force(d, previous);
        assert!(
            (response.force - force).abs() <= 1e-15 * 2.0 * MODULUS * previous * max_overlap,
            "scale {scale}: force {} (A3) {force}",
            response.force
        );
        assert!(
            (response.stiffness - 2.0 * MODULUS * previous).abs()
                <= 1e-15 * 2.0 * MODULUS * previous
        );
        assert_eq!(state.adhesive_work, 0.0);
        let d = at_limit - 1e-6 * limit;
        let (_, state) = unload(&law, max_overlap, previous, d);
        let root = crater.retreated_edge(previous, d);
        assert!(
            state.contact_radius < previous && (state.contact_radius - root).abs() <= 1e-14 * root,
            "scale {scale}: edge {} past its limit, root of (A5) {root}",
            state.contact_radius
        );
    }
}

/// A contact pulled far apart in one step (from `d_max = 0.8 mm`, no crater, to `d = −10 m`
/// and `−1 km`) lets go: no force, no radius, and the adhesive work of (A6) at the weakest edge
/// (A7): the annulus `π Δγ (a₀² − a*²)` and the springs inside it at `δ(a*)`,
/// `E* ∫₀^{a*} (δ(a*) − x²/R)² dx`, with `a* = (cR/4)^{2/3}` (10 mm, inside the edge at
/// 28 mm). Kills the held edge's elongation `h(a) − d` as `h(a)/d`, whose square there is
/// below `c² a` (the far-apart contact held with the force of (A3)).
#[test]
fn a_contact_pulled_far_apart_in_one_step_lets_go_with_what_its_springs_held() {
    let law = law(1.0);
    let max_overlap = 8e-4;
    let crater = crater_of(max_overlap, 1.0);
    let previous = (RADIUS * max_overlap).sqrt();
    let weakest = (C * RADIUS / 4.0).powf(2.0 / 3.0);
    assert!(weakest < previous);
    let at_weakest = crater.edge_overlap(weakest);
    let held = PI * gamma(1.0) * (previous * previous - weakest * weakest)
        + MODULUS * crater.integrate(weakest, |x| (at_weakest - x * x / RADIUS).powi(2));
    for d in [-10.0, -1e3] {
        let mut state = AdhesiveMdrState::default();
        law.update(&mut state, max_overlap);
        assert_eq!(state.contact_radius, previous);
        let response = law.update(&mut state, d);
        assert_eq!(response.force, 0.0, "d = {d}");
        assert_eq!(state.contact_radius, 0.0);
        assert!(!law.holds(&state));
        assert!(
            (state.adhesive_work - held).abs() <= 1e-14 * held,
            "d = {d}: let-go work {} (A6) {held}",
            state.adhesive_work
        );
    }
}
