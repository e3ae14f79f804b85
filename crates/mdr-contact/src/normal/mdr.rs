//! The MDR elasto-plastic law with nonlocal plasticity and linear hardening (Lyashenko & Popov
//! 2018), in its continuum closed form for the parabolic profile `g(x) = x²/R`
//! (`docs/theory.md` §4). O(1) time and O(1) state per contact.
//!
//! Every spring of the MDR bed (eqs. 9–13) sees the same indentation `d`, so the plastic state of
//! the whole bed is fixed by the largest indentation reached so far, `d_max`: the spring at `x`
//! has plastic offset `u_pl(x) = (1 − θ)(d_max − u_c − g(x))₊` (eq. 13), `θ = Θ/E*`,
//! `u_c = π q_c / (2 E*)` (eq. 11). Integrating the spring forces (eq. 6 with `Δx → 0`) gives the
//! branches implemented in [`MdrLaw::update`].

use super::{pow3_2, pow5_2, NormalLaw, NormalModel, NormalResponse};
use crate::error::{finite, in_closed_range, non_negative, positive, ContactError, Result};
use crate::material::ContactPair;
use crate::params::{Declared, LawDeclaration, LawKind, Param, Range};
use std::f64::consts::PI;

/// How the hardening modulus `Θ` (eq. 12) is given.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Hardening {
    /// `Θ/E*` in `[0, 1]`; the same ratio for every pair.
    Ratio(f64),
    /// `Θ` in Pa (per unit length, same units as `E*`), in `[0, E*]` of every pair it is bound to.
    Modulus(f64),
}

/// Parameters of the MDR elasto-plastic law (a [`NormalModel`]): the critical linear force
/// density `q_c` (N/m, eq. 7) and the hardening modulus `Θ` (eq. 12).
///
/// ```
/// use mdr_contact::prelude::*;
/// let pair = ContactPair::paper_fig2();
/// let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
/// // Plasticity starts at u_c = π q_c / (2 E*), eq. (11).
/// let u_c = std::f64::consts::PI * 3.8e5 / (2.0 * pair.effective_modulus());
/// assert!((law.yield_overlap() - u_c).abs() < 1e-18);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MdrElastoPlastic {
    critical_line_load: f64,
    hardening: Hardening,
}

/// The MDR law's parameters: `q_c` (eq. 7) and `Θ/E*` (eq. 12).
impl Declared for MdrElastoPlastic {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "mdr",
        kind: LawKind::Normal,
        summary: "MDR elasto-plastic with nonlocal plasticity and linear hardening (Lyashenko & Popov 2018), closed form",
        params: &[
            Param::new(
                "critical_line_load_n_per_m",
                "q_c",
                "N/m",
                Range::NON_NEGATIVE,
                "critical line load: plasticity starts at u_c = π q_c / (2 E*), eqs. (7), (11)",
            )
            .flag("qc")
            .python("qc")
            .lammps("qc"),
            Param::new(
                "hardening_ratio",
                "Θ/E*",
                "1",
                Range::UNIT_INTERVAL,
                "hardening modulus over the pair's E*: 0 ideally plastic, 1 elastic, eq. (12)",
            )
            .flag("theta-ratio")
            .python("theta_ratio")
            .lammps("theta"),
        ],
    };

    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Self::new(values[0], values[1])
    }
}

impl MdrElastoPlastic {
    /// `q_c` (N/m, finite, ≥ 0) and `Θ/E*` (in `[0, 1]`).
    pub fn new(critical_line_load: f64, hardening_ratio: f64) -> Result<Self> {
        non_negative("q_c", critical_line_load)?;
        in_closed_range("theta_ratio", hardening_ratio, 0.0, 1.0, "[0, 1]")?;
        Ok(Self {
            critical_line_load,
            hardening: Hardening::Ratio(hardening_ratio),
        })
    }

    /// `q_c` (N/m, finite, ≥ 0) and an absolute hardening modulus `Θ` (Pa, finite, ≥ 0; checked
    /// against `[0, E*]` when bound to a pair).
    pub fn with_hardening_modulus(critical_line_load: f64, hardening_modulus: f64) -> Result<Self> {
        non_negative("q_c", critical_line_load)?;
        non_negative("theta", hardening_modulus)?;
        Ok(Self {
            critical_line_load,
            hardening: Hardening::Modulus(hardening_modulus),
        })
    }

    /// The purely elastic limit `q_c → ∞` (Hertz).
    pub fn elastic() -> Self {
        Self {
            critical_line_load: f64::INFINITY,
            hardening: Hardening::Ratio(1.0),
        }
    }

    /// The paper's Fig. 2 values: `q_c = 3.8·10⁵ N/m`, `Θ = 0.37 E*`.
    pub fn paper() -> Self {
        Self {
            critical_line_load: 3.8e5,
            hardening: Hardening::Ratio(0.37),
        }
    }

    /// `q_c` (N/m); infinite for [`MdrElastoPlastic::elastic`].
    pub fn critical_line_load(&self) -> f64 {
        self.critical_line_load
    }

    /// The hardening as given.
    pub fn hardening(&self) -> Hardening {
        self.hardening
    }
}

impl NormalModel for MdrElastoPlastic {
    type Law = MdrLaw;
    fn bind(&self, pair: &ContactPair) -> Result<MdrLaw> {
        let e = pair.effective_modulus();
        let ratio = match self.hardening {
            Hardening::Ratio(r) => r,
            Hardening::Modulus(theta) => {
                finite("theta", theta)?;
                if !(0.0..=e).contains(&theta) {
                    return Err(ContactError::OutOfRange {
                        name: "theta",
                        value: theta,
                        range: "[0, E*] (E* of the pair)",
                    });
                }
                theta / e
            }
        };
        Ok(MdrLaw::from_parts(
            e,
            pair.effective_radius(),
            // eq. (11): u_crit = f_c / (E* Δx) = π q_c / (2 E*)
            PI * self.critical_line_load / (2.0 * e),
            ratio,
        ))
    }
}

/// History of one MDR contact: the largest indentation reached so far (m). Everything else
/// (plastic offsets of all springs, residual depth) follows from it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MdrState {
    /// Largest overlap so far, `d_max` (m).
    pub max_overlap: f64,
}

/// The part of the crater that touches at the present overlap (the branches of
/// [`MdrLaw::update`], docs/theory.md §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Touching {
    /// `d ≥ s = d_max − u_c`: the sphere's profile out to `√(R d)` (loading, or unloading
    /// above `s`).
    Sphere,
    /// `(1 − θ)s < d < s`: only the flattened plastic zone, out to `√(R (d − (1 − θ)s)/θ)`.
    Flattened,
    /// No spring: apart (`d ≤ 0`) or inside the residual crater.
    Nothing,
}

/// What a law built on the MDR law does with its response ([`MdrLaw::touching`]).
pub(crate) trait AfterTouching {
    type Output;
    /// Called in each branch of the MDR law with that branch's `part` and `d_max` after the
    /// update; implementations are always inlined, so that their code for each part is laid
    /// out in its branch.
    fn after(self, response: NormalResponse, part: Touching, max_overlap: f64) -> Self::Output;
}

/// The MDR law's own response.
struct TouchingResponse;

impl AfterTouching for TouchingResponse {
    type Output = NormalResponse;
    #[inline(always)]
    fn after(self, response: NormalResponse, _: Touching, _: f64) -> NormalResponse {
        response
    }
}

/// Outcome of one impact evaluated with the time-free energy route (docs/theory.md §4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyRouteImpact {
    /// Coefficient of restitution `e_n = sqrt(W_returned / W_in)`, eq. (14).
    pub restitution: f64,
    /// History after the impact.
    pub state: MdrState,
    /// Largest overlap during this impact (m).
    pub max_overlap: f64,
}

/// The MDR elasto-plastic closed-form law bound to one pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MdrLaw {
    effective_modulus: f64,
    effective_radius: f64,
    /// `√R`, so that the contact radius `√(R d)` reuses `√d`.
    sqrt_radius: f64,
    /// `2 E* √R`: the tangent stiffness `2 E* a` is `stiffness_coefficient · √d`.
    stiffness_coefficient: f64,
    /// `√(R/θ)`: radius factor of the flattened residual profile.
    flat_radius_sqrt: f64,
    /// `(4/3) E* √(R/θ)`.
    flat_force_coefficient: f64,
    /// `(4/3) E* √R`: `F_H(d) = force_coefficient · d^{3/2}`.
    force_coefficient: f64,
    /// `u_c = π q_c / (2 E*)`, eq. (11).
    yield_displacement: f64,
    /// `θ = Θ / E*`.
    hardening_ratio: f64,
    /// `1 − θ`: fraction of the excess indentation that stays as plastic offset, eq. (13).
    plastic_fraction: f64,
    /// `θ^{-1/2}`: the flattened residual profile has radius `R/θ`.
    flat_factor: f64,
}

impl MdrLaw {
    /// Build from `E*` (Pa), `R` (m), `u_c` (m) and `θ = Θ/E*` directly.
    pub fn from_parts(
        effective_modulus: f64,
        effective_radius: f64,
        yield_displacement: f64,
        hardening_ratio: f64,
    ) -> Self {
        // θ^{-1/2}; with θ = 0 the flattened branch never occurs (its force would be 0·∞).
        let flat_factor = if hardening_ratio > 0.0 {
            1.0 / hardening_ratio.sqrt()
        } else {
            f64::INFINITY
        };
        Self {
            effective_modulus,
            effective_radius,
            sqrt_radius: effective_radius.sqrt(),
            stiffness_coefficient: 2.0 * effective_modulus * effective_radius.sqrt(),
            flat_radius_sqrt: effective_radius.sqrt() * flat_factor,
            flat_force_coefficient: 4.0 / 3.0
                * effective_modulus
                * effective_radius.sqrt()
                * flat_factor,
            force_coefficient: 4.0 / 3.0 * effective_modulus * effective_radius.sqrt(),
            yield_displacement,
            hardening_ratio,
            plastic_fraction: 1.0 - hardening_ratio,
            flat_factor,
        }
    }

    /// `θ = Θ/E*`.
    pub fn hardening_ratio(&self) -> f64 {
        self.hardening_ratio
    }

    /// `E*` (Pa).
    pub fn effective_modulus(&self) -> f64 {
        self.effective_modulus
    }

    /// `R` (m).
    pub fn effective_radius(&self) -> f64 {
        self.effective_radius
    }

    /// Residual depth `(1 − θ)(d_max − u_c)₊` after unloading from `max_overlap` (m).
    #[inline]
    pub fn residual_depth(&self, max_overlap: f64) -> f64 {
        self.plastic_fraction * (max_overlap - self.yield_displacement).max(0.0)
    }

    /// Work done on the contact when loading monotonically from 0 to `d` (J):
    /// `(8/15) E* √R [d^{5/2} − (1 − θ)(d − u_c)₊^{5/2}]`.
    pub fn loading_work(&self, d: f64) -> f64 {
        if d <= 0.0 {
            return 0.0;
        }
        let s = (d - self.yield_displacement).max(0.0);
        0.4 * self.force_coefficient * (pow5_2(d) - self.plastic_fraction * pow5_2(s))
    }

    /// Elastic energy stored at overlap `d` on the unloading branch from `max_overlap` (J).
    pub fn stored_energy(&self, max_overlap: f64, d: f64) -> f64 {
        let s = max_overlap - self.yield_displacement;
        if s <= 0.0 {
            return if d > 0.0 {
                0.4 * self.force_coefficient * pow5_2(d)
            } else {
                0.0
            };
        }
        let residual = self.plastic_fraction * s;
        if d <= residual {
            return 0.0;
        }
        // Flattened part, residual < d' < min(d, s): Hertz with radius R/θ.
        let flat = if self.hardening_ratio > 0.0 {
            0.4 * self.force_coefficient * self.flat_factor * pow5_2(d.min(s) - residual)
        } else {
            0.0
        };
        // Outer part, s < d' < d: F = F_H(d') − (1 − θ) F_H(s).
        let outer = if d > s {
            0.4 * self.force_coefficient * (pow5_2(d) - pow5_2(s))
                - self.plastic_fraction * self.force_coefficient * pow3_2(s) * (d - s)
        } else {
            0.0
        };
        flat + outer
    }

    /// Speed (m/s) at which a body of mass `mass` (kg) coming from far first indents to `u_c`:
    /// `m v_y²/2 = (8/15) E* √R u_c^{5/2}` (docs/theory.md §4). Below it the impact is elastic.
    pub fn yield_speed(&self, mass: f64) -> f64 {
        (2.0 * self.loading_work(self.yield_displacement) / mass).sqrt()
    }

    /// One impact at normal approach speed `speed` (m/s) of reduced mass `mass` (kg) on a contact
    /// with history `state`, without time stepping: the kinetic energy is spent first on the
    /// elastic reloading branch up to the old `d_max`, then on plastic loading; the restitution is
    /// `e² = W_returned / W_in` (docs/theory.md §4). A re-impact whose energy fits within the old branch
    /// is elastic (`e = 1`, as at `speed = 0`).
    ///
    /// Refuses (naming the parameter) a `speed` that is NaN, infinite or negative and a `mass`
    /// that is not finite and positive: the energy route has no answer for them.
    ///
    /// ```
    /// use mdr_contact::prelude::*;
    /// use mdr_contact::normal::MdrState;
    /// let pair = ContactPair::paper_fig2();
    /// let law = MdrElastoPlastic::paper().bind(&pair).unwrap();
    /// let m = pair.reduced_mass();
    /// assert!(law.impact(&MdrState::default(), m, 1.0).unwrap().restitution < 1.0);
    /// assert!(law.impact(&MdrState::default(), m, f64::NAN).is_err());
    /// ```
    pub fn impact(&self, state: &MdrState, mass: f64, speed: f64) -> Result<EnergyRouteImpact> {
        non_negative("speed", speed)?;
        positive("mass", mass)?;
        let kinetic = 0.5 * mass * speed * speed;
        let old_max = state.max_overlap;
        let capacity = self.stored_energy(old_max, old_max);
        if kinetic <= capacity || kinetic <= 0.0 {
            // Elastic re-impact on the old branch; the history does not change.
            let mut lo = self.residual_depth(old_max);
            let mut hi = old_max;
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if self.stored_energy(old_max, mid) < kinetic {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Ok(EnergyRouteImpact {
                restitution: 1.0,
                state: *state,
                max_overlap: 0.5 * (lo + hi),
            });
        }
        // Past the old maximum: W_load(D) − W_load(d_max,old) = kinetic − capacity.
        let target = kinetic - capacity + self.loading_work(old_max);
        let d = self.solve_loading_work(target, old_max);
        let returned = self.stored_energy(d, d);
        Ok(EnergyRouteImpact {
            restitution: (returned / kinetic).sqrt().min(1.0),
            state: MdrState { max_overlap: d },
            max_overlap: d,
        })
    }

    /// `D ≥ lower` with `loading_work(D) = target`. `loading_work` is increasing and convex, so
    /// Newton steps from above converge monotonically; bisection guards the bracket.
    fn solve_loading_work(&self, target: f64, lower: f64) -> f64 {
        // Hertz overlap for the same work is a lower bound (plastic loading is softer).
        let hertz = (target / (0.4 * self.force_coefficient)).powf(0.4);
        let mut lo = lower.max(hertz);
        if self.loading_work(lo) >= target {
            return lo;
        }
        // Grow geometrically until the work exceeds the target (it grows at least like θ d^{5/2}
        // and like u_c d^{3/2}).
        let mut hi = 2.0 * lo;
        while self.loading_work(hi) < target {
            lo = hi;
            hi *= 2.0;
        }
        let mut d = hi;
        for _ in 0..60 {
            let w = self.loading_work(d) - target;
            if w.abs() <= 1e-15 * target {
                break;
            }
            if w > 0.0 {
                hi = d;
            } else {
                lo = d;
            }
            let f = self.loading_force(d);
            let newton = d - w / f;
            d = if newton > lo && newton < hi && f > 0.0 {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if hi - lo <= 1e-15 * hi {
                break;
            }
        }
        d
    }

    /// [`NormalLaw::update`], handing its response and the part of the crater that touches to
    /// `then` (for the laws built on this one: each branch calls it with its own constant
    /// part, so the caller's code for each part is laid out in that branch). Loading
    /// (`d = d_max`) and unloading with `d ≥ s` share one formula,
    /// `F = F_H(d) − (1 − θ) F_H(s₊)` with `s = d_max − u_c` (docs/theory.md §4), so the common
    /// case is one branch and two square roots (`√d`, `√s`); the contact radius reuses `√d`
    /// through the precomputed `√R`.
    #[inline(always)]
    pub(crate) fn touching<R>(
        &self,
        state: &mut MdrState,
        d: f64,
        then: impl AfterTouching<Output = R>,
    ) -> R {
        if d <= 0.0 {
            return then.after(
                NormalResponse::default(),
                Touching::Nothing,
                state.max_overlap,
            );
        }
        let loading = d >= state.max_overlap;
        // Stored unconditionally: in a vibrating bed loading and unloading alternate at random,
        // and a conditional store would be a mispredicted branch.
        state.max_overlap = state.max_overlap.max(d);
        let s = state.max_overlap - self.yield_displacement;
        if d >= s {
            // Elastic or plastic loading (eqs. 5, 10–13 integrated), or elastic unloading and
            // reloading while every spring with g < d is in contact.
            let sqrt_d = d.sqrt();
            let s = s.max(0.0);
            let sqrt_s = s.sqrt();
            let a = self.sqrt_radius * sqrt_d;
            // Tangent stiffness: 2E*√R(√d − (1 − θ)√s) on plastic loading, 2E* a otherwise.
            let softening = if loading {
                self.plastic_fraction * sqrt_s
            } else {
                0.0
            };
            return then.after(
                NormalResponse {
                    force: self.force_coefficient
                        * (d * sqrt_d - self.plastic_fraction * s * sqrt_s),
                    contact_radius: a,
                    stiffness: self.stiffness_coefficient * (sqrt_d - softening),
                },
                Touching::Sphere,
                state.max_overlap,
            );
        }
        let excess = d - self.plastic_fraction * s;
        if excess <= 0.0 {
            // Inside the residual crater: no contact.
            return then.after(
                NormalResponse::default(),
                Touching::Nothing,
                state.max_overlap,
            );
        }
        // Only the flattened plastic zone touches: Hertz with radius R/θ about the residual depth.
        let sqrt_excess = excess.sqrt();
        let a = self.flat_radius_sqrt * sqrt_excess;
        then.after(
            NormalResponse {
                force: self.flat_force_coefficient * excess * sqrt_excess,
                contact_radius: a,
                stiffness: 2.0 * self.effective_modulus * a,
            },
            Touching::Flattened,
            state.max_overlap,
        )
    }

    /// Force on the loading branch, `d = d_max` (docs/theory.md §4).
    #[inline]
    fn loading_force(&self, d: f64) -> f64 {
        let s = d - self.yield_displacement;
        if s <= 0.0 {
            self.force_coefficient * pow3_2(d)
        } else {
            self.force_coefficient * (pow3_2(d) - self.plastic_fraction * pow3_2(s))
        }
    }
}

impl NormalLaw for MdrLaw {
    type State = MdrState;

    /// The hot path of many-particle runs: `MdrLaw::touching`.
    #[inline]
    fn update(&self, state: &mut MdrState, d: f64) -> NormalResponse {
        self.touching(state, d, TouchingResponse)
    }

    fn max_overlap(&self, state: &MdrState) -> f64 {
        state.max_overlap
    }

    fn residual_overlap(&self, state: &MdrState) -> f64 {
        self.residual_depth(state.max_overlap)
    }

    fn dissipated_work(&self, state: &MdrState) -> f64 {
        (self.loading_work(state.max_overlap)
            - self.stored_energy(state.max_overlap, state.max_overlap))
        .max(0.0)
    }

    fn elastic_energy(&self, state: &MdrState, overlap: f64) -> f64 {
        self.stored_energy(state.max_overlap.max(overlap), overlap)
    }

    fn yield_overlap(&self) -> f64 {
        self.yield_displacement
    }
}
