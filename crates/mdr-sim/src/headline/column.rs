//! Column collapse: run-out distance and final height, compared with the axisymmetric run-out
//! scaling of Lube, Huppert, Sparks & Hallworth, J. Fluid Mech. 508, 175 (2004).

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

    fn report(&self, _scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport {
        let Self { r0, h0, .. } = *self;
        let mut r = HeadlineReport::default();
        let Some(last) = samples.last() else {
            return r;
        };
        let (runout, height) = (last.values[0], last.values[1]);
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
        r.text = format!(
            "column collapse: aspect ratio a = H0/R0 = {a:.3} (R0 = {r0:.4e} m, H0 = {h0:.4e} m)\n  \
             run-out R = {runout:.4e} m, (R − R0)/R0 = {spread:.3} (Lube et al. 2004: {lube:.3})\n  \
             final height at the axis H = {height:.4e} m, H/R0 = {:.3} ({})",
            height / r0,
            if a < 0.74 {
                format!("Lube et al. 2004 for a < 0.74: H = H0 = {h0:.4e} m, ratio {:.3}", height / h0)
            } else {
                "no height correlation for a ≥ 0.74 here".to_owned()
            }
        );
        r
    }
}
