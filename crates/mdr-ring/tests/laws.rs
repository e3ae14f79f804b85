//! The restitution laws of the ring: Bridges et al. (1984) values, the constant law's range, and
//! the MDR ice law against `mdr-contact` and against Bridges where ring impacts happen.

use mdr_contact::normal::{MdrState, NormalModel};
use mdr_contact::ContactPair;
use mdr_ring::prelude::*;

fn equal_pair(r: f64) -> ImpactPair {
    let m = 400.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    ImpactPair {
        radius1: r,
        radius2: r,
        mass1: m,
        mass2: m,
    }
}

#[test]
fn bridges_law_values() {
    let law = BridgesLaw::default();
    // ε(1 mm/s) = 0.32 · 0.1^−0.234, ε(1 cm/s) = 0.32, ε = 1 below 0.32^{1/0.234} cm/s.
    assert!((law.at(1e-3) - 0.32 * 0.1f64.powf(-0.234)).abs() < 1e-12);
    assert!((law.at(1e-2) - 0.32).abs() < 1e-12);
    let v1 = law.elastic_speed();
    assert!((v1 - 0.01 * 0.32f64.powf(1.0 / 0.234)).abs() < 1e-15);
    assert_eq!(law.at(0.5 * v1), 1.0);
    assert!(law.at(2.0 * v1) < 1.0);
}

#[test]
fn constant_law_rejects_values_outside_zero_one() {
    assert!(ConstantRestitution::new(-0.1).is_err());
    assert!(ConstantRestitution::new(1.1).is_err());
    assert!(ConstantRestitution::new(f64::NAN).is_err());
    assert_eq!(
        ConstantRestitution::new(0.4)
            .unwrap()
            .first_impact(&equal_pair(1.0), 1e-3),
        0.4
    );
}

#[test]
fn mdr_ice_law_is_the_energy_route_of_mdr_contact() {
    let law = MdrRestitution::ice();
    let pair = equal_pair(1.6);
    let contact =
        ContactPair::sphere_on_sphere(1.6, &law.material(), 1.6, &law.material()).unwrap();
    let bound = law.model().bind(&contact).unwrap();
    for v in [1e-5, 3e-4, 1e-3, 1e-2] {
        let direct = bound
            .impact(&MdrState::default(), contact.reduced_mass(), v)
            .unwrap();
        let mut history = MdrState::default();
        let e = law.restitution(&pair, &mut history, v);
        assert!((e - direct.restitution).abs() < 1e-12, "v = {v}");
        let d = direct.state.max_overlap;
        assert!((history.max_overlap - d).abs() <= 1e-12 * d, "v = {v}");
    }
}

#[test]
fn mdr_ice_law_is_elastic_below_yield_and_remembers_plastic_history() {
    let law = MdrRestitution::ice();
    let pair = equal_pair(1.6);
    let vy = law.yield_speed(&pair).unwrap();
    assert_eq!(law.first_impact(&pair, 0.9 * vy), 1.0);
    assert!(law.first_impact(&pair, 3.0 * vy) < 1.0);
    // A second, slower impact of the same contact is elastic (flattened profile, eq. 13).
    let mut history = MdrState::default();
    let first = law.restitution(&pair, &mut history, 1e-3);
    assert!(first < 1.0 && history.max_overlap > 0.0);
    assert_eq!(law.restitution(&pair, &mut history, 5e-4), 1.0);
}

#[test]
fn mdr_ice_law_follows_bridges_over_ring_impact_speeds() {
    // The ice parameters were fitted to Bridges over 0.05–5 mm/s for 1.6 m particles
    // (docs/rings.md §6): within 0.06 at 0.3–3 mm/s, where most ring impacts are.
    let (mdr, bridges) = (MdrRestitution::ice(), BridgesLaw::default());
    let pair = equal_pair(1.6);
    for v in [3e-4, 1e-3, 3e-3] {
        // Bridges, Hatzes & Lin (1984): ε = 0.32 (v / 1 cm/s)^−0.234, written out here.
        let published = (0.32 * (v / 0.01f64).powf(-0.234)).min(1.0);
        let (a, b) = (mdr.first_impact(&pair, v), bridges.at(v));
        assert!((b - published).abs() < 1e-12, "v = {v}: {b} vs {published}");
        assert!(
            (a - published).abs() < 0.06,
            "v = {v}: MDR {a}, Bridges {published}"
        );
    }
    // High-speed limit sqrt(Θ/E*) (docs/theory.md §4).
    let fast = mdr.first_impact(&pair, 10.0);
    assert!((fast - 0.2f64.sqrt()).abs() < 0.02, "e(10 m/s) = {fast}");
}

/// The ice law's yield speed from the energy argument of docs/theory.md §4, written out here
/// (independent of the law crates): equal ice spheres of radius 1.6 m, `E* = E/(2(1 − ν²))`
/// (eq. 16), `R = r/2`, `m = m₁/2`, `u_c = π q_c/(2E*)` (eq. 11), `m v_y²/2 = (8/15) E* √R u_c^{5/2}`.
/// Below it the law is elastic, above it plastic.
#[test]
fn mdr_ice_law_yields_at_the_energy_argument_speed() {
    let law = MdrRestitution::ice();
    let pair = equal_pair(1.6);
    let (e, nu, rho, r, q_c) = (9.0e9_f64, 0.33_f64, 400.0_f64, 1.6_f64, 8.0e3_f64);
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let mass = 0.5 * rho * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let u_c = std::f64::consts::PI * q_c / (2.0 * e_star);
    let work = 8.0 / 15.0 * e_star * (0.5 * r).sqrt() * u_c.powf(2.5);
    let by_hand = (2.0 * work / mass).sqrt();
    let vy = law.yield_speed(&pair).unwrap();
    assert!((vy / by_hand - 1.0).abs() < 1e-12, "{vy} vs {by_hand}");
    let below = law.first_impact(&pair, 0.999 * by_hand);
    assert!((below - 1.0).abs() < 1e-12, "e(0.999 v_y) = {below}");
    assert!(law.first_impact(&pair, 1.01 * by_hand) < 1.0);
}
