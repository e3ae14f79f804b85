//! Funnel discharge: spheres left in the funnel against time (the discharge curve), its steady
//! rate and half-emptying time.

use super::fit::linear_fit;
use super::{up, HeadlineReport, HeadlineSample, HeadlineTracker, ParticleView};
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

/// The heights that split the spheres into in the funnel, discharged and removed, and the time
/// the funnel opens.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FunnelTracker {
    /// Height (along `up`) below which a sphere has left the funnel.
    discharge_z: f64,
    /// Height below which a sphere is removed (`−∞` without a sink).
    delete_z: f64,
    /// Time the plug opens (s): the earliest `removed_at_s` of the walls (0 without one).
    opened_at: f64,
}

impl FunnelTracker {
    /// The funnel of `scene`: its discharge height (default: the lowest sphere's bottom), its
    /// sink and its plug.
    pub fn new(scene: &Scene) -> Self {
        let up = up(scene);
        let lowest = scene
            .particles
            .iter()
            .map(|p| p.position.dot(&up) - p.radius)
            .fold(f64::INFINITY, f64::min);
        Self {
            discharge_z: scene.discharge_height.unwrap_or(lowest),
            delete_z: scene.source.run.delete_below_m.unwrap_or(f64::NEG_INFINITY),
            opened_at: scene
                .walls
                .iter()
                .filter_map(|w| w.removed_at)
                .fold(f64::INFINITY, f64::min)
                .min(scene.duration)
                .max(0.0),
        }
    }
}

impl HeadlineTracker for FunnelTracker {
    fn series_names(&self) -> &'static [&'static str] {
        &["spheres_in_funnel", "spheres_remaining"]
    }

    fn sample(&self, scene: &Scene, view: &ParticleView<'_>) -> Vec<f64> {
        let up = up(scene);
        let (mut inside, mut remaining) = (0usize, 0usize);
        for p in view.position {
            let h = p.dot(&up);
            inside += usize::from(h >= self.discharge_z);
            remaining += usize::from(h >= self.delete_z);
        }
        vec![inside as f64, remaining as f64]
    }

    fn report(&self, scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport {
        let opened_at = self.opened_at;
        let mut r = HeadlineReport::default();
        let n0 = scene.particles.len() as f64;
        let curve: Vec<(f64, f64)> = samples.iter().map(|s| (s.time, s.values[0])).collect();
        let summary = discharge_summary(&curve, opened_at, n0);
        let last = samples
            .last()
            .map_or([n0, n0], |s| [s.values[0], s.values[1]]);
        r.push("spheres", n0);
        r.push("opened_at_s", opened_at);
        r.push("spheres_in_funnel_at_opening", summary.at_opening);
        r.push("spheres_in_funnel_at_end", last[0]);
        r.push("spheres_remaining_at_end", last[1]);
        r.push("discharge_rate_spheres_per_s", summary.rate);
        r.push("half_discharge_time_s", summary.half_time);
        r.text = format!(
            "funnel discharge: {n0} spheres, plug removed at t = {opened_at:.4} s with {:.0} in the funnel\n  \
             steady discharge rate {:.4} spheres/s (fit while 90 % to 30 % of them remain), half emptied \
             {:.4} s after opening\n  at the end (t = {:.4} s): {:.0} in the funnel, {:.0} not removed",
            summary.at_opening,
            summary.rate,
            summary.half_time,
            samples.last().map_or(0.0, |s| s.time),
            last[0],
            last[1]
        );
        r
    }
}

/// Figures of a discharge curve (spheres in the funnel against time).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DischargeSummary {
    /// Spheres in the funnel when it opens (the sample nearest after the opening).
    pub at_opening: f64,
    /// Steady discharge rate (spheres/s): minus the slope of a least-squares line through the
    /// samples after the opening while between 90 % and 30 % of `at_opening` remain (NaN with
    /// fewer than three such samples).
    pub rate: f64,
    /// Time after the opening until half of `at_opening` have left, interpolated linearly
    /// between samples (NaN if it does not happen within the curve).
    pub half_time: f64,
}

/// Summarise a discharge curve `(time, spheres in the funnel)` of a funnel opened at `opened_at`
/// that held `n0` spheres in all.
pub fn discharge_summary(curve: &[(f64, f64)], opened_at: f64, n0: f64) -> DischargeSummary {
    let after: Vec<(f64, f64)> = curve
        .iter()
        .copied()
        .filter(|(t, _)| *t >= opened_at)
        .collect();
    let at_opening = after.first().map_or(n0, |p| p.1);
    let window: Vec<(f64, f64)> = after
        .iter()
        .copied()
        .filter(|(_, n)| *n <= 0.9 * at_opening && *n >= 0.3 * at_opening)
        .collect();
    let rate = linear_fit(&window).map_or(f64::NAN, |(_, b)| -b);
    let half = 0.5 * at_opening;
    let half_time = after
        .windows(2)
        .find(|w| w[0].1 > half && w[1].1 <= half)
        .map_or(f64::NAN, |w| {
            let f = (w[0].1 - half) / (w[0].1 - w[1].1);
            w[0].0 + f * (w[1].0 - w[0].0) - opened_at
        });
    DischargeSummary {
        at_opening,
        rate,
        half_time,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A plugged funnel of 100 spheres opened at t = 2 s and emptying at 10 spheres/s.
    #[test]
    fn discharge_summary_of_a_linear_curve() {
        let curve: Vec<(f64, f64)> = (0..80)
            .map(|i| {
                let t = 0.1 * i as f64;
                (t, (100.0 - 10.0 * (t - 2.0).max(0.0)).max(0.0))
            })
            .collect();
        let s = discharge_summary(&curve, 2.0, 100.0);
        assert!((s.at_opening - 100.0).abs() < 1e-9, "{s:?}");
        assert!((s.rate - 10.0).abs() < 1e-9, "{s:?}");
        assert!((s.half_time - 5.0).abs() < 1e-9, "{s:?}");
    }
}
