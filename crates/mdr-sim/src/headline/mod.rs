//! Each built-in scene's headline quantity, measured from the particle states, one module per
//! headline behind one trait ([`HeadlineTracker`]: sample, report):
//!
//! - [`column`](mod@column): run-out distance and final height of a column collapse (compared with the
//!   axisymmetric run-out scaling of Lube, Huppert, Sparks & Hallworth, J. Fluid Mech. 508, 175
//!   (2004));
//! - [`hopper`]: steady mass flow rate, fitted over the second half of the time after the plug
//!   opens (compared with the Beverloo correlation `W = C ρ_b √g (D − k d)^{5/2}`, Beverloo,
//!   Leniger & van de Velde, Chem. Eng. Sci. 15, 260 (1961), with `C = 0.58`, `k = 1.5`,
//!   `ρ_b = 0.6 ρ_p`);
//! - [`drum`]: dynamic angle of repose of the free surface of a rotating drum;
//! - [`drop`](mod@drop): coefficient of restitution of the first bounce (compared with the law's energy
//!   route, `MdrLaw::impact`, docs/theory.md §4);
//! - [`funnel`]: spheres left in the funnel against time (the discharge curve), written as a CSV.
//!
//! The fits the headlines share (a least-squares line, Beverloo's `C` and `k`) are in [`fit`];
//! the time series' CSV is written by `series_csv`. The hopper orifice sweep, which runs whole
//! scenes, is the runner's (`run::run_orifice_sweep`).

pub mod column;
pub mod drop;
pub mod drum;
pub mod fit;
pub mod funnel;
pub mod hopper;
mod series_csv;

pub use fit::{fit_beverloo, linear_fit, BeverlooFit};
pub use funnel::{discharge_summary, DischargeSummary};
pub use hopper::{plug_opened_at, BEVERLOO_C, BEVERLOO_K, BULK_SOLID_FRACTION, JAMMING_RATIO};

use crate::scene::{Headline, Scene};
use column::ColumnTracker;
use drop::DropTracker;
use drum::DrumTracker;
use funnel::FunnelTracker;
use hopper::HopperTracker;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// One sample of the headline time series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeadlineSample {
    /// Simulated time (s).
    pub time: f64,
    /// The scene's quantities at that time (see [`Tracker::series_names`]).
    pub values: Vec<f64>,
}

/// One reported number.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeadlineValue {
    /// Name with its unit, e.g. `runout_m`.
    pub name: String,
    /// Value.
    pub value: f64,
}

/// The headline result of a run.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct HeadlineReport {
    /// Named numbers.
    pub values: Vec<HeadlineValue>,
    /// A human-readable summary.
    pub text: String,
}

impl HeadlineReport {
    /// The value named `name`.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|v| v.name == name).map(|v| v.value)
    }

    fn push(&mut self, name: &str, value: f64) {
        self.values.push(HeadlineValue {
            name: name.to_owned(),
            value,
        });
    }
}

/// The state of the particles that the trackers read.
pub struct ParticleView<'a> {
    /// Centres (m).
    pub position: &'a [Vector3<f64>],
    /// Velocities (m/s).
    pub velocity: &'a [Vector3<f64>],
    /// Radii (m).
    pub radius: &'a [f64],
    /// Masses (kg).
    pub mass: &'a [f64],
    /// Touching contacts per particle.
    pub contacts: &'a [u32],
}

/// One scene headline: what it samples along the run and what it reports at the end.
pub trait HeadlineTracker {
    /// Names (with units) of the sampled series, in the order of [`HeadlineTracker::sample`].
    fn series_names(&self) -> &'static [&'static str];

    /// The series' values now.
    fn sample(&self, scene: &Scene, view: &ParticleView<'_>) -> Vec<f64>;

    /// The final report from the samples and the scene.
    fn report(&self, scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport;

    /// Whether [`HeadlineTracker::on_step`] must see every step rather than the sampled ones.
    fn needs_every_step(&self) -> bool {
        false
    }

    /// Per-step update, for a headline that follows events shorter than the sampling interval.
    fn on_step(&mut self, _scene: &Scene, _view: &ParticleView<'_>) {}
}

/// Measures a scene's headline quantity along the run: the scene's [`HeadlineTracker`], chosen
/// by its [`Headline`]. Saved in checkpoints, so its serialised form is part of the checkpoint
/// format.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tracker {
    kind: TrackerKind,
    /// The drop headline's per-step state (kept beside the kind, where the checkpoint format
    /// has it).
    drop: DropTracker,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
enum TrackerKind {
    None,
    Column(ColumnTracker),
    Hopper(HopperTracker),
    Drum(DrumTracker),
    Drop,
    Funnel(FunnelTracker),
}

/// The unit vector against gravity (`+z` without gravity).
fn up(scene: &Scene) -> Vector3<f64> {
    let g = scene.gravity.norm();
    if g > 0.0 {
        -scene.gravity / g
    } else {
        Vector3::z()
    }
}

/// Mean particle diameter of the scene (m).
pub(crate) fn mean_diameter(scene: &Scene) -> f64 {
    2.0 * scene.particles.iter().map(|p| p.radius).sum::<f64>() / scene.particles.len() as f64
}

impl Tracker {
    /// A tracker for `scene`'s headline, set up from the initial placement.
    pub fn new(scene: &Scene) -> Self {
        let kind = match scene.headline {
            Headline::None => TrackerKind::None,
            Headline::Column => TrackerKind::Column(ColumnTracker::new(scene)),
            Headline::Hopper => TrackerKind::Hopper(HopperTracker::new(scene)),
            Headline::Drum => TrackerKind::Drum(DrumTracker::new(scene)),
            Headline::Drop => TrackerKind::Drop,
            Headline::Funnel => TrackerKind::Funnel(FunnelTracker::new(scene)),
        };
        Self {
            kind,
            drop: DropTracker::default(),
        }
    }

    /// The scene's headline, `None` for a scene without one.
    fn headline(&self) -> Option<&dyn HeadlineTracker> {
        match &self.kind {
            TrackerKind::None => None,
            TrackerKind::Column(t) => Some(t),
            TrackerKind::Hopper(t) => Some(t),
            TrackerKind::Drum(t) => Some(t),
            TrackerKind::Drop => Some(&self.drop),
            TrackerKind::Funnel(t) => Some(t),
        }
    }

    /// Names (with units) of the sampled series.
    pub fn series_names(&self) -> &'static [&'static str] {
        self.headline().map_or(&[], |h| h.series_names())
    }

    /// Whether [`Tracker::on_step`] must see every step.
    pub fn needs_every_step(&self) -> bool {
        self.headline().is_some_and(|h| h.needs_every_step())
    }

    /// Per-step update (only the drop needs every step: contacts last a few hundred steps).
    pub fn on_step(&mut self, scene: &Scene, view: &ParticleView<'_>) {
        if let TrackerKind::Drop = self.kind {
            self.drop.on_step(scene, view);
        }
    }

    /// A sample for the time series.
    pub fn sample(&self, scene: &Scene, time: f64, view: &ParticleView<'_>) -> HeadlineSample {
        let values = self
            .headline()
            .map_or_else(Vec::new, |h| h.sample(scene, view));
        HeadlineSample { time, values }
    }

    /// The final report from the samples and the scene.
    pub fn report(&self, scene: &Scene, samples: &[HeadlineSample]) -> HeadlineReport {
        self.headline()
            .map_or_else(HeadlineReport::default, |h| h.report(scene, samples))
    }

    /// Write the headline time series as CSV (`time_s` and one column per series name), e.g.
    /// the funnel's discharge curve; nothing for a scene without series.
    pub fn write_csv(
        &self,
        path: &std::path::Path,
        samples: &[HeadlineSample],
    ) -> std::io::Result<()> {
        series_csv::write_series_csv(path, self.series_names(), samples)
    }

    /// Plot the headline time series with the literature's [`reference_lines`] as
    /// `NAME_headline.svg` in `out`: its path, or `None` (nothing written) for a scene without
    /// series or samples. An error comes with the path it concerns.
    pub fn write_chart(
        &self,
        scene: &Scene,
        samples: &[HeadlineSample],
        out: &std::path::Path,
    ) -> Result<Option<std::path::PathBuf>, (std::path::PathBuf, std::io::Error)> {
        let names = self.series_names();
        if names.is_empty() || samples.is_empty() {
            return Ok(None);
        }
        let series: Vec<(&str, Vec<(f64, f64)>)> = names
            .iter()
            .enumerate()
            .map(|(i, n)| (*n, samples.iter().map(|s| (s.time, s.values[i])).collect()))
            .collect();
        let path = out.join(format!("{}_headline.svg", scene.name));
        let report = self.report(scene, samples);
        crate::output::plot::write_chart(
            &path,
            &format!("{}: headline", scene.name),
            "time (s)",
            &crate::output::plot::axis_label(names),
            &series,
            &reference_lines(&report, samples),
        )
        .map_err(|e| (path.clone(), e))?;
        Ok(Some(path))
    }
}

/// The literature's prediction drawn next to a headline's time series, as labelled lines in the
/// series' units: the column's run-out of Lube et al. (2004) (and its final height, `H = H0`
/// below `a = 0.74`), the hopper's discharged mass at Beverloo's rate from the start of the
/// fitted window. Other headlines have none.
pub fn reference_lines(
    report: &HeadlineReport,
    samples: &[HeadlineSample],
) -> Vec<(String, Vec<(f64, f64)>)> {
    let (Some(first), Some(last)) = (samples.first(), samples.last()) else {
        return Vec::new();
    };
    let span = |v: f64| vec![(first.time, v), (last.time, v)];
    let mut lines = Vec::new();
    if let (Some(r0), Some(lube)) = (
        report.get("initial_radius_m"),
        report.get("lube_2004_normalised_runout"),
    ) {
        lines.push((
            format!("Lube et al. 2004 run-out R0 (1 + {lube:.3})"),
            span(r0 * (1.0 + lube)),
        ));
        if let Some(h) = report
            .get("lube_2004_final_height_m")
            .filter(|h| h.is_finite())
        {
            lines.push(("Lube et al. 2004 height H = H0".to_owned(), span(h)));
        }
    }
    if let (Some(w), Some(start)) = (
        report.get("beverloo_kg_per_s").filter(|w| *w > 0.0),
        report.get("fit_window_start_s"),
    ) {
        if let Some(s0) = samples.iter().find(|s| s.time >= start) {
            let m0 = s0.values[0];
            lines.push((
                format!("Beverloo et al. 1961: W = {w:.3e} kg/s"),
                vec![(s0.time, m0), (last.time, m0 + w * (last.time - s0.time))],
            ));
        }
    }
    lines
}
