//! Thornton's (1997) elastic–perfectly-plastic law for comparison.
//!
//! C. Thornton, "Coefficient of restitution for collinear collisions of elastic-perfectly plastic
//! spheres", J. Appl. Mech. 64, 383–386 (1997). Hertz until the contact pressure reaches the
//! limiting value `p_y`; then `F = F_y + π p_y R (δ − δ_y)`; unloading is Hertzian with an
//! enlarged radius `R_p` about a residual overlap `δ_p` (see `docs/theory.md` §6).

use super::{pow3_2, pow5_2, NormalLaw, NormalModel, NormalResponse};
use crate::error::{positive, Result};
use crate::material::ContactPair;
use std::f64::consts::PI;

/// Parameters of Thornton's law: the limiting contact pressure `p_y` (Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Thornton {
    yield_pressure: f64,
}

impl Thornton {
    /// `p_y` (Pa, > 0), the limiting contact pressure (the "yield stress" of the model).
    pub fn new(yield_pressure: f64) -> Result<Self> {
        Ok(Self {
            yield_pressure: positive("yield_stress", yield_pressure)?,
        })
    }

    /// `p_y` (Pa).
    pub fn yield_pressure(&self) -> f64 {
        self.yield_pressure
    }
}

impl NormalModel for Thornton {
    type Law = ThorntonLaw;
    fn bind(&self, pair: &ContactPair) -> Result<ThorntonLaw> {
        Ok(ThorntonLaw::new(pair, self.yield_pressure))
    }
}

/// History of one Thornton contact: the largest overlap and the unloading curve it defines.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ThorntonState {
    /// Largest overlap `δ*` (m).
    pub max_overlap: f64,
    /// `(4/3) E* √R_p` of the unloading curve (0 while elastic).
    unloading_coefficient: f64,
    /// Residual overlap `δ_p` (m).
    residual_overlap: f64,
}

/// Thornton's law bound to one pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThorntonLaw {
    effective_modulus: f64,
    effective_radius: f64,
    yield_pressure: f64,
    force_coefficient: f64,
    /// `δ_y = R (π p_y / (2 E*))²`.
    yield_overlap: f64,
    /// `F_y = (4/3) E* √R δ_y^{3/2}`.
    yield_force: f64,
}

impl ThorntonLaw {
    /// Bind `p_y` (Pa) to `pair`.
    pub fn new(pair: &ContactPair, yield_pressure: f64) -> Self {
        let e = pair.effective_modulus();
        let r = pair.effective_radius();
        let c = 4.0 / 3.0 * e * r.sqrt();
        let yield_overlap = r * (PI * yield_pressure / (2.0 * e)).powi(2);
        Self {
            effective_modulus: e,
            effective_radius: r,
            yield_pressure,
            force_coefficient: c,
            yield_overlap,
            yield_force: c * pow3_2(yield_overlap),
        }
    }

    /// Yield speed `v_y` (m/s) for reduced mass `mass`: the kinetic energy equal to the Hertz work
    /// up to `δ_y`.
    pub fn yield_speed(&self, mass: f64) -> f64 {
        (2.0 * 0.4 * self.force_coefficient * pow5_2(self.yield_overlap) / mass).sqrt()
    }

    /// Work of monotonic loading from 0 to `d` (J).
    pub fn loading_work(&self, d: f64) -> f64 {
        if d <= self.yield_overlap {
            return 0.4 * self.force_coefficient * pow5_2(d.max(0.0));
        }
        let x = d - self.yield_overlap;
        0.4 * self.force_coefficient * pow5_2(self.yield_overlap)
            + self.yield_force * x
            + 0.5 * PI * self.yield_pressure * self.effective_radius * x * x
    }

    fn loading_force(&self, d: f64) -> f64 {
        if d <= self.yield_overlap {
            self.force_coefficient * pow3_2(d)
        } else {
            self.yield_force
                + PI * self.yield_pressure * self.effective_radius * (d - self.yield_overlap)
        }
    }
}

/// Thornton's published restitution coefficient for `v_i > v_y` (eq. 31 of the 1997 paper):
/// `e = [6√3/5 (1 − (v_y/v)²/6)]^{1/2} · [(v_y/v) / (v_y/v + 2 √(6/5 − (v_y/v)²/5))]^{1/4}`;
/// `e = 1` for `v ≤ v_y`.
pub fn thornton_restitution(speed_over_yield_speed: f64) -> f64 {
    if speed_over_yield_speed <= 1.0 {
        return 1.0;
    }
    let r = 1.0 / speed_over_yield_speed;
    let r2 = r * r;
    let first = (6.0 * 3f64.sqrt() / 5.0 * (1.0 - r2 / 6.0)).sqrt();
    let second = (r / (r + 2.0 * (6.0 / 5.0 - r2 / 5.0).sqrt())).powf(0.25);
    first * second
}

impl NormalLaw for ThorntonLaw {
    type State = ThorntonState;

    fn update(&self, state: &mut ThorntonState, d: f64) -> NormalResponse {
        if d <= 0.0 {
            return NormalResponse::default();
        }
        let e2 = 2.0 * self.effective_modulus;
        if d >= state.max_overlap {
            state.max_overlap = d;
            let a = (self.effective_radius * d).sqrt();
            if d <= self.yield_overlap {
                return NormalResponse {
                    force: self.force_coefficient * pow3_2(d),
                    contact_radius: a,
                    stiffness: e2 * a,
                };
            }
            let force = self.loading_force(d);
            // Unloading curve from (δ*, F*): contact radius a*² = R δ* (= (2F* + F_y)/(2π p_y)),
            // R_p = 4 E* a*³ / (3 F*), δ_p = δ* − (3 F* / (4 E* √R_p))^{2/3}.
            let r_p = 4.0 * self.effective_modulus * a * a * a / (3.0 * force);
            let coefficient = 4.0 / 3.0 * self.effective_modulus * r_p.sqrt();
            state.unloading_coefficient = coefficient;
            state.residual_overlap = d - (force / coefficient).powf(2.0 / 3.0);
            return NormalResponse {
                force,
                contact_radius: a,
                stiffness: PI * self.yield_pressure * self.effective_radius,
            };
        }
        if state.max_overlap <= self.yield_overlap {
            let a = (self.effective_radius * d).sqrt();
            return NormalResponse {
                force: self.force_coefficient * pow3_2(d),
                contact_radius: a,
                stiffness: e2 * a,
            };
        }
        let x = d - state.residual_overlap;
        if x <= 0.0 {
            return NormalResponse::default();
        }
        let c = state.unloading_coefficient;
        // a = sqrt(R_p x) with R_p = (3c / (4E*))².
        let r_p = (0.75 * c / self.effective_modulus).powi(2);
        let a = (r_p * x).sqrt();
        NormalResponse {
            force: c * pow3_2(x),
            contact_radius: a,
            stiffness: e2 * a,
        }
    }

    fn max_overlap(&self, state: &ThorntonState) -> f64 {
        state.max_overlap
    }

    fn residual_overlap(&self, state: &ThorntonState) -> f64 {
        state.residual_overlap
    }

    fn dissipated_work(&self, state: &ThorntonState) -> f64 {
        (self.loading_work(state.max_overlap) - self.elastic_energy(state, state.max_overlap))
            .max(0.0)
    }

    fn elastic_energy(&self, state: &ThorntonState, overlap: f64) -> f64 {
        if state.max_overlap <= self.yield_overlap || overlap > state.max_overlap {
            if overlap > self.yield_overlap && overlap > state.max_overlap {
                let mut trial = *state;
                self.update(&mut trial, overlap);
                return self.elastic_energy(&trial, overlap);
            }
            return 0.4 * self.force_coefficient * pow5_2(overlap.max(0.0));
        }
        let x = (overlap - state.residual_overlap).max(0.0);
        0.4 * state.unloading_coefficient * pow5_2(x)
    }

    fn yield_overlap(&self) -> f64 {
        self.yield_overlap
    }
}
