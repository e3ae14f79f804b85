//! Analytical references: Hertz's elastic impact and the rigid-body impulse theory of an oblique
//! impact in gross sliding (Maw, Barber & Fawcett 1976; Thornton et al. 2001). Derivations in
//! `docs/verification.md` §2.

use mdr_contact::ContactPair;

/// `∫₀¹ (1 − x^{5/2})^{−1/2} dx = (2/5) B(2/5, 1/2) = (2/5) Γ(2/5) Γ(1/2) / Γ(9/10)`.
/// Γ(2/5) = 2.218159543757688, Γ(1/2) = √π, Γ(9/10) = 1.068628702119319.
pub const HERTZ_TIME_INTEGRAL: f64 =
    0.4 * 2.218_159_543_757_688 * 1.772_453_850_905_516 / 1.068_628_702_119_319;

/// Hertz's elastic impact at normal approach speed `v` (m/s) of `pair`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzImpact {
    /// Largest overlap `δ_max = (15 m v² / (16 E* √R))^{2/5}` (m).
    pub max_overlap: f64,
    /// Largest force `(4/3) E* √R δ_max^{3/2}` (N), eq. (5).
    pub peak_force: f64,
    /// Contact time `2 (δ_max/v) ∫₀¹ (1 − x^{5/2})^{−1/2} dx ≈ 2.9432 δ_max/v` (s).
    pub contact_time: f64,
}

impl HertzImpact {
    /// Hertz's values for `pair` at `v`.
    pub fn new(pair: &ContactPair, v: f64) -> Self {
        let max_overlap = pair.hertz_max_overlap(v);
        Self {
            max_overlap,
            peak_force: hertz_force(pair, max_overlap),
            contact_time: 2.0 * HERTZ_TIME_INTEGRAL * max_overlap / v,
        }
    }
}

/// Hertz force `(4/3) E* √R δ^{3/2}` (N), eq. (5).
pub fn hertz_force(pair: &ContactPair, overlap: f64) -> f64 {
    4.0 / 3.0 * pair.effective_modulus() * pair.effective_radius().sqrt() * overlap.powf(1.5)
}

/// Normalised slip `ψ = v_slip / (μ v_n)` above which the contact slides during the whole
/// impact (rigid-body impulse theory, solid spheres): the slip velocity falls by
/// `3.5 μ (1+e) v_n` over the impact, so it keeps its sign while `ψ > 3.5 (1+e)`.
pub fn gross_sliding_threshold(normal_restitution: f64) -> f64 {
    3.5 * (1.0 + normal_restitution)
}

/// Tangential impulse (N s, along `+t`) of an impact that slides throughout:
/// `J_t = −sign(v_slip) μ J_n`, `J_n = m* (1+e) v_n`.
pub fn sliding_tangential_impulse(
    reduced_mass: f64,
    friction: f64,
    normal_restitution: f64,
    normal_speed: f64,
    slip_velocity: f64,
) -> f64 {
    -slip_velocity.signum() * friction * reduced_mass * (1.0 + normal_restitution) * normal_speed
}
