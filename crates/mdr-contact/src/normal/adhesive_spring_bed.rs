//! The discrete MDR spring bed with Heß's adhesion rule, for any profile: the reference the
//! closed form [`super::AdhesiveMdrLaw`] converges to as `Δx → 0`.
//!
//! The springs of a [`SpringBed`] (eqs. 2, 6, 9–13) with, on top:
//! - a spring attaches when it touches (its displacement `u − u_pl ≥ 0`), with zero elongation:
//!   no jump-in on approach;
//! - an attached spring carries tension, `f = E* Δx (u − u_pl) < 0` when stretched (eq. 10);
//! - the outermost attached spring, at `x = a`, lets go when its elongation exceeds
//!   `Δl_max(a) = √(2π a Δγ / E*)` (Popov & Heß; the paper's ref. [12]); the next one inwards is
//!   then the outermost and is checked in turn. The energy a spring held when it let go is
//!   booked as adhesive work.

use super::{NormalLaw, NormalModel, NormalResponse, SpringBed, SpringBedState};
use crate::error::{non_negative, Result};
use crate::material::ContactPair;
use crate::normal::AdhesiveMdr;
use std::f64::consts::PI;

/// History of one adhesive spring-bed contact.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AdhesiveSpringBedState {
    /// The springs' plastic memory, as in the non-adhesive bed.
    pub bed: SpringBedState,
    /// Whether each stored spring is attached, in the order of [`SpringBed::positions`]; empty
    /// until the first update.
    pub attached: Vec<bool>,
    /// Energy the springs held when they let go, summed (J).
    pub adhesive_work: f64,
}

/// The adhesive MDR spring bed: a [`SpringBed`] and the work of adhesion `Δγ`.
///
/// ```
/// use mdr_contact::prelude::*;
/// let pair = ContactPair::paper_fig2();
/// let model = AdhesiveMdr::new(MdrElastoPlastic::elastic(), 50.0).unwrap();
/// let bed = AdhesiveSpringBed::sphere(&pair, &model, 2000).unwrap().half_width(1e-4).unwrap();
/// let mut state = AdhesiveSpringBedState::default();
/// bed.update(&mut state, 1e-7);
/// // Unloaded past zero overlap the attached springs pull.
/// let response = bed.update(&mut state, -1e-9);
/// assert!(response.force < 0.0 && bed.holds(&state));
/// ```
#[derive(Debug, Clone)]
pub struct AdhesiveSpringBed {
    bed: SpringBed,
    work_of_adhesion: f64,
    /// `√(2π Δγ / E*)`.
    detach_coefficient: f64,
    /// `(3/2) π Δγ R` for a sphere of radius `R` (0 for other profiles).
    pull_off: f64,
}

impl AdhesiveSpringBed {
    /// The bed `bed` with the work of adhesion `work_of_adhesion` (J/m², finite, ≥ 0; zero gives
    /// the bed's own law exactly). Its [`NormalLaw::pull_off_force`] (the Coulomb offset of the
    /// tangential law) is zero: a general profile has no closed-form pull-off force; a sphere
    /// built with [`AdhesiveSpringBed::sphere`] has the JKR one.
    pub fn new(bed: SpringBed, work_of_adhesion: f64) -> Result<Self> {
        non_negative("work_of_adhesion", work_of_adhesion)?;
        let detach_coefficient = (2.0 * PI * work_of_adhesion / bed.effective_modulus()).sqrt();
        Ok(Self {
            bed,
            work_of_adhesion,
            detach_coefficient,
            pull_off: 0.0,
        })
    }

    /// A sphere of the pair's effective radius `R` with the parameters of `model` and
    /// `n_springs` springs over the default half-width (see [`SpringBed::sphere`]); its
    /// pull-off force is the JKR `(3/2) π Δγ R`.
    pub fn sphere(pair: &ContactPair, model: &AdhesiveMdr, n_springs: usize) -> Result<Self> {
        Ok(Self::new(
            SpringBed::sphere(pair, model.params(), n_springs)?,
            model.work_of_adhesion(),
        )?
        .with_sphere_pull_off(pair))
    }

    /// The same bed with the JKR pull-off force `(3/2) π Δγ R` of a sphere of the pair's
    /// effective radius `R` (for a bed built with [`AdhesiveSpringBed::new`] on a sphere).
    pub fn with_sphere_pull_off(mut self, pair: &ContactPair) -> Self {
        self.pull_off = 1.5 * PI * self.work_of_adhesion * pair.effective_radius();
        self
    }

    /// The same bed over another half-width (m, > 0).
    pub fn half_width(self, half_width: f64) -> Result<Self> {
        let pull_off = self.pull_off;
        let mut bed = Self::new(self.bed.half_width(half_width)?, self.work_of_adhesion)?;
        bed.pull_off = pull_off;
        Ok(bed)
    }

    /// The springs.
    pub fn bed(&self) -> &SpringBed {
        &self.bed
    }

    /// `Δγ` (J/m²).
    pub fn work_of_adhesion(&self) -> f64 {
        self.work_of_adhesion
    }

    /// `Δl_max(a) = √(2π a Δγ / E*)` (m).
    fn critical_elongation(&self, x: f64) -> f64 {
        self.detach_coefficient * x.sqrt()
    }

    /// Elongation `−(u − u_pl)` of stored spring `i` at overlap `d` (m; negative when pressed).
    fn elongation(&self, state: &AdhesiveSpringBedState, i: usize, d: f64) -> f64 {
        let u_max = state.bed.max_displacements[i];
        self.bed.plastic_offset(u_max) - (d - self.bed.heights()[i])
    }
}

impl NormalLaw for AdhesiveSpringBed {
    type State = AdhesiveSpringBedState;

    fn update(&self, state: &mut AdhesiveSpringBedState, overlap: f64) -> NormalResponse {
        if self.work_of_adhesion == 0.0 {
            return self.bed.update(&mut state.bed, overlap);
        }
        let n = self.bed.heights().len();
        if state.bed.max_displacements.len() != n {
            state.bed.max_displacements = vec![0.0; n];
        }
        if state.attached.len() != n {
            state.attached = vec![false; n];
        }
        state.bed.overlap = overlap;
        state.bed.max_overlap = state.bed.max_overlap.max(overlap);
        // Plastic memory, and attach every spring that touches (zero elongation at touch).
        for i in 0..n {
            let u = overlap - self.bed.heights()[i];
            let u_max = &mut state.bed.max_displacements[i];
            if u > *u_max {
                *u_max = u;
            }
            if u - self.bed.plastic_offset(*u_max) >= 0.0 {
                state.attached[i] = true;
            }
        }
        // The outermost attached spring lets go past Δl_max(a), then the next one inwards. On
        // the continuous path from the last overlap, spring i lets go at the overlap
        // `level = min(δ_i, level of the spring outside it)`, `δ_i = h_i − Δl_max(x_i)`, with
        // the energy it holds there.
        let k = self.bed.effective_modulus() * self.bed.spacing();
        let mut level = f64::INFINITY;
        for i in (0..n).rev() {
            if !state.attached[i] {
                continue;
            }
            let limit = self.critical_elongation(self.bed.positions()[i]);
            if self.elongation(state, i, overlap) <= limit {
                break;
            }
            let height =
                self.bed.heights()[i] + self.bed.plastic_offset(state.bed.max_displacements[i]);
            level = level.min(height - limit);
            let stretch = height - level;
            state.attached[i] = false;
            state.adhesive_work += self.bed.weights()[i] * 0.5 * k * stretch * stretch;
        }
        let k_plastic = k * self.bed.hardening_ratio();
        let mut response = NormalResponse::default();
        for i in 0..n {
            if !state.attached[i] {
                continue;
            }
            let u = overlap - self.bed.heights()[i];
            let (f, plastic) = self
                .bed
                .signed_spring_force(u, state.bed.max_displacements[i]);
            let w = self.bed.weights()[i];
            response.force += w * f;
            response.stiffness += w * if plastic { k_plastic } else { k };
            response.contact_radius = self.bed.positions()[i];
        }
        response
    }

    fn max_overlap(&self, state: &AdhesiveSpringBedState) -> f64 {
        state.bed.max_overlap
    }

    fn residual_overlap(&self, state: &AdhesiveSpringBedState) -> f64 {
        self.bed.residual_overlap(&state.bed)
    }

    /// The springs' plastic loops plus the adhesive work.
    fn dissipated_work(&self, state: &AdhesiveSpringBedState) -> f64 {
        self.bed.dissipated_work(&state.bed) + state.adhesive_work
    }

    /// `Σ f²/(2 k_z)` over the attached springs at `overlap`.
    fn elastic_energy(&self, state: &AdhesiveSpringBedState, overlap: f64) -> f64 {
        if self.work_of_adhesion == 0.0 {
            return self.bed.elastic_energy(&state.bed, overlap);
        }
        let mut trial = state.clone();
        self.update(&mut trial, overlap);
        let k = self.bed.effective_modulus() * self.bed.spacing();
        (0..trial.attached.len())
            .filter(|&i| trial.attached[i])
            .map(|i| {
                let u = overlap - self.bed.heights()[i];
                let (f, _) = self
                    .bed
                    .signed_spring_force(u, trial.bed.max_displacements[i]);
                self.bed.weights()[i] * f * f / (2.0 * k)
            })
            .sum()
    }

    fn yield_overlap(&self) -> f64 {
        self.bed.yield_overlap()
    }

    fn holds(&self, state: &AdhesiveSpringBedState) -> bool {
        self.work_of_adhesion > 0.0 && state.attached.iter().any(|&a| a)
    }

    /// The smallest `h_i − Δl_max(x_i)` over the attached springs: unloading lets the outermost
    /// go first, and each one inwards at the latest at its own limit.
    fn detachment_overlap(&self, state: &AdhesiveSpringBedState) -> f64 {
        if !self.holds(state) {
            return self.residual_overlap(state);
        }
        (0..state.attached.len())
            .filter(|&i| state.attached[i])
            .map(|i| {
                let h =
                    self.bed.heights()[i] + self.bed.plastic_offset(state.bed.max_displacements[i]);
                h - self.critical_elongation(self.bed.positions()[i])
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn pull_off_force(&self) -> f64 {
        self.pull_off
    }
}

/// Adhesive spring-bed parameters for a sphere, as a [`NormalModel`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SphereAdhesiveSpringBed {
    /// MDR parameters and `Δγ`.
    pub model: AdhesiveMdr,
    /// Number of springs over the full width (≥ 2).
    pub n_springs: usize,
    /// Half-width covered by the springs (m), or `None` for the default `R/4`.
    pub half_width: Option<f64>,
}

impl NormalModel for SphereAdhesiveSpringBed {
    type Law = AdhesiveSpringBed;
    fn bind(&self, pair: &ContactPair) -> Result<AdhesiveSpringBed> {
        let bed = AdhesiveSpringBed::sphere(pair, &self.model, self.n_springs)?;
        match self.half_width {
            Some(half_width) => bed.half_width(half_width),
            None => Ok(bed),
        }
    }
}
