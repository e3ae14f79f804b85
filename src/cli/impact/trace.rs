//! `mdr-dem impact trace`: the time history of one impact and its force–indentation loop.

use super::common::{emit, impact_error, positive, save_plot, CommonArgs, Settings};
use anyhow::anyhow;
use clap::Args;
use mdr_impact::output::trace_csv;
use mdr_impact::plot::Figure;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Flags of `impact trace`.
#[derive(Debug, Clone, Args)]
pub struct TraceArgs {
    #[command(flatten)]
    common: CommonArgs,
    /// Impact speed (m/s).
    #[arg(long, allow_negative_numbers = true)]
    v0: f64,
    /// CSV output file, or `-` for stdout [default: stdout].
    #[arg(long, value_name = "PATH|-")]
    csv: Option<PathBuf>,
    /// Force–indentation plot (.svg or .png).
    #[arg(long, value_name = "PATH")]
    plot: Option<PathBuf>,
    /// JSON summary of the impact (e_n, d_max_m, pull_off_force_n, release_overlap_m, stuck,
    /// …), or `-` for stdout (then --csv must name a file).
    #[arg(long, value_name = "PATH|-")]
    json: Option<PathBuf>,
}

/// The `impact trace --json` summary (keys are a contract). NaN (a stuck impact's contact time
/// and release overlap) is written as `null`.
#[derive(Debug, Serialize)]
struct TraceSummary {
    v0_m_per_s: f64,
    e_n: f64,
    d_max_m: f64,
    d_residual_m: f64,
    contact_time_s: f64,
    f_max_n: f64,
    /// Largest tensile force during the impact (N, ≥ 0).
    pull_off_force_n: f64,
    /// Overlap at which the contact let go (m).
    release_overlap_m: f64,
    stuck: bool,
    work_of_adhesion_j_per_m2: f64,
}

pub(super) fn run_trace(args: &TraceArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    positive("--v0", args.v0)?;
    if settings.laws.len() != 1 {
        return Err(anyhow!("invalid value for --law: trace takes one law"));
    }
    let stdout = Path::new("-");
    if args.json.as_deref() == Some(stdout) && args.csv.as_deref().unwrap_or(stdout) == stdout {
        return Err(anyhow!(
            "invalid value for --json: `-` needs the CSV in a file (--csv PATH)"
        ));
    }
    let (outcome, points) = settings
        .impact(settings.laws[0], args.v0)
        .trace()
        .map_err(impact_error("--v0"))?;
    emit(
        args.csv.as_deref().unwrap_or(Path::new("-")),
        &trace_csv(&points),
    )?;
    eprintln!(
        "e_n = {:.6}, d_max = {:.4} µm, residual = {:.4} µm, t_c = {:.3} µs, F_max = {:.2} N",
        outcome.normal_restitution,
        outcome.max_overlap * 1e6,
        outcome.residual_overlap * 1e6,
        outcome.contact_time * 1e6,
        outcome.peak_force
    );
    if outcome.stuck || settings.work_of_adhesion > 0.0 {
        eprintln!(
            "stuck = {}, pull-off force = {:.4e} N, let go at overlap {:.4e} m",
            outcome.stuck, outcome.pull_off_force, outcome.release_overlap
        );
    }
    if let Some(path) = &args.json {
        let summary = TraceSummary {
            v0_m_per_s: args.v0,
            e_n: outcome.normal_restitution,
            d_max_m: outcome.max_overlap,
            d_residual_m: outcome.residual_overlap,
            contact_time_s: outcome.contact_time,
            f_max_n: outcome.peak_force,
            pull_off_force_n: outcome.pull_off_force,
            release_overlap_m: outcome.release_overlap,
            stuck: outcome.stuck,
            work_of_adhesion_j_per_m2: settings.work_of_adhesion,
        };
        let mut text = serde_json::to_string_pretty(&summary)?;
        text.push('\n');
        emit(path, &text)?;
    }
    if let Some(path) = &args.plot {
        let loop_points = points.iter().map(|p| (p.overlap * 1e6, p.force)).collect();
        let figure = Figure::new(
            format!(
                "Force–indentation at v0 = {} m/s ({}), e_n = {:.4}",
                args.v0,
                settings.laws[0].name(),
                outcome.normal_restitution
            ),
            "indentation d (µm)",
            "normal force F (N)",
        )
        .line("loading and unloading", loop_points, false)
        .marker(
            format!("residual depth {:.3} µm", outcome.residual_overlap * 1e6),
            outcome.residual_overlap * 1e6,
        );
        save_plot(&figure, path)?;
    }
    Ok(())
}
