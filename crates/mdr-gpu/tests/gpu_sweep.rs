//! The hopper's orifice sweep on the GPU ([`run_gpu_orifice_sweep`]) against the CPU sweep of
//! the same scene ([`run_orifice_sweep`]): the same points (diameter, mass flow rate,
//! Beverloo's rate), the same fit and table, the same run folders and CSV columns. Negative
//! control: one diameter changed on the GPU alone moves its rate. An interrupted GPU sweep stops
//! after the run it was in, with that run's checkpoint, which resumes alone as the interrupt's
//! message says. The device tests need a Vulkan (or Metal/DX12) device with 64-bit floats (on
//! Linux without a GPU, Mesa's lavapipe).

#[path = "common/bodies.rs"]
mod bodies;
#[path = "common/hopper_sweep.rs"]
mod hopper_sweep;

use bodies::{body_differences, same_bits};
use hopper_sweep::{hopper_sweep_text, write_hopper_sweep, DIAMETERS, NAME};
use mdr_gpu::{run_gpu_orifice_sweep, run_gpu_scene, GpuContext, GpuRunOptions, GpuRunSummary};
use mdr_sim::run::{run_orifice_sweep, CheckpointData, SweepSummary};
use mdr_sim::scene::load_scene;
use mdr_sim::{RunOptions, Scene};
use std::path::{Path, PathBuf};

/// The largest GPU − CPU difference of the runs' end positions, in diameters: measured on
/// lavapipe, 3.8e-13 after the 2,499 steps of a run (4.8e-14 to 3.8e-13 over the three runs;
/// velocities within 5.6e-14 m/s). A flow rate is the slope of the discharged mass sampled
/// every 5 ms, which moves only when a sphere crosses the discharge height on the other side
/// of a sample: differences this small move none, and the rates, Beverloo's rates, the fit and
/// the table are the CPU sweep's bit for bit (measured: 0). The last diameter 0.5 mm wider on
/// the GPU alone moves that run's rate by 0.135 of it.
const POSITION_TOLERANCE: f64 = 1e-12;

/// The spheres' diameter (m).
const DIAMETER: f64 = 0.002;

fn context() -> GpuContext {
    GpuContext::new().unwrap_or_else(|e| panic!("{e}"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("gpu_sweep")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn sweep_scene(dir: &Path, sweep: &[f64]) -> Scene {
    load_scene(&write_hopper_sweep(dir, sweep)).unwrap_or_else(|p| panic!("{p}"))
}

fn gpu_options(out: &Path) -> GpuRunOptions {
    GpuRunOptions {
        out_dir: out.to_path_buf(),
        quiet: true,
        no_frames: true,
        ..GpuRunOptions::default()
    }
}

fn gpu_sweep(
    ctx: &GpuContext,
    scene: &Scene,
    options: &GpuRunOptions,
) -> SweepSummary<GpuRunSummary> {
    run_gpu_orifice_sweep(ctx, scene, options).unwrap_or_else(|e| panic!("{e}"))
}

/// The state of a run's end checkpoint.
fn end(checkpoint: &Option<PathBuf>) -> CheckpointData {
    CheckpointData::read(checkpoint.as_deref().expect("the run's end checkpoint"))
        .unwrap_or_else(|e| panic!("{e}"))
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The largest relative difference of the rates of two sweeps' points, the diameters and
/// Beverloo's rates equal.
fn rate_difference(gpu: &[(f64, f64, f64)], cpu: &[(f64, f64, f64)]) -> f64 {
    assert_eq!(gpu.len(), cpu.len());
    gpu.iter()
        .zip(cpu)
        .map(|(g, c)| relative(g.1, c.1))
        .fold(0.0, f64::max)
}

fn csv_header(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines().next().unwrap_or_default().to_owned()
}

#[test]
fn a_gpu_sweep_gives_the_cpu_sweeps_points_fit_and_files() {
    let ctx = context();
    let dir = scratch("sweep");
    let scene = sweep_scene(&dir, &DIAMETERS);
    let (cpu_out, gpu_out) = (dir.join("cpu"), dir.join("gpu"));
    let cpu = run_orifice_sweep(
        &scene,
        &RunOptions::new(&cpu_out).quiet(true).no_frames(true),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let gpu = gpu_sweep(&ctx, &scene, &gpu_options(&gpu_out));
    eprintln!("CPU:\n{}\nGPU:\n{}", cpu.text, gpu.text);
    assert_eq!(gpu.points.len(), DIAMETERS.len());
    for ((g, c), d) in gpu.points.iter().zip(&cpu.points).zip(DIAMETERS) {
        assert_eq!((g.0, c.0), (d, d));
        assert_eq!(g.2.to_bits(), c.2.to_bits(), "Beverloo's rate at D = {d}");
        assert!(g.1 > 0.0, "the hopper drains at D = {d}: {g:?}");
    }
    // The runs' end states (their end checkpoints): the trajectories' round-off differences.
    let n = scene.particles.len();
    for (i, (g, c)) in gpu.runs.iter().zip(&cpu.runs).enumerate() {
        let [x, v, _] = body_differences(&end(&g.checkpoint), &end(&c.checkpoint), n);
        let x = x / DIAMETER;
        eprintln!(
            "run {i}: GPU - CPU at the end: positions {x:.2e} diameters, velocities {v:.2e} m/s"
        );
        assert!(x <= POSITION_TOLERANCE, "run {i}: {x:e}");
    }
    let rates = rate_difference(&gpu.points, &cpu.points);
    let (gpu_fit, cpu_fit) = (gpu.fit.expect("GPU fit"), cpu.fit.expect("CPU fit"));
    let fit = relative(gpu_fit.c, cpu_fit.c).max(relative(gpu_fit.k, cpu_fit.k));
    eprintln!("GPU - CPU: rates {rates:.2e}, C and k {fit:.2e}");
    assert_eq!((rates, fit), (0.0, 0.0));
    assert_eq!(gpu.text, cpu.text);
    // The same run folders, each with its headline, and the CSV with the CPU's columns.
    for i in 0..DIAMETERS.len() {
        let headline = format!("{NAME}_D{i}/{NAME}_D{i}_headline.toml");
        assert!(cpu_out.join(&headline).exists(), "{headline}");
        assert!(gpu_out.join(&headline).exists(), "{headline}");
    }
    let csv = format!("{NAME}_beverloo.csv");
    assert_eq!(gpu.files, [gpu_out.join(&csv)]);
    assert_eq!(
        csv_header(&gpu_out.join(&csv)),
        csv_header(&cpu_out.join(&csv))
    );
    let rows = std::fs::read_to_string(gpu_out.join(&csv)).unwrap();
    assert_eq!(rows.lines().count(), 1 + DIAMETERS.len(), "{rows}");

    // The last diameter 0.5 mm wider on the GPU alone: that run's rate moves.
    let mut wider = DIAMETERS;
    wider[2] += 0.0005;
    let other = sweep_scene(&dir.join("wider"), &wider);
    let moved = gpu_sweep(&ctx, &other, &gpu_options(&dir.join("wider_out")));
    let d = relative(moved.points[2].1, cpu.points[2].1);
    eprintln!("the last diameter 0.5 mm wider on the GPU: its rate moves by {d:.2e}");
    assert!(d > 0.05, "{d:e}");
}

#[test]
fn an_interrupted_gpu_sweep_stops_with_a_checkpoint_that_resumes_its_run_alone() {
    let ctx = context();
    let dir = scratch("interrupted");
    let scene = sweep_scene(&dir, &DIAMETERS);
    let stop = scene.total_steps() / 2;
    let out = dir.join("out");
    let options = GpuRunOptions {
        stop_at_step: Some(stop),
        ..gpu_options(&out)
    };
    let sweep = gpu_sweep(&ctx, &scene, &options);
    // The sweep stopped in its first run, and wrote that one point (no fit).
    assert_eq!(sweep.runs.len(), 1);
    assert!(sweep.runs[0].stopped_early);
    assert_eq!(sweep.runs[0].step, stop);
    assert!(sweep.fit.is_none());
    let checkpoint = sweep.runs[0]
        .checkpoint
        .clone()
        .expect("the run's checkpoint");
    assert!(
        checkpoint.starts_with(out.join(format!("{NAME}_D0"))),
        "{}",
        checkpoint.display()
    );
    // As the interrupt's message says: that run's diameter written into the scene (under the
    // run's name), the sweep removed, and resumed with the checkpoint; it ends as the
    // uninterrupted run of that diameter ends, bit for bit.
    let one = dir.join("one");
    std::fs::create_dir_all(&one).unwrap();
    let text: String = hopper_sweep_text(&DIAMETERS)
        .replace(
            &format!("name = \"{NAME}\""),
            &format!("name = \"{NAME}_D0\""),
        )
        .lines()
        .filter(|l| !l.starts_with("orifice_sweep_m"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(text.contains(&format!("orifice_diameter_m = {:?}", DIAMETERS[0])));
    std::fs::write(one.join("hopper.toml"), text).unwrap();
    let alone = load_scene(&one.join("hopper.toml")).unwrap_or_else(|p| panic!("{p}"));
    let resumed = run_gpu_scene(
        &ctx,
        &alone,
        &GpuRunOptions {
            resume: Some(checkpoint),
            ..gpu_options(&out.join(format!("{NAME}_D0")))
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let straight = run_gpu_scene(&ctx, &alone, &gpu_options(&dir.join("straight")))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!resumed.stopped_early);
    let n = scene.particles.len();
    assert!(same_bits(
        &end(&resumed.checkpoint),
        &end(&straight.checkpoint),
        n
    ));
    let rate = |s: &GpuRunSummary| s.headline.get("mass_flow_rate_kg_per_s").unwrap();
    assert_eq!(rate(&resumed), rate(&straight));
    assert!(rate(&straight) > 0.0);
}
