//! Outputs of a ring run, each written atomically ([`mdr_output`]): the time series
//! (CSV), the summary (JSON), particle frames (legacy VTK poly data, readable by ParaView) and
//! plots (SVG).

use crate::diagnostics::Sample;
use crate::error::{Result, RingError};
use crate::particles::Particles;
use mdr_output::font::register_plot_font;
use plotters::prelude::*;
use std::path::Path;

/// Write `bytes` to `path` atomically ([`mdr_output::write_atomic`]), with this crate's error.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    mdr_output::write_atomic(path, bytes).map_err(|source| RingError::Io {
        path: path.display().to_string(),
        source,
    })
}

fn output_error(path: &Path, reason: impl ToString) -> RingError {
    RingError::Output {
        path: path.display().to_string(),
        reason: reason.to_string(),
    }
}

/// The time series as CSV, one row per sample.
pub fn write_samples_csv(path: &Path, samples: &[Sample]) -> Result<()> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    for s in samples {
        writer.serialize(s).map_err(|e| output_error(path, e))?;
    }
    let bytes = writer.into_inner().map_err(|e| output_error(path, e))?;
    write_atomic(path, &bytes)
}

/// Any serialisable value as pretty JSON.
pub fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    let text = serde_json::to_string_pretty(value).map_err(|e| output_error(path, e))?;
    write_atomic(path, text.as_bytes())
}

/// The particles as legacy-VTK poly data: one vertex per particle with point data `radius`
/// (m) and `velocity` (m/s, rotating frame, shear included).
pub fn write_vtk_frame(path: &Path, particles: &Particles, title: &str) -> Result<()> {
    write_vtk(path, particles, None, title)
}

/// [`write_vtk_frame`] with each particle's cluster of touching particles
/// ([`crate::clusters::Clusters`]): the point fields `cluster` (the cluster's index) and
/// `cluster_size` (its number of particles) besides `radius` and `velocity`.
pub fn write_vtk_frame_with_clusters(
    path: &Path,
    particles: &Particles,
    clusters: &crate::clusters::Clusters,
    title: &str,
) -> Result<()> {
    write_vtk(path, particles, Some(clusters), title)
}

fn write_vtk(
    path: &Path,
    particles: &Particles,
    clusters: Option<&crate::clusters::Clusters>,
    title: &str,
) -> Result<()> {
    use vtkio::model::*;
    let n = particles.len();
    let points: Vec<f64> = particles
        .position
        .iter()
        .flat_map(|p| [p.x, p.y, p.z])
        .collect();
    let velocity: Vec<f64> = particles
        .velocity
        .iter()
        .flat_map(|v| [v.x, v.y, v.z])
        .collect();
    let vertices: Vec<u32> = (0..n as u32).flat_map(|i| [1, i]).collect();
    let vtk = Vtk {
        version: Version::new_legacy(4, 2),
        title: title.to_string(),
        byte_order: ByteOrder::BigEndian,
        file_path: None,
        data: DataSet::inline(PolyDataPiece {
            points: points.into(),
            verts: Some(VertexNumbers::Legacy {
                num_cells: n as u32,
                vertices,
            }),
            data: Attributes {
                point: {
                    let mut fields = vec![
                        Attribute::scalars("radius", 1).with_data(particles.radius.clone()),
                        Attribute::vectors("velocity").with_data(velocity),
                    ];
                    if let Some(c) = clusters {
                        fields.push(Attribute::scalars("cluster", 1).with_data(c.label.clone()));
                        fields.push(
                            Attribute::scalars("cluster_size", 1).with_data(c.size_of.clone()),
                        );
                    }
                    fields
                },
                cell: vec![],
            },
            ..Default::default()
        }),
    };
    let mut bytes = Vec::new();
    vtk.write_legacy(&mut bytes)
        .map_err(|e| output_error(path, format!("{e:?}")))?;
    write_atomic(path, &bytes)
}

/// One named curve of a plot.
pub struct Curve<'a> {
    /// Legend label.
    pub label: String,
    /// `(x, y)` points.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub color: &'a RGBColor,
}

/// A panel: title, axis labels, curves, logarithmic axes.
pub struct Panel<'a> {
    /// Caption.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// Curves.
    pub curves: Vec<Curve<'a>>,
    /// Logarithmic x axis.
    pub log_x: bool,
}

fn range_of(points: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in points.filter(|v| v.is_finite() && (!log || *v > 0.0)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if log {
        return (lo, hi.max(lo * 1.01));
    }
    let pad = 0.05 * (hi - lo).max(hi.abs() * 1e-3).max(1e-12);
    (lo.min(0.0), hi + pad)
}

/// Panels stacked vertically in one SVG file.
pub fn write_panels_svg(path: &Path, panels: &[Panel]) -> Result<()> {
    register_plot_font();
    let mut svg = String::new();
    {
        let height = 300 * panels.len().max(1) as u32;
        let root = SVGBackend::with_string(&mut svg, (900, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| output_error(path, e))?;
        let areas = root.split_evenly((panels.len().max(1), 1));
        for (panel, area) in panels.iter().zip(areas) {
            draw_panel(panel, &area).map_err(|e| output_error(path, e))?;
        }
        root.present().map_err(|e| output_error(path, e))?;
    }
    write_atomic(path, svg.as_bytes())
}

type DrawResult = std::result::Result<(), Box<dyn std::error::Error>>;

fn draw_panel(panel: &Panel, area: &DrawingArea<SVGBackend, plotters::coord::Shift>) -> DrawResult {
    let xs = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter().map(|p| p.0));
    let ys = panel
        .curves
        .iter()
        .flat_map(|c| c.points.iter().map(|p| p.1));
    let (x0, x1) = range_of(xs, panel.log_x);
    let (y0, y1) = range_of(ys, false);
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(&panel.title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70);
    macro_rules! finish {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(panel.x_label.as_str())
                .y_desc(panel.y_label.as_str())
                .draw()?;
            for curve in &panel.curves {
                let color = *curve.color;
                chart
                    .draw_series(LineSeries::new(
                        curve.points.iter().copied(),
                        color.stroke_width(2),
                    ))?
                    .label(curve.label.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2))
                    });
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()?;
        }};
    }
    if panel.log_x {
        finish!(builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1)?);
    } else {
        finish!(builder.build_cartesian_2d(x0..x1, y0..y1)?);
    }
    Ok(())
}

/// The equilibration plot of one or more runs: `c(t)`, `z_rms(t)` and the mid-plane filling
/// factor against time in orbits.
pub fn write_equilibration_svg(path: &Path, runs: &[(String, &[Sample])]) -> Result<()> {
    const COLORS: [RGBColor; 6] = [BLUE, RED, GREEN, MAGENTA, CYAN, BLACK];
    let panel = |title: &str, y: &str, f: fn(&Sample) -> f64| Panel {
        title: title.to_string(),
        x_label: "t [orbits]".to_string(),
        y_label: y.to_string(),
        curves: runs
            .iter()
            .enumerate()
            .map(|(k, (label, samples))| Curve {
                label: label.clone(),
                points: samples.iter().map(|s| (s.t_orbits, f(s))).collect(),
                color: &COLORS[k % COLORS.len()],
            })
            .collect(),
        log_x: false,
    };
    write_panels_svg(
        path,
        &[
            panel("velocity dispersion", "c [mm/s]", |s| s.c * 1e3),
            panel("vertical thickness (mass-weighted)", "z_rms [m]", |s| {
                s.z_rms
            }),
            panel("mid-plane filling factor", "FF(z=0)", |s| {
                s.filling_factor_z0
            }),
        ],
    )
}

/// The surface density of the patch as a PNG image (grey scale, white = dense, `Σ/⟨Σ⟩` from 0 to
/// 2.5; x radial to the right, y azimuthal upwards, axes in metres), the way ring papers show
/// gravitational wakes. Written to a temporary file in the same directory and renamed.
pub fn write_surface_density_png(
    path: &Path,
    grid: &crate::wakes::SurfaceDensity,
    title: &str,
) -> Result<()> {
    write_png_atomic(path, |tmp| draw_surface_density(tmp, grid, title))
}

/// The patch seen from above as a PNG image: every particle a filled disc of its radius, drawn
/// from the lowest to the highest (x radial to the right, y azimuthal upwards, axes in metres),
/// the way ring simulation papers show gravitational wakes (Salo et al. 2004, Fig. 1). Written to
/// a temporary file in the same directory and renamed.
pub fn write_top_view_png(
    path: &Path,
    domain: &crate::boundary::ShearingBox,
    particles: &Particles,
    title: &str,
) -> Result<()> {
    write_png_atomic(path, |tmp| draw_top_view(tmp, domain, particles, title))
}

/// Draw with `draw` into a temporary `.png` beside `path`, then rename it to `path`
/// ([`mdr_output::write_atomic_with`]).
fn write_png_atomic(path: &Path, draw: impl FnOnce(&Path) -> DrawResult) -> Result<()> {
    register_plot_font();
    // A drawing failure is reported as an output error, an I/O failure as an I/O error.
    let mut drawing_failure = None;
    let written = mdr_output::write_atomic_with(path, |temporary| {
        draw(temporary).map_err(|e| {
            let reason = e.to_string();
            drawing_failure = Some(reason.clone());
            std::io::Error::other(reason)
        })
    });
    match (written, drawing_failure) {
        (Ok(()), _) => Ok(()),
        (Err(_), Some(reason)) => Err(output_error(path, reason)),
        (Err(source), None) => Err(RingError::Io {
            path: path.display().to_string(),
            source,
        }),
    }
}

type PatchChart<'a> = ChartContext<
    'a,
    BitMapBackend<'a>,
    plotters::coord::cartesian::Cartesian2d<
        plotters::coord::types::RangedCoordf64,
        plotters::coord::types::RangedCoordf64,
    >,
>;

/// A PNG of the `lx × ly` patch centred on the origin (x radial to the right, y azimuthal
/// upwards, axes in metres) with `caption`; `draw` fills the plotting area.
fn draw_patch(
    path: &Path,
    height: u32,
    caption: String,
    (lx, ly): (f64, f64),
    draw: impl FnOnce(&mut PatchChart<'_>) -> DrawResult,
) -> DrawResult {
    let root = BitMapBackend::new(path, (640, height)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(-0.5 * lx..0.5 * lx, -0.5 * ly..0.5 * ly)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x (radial) [m]")
        .y_desc("y (azimuthal) [m]")
        .draw()?;
    draw(&mut chart)?;
    root.present()?;
    Ok(())
}

fn draw_top_view(
    path: &Path,
    domain: &crate::boundary::ShearingBox,
    particles: &Particles,
    title: &str,
) -> DrawResult {
    let (lx, ly) = (domain.lx(), domain.ly());
    let caption = format!("particles from above, {title}");
    draw_patch(path, 640, caption, (lx, ly), |chart| {
        let pixels = chart.plotting_area().get_pixel_range();
        let per_metre = f64::from(pixels.0.end - pixels.0.start) / lx;
        let mut order: Vec<usize> = (0..particles.len()).collect();
        order.sort_by(|&a, &b| particles.position[a].z.total_cmp(&particles.position[b].z));
        let z_scale = particles
            .position
            .iter()
            .map(|p| p.z.abs())
            .fold(1e-9, f64::max);
        chart.draw_series(order.into_iter().map(|i| {
            let p = particles.position[i];
            // Higher particles lighter, so that overlapping discs stay apart.
            let grey = (90.0 + 100.0 * (p.z / z_scale)).clamp(0.0, 200.0) as u8;
            let size = (particles.radius[i] * per_metre).round().max(1.0) as i32;
            Circle::new((p.x, p.y), size, RGBColor(grey, grey, grey).filled())
        }))?;
        Ok(())
    })
}

fn draw_surface_density(
    path: &Path,
    grid: &crate::wakes::SurfaceDensity,
    title: &str,
) -> DrawResult {
    let (lx, ly) = (grid.dx * grid.nx as f64, grid.dy * grid.ny as f64);
    let caption = format!("surface density, {title}");
    draw_patch(path, 600, caption, (lx, ly), |chart| {
        let mean = grid.mean().max(f64::MIN_POSITIVE);
        chart.draw_series((0..grid.ny).flat_map(|iy| {
            (0..grid.nx).map(move |ix| {
                let level = (grid.sigma[iy * grid.nx + ix] / mean / 2.5).clamp(0.0, 1.0);
                let grey = (255.0 * level).round() as u8;
                let x0 = -0.5 * lx + ix as f64 * grid.dx;
                let y0 = -0.5 * ly + iy as f64 * grid.dy;
                Rectangle::new(
                    [(x0, y0), (x0 + grid.dx, y0 + grid.dy)],
                    RGBColor(grey, grey, grey).filled(),
                )
            })
        }))?;
        Ok(())
    })
}
