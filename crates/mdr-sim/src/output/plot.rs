//! SVG plots (plotters): the energy books against time, and a scene's headline quantity.

use super::atomic::write_atomic;
use super::energy::EnergyRow;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::path::Path;
use std::sync::Once;

/// DejaVu Sans (shipped with `mdr-impact`, license next to it), so the plots do not depend on
/// the fonts installed on the machine.
static FONT: &[u8] = include_bytes!("../../../mdr-impact/assets/DejaVuSans.ttf");

fn register_embedded_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // A valid TrueType font: a failure would be a packaging error, reported by plotters as
        // missing glyphs when drawing.
        let _ = register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

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
    register_embedded_font();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 560)).into_drawing_area();
        let err = |e: &dyn std::fmt::Display| std::io::Error::other(format!("plot: {e}"));
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let (x0, x1) = range(series.iter().flat_map(|s| s.1.iter().map(|p| p.0)));
        let (y0, y1) = range(series.iter().flat_map(|s| s.1.iter().map(|p| p.1)));
        let mut chart = ChartBuilder::on(&root)
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
        for (i, (label, points)) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    color.stroke_width(2),
                ))
                .map_err(|e| err(&e))?
                .label(*label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    write_atomic(path, svg.as_bytes())
}

/// The energy books against time.
pub fn write_energy_plot(path: &Path, title: &str, rows: &[EnergyRow]) -> std::io::Result<()> {
    let col = |f: fn(&EnergyRow) -> f64| rows.iter().map(|r| (r.time_s, f(r))).collect::<Vec<_>>();
    let series = vec![
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
    write_lines(path, title, "time (s)", "energy (J)", &series)
}
