//! Rolling resistance sub-models (optional; off by default). Kept separate from the normal and
//! tangential laws, with their own parameters and per-contact state, so that a coupling can add
//! them to any [`crate::model::ContactModel`].
//!
//! The elastic–plastic spring model ([`EpsdRolling`]) is the "type C" model of Ai, Chen, Rotter &
//! Ooi, Powder Technology 206 (2011) 269–282 (without its optional dashpot), written incrementally
//! like the Mindlin law: a rotational spring `k_r = 2.25 k_n μ_r² R²` on the relative rolling
//! rotation, capped at the limiting torque `μ_r R F_N`.
//!
//! Energy books (like the tangential laws): the spring stores `|M_r|² / (2 k_r)` (the energy it
//! returns on elastic unloading at its current stiffness), and the plastic rolling rotation
//! dissipates `|M_r| Δθ_plastic` at the cap. Both are reported per state
//! ([`RollingLaw::elastic_energy`], [`RollingLaw::dissipated_work`]) so that a coupling can add
//! them to its energy balance; the derivation is in docs/coupling.md ("Rolling resistance:
//! energy books").

use crate::error::{non_negative, Result};
use crate::material::ContactPair;
use crate::params::{Declared, LawDeclaration, LawKind, Param, Range};
use nalgebra::Vector3;

/// Input of one rolling-resistance update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingInput {
    /// Unit contact normal, pointing from body 2 towards body 1.
    pub normal: Vector3<f64>,
    /// Relative rotation of body 1 with respect to body 2 during this step (rad):
    /// `(ω₁ − ω₂) · dt`. Its normal part (twisting) is ignored.
    pub rotation_increment: Vector3<f64>,
    /// Total normal force of the contact (N, ≥ 0).
    pub normal_force: f64,
    /// Tangent normal stiffness `dF/dδ` of the normal law (N/m).
    pub normal_stiffness: f64,
}

/// What a rolling law returns.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RollingResponse {
    /// Rolling-resistance torque on body 1 (N·m); body 2 receives the opposite.
    pub torque: Vector3<f64>,
    /// Whether the torque is at its limit `μ_r R F_N` (the contact rolls).
    pub rolling: bool,
    /// Work dissipated during this update (J, ≥ 0).
    pub dissipated: f64,
    /// Elastic energy stored in the rolling spring after the update (J).
    pub elastic_energy: f64,
    /// Energy the spring gained in this update without work on the bodies (J; negative when it
    /// lost it): `|M|²/(2 k_r)` changing with the stiffness at a fixed torque
    /// ([`EpsdRollingState::stiffness_energy_change`]).
    pub stiffness_energy: f64,
}

/// A rolling-resistance law bound to one pair.
pub trait RollingLaw: Send + Sync {
    /// Per-contact history.
    type State: Clone + Default + std::fmt::Debug + Send + Sync;
    /// Advance the history by one step and return the torque.
    fn update(&self, state: &mut Self::State, input: &RollingInput) -> RollingResponse;
    /// Elastic energy stored in the rolling spring of `state` (J).
    fn elastic_energy(&self, state: &Self::State) -> f64;
    /// Work dissipated by rolling since the pair's history began (J, ≥ 0, never decreasing while
    /// the history lives: it survives an unloading that resets the spring).
    fn dissipated_work(&self, state: &Self::State) -> f64;
}

/// Material-level parameters of a rolling-resistance law.
pub trait RollingModel: Clone + Send + Sync {
    /// The law for one pair.
    type Law: RollingLaw;
    /// Bind to a pair.
    fn bind(&self, pair: &ContactPair) -> Result<Self::Law>;

    /// Whether the model can ever give a torque. One that cannot (no rolling resistance, or a
    /// coefficient of 0) lets a coupling run the contact without rolling history or rolling
    /// branch, as [`NoRolling`].
    fn resists(&self) -> bool {
        true
    }
}

/// No rolling resistance (the default).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoRolling;

impl RollingModel for NoRolling {
    type Law = NoRolling;
    fn bind(&self, _pair: &ContactPair) -> Result<NoRolling> {
        Ok(NoRolling)
    }
    fn resists(&self) -> bool {
        false
    }
}

impl RollingLaw for NoRolling {
    type State = ();
    #[inline]
    fn update(&self, _state: &mut (), _input: &RollingInput) -> RollingResponse {
        RollingResponse::default()
    }
    #[inline]
    fn elastic_energy(&self, _state: &()) -> f64 {
        0.0
    }
    #[inline]
    fn dissipated_work(&self, _state: &()) -> f64 {
        0.0
    }
}

/// Elastic–plastic spring rolling resistance with coefficient `μ_r` (dimensionless, ≥ 0):
/// `M_r ← M_r − k_r Δθ_r`, `|M_r| ≤ μ_r R F_N`, `k_r = 2.25 k_n μ_r² R²` (Ai et al. 2011, eqs. 13–16).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EpsdRolling {
    coefficient: f64,
}

impl EpsdRolling {
    /// `μ_r` (finite, ≥ 0).
    pub fn new(coefficient: f64) -> Result<Self> {
        Ok(Self {
            coefficient: non_negative("mu_r", coefficient)?,
        })
    }

    /// `μ_r`.
    pub fn coefficient(&self) -> f64 {
        self.coefficient
    }
}

/// [`EpsdRolling`] bound to a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EpsdRollingLaw {
    /// `μ_r R`: lever arm of the limiting torque (m).
    arm: f64,
    /// `2.25 μ_r² R²`: `k_r / k_n` (m²).
    stiffness_ratio: f64,
}

impl RollingModel for EpsdRolling {
    type Law = EpsdRollingLaw;
    fn bind(&self, pair: &ContactPair) -> Result<EpsdRollingLaw> {
        let arm = self.coefficient * pair.effective_radius();
        Ok(EpsdRollingLaw {
            arm,
            stiffness_ratio: 2.25 * arm * arm,
        })
    }
    /// Off at `μ_r = 0`: its limiting torque `μ_r R F_N` is then 0.
    fn resists(&self) -> bool {
        self.coefficient > 0.0
    }
}

/// History of [`EpsdRolling`]: the rolling torque stored in the spring (N·m, in the contact
/// plane), the spring's stiffness at the last update and the work dissipated so far.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EpsdRollingState {
    /// Stored torque on body 1 (N·m).
    pub torque: Vector3<f64>,
    /// Rolling stiffness `k_r` of the last update (N·m/rad); 0 when unloaded.
    pub stiffness: f64,
    /// Work dissipated by rolling so far (J).
    pub dissipated_work: f64,
}

impl EpsdRollingState {
    /// `|M_r|² / (2 k_r)`: the energy the spring returns on elastic unloading (J).
    #[inline]
    pub fn elastic_energy(&self) -> f64 {
        if self.stiffness > 0.0 {
            0.5 * self.torque.norm_squared() / self.stiffness
        } else {
            0.0
        }
    }
}

impl EpsdRollingState {
    /// Energy the spring gains without work when an update changes its stiffness from
    /// `previous_stiffness` to `stiffness` while it carries a torque of squared length
    /// `torque_len2` (J; negative when it loses energy): `½|M|² (1/k_r − 1/k_r,prev)`.
    ///
    /// The law is written in forces (`M ← M − k_r Δθ`), so the update keeps the torque while
    /// `k_r = 2.25 μ_r² R² k_n` follows the normal law's tangent stiffness; the stored energy
    /// `|M|²/(2 k_r)` then changes with no rotation. The rest of the update satisfies
    /// `|M'−k_rΔθ|²/(2k_r) − |M'|²/(2k_r) = −M'·Δθ + ½k_r|Δθ|²` (docs/theory.md, "Energy books
    /// of the incremental springs"). Pass the stiffness the update stored: 0 when it dropped the
    /// spring (the contact opened), where the law already booked what the spring held as
    /// dissipated, so this returns 0 then. [`RollingLaw::update`] reports it as
    /// [`RollingResponse::stiffness_energy`].
    pub fn stiffness_energy_change(
        torque_len2: f64,
        previous_stiffness: f64,
        stiffness: f64,
    ) -> f64 {
        if previous_stiffness > 0.0 && stiffness > 0.0 {
            0.5 * torque_len2 * (1.0 / stiffness - 1.0 / previous_stiffness)
        } else {
            0.0
        }
    }
}

impl RollingLaw for EpsdRollingLaw {
    type State = EpsdRollingState;

    #[inline(always)]
    fn update(&self, state: &mut EpsdRollingState, input: &RollingInput) -> RollingResponse {
        if input.normal_force <= 0.0 {
            // The contact opened: the spring is released without doing work on the bodies, so
            // what it stored is lost (booked as dissipated; at most (μ_r R F_N)²/(2 k_r) of the
            // last loaded step, since the cap follows F_N down).
            let released = state.elastic_energy();
            *state = EpsdRollingState {
                dissipated_work: state.dissipated_work + released,
                ..EpsdRollingState::default()
            };
            return RollingResponse {
                dissipated: released,
                ..RollingResponse::default()
            };
        }
        let n = input.normal;
        // Keep the stored torque in the current contact plane (the frame rotated, the spring did
        // not twist), at its length.
        let mut torque = state.torque;
        let old_len2 = torque.norm_squared();
        if old_len2 > 0.0 {
            torque -= n * n.dot(&torque);
            let new_len2 = torque.norm_squared();
            if new_len2 > 0.0 {
                torque *= (old_len2 / new_len2).sqrt();
            }
        }
        let rotation = input.rotation_increment - n * n.dot(&input.rotation_increment);
        let stiffness = self.stiffness_ratio * input.normal_stiffness;
        let stiffness_energy =
            EpsdRollingState::stiffness_energy_change(old_len2, state.stiffness, stiffness);
        let elastic_increment = -stiffness * rotation;
        torque += elastic_increment;
        let cap = self.arm * input.normal_force;
        let mut response = RollingResponse {
            stiffness_energy,
            ..RollingResponse::default()
        };
        // Squared lengths first: the square root is taken only at the limit (both sides ≥ 0).
        let magnitude2 = torque.norm_squared();
        if magnitude2 > cap * cap {
            let magnitude = magnitude2.sqrt();
            // At the limit: the excess rotation `Δθ_p = (|M_trial| − cap)/k_r` is plastic and
            // dissipates `cap · Δθ_p`.
            let excess = magnitude - cap;
            torque *= cap / magnitude;
            response.rolling = true;
            response.dissipated = if stiffness > 0.0 {
                cap * excess / stiffness
            } else {
                cap * rotation.norm()
            };
        }
        state.torque = torque;
        state.stiffness = stiffness;
        state.dissipated_work += response.dissipated;
        response.torque = torque;
        response.elastic_energy = state.elastic_energy();
        response
    }

    #[inline]
    fn elastic_energy(&self, state: &EpsdRollingState) -> f64 {
        state.elastic_energy()
    }

    #[inline]
    fn dissipated_work(&self, state: &EpsdRollingState) -> f64 {
        state.dissipated_work
    }
}

/// No rolling resistance: no parameters.
impl Declared for NoRolling {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "none",
        kind: LawKind::Rolling,
        summary: "no rolling resistance",
        params: &[],
    };
    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Ok(NoRolling)
    }
}

/// `μ_r`; 0 leaves the spring without torque, the scenes' default.
impl Declared for EpsdRolling {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "epsd",
        kind: LawKind::Rolling,
        summary: "elastic-plastic spring rolling resistance (Ai et al. 2011, eqs. 13-16)",
        params: &[Param::new(
            "rolling_friction",
            "μ_r",
            "1",
            Range::NON_NEGATIVE,
            "rolling-resistance coefficient: |M_r| ≤ μ_r R F_N, k_r = 2.25 k_n μ_r² R²; 0 is off",
        )
        .default(0.0)
        .flag("rolling")
        .python("rolling")
        .lammps("rolling")],
    };
    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Self::new(values[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(rotation: f64, normal_force: f64) -> RollingInput {
        RollingInput {
            normal: Vector3::z(),
            rotation_increment: Vector3::new(rotation, 0.0, 0.0),
            normal_force,
            normal_stiffness: 1.0e7,
        }
    }

    #[test]
    fn epsd_is_elastic_then_capped_at_mu_r_r_fn() {
        let pair = ContactPair::paper_fig2();
        let law = EpsdRolling::new(0.1).unwrap().bind(&pair).unwrap();
        let mut state = EpsdRollingState::default();
        let r = pair.effective_radius();
        let k_r = 2.25 * 1.0e7 * (0.1 * r) * (0.1 * r);
        // Small rotation: linear spring, opposing the rotation.
        let small = law.update(&mut state, &input(1e-6, 10.0));
        assert!((small.torque.x + k_r * 1e-6).abs() < 1e-12 * k_r);
        assert!(!small.rolling);
        // Large rotation: capped at μ_r R F_N.
        let big = law.update(&mut state, &input(1.0, 10.0));
        assert!((big.torque.norm() - 0.1 * r * 10.0).abs() < 1e-12);
        assert!(big.rolling && big.dissipated > 0.0);
        // Twisting about the normal is not resisted.
        let mut fresh = EpsdRollingState::default();
        let twist = law.update(
            &mut fresh,
            &RollingInput {
                rotation_increment: Vector3::new(0.0, 0.0, 1.0),
                ..input(0.0, 10.0)
            },
        );
        assert_eq!(twist.torque, Vector3::zeros());
        // Unloaded contact forgets the spring; what it stored is booked as dissipated.
        let stored = state.elastic_energy();
        let before = law.dissipated_work(&state);
        assert!(stored > 0.0);
        let apart = law.update(&mut state, &input(0.0, 0.0));
        assert_eq!(apart.torque, Vector3::zeros());
        assert_eq!(state.torque, Vector3::zeros());
        assert_eq!(apart.dissipated, stored);
        assert_eq!(law.dissipated_work(&state), before + stored);
        assert_eq!(law.elastic_energy(&state), 0.0);
    }

    /// A closed rolling cycle `0 → θ_a → −θ_a → θ_a` at constant `F_N` and `k_n`: the spring is
    /// elastic–perfectly plastic, so the `(θ, −M)` loop is a parallelogram of height `2 M_c` and
    /// width `2(θ_a − M_c/k_r)` at the cap: area `4 M_c (θ_a − M_c/k_r)`. The booked dissipation
    /// over the closed part equals it to round-off; the loop area integrated from the torque
    /// history (trapezoid rule) equals it up to the chord error of the two steps that cross
    /// onto the cap (each below `k_r Δθ² / 2`); every elastic step satisfies the work identity
    /// `−M̄ Δθ = ΔE` exactly (trapezoid of a linear spring).
    #[test]
    fn closed_cycle_dissipation_is_the_loop_area() {
        let pair = ContactPair::paper_fig2();
        let law = EpsdRolling::new(0.2).unwrap().bind(&pair).unwrap();
        let r = pair.effective_radius();
        let (force, k_n) = (10.0, 1.0e7);
        let k_r = 2.25 * k_n * (0.2 * r) * (0.2 * r);
        let cap = 0.2 * r * force;
        let theta_a = 5.0 * cap / k_r;
        let n = 1000;
        let d = theta_a / n as f64;
        let mut state = EpsdRollingState::default();
        let step = |state: &mut EpsdRollingState, dtheta: f64| {
            law.update(
                state,
                &RollingInput {
                    normal: Vector3::z(),
                    rotation_increment: Vector3::new(dtheta, 0.0, 0.0),
                    normal_force: force,
                    normal_stiffness: k_n,
                },
            )
        };
        for _ in 0..n {
            step(&mut state, d);
        }
        let w0 = state.dissipated_work;
        let e0 = state.elastic_energy();
        let mut area = 0.0;
        let mut m_old = state.torque.x;
        let mut booked = 0.0;
        for (count, sign) in [(2 * n, -1.0), (2 * n, 1.0)] {
            for _ in 0..count {
                let e_before = state.elastic_energy();
                let out = step(&mut state, sign * d);
                let work_in = -0.5 * (m_old + out.torque.x) * sign * d;
                if !out.rolling {
                    let de = out.elastic_energy - e_before;
                    assert!((work_in - de).abs() <= 1e-12 * e0, "{work_in} vs {de}");
                }
                area += work_in;
                booked += out.dissipated;
                m_old = out.torque.x;
            }
        }
        let exact = 4.0 * cap * (theta_a - cap / k_r);
        let dissipated = state.dissipated_work - w0;
        assert!((dissipated - booked).abs() <= 1e-12 * exact);
        assert!(
            (dissipated - exact).abs() <= 1e-9 * exact,
            "{dissipated} vs {exact}"
        );
        // Back where it started: the same stored energy, so all the work put in was dissipated.
        assert!((state.elastic_energy() - e0).abs() <= 1e-12 * e0);
        let chord = 2.0 * 0.5 * k_r * d * d;
        assert!(
            (area - dissipated).abs() <= chord,
            "loop area {area} vs dissipated {dissipated} (bound {chord})"
        );
        // The bound is not vacuous: it is a small fraction of the loop.
        assert!(chord < 1e-3 * exact);
    }
}
