//! The hopper orifice sweep on the GPU ([`run_gpu_orifice_sweep`]): `mdr_sim`'s sweep
//! ([`orifice_sweep`]: the same scene per diameter, run folders, points, fit, text and CSV) with
//! each run on the device ([`run_gpu_scene`]).

use crate::device::GpuContext;
use crate::run::{gpu_run_support, run_gpu_scene, GpuRunError, GpuRunOptions, GpuRunSummary};
use mdr_sim::headline::HeadlineReport;
use mdr_sim::run::{orifice_sweep, SweepRun, SweepSummary};
use mdr_sim::Scene;

impl SweepRun for GpuRunSummary {
    fn headline(&self) -> &HeadlineReport {
        &self.headline
    }

    fn stopped_early(&self) -> bool {
        self.stopped_early
    }
}

/// Run a hopper scene once per diameter of its `orifice_sweep_m` on `ctx`'s device, each run in
/// `options.out_dir/<name>_D<i>` with `options` (no resume: a run of the sweep is resumed alone,
/// its diameter and name written into the scene), then fit Beverloo's `C` and `k` and write
/// `<name>_beverloo.csv` as the CPU sweep does. The scene is checked ([`gpu_run_support`])
/// before the first run.
pub fn run_gpu_orifice_sweep(
    ctx: &GpuContext,
    scene: &Scene,
    options: &GpuRunOptions,
) -> Result<SweepSummary<GpuRunSummary>, GpuRunError> {
    gpu_run_support(scene)?;
    orifice_sweep(scene, &options.out_dir, |one, out_dir| {
        let mut opts = options.clone();
        opts.out_dir = out_dir.to_path_buf();
        opts.resume = None;
        run_gpu_scene(ctx, one, &opts)
    })
}
