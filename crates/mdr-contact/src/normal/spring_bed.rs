//! The discrete MDR spring bed (eqs. 2, 6, 9–13) for any 1D profile `g(x)`.
//!
//! A row of `n` independent springs of spacing `Δx = 2L/n` centred at
//! `x_j = −L + (j + ½) Δx` over `[−L, L]` (`L` the half-width). Pressing the profile in by `d`
//! displaces the spring at `x` by `u = d − g(x)` (eq. 4). Each spring (force per spring):
//!
//! - stiffness `k_z = E* Δx` (eq. 2); elastic up to `u_crit = π q_c / (2 E*)` (eq. 11), where it
//!   carries the nonlocal yield force `f_c = (π/2) q_c Δx` (eq. 9);
//! - plastic loading (`u` at its maximum so far and `> u_crit`):
//!   `f = f_c + (u − u_crit) Θ Δx` (eq. 12);
//! - after reaching `u_max > u_crit` it keeps the plastic offset
//!   `u_pl = (u_max − u_crit)(1 − Θ/E*)` (eq. 13) and unloads and reloads elastically,
//!   `f = E* Δx (u − u_pl)` (eq. 10);
//! - no tension: `f ≥ 0`.
//!
//! The normal force is the sum over the springs (eq. 6). The profile is even, so only the springs
//! at `x ≥ 0` are stored, each with a weight 2 (1 for a spring on the axis when `n` is odd).
//!
//! Every spring keeps its own history (`u_max`), so the bed handles any indentation history and
//! any profile; it is the reference the closed form [`super::MdrLaw`] converges to as `Δx → 0`.

use super::{NormalLaw, NormalModel, NormalResponse};
use crate::error::{finite, in_closed_range, positive, ContactError, Result};
use crate::material::ContactPair;
use crate::normal::MdrElastoPlastic;
use crate::profile::{Profile, Sphere};
use std::f64::consts::PI;
use std::sync::Arc;

/// History of one spring-bed contact.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SpringBedState {
    /// Largest displacement `u_max` each stored spring has reached (m); empty until the first
    /// update (then one entry per stored spring, in the order of [`SpringBed::positions`]).
    pub max_displacements: Vec<f64>,
    /// Largest overlap so far (m).
    pub max_overlap: f64,
    /// Overlap of the last update (m); the tangential spring bed reads the springs' normal
    /// forces at this overlap.
    pub overlap: f64,
}

/// The MDR spring bed bound to a profile and a pair; a [`NormalLaw`] with per-spring state
/// [`SpringBedState`].
///
/// ```
/// use mdr_contact::prelude::*;
/// use mdr_contact::normal::{SpringBed, SpringBedState};
/// let pair = ContactPair::paper_fig2();
/// let bed = SpringBed::sphere(&pair, &MdrElastoPlastic::paper(), 2001)
///     .unwrap()
///     .half_width(3e-4)
///     .unwrap();
/// let closed = MdrElastoPlastic::paper().bind(&pair).unwrap();
/// let (mut bed_state, mut closed_state) = (SpringBedState::default(), MdrState::default());
/// for d in [4e-6, 2e-6, 6e-6] {
///     let f_bed = bed.update(&mut bed_state, d).force;
///     let f_closed = closed.update(&mut closed_state, d).force;
///     assert!((f_bed - f_closed).abs() < 1e-3 * f_closed);
/// }
/// ```
#[derive(Debug, Clone)]
pub struct SpringBed {
    profile: Arc<dyn Profile>,
    effective_modulus: f64,
    critical_line_load: f64,
    hardening_ratio: f64,
    half_width: f64,
    n_springs: usize,
    /// `Δx = 2L / n` (m).
    spacing: f64,
    /// Stored springs (x ≥ 0), ascending.
    positions: Vec<f64>,
    /// `g(x_i)` of the stored springs (m).
    heights: Vec<f64>,
    /// 2 for a pair of springs at ±x, 1 for the spring on the axis.
    weights: Vec<f64>,
    /// `u_crit = π q_c / (2 E*)`, eq. (11) (m).
    critical_displacement: f64,
}

impl SpringBed {
    /// The most springs [`SpringBed::with_spacing`] lays out: `10⁸`, whose stored springs'
    /// positions, heights and weights take 1.2 GB.
    pub const MAX_SPRINGS: usize = 100_000_000;

    /// A bed of `n_springs` springs over `[−half_width, half_width]` for `profile`.
    ///
    /// - `effective_modulus`: `E*` (Pa, > 0), eq. (3);
    /// - `critical_line_load`: `q_c` (N/m, ≥ 0; `+∞` makes the bed elastic);
    /// - `hardening_ratio`: `Θ/E*` in `[0, 1]`;
    /// - `half_width`: `L` (m, > 0, at most the profile's [`Profile::max_radius`]); springs cover
    ///   contact radii up to `L`;
    /// - `n_springs` in `[2, MAX_SPRINGS]`: the number of springs over the full width `2L`, so
    ///   `Δx = 2L/n`.
    pub fn new<P: Profile + 'static>(
        profile: P,
        effective_modulus: f64,
        critical_line_load: f64,
        hardening_ratio: f64,
        half_width: f64,
        n_springs: usize,
    ) -> Result<Self> {
        Self::from_shared(
            Arc::new(profile),
            effective_modulus,
            critical_line_load,
            hardening_ratio,
            half_width,
            n_springs,
        )
    }

    /// As [`SpringBed::new`] with a spacing `Δx` (m, > 0) instead of a count: the bed uses
    /// `n = ⌈2L/Δx⌉` springs, so its spacing is at most `Δx`.
    pub fn with_spacing<P: Profile + 'static>(
        profile: P,
        effective_modulus: f64,
        critical_line_load: f64,
        hardening_ratio: f64,
        half_width: f64,
        spacing: f64,
    ) -> Result<Self> {
        Self::new(
            profile,
            effective_modulus,
            critical_line_load,
            hardening_ratio,
            half_width,
            Self::spring_count_for_spacing(half_width, spacing)?,
        )
    }

    /// The spring count `n = ⌈2L/Δx⌉` that [`SpringBed::with_spacing`] uses for a half-width
    /// `L` (m, > 0) and a spacing `Δx` (m, > 0), checked before anything is allocated: at most
    /// [`SpringBed::MAX_SPRINGS`], else `spacing` is out of range.
    pub fn spring_count_for_spacing(half_width: f64, spacing: f64) -> Result<usize> {
        positive("half_width", half_width)?;
        positive("spacing", spacing)?;
        let count = (2.0 * half_width / spacing).ceil();
        if count > Self::MAX_SPRINGS as f64 {
            return Err(ContactError::OutOfRange {
                name: "spacing",
                value: spacing,
                range: "[2 half_width / 1e8, inf)",
            });
        }
        Ok(count as usize)
    }

    /// A sphere of the pair's effective radius (parabolic profile `g = x²/R`) with the MDR
    /// parameters `params` (their hardening resolved against the pair's `E*` as in
    /// [`MdrElastoPlastic::bind`]) and `n_springs` springs.
    ///
    /// The half-width defaults to `R/4` (contact radii up to `R/4`, i.e. overlaps up to `R/16`,
    /// beyond the range where the parabolic profile is meaningful). Callers who know the largest
    /// contact radius they need (e.g. `a = sqrt(R δ_max)` of an impact, with a margin) should set
    /// it with [`SpringBed::half_width`] to get finer springs.
    pub fn sphere(pair: &ContactPair, params: &MdrElastoPlastic, n_springs: usize) -> Result<Self> {
        let bound = params.bind(pair)?;
        let radius = pair.effective_radius();
        Self::new(
            Sphere::new(radius)?,
            pair.effective_modulus(),
            params.critical_line_load(),
            bound.hardening_ratio(),
            0.25 * radius,
            n_springs,
        )
    }

    /// The same bed over another half-width `L` (m, > 0), same number of springs.
    pub fn half_width(self, half_width: f64) -> Result<Self> {
        Self::from_shared(
            self.profile,
            self.effective_modulus,
            self.critical_line_load,
            self.hardening_ratio,
            half_width,
            self.n_springs,
        )
    }

    /// The same bed with another number of springs (≥ 2), same half-width.
    pub fn n_springs(self, n_springs: usize) -> Result<Self> {
        Self::from_shared(
            self.profile,
            self.effective_modulus,
            self.critical_line_load,
            self.hardening_ratio,
            self.half_width,
            n_springs,
        )
    }

    fn from_shared(
        profile: Arc<dyn Profile>,
        effective_modulus: f64,
        critical_line_load: f64,
        hardening_ratio: f64,
        half_width: f64,
        n_springs: usize,
    ) -> Result<Self> {
        positive("effective_modulus", effective_modulus)?;
        if critical_line_load.is_nan() || critical_line_load < 0.0 {
            return Err(ContactError::OutOfRange {
                name: "q_c",
                value: critical_line_load,
                range: "[0, inf]",
            });
        }
        in_closed_range("theta_ratio", hardening_ratio, 0.0, 1.0, "[0, 1]")?;
        positive("half_width", half_width)?;
        let max_radius = profile.max_radius();
        if half_width > max_radius {
            return Err(ContactError::OutOfRange {
                name: "half_width",
                value: half_width,
                range: "(0, max_radius of the profile]",
            });
        }
        if n_springs < 2 {
            return Err(ContactError::TooFew {
                name: "n_springs",
                value: n_springs,
                min: 2,
            });
        }
        // Bounded before the springs are allocated (a count from the user, e.g. `--springs`).
        if n_springs > Self::MAX_SPRINGS {
            return Err(ContactError::OutOfRange {
                name: "n_springs",
                value: n_springs as f64,
                range: "[2, 1e8]",
            });
        }
        let spacing = 2.0 * half_width / n_springs as f64;
        // Springs j = n/2 .. n−1 sit at x ≥ 0; for odd n the first of them is on the axis.
        let first = n_springs / 2;
        let positions: Vec<f64> = (first..n_springs)
            .map(|j| (-half_width + (j as f64 + 0.5) * spacing).max(0.0))
            .collect();
        let weights: Vec<f64> = positions
            .iter()
            .enumerate()
            .map(|(i, _)| {
                if i == 0 && n_springs % 2 == 1 {
                    1.0
                } else {
                    2.0
                }
            })
            .collect();
        let heights: Vec<f64> = positions.iter().map(|&x| profile.mdr_height(x)).collect();
        if let Some(i) = heights.iter().position(|h| h.is_nan()) {
            finite("profile height g(x)", heights[i])?;
        }
        Ok(Self {
            profile,
            effective_modulus,
            critical_line_load,
            hardening_ratio,
            half_width,
            n_springs,
            spacing,
            positions,
            heights,
            weights,
            // eq. (11): u_crit = f_c / (E* Δx) = π q_c / (2 E*), independent of Δx.
            critical_displacement: PI * critical_line_load / (2.0 * effective_modulus),
        })
    }

    /// `E*` (Pa).
    pub fn effective_modulus(&self) -> f64 {
        self.effective_modulus
    }

    /// `q_c` (N/m).
    pub fn critical_line_load(&self) -> f64 {
        self.critical_line_load
    }

    /// `θ = Θ/E*`.
    pub fn hardening_ratio(&self) -> f64 {
        self.hardening_ratio
    }

    /// `u_crit = π q_c / (2 E*)` (m), eq. (11).
    pub fn critical_displacement(&self) -> f64 {
        self.critical_displacement
    }

    /// Half-width `L` covered by the springs (m).
    pub fn covered_half_width(&self) -> f64 {
        self.half_width
    }

    /// Number of springs over the full width.
    pub fn spring_count(&self) -> usize {
        self.n_springs
    }

    /// Spring spacing `Δx` (m).
    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// The profile.
    pub fn profile(&self) -> &dyn Profile {
        self.profile.as_ref()
    }

    /// Positions `x ≥ 0` of the stored springs (m), ascending.
    pub fn positions(&self) -> &[f64] {
        &self.positions
    }

    /// How many physical springs each stored spring stands for (2 for `±x`, 1 on the axis).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// `g(x_i)` of the stored springs (m).
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// Force of one spring (N) at displacement `u` with largest displacement so far `u_max`
    /// (both m), and whether it is on its plastic loading branch.
    #[inline]
    fn spring_force(&self, u: f64, u_max: f64) -> (f64, bool) {
        let (force, plastic) = self.signed_spring_force(u, u_max);
        // No tension without adhesion.
        (force.max(0.0), plastic)
    }

    /// As `spring_force`, but a stretched spring carries tension (an attached spring of the
    /// adhesive bed).
    #[inline]
    pub(crate) fn signed_spring_force(&self, u: f64, u_max: f64) -> (f64, bool) {
        let e = self.effective_modulus;
        let u_c = self.critical_displacement;
        if u >= u_max && u > u_c {
            // Plastic loading, eq. (12): f = f_c + (u − u_crit) Θ Δx, f_c = E* u_crit Δx.
            let force = e * self.spacing * (u_c + self.hardening_ratio * (u - u_c));
            return (force, true);
        }
        // Elastic branch, eq. (10), with the offset of eq. (13).
        (e * self.spacing * (u - self.plastic_offset(u_max)), false)
    }

    /// Plastic offset `u_pl = (1 − θ)(u_max − u_crit)₊` of a spring (eq. 13, m).
    #[inline]
    pub(crate) fn plastic_offset(&self, u_max: f64) -> f64 {
        (1.0 - self.hardening_ratio) * (u_max - self.critical_displacement).max(0.0)
    }

    /// Normal force of each stored spring (N, one spring, not weighted) at the state's last
    /// overlap, in the order of [`SpringBed::positions`].
    pub fn spring_forces<'a>(
        &'a self,
        state: &'a SpringBedState,
    ) -> impl Iterator<Item = f64> + 'a {
        let d = state.overlap;
        self.heights.iter().enumerate().map(move |(i, &g)| {
            let u_max = state.max_displacements.get(i).copied().unwrap_or(0.0);
            self.spring_force(d - g, u_max).0
        })
    }

    /// Whether the outermost spring touches: the contact has reached the edge of the bed and
    /// the force is underestimated (make the half-width larger).
    pub fn is_saturated(&self, state: &SpringBedState) -> bool {
        self.spring_forces(state).last().is_some_and(|f| f > 0.0)
    }

    /// `Σ f²/(2 k_z)` over the springs at overlap `d`, without changing the history (a new
    /// maximum is loaded on a copy of each spring's `u_max`).
    fn energy_at(&self, state: &SpringBedState, d: f64) -> f64 {
        let k = self.effective_modulus * self.spacing;
        let mut energy = 0.0;
        for (i, (&g, &w)) in self.heights.iter().zip(&self.weights).enumerate() {
            let u = d - g;
            let u_max = state
                .max_displacements
                .get(i)
                .copied()
                .unwrap_or(0.0)
                .max(u);
            let (force, _) = self.spring_force(u, u_max);
            energy += w * force * force / (2.0 * k);
        }
        energy
    }
}

impl NormalLaw for SpringBed {
    type State = SpringBedState;

    fn update(&self, state: &mut SpringBedState, overlap: f64) -> NormalResponse {
        if state.max_displacements.len() != self.heights.len() {
            state.max_displacements = vec![0.0; self.heights.len()];
        }
        state.overlap = overlap;
        if overlap > state.max_overlap {
            state.max_overlap = overlap;
        }
        let k_elastic = self.effective_modulus * self.spacing;
        let k_plastic = k_elastic * self.hardening_ratio;
        let mut force = 0.0;
        let mut stiffness = 0.0;
        let mut contact_radius = 0.0;
        for (((&g, &w), u_max), &x) in self
            .heights
            .iter()
            .zip(&self.weights)
            .zip(state.max_displacements.iter_mut())
            .zip(&self.positions)
        {
            let u = overlap - g;
            if u > *u_max {
                *u_max = u;
            }
            let (f, plastic) = self.spring_force(u, *u_max);
            if f > 0.0 {
                force += w * f;
                stiffness += w * if plastic { k_plastic } else { k_elastic };
                contact_radius = x;
            }
        }
        NormalResponse {
            force,
            contact_radius,
            stiffness,
        }
    }

    fn max_overlap(&self, state: &SpringBedState) -> f64 {
        state.max_overlap
    }

    /// The overlap below which no spring touches: `min_i (g(x_i) + u_pl,i)`.
    fn residual_overlap(&self, state: &SpringBedState) -> f64 {
        let u_c = self.critical_displacement;
        self.heights
            .iter()
            .enumerate()
            .map(|(i, &g)| {
                let u_max = state.max_displacements.get(i).copied().unwrap_or(0.0);
                g + (1.0 - self.hardening_ratio) * (u_max - u_c).max(0.0)
            })
            .fold(f64::INFINITY, f64::min)
            .max(0.0)
    }

    /// `Σ` over the springs of the area of their plastic loop: a spring loaded to
    /// `u_max = u_crit + p` and unloaded to zero force has dissipated
    /// `(1 − θ) (E* u_crit p + Θ p²/2) Δx` (`docs/theory.md` §3).
    fn dissipated_work(&self, state: &SpringBedState) -> f64 {
        let u_c = self.critical_displacement;
        let e = self.effective_modulus;
        let theta = self.hardening_ratio;
        let mut work = 0.0;
        for (&u_max, &w) in state.max_displacements.iter().zip(&self.weights) {
            let p = u_max - u_c;
            if p > 0.0 {
                work += w * (e * u_c * p + 0.5 * theta * e * p * p);
            }
        }
        (1.0 - theta) * self.spacing * work
    }

    /// `Σ f²/(2 k_z)` at `overlap` (loading the history there first if it is a new maximum).
    fn elastic_energy(&self, state: &SpringBedState, overlap: f64) -> f64 {
        self.energy_at(state, overlap)
    }

    /// `min_i g(x_i) + u_crit`: the overlap at which the first spring yields.
    fn yield_overlap(&self) -> f64 {
        self.heights.iter().copied().fold(f64::INFINITY, f64::min) + self.critical_displacement
    }
}

/// Spring-bed parameters for a sphere, as a [`NormalModel`]: binding to a pair builds
/// [`SpringBed::sphere`] with the given spring count and half-width.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SphereSpringBed {
    /// MDR parameters `q_c`, `Θ`.
    pub params: MdrElastoPlastic,
    /// Number of springs over the full width (≥ 2).
    pub n_springs: usize,
    /// Half-width covered by the springs (m), or `None` for the default `R/4`.
    pub half_width: Option<f64>,
}

impl NormalModel for SphereSpringBed {
    type Law = SpringBed;
    fn bind(&self, pair: &ContactPair) -> Result<SpringBed> {
        let bed = SpringBed::sphere(pair, &self.params, self.n_springs)?;
        match self.half_width {
            Some(half_width) => bed.half_width(half_width),
            None => Ok(bed),
        }
    }
}
