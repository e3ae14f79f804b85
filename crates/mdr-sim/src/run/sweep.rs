//! Sweeps of whole scenes: the hopper orifice sweep, one run per orifice diameter, and
//! Beverloo's `C` and `k` fitted to the measured flow rates.

use super::{run_scene, RunOptions, RunSummary};
use crate::headline::{
    fit_beverloo, mean_diameter, BeverlooFit, BEVERLOO_C, BEVERLOO_K, BULK_SOLID_FRACTION,
};
use crate::scene::schema::WallKind;
use crate::scene::Scene;
use crate::SimError;

/// The result of an orifice sweep.
#[derive(Debug, Clone)]
pub struct SweepSummary {
    /// `(orifice diameter (m), measured mass flow rate (kg/s), Beverloo with C = 0.58, k = 1.5)`.
    pub points: Vec<(f64, f64, f64)>,
    /// The fit to the measured rates (`None` if a rate could not be measured).
    pub fit: Option<BeverlooFit>,
    /// Each run's summary, in sweep order.
    pub runs: Vec<RunSummary>,
    /// Human-readable summary.
    pub text: String,
    /// Files written by the sweep itself (the CSV of the points).
    pub files: Vec<std::path::PathBuf>,
}

/// Run a hopper scene once per diameter of its `orifice_sweep_m` (each run in
/// `out_dir/<name>_D<i>`, the orifice plate's diameter replaced, everything else as written),
/// then fit Beverloo's `C` and `k` to the measured flow rates ([`fit_beverloo`]) and write
/// `<name>_beverloo.csv`. Resuming is per run: resume a run by writing its diameter into the
/// scene and running it alone.
pub fn run_orifice_sweep(scene: &Scene, options: &RunOptions) -> Result<SweepSummary, SimError> {
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
        let one = crate::scene::validate::parse_scene(&scene.file, &text)?;
        let mut opts = options.clone();
        opts.out_dir = options.out_dir.join(&one.name);
        opts.resume = None;
        let summary = run_scene(&one, &opts)?;
        let rate = summary
            .headline
            .get("mass_flow_rate_kg_per_s")
            .unwrap_or(f64::NAN);
        let beverloo = summary
            .headline
            .get("beverloo_kg_per_s")
            .unwrap_or(f64::NAN);
        points.push((*diameter, rate, beverloo));
        let stopped = summary.stopped_early;
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
    let csv_path = options
        .out_dir
        .join(format!("{}_beverloo.csv", scene.source.run.name));
    let mut csv = String::from("orifice_diameter_m,mass_flow_rate_kg_per_s,beverloo_kg_per_s\n");
    for (dd, w, b) in &points {
        csv.push_str(&format!("{dd},{w},{b}\n"));
    }
    std::fs::create_dir_all(&options.out_dir).map_err(crate::error::output(&options.out_dir))?;
    mdr_output::write_atomic(&csv_path, csv.as_bytes()).map_err(crate::error::output(&csv_path))?;
    Ok(SweepSummary {
        points,
        fit,
        runs,
        text,
        files: vec![csv_path],
    })
}
