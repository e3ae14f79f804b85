//! Sweeps of whole scenes: the hopper orifice sweep, one run per orifice diameter, and
//! Beverloo's `C` and `k` fitted to the measured flow rates. The sweep is written once
//! ([`orifice_sweep`]) over a runner of one prepared scene: the CPU's [`run_scene`] here
//! ([`run_orifice_sweep`]), the GPU's in `mdr-gpu`.

use super::{run_scene, RunOptions, RunSummary};
use crate::headline::{
    fit_beverloo, mean_diameter, BeverlooFit, HeadlineReport, BEVERLOO_C, BEVERLOO_K,
    BULK_SOLID_FRACTION,
};
use crate::scene::schema::WallKind;
use crate::scene::Scene;
use crate::SimError;
use std::path::Path;

/// What the sweep reads from one run, on either device.
pub trait SweepRun {
    /// The run's headline: its measured mass flow rate and Beverloo's.
    fn headline(&self) -> &HeadlineReport;
    /// Whether the run stopped before its end (an interrupt): the sweep then stops there.
    fn stopped_early(&self) -> bool;
}

impl SweepRun for RunSummary {
    fn headline(&self) -> &HeadlineReport {
        &self.headline
    }

    fn stopped_early(&self) -> bool {
        self.stopped_early
    }
}

/// The result of an orifice sweep whose runs gave `R` (the CPU's [`RunSummary`] by default).
#[derive(Debug, Clone)]
pub struct SweepSummary<R = RunSummary> {
    /// `(orifice diameter (m), measured mass flow rate (kg/s), Beverloo with C = 0.58, k = 1.5)`.
    pub points: Vec<(f64, f64, f64)>,
    /// The fit to the measured rates (`None` if a rate could not be measured).
    pub fit: Option<BeverlooFit>,
    /// Each run's summary, in sweep order.
    pub runs: Vec<R>,
    /// Human-readable summary.
    pub text: String,
    /// Files written by the sweep itself (the CSV of the points).
    pub files: Vec<std::path::PathBuf>,
}

/// Run a hopper scene once per diameter of its `orifice_sweep_m` on the CPU (each run in
/// `out_dir/<name>_D<i>`): [`orifice_sweep`] with [`run_scene`] and `options` (no resume).
/// Resuming is per run: resume a run by writing its diameter and its name `<name>_D<i>` (which
/// its checkpoints' fingerprint holds) into the scene and running it alone.
pub fn run_orifice_sweep(scene: &Scene, options: &RunOptions) -> Result<SweepSummary, SimError> {
    orifice_sweep(scene, &options.out_dir, |one, out_dir| {
        let mut opts = options.clone();
        opts.out_dir = out_dir.to_path_buf();
        opts.resume = None;
        run_scene(one, &opts)
    })
}

/// Run a hopper scene once per diameter of its `orifice_sweep_m` with `run_one` (the scene of
/// one diameter and its folder `out_dir/<name>_D<i>`: the orifice plate's diameter replaced,
/// `orifice_sweep_m` removed, everything else as written), stopping after a run that stopped
/// early; then fit Beverloo's `C` and `k` to the measured flow rates ([`fit_beverloo`]) and write
/// `out_dir/<name>_beverloo.csv`.
pub fn orifice_sweep<R, E>(
    scene: &Scene,
    out_dir: &Path,
    mut run_one: impl FnMut(&Scene, &Path) -> Result<R, E>,
) -> Result<SweepSummary<R>, E>
where
    R: SweepRun,
    E: From<SimError>,
{
    let sweep = scene.source.run.orifice_sweep_m.clone().unwrap_or_default();
    let mut points = Vec::new();
    let mut runs = Vec::new();
    for (i, diameter) in sweep.iter().enumerate() {
        let mut file = scene.source.clone();
        file.run.orifice_sweep_m = None;
        file.run.name = format!("{}_D{i}", scene.source.run.name);
        for w in file
            .walls
            .iter_mut()
            .filter(|w| w.kind == WallKind::OrificePlate)
        {
            w.orifice_diameter_m = Some(*diameter);
        }
        let text =
            toml::to_string(&file).map_err(|e| SimError::Build(format!("orifice sweep: {e}")))?;
        let one =
            crate::scene::validate::parse_scene(&scene.file, &text).map_err(SimError::from)?;
        let summary = run_one(&one, &out_dir.join(&one.name))?;
        let headline = summary.headline();
        let rate = headline.get("mass_flow_rate_kg_per_s").unwrap_or(f64::NAN);
        let beverloo = headline.get("beverloo_kg_per_s").unwrap_or(f64::NAN);
        points.push((*diameter, rate, beverloo));
        let stopped = summary.stopped_early();
        runs.push(summary);
        if stopped {
            break;
        }
    }
    let d = mean_diameter(scene);
    let rho_p = scene.materials[scene.particles[0].material].1.density();
    let bulk = BULK_SOLID_FRACTION * rho_p;
    let g = scene.gravity.norm();
    let fit = fit_beverloo(
        &points.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>(),
        d,
        bulk,
        g,
    );
    let mut text =
        String::from("orifice sweep:\n  D (m)        D/d    W (kg/s)     Beverloo (kg/s)  ratio\n");
    for (dd, w, b) in &points {
        text.push_str(&format!(
            "  {dd:.4e}  {:>5.2}  {w:.4e}   {b:.4e}       {:.3}\n",
            dd / d,
            w / b
        ));
    }
    match fit {
        Some(f) => text.push_str(&format!(
            "  fitted W = C ρ_b √g (D − k d)^{{5/2}} (least squares of W^{{2/5}} against D): C = {:.4}, k = {:.4} \
             (Beverloo et al. 1961: C = {BEVERLOO_C}, k = {BEVERLOO_K}; ρ_b = {BULK_SOLID_FRACTION} ρ_p, d = {d:.4e} m)",
            f.c, f.k
        )),
        None => text.push_str("  fit: not possible (fewer than three measured flow rates)"),
    }
    let csv_path = out_dir.join(format!("{}_beverloo.csv", scene.source.run.name));
    let mut csv = String::from("orifice_diameter_m,mass_flow_rate_kg_per_s,beverloo_kg_per_s\n");
    for (dd, w, b) in &points {
        csv.push_str(&format!("{dd},{w},{b}\n"));
    }
    std::fs::create_dir_all(out_dir).map_err(crate::error::output(out_dir))?;
    mdr_output::write_atomic(&csv_path, csv.as_bytes()).map_err(crate::error::output(&csv_path))?;
    Ok(SweepSummary {
        points,
        fit,
        runs,
        text,
        files: vec![csv_path],
    })
}
