//! Line plots in SVG or PNG (chosen by the file extension) with plotters. Text is laid out with
//! the embedded font of `mdr-output` ([`mdr_output::font`]), so PNG output does not depend on
//! the fonts installed on the machine.

use crate::error::{ImpactError, Result};
use mdr_output::font::register_plot_font;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// A curve drawn as a line.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// Legend entry.
    pub label: String,
    /// `(x, y)` points in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Dashed instead of solid.
    pub dashed: bool,
}

/// Points drawn as markers (e.g. measured data).
#[derive(Debug, Clone, PartialEq)]
pub struct Scatter {
    /// Legend entry.
    pub label: String,
    /// `(x, y)` points.
    pub points: Vec<(f64, f64)>,
}

/// A vertical line across the plot (e.g. the yield speed).
#[derive(Debug, Clone, PartialEq)]
pub struct VerticalMarker {
    /// Legend entry.
    pub label: String,
    /// Abscissa.
    pub x: f64,
}

/// A 2D line plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Caption above the plot.
    pub title: String,
    /// Horizontal axis label.
    pub x_label: String,
    /// Vertical axis label.
    pub y_label: String,
    /// Logarithmic horizontal axis.
    pub log_x: bool,
    /// Lines.
    pub lines: Vec<Line>,
    /// Scatter sets.
    pub scatters: Vec<Scatter>,
    /// Vertical markers.
    pub markers: Vec<VerticalMarker>,
    /// Fixed vertical range; automatic when `None`.
    pub y_range: Option<(f64, f64)>,
    /// Size in pixels.
    pub size: (u32, u32),
}

impl Figure {
    /// An empty figure.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            log_x: false,
            lines: Vec::new(),
            scatters: Vec::new(),
            markers: Vec::new(),
            y_range: None,
            size: (900, 600),
        }
    }

    /// Logarithmic horizontal axis.
    pub fn log_x(mut self, yes: bool) -> Self {
        self.log_x = yes;
        self
    }

    /// Add a line.
    pub fn line(mut self, label: impl Into<String>, points: Vec<(f64, f64)>, dashed: bool) -> Self {
        self.lines.push(Line {
            label: label.into(),
            points,
            dashed,
        });
        self
    }

    /// Add a scatter set.
    pub fn scatter(mut self, label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self.scatters.push(Scatter {
            label: label.into(),
            points,
        });
        self
    }

    /// Add a vertical marker.
    pub fn marker(mut self, label: impl Into<String>, x: f64) -> Self {
        self.markers.push(VerticalMarker {
            label: label.into(),
            x,
        });
        self
    }

    /// Fix the vertical range.
    pub fn y_range(mut self, min: f64, max: f64) -> Self {
        self.y_range = Some((min, max));
        self
    }

    fn all_points(&self) -> impl Iterator<Item = &(f64, f64)> {
        self.lines
            .iter()
            .flat_map(|l| l.points.iter())
            .chain(self.scatters.iter().flat_map(|s| s.points.iter()))
            .filter(|(x, y)| x.is_finite() && y.is_finite() && (!self.log_x || *x > 0.0))
    }

    fn ranges(&self) -> Option<((f64, f64), (f64, f64))> {
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &(x, y) in self.all_points() {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        if !(x0.is_finite() && y0.is_finite()) {
            return None;
        }
        if x1 <= x0 {
            x1 = if self.log_x { x0 * 10.0 } else { x0 + 1.0 };
        }
        let (y0, y1) = self.y_range.unwrap_or_else(|| {
            let pad = 0.05 * (y1 - y0).max(1e-12 * y1.abs().max(1.0));
            (y0 - pad, y1 + pad)
        });
        Some(((x0, x1), (y0, y1)))
    }

    /// Draw to `path`: SVG for `.svg`, PNG for `.png`. Written atomically
    /// ([`mdr_output::write_atomic_with`]).
    pub fn save(&self, path: &Path) -> Result<()> {
        register_plot_font();
        let fail = |reason: String| ImpactError::Plot {
            path: path.to_path_buf(),
            reason,
        };
        let extension = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        if !matches!(extension.as_str(), "svg" | "png") {
            return Err(fail(format!(
                "unknown image type `.{extension}`: use .svg or .png"
            )));
        }
        // A drawing failure is reported as a plot error, an I/O failure as an I/O error.
        let mut drawing_failure = None;
        let written = mdr_output::write_atomic_with(path, |temporary| {
            self.render(temporary, &extension).map_err(|reason| {
                drawing_failure = Some(reason.clone());
                std::io::Error::other(reason)
            })
        });
        match (written, drawing_failure) {
            (Ok(()), _) => Ok(()),
            (Err(_), Some(reason)) => Err(fail(reason)),
            (Err(source), None) => Err(ImpactError::Io {
                path: path.to_path_buf(),
                source,
            }),
        }
    }

    /// Draw into the file `path` as `extension` (`svg` or `png`).
    fn render(&self, path: &Path, extension: &str) -> std::result::Result<(), String> {
        if extension == "svg" {
            let root = SVGBackend::new(path, self.size).into_drawing_area();
            self.draw(&root)?;
            root.present().map_err(|e| e.to_string())
        } else {
            let root = BitMapBackend::new(path, self.size).into_drawing_area();
            self.draw(&root)?;
            root.present().map_err(|e| e.to_string())
        }
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String> {
        let text = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        root.fill(&WHITE).map_err(text)?;
        let Some(((x0, x1), (y0, y1))) = self.ranges() else {
            return Err("nothing to plot".into());
        };
        let mut builder = ChartBuilder::on(root);
        builder
            .caption(&self.title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70);
        if self.log_x {
            let mut chart = builder
                .build_cartesian_2d((x0..x1).log_scale(), y0..y1)
                .map_err(text)?;
            chart
                .configure_mesh()
                .x_desc(&self.x_label)
                .y_desc(&self.y_label)
                .label_style(("sans-serif", 15))
                .axis_desc_style(("sans-serif", 17))
                .x_label_formatter(&|x| format!("{x}"))
                .light_line_style(RGBColor(235, 235, 235))
                .draw()
                .map_err(text)?;
            self.draw_series(&mut chart, y0, y1).map_err(text)?;
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 15))
                .draw()
                .map_err(text)?;
        } else {
            let mut chart = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(text)?;
            chart
                .configure_mesh()
                .x_desc(&self.x_label)
                .y_desc(&self.y_label)
                .label_style(("sans-serif", 15))
                .axis_desc_style(("sans-serif", 17))
                .light_line_style(RGBColor(235, 235, 235))
                .draw()
                .map_err(text)?;
            self.draw_series(&mut chart, y0, y1).map_err(text)?;
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 15))
                .draw()
                .map_err(text)?;
        }
        Ok(())
    }

    fn draw_series<'a, DB, X>(
        &self,
        chart: &mut ChartContext<'a, DB, Cartesian2d<X, plotters::coord::types::RangedCoordf64>>,
        y0: f64,
        y1: f64,
    ) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>>
    where
        DB: DrawingBackend + 'a,
        X: Ranged<ValueType = f64>,
    {
        let colours = [
            RGBColor(31, 119, 180),
            RGBColor(214, 39, 40),
            RGBColor(44, 160, 44),
            RGBColor(148, 103, 189),
            RGBColor(255, 127, 14),
            RGBColor(140, 86, 75),
        ];
        for (i, line) in self.lines.iter().enumerate() {
            let style = colours[i % colours.len()].stroke_width(2);
            let points: Vec<(f64, f64)> = line
                .points
                .iter()
                .copied()
                .filter(|(x, y)| x.is_finite() && y.is_finite() && (!self.log_x || *x > 0.0))
                .collect();
            let anchor = if line.dashed {
                chart.draw_series(DashedLineSeries::new(points, 8, 5, style))?
            } else {
                chart.draw_series(LineSeries::new(points, style))?
            };
            anchor
                .label(&line.label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        }
        for (i, set) in self.scatters.iter().enumerate() {
            let colour = [BLACK, RGBColor(120, 120, 120)][i % 2];
            chart
                .draw_series(
                    set.points
                        .iter()
                        .map(|&p| Circle::new(p, 4, colour.filled())),
                )?
                .label(&set.label)
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, colour.filled()));
        }
        for marker in &self.markers {
            let style = RGBColor(90, 90, 90).stroke_width(1);
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(marker.x, y0), (marker.x, y1)],
                    4,
                    4,
                    style,
                ))?
                .label(&marker.label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        }
        Ok(())
    }
}
