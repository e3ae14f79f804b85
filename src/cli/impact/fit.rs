//! `mdr-dem impact fit`: least-squares fit of `q_c`, `Θ/E*` and the scale to measured
//! restitution data.

use super::common::{impact_error, load_data, save_plot, CommonArgs, Settings};
use anyhow::anyhow;
use clap::Args;
use mdr_impact::fit::{fit, predict, FitParameter, FitValues};
use mdr_impact::plot::Figure;
use mdr_impact::{log_spaced, ImpactError, NormalSpec};
use std::path::PathBuf;

/// Flags of `impact fit`.
#[derive(Debug, Clone, Args)]
pub struct FitArgs {
    #[command(flatten)]
    common: CommonArgs,
    /// Measured data, CSV with header `v0_m_per_s,e_n`.
    #[arg(long, value_name = "FILE.csv")]
    data: PathBuf,
    /// Parameters to fit, comma-separated subset of qc,theta_ratio,scale,work_of_adhesion
    /// (work_of_adhesion needs data that show sticking: points with e_n = 0).
    #[arg(long, default_value = "qc,theta_ratio,scale")]
    free: String,
    /// Print one JSON object (keys q_c, theta_ratio, scale, work_of_adhesion, rmse, n_points,
    /// and uncertainties).
    #[arg(long)]
    json: bool,
    /// Plot of the data and the fitted curve (.svg or .png).
    #[arg(long, value_name = "PATH")]
    plot: Option<PathBuf>,
}

pub(super) fn run_fit(args: &FitArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    if settings.laws != [NormalSpec::Mdr(settings.mdr)] {
        return Err(anyhow!(
            "invalid value for --law: the fit adjusts the MDR law (--law mdr, not --elastic)"
        ));
    }
    let free = args
        .free
        .split(',')
        .map(FitParameter::parse)
        .collect::<Result<Vec<_>, _>>()
        .map_err(impact_error("--data"))?;
    let data = load_data(&args.data)?;
    let hardening = match settings.mdr.hardening() {
        mdr_contact::normal::Hardening::Ratio(r) => r,
        mdr_contact::normal::Hardening::Modulus(t) => t / settings.pair.effective_modulus(),
    };
    let initial = FitValues {
        q_c: settings.mdr.critical_line_load(),
        theta_ratio: hardening,
        scale: settings.scale,
        work_of_adhesion: settings.work_of_adhesion,
    };
    let report = fit(&settings.pair, initial, &free, &data).map_err(|e| match e {
        ImpactError::Underdetermined(_) => anyhow!("--data: {e}"),
        other => impact_error("--data")(other),
    })?;
    let sigma = |p: FitParameter| {
        report
            .uncertainties
            .iter()
            .find(|(q, _)| *q == p)
            .map(|(_, s)| *s)
    };
    if args.json {
        let mut object = serde_json::json!({
            "q_c": report.values.q_c,
            "theta_ratio": report.values.theta_ratio,
            "scale": report.values.scale,
            "work_of_adhesion": report.values.work_of_adhesion,
            "rmse": report.rmse,
            "n_points": report.n_points,
        });
        let mut uncertainty = serde_json::Map::new();
        for (p, key) in [
            (FitParameter::CriticalLineLoad, "q_c"),
            (FitParameter::HardeningRatio, "theta_ratio"),
            (FitParameter::Scale, "scale"),
            (FitParameter::WorkOfAdhesion, "work_of_adhesion"),
        ] {
            if let Some(s) = sigma(p) {
                uncertainty.insert(key.into(), s.into());
            }
        }
        object["uncertainty"] = uncertainty.into();
        object["yield_speed_m_per_s"] = report.yield_speed.into();
        println!("{object}");
    } else {
        let show = |name: &str, value: f64, p: FitParameter| match sigma(p) {
            Some(s) => println!("{name:>12} = {value:.6e} ± {s:.2e}"),
            None => println!("{name:>12} = {value:.6e} (fixed)"),
        };
        show(
            "q_c (N/m)",
            report.values.q_c,
            FitParameter::CriticalLineLoad,
        );
        show(
            "theta_ratio",
            report.values.theta_ratio,
            FitParameter::HardeningRatio,
        );
        show("scale", report.values.scale, FitParameter::Scale);
        show(
            "Δγ (J/m²)",
            report.values.work_of_adhesion,
            FitParameter::WorkOfAdhesion,
        );
        println!("{:>12} = {:.3e}", "rmse", report.rmse);
        println!("{:>12} = {}", "n_points", report.n_points);
        println!(
            "{:>12} = {:.4} m/s ({} points above it)",
            "yield speed", report.yield_speed, report.n_plastic
        );
    }
    if let Some(path) = &args.plot {
        let (lo, hi) = data.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), m| {
            (lo.min(m.speed), hi.max(m.speed))
        });
        let speeds = log_spaced(lo / 2.0, hi * 2.0, 200);
        let model = predict(&settings.pair, &report.values, &speeds)?;
        let figure = Figure::new(
            "Fit of the MDR law to measured restitution",
            "impact speed v0 (m/s)",
            "coefficient of restitution e",
        )
        .log_x(true)
        .line(
            format!(
                "fit: q_c = {:.3e} N/m, Θ/E* = {:.3}, scale = {:.3}",
                report.values.q_c, report.values.theta_ratio, report.values.scale
            ),
            speeds.into_iter().zip(model).collect(),
            false,
        )
        .scatter(
            "measured",
            data.iter().map(|m| (m.speed, m.restitution)).collect(),
        )
        .marker(
            format!("yield speed {:.3} m/s", report.yield_speed),
            report.yield_speed,
        );
        save_plot(&figure, path)?;
    }
    Ok(())
}
