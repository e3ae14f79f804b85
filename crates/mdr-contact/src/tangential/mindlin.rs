//! The O(1) incremental Mindlin law with a Coulomb cap (docs/theory.md §5; LAMMPS `tangential
//! mindlin/rescale`): one 3D tangential displacement per contact, kept in the contact plane.

use super::{TangentialInput, TangentialLaw, TangentialModel, TangentialResponse};
use crate::error::{non_negative, Result};
use crate::material::ContactPair;
use crate::params::{Declared, LawDeclaration, LawKind, Param, Range};
use nalgebra::Vector3;

/// Parameters: the Coulomb friction coefficient `μ`, and whether the stored displacement is
/// rescaled by `a/a_prev` when the contact radius shrinks.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Mindlin {
    friction_coefficient: f64,
    rescale_on_unloading: bool,
    form: MindlinForm,
}

/// How the stored tangential state turns into a force when the contact radius changes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum MindlinForm {
    /// `F_t = −k_t(a) ξ`: the whole stored displacement is carried by the current stiffness, so a
    /// growing contact stiffens the old displacement too (LAMMPS `tangential mindlin`).
    #[default]
    Displacement,
    /// `ΔF_t = −k_t(a) Δξ`: springs entering a growing contact start unstretched, exactly as in the
    /// MDR spring bed while every spring sticks (LAMMPS `tangential mindlin_force`). The stored
    /// displacement is then the equivalent `ξ = −F_t / k_t(a)`.
    Force,
}

impl Mindlin {
    /// `μ` (finite, ≥ 0). The displacement is rescaled when the contact shrinks (as LAMMPS
    /// `mindlin/rescale`); turn it off with [`Mindlin::rescale_on_unloading`].
    pub fn new(friction_coefficient: f64) -> Result<Self> {
        Ok(Self {
            friction_coefficient: non_negative("mu", friction_coefficient)?,
            rescale_on_unloading: true,
            form: MindlinForm::Displacement,
        })
    }

    /// Choose the [`MindlinForm`] (default [`MindlinForm::Displacement`]).
    pub fn form(mut self, form: MindlinForm) -> Self {
        self.form = form;
        self
    }

    /// Whether to rescale the stored displacement by `a/a_prev` when the contact shrinks, so that
    /// unloading cannot release more tangential energy than was stored.
    pub fn rescale_on_unloading(mut self, yes: bool) -> Self {
        self.rescale_on_unloading = yes;
        self
    }

    /// `μ`.
    pub fn friction_coefficient(&self) -> f64 {
        self.friction_coefficient
    }
}

impl TangentialModel for Mindlin {
    type Law = MindlinLaw;
    fn bind(&self, pair: &ContactPair) -> Result<MindlinLaw> {
        Ok(MindlinLaw {
            effective_shear_modulus: pair.effective_shear_modulus(),
            friction_coefficient: self.friction_coefficient,
            rescale_on_unloading: self.rescale_on_unloading,
            form: self.form,
        })
    }
}

/// History: the elastic tangential displacement `ξ` (m, in the contact plane) and the contact
/// radius at the previous step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MindlinState {
    /// Stored elastic tangential displacement `ξ` (m).
    pub displacement: Vector3<f64>,
    /// Contact radius at the previous update (m).
    pub contact_radius: f64,
}

/// The Mindlin law of one pair: `F_t = −k_t ξ`, `k_t = 2 G* a`, `|F_t| ≤ μ F_N`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MindlinLaw {
    effective_shear_modulus: f64,
    friction_coefficient: f64,
    rescale_on_unloading: bool,
    form: MindlinForm,
}

impl MindlinLaw {
    /// Tangential stiffness `k_t = 2 G* a` (N/m) at contact radius `a`.
    #[inline]
    pub fn stiffness(&self, contact_radius: f64) -> f64 {
        2.0 * self.effective_shear_modulus * contact_radius
    }
}

impl MindlinLaw {
    /// The factor `r_num / r_den` by which an update at contact radius `a` scales the stored
    /// displacement of a contact whose previous radius was `previous_radius` (see
    /// [`MindlinForm`] and [`Mindlin::rescale_on_unloading`]); `(1, 1)` when it is kept.
    #[inline(always)]
    fn rescale(&self, previous_radius: f64, a: f64) -> (f64, f64) {
        let shrinking_rescaled = self.rescale_on_unloading && a < previous_radius;
        match self.form {
            // F = k(a) ξ: rescaling ξ by a/a_prev on unloading keeps the released energy
            // below the stored one.
            MindlinForm::Displacement if previous_radius > 0.0 && shrinking_rescaled => {
                (a, previous_radius)
            }
            // Keep the force k(a_prev) ξ (scaled by a/a_prev on unloading when rescaling)
            // and store it as the equivalent displacement at the new stiffness.
            MindlinForm::Force if previous_radius > 0.0 && !shrinking_rescaled => {
                (previous_radius, a)
            }
            _ => (1.0, 1.0),
        }
    }

    /// Energy the spring gains without work when an update at contact radius `contact_radius`
    /// starts from a stored displacement of squared length `displacement_len2` held at
    /// `previous_radius` (J; negative when it loses energy): `½ k_t(a) |ξ'|² − ½ k_t(a_prev) |ξ|²`,
    /// where `ξ'` is the displacement the update carries over (rotated into the new contact
    /// plane at its length, times the radius rescale of [`MindlinForm`]). The update then adds
    /// the displacement increment to `ξ'` at the stiffness `k_t(a)`; the work identity of that
    /// part is `½k|ξ'+Δu|² − ½k|ξ'|² = −F'·Δu + ½k|Δu|²` (`F' = −k ξ'`). A contact that opens
    /// (`a ≤ 0`) releases the whole `½ k_t(a_prev) |ξ|²`: the update drops the spring.
    /// [`TangentialLaw::update`] reports the same quantity as
    /// [`TangentialResponse::stiffness_energy`] (docs/theory.md, "Energy books of the incremental
    /// springs"); this form takes the state before an update, for books kept outside the law.
    #[inline]
    pub fn stiffness_energy_change(
        &self,
        displacement_len2: f64,
        previous_radius: f64,
        contact_radius: f64,
    ) -> f64 {
        let before = 0.5 * self.stiffness(previous_radius) * displacement_len2;
        if contact_radius <= 0.0 {
            return -before;
        }
        if displacement_len2 <= 0.0 {
            return 0.0;
        }
        let (r_num, r_den) = self.rescale(previous_radius, contact_radius);
        self.carried_energy_change(
            displacement_len2,
            previous_radius,
            self.stiffness(contact_radius),
            r_num / r_den,
        )
    }

    /// `½ k |ξ|² ratio² − ½ k_t(a_prev) |ξ|²`: [`MindlinLaw::stiffness_energy_change`] of a spring
    /// in contact, with the new stiffness `k` and the radius rescale `ratio` already at hand
    /// (the update has both).
    #[inline(always)]
    fn carried_energy_change(
        &self,
        displacement_len2: f64,
        previous_radius: f64,
        k: f64,
        ratio: f64,
    ) -> f64 {
        let before = 0.5 * self.stiffness(previous_radius) * displacement_len2;
        0.5 * k * displacement_len2 * ratio * ratio - before
    }
}

impl TangentialLaw for MindlinLaw {
    type State = MindlinState;

    /// One step of docs/theory.md §5. The arithmetic is arranged for the per-contact hot loop (the
    /// results are those of the textbook sequence to round-off):
    /// - the plane projection's length factor `√(|ξ|²/|ξ_⊥|²)` needs only the normal and the
    ///   stored ξ, so it does not wait for the normal law; for the small tilts of a dense bed it
    ///   is a series (one division, no square root), and the radius rescale `r_num/r_den`
    ///   (`a/a_prev`, `a_prev/a` or 1, see [`MindlinForm`]) multiplies it only when it is not 1;
    /// - the Coulomb test compares squares, `k² |ξ|² > (μ F_N)²`, so the stick branch (the common
    ///   one) takes no square root after the projection; `|ξ|` is formed only on gross slip;
    /// - the stored elastic energy reuses `|ξ|²` (times `keep²` after a slip) instead of a new norm.
    #[inline(always)]
    fn update(&self, state: &mut MindlinState, input: &TangentialInput) -> TangentialResponse {
        let n = input.normal;
        let a = input.normal_response.contact_radius;
        let normal_force = input.normal_response.force;
        if a <= 0.0 || normal_force <= 0.0 {
            // Out of contact: springs leaving the contact forget their displacement, and the
            // energy they held with it.
            let released = self.stiffness_energy_change(
                state.displacement.norm_squared(),
                state.contact_radius,
                0.0,
            );
            *state = MindlinState::default();
            return TangentialResponse {
                stiffness_energy: released,
                ..TangentialResponse::default()
            };
        }
        // Keep ξ in the current contact plane: drop its normal part, keep its length (the
        // contact frame rotated, the springs did not stretch).
        let mut xi = state.displacement;
        let old_len2 = xi.norm_squared();
        let k = self.stiffness(a);
        // Energy the carried-over spring gains without work (the frame turn keeps |ξ|).
        let mut stiffness_energy = 0.0;
        if old_len2 > 0.0 {
            let along_normal = n.dot(&xi);
            xi -= n * along_normal;
            // The frame factor √(|ξ|²/|ξ_⊥|²) = (1 − t)^{-1/2} with t = (n·ξ)²/|ξ|² (|n| = 1).
            // It does not wait for the normal law (it needs only the normal and the stored ξ).
            // A contact plane that turns by θ per step has t ≈ θ² (tiny in a dense bed): for
            // t < 10⁻⁶ the series 1 + t/2 + 3t²/8 is exact to 5t³/16 < 4·10⁻¹⁹, below a double's
            // rounding, and saves the square root of the exact factor.
            let tilt = along_normal * along_normal;
            let frame = if tilt < 1e-6 * old_len2 {
                let t = tilt / old_len2;
                1.0 + t * (0.5 + 0.375 * t)
            } else {
                let new_len2 = xi.norm_squared();
                if new_len2 > 0.0 {
                    (old_len2 / new_len2).sqrt()
                } else {
                    1.0
                }
            };
            let (r_num, r_den) = self.rescale(state.contact_radius, a);
            // `frame * 1.0` is `frame` exactly: no division unless the radius rescales.
            let ratio = if r_num != r_den { r_num / r_den } else { 1.0 };
            xi *= frame * ratio;
            stiffness_energy = self.carried_energy_change(old_len2, state.contact_radius, k, ratio);
        }
        let du = input.displacement_increment - n * n.dot(&input.displacement_increment);
        xi += du;
        let cap = self.friction_coefficient * normal_force;
        let len2 = xi.norm_squared();
        let mut response = TangentialResponse {
            stiffness_energy,
            ..TangentialResponse::default()
        };
        let mut stored2 = len2;
        if k * k * len2 > cap * cap {
            // Gross slip: the spring is reset to the Coulomb limit (trial force k|ξ| > μ F_N);
            // μ F_N times the slip length is dissipated.
            let len = len2.sqrt();
            let trial = k * len;
            let keep = if trial > 0.0 { cap / trial } else { 0.0 };
            xi *= keep;
            stored2 = len2 * keep * keep;
            response.sliding = true;
            response.dissipated = cap * (len * (1.0 - keep));
        }
        state.displacement = xi;
        state.contact_radius = a;
        response.force = -k * xi;
        response.elastic_energy = 0.5 * k * stored2;
        response
    }

    /// `½ k_t(a) |ξ|²` at the stored contact radius.
    fn elastic_energy(&self, state: &MindlinState) -> f64 {
        0.5 * self.stiffness(state.contact_radius) * state.displacement.norm_squared()
    }
}

/// `μ`, required: a frictional contact states its friction.
impl Declared for Mindlin {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "mindlin",
        kind: LawKind::Tangential,
        summary: "incremental Mindlin with a Coulomb cap, k_t = 2 G* a (docs/theory.md §5)",
        params: &[Param::new(
            "friction",
            "μ",
            "1",
            Range::NON_NEGATIVE,
            "Coulomb friction coefficient: |F_t| ≤ μ F_n",
        )
        .flag("mu")
        .python("mu")
        .lammps("friction")],
    };
    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Self::new(values[0])
    }
}
