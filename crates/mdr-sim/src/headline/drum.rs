//! Rotating drum: the dynamic angle of repose of the free surface.

use super::fit::linear_fit;
use super::{up, HeadlineReport, HeadlineSample, HeadlineTracker, ParticleView};
use crate::scene::schema::WallKind;
use crate::scene::Scene;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// The drum's axis and radius.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DrumTracker {
    center: [f64; 3],
    axis: [f64; 3],
    radius: f64,
}

impl DrumTracker {
    /// The drum of `scene`: its cylinder wall.
    pub fn new(scene: &Scene) -> Self {
        let drum = scene
            .source
            .walls
            .iter()
            .find(|w| w.kind == WallKind::Cylinder);
        let (center, axis, radius) = drum
            .map(|w| {
                (
                    w.center_m.unwrap_or([0.0; 3]),
                    w.axis.unwrap_or([0.0, 0.0, 1.0]),
                    w.radius_m.unwrap_or(f64::NAN),
                )
            })
            .unwrap_or(([0.0; 3], [0.0, 1.0, 0.0], f64::NAN));
        let a = Vector3::from(axis).normalize();
        Self {
            center,
            axis: [a.x, a.y, a.z],
            radius,
        }
    }
}

impl HeadlineTracker for DrumTracker {
    fn series_names(&self) -> &'static [&'static str] {
        &["surface_angle_deg"]
    }

    fn sample(&self, scene: &Scene, view: &ParticleView<'_>) -> Vec<f64> {
        vec![surface_angle(
            &Vector3::from(self.center),
            &Vector3::from(self.axis),
            self.radius,
            &up(scene),
            view,
        )]
    }

    fn report(&self, _scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport {
        let mut r = HeadlineReport::default();
        let t_end = samples.last().map_or(0.0, |s| s.time);
        let late: Vec<f64> = samples
            .iter()
            .filter(|s| s.time >= 0.5 * t_end && s.values[0].is_finite())
            .map(|s| s.values[0])
            .collect();
        let n = late.len() as f64;
        let mean = late.iter().sum::<f64>() / n;
        let std = (late.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / n).sqrt();
        r.push("dynamic_angle_of_repose_deg", mean);
        r.push("angle_std_deg", std);
        r.text = format!(
            "rotating drum: dynamic angle of repose {mean:.2}° ± {std:.2}° (mean ± s.d. over {} frames of the second half)",
            late.len()
        );
        r
    }
}

/// Angle (degrees) of the free surface in the drum's cross-section: the top particle of each
/// bin across the middle 60 % of the drum, fitted by a line.
fn surface_angle(
    center: &Vector3<f64>,
    axis: &Vector3<f64>,
    radius: f64,
    up: &Vector3<f64>,
    view: &ParticleView<'_>,
) -> f64 {
    let across = axis.cross(up);
    let n = across.norm();
    if n == 0.0 || view.radius.is_empty() {
        return f64::NAN;
    }
    let across = across / n;
    let vertical = across.cross(axis);
    let d = 2.0 * view.radius.iter().sum::<f64>() / view.radius.len() as f64;
    let half = 0.6 * radius;
    let bins = ((2.0 * half / (2.0 * d)).floor() as usize).max(1);
    let mut top = vec![f64::NEG_INFINITY; bins];
    for p in view.position {
        let rel = p - center;
        let u = rel.dot(&across);
        if u.abs() >= half {
            continue;
        }
        let i = (((u + half) / (2.0 * half)) * bins as f64) as usize;
        let w = rel.dot(&vertical);
        top[i.min(bins - 1)] = top[i.min(bins - 1)].max(w);
    }
    let points: Vec<(f64, f64)> = top
        .iter()
        .enumerate()
        .filter(|(_, w)| w.is_finite())
        .map(|(i, w)| (-half + (i as f64 + 0.5) * 2.0 * half / bins as f64, *w))
        .collect();
    if points.len() < 4 {
        return f64::NAN;
    }
    linear_fit(&points).map_or(f64::NAN, |(_, b)| b.atan().abs().to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_angle_of_a_tilted_layer() {
        // Particles on a 30° slope in the x-z plane of a drum with axis y.
        let mut pos = Vec::new();
        for i in -40..=40 {
            let x = i as f64 * 0.002;
            for k in 0..3 {
                pos.push(Vector3::new(
                    x,
                    0.0,
                    x * 30f64.to_radians().tan() - k as f64 * 0.002,
                ));
            }
        }
        let n = pos.len();
        let zero = vec![Vector3::zeros(); n];
        let view = ParticleView {
            position: &pos,
            velocity: &zero,
            radius: &vec![0.001; n],
            mass: &vec![1.0; n],
            contacts: &vec![0; n],
        };
        let a = surface_angle(&Vector3::zeros(), &Vector3::y(), 0.1, &Vector3::z(), &view);
        assert!((a - 30.0).abs() < 0.5, "{a}");
    }
}
