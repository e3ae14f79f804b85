//! One ring run from options to files, shared by `mdr-dem sim ring` and the examples: pick the
//! law, run, and write the time series (`timeseries.csv`), the summary (`summary.json`), the
//! equilibration plot (`equilibration.svg`), the law's `e(v)` next to Bridges'
//! (`restitution.svg`), VTK frames (`frames/ring_NNNN.vtk`) and surface-density images
//! (`frames/sigma_NNNN.png`); the wake pitch angle and wavelength come from the surface density's
//! autocorrelation averaged over the second half of the run (one snapshot per orbit).

use crate::clusters::Clusters;
use crate::diagnostics::{Sample, Summary};
use crate::error::Result;
use crate::gravity::GRAVITATIONAL_CONSTANT;
use crate::law::{BridgesLaw, ConstantRestitution, ImpactPair, MdrRestitution, RestitutionLaw};
use crate::output::{
    write_equilibration_svg, write_json, write_panels_svg, write_samples_csv,
    write_surface_density_png, write_top_view_png, write_vtk_frame_with_clusters, Curve, Panel,
};
use crate::particles::Population;
use crate::run::{RingConfig, RingSimulation};
use crate::wakes::{critical_wavelength, Autocorrelation, SurfaceDensity};
use plotters::style::{BLACK, BLUE, GREEN, RED};
use serde::Serialize;
use std::path::PathBuf;

/// The restitution law of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LawChoice {
    /// MDR elasto-plastic law (energy route).
    Mdr(MdrRestitution),
    /// Bridges et al. (1984).
    Bridges(BridgesLaw),
    /// A constant ε.
    Constant(ConstantRestitution),
}

impl LawChoice {
    /// `mdr`, `bridges` or `constant`.
    pub fn name(&self) -> &'static str {
        match self {
            LawChoice::Mdr(l) => l.name(),
            LawChoice::Bridges(l) => l.name(),
            LawChoice::Constant(l) => l.name(),
        }
    }

    /// The first-impact `e(v)` of `pair`.
    pub fn first_impact(&self, pair: &ImpactPair, speed: f64) -> f64 {
        match self {
            LawChoice::Mdr(l) => l.first_impact(pair, speed),
            LawChoice::Bridges(l) => l.first_impact(pair, speed),
            LawChoice::Constant(l) => l.first_impact(pair, speed),
        }
    }
}

/// The parameters of the law, for the record of the run.
#[derive(Debug, Clone, Serialize)]
pub struct LawRecord {
    /// `mdr`, `bridges` or `constant`.
    pub name: &'static str,
    /// Constant ε (constant law).
    pub eps: Option<f64>,
    /// Young's modulus (Pa, MDR).
    pub youngs_modulus_pa: Option<f64>,
    /// Poisson's ratio (MDR).
    pub poisson_ratio: Option<f64>,
    /// `q_c` (N/m, MDR).
    pub critical_line_load_n_per_m: Option<f64>,
    /// `Θ/E*` (MDR).
    pub hardening_ratio: Option<f64>,
    /// Work of adhesion `Δγ` (J/m², MDR).
    pub work_of_adhesion_j_per_m2: Option<f64>,
}

impl From<&LawChoice> for LawRecord {
    fn from(law: &LawChoice) -> Self {
        let mut record = LawRecord {
            name: law.name(),
            eps: None,
            youngs_modulus_pa: None,
            poisson_ratio: None,
            critical_line_load_n_per_m: None,
            hardening_ratio: None,
            work_of_adhesion_j_per_m2: None,
        };
        match law {
            LawChoice::Mdr(l) => {
                record.youngs_modulus_pa = Some(l.material().youngs_modulus());
                record.poisson_ratio = Some(l.material().poisson_ratio());
                record.critical_line_load_n_per_m = Some(l.model().critical_line_load());
                record.work_of_adhesion_j_per_m2 = Some(l.work_of_adhesion());
                if let mdr_contact::normal::Hardening::Ratio(r) = l.model().hardening() {
                    record.hardening_ratio = Some(r);
                }
            }
            LawChoice::Constant(l) => record.eps = Some(l.value()),
            LawChoice::Bridges(_) => {}
        }
        record
    }
}

/// Everything a run needs.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// Ring settings.
    pub config: RingConfig,
    /// Restitution law.
    pub law: LawChoice,
    /// Length of the run in orbits.
    pub orbits: f64,
    /// Output directory (None: no files).
    pub out: Option<PathBuf>,
    /// Interval between VTK frames in orbits (None: no frames).
    pub frame_orbits: Option<f64>,
    /// Print a progress line every orbit to stderr.
    pub progress: bool,
}

/// What a run reports: its settings and the second-half averages.
#[derive(Debug, Clone, Serialize)]
pub struct RunReport {
    /// Second-half averages (the keys of `--json`).
    #[serde(flatten)]
    pub summary: Summary,
    /// The law and its parameters.
    pub law: LawRecord,
    /// Seed.
    pub seed: u64,
    /// Orbits run.
    pub orbits: f64,
    /// Box side (m).
    pub box_m: f64,
    /// Surface density (kg/m²).
    pub surface_density: f64,
    /// Self-gravity on.
    pub self_gravity: bool,
    /// Gravity solver: `tree`, `direct` or `none`.
    pub gravity: &'static str,
    /// Wake pitch angle from the surface density's autocorrelation (degrees from the azimuthal
    /// direction, positive trailing; docs/rings.md §10); null without wakes (anisotropy below
    /// [`WAKE_MIN_ANISOTROPY`]).
    pub wake_pitch_deg: Option<f64>,
    /// Wake wavelength: distance to the autocorrelation's first side maximum perpendicular to the
    /// wakes (m); null when there is none within half the box.
    pub wake_wavelength_m: Option<f64>,
    /// Axis ratio of the autocorrelation's central ellipse (1: no preferred direction).
    pub wake_anisotropy: Option<f64>,
    /// The clusters of touching particles at the end of the run (`clusters.distribution`:
    /// `[size, count]` pairs by increasing size; [`crate::clusters`]).
    pub clusters: Clusters,
    /// Clusters of at least two particles at the end of the run.
    pub agglomerates: u32,
    /// Fraction of the particles in such clusters at the end of the run.
    pub agglomerated_fraction: f64,
    /// Particles in the largest cluster at the end of the run.
    pub largest_cluster: u32,
    /// The time series (not serialised; written as CSV).
    #[serde(skip)]
    pub samples: Vec<Sample>,
}

/// Level of the autocorrelation that outlines its central ellipse (Salo et al. 2004 use the
/// half-maximum contour).
pub const WAKE_LEVEL: f64 = 0.5;

/// Below this axis ratio of the central ellipse the autocorrelation has no preferred direction
/// (uniform random particles give about 1): no pitch angle or wavelength is reported.
pub const WAKE_MIN_ANISOTROPY: f64 = 1.5;

/// Cell of the surface-density grid (m) for a box of side `side` whose critical wavelength is
/// `critical_wavelength` (`λ_cr = 4π² G Σ / Ω²`, the scale of the wakes: Salo et al. 2004 find
/// wavelengths of 0.5–1 λ_cr): a sixth of `λ_cr`, so that a wake spans several cells while each
/// cell holds a few particles, whose Poisson noise would otherwise hide the correlation between
/// neighbouring cells; at least 5 m, and at most 128 cells per side so that the direct
/// autocorrelation stays cheap. REBOUND's 200 m sheet (λ_cr = 61 m) gets 10 m cells, about four
/// particles each.
pub fn wake_cell(side: f64, critical_wavelength: f64) -> f64 {
    (critical_wavelength / 6.0).max(5.0).max(side / 128.0)
}

/// Run and write the outputs.
pub fn run(options: &RunOptions) -> Result<RunReport> {
    match options.law {
        LawChoice::Mdr(law) => run_with(options, law),
        LawChoice::Bridges(law) => run_with(options, law),
        LawChoice::Constant(law) => run_with(options, law),
    }
}

fn run_with<L: RestitutionLaw>(options: &RunOptions, law: L) -> Result<RunReport> {
    let mut ring = RingSimulation::new(options.config, law)?;
    let frames_dir = options.out.as_ref().map(|d| d.join("frames"));
    let frame_every = options
        .frame_orbits
        .map(|f| (f / options.config.sample_orbits).round().max(1.0) as u64);
    let mut frame_error = None;
    let mut index = 0u64;
    if let (Some(dir), Some(_)) = (&frames_dir, frame_every) {
        write_vtk_frame_with_clusters(
            &dir.join("ring_0000.vtk"),
            ring.particles(),
            &Clusters::of(ring.domain(), ring.particles(), 0.0),
            "ring t = 0 orbits",
        )?;
    }
    let domain = *ring.domain();
    let period = domain.frame().period();
    let sigma = ring.particles().total_mass() / domain.area();
    let cell = wake_cell(
        domain.lx().max(domain.ly()),
        critical_wavelength(domain.frame().omega(), GRAVITATIONAL_CONSTANT, sigma),
    );
    if let (Some(dir), Some(_)) = (&frames_dir, frame_every) {
        let grid = SurfaceDensity::of(&domain, ring.particles(), 0.0, cell);
        write_surface_density_png(&dir.join("sigma_0000.png"), &grid, "t = 0 orbits")?;
        write_top_view_png(
            &dir.join("top_0000.png"),
            &domain,
            ring.particles(),
            "t = 0 orbits",
        )?;
    }
    let mut correlations = Vec::new();
    let samples_per_orbit = (1.0 / options.config.sample_orbits).round().max(1.0) as u64;
    let orbits = options.orbits;
    let progress = options.progress;
    let result = ring.run(options.orbits, |sample, particles| {
        index += 1;
        let last = sample.t_orbits >= orbits - 1e-9;
        let second_half = sample.t_orbits >= 0.5 * orbits - 1e-9;
        if second_half && (index.is_multiple_of(samples_per_orbit) || last) {
            let grid = SurfaceDensity::of(&domain, particles, sample.t_orbits * period, cell);
            correlations.push(grid.autocorrelation());
        }
        if progress && index.is_multiple_of(10) {
            eprintln!(
                "orbit {:6.1}  c {:.3} mm/s  z_rms {:.2} m  FF0 {:.3}  collisions {}  wall {:.1} s",
                sample.t_orbits,
                sample.c * 1e3,
                sample.z_rms,
                sample.filling_factor_z0,
                sample.collisions,
                sample.wall_s
            );
        }
        if let (Some(dir), Some(every)) = (&frames_dir, frame_every) {
            if index.is_multiple_of(every) && frame_error.is_none() {
                let path = dir.join(format!("ring_{:04}.vtk", index / every));
                let title = format!("ring t = {:.2} orbits", sample.t_orbits);
                let grid = SurfaceDensity::of(&domain, particles, sample.t_orbits * period, cell);
                let png = dir.join(format!("sigma_{:04}.png", index / every));
                let top = dir.join(format!("top_{:04}.png", index / every));
                let when = format!("t = {:.2} orbits", sample.t_orbits);
                let clusters = Clusters::of(&domain, particles, sample.t_orbits * period);
                let written = write_vtk_frame_with_clusters(&path, particles, &clusters, &title)
                    .and_then(|_| write_surface_density_png(&png, &grid, &when))
                    .and_then(|_| write_top_view_png(&top, &domain, particles, &when));
                if let Err(e) = written {
                    frame_error = Some(e);
                }
            }
        }
    })?;
    if let Some(e) = frame_error {
        return Err(e);
    }
    let surface_density = ring.particles().total_mass() / ring.domain().area();
    let wakes = Autocorrelation::average(&correlations).map(|c| c.wakes(WAKE_LEVEL));
    let clusters = Clusters::of(ring.domain(), ring.particles(), ring.time());
    let report = RunReport {
        agglomerates: clusters.agglomerates(),
        agglomerated_fraction: clusters.agglomerated_fraction(),
        largest_cluster: clusters.largest(),
        clusters,
        summary: result.summary,
        law: LawRecord::from(&options.law),
        seed: options.config.seed,
        orbits: options.orbits,
        box_m: options.config.box_size,
        surface_density,
        self_gravity: options.config.gravity.is_some(),
        gravity: options.config.gravity.map_or("none", |g| g.solver.name()),
        wake_pitch_deg: wakes
            .filter(|w| w.anisotropy >= WAKE_MIN_ANISOTROPY)
            .map(|w| w.pitch_deg),
        wake_wavelength_m: wakes
            .filter(|w| w.anisotropy >= WAKE_MIN_ANISOTROPY)
            .and_then(|w| w.wavelength_m),
        wake_anisotropy: wakes.map(|w| w.anisotropy),
        samples: result.samples,
    };
    if let Some(dir) = &options.out {
        write_samples_csv(&dir.join("timeseries.csv"), &report.samples)?;
        write_json(&dir.join("summary.json"), &report)?;
        write_equilibration_svg(
            &dir.join("equilibration.svg"),
            &[(options.law.name().to_string(), &report.samples)],
        )?;
        write_restitution_svg(&dir.join("restitution.svg"), &options.law)?;
    }
    Ok(report)
}

/// `e(v)` of `law` for first impacts of equal pairs of 1, 1.6 and 4 m particles (ρ = 400 kg/m³)
/// next to the Bridges law, 10 µm/s to 3 cm/s.
pub fn write_restitution_svg(path: &std::path::Path, law: &LawChoice) -> Result<()> {
    let speeds: Vec<f64> = (0..=120)
        .map(|k| 1e-5 * 10f64.powf(3.5 * k as f64 / 120.0))
        .collect();
    let pair = |r: f64| {
        let m = 400.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
        ImpactPair {
            radius1: r,
            radius2: r,
            mass1: m,
            mass2: m,
        }
    };
    let bridges = BridgesLaw::default();
    let mut curves = vec![Curve {
        label: "Bridges et al. 1984".to_string(),
        points: speeds.iter().map(|&v| (v * 1e3, bridges.at(v))).collect(),
        color: &BLACK,
    }];
    if !matches!(law, LawChoice::Bridges(_)) {
        let colors = [&BLUE, &RED, &GREEN];
        for (k, r) in [1.0, 1.6, 4.0].into_iter().enumerate() {
            curves.push(Curve {
                label: format!("{} (two {r} m particles)", law.name()),
                points: speeds
                    .iter()
                    .map(|&v| (v * 1e3, law.first_impact(&pair(r), v)))
                    .collect(),
                color: colors[k],
            });
            if matches!(law, LawChoice::Constant(_)) {
                break;
            }
        }
    }
    write_panels_svg(
        path,
        &[Panel {
            title: "coefficient of restitution of a first impact".to_string(),
            x_label: "impact speed [mm/s]".to_string(),
            y_label: "e".to_string(),
            curves,
            log_x: true,
        }],
    )
}

/// The surface density of a population, for reports (kg/m²; None for a fixed count).
pub fn population_density(population: Population) -> Option<f64> {
    match population {
        Population::SurfaceDensity(s) => Some(s),
        Population::Count(_) => None,
    }
}
