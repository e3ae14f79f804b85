//! Many impacts in parallel (rayon). Each impact is independent and deterministic, so the results
//! come back in input order and do not depend on the number of threads.

use crate::error::Result;
use crate::impact::{Impact, ImpactOutcome};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Whether a sweep may show a progress bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Progress {
    /// Never.
    #[default]
    Hidden,
    /// On stderr, if stderr is a terminal and the sweep runs longer than about a second.
    Auto,
}

/// How long a sweep runs before its progress bar appears.
const PROGRESS_DELAY: Duration = Duration::from_secs(1);

/// A list of impacts to run in parallel.
///
/// ```
/// use mdr_impact::{Impact, Sweep, log_spaced};
/// let speeds = log_spaced(0.01, 10.0, 5);
/// let outcomes = Sweep::speeds(Impact::paper(1.0), &speeds).run().unwrap();
/// assert_eq!(outcomes.len(), 5);
/// assert!(outcomes[0].normal_restitution > outcomes[4].normal_restitution);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    impacts: Vec<Impact>,
    progress: Progress,
}

impl Sweep {
    /// Any list of impacts.
    pub fn new(impacts: Vec<Impact>) -> Self {
        Self {
            impacts,
            progress: Progress::Hidden,
        }
    }

    /// `template` at each of `speeds` (m/s).
    pub fn speeds(template: Impact, speeds: &[f64]) -> Self {
        Self::new(speeds.iter().map(|&v| template.speed(v)).collect())
    }

    /// `template` at each of `angles` (degrees from the normal).
    pub fn angles(template: Impact, angles: &[f64]) -> Self {
        Self::new(angles.iter().map(|&a| template.angle_degrees(a)).collect())
    }

    /// Progress display.
    pub fn progress(mut self, progress: Progress) -> Self {
        self.progress = progress;
        self
    }

    /// The impacts.
    pub fn impacts(&self) -> &[Impact] {
        &self.impacts
    }

    /// Run every impact; results in input order. On failure, the error of the first failing
    /// impact in input order.
    pub fn run(&self) -> Result<Vec<ImpactOutcome>> {
        for impact in &self.impacts {
            impact.validate()?;
        }
        let bar = ProgressBar::with_draw_target(
            Some(self.impacts.len() as u64),
            ProgressDrawTarget::hidden(),
        );
        if let Ok(style) = ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] {pos}/{len} impacts, ETA {eta}",
        ) {
            bar.set_style(style);
        }
        let may_show = self.progress == Progress::Auto && std::io::stderr().is_terminal();
        let shown = AtomicBool::new(false);
        let start = Instant::now();
        let results: Vec<Result<ImpactOutcome>> = self
            .impacts
            .par_iter()
            .map(|impact| {
                let outcome = impact.run();
                bar.inc(1);
                if may_show
                    && start.elapsed() > PROGRESS_DELAY
                    && !shown.swap(true, Ordering::Relaxed)
                {
                    bar.set_draw_target(ProgressDrawTarget::stderr());
                }
                outcome
            })
            .collect();
        bar.finish_and_clear();
        results.into_iter().collect()
    }
}

/// `count` speeds spaced evenly in log between `min` and `max` (inclusive); `count ≥ 2`.
pub fn log_spaced(min: f64, max: f64, count: usize) -> Vec<f64> {
    if count < 2 {
        return vec![min];
    }
    let (a, b) = (min.ln(), max.ln());
    (0..count)
        .map(|i| (a + (b - a) * i as f64 / (count - 1) as f64).exp())
        .collect()
}
