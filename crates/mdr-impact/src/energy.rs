//! The time-free energy route for the parabolic profile (docs/theory.md §4): the kinetic energy is
//! spent on plastic loading up to `d_max` ([`MdrLaw::impact`]), and `e_n² = W_unload / W_load`.
//! The contact time follows from the same energies by quadrature of `dt = dδ / v(δ)`.

use mdr_contact::normal::{MdrLaw, MdrState, NormalLaw};
use std::sync::OnceLock;

/// Result of the energy route for one head-on impact on a fresh contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EnergyRun {
    pub restitution: f64,
    pub max_overlap: f64,
    pub residual_overlap: f64,
    pub contact_time: f64,
    pub peak_force: f64,
}

/// Gauss–Legendre nodes and weights on `[0, 1]`.
const QUADRATURE_POINTS: usize = 32;

fn gauss_legendre() -> &'static [(f64, f64); QUADRATURE_POINTS] {
    static TABLE: OnceLock<[(f64, f64); QUADRATURE_POINTS]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let n = QUADRATURE_POINTS;
        let mut table = [(0.0, 0.0); QUADRATURE_POINTS];
        for (i, entry) in table.iter_mut().enumerate() {
            // Newton iteration on P_n from the Chebyshev-like first guess.
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut derivative = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                derivative = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / derivative;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
            *entry = (0.5 * (x + 1.0), 0.5 * weight);
        }
        table
    })
}

/// `∫₀¹ f(s) ds` by Gauss–Legendre.
fn integrate_unit(f: impl Fn(f64) -> f64) -> f64 {
    gauss_legendre().iter().map(|&(s, w)| w * f(s)).sum()
}

/// Energy route for a sphere of reduced mass `mass` (kg) at normal speed `speed` (m/s); the
/// law's error for a speed that is NaN, infinite or negative.
pub(crate) fn energy_route(law: &MdrLaw, mass: f64, speed: f64) -> mdr_contact::Result<EnergyRun> {
    let outcome = law.impact(&MdrState::default(), mass, speed)?;
    let d_max = outcome.max_overlap;
    let state = outcome.state;
    let residual = law.residual_overlap(&state);
    let peak_force = law.evaluate(&state, d_max).force;
    let v2 = speed * speed;
    // Loading, δ = D (1 − s²): v² = v0² − 2 W_load(δ)/m, finite integrand at the turning point.
    let loading = integrate_unit(|s| {
        let d = d_max * (1.0 - s * s);
        let v_squared = (v2 - 2.0 * law.loading_work(d) / mass).max(0.0);
        2.0 * d_max * s / v_squared.sqrt().max(f64::MIN_POSITIVE)
    });
    // Unloading, δ = D − (D − δ_r) s²: v² = 2 (W(D) − W(δ))/m with W the stored elastic energy.
    let stored = law.elastic_energy(&state, d_max);
    let span = d_max - residual;
    let unloading = integrate_unit(|s| {
        let d = d_max - span * s * s;
        let v_squared = (2.0 * (stored - law.elastic_energy(&state, d)) / mass).max(0.0);
        2.0 * span * s / v_squared.sqrt().max(f64::MIN_POSITIVE)
    });
    Ok(EnergyRun {
        restitution: outcome.restitution,
        max_overlap: d_max,
        residual_overlap: residual,
        contact_time: loading + unloading,
        peak_force,
    })
}
