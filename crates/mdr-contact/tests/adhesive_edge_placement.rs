//! Where the adhesive MDR law places the edge of an attached disc that retreats on unloading
//! (docs/theory.md §9, eqs. A5, A12, A12a), against the root of (A5) found here by bisection.
//!
//! Where springs touch out to `a_t` on a branch `h = κx² + h₀` of the crater, (A5) on that
//! branch is the quartic `u⁴ − εu − 1 = 0` in `u = √(a/a_t)`, `ε = Δl_max(a_t)/(d − h₀)`, and
//! the edge is `a_t u²` with `u` its largest root. The law takes `y/ε = (u² − 1)/ε` from the
//! series (A12) for `ε ≤ 1/16` and from the two fits (A12a) up to `ε = 2`, each within
//! `8·10⁻¹⁷` of `y/ε` in double precision (docs/theory.md): the edge to round-off. The laws here
//! are in round units (`E* = 1 Pa`, `R = 1 m`, `θ = 1/4`, touching radius `1/4 m`), where the
//! touching radius and `ε` are exact in double precision, and with every length `4⁻⁶`, `4⁶` and
//! `4⁻²⁴` times as large, so the edge is held to the root at a few units in the last place: a
//! fit coefficient with its sign changed moves the edge by at least `1.9·10⁻¹⁴` of it. Beyond
//! `ε = 2`, for a root beyond the plastic radius and for a neck held by adhesion alone (also just
//! past its weakest edge), the edge is held to the largest root of (A5) on the whole crater
//! (A1), found by bisection.

use mdr_contact::prelude::*;
use std::f64::consts::PI;

const MODULUS: f64 = 1.0;
const THETA: f64 = 0.25;
/// The touching radius of every case, in units of the length scale.
const TOUCHING: f64 = 0.25;
/// The length scales: every length (`R`, `u_c`, overlaps, radii) times these, `1`, `4⁻⁶`,
/// `4⁶` and `4⁻²⁴` (`3.6·10⁻¹⁵`): the placement is free of the unit of length. (Halley's
/// iteration stopped by `t − t_next ≤ 10⁻¹⁵/t` for `≤ 10⁻¹⁵ t` ends after its first step at
/// `4⁻²⁴` and fails every test of the iteration there.)
const SCALES: [f64; 4] = [1.0, 1.0 / 4096.0, 4096.0, 1.0 / 281_474_976_710_656.0];

/// `y/ε` of the largest root `u` of `u⁴ − εu − 1 = 0`, `y = u² − 1`, by bisection. With
/// `u² = 1 + εz` the quartic is `z(2 + εz) = √(1 + εz)`, written as
/// `2z − 1 + zw − w/(1 + √(1 + w))` with `w = εz` (`√(1 + w) − 1 = w/(1 + √(1 + w))`): near the
/// root `z ≈ 1/2` its terms are of the order of `ε`, not 1, so its rounding is small. The left
/// side is `−1` at `z = 0` and positive at `z = 1/2` for every `ε > 0`.
fn edge_ratio(eps: f64) -> f64 {
    let residual = |z: f64| {
        let w = eps * z;
        (2.0 * z - 1.0) + z * w - w / (1.0 + (1.0 + w).sqrt())
    };
    let (mut lo, mut hi) = (0.0_f64, 0.5_f64);
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return mid;
        }
        if residual(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
}

/// One unloading step: the law with `√(2πΔγ/E*) = c` and every length times `scale`, loaded to
/// `max_overlap` (its edge `√(R d_max)`) and unloaded to `overlap`, where the springs touch out
/// to `TOUCHING · scale` on the branch of curvature `κ`.
struct Unloading {
    /// `u_c` in units of the length scale.
    yield_overlap: f64,
    /// `d_max` in units of the length scale.
    max_overlap: f64,
    /// `d` in units of the length scale.
    overlap: f64,
    /// `κ R`: 1 on the sphere's branch, `θ` on the flattened one.
    kappa_radius: f64,
}

/// Outside the plastic radius: `s = 1/32`, `b = 0.177`, `d = 1/16 ≥ s`, `a_t = √(R d) = 1/4`,
/// the loaded edge `1` (so every root up to `ε = 7.5`, `u = 2`, lies inside it).
const SPHERES_BRANCH: Unloading = Unloading {
    yield_overlap: 0.96875,
    max_overlap: 1.0,
    overlap: 0.0625,
    kappa_radius: 1.0,
};

/// Inside the plastic radius: `s = 9/16`, `b = 3/4`, `h₀ = (1 − θ)s = 27/64`, `d = h₀ + 1/64`
/// (`< s`), `a_t = √(R(d − h₀)/θ) = 1/4`; every root up to `ε = 4.6` (`a = 3 a_t`) lies inside
/// `b`, and the loaded edge `√(R d_max) = 0.79` beyond it.
const FLATTENED_BRANCH: Unloading = Unloading {
    yield_overlap: 0.0625,
    max_overlap: 0.625,
    overlap: 0.4375,
    kappa_radius: THETA,
};

impl Unloading {
    /// The law at `scale` with `Δγ = E* c²/(2π)`, `c = eps · κ a_t^{3/2}`; and the `ε` its
    /// `√(2πΔγ/E*)` (rounded) gives, exact as `κ a_t^{3/2}` is a power of two.
    fn law(&self, eps: f64, scale: f64) -> (AdhesiveMdrLaw, f64) {
        let kappa = self.kappa_radius / scale;
        let a_t = TOUCHING * scale;
        let branch_scale = kappa * a_t * a_t.sqrt();
        let law = self.law_for(eps * branch_scale / scale.sqrt(), scale);
        let eps = law.critical_elongation(1.0) / branch_scale;
        (law, eps)
    }

    /// The law at `scale` (`R = scale`) with `√(2πΔγ/E*) = c √scale`, `c` in units of the
    /// length scale (m^½ at scale 1).
    fn law_for(&self, c: f64, scale: f64) -> AdhesiveMdrLaw {
        let c = c * scale.sqrt();
        AdhesiveMdrLaw::new(
            MdrLaw::from_parts(MODULUS, scale, self.yield_overlap * scale, THETA),
            MODULUS * c * c / (2.0 * PI),
        )
    }

    /// The edge after the step, from the loaded edge `√(R d_max)` (or `previous` if given).
    fn edge(&self, law: &AdhesiveMdrLaw, scale: f64, previous: Option<f64>) -> f64 {
        let max_overlap = self.max_overlap * scale;
        let mut state = AdhesiveMdrState {
            max_overlap,
            contact_radius: previous.unwrap_or((scale * max_overlap).sqrt()),
            adhesive_work: 0.0,
        };
        law.update(&mut state, self.overlap * scale);
        state.contact_radius
    }

    /// The crater's profile (A1) at `x` (all in units of the length scale, `R = 1`).
    fn profile(&self, x: f64) -> f64 {
        let s = (self.max_overlap - self.yield_overlap).max(0.0);
        if x * x < s {
            THETA * x * x + (1.0 - THETA) * s
        } else {
            x * x
        }
    }
}

/// The touching radius of both cases is `1/4` of the length scale exactly: the non-adhesive
/// law's (`Δγ = 0`), on the branch each case names.
#[test]
fn the_cases_touch_out_to_a_quarter_of_the_length_scale() {
    for case in [&SPHERES_BRANCH, &FLATTENED_BRANCH] {
        let s = case.max_overlap - case.yield_overlap;
        let depth = (1.0 - THETA) * s;
        assert!(case.overlap > depth);
        assert_eq!(case.overlap >= s, case.kappa_radius == 1.0);
        // κ a_t² = d − h₀ on the branch.
        let h0 = if case.overlap >= s { 0.0 } else { depth };
        assert_eq!(case.kappa_radius * TOUCHING * TOUCHING, case.overlap - h0);
        for scale in SCALES {
            let (law, _) = case.law(0.0, scale);
            let mut state = AdhesiveMdrState {
                max_overlap: case.max_overlap * scale,
                ..Default::default()
            };
            let response = law.update(&mut state, case.overlap * scale);
            assert_eq!(response.contact_radius, TOUCHING * scale);
        }
    }
}

/// The values of `ε` in each band: log-spaced from `10⁻³` to the series' limit `1/16`, evenly
/// spaced over the two fitted bands `(1/16, 1/2]` and `(1/2, 2]`, with the bands' limits.
fn epsilons() -> Vec<f64> {
    let mut eps: Vec<f64> = (0..24)
        .map(|k| 1e-3 * 62.5_f64.powf(k as f64 / 23.0))
        .collect();
    eps.extend((1..=40).map(|k| 0.0625 + (0.5 - 0.0625) * k as f64 / 40.0));
    eps.extend((1..=40).map(|k| 0.5 + 1.5 * k as f64 / 40.0));
    eps.extend([
        0.0625,
        0.0625 * (1.0 + 1e-15),
        0.5 * (1.0 - 1e-15),
        0.5,
        2.0,
    ]);
    eps
}

/// On unloading from the loaded edge, the edge retreats to `a_t (1 + ε y/ε)` with `y/ε` the root
/// of the quartic (bisection above), within `6·10⁻¹⁶` of it (three units in the last place;
/// measured `2.1·10⁻¹⁶`, the law and the reference each within `1.2·10⁻¹⁶` of the root computed
/// to 40 digits), for `ε` from `10⁻³` to 2 over the series and both fitted bands, on the
/// sphere's branch and on the flattened branch, at every length scale; an edge inside the root
/// holds. Every fit coefficient with its sign changed moves the edge by `1.9·10⁻¹⁴` of it or
/// more (`EDGE_FIT[0]`, the smallest, at the fitted band's ends), a series coefficient by more.
#[test]
fn the_edge_is_the_root_of_the_quartic_to_round_off_in_every_band() {
    for case in [&SPHERES_BRANCH, &FLATTENED_BRANCH] {
        for scale in SCALES {
            let a_t = TOUCHING * scale;
            for eps_asked in epsilons() {
                let (law, eps) = case.law(eps_asked, scale);
                let expected = a_t + a_t * eps * edge_ratio(eps);
                let edge = case.edge(&law, scale, None);
                assert!(
                    (edge - expected).abs() <= 6e-16 * expected,
                    "κR = {}, scale {scale}, ε = {eps}: edge {edge:e}, root {expected:e}, \
                     off by {:e} of it",
                    case.kappa_radius,
                    (edge - expected) / expected
                );
                // An edge inside the root holds.
                let inside = a_t + 0.5 * (expected - a_t);
                assert_eq!(case.edge(&law, scale, Some(inside)), inside);
            }
        }
    }
}

/// The largest root of (A5) `h(a) − √(2πΔγ/E*) √a = d` on the crater (A1) below `previous`, by
/// bisection in units of the length scale (`c` in those units); `None` where `h − c√a − d` is
/// positive on the whole disc (the contact lets go). `δ = h − c√a` is convex in `√a`, so its
/// part below `d` is one interval: a grid of `4096` points in `√a` finds a point in it.
fn crater_root(case: &Unloading, c: f64, previous: f64) -> Option<f64> {
    let phi = |a: f64| case.profile(a) - c * a.sqrt() - case.overlap;
    let n = 4096;
    let below = (0..=n).rev().find_map(|k| {
        let a = previous * (k as f64 / n as f64).powi(2);
        (phi(a) < 0.0).then_some(a)
    })?;
    let (mut lo, mut hi) = (below, previous);
    assert!(phi(hi) > 0.0, "the edge holds at {previous}");
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return Some(mid);
        }
        if phi(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
}

/// What the rounding of (A5) allows an edge at the root `a` of `φ(a) = h(a) − c√a − d` to be off
/// by: `10⁻¹⁵ a`, and 4 units in the last place of `φ`'s terms over its slope `dφ/da` (large
/// near the weakest edge, where `φ` is flat).
fn root_tolerance(case: &Unloading, c: f64, a: f64) -> f64 {
    let s = (case.max_overlap - case.yield_overlap).max(0.0);
    let profile_slope = if a * a < s { 2.0 * THETA * a } else { 2.0 * a };
    let slope = profile_slope - 0.5 * c / a.sqrt();
    let terms = case.profile(a) + c * a.sqrt() + case.overlap.abs();
    1e-15 * a + 4.0 * f64::EPSILON * terms / slope.abs()
}

/// Beyond the fits (`ε = 2.5`, `4`, `7` on the sphere's branch; `2.5`, `4` on the flattened
/// branch, Halley's iteration), and where the flattened branch's root would lie beyond the
/// plastic radius (`ε = 6` there: the root on the sphere's branch, `ε ≈ 0.35` on it, the fit),
/// the edge retreats from the loaded edge to the largest root of (A5) on the crater, within the
/// rounding of (A5) (`root_tolerance`), at every length scale.
#[test]
fn past_the_fits_the_edge_is_the_root_on_the_crater() {
    let cases = [
        (&SPHERES_BRANCH, [2.5, 4.0, 7.0].as_slice()),
        (&FLATTENED_BRANCH, [2.5, 4.0, 6.0].as_slice()),
    ];
    for (case, epsilons) in cases {
        for &eps_asked in epsilons {
            for scale in SCALES {
                let (law, _) = case.law(eps_asked, scale);
                let c = law.critical_elongation(1.0) / scale.sqrt();
                let previous = case.max_overlap.sqrt();
                let root = crater_root(case, c, previous).expect("a root");
                let edge = case.edge(&law, scale, None) / scale;
                assert!(
                    (edge - root).abs() <= root_tolerance(case, c, root),
                    "κR = {}, scale {scale}, ε = {eps_asked}: edge {edge}, root {root}",
                    case.kappa_radius
                );
            }
        }
    }
}

/// A neck held by adhesion alone (the overlap below the residual depth `h₀ = 27/64` of the
/// flattened case's crater: no spring touches) with `√(2πΔγ/E*) = 0.1 m^½`, whose `δ` has its
/// smallest value `0.387` at `a = 0.215`: at `d = 0.4` the edge retreats from the loaded edge to
/// the largest root of (A5) on the crater (Halley's iteration down to no touching radius),
/// within the rounding of (A5); at `d = 0.38` no root is left and the contact lets go. At every length
/// scale.
#[test]
fn a_neck_held_by_adhesion_alone_retreats_to_its_root_or_lets_go() {
    for (overlap, holds) in [(0.4, true), (0.38, false)] {
        let case = Unloading {
            overlap,
            ..FLATTENED_BRANCH
        };
        for scale in SCALES {
            let law = case.law_for(0.1, scale);
            let c = law.critical_elongation(1.0) / scale.sqrt();
            let previous = case.max_overlap.sqrt();
            let edge = case.edge(&law, scale, None) / scale;
            match crater_root(&case, c, previous) {
                Some(root) => {
                    assert!(holds, "d = {overlap}: a root {root}");
                    assert!(
                        (edge - root).abs() <= root_tolerance(&case, c, root),
                        "scale {scale}, d = {overlap}: edge {edge}, root {root}"
                    );
                }
                None => {
                    assert!(!holds, "d = {overlap}: no root");
                    assert_eq!(edge, 0.0, "scale {scale}, d = {overlap}");
                }
            }
        }
    }
}

/// A neck held apart by adhesion alone on an elastic sphere (`s = 0`), its edge `a₀` a little
/// past the weakest edge `a* = (cR/4)^{2/3}` (A7), where `φ(t) = h(t²) − ct − d` (`t = √a`)
/// rises slowly, and `d` a little above the let-go overlap `δ(a*)`: the edge retreats to the
/// largest root of (A5), within the rounding of (A5), and does not let go, at every length scale.
/// `c = 0.1 m^½`, `a₀ = R/8` (`a* = 0.085 R`), `d = −0.021 R` (`δ(a*) = −0.0219 R`); and at
/// the far end of the formula's range, `c = 3 m^½`, `a₀ = R`, `d = −2.02 R`
/// (`δ(a*) = −2.044 R`). The iteration's shortcut that lets go where `φ` falls at the edge,
/// with its slope `2t h'(t²) − c` read as `2 + t h' − c`, `2t + h' − c` or `2t/h' − c`, lets
/// the second neck go (at `R = 4096 m`; the last at every scale).
#[test]
fn a_neck_near_its_weakest_edge_retreats_to_its_root() {
    for (c, previous, overlap) in [(0.1, 0.125, -0.021), (3.0, 1.0, -2.02)] {
        let case = Unloading {
            yield_overlap: 1e3,
            max_overlap: previous * previous,
            overlap,
            kappa_radius: 1.0,
        };
        for scale in SCALES {
            let law = case.law_for(c, scale);
            let c = law.critical_elongation(1.0) / scale.sqrt();
            let root = crater_root(&case, c, previous).expect("a root");
            let edge = case.edge(&law, scale, None) / scale;
            assert!(
                (edge - root).abs() <= root_tolerance(&case, c, root),
                "c = {c}, scale {scale}: edge {edge}, root {root}"
            );
        }
    }
}
