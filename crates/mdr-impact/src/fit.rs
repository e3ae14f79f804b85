//! Least-squares fit of the MDR law to measured restitution data: any subset of
//! {`q_c`, `Θ/E*`, scale, `Δγ`} is adjusted so that `scale · e_n(v; q_c, Θ/E*, Δγ)` matches the
//! measured `(v0, e)` pairs. Without adhesion `e_n` comes from the energy route (docs/theory.md
//! §4); with it, from time integration (docs/theory.md, "Adhesive impacts"). The work of
//! adhesion `Δγ` can be fitted when the data show sticking (points with `e = 0`): the sticking
//! speed is what determines it.
//!
//! The optimiser is argmin's Nelder–Mead on the sum of squared residuals, in internal coordinates
//! that keep the parameters in range (`ln q_c`, logit of `Θ/E*`, `ln Δγ`). The uncertainties come from the
//! Jacobian `J` of the residuals in the natural parameters at the optimum:
//! `cov = s² (JᵀJ)⁻¹`, `s² = SSE / (n − p)`.

use crate::error::{ImpactError, Result};
use crate::impact::Impact;
use crate::law::NormalSpec;
use crate::output::Measurement;
use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;
use mdr_contact::normal::{MdrElastoPlastic, MdrState, NormalModel};
use mdr_contact::ContactPair;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// A parameter the fit may adjust.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FitParameter {
    /// Critical line load `q_c` (N/m), eq. (7).
    CriticalLineLoad,
    /// Hardening ratio `Θ/E*`, eq. (12).
    HardeningRatio,
    /// The scale factor applied to the model's `e_n` (docs/theory.md §7).
    Scale,
    /// The work of adhesion `Δγ` (J/m²); needs data that show sticking.
    WorkOfAdhesion,
}

impl FitParameter {
    /// Name as used by `--free` and in JSON: `qc`, `theta_ratio`, `scale`, `work_of_adhesion`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::CriticalLineLoad => "qc",
            Self::HardeningRatio => "theta_ratio",
            Self::Scale => "scale",
            Self::WorkOfAdhesion => "work_of_adhesion",
        }
    }

    /// Parse a `--free` entry (`qc`/`q_c`, `theta_ratio`/`theta-ratio`, `scale`,
    /// `work_of_adhesion`/`work-of-adhesion`).
    pub fn parse(text: &str) -> Result<Self> {
        match text.trim() {
            "qc" | "q_c" => Ok(Self::CriticalLineLoad),
            "theta_ratio" | "theta-ratio" => Ok(Self::HardeningRatio),
            "scale" => Ok(Self::Scale),
            "work_of_adhesion" | "work-of-adhesion" => Ok(Self::WorkOfAdhesion),
            other => Err(ImpactError::invalid(
                "free",
                other,
                "a comma-separated subset of qc,theta_ratio,scale,work_of_adhesion",
            )),
        }
    }
}

/// Values of the three fit parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitValues {
    /// `q_c` (N/m).
    pub q_c: f64,
    /// `Θ/E*`.
    pub theta_ratio: f64,
    /// Scale factor.
    pub scale: f64,
    /// Work of adhesion `Δγ` (J/m²).
    pub work_of_adhesion: f64,
}

impl FitValues {
    /// The paper's values: `q_c = 3.8·10⁵ N/m`, `Θ/E* = 0.37`, scale 0.95.
    pub fn paper() -> Self {
        Self {
            q_c: 3.8e5,
            theta_ratio: 0.37,
            scale: crate::PAPER_SCALE,
            work_of_adhesion: 0.0,
        }
    }

    fn get(&self, p: FitParameter) -> f64 {
        match p {
            FitParameter::CriticalLineLoad => self.q_c,
            FitParameter::HardeningRatio => self.theta_ratio,
            FitParameter::Scale => self.scale,
            FitParameter::WorkOfAdhesion => self.work_of_adhesion,
        }
    }

    fn set(&mut self, p: FitParameter, value: f64) {
        match p {
            FitParameter::CriticalLineLoad => self.q_c = value,
            FitParameter::HardeningRatio => self.theta_ratio = value,
            FitParameter::Scale => self.scale = value,
            FitParameter::WorkOfAdhesion => self.work_of_adhesion = value,
        }
    }
}

/// Result of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitReport {
    /// Fitted values (fixed parameters keep their given values).
    pub values: FitValues,
    /// The parameters that were fitted, with their standard uncertainty (1σ).
    pub uncertainties: Vec<(FitParameter, f64)>,
    /// Root-mean-square residual.
    pub rmse: f64,
    /// Number of data points.
    pub n_points: usize,
    /// Number of points above the fitted yield speed (where the data carry plastic information).
    pub n_plastic: usize,
    /// Fitted yield speed (m/s).
    pub yield_speed: f64,
}

/// Model prediction `scale · e_n(v)` for every speed; an error if the values are out of range
/// or a speed is NaN, infinite or negative.
pub fn predict(pair: &ContactPair, values: &FitValues, speeds: &[f64]) -> Result<Vec<f64>> {
    let params = MdrElastoPlastic::new(values.q_c, values.theta_ratio)
        .map_err(ImpactError::parameter("qc"))?;
    let law = params
        .bind(pair)
        .map_err(ImpactError::parameter("theta-ratio"))?;
    if values.work_of_adhesion != 0.0 {
        // Adhesion: time integration (the energy route has none); stuck impacts give 0.
        return speeds
            .iter()
            .map(|&v| {
                Impact::new(*pair, NormalSpec::Mdr(params), v)
                    .work_of_adhesion(values.work_of_adhesion)
                    .run()
                    .map(|o| values.scale * o.normal_restitution)
            })
            .collect();
    }
    let mass = pair.reduced_mass();
    speeds
        .iter()
        .map(|&v| {
            law.impact(&MdrState::default(), mass, v)
                .map(|o| values.scale * o.restitution)
                .map_err(ImpactError::parameter("speed"))
        })
        .collect()
}

struct Problem<'a> {
    pair: &'a ContactPair,
    base: FitValues,
    free: &'a [FitParameter],
    data: &'a [Measurement],
}

impl Problem<'_> {
    /// Internal coordinates → values.
    fn values(&self, x: &[f64]) -> FitValues {
        let mut values = self.base;
        for (p, &xi) in self.free.iter().zip(x) {
            let v = match p {
                FitParameter::CriticalLineLoad => xi.exp(),
                FitParameter::HardeningRatio => 1.0 / (1.0 + (-xi).exp()),
                FitParameter::Scale => xi,
                FitParameter::WorkOfAdhesion => xi.exp(),
            };
            values.set(*p, v);
        }
        values
    }

    fn internal(&self, values: &FitValues) -> Vec<f64> {
        self.free
            .iter()
            .map(|p| match p {
                FitParameter::CriticalLineLoad => values.q_c.ln(),
                FitParameter::HardeningRatio => {
                    let t = values.theta_ratio.clamp(1e-6, 1.0 - 1e-6);
                    (t / (1.0 - t)).ln()
                }
                FitParameter::Scale => values.scale,
                FitParameter::WorkOfAdhesion => values.work_of_adhesion.ln(),
            })
            .collect()
    }

    fn residuals(&self, values: &FitValues) -> Result<Vec<f64>> {
        let speeds: Vec<f64> = self.data.iter().map(|m| m.speed).collect();
        Ok(predict(self.pair, values, &speeds)?
            .into_iter()
            .zip(self.data)
            .map(|(model, m)| m.restitution - model)
            .collect())
    }
}

impl CostFunction for Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, x: &Vec<f64>) -> std::result::Result<f64, argmin::core::Error> {
        Ok(match self.residuals(&self.values(x)) {
            Ok(r) => r.iter().map(|ri| ri * ri).sum(),
            Err(_) => f64::INFINITY,
        })
    }
}

/// Fit the `free` parameters to `data`, starting from `initial` (which also holds the values of
/// the fixed ones). Refuses data that cannot determine the parameters.
pub fn fit(
    pair: &ContactPair,
    initial: FitValues,
    free: &[FitParameter],
    data: &[Measurement],
) -> Result<FitReport> {
    let mut free_unique: Vec<FitParameter> = Vec::new();
    for p in free {
        if !free_unique.contains(p) {
            free_unique.push(*p);
        }
    }
    let free = &free_unique[..];
    if free.is_empty() {
        return Err(ImpactError::invalid(
            "free",
            "(none)",
            "at least one of qc,theta_ratio,scale",
        ));
    }
    // Check the starting values through the law crate's own validation.
    predict(pair, &initial, &[1.0])?;
    if let Some(bad) = data
        .iter()
        .find(|m| !(m.speed.is_finite() && m.speed > 0.0))
    {
        return Err(ImpactError::invalid(
            "speed",
            bad.speed,
            "measured impact speeds > 0 m/s (finite)",
        ));
    }
    if let Some(bad) = data.iter().find(|m| !m.restitution.is_finite()) {
        return Err(ImpactError::invalid(
            "restitution",
            bad.restitution,
            "measured coefficients of restitution (finite)",
        ));
    }
    if !(initial.scale.is_finite() && initial.scale > 0.0) {
        return Err(ImpactError::invalid("scale", initial.scale, "a scale > 0"));
    }
    let (n, p) = (data.len(), free.len());
    if n < p + 1 {
        return Err(ImpactError::Underdetermined(format!(
            "{n} data point(s) for {p} free parameter(s): at least {} points are needed \
             (one more than the free parameters, for an uncertainty estimate)",
            p + 1
        )));
    }
    let plastic_free = free
        .iter()
        .filter(|p| {
            matches!(
                p,
                FitParameter::CriticalLineLoad | FitParameter::HardeningRatio
            )
        })
        .count();
    let mut initial = initial;
    if !(initial.work_of_adhesion.is_finite() && initial.work_of_adhesion >= 0.0) {
        return Err(ImpactError::invalid(
            "work-of-adhesion",
            initial.work_of_adhesion,
            "a work of adhesion ≥ 0 J/m² (finite)",
        ));
    }
    if free.contains(&FitParameter::WorkOfAdhesion) {
        initial.work_of_adhesion = initial_work_of_adhesion(pair, &initial, data)?;
    }
    let initial = initial;
    let problem = Problem {
        pair,
        base: initial,
        free,
        data,
    };
    let mut x = problem.internal(&initial);
    // Two Nelder–Mead passes: the second restarts from the first one's optimum with a fresh
    // simplex, which guards against a collapsed simplex.
    for (pass, width) in [(0, 1.0), (1, 0.2)] {
        let steps: Vec<f64> = free
            .iter()
            .map(|p| match p {
                FitParameter::CriticalLineLoad => 0.7 * width,
                FitParameter::HardeningRatio => 1.0 * width,
                FitParameter::Scale => 0.05 * width,
                FitParameter::WorkOfAdhesion => 0.7 * width,
            })
            .collect();
        let mut simplex = vec![x.clone()];
        for (i, step) in steps.iter().enumerate() {
            let mut vertex = x.clone();
            vertex[i] += step;
            simplex.push(vertex);
        }
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(1e-13)
            .map_err(|e| ImpactError::Optimiser(e.to_string()))?;
        let result = Executor::new(
            Problem {
                pair,
                base: initial,
                free,
                data,
            },
            solver,
        )
        .configure(|state| state.max_iters(if pass == 0 { 3000 } else { 1500 }))
        .run()
        .map_err(|e| ImpactError::Optimiser(e.to_string()))?;
        x = result
            .state()
            .get_best_param()
            .cloned()
            .ok_or_else(|| ImpactError::Optimiser("no best parameter".into()))?;
    }
    let values = problem.values(&x);
    let residuals = problem.residuals(&values)?;
    let sse: f64 = residuals.iter().map(|r| r * r).sum();
    let rmse = (sse / n as f64).sqrt();

    let law = MdrElastoPlastic::new(values.q_c, values.theta_ratio)
        .map_err(ImpactError::parameter("qc"))?
        .bind(pair)
        .map_err(ImpactError::parameter("theta-ratio"))?;
    let yield_speed = law.yield_speed(pair.reduced_mass());
    let n_plastic = data.iter().filter(|m| m.speed > yield_speed).count();
    if plastic_free > 0 && n_plastic < plastic_free {
        return Err(ImpactError::Underdetermined(format!(
            "only {n_plastic} point(s) lie above the fitted yield speed {yield_speed:.4} m/s, \
             but {plastic_free} plastic parameter(s) (qc, theta_ratio) are free: below the yield \
             speed e_n = 1 whatever their values; measure at higher speeds or fix them"
        )));
    }

    // Jacobian of the model in the natural parameters (central differences).
    let mut jacobian = DMatrix::<f64>::zeros(n, p);
    for (j, param) in free.iter().enumerate() {
        let value = values.get(*param);
        let h = match param {
            FitParameter::HardeningRatio => 1e-5_f64.min(0.5 * value.min(1.0 - value)).max(1e-9),
            // Time-integrated e_n: a step well above the integrator's resolution.
            FitParameter::WorkOfAdhesion => 1e-3 * value,
            _ => 1e-5 * value.abs().max(1e-12),
        };
        let mut plus = values;
        plus.set(*param, value + h);
        let mut minus = values;
        minus.set(*param, value - h);
        let (rp, rm) = (problem.residuals(&plus)?, problem.residuals(&minus)?);
        for i in 0..n {
            // residual = data − model, so d model = −d residual.
            jacobian[(i, j)] = -(rp[i] - rm[i]) / (2.0 * h);
        }
    }
    let normal_matrix = jacobian.transpose() * &jacobian;
    // Identifiability: the correlation form of JᵀJ must be well conditioned.
    let diagonal = DVector::from_iterator(p, (0..p).map(|j| normal_matrix[(j, j)]));
    if let Some(j) = (0..p).find(|&j| diagonal[j].is_nan() || diagonal[j] <= 0.0) {
        return Err(ImpactError::Underdetermined(format!(
            "the data do not depend on `{}` (zero sensitivity at the optimum)",
            free[j].name()
        )));
    }
    let scaled = DMatrix::from_fn(p, p, |i, j| {
        normal_matrix[(i, j)] / (diagonal[i] * diagonal[j]).sqrt()
    });
    let eigen = scaled.clone().symmetric_eigen();
    let smallest = eigen
        .eigenvalues
        .iter()
        .cloned()
        .fold(f64::INFINITY, f64::min);
    if smallest < 1e-9 {
        return Err(ImpactError::Underdetermined(format!(
            "the free parameters {} are not independently determined by these data \
             (their effects on e_n are indistinguishable)",
            free.iter().map(|p| p.name()).collect::<Vec<_>>().join(",")
        )));
    }
    let inverse = normal_matrix
        .try_inverse()
        .ok_or_else(|| ImpactError::Underdetermined("JᵀJ is singular".into()))?;
    let variance = if n > p { sse / (n - p) as f64 } else { 0.0 };
    let uncertainties = free
        .iter()
        .enumerate()
        .map(|(j, param)| (*param, (variance * inverse[(j, j)]).max(0.0).sqrt()))
        .collect();
    Ok(FitReport {
        values,
        uncertainties,
        rmse,
        n_points: n,
        n_plastic,
        yield_speed,
    })
}

/// A starting `Δγ` for the fit from the data's sticking speed `v_s` (between the fastest stuck
/// point and the slowest rebounding one): the elastic sticking speed of Heß's rule,
/// `v_s = 1.309 (F_c⁵ / (E*² R m³))^{1/6}` with `F_c = (3/2) π Δγ R` (docs/theory.md, "Adhesive
/// impacts"), solved for `Δγ`. The data must show sticking.
fn initial_work_of_adhesion(
    pair: &ContactPair,
    values: &FitValues,
    data: &[Measurement],
) -> Result<f64> {
    let stuck = data
        .iter()
        .filter(|m| m.restitution == 0.0)
        .map(|m| m.speed)
        .fold(0.0_f64, f64::max);
    if stuck == 0.0 {
        return Err(ImpactError::Underdetermined(
            "the data show no sticking (no point with e_n = 0): they do not determine \
             work_of_adhesion; fix it with --work-of-adhesion"
                .into(),
        ));
    }
    let rebounding = data
        .iter()
        .filter(|m| m.restitution > 0.0 && m.speed > stuck)
        .map(|m| m.speed)
        .fold(f64::INFINITY, f64::min);
    let sticking_speed = if rebounding.is_finite() {
        (stuck * rebounding).sqrt()
    } else {
        stuck
    };
    let (e, r, m) = (
        pair.effective_modulus(),
        pair.effective_radius(),
        pair.reduced_mass(),
    );
    // v_s⁶ = C⁶ F_c⁵ / (E*² R m³)  →  F_c = (v_s⁶ E*² R m³ / C⁶)^{1/5}.
    let c: f64 = 1.309;
    let pull_off = (sticking_speed.powi(6) * e * e * r * m.powi(3) / c.powi(6)).powf(0.2);
    let guess = pull_off / (1.5 * PI * r);
    Ok(if values.work_of_adhesion > 0.0 {
        values.work_of_adhesion
    } else {
        guess
    })
}
