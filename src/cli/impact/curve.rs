//! `mdr-dem impact curve`: restitution against impact speed for one or several laws, and the
//! curve machinery (sweep, table, figure) that `impact fig2` shares.

use super::common::{
    emit, impact_error, load_data, number_list, positive, save_plot, CommonArgs, Settings,
};
use anyhow::anyhow;
use clap::Args;
use mdr_impact::output::{curve_csv, Measurement};
use mdr_impact::plot::Figure;
use mdr_impact::{log_spaced, ImpactOutcome, NormalSpec, Sweep};
use std::path::{Path, PathBuf};

/// Flags of `impact curve`.
#[derive(Debug, Clone, Args)]
pub struct CurveArgs {
    #[command(flatten)]
    common: CommonArgs,
    /// Impact speeds (m/s), comma-separated.
    #[arg(long, conflicts_with_all = ["v_min", "v_max", "points"])]
    velocities: Option<String>,
    /// Smallest speed of a log-spaced sweep (m/s).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.01)]
    v_min: f64,
    /// Largest speed of a log-spaced sweep (m/s).
    #[arg(long, allow_negative_numbers = true, default_value_t = 30.0)]
    v_max: f64,
    /// Number of log-spaced speeds.
    #[arg(long, default_value_t = 200)]
    points: usize,
    /// CSV output file, or `-` for stdout (several laws: one file per law, `NAME_<law>.csv`).
    #[arg(long, value_name = "PATH|-")]
    csv: Option<PathBuf>,
    /// Plot file (.svg or .png).
    #[arg(long, value_name = "PATH")]
    plot: Option<PathBuf>,
    /// Measured `v0_m_per_s,e_n` points to overlay on the plot.
    #[arg(long, value_name = "FILE")]
    data: Option<PathBuf>,
}

fn speeds_of(args: &CurveArgs) -> anyhow::Result<Vec<f64>> {
    if let Some(list) = &args.velocities {
        let speeds = number_list("--velocities", list)?;
        for &v in &speeds {
            positive("--velocities", v)?;
        }
        return Ok(speeds);
    }
    positive("--v-min", args.v_min)?;
    positive("--v-max", args.v_max)?;
    if args.v_max <= args.v_min {
        return Err(anyhow!(
            "invalid value for --v-max: {} must exceed --v-min {}",
            args.v_max,
            args.v_min
        ));
    }
    if args.points < 2 {
        return Err(anyhow!(
            "invalid value for --points: {} (at least 2)",
            args.points
        ));
    }
    Ok(log_spaced(args.v_min, args.v_max, args.points))
}

/// One law's curve.
pub(super) struct Curve {
    pub(super) law: NormalSpec,
    pub(super) outcomes: Vec<ImpactOutcome>,
    pub(super) yield_speed: f64,
}

pub(super) fn compute_curves(settings: &Settings, speeds: &[f64]) -> anyhow::Result<Vec<Curve>> {
    settings
        .laws
        .iter()
        .map(|&law| {
            let template = settings.impact(law, 1.0);
            let outcomes = Sweep::speeds(template, speeds)
                .progress(settings.progress())
                .run()
                .map_err(impact_error("--velocities"))?;
            let yield_speed = template
                .yield_speed()
                .map_err(impact_error("--velocities"))?;
            Ok(Curve {
                law,
                outcomes,
                yield_speed,
            })
        })
        .collect()
}

fn law_label(law: &NormalSpec) -> String {
    match law {
        NormalSpec::Mdr(m) => {
            let theta = match m.hardening() {
                mdr_contact::normal::Hardening::Ratio(r) => format!("{r}"),
                mdr_contact::normal::Hardening::Modulus(t) => format!("{t:.3e} Pa"),
            };
            format!(
                "MDR (q_c = {:.3e} N/m, Θ/E* = {theta})",
                m.critical_line_load()
            )
        }
        NormalSpec::Thornton(t) => format!("Thornton (p_y = {:.3e} Pa)", t.yield_pressure()),
        NormalSpec::Hertz => "Hertz".into(),
        NormalSpec::Declared(law) => {
            let values = law
                .declaration()
                .params
                .iter()
                .zip(law.values())
                .map(|(p, v)| format!("{} = {v:.3e} {}", p.symbol, p.unit))
                .collect::<Vec<_>>();
            format!("{} ({})", law.name(), values.join(", "))
        }
    }
}

pub(super) fn curve_figure(
    curves: &[Curve],
    scale: f64,
    data: Option<&[Measurement]>,
    with_raw: bool,
) -> Figure {
    let mut figure = Figure::new(
        "Coefficient of restitution vs impact speed",
        "impact speed v0 (m/s)",
        "coefficient of restitution e",
    )
    .log_x(true);
    for curve in curves {
        let label = law_label(&curve.law);
        let scaled = curve
            .outcomes
            .iter()
            .map(|o| (o.speed, scale * o.normal_restitution))
            .collect();
        figure = figure.line(format!("{label}, scaled × {scale}"), scaled, false);
        if with_raw {
            let raw = curve
                .outcomes
                .iter()
                .map(|o| (o.speed, o.normal_restitution))
                .collect();
            figure = figure.line(format!("{label}, raw"), raw, true);
        }
    }
    for curve in curves {
        if curve.yield_speed.is_finite() {
            figure = figure.marker(
                format!(
                    "yield speed {} = {:.3} m/s",
                    curve.law.name(),
                    curve.yield_speed
                ),
                curve.yield_speed,
            );
        }
    }
    if let Some(points) = data {
        figure = figure.scatter(
            "measured",
            points.iter().map(|m| (m.speed, m.restitution)).collect(),
        );
    }
    let low = curves
        .iter()
        .flat_map(|c| c.outcomes.iter().map(|o| scale * o.normal_restitution))
        .chain(data.unwrap_or(&[]).iter().map(|m| m.restitution))
        .fold(1.0_f64, f64::min);
    figure.y_range((low - 0.05).clamp(0.0, 0.9), 1.05)
}

pub(super) fn print_table(curves: &[Curve], scale: f64) {
    for curve in curves {
        println!("{}", law_label(&curve.law));
        println!("  yield speed: {:.4} m/s", curve.yield_speed);
        println!(
            "  {:>10}  {:>8}  {:>10}  {:>11}  {:>11}  {:>12}  {:>10}",
            "v0 (m/s)", "e_n", "e_n scaled", "d_max (µm)", "d_res (µm)", "t_c (µs)", "F_max (N)"
        );
        for o in &curve.outcomes {
            println!(
                "  {:>10.4}  {:>8.5}  {:>10.5}  {:>11.4}  {:>11.4}  {:>12.3}  {:>10.2}",
                o.speed,
                o.normal_restitution,
                scale * o.normal_restitution,
                o.max_overlap * 1e6,
                o.residual_overlap * 1e6,
                o.contact_time * 1e6,
                o.peak_force
            );
        }
    }
}

pub(super) fn run_curve(args: &CurveArgs) -> anyhow::Result<()> {
    let settings = Settings::resolve(&args.common)?;
    let speeds = speeds_of(args)?;
    let data = args.data.as_deref().map(load_data).transpose()?;
    if settings.laws.len() > 1 && args.csv.as_deref() == Some(Path::new("-")) {
        return Err(anyhow!(
            "invalid value for --csv: several laws write one file each; give a file path, not `-`"
        ));
    }
    let curves = compute_curves(&settings, &speeds)?;
    match &args.csv {
        Some(path) if curves.len() == 1 => {
            emit(path, &curve_csv(&curves[0].outcomes, settings.scale))?
        }
        Some(path) => {
            for curve in &curves {
                let stem = path.file_stem().unwrap_or_default().to_string_lossy();
                let file = path.with_file_name(format!("{stem}_{}.csv", curve.law.name()));
                emit(&file, &curve_csv(&curve.outcomes, settings.scale))?;
            }
        }
        None => print_table(&curves, settings.scale),
    }
    if let Some(path) = &args.plot {
        let figure = curve_figure(&curves, settings.scale, data.as_deref(), curves.len() == 1);
        save_plot(&figure, path)?;
    }
    Ok(())
}
