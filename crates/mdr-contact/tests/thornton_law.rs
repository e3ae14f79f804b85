//! Thornton's (1997) law state by state against his equations, written out here: Hertz up to the
//! yield overlap `δ_y = R (π p_y/(2E*))²`, then `F = F_y + π p_y R (δ − δ_y)` (his eq. 22); on
//! unloading Hertz with the enlarged radius `R_p = 4E* a*³/(3F*)` about
//! `δ_p = δ* − (3F*/(4E*√R_p))^{2/3}` (eqs. 24–26), or, for LIGGGHTS' `thornton_ning`, the Hertz
//! curve of the original radius shifted down (docs/theory.md §6.1); the yield speed
//! `v_y = (π²/√40) (p_y⁵/(E*⁴ ρ))^{1/2} = 1.56 (p_y⁵/(E*⁴ ρ))^{1/2}` of a sphere on a rigid wall
//! (his eq. 27); the works as the integrals of these forces. Exact formulas: tolerance 1e-12.

use mdr_contact::normal::{NormalLaw, ThorntonUnloading};
use mdr_contact::prelude::*;
use std::f64::consts::PI;

const P_Y: f64 = 1.0e9;

fn pair() -> ContactPair {
    ContactPair::paper_fig2()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(a.abs()) + 1e-300
}

fn assert_close(what: &str, a: f64, b: f64) {
    assert!(close(a, b), "{what}: {a} vs {b} ({:e})", a / b - 1.0);
}

struct Written {
    e: f64,
    r: f64,
    d_y: f64,
    f_y: f64,
}

fn written() -> Written {
    let p = pair();
    let (e, r) = (p.effective_modulus(), p.effective_radius());
    let d_y = r * (PI * P_Y / (2.0 * e)).powi(2);
    Written {
        e,
        r,
        d_y,
        f_y: 4.0 / 3.0 * e * r.sqrt() * d_y.powf(1.5),
    }
}

fn hertz(w: &Written, d: f64) -> f64 {
    4.0 / 3.0 * w.e * w.r.sqrt() * d.powf(1.5)
}

fn loading(w: &Written, d: f64) -> f64 {
    w.f_y + PI * P_Y * w.r * (d - w.d_y)
}

#[test]
fn yield_overlap_and_speed_are_thorntons() {
    let w = written();
    let law = Thornton::new(P_Y).unwrap().bind(&pair()).unwrap();
    assert_close("δ_y", law.yield_overlap(), w.d_y);
    // A sphere on a rigid wall (the paper's pair is steel on a 10⁶-times stiffer wall, so
    // m is the sphere's and E* within 1e-6 of the pair's: use the pair's own E* and m).
    let m = pair().reduced_mass();
    let rho = m / (4.0 / 3.0 * PI * w.r.powi(3));
    let v_y = PI * PI / 40f64.sqrt() * (P_Y.powi(5) / (w.e.powi(4) * rho)).sqrt();
    assert_close("v_y", law.yield_speed(m), v_y);
    assert!((PI * PI / 40f64.sqrt() - 1.56).abs() < 1e-3);
}

#[test]
fn loading_is_hertz_then_linear() {
    let w = written();
    let law = Thornton::new(P_Y).unwrap().bind(&pair()).unwrap();
    let mut state = ThorntonState::default();
    for d in [0.3 * w.d_y, 0.99 * w.d_y, w.d_y] {
        let r = law.update(&mut state, d);
        assert_close("F elastic", r.force, hertz(&w, d));
        assert_close("a", r.contact_radius, (w.r * d).sqrt());
        assert_close("k", r.stiffness, 2.0 * w.e * (w.r * d).sqrt());
        assert_eq!(law.max_overlap(&state), d);
        assert_eq!(law.residual_overlap(&state), 0.0);
        assert_close("W", law.loading_work(d), 0.4 * hertz(&w, d) * d);
        assert_close("E", law.elastic_energy(&state, d), 0.4 * hertz(&w, d) * d);
        assert!(law.dissipated_work(&state) <= 1e-12 * law.loading_work(d));
    }
    // Unloading and reloading below the yield overlap stay on the Hertz curve.
    let r = law.update(&mut state, 0.5 * w.d_y);
    assert_close("F elastic unloading", r.force, hertz(&w, 0.5 * w.d_y));
    assert_close("k", r.stiffness, 2.0 * w.e * (w.r * 0.5 * w.d_y).sqrt());
    assert_eq!(law.max_overlap(&state), w.d_y);
    for d in [1.5 * w.d_y, 4.0 * w.d_y, 30.0 * w.d_y] {
        let r = law.update(&mut state, d);
        assert_close("F plastic", r.force, loading(&w, d));
        assert_close("a", r.contact_radius, (w.r * d).sqrt());
        assert_close("k plastic", r.stiffness, PI * P_Y * w.r);
        let x = d - w.d_y;
        let work = 0.4 * w.f_y * w.d_y + w.f_y * x + 0.5 * PI * P_Y * w.r * x * x;
        assert_close("W plastic", law.loading_work(d), work);
    }
    assert_eq!(law.update(&mut state, 0.0), NormalResponse::default());
    assert_eq!(law.update(&mut state, -1e-9), NormalResponse::default());
    assert_eq!(law.loading_work(-1e-9), 0.0);
}

#[test]
fn thornton_unloading_uses_the_enlarged_radius() {
    let w = written();
    let law = Thornton::new(P_Y).unwrap().bind(&pair()).unwrap();
    assert_eq!(law.unloading(), ThorntonUnloading::Thornton1997);
    let mut state = ThorntonState::default();
    let peak = 8.0 * w.d_y;
    law.update(&mut state, peak);
    let f_star = loading(&w, peak);
    let a_star = (w.r * peak).sqrt();
    let r_p = 4.0 * w.e * a_star.powi(3) / (3.0 * f_star);
    let c_p = 4.0 / 3.0 * w.e * r_p.sqrt();
    let d_p = peak - (f_star / c_p).powf(2.0 / 3.0);
    assert!(d_p > 0.0 && d_p < peak);
    assert_close("δ_p", law.residual_overlap(&state), d_p);
    for d in [0.999 * peak, 0.5 * (peak + d_p), d_p + 0.01 * (peak - d_p)] {
        let r = law.update(&mut state, d);
        let x = d - d_p;
        assert_close("F unloading", r.force, c_p * x.powf(1.5));
        assert_close("a unloading", r.contact_radius, (r_p * x).sqrt());
        assert_close("k unloading", r.stiffness, 2.0 * w.e * (r_p * x).sqrt());
        assert_close(
            "E unloading",
            law.elastic_energy(&state, d),
            0.4 * c_p * x.powf(2.5),
        );
        assert_eq!(law.max_overlap(&state), peak);
    }
    let stored = 0.4 * c_p * (peak - d_p).powf(2.5);
    let x = peak - w.d_y;
    let work = 0.4 * w.f_y * w.d_y + w.f_y * x + 0.5 * PI * P_Y * w.r * x * x;
    assert_close("dissipated", law.dissipated_work(&state), work - stored);
    assert_eq!(law.update(&mut state, 0.9 * d_p), NormalResponse::default());
    assert_eq!(law.update(&mut state, d_p), NormalResponse::default());
    assert_eq!(law.elastic_energy(&state, 0.5 * d_p), 0.0);
    // Past the old maximum the law loads plastically again and the energy it would return is
    // that of the new unloading curve.
    let deeper = 1.2 * peak;
    let mut trial = state;
    law.update(&mut trial, deeper);
    assert_close(
        "E beyond δ*",
        law.elastic_energy(&state, deeper),
        law.elastic_energy(&trial, deeper),
    );
    assert_eq!(state.max_overlap, peak);
}

#[test]
fn liggghts_unloading_is_the_shifted_hertz_curve() {
    let w = written();
    let model = Thornton::new(P_Y)
        .unwrap()
        .with_unloading(ThorntonUnloading::LiggghtsThorntonNing);
    assert_eq!(model.unloading(), ThorntonUnloading::LiggghtsThorntonNing);
    assert_eq!(model.yield_pressure(), P_Y);
    let law = model.bind(&pair()).unwrap();
    assert_eq!(law.unloading(), ThorntonUnloading::LiggghtsThorntonNing);
    let mut state = ThorntonState::default();
    let peak = 8.0 * w.d_y;
    let r = law.update(&mut state, peak);
    assert_close("F*", r.force, loading(&w, peak));
    let c = 4.0 / 3.0 * w.e * w.r.sqrt();
    let p32 = peak.powf(1.5) - loading(&w, peak) / c;
    let d_p = p32.powf(2.0 / 3.0);
    assert_close("δ_p", law.residual_overlap(&state), d_p);
    for d in [0.999 * peak, 0.5 * (peak + d_p), d_p + 0.01 * (peak - d_p)] {
        let r = law.update(&mut state, d);
        assert_close("F", r.force, c * (d.powf(1.5) - p32));
        assert_close("a", r.contact_radius, (w.r * d).sqrt());
        assert_close("k", r.stiffness, 2.0 * w.e * (w.r * d).sqrt());
        let stored = c * (0.4 * (d.powf(2.5) - d_p.powf(2.5)) - p32 * (d - d_p));
        // Differences of nearly equal powers near δ_p: round-off 2e-12 (measured).
        let e = law.elastic_energy(&state, d);
        assert!((e / stored - 1.0).abs() < 1e-10, "E: {e} vs {stored}");
    }
    assert_eq!(
        law.update(&mut state, 0.99 * d_p),
        NormalResponse::default()
    );
    assert_eq!(law.elastic_energy(&state, 0.99 * d_p), 0.0);
    // The same loading as Thornton's: the works up to δ* agree, the stored energies do not.
    let thornton = Thornton::new(P_Y).unwrap().bind(&pair()).unwrap();
    assert_close("W", law.loading_work(peak), thornton.loading_work(peak));
}

/// The stored energy is the integral of the unloading force (Simpson, 2000 intervals): checks
/// the force and the energy of both branches against each other.
#[test]
fn stored_energy_is_the_integral_of_the_unloading_force() {
    let w = written();
    for unloading in [
        ThorntonUnloading::Thornton1997,
        ThorntonUnloading::LiggghtsThorntonNing,
    ] {
        let law = Thornton::new(P_Y)
            .unwrap()
            .with_unloading(unloading)
            .bind(&pair())
            .unwrap();
        let mut state = ThorntonState::default();
        let peak = 5.0 * w.d_y;
        law.update(&mut state, peak);
        let d_p = law.residual_overlap(&state);
        let n = 2000;
        let h = (peak - d_p) / n as f64;
        let mut sum = 0.0;
        for i in 0..=n {
            let weight = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let mut s = state;
            sum += weight * law.update(&mut s, d_p + i as f64 * h).force;
        }
        let integral = sum * h / 3.0;
        let stored = law.elastic_energy(&state, peak);
        assert!(
            (integral / stored - 1.0).abs() < 1e-6,
            "{unloading:?}: {integral} vs {stored}"
        );
    }
}
