//! SVG plots (plotters): the energy books against time, and a scene's headline quantity.

use super::energy::EnergyRow;
use mdr_output::font::register_plot_font;
use mdr_output::write_atomic;
use plotters::prelude::*;
use std::path::Path;

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05)
        .max(hi.abs().max(lo.abs()) * 1e-9)
        .max(1e-300);
    (lo - pad, hi + pad)
}

/// Curves `(label, points)` on one chart, written as SVG to `path` atomically.
pub fn write_lines(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[(&str, Vec<(f64, f64)>)],
) -> std::io::Result<()> {
    write_chart(path, title, x_label, y_label, series, &[])
}

/// Width (px) of the legend column right of the chart: the legend never covers a curve.
const LEGEND_WIDTH: u32 = 280;

/// [`write_lines`] with `references` (the literature's predictions) drawn dashed, in the same
/// units, and every curve named in a legend beside the chart.
pub fn write_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[(&str, Vec<(f64, f64)>)],
    references: &[(String, Vec<(f64, f64)>)],
) -> std::io::Result<()> {
    register_plot_font();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900 + LEGEND_WIDTH, 560)).into_drawing_area();
        let err = |e: &dyn std::fmt::Display| std::io::Error::other(format!("plot: {e}"));
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let (plot_area, legend_area) = root.split_horizontally(900);
        let all = || {
            series
                .iter()
                .flat_map(|s| s.1.iter())
                .chain(references.iter().flat_map(|s| s.1.iter()))
        };
        let (x0, x1) = range(all().map(|p| p.0));
        let (y0, y1) = range(all().map(|p| p.1));
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .draw()
            .map_err(|e| err(&e))?;
        let mut legend: Vec<(String, RGBAColor, bool)> = Vec::new();
        for (i, (label, points)) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    color.stroke_width(2),
                ))
                .map_err(|e| err(&e))?;
            legend.push(((*label).to_owned(), color, false));
        }
        for (label, points) in references {
            let color = BLACK.to_rgba();
            chart
                .draw_series(DashedLineSeries::new(
                    points.iter().copied(),
                    8,
                    5,
                    color.stroke_width(2),
                ))
                .map_err(|e| err(&e))?;
            legend.push((label.clone(), color, true));
        }
        for (k, (label, color, dashed)) in legend.iter().enumerate() {
            let y = 50 + 22 * k as i32;
            let style = color.stroke_width(2);
            let line = if *dashed {
                vec![(6, y), (14, y), (19, y), (27, y)]
            } else {
                vec![(6, y), (30, y)]
            };
            if *dashed {
                for seg in line.chunks(2) {
                    legend_area
                        .draw(&PathElement::new(seg.to_vec(), style))
                        .map_err(|e| err(&e))?;
                }
            } else {
                legend_area
                    .draw(&PathElement::new(line, style))
                    .map_err(|e| err(&e))?;
            }
            legend_area
                .draw(&Text::new(
                    label.clone(),
                    (36, y - 7),
                    ("sans-serif", 13).into_font(),
                ))
                .map_err(|e| err(&e))?;
        }
        root.present().map_err(|e| err(&e))?;
    }
    write_atomic(path, svg.as_bytes())
}

/// The axis label of series named with their unit as a suffix (`runout_m`,
/// `discharged_mass_kg`, `vertical_velocity_m_per_s`, `spheres_in_funnel`): the names in words,
/// each unit once: `runout, height (m)`, `height (m), vertical velocity (m/s)`.
pub fn axis_label(names: &[&str]) -> String {
    const UNITS: [(&str, &str); 6] = [
        ("_m_per_s", "m/s"),
        ("_kg", "kg"),
        ("_deg", "°"),
        ("_s", "s"),
        ("_j", "J"),
        ("_m", "m"),
    ];
    let split = |name: &str| -> (String, Option<&'static str>) {
        for (suffix, unit) in UNITS {
            if let Some(stem) = name.strip_suffix(suffix) {
                return (stem.replace('_', " "), Some(unit));
            }
        }
        (name.replace('_', " "), None)
    };
    let parts: Vec<_> = names.iter().map(|n| split(n)).collect();
    let same_unit = parts.windows(2).all(|w| w[0].1 == w[1].1);
    if same_unit {
        let words: Vec<_> = parts.iter().map(|p| p.0.clone()).collect();
        let unit = parts
            .first()
            .and_then(|p| p.1)
            .map_or(" (count)".to_owned(), |u| format!(" ({u})"));
        return format!("{}{unit}", words.join(", "));
    }
    parts
        .iter()
        .map(|(w, u)| format!("{w} ({})", u.unwrap_or("count")))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The energy books against time.
pub fn write_energy_plot(path: &Path, title: &str, rows: &[EnergyRow]) -> std::io::Result<()> {
    let col = |f: fn(&EnergyRow) -> f64| rows.iter().map(|r| (r.time_s, f(r))).collect::<Vec<_>>();
    let mut series = vec![
        ("kinetic (transl.)", col(|r| r.kinetic_translational_j)),
        ("kinetic (rot.)", col(|r| r.kinetic_rotational_j)),
        ("gravitational", col(|r| r.gravitational_j)),
        (
            "elastic",
            col(|r| r.elastic_normal_j + r.elastic_tangential_j + r.elastic_rolling_j),
        ),
        ("plastic", col(|r| r.plastic_j)),
        ("friction", col(|r| r.friction_j)),
        ("damping", col(|r| r.damping_j)),
        ("rolling", col(|r| r.rolling_j)),
        (
            "stiffness",
            col(|r| r.stiffness_tangential_j + r.stiffness_rolling_j),
        ),
        ("wall work", col(|r| r.wall_work_j)),
        ("balance", col(|r| r.balance_j)),
    ];
    if rows.iter().any(|r| r.adhesive_j != 0.0) {
        series.insert(5, ("adhesive", col(|r| r.adhesive_j)));
    }
    write_lines(path, title, "time (s)", "energy (J)", &series)
}

#[cfg(test)]
mod tests {
    use super::axis_label;

    #[test]
    fn axis_labels_carry_the_units_of_the_series_names() {
        assert_eq!(axis_label(&["runout_m", "height_m"]), "runout, height (m)");
        assert_eq!(axis_label(&["discharged_mass_kg"]), "discharged mass (kg)");
        assert_eq!(
            axis_label(&["height_m", "vertical_velocity_m_per_s"]),
            "height (m), vertical velocity (m/s)"
        );
        assert_eq!(
            axis_label(&["spheres_in_funnel", "spheres_remaining"]),
            "spheres in funnel, spheres remaining (count)"
        );
        assert_eq!(axis_label(&["surface_angle_deg"]), "surface angle (°)");
    }
}
