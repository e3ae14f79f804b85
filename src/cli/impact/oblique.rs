//! `mdr-dem impact oblique`: oblique impacts on a half-space with friction and rotation.

use super::common::{emit, impact_error, number_list, positive, save_plot, CommonArgs, Settings};
use anyhow::anyhow;
use clap::{Args, ValueEnum};
use mdr_impact::output::oblique_csv;
use mdr_impact::plot::Figure;
use mdr_impact::{ImpactOutcome, Method, NormalSpec, Sweep, TangentialSpec, DEFAULT_SPRINGS};
use std::path::{Path, PathBuf};

/// Tangential law names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TangentialName {
    /// MDR spring bed with per-spring stick/slip (needs --method springs).
    Springs,
    /// O(1) incremental Mindlin law with a Coulomb cap.
    Mindlin,
}

/// Flags of `impact oblique`.
#[derive(Debug, Clone, Args)]
pub struct ObliqueArgs {
    #[command(flatten)]
    common: CommonArgs,
    /// Impact speed (m/s).
    #[arg(long, allow_negative_numbers = true)]
    speed: f64,
    /// Impact angles from the normal (degrees, in [0, 90)), comma-separated.
    #[arg(long, default_value = "5,10,20,30,40,50,60,70,80,85")]
    angles: String,
    /// Tangential law [default: springs, the MDR spring bed; mindlin with --method closed].
    #[arg(long, value_enum)]
    tangential: Option<TangentialName>,
    /// Initial angular velocity (rad/s), positive in the sense of rolling forward.
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0)]
    spin: f64,
    /// CSV output file, or `-` for stdout [default: stdout].
    #[arg(long, value_name = "PATH|-")]
    csv: Option<PathBuf>,
    /// Plot of e_n, e_t and the rebound angle against the impact angle (.svg or .png).
    #[arg(long, value_name = "PATH")]
    plot: Option<PathBuf>,
}

pub(super) fn run_oblique(args: &ObliqueArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    positive("--speed", args.speed)?;
    if !args.spin.is_finite() {
        return Err(anyhow!(
            "invalid value for --spin: {} (must be finite)",
            args.spin
        ));
    }
    if !settings.half_space {
        return Err(anyhow!(
            "invalid value for --target-radius: oblique impacts are computed on a half-space; \
             omit --target-radius and --target-density"
        ));
    }
    if settings.laws.len() != 1 {
        return Err(anyhow!("invalid value for --law: oblique takes one law"));
    }
    let angles = number_list("--angles", &args.angles)?;
    for &a in &angles {
        if !(a.is_finite() && (0.0..90.0).contains(&a)) {
            return Err(anyhow!(
                "invalid value for --angles: {a} (angles from the normal in [0, 90) degrees)"
            ));
        }
    }
    let law = settings.laws[0];
    let tangential = match args.tangential {
        Some(TangentialName::Springs) => TangentialSpec::SpringBed,
        Some(TangentialName::Mindlin) => TangentialSpec::Mindlin,
        None if matches!(law, NormalSpec::Mdr(_)) && settings.method != Some(Method::Closed) => {
            TangentialSpec::SpringBed
        }
        None => TangentialSpec::Mindlin,
    };
    let method = match (settings.method, tangential) {
        (Some(m), _) => m,
        (None, TangentialSpec::SpringBed) => Method::Springs {
            springs: args.common.springs.unwrap_or(DEFAULT_SPRINGS),
        },
        (None, TangentialSpec::Mindlin) => Method::Closed,
    };
    if tangential == TangentialSpec::SpringBed && !matches!(method, Method::Springs { .. }) {
        return Err(anyhow!(
            "invalid value for --tangential: springs needs --method springs (or use --tangential mindlin)"
        ));
    }
    let template = settings
        .impact(law, args.speed)
        .method(method)
        .tangential(tangential)
        .spin(args.spin);
    let outcomes = Sweep::angles(template, &angles)
        .progress(settings.progress())
        .run()
        .map_err(impact_error("--speed"))?;
    emit(
        args.csv.as_deref().unwrap_or(Path::new("-")),
        &oblique_csv(&outcomes),
    )?;
    if let Some(path) = &args.plot {
        let series = |f: &dyn Fn(&ImpactOutcome) -> f64| {
            outcomes
                .iter()
                .map(|o| (o.angle_degrees, f(o)))
                .collect::<Vec<_>>()
        };
        let figure = Figure::new(
            format!(
                "Oblique impact at {} m/s, μ = {} ({} tangential law)",
                args.speed,
                settings.mu,
                tangential.name()
            ),
            "impact angle from the normal (degrees)",
            "coefficient of restitution",
        )
        .line("e_n", series(&|o| o.normal_restitution), false)
        .line(
            "e_t = |v_t,out| / |v_t,in|",
            series(&|o| o.tangential_restitution.unwrap_or(f64::NAN)),
            false,
        )
        .line(
            "rebound angle / impact angle",
            series(&|o| o.rebound_angle_degrees / o.angle_degrees),
            true,
        );
        save_plot(&figure, path)?;
    }
    Ok(())
}
