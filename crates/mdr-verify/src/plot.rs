//! SVG figures of the tests (plotters): reference curves as lines, simulations as points.

use crate::error::{Result, VerifyError};
use crate::report::{Figure, Style};
use mdr_output::font::register_plot_font;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

const COLOURS: [RGBColor; 6] = [
    RGBColor(0, 0, 0),
    RGBColor(120, 120, 120),
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
];

fn plot_error(path: &Path, e: impl std::fmt::Display) -> VerifyError {
    VerifyError::Plot {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

fn bounds(figure: &Figure) -> ((f64, f64), (f64, f64)) {
    let mut x = (f64::INFINITY, f64::NEG_INFINITY);
    let mut y = (f64::INFINITY, f64::NEG_INFINITY);
    for (px, py) in figure.series.iter().flat_map(|s| s.points.iter()) {
        if px.is_finite() && py.is_finite() {
            x = (x.0.min(*px), x.1.max(*px));
            y = (y.0.min(*py), y.1.max(*py));
        }
    }
    let pad = |(a, b): (f64, f64)| {
        if !a.is_finite() {
            return (0.0, 1.0);
        }
        let d = if b > a {
            0.05 * (b - a)
        } else {
            0.5 * a.abs().max(1.0)
        };
        (a - d, b + d)
    };
    (pad(x), pad(y))
}

/// Write `figure` as `dir/<name>.svg` (atomically, [`mdr_output::write_atomic`]) and return the
/// path.
pub fn write_svg(figure: &Figure, dir: &Path) -> Result<PathBuf> {
    register_plot_font();
    std::fs::create_dir_all(dir).map_err(|e| plot_error(dir, e))?;
    let path = dir.join(format!("{}.svg", figure.name));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(&path, e))?;
        let ((x0, x1), (y0, y1)) = bounds(figure);
        let mut chart = ChartBuilder::on(&root)
            .caption(&figure.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| plot_error(&path, e))?;
        chart
            .configure_mesh()
            .x_desc(figure.x_label.as_str())
            .y_desc(figure.y_label.as_str())
            .draw()
            .map_err(|e| plot_error(&path, e))?;
        for (k, s) in figure.series.iter().enumerate() {
            let colour = COLOURS[k % COLOURS.len()];
            let legend_colour = colour;
            match s.style {
                Style::Line => {
                    chart
                        .draw_series(LineSeries::new(s.points.clone(), colour.stroke_width(2)))
                        .map_err(|e| plot_error(&path, e))?
                        .label(s.label.as_str())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 20, y)], legend_colour)
                        });
                }
                Style::Dashed => {
                    chart
                        .draw_series(DashedLineSeries::new(
                            s.points.clone(),
                            6,
                            4,
                            colour.stroke_width(1),
                        ))
                        .map_err(|e| plot_error(&path, e))?
                        .label(s.label.as_str())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 20, y)], legend_colour)
                        });
                }
                Style::Points => {
                    let marker = k % 3;
                    chart
                        .draw_series(s.points.iter().map(move |&(x, y)| match marker {
                            0 => Circle::new((x, y), 4, colour.stroke_width(1)).into_dyn(),
                            1 => TriangleMarker::new((x, y), 5, colour.stroke_width(1)).into_dyn(),
                            _ => Cross::new((x, y), 4, colour.stroke_width(1)).into_dyn(),
                        }))
                        .map_err(|e| plot_error(&path, e))?
                        .label(s.label.as_str())
                        .legend(move |(x, y)| Circle::new((x + 10, y), 4, legend_colour));
                }
                Style::Measured => {
                    chart
                        .draw_series(s.points.iter().map(|&(x, y)| {
                            EmptyElement::at((x, y))
                                + Rectangle::new([(-4, -4), (4, 4)], BLACK.filled())
                        }))
                        .map_err(|e| plot_error(&path, e))?
                        .label(s.label.as_str())
                        .legend(|(x, y)| {
                            Rectangle::new([(x + 6, y - 4), (x + 14, y + 4)], BLACK.filled())
                        });
                }
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| plot_error(&path, e))?;
        root.present().map_err(|e| plot_error(&path, e))?;
    }
    mdr_output::write_atomic(&path, svg.as_bytes()).map_err(|e| plot_error(&path, e))?;
    Ok(path)
}
