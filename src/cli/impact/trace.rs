//! `mdr-dem impact trace`: the time history of one impact and its force–indentation loop.

use super::common::{emit, impact_error, positive, save_plot, CommonArgs, Settings};
use anyhow::anyhow;
use clap::Args;
use mdr_impact::output::trace_csv;
use mdr_impact::plot::Figure;
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
}

pub(super) fn run_trace(args: &TraceArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    positive("--v0", args.v0)?;
    if settings.laws.len() != 1 {
        return Err(anyhow!("invalid value for --law: trace takes one law"));
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
