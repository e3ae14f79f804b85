//! The sink (`[run] delete_below_m`) on the GPU against the CPU run of the same scene: 27
//! spheres falling and colliding through a sink (some parked during the run, some not) end
//! where the CPU run ends, the parked ones on the CPU's spots at rest; the energy they take
//! out of the run (`removed_j`) and the balance are the CPU run's; checkpoints taken across a
//! parking continue on either device with the parked spheres parked. Negative controls: the
//! sink 1 µm higher on the GPU alone, and no sink on the GPU. Then the shipped scenes with a
//! sink, loaded from disk and unchanged: the funnel and the hopper. The
//! device tests need a Vulkan (or Metal/DX12) device with 64-bit floats (on Linux without a
//! GPU, Mesa's lavapipe).

#[path = "common/bodies.rs"]
mod bodies;
mod common;
#[path = "common/scene_end.rs"]
mod scene_end;
#[path = "common/scenes.rs"]
mod scenes;

use bodies::{body_differences, same_bits};
use common::box_csv;
use mdr_gpu::{run_gpu_scene, GpuContext, GpuRunOptions, GpuState};
use mdr_sim::output::run_dir::checkpoint_name;
use mdr_sim::run::{scene_sink, CheckpointData};
use mdr_sim::scene::load_scene;
use mdr_sim::walls::Sink;
use mdr_sim::{run_scene, RunOptions, Scene};
use nalgebra::Vector3;
use scene_end::{CpuEnd, Differences};
use scenes::scene_file;
use std::path::{Path, PathBuf};

/// Steps of the sink scene (6 ms).
const STEPS: usize = 300;
/// The spheres' radius (m).
const RADIUS: f64 = 0.002;
/// The sink's height (m): the lowest layer starts 4 mm above it.
const HEIGHT: f64 = 0.0;

/// The largest GPU − CPU differences: positions over the diameter, velocities and angular
/// velocities over the largest. Measured on lavapipe: the sink scene 0 diameters, 5.4e-17 and
/// 3.4e-16 after 300 steps (resumed across devices, 0 diameters); the hopper 0, 1.8e-16 and
/// 3.6e-16 after 464 steps (shipped, unchanged). The sink 1 µm higher on the GPU alone moves the parked spheres by
/// 2.5e-4 diameters.
const TOLERANCE: [f64; 3] = [1e-16, 1e-15, 1e-15];

/// Largest difference of an energy column between the GPU and the CPU run over every row, as a
/// fraction of the initial kinetic energy: measured on lavapipe, 1.4e-15 (`balance_j`; the
/// removed energy 1.2e-15), and 8.2e-16 of the removed energy after a checkpoint; the balance
/// without the removed energy misses the CPU's by 0.41.
const ENERGY_TOLERANCE: f64 = 5e-15;

fn context() -> GpuContext {
    GpuContext::new().unwrap_or_else(|e| panic!("{e}"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("gpu_sink")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// 27 spheres of radius 2 mm (E = 2 MPa) on a 6 mm lattice whose lowest layer is 4 mm above
/// the sink, each with the box scenes' pseudo-random velocity of up to 0.5 m/s per component
/// and 1 m/s downwards: within 300 steps (6 ms) they collide, a few touch the plane wall at
/// x = −1 cm, and the fastest of the lowest layer fall through the sink while the rest stay.
const SCENE: &str = r#"
[run]
name = "sink"
duration_s = 0.006
dt_s = 2.0e-5
max_speed_m_per_s = 2.0
output_interval_s = 0.003
energy_interval_s = 0.0005
{RUN}

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 2.0e6
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 20.0
hardening_ratio = 0.37
tangential = "mindlin"
friction = 0.5
rolling_friction = 0.1
damping = "hertzian_viscous"
damping_gamma_n_per_m_s = 1.0e4
damping_tangential_ratio = 0.5

[[particles]]
material = "grain"
placement = "csv"
file = "particles.csv"

[[walls]]
kind = "plane"
material = "grain"
point_m = [-0.01, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
"#;

/// The box scenes' particles with 1 m/s downwards added to each.
fn falling_csv() -> String {
    let csv = box_csv();
    let mut lines = csv.lines();
    let mut out = format!("{}\n", lines.next().unwrap());
    for line in lines {
        let mut values: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        values[6] -= 1.0;
        let row: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

/// The sink scene with its sink at `height` (none: no sink) and extra `[run]` keys `run`,
/// written into `dir`.
fn sink_scene(dir: &Path, height: Option<f64>, run: &str) -> Scene {
    std::fs::write(dir.join("particles.csv"), falling_csv()).unwrap();
    let sink = height.map_or(String::new(), |h| format!("delete_below_m = {h:?}\n"));
    let text = SCENE.replace("{RUN}", &format!("{sink}{run}"));
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}

/// The CPU run's end state after `steps` steps with the parking its next step begins with
/// (`Sink::apply`, the CPU run's own), where the device, which parks at the end of a step's
/// integration, holds it. The energy is compared elsewhere, from the runs' books.
fn parked_cpu_end(scene: &Scene, steps: usize) -> CpuEnd {
    let mut end = scene_end::cpu_run(scene, steps);
    if let Some(sink) = scene_sink(scene) {
        sink.apply(&mut end.position, &mut end.linvel, &mut end.angvel, |_| {
            (0.0, 0.0)
        });
    }
    end
}

fn within(d: &Differences) -> bool {
    d.position_diameters <= TOLERANCE[0]
        && d.velocity_relative <= TOLERANCE[1]
        && d.angular_velocity_relative <= TOLERANCE[2]
}

/// The spheres of `position` below `sink`; each is on its spot at rest.
fn parked_at_rest(sink: &Sink, state: &GpuState) -> usize {
    let mut parked = 0;
    for (i, x) in state.position.iter().enumerate() {
        if sink.is_removed(x) {
            parked += 1;
            assert_eq!(*x, sink.spot(i), "sphere {i}");
            assert_eq!(state.linvel[i], Vector3::zeros(), "sphere {i}");
            assert_eq!(state.angvel[i], Vector3::zeros(), "sphere {i}");
        }
    }
    parked
}

#[test]
fn a_gpu_run_parks_the_spheres_the_cpu_run_parks() {
    let ctx = context();
    let dir = scratch("end");
    let scene = sink_scene(&dir, Some(HEIGHT), "");
    let sink = scene_sink(&scene).unwrap();
    let n = scene.particles.len();
    let cpu = parked_cpu_end(&scene, STEPS);
    let parked = sink.removed(&cpu.position);
    // Half-way, fewer are parked: the parkings happen during the run.
    let halfway = sink.removed(&parked_cpu_end(&scene, STEPS / 2).position);
    eprintln!("parked: {halfway} at step 150, {parked} of {n} at step 300");
    assert!(0 < halfway && halfway < parked && parked < n);
    let gpu = scene_end::gpu_run(&ctx, &scene, STEPS);
    assert_eq!(parked_at_rest(&sink, &gpu), parked);
    let d = scene_end::differences(&gpu, &cpu, 2.0 * RADIUS);
    let pairs = gpu.pairs.iter().filter(|p| p.active).count();
    let walls = gpu.floor.iter().filter(|w| w.is_some()).count();
    eprintln!(
        "GPU - CPU: {d:?}; {pairs} touching pairs and {walls} wall contacts (CPU: {} and {})",
        cpu.sphere_contacts, cpu.wall_contacts
    );
    assert!(within(&d), "{d:?}");
    assert_eq!(gpu.asymmetric_pairs, 0);
    assert_eq!((pairs, walls), (cpu.sphere_contacts, cpu.wall_contacts));
    // The sink 1 µm higher on the GPU alone, and no sink on the GPU.
    let higher = sink_scene(&scratch("higher"), Some(HEIGHT + 1e-6), "");
    let d = scene_end::differences(
        &scene_end::gpu_run(&ctx, &higher, STEPS),
        &cpu,
        2.0 * RADIUS,
    );
    eprintln!("sink 1 um higher on the GPU: {d:?}");
    assert!(!within(&d), "{d:?}");
    let without = sink_scene(&scratch("without"), None, "");
    let d = scene_end::differences(
        &scene_end::gpu_run(&ctx, &without, STEPS),
        &cpu,
        2.0 * RADIUS,
    );
    eprintln!("no sink on the GPU: {d:?}");
    assert!(!within(&d), "{d:?}");
}

/// The energy CSV of a run: its header and rows.
struct Energy {
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Energy {
    fn read(out: &Path) -> Self {
        let text = std::fs::read_to_string(out.join("sink_energy.csv")).unwrap();
        let mut lines = text.lines();
        let header = lines
            .next()
            .unwrap()
            .split(',')
            .map(str::to_owned)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect();
        Self { header, rows }
    }

    fn column(&self, name: &str) -> Vec<f64> {
        let k = self.header.iter().position(|h| h == name).unwrap();
        self.rows.iter().map(|r| r[k]).collect()
    }

    /// The initial kinetic energy: the scale the differences are measured against.
    fn scale(&self) -> f64 {
        self.column("kinetic_translational_j")[0] + self.column("kinetic_rotational_j")[0]
    }
}

/// The largest difference of two series, as a fraction of `scale`.
fn series_difference(a: &[f64], b: &[f64], scale: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(u, v)| (u - v).abs() / scale)
        .fold(0.0, f64::max)
}

fn gpu_options(out: &Path, stop: Option<u64>, resume: Option<PathBuf>) -> GpuRunOptions {
    GpuRunOptions {
        out_dir: out.to_path_buf(),
        quiet: true,
        no_frames: true,
        stop_at_step: stop,
        resume,
        ..GpuRunOptions::default()
    }
}

fn gpu_run(
    ctx: &GpuContext,
    scene: &Scene,
    out: &Path,
    stop: Option<u64>,
    resume: Option<PathBuf>,
) -> mdr_gpu::GpuRunSummary {
    run_gpu_scene(ctx, scene, &gpu_options(out, stop, resume)).unwrap_or_else(|e| panic!("{e}"))
}

fn cpu_run(
    scene: &Scene,
    out: &Path,
    stop: Option<u64>,
    resume: Option<PathBuf>,
) -> mdr_sim::RunSummary {
    let options = RunOptions::new(out)
        .quiet(true)
        .no_frames(true)
        .stop_at_step(stop)
        .resume(resume);
    run_scene(scene, &options).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_energy_the_parked_spheres_take_out_is_the_cpu_runs_and_the_balance_closes() {
    let ctx = context();
    let dir = scratch("books");
    let scene = sink_scene(&dir, Some(HEIGHT), "");
    let (gpu_out, cpu_out) = (dir.join("gpu"), dir.join("cpu"));
    gpu_run(&ctx, &scene, &gpu_out, None, None);
    cpu_run(&scene, &cpu_out, None, None);
    let (gpu, cpu) = (Energy::read(&gpu_out), Energy::read(&cpu_out));
    assert_eq!(gpu.header, cpu.header);
    let scale = cpu.scale();
    let mut worst = 0.0f64;
    for name in &cpu.header {
        let d = series_difference(&gpu.column(name), &cpu.column(name), scale);
        eprintln!("{name}: {d:.2e}");
        if name != "time_s" && name != "contacts" {
            worst = worst.max(d);
        }
    }
    assert!(worst <= ENERGY_TOLERANCE, "{worst:e}");
    assert_eq!(gpu.column("contacts"), cpu.column("contacts"));
    let removed = cpu.column("removed_j");
    let balance = cpu.column("balance_j");
    let last = removed.len() - 1;
    eprintln!(
        "removed_j at the end {:.4e} of {scale:.4e}; balance drift {:+.3e} (GPU {:+.3e})",
        removed[last],
        balance[last] - balance[0],
        gpu.column("balance_j")[last] - gpu.column("balance_j")[0]
    );
    // The balance without the energy the parked spheres took out misses the CPU's.
    let without: Vec<f64> = gpu
        .column("balance_j")
        .iter()
        .zip(gpu.column("removed_j"))
        .map(|(b, r)| b - r)
        .collect();
    let missed = series_difference(&without, &balance, scale);
    eprintln!("balance without removed_j: {missed:.2e}");
    assert!(missed > 1e3 * ENERGY_TOLERANCE, "{missed:e}");
}

fn end_checkpoint(out: &Path, step: u64) -> CheckpointData {
    let path = out.join("checkpoints").join(checkpoint_name("sink", step));
    CheckpointData::read(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// The particles of a checkpoint below the sink, each checked to be on its spot at rest.
fn parked_in_checkpoint(sink: &Sink, data: &CheckpointData, n: usize) -> usize {
    let state: Vec<_> = data.bodies[..n].iter().collect();
    let mut parked = 0;
    for (i, b) in state.iter().enumerate() {
        let x = Vector3::from(b.translation);
        if sink.is_removed(&x) {
            parked += 1;
            assert_eq!(x, sink.spot(i), "sphere {i}");
            assert_eq!(b.linvel, [0.0; 3], "sphere {i}");
            assert_eq!(b.angvel, [0.0; 3], "sphere {i}");
        }
    }
    parked
}

#[test]
fn checkpoints_across_a_parking_keep_the_parked_spheres_parked_on_either_device() {
    let ctx = context();
    let dir = scratch("checkpoints");
    let scene = sink_scene(&dir, Some(HEIGHT), "");
    let sink = scene_sink(&scene).unwrap();
    let n = scene.particles.len();
    let total = STEPS as u64;
    let half = total / 2;
    let gpu_straight = dir.join("gpu_straight");
    let gpu_summary = gpu_run(&ctx, &scene, &gpu_straight, None, None);
    let cpu_straight = dir.join("cpu_straight");
    let cpu_summary = cpu_run(&scene, &cpu_straight, None, None);
    let gpu_end = end_checkpoint(&gpu_straight, total);
    let cpu_end = end_checkpoint(&cpu_straight, total);
    // Stopped half-way on either device.
    let gpu_half = dir.join("gpu_half");
    gpu_run(&ctx, &scene, &gpu_half, Some(half), None);
    let cpu_half = dir.join("cpu_half");
    cpu_run(&scene, &cpu_half, Some(half), None);
    let at_half = parked_in_checkpoint(&sink, &end_checkpoint(&gpu_half, half), n);
    let at_end = parked_in_checkpoint(&sink, &gpu_end, n);
    assert_eq!(parked_in_checkpoint(&sink, &cpu_end, n), at_end);
    eprintln!("parked: {at_half} in the checkpoint at step {half}, {at_end} at the end");
    assert!(0 < at_half && at_half < at_end);
    let gpu_checkpoint = gpu_half
        .join("checkpoints")
        .join(checkpoint_name("sink", half));
    let cpu_checkpoint = cpu_half
        .join("checkpoints")
        .join(checkpoint_name("sink", half));
    let removed = |rows: &[f64]| rows[rows.len() - 1];
    let gpu_removed = removed(
        &gpu_summary
            .energy
            .iter()
            .map(|r| r.removed_j)
            .collect::<Vec<_>>(),
    );
    let cpu_removed = removed(
        &cpu_summary
            .energy
            .iter()
            .map(|r| r.removed_j)
            .collect::<Vec<_>>(),
    );
    // GPU, then GPU: the same bits.
    let out = dir.join("gpu_gpu");
    let summary = gpu_run(&ctx, &scene, &out, None, Some(gpu_checkpoint.clone()));
    assert!(same_bits(&end_checkpoint(&out, total), &gpu_end, n));
    // The checkpoint keeps the books' totals, not each sphere's share: the same energy summed
    // in another order.
    let q = (summary.energy.last().unwrap().removed_j - gpu_removed).abs() / gpu_removed;
    eprintln!("GPU then GPU: removed_j {q:.1e}");
    // GPU, then CPU; CPU, then GPU: the runs that were not stopped, within the comparison's
    // bounds.
    let out = dir.join("gpu_cpu");
    let summary = cpu_run(&scene, &out, None, Some(gpu_checkpoint));
    let end = end_checkpoint(&out, total);
    assert_eq!(parked_in_checkpoint(&sink, &end, n), at_end);
    let d = body_differences(&end, &cpu_end, n);
    let r = (summary.energy.last().unwrap().removed_j - cpu_removed).abs() / cpu_removed;
    eprintln!("GPU then CPU: {d:?}, removed_j {r:.1e}");
    let out = dir.join("cpu_gpu");
    let summary = gpu_run(&ctx, &scene, &out, None, Some(cpu_checkpoint));
    let end = end_checkpoint(&out, total);
    assert_eq!(parked_in_checkpoint(&sink, &end, n), at_end);
    let e = body_differences(&end, &gpu_end, n);
    let s = (summary.energy.last().unwrap().removed_j - gpu_removed).abs() / gpu_removed;
    eprintln!("CPU then GPU: {e:?}, removed_j {s:.1e}");
    assert!(q <= ENERGY_TOLERANCE, "{q:e}");
    for (diff, removed) in [(d, r), (e, s)] {
        assert!(diff[0] <= TOLERANCE[0] * 2.0 * RADIUS, "{diff:?}");
        assert!(removed <= ENERGY_TOLERANCE, "{removed:e}");
    }
}

/// A shipped scene's `steps` steps on both paths: the GPU − CPU differences (positions over
/// `diameter`) within the sink scene's bounds, with the same contacts. Before their spheres
/// touch, no sphere turns: the angular velocities are then zero on both paths.
fn shipped_scene_follows_the_cpu(ctx: &GpuContext, scene: &Scene, steps: usize, diameter: f64) {
    assert!(scene_sink(scene).is_some());
    let cpu = scene_end::cpu_run(scene, steps);
    let gpu = scene_end::gpu_run(ctx, scene, steps);
    let d = scene_end::differences(&gpu, &cpu, diameter);
    let pairs = gpu.pairs.iter().filter(|p| p.active).count();
    let walls = gpu.floor.iter().filter(|w| w.is_some()).count();
    eprintln!(
        "{}, {steps} steps of {:.3e} s: GPU - CPU {d:?}; {pairs} touching pairs and {walls} wall \
         contacts (CPU: {} and {})",
        scene.name, scene.dt, cpu.sphere_contacts, cpu.wall_contacts
    );
    assert!(d.position_diameters <= TOLERANCE[0], "{d:?}");
    assert!(d.velocity_relative <= TOLERANCE[1], "{d:?}");
    let turning = cpu.angvel.iter().any(|w| *w != Vector3::zeros());
    assert!(d.angular_velocity_relative <= TOLERANCE[2] || !turning && gpu.angvel == cpu.angvel);
    assert_eq!((pairs, walls), (cpu.sphere_contacts, cpu.wall_contacts));
}

/// `scenes/funnel.toml` as shipped (Hertz, Mindlin, Hertzian damping, the cone and spout, the
/// plug removed at a time, the sink at z = −20) runs on the GPU; its first 300 steps follow
/// the CPU run's. Its spheres fall from z ≥ 30 and touch nothing this early (the sink scene
/// above covers the parking and the contacts).
#[test]
fn the_shipped_funnel_runs_unchanged() {
    let ctx = context();
    shipped_scene_follows_the_cpu(&ctx, &scene_file("funnel.toml"), 300, 0.5);
}

/// `scenes/hopper.toml` unchanged from disk: the cylinder on the orifice plate, the sink and
/// the stiffness-viscous dashpot, 20,734 spheres.
#[test]
fn the_shipped_hopper_follows_the_cpu_run() {
    let ctx = context();
    let hopper = scene_file("hopper.toml");
    // 8 ms: the lowest spheres, at most 0.2 mm above the plate, land on it.
    let steps = (0.008 / hopper.dt).ceil() as usize;
    shipped_scene_follows_the_cpu(&ctx, &hopper, steps, 0.004);
}
