//! Thornton's (1997) elastic–perfectly-plastic law for comparison.
//!
//! C. Thornton, "Coefficient of restitution for collinear collisions of elastic-perfectly plastic
//! spheres", J. Appl. Mech. 64, 383–386 (1997). Hertz until the contact pressure reaches the
//! limiting value `p_y`; then `F = F_y + π p_y R (δ − δ_y)`; unloading is Hertzian with an
//! enlarged radius `R_p` about a residual overlap `δ_p` (see `docs/theory.md` §6).
//!
//! [`ThorntonUnloading::LiggghtsThorntonNing`] selects instead the unloading branch of LIGGGHTS
//! 3.8 `normal_model thornton_ning` at zero surface energy (`docs/theory.md` §6.1), used by the
//! cross-code check of `docs/verification.md` §4.2.

use super::{pow3_2, pow5_2, NormalLaw, NormalModel, NormalResponse};
use crate::error::{non_negative, positive, Result};
use crate::material::ContactPair;
use crate::params::{Declared, LawDeclaration, LawKind, Param, Range};
use std::f64::consts::PI;

/// The unloading (and reloading) branch after yield. Loading is the same for both: Hertz up to
/// `δ_y`, then `F = F_y + π p_y R (δ − δ_y)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ThorntonUnloading {
    /// Thornton (1997): Hertzian with the enlarged radius `R_p = 4E* a*³/(3F*)` about the
    /// residual overlap `δ_p`, `F = (4/3) E* √R_p (δ − δ_p)^{3/2}` (`docs/theory.md` §6).
    #[default]
    Thornton1997,
    /// LIGGGHTS 3.8 `normal_model thornton_ning` with `surfaceEnergy 0`: the force decreases by
    /// `dF = 2 E* √(R δ) dδ` (original radius, total overlap), i.e. the Hertz curve shifted down,
    /// `F = (4/3) E* √R (δ^{3/2} − δ_p^{3/2})` with `δ_p^{3/2} = δ*^{3/2} − F*/((4/3)E*√R)`
    /// (`docs/theory.md` §6.1).
    LiggghtsThorntonNing,
}

/// Parameters of Thornton's law: the limiting contact pressure `p_y` (Pa) and the unloading
/// branch.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Thornton {
    yield_pressure: f64,
    #[cfg_attr(feature = "serde", serde(default))]
    unloading: ThorntonUnloading,
}

/// Thornton's parameter: the limiting contact pressure `p_y`.
impl Declared for Thornton {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "thornton",
        kind: LawKind::Normal,
        summary:
            "Thornton (1997) elastic-perfectly plastic: Hertz until the mean pressure reaches p_y",
        params: &[Param::new(
            "yield_pressure_pa",
            "p_y",
            "Pa",
            Range::POSITIVE,
            "limiting contact pressure; the yield overlap is R (π p_y / (2 E*))²",
        )
        .flag("yield-stress")
        .python("yield_stress")
        .lammps("yield_stress")],
    };

    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Self::new(values[0])
    }
}

impl Thornton {
    /// `p_y` (Pa, > 0), the limiting contact pressure (the "yield stress" of the model), with
    /// Thornton's (1997) unloading.
    pub fn new(yield_pressure: f64) -> Result<Self> {
        Ok(Self {
            yield_pressure: positive("yield_stress", yield_pressure)?,
            unloading: ThorntonUnloading::Thornton1997,
        })
    }

    /// The same law with another unloading branch.
    pub fn with_unloading(self, unloading: ThorntonUnloading) -> Self {
        Self { unloading, ..self }
    }

    /// `p_y` (Pa).
    pub fn yield_pressure(&self) -> f64 {
        self.yield_pressure
    }

    /// The unloading branch.
    pub fn unloading(&self) -> ThorntonUnloading {
        self.unloading
    }
}

impl NormalModel for Thornton {
    type Law = ThorntonLaw;
    fn bind(&self, pair: &ContactPair) -> Result<ThorntonLaw> {
        Ok(ThorntonLaw::new(pair, self.yield_pressure).with_unloading(self.unloading))
    }
}

/// History of one Thornton contact: the largest overlap and the unloading curve it defines.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ThorntonState {
    /// Largest overlap `δ*` (m).
    pub max_overlap: f64,
    /// `(4/3) E* √R_p` of the unloading curve (0 while elastic; `(4/3) E* √R` for
    /// [`ThorntonUnloading::LiggghtsThorntonNing`]).
    unloading_coefficient: f64,
    /// Residual overlap `δ_p` (m).
    residual_overlap: f64,
}

impl ThorntonState {
    /// The history of its parts: the largest overlap `δ*` (m), the unloading coefficient
    /// `(4/3) E* √R_p` (0 while elastic) and the residual overlap `δ_p` (m), as
    /// [`ThorntonState::parts`] gives them (a history kept outside this crate: a GPU's buffers).
    pub fn from_parts(max_overlap: f64, unloading_coefficient: f64, residual_overlap: f64) -> Self {
        Self {
            max_overlap,
            unloading_coefficient,
            residual_overlap,
        }
    }

    /// `[δ*, (4/3) E* √R_p, δ_p]`.
    pub fn parts(&self) -> [f64; 3] {
        [
            self.max_overlap,
            self.unloading_coefficient,
            self.residual_overlap,
        ]
    }
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
    unloading: ThorntonUnloading,
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
            unloading: ThorntonUnloading::Thornton1997,
        }
    }

    /// The same law with another unloading branch.
    pub fn with_unloading(self, unloading: ThorntonUnloading) -> Self {
        Self { unloading, ..self }
    }

    /// The unloading branch.
    pub fn unloading(&self) -> ThorntonUnloading {
        self.unloading
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
/// `e = 1` for `v ≤ v_y`. Refuses a ratio that is NaN, infinite or negative.
pub fn thornton_restitution(speed_over_yield_speed: f64) -> Result<f64> {
    if non_negative("speed_over_yield_speed", speed_over_yield_speed)? <= 1.0 {
        return Ok(1.0);
    }
    let r = 1.0 / speed_over_yield_speed;
    let r2 = r * r;
    let first = (6.0 * 3f64.sqrt() / 5.0 * (1.0 - r2 / 6.0)).sqrt();
    let second = (r / (r + 2.0 * (6.0 / 5.0 - r2 / 5.0).sqrt())).powf(0.25);
    Ok(first * second)
}

/// Restitution coefficient of the [`ThorntonUnloading::LiggghtsThorntonNing`] branch, closed form
/// (`docs/theory.md` §6.1). With `r = v/v_y`, `s = δ*/δ_y` from the energy balance
/// `(2/5) r² = 2/5 + (s − 1) + (3/4)(s − 1)²`, `f = F*/F_y = 1 + (3/2)(s − 1)` and
/// `q = δ_p/δ_y = (s^{3/2} − f)^{2/3}`:
/// `e² = [(2/5)(s^{5/2} − q^{5/2}) − q^{3/2}(s − q)] / ((2/5) r²)`; `e = 1` for `r ≤ 1`.
/// Refuses a ratio that is NaN, infinite or negative.
pub fn liggghts_thornton_ning_restitution(speed_over_yield_speed: f64) -> Result<f64> {
    let r = non_negative("speed_over_yield_speed", speed_over_yield_speed)?;
    if r <= 1.0 {
        return Ok(1.0);
    }
    let x = ((1.0 + 1.2 * (r * r - 1.0)).sqrt() - 1.0) / 1.5;
    let s = 1.0 + x;
    let f = 1.0 + 1.5 * x;
    let q = (pow3_2(s) - f).max(0.0).powf(2.0 / 3.0);
    let returned = 0.4 * (pow5_2(s) - pow5_2(q)) - pow3_2(q) * (s - q);
    Ok((returned / (0.4 * r * r)).sqrt())
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
            match self.unloading {
                ThorntonUnloading::Thornton1997 => {
                    // Unloading curve from (δ*, F*): contact radius a*² = R δ*
                    // (= (2F* + F_y)/(2π p_y)), R_p = 4 E* a*³ / (3 F*),
                    // δ_p = δ* − (3 F* / (4 E* √R_p))^{2/3}.
                    let r_p = 4.0 * self.effective_modulus * a * a * a / (3.0 * force);
                    let coefficient = 4.0 / 3.0 * self.effective_modulus * r_p.sqrt();
                    state.unloading_coefficient = coefficient;
                    state.residual_overlap = d - (force / coefficient).powf(2.0 / 3.0);
                }
                ThorntonUnloading::LiggghtsThorntonNing => {
                    // F = c (δ^{3/2} − δ_p^{3/2}), c = (4/3) E* √R, through (δ*, F*).
                    let c = self.force_coefficient;
                    state.unloading_coefficient = c;
                    state.residual_overlap = (pow3_2(d) - force / c).max(0.0).powf(2.0 / 3.0);
                }
            }
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
        if self.unloading == ThorntonUnloading::LiggghtsThorntonNing {
            // LIGGGHTS: a = √(R δ) of the total overlap, dF/dδ = 2 E* a.
            let a = (self.effective_radius * d).sqrt();
            return NormalResponse {
                force: c * (pow3_2(d) - pow3_2(state.residual_overlap)),
                contact_radius: a,
                stiffness: e2 * a,
            };
        }
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
        if self.unloading == ThorntonUnloading::LiggghtsThorntonNing {
            // ∫_{δ_p}^{δ} c (u^{3/2} − δ_p^{3/2}) du.
            let p = state.residual_overlap;
            if overlap <= p {
                return 0.0;
            }
            return state.unloading_coefficient
                * (0.4 * (pow5_2(overlap) - pow5_2(p)) - pow3_2(p) * (overlap - p));
        }
        0.4 * state.unloading_coefficient * pow5_2(x)
    }

    fn yield_overlap(&self) -> f64 {
        self.yield_overlap
    }
}
