//! The MDR spring-bed tangential law with per-spring stick/slip and Coulomb friction
//! (`docs/theory.md` §5).
//!
//! Every spring of a [`SpringBed`] also has a tangential stiffness `k_x = G* Δx`. While a spring
//! sticks, its tangential displacement `u_x` follows the relative tangential displacement of the
//! bodies; when `G* |u_x| > μ q_z` (`q_z = f_z/Δx`, its normal force per unit length) it slips
//! and is reset to `|u_x| = μ q_z / G*`; a spring that leaves the contact (`f_z = 0`) forgets
//! its displacement. The tangential force is `F_x = G* Δx Σ u_x`. Under monotonic loading at
//! constant normal force this reproduces Cattaneo–Mindlin partial slip exactly in the continuum
//! limit, `F_x = μ F_N (1 − (c/a)³)`.
//!
//! Displacements are 2D vectors in the contact plane, with an isotropic slip criterion
//! `G* |u| > μ q_z`; for loading along one fixed direction this is the 1D law of the MDR, for
//! changing directions it is the usual vector generalisation (an approximation: the MDR proper
//! is exact for collinear loading).

use crate::error::{non_negative, positive, Result};
use crate::material::ContactPair;
use crate::normal::{SpringBed, SpringBedState};
use nalgebra::Vector2;

/// Tangential history of a spring-bed contact.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SpringBedTangentialState {
    /// Tangential displacement of each stored spring (m), in the order of
    /// [`SpringBed::positions`]; empty until the first update.
    pub displacements: Vec<Vector2<f64>>,
    /// Work dissipated by slip so far (J).
    pub dissipated_work: f64,
}

/// The MDR spring-bed tangential law of one pair: `G*` and `μ`.
///
/// ```
/// use mdr_contact::prelude::*;
/// use mdr_contact::normal::{SpringBed, SpringBedState};
/// use mdr_contact::tangential::{SpringBedTangential, SpringBedTangentialState};
/// let pair = ContactPair::paper_fig2();
/// let bed = SpringBed::sphere(&pair, &MdrElastoPlastic::elastic(), 2001)
///     .unwrap()
///     .half_width(2e-4)
///     .unwrap();
/// let tangential = SpringBedTangential::new(&pair, 0.3).unwrap();
/// let (mut normal_state, mut state) = (SpringBedState::default(), SpringBedTangentialState::default());
/// let normal_force = bed.update(&mut normal_state, 2e-6).force;
/// let mut force = 0.0;
/// for _ in 0..100 {
///     force = tangential.update(&bed, &normal_state, &mut state, 1e-8);
/// }
/// // Past gross slip the force is μ F_N.
/// assert!((force - 0.3 * normal_force).abs() < 1e-9 * normal_force);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SpringBedTangential {
    effective_shear_modulus: f64,
    friction_coefficient: f64,
}

impl SpringBedTangential {
    /// The law for `pair` (its `G*`) with friction coefficient `μ` (finite, ≥ 0).
    pub fn new(pair: &ContactPair, friction_coefficient: f64) -> Result<Self> {
        Self::from_parts(pair.effective_shear_modulus(), friction_coefficient)
    }

    /// From `G*` (Pa, > 0) and `μ` (finite, ≥ 0) directly.
    pub fn from_parts(effective_shear_modulus: f64, friction_coefficient: f64) -> Result<Self> {
        Ok(Self {
            effective_shear_modulus: positive("effective_shear_modulus", effective_shear_modulus)?,
            friction_coefficient: non_negative("mu", friction_coefficient)?,
        })
    }

    /// `G*` (Pa).
    pub fn effective_shear_modulus(&self) -> f64 {
        self.effective_shear_modulus
    }

    /// `μ`.
    pub fn friction_coefficient(&self) -> f64 {
        self.friction_coefficient
    }

    /// Advance by a relative tangential displacement `increment` (m) along one fixed direction
    /// and return the tangential force `F_x = G* Δx Σ u_x` (N, along the displacement of the
    /// springs: the force on body 1 is its negative).
    ///
    /// `normal_state` must already be updated to this step's overlap (call the bed's
    /// [`NormalLaw::update`](crate::normal::NormalLaw::update) first): the springs' normal
    /// forces are read from it.
    pub fn update(
        &self,
        bed: &SpringBed,
        normal_state: &SpringBedState,
        state: &mut SpringBedTangentialState,
        increment: f64,
    ) -> f64 {
        self.update_vector(bed, normal_state, state, Vector2::new(increment, 0.0))
            .x
    }

    /// As [`SpringBedTangential::update`] with a 2D displacement increment in the contact
    /// plane (m); returns the 2D force `G* Δx Σ u` (N).
    pub fn update_vector(
        &self,
        bed: &SpringBed,
        normal_state: &SpringBedState,
        state: &mut SpringBedTangentialState,
        increment: Vector2<f64>,
    ) -> Vector2<f64> {
        let n = bed.positions().len();
        if state.displacements.len() != n {
            state.displacements = vec![Vector2::zeros(); n];
        }
        let g = self.effective_shear_modulus;
        let dx = bed.spacing();
        let mut sum = Vector2::zeros();
        for ((u, normal_force), &w) in state
            .displacements
            .iter_mut()
            .zip(bed.spring_forces(normal_state))
            .zip(bed.weights())
        {
            if normal_force <= 0.0 {
                // Out of contact: the spring forgets its displacement.
                *u = Vector2::zeros();
                continue;
            }
            *u += increment;
            // Slip limit |u| ≤ μ q_z / G* with q_z = f_z / Δx.
            let limit = self.friction_coefficient * normal_force / (dx * g);
            let length = u.norm();
            if length > limit {
                let slip = length - limit;
                *u *= limit / length;
                // Friction μ f_z acts over the slip distance.
                state.dissipated_work += w * self.friction_coefficient * normal_force * slip;
            }
            sum += w * *u;
        }
        g * dx * sum
    }

    /// Elastic energy in the tangential springs (J): `Σ G* Δx |u|² / 2`.
    pub fn elastic_energy(&self, bed: &SpringBed, state: &SpringBedTangentialState) -> f64 {
        let k = self.effective_shear_modulus * bed.spacing();
        state
            .displacements
            .iter()
            .zip(bed.weights())
            .map(|(u, &w)| 0.5 * w * k * u.norm_squared())
            .sum()
    }

    /// Radius of the stick zone (m): the outermost spring in contact that has not slipped in the
    /// last update (its `|u|` is below the slip limit); 0 when every spring in contact slips.
    pub fn stick_radius(
        &self,
        bed: &SpringBed,
        normal_state: &SpringBedState,
        state: &SpringBedTangentialState,
    ) -> f64 {
        let g = self.effective_shear_modulus;
        let dx = bed.spacing();
        let mut radius = 0.0;
        for ((u, normal_force), &x) in state
            .displacements
            .iter()
            .zip(bed.spring_forces(normal_state))
            .zip(bed.positions())
        {
            let limit = self.friction_coefficient * normal_force / (dx * g);
            if normal_force > 0.0 && u.norm() < limit * (1.0 - 1e-12) {
                radius = x;
            }
        }
        radius
    }
}
