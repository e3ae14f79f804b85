//! Column collapse: run-out distance and final height, compared with the axisymmetric run-out
//! scaling of Lube, Huppert, Sparks & Hallworth, J. Fluid Mech. 508, 175 (2004), whose figures
//! are those of the final deposit: the report says whether, and from when, the deposit was at
//! rest ([`rest_time`]: run-out and height unchanged within [`REST_TOLERANCE`] of `R0` over the
//! last [`REST_WINDOW_FREE_FALL_TIMES`] free-fall times of the column).

use super::{HeadlineReport, HeadlineSample, HeadlineTracker, ParticleView};
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

/// The column's axis, floor and initial size, from the initial placement.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ColumnTracker {
    axis: [f64; 2],
    floor: f64,
    r0: f64,
    h0: f64,
}

impl ColumnTracker {
    /// The column of `scene`'s initial placement.
    pub fn new(scene: &Scene) -> Self {
        let n = scene.particles.len() as f64;
        let cx = scene.particles.iter().map(|p| p.position.x).sum::<f64>() / n;
        let cy = scene.particles.iter().map(|p| p.position.y).sum::<f64>() / n;
        let floor = scene
            .particles
            .iter()
            .map(|p| p.position.z - p.radius)
            .fold(f64::INFINITY, f64::min);
        let r0 = scene
            .particles
            .iter()
            .map(|p| ((p.position.x - cx).hypot(p.position.y - cy)) + p.radius)
            .fold(0.0, f64::max);
        let h0 = scene
            .particles
            .iter()
            .map(|p| p.position.z + p.radius - floor)
            .fold(0.0, f64::max);
        Self {
            axis: [cx, cy],
            floor,
            r0,
            h0,
        }
    }
}

/// The deposit is at rest once its run-out and its height at the axis stay within this fraction
/// of the initial radius `R0` (for the built-in column 0.46 mm, about a tenth of a diameter) ...
pub const REST_TOLERANCE: f64 = 0.005;

/// ... for at least this many free-fall times `√(2 H0/g)` of the column (the collapse itself
/// lasts about three, Lube et al. 2004) until the end of the run.
pub const REST_WINDOW_FREE_FALL_TIMES: f64 = 3.0;

/// The earliest sample time from which every later `(run-out, height)` sample stays within
/// `tolerance` of every other, provided that the run went on for `window` after it; `None` when
/// the deposit was still changing within `window` of the end.
pub fn rest_time(samples: &[HeadlineSample], tolerance: f64, window: f64) -> Option<f64> {
    let last = samples.last()?;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let mut rest = None;
    for sample in samples.iter().rev() {
        if !sample.values[..2].iter().all(|v| v.is_finite()) {
            break;
        }
        for k in 0..2 {
            lo[k] = lo[k].min(sample.values[k]);
            hi[k] = hi[k].max(sample.values[k]);
        }
        if (0..2).any(|k| hi[k] - lo[k] > tolerance) {
            break;
        }
        rest = Some(sample.time);
    }
    rest.filter(|t| last.time - t >= window)
}

/// The `q` quantile of `v` (nearest rank); NaN for no values.
fn percentile(mut v: Vec<f64>, q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let i = ((v.len() - 1) as f64 * q).round() as usize;
    v[i]
}

impl HeadlineTracker for ColumnTracker {
    fn series_names(&self) -> &'static [&'static str] {
        &["runout_m", "height_m"]
    }

    fn sample(&self, _scene: &Scene, view: &ParticleView<'_>) -> Vec<f64> {
        let Self {
            axis, floor, r0, ..
        } = *self;
        let runout = percentile(
            view.position
                .iter()
                .zip(view.radius)
                .map(|(p, r)| (p.x - axis[0]).hypot(p.y - axis[1]) + r)
                .collect(),
            0.99,
        );
        let near_axis: Vec<f64> = view
            .position
            .iter()
            .zip(view.radius)
            .filter(|(p, _)| (p.x - axis[0]).hypot(p.y - axis[1]) < 0.5 * r0)
            .map(|(p, r)| p.z + r - floor)
            .collect();
        let height = near_axis.iter().copied().fold(0.0, f64::max);
        vec![runout, height]
    }

    fn report(&self, scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport {
        let Self { r0, h0, .. } = *self;
        let mut r = HeadlineReport::default();
        let Some(last) = samples.last() else {
            return r;
        };
        let (runout, height) = (last.values[0], last.values[1]);
        let g = scene.gravity.norm();
        let window = if g > 0.0 {
            REST_WINDOW_FREE_FALL_TIMES * (2.0 * h0 / g).sqrt()
        } else {
            f64::INFINITY
        };
        let rest = rest_time(samples, REST_TOLERANCE * r0, window);
        let a = h0 / r0;
        let spread = (runout - r0) / r0;
        // Lube et al. (2004), axisymmetric collapse: ΔR/R0 = 1.24 a (a < 1.7),
        // 1.6 a^{1/2} (a > 1.7); for a < 0.74 the failure surface does not reach the
        // top of the column, which keeps its height: H∞ = H0.
        let lube = if a < 1.7 { 1.24 * a } else { 1.6 * a.sqrt() };
        let lube_height = if a < 0.74 { h0 } else { f64::NAN };
        r.push("initial_radius_m", r0);
        r.push("initial_height_m", h0);
        r.push("aspect_ratio", a);
        r.push("runout_m", runout);
        r.push("final_height_m", height);
        r.push("normalised_runout", spread);
        r.push("lube_2004_normalised_runout", lube);
        r.push("lube_2004_final_height_m", lube_height);
        r.push("at_rest", if rest.is_some() { 1.0 } else { 0.0 });
        r.push("rest_time_s", rest.unwrap_or(f64::NAN));
        r.push("rest_window_s", window);
        let bond = bond_number(scene);
        if let Some(bo) = bond {
            r.push("bond_number", bo);
        }
        let rest_text = match rest {
            Some(t) => format!(
                "at rest from t = {t:.3} s (run-out and height within {:.1} % of R0 until the end \
                 at {:.3} s)",
                100.0 * REST_TOLERANCE,
                last.time
            ),
            None => format!(
                "NOT at rest at the end ({:.3} s): run-out or height still changed by more than \
                 {:.1} % of R0 within the last {window:.3} s; the deposit is not final",
                last.time,
                100.0 * REST_TOLERANCE
            ),
        };
        r.text = format!(
            "column collapse: aspect ratio a = H0/R0 = {a:.3} (R0 = {r0:.4e} m, H0 = {h0:.4e} m)\n  \
             run-out R = {runout:.4e} m, (R − R0)/R0 = {spread:.3} (Lube et al. 2004: {lube:.3})\n  \
             final height at the axis H = {height:.4e} m, H/R0 = {:.3} ({})\n  {rest_text}",
            height / r0,
            if a < 0.74 {
                format!("Lube et al. 2004 for a < 0.74: H = H0 = {h0:.4e} m, ratio {:.3}", height / h0)
            } else {
                "no height correlation for a ≥ 0.74 here".to_owned()
            }
        );
        if let Some(bo) = bond {
            r.text.push_str(&format!(
                "\n  cohesive: Bond number Bo = F_c/(m g) = {bo:.3} (JKR pull-off of two mean spheres over \
                 one's weight; the run-out shrinks as Bo grows, Abramian, Staron & Lagrée 2020)"
            ));
        }
        r
    }
}

/// The Bond number of a scene with the adhesive law and gravity: the JKR pull-off force of two
/// spheres of the mean radius `R`, `F_c = (3/2) π Δγ R*` with `R* = R/2`, over the weight
/// `m g` of one (the first particle's material): `Bo = 9 Δγ / (16 ρ g R²)`. `None` without
/// adhesion or gravity.
pub fn bond_number(scene: &Scene) -> Option<f64> {
    let g = scene.gravity.norm();
    let first = scene.particles.first()?;
    let gamma = scene
        .contact
        .pair_work_of_adhesion(first.material, first.material);
    if gamma <= 0.0 || g <= 0.0 {
        return None;
    }
    let n = scene.particles.len() as f64;
    let radius = scene.particles.iter().map(|p| p.radius).sum::<f64>() / n;
    let mass = scene.materials[first.material].1.sphere_mass(radius);
    let pull_off = 1.5 * std::f64::consts::PI * gamma * 0.5 * radius;
    Some(pull_off / (mass * g))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn samples(series: &[(f64, f64, f64)]) -> Vec<HeadlineSample> {
        series
            .iter()
            .map(|&(time, runout, height)| HeadlineSample {
                time,
                values: vec![runout, height],
            })
            .collect()
    }

    #[test]
    fn rest_starts_where_both_series_stop_changing() {
        let s = samples(&[
            (0.0, 1.0, 1.0),
            (0.1, 1.5, 0.9),
            (0.2, 1.80, 0.8),
            (0.3, 1.81, 0.8),
            (0.4, 1.805, 0.801),
            (0.5, 1.81, 0.8),
        ]);
        // From 0.2 s the run-out spans 1.80..1.81 and the height 0.8..0.801.
        assert_eq!(rest_time(&s, 0.011, 0.2), Some(0.2));
        // A tighter tolerance moves the start later: from 0.3 s the run-out spans 0.005.
        assert_eq!(rest_time(&s, 0.006, 0.1), Some(0.3));
        assert_eq!(rest_time(&s, 0.004, 0.0), Some(0.5));
        // The window must fit between the rest time and the end.
        assert_eq!(rest_time(&s, 0.011, 0.35), None);
    }

    #[test]
    fn a_height_that_still_changes_is_not_rest() {
        let s = samples(&[(0.0, 1.0, 1.0), (0.1, 1.0, 0.9), (0.2, 1.0, 0.8)]);
        assert_eq!(rest_time(&s, 0.05, 0.0), Some(0.2));
        assert_eq!(rest_time(&s, 0.05, 0.1), None);
        let spreading = samples(&[(0.0, 1.0, 1.0), (0.1, 1.1, 1.0), (0.2, 1.2, 1.0)]);
        assert_eq!(rest_time(&spreading, 0.05, 0.1), None);
        let broken = samples(&[(0.0, 1.0, 1.0), (0.1, f64::NAN, 1.0), (0.2, 1.0, 1.0)]);
        assert_eq!(rest_time(&broken, 0.05, 0.1), None);
        assert_eq!(rest_time(&[], 0.05, 0.0), None);
    }
}
