//! `sim run` on the GPU against the CPU run of the same scene: a sphere dropped onto a plane
//! (the drop headline's restitution) and a box of spheres thrown about (frame positions,
//! velocities, contacts; the energy columns the GPU writes), each compared with the CPU run's
//! outputs read back from disk; negative controls (a 2 % change of `q_c`, of the friction
//! coefficient, on the GPU alone); and the scene keys it refuses by name (each sphere's
//! `plastic_work_j` per law in `gpu_books.rs`). The device tests need a
//! Vulkan (or Metal/DX12) device with 64-bit floats (on Linux without a GPU, Mesa's lavapipe).

#[path = "common/box_toml.rs"]
mod box_toml;
mod common;
use box_toml::BoxToml;
use common::box_csv;
use mdr_gpu::{gpu_run_support, run_gpu_scene, GpuContext, GpuRunOptions, GPU_ENERGY_COLUMNS};
use mdr_sim::output::run_dir::checkpoint_name;
use mdr_sim::output::vtk::{read_particles, ParticleFrame};
use mdr_sim::run::CheckpointData;
use mdr_sim::scene::load_scene;
use mdr_sim::{run_scene, RunOptions, Scene};
use std::path::{Path, PathBuf};

fn context() -> GpuContext {
    GpuContext::new().unwrap_or_else(|e| panic!("{e}"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("gpu_run")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `toml` (with `{Q_C}` and `{FRICTION}` filled in) and `csv` (the placement file
/// `particles.csv`) written into `dir`, loaded.
fn write_scene(dir: &Path, toml: &str, csv: &str, q_c: f64, friction: f64) -> Scene {
    std::fs::write(dir.join("particles.csv"), csv).unwrap();
    let text = toml
        .replace("{Q_C}", &format!("{q_c:?}"))
        .replace("{FRICTION}", &format!("{friction:?}"));
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}

/// The steel sphere of `scenes/drop.toml` (radius 6.35 mm, MDR with the paper's `q_c`) 10 µm
/// above the plane, approaching it at 0.5 m/s under gravity: 250 steps cover the approach,
/// the bounce and the rebound.
const DROP: &str = r#"
[run]
name = "drop"
duration_s = 2.0e-4
dt_s = 8.0e-7
max_speed_m_per_s = 0.6
output_interval_s = 5.0e-5
energy_interval_s = 1.0e-5
headline = "drop"

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "steel"
youngs_pa = 2.0e11
poisson_ratio = 0.286
density_kg_per_m3 = 7800.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = {Q_C}
hardening_ratio = 0.37

[[particles]]
material = "steel"
placement = "csv"
file = "particles.csv"

[[walls]]
kind = "plane"
material = "steel"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#;

const DROP_CSV: &str = "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n\
                        0.0,0.0,0.00636,0.00635,0.0,0.0,-0.5\n";

fn drop_scene(dir: &Path, q_c: f64) -> Scene {
    write_scene(dir, DROP, DROP_CSV, q_c, 0.5)
}

/// 27 spheres of radius 2 mm on a 6 mm lattice in the closed box `[-1, 1] cm³ × [0, 2] cm`,
/// each with a fixed pseudo-random velocity of up to 0.5 m/s per component: within 300 steps
/// (6 ms) they collide with each other and the walls, load plastically (MDR), slide (Mindlin),
/// roll (rolling resistance) and are damped (Hertzian viscous).
const BOX: BoxToml = BoxToml {
    name: "box",
    duration_s: 0.006,
    dt_s: 2.0e-5,
    max_speed_m_per_s: 1.0,
    output_interval_s: 0.002,
    run: "energy_interval_s = 0.0005",
    materials: &[("grain", 2.0e6, 0.25, 2500.0, "")],
    contact: "normal = \"mdr\"\ncritical_line_load_n_per_m = {Q_C}\nhardening_ratio = 0.37\n\
              tangential = \"mindlin\"\nfriction = {FRICTION}\nrolling_friction = 0.1\n\
              damping = \"hertzian_viscous\"\ndamping_gamma_n_per_m_s = 1.0e4\n\
              damping_tangential_ratio = 0.5",
    particles: &[("grain", "particles.csv")],
    wall_material: "grain",
    min_m: [-0.01, -0.01, 0.0],
    max_m: [0.01, 0.01, 0.02],
    thickness_m: 0.004,
    open_top: false,
};

fn box_scene(dir: &Path, friction: f64) -> Scene {
    write_scene(dir, &BOX.text(), &box_csv(), 20.0, friction)
}

fn cpu_run(scene: &Scene, out: &Path) {
    run_scene(scene, &RunOptions::new(out).quiet(true)).unwrap_or_else(|e| panic!("{e}"));
}

fn gpu_run(ctx: &GpuContext, scene: &Scene, out: &Path) -> mdr_gpu::GpuRunSummary {
    let options = GpuRunOptions {
        out_dir: out.to_path_buf(),
        quiet: true,
        ..GpuRunOptions::default()
    };
    run_gpu_scene(ctx, scene, &options).unwrap_or_else(|e| panic!("{e}"))
}

/// The frames of a run, in the order of its collection.
fn frames(out: &Path, name: &str) -> Vec<ParticleFrame> {
    let mut paths: Vec<_> = std::fs::read_dir(out.join("frames"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|f| f.to_string_lossy().starts_with(&format!("{name}_")))
        })
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| read_particles(p).unwrap_or_else(|e| panic!("{e}")))
        .collect()
}

/// The largest difference of a vector field between two runs' frames, over every frame and
/// particle, and the largest magnitude of the field.
fn field_difference(
    a: &[ParticleFrame],
    b: &[ParticleFrame],
    field: fn(&ParticleFrame) -> &Vec<[f64; 3]>,
) -> (f64, f64) {
    assert_eq!(a.len(), b.len(), "frame counts");
    let (mut diff, mut scale) = (0.0f64, 0.0f64);
    for (fa, fb) in a.iter().zip(b) {
        assert_eq!(field(fa).len(), field(fb).len());
        for (x, y) in field(fa).iter().zip(field(fb)) {
            let d = (0..3).map(|k| (x[k] - y[k]).powi(2)).sum::<f64>().sqrt();
            diff = diff.max(d);
            scale = scale.max((0..3).map(|k| x[k] * x[k]).sum::<f64>().sqrt());
        }
    }
    (diff, scale)
}

/// The energy CSV of a run as a header and rows of numbers.
fn energy_csv(out: &Path, name: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(out.join(format!("{name}_energy.csv"))).unwrap();
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
    (header, rows)
}

/// The restitution the drop's headline reports (`<name>_headline.toml`).
fn restitution(out: &Path) -> f64 {
    let text = std::fs::read_to_string(out.join("drop_headline.toml")).unwrap();
    let value: toml::Table = toml::from_str(&text).unwrap();
    value["values"]
        .as_array()
        .unwrap()
        .iter()
        .find(|v| v["name"].as_str() == Some("restitution"))
        .and_then(|v| v["value"].as_float())
        .unwrap()
}

#[test]
fn a_drop_run_on_the_gpu_reports_the_cpu_runs_restitution() {
    let ctx = context();
    let q_c = 3.8e5;
    let cpu_dir = scratch("drop_cpu");
    let gpu_dir = scratch("drop_gpu");
    let scene = drop_scene(&cpu_dir, q_c);
    cpu_run(&scene, &cpu_dir.join("out"));
    let gpu_scene = drop_scene(&gpu_dir, q_c);
    let summary = gpu_run(&ctx, &gpu_scene, &gpu_dir.join("out"));
    assert!(!summary.stopped_early);
    assert_eq!(summary.step, scene.total_steps());
    let e_cpu = restitution(&cpu_dir.join("out"));
    let e_gpu = restitution(&gpu_dir.join("out"));
    assert_eq!(summary.headline.get("restitution"), Some(e_gpu));
    // A plastic bounce: the MDR law's e_n at 0.5 m/s is well below 1.
    assert!(e_cpu > 0.3 && e_cpu < 0.95, "{e_cpu}");
    let d = (e_gpu / e_cpu - 1.0).abs();
    println!("drop: e_n CPU {e_cpu}, GPU {e_gpu}, relative difference {d:.3e}");
    // Measured on lavapipe: 0 (the one-sphere contact's arithmetic is the CPU path's); a
    // sample taken a step off (the contacts of the step before) moves e_n by 3.4e-5.
    assert!(d < 5e-16, "e_n: CPU {e_cpu}, GPU {e_gpu}");
    let (pos, scale) = field_difference(
        &frames(&cpu_dir.join("out"), "drop"),
        &frames(&gpu_dir.join("out"), "drop"),
        |f| &f.position,
    );
    println!("drop: positions differ by {pos:.3e} m (largest {scale:.3e} m)");
    // Measured on lavapipe: 0; the bound is a few units in the last place of 6.4 mm.
    assert!(pos < 4e-18, "positions differ by {pos:.3e} m");

    // Negative control: q_c 2 % higher on the GPU alone changes e_n far beyond the tolerance.
    let control_dir = scratch("drop_control");
    let control = drop_scene(&control_dir, 1.02 * q_c);
    gpu_run(&ctx, &control, &control_dir.join("out"));
    let e_control = restitution(&control_dir.join("out"));
    println!("drop: q_c + 2 % on the GPU gives e_n {e_control}");
    assert!(
        (e_control / e_cpu - 1.0).abs() > 1e-4,
        "e_n with q_c + 2 %: {e_control}, CPU {e_cpu}"
    );
}

#[test]
fn a_box_run_on_the_gpu_writes_the_cpu_runs_frames_and_energies() {
    let ctx = context();
    let cpu_dir = scratch("box_cpu");
    let gpu_dir = scratch("box_gpu");
    let scene = box_scene(&cpu_dir, 0.5);
    let (cpu_out, gpu_out) = (cpu_dir.join("out"), gpu_dir.join("out"));
    cpu_run(&scene, &cpu_out);
    let gpu_scene = box_scene(&gpu_dir, 0.5);
    gpu_run(&ctx, &gpu_scene, &gpu_out);

    let (cpu_frames, gpu_frames) = (frames(&cpu_out, "box"), frames(&gpu_out, "box"));
    assert_eq!(gpu_frames.len(), 4, "frames at 0, 2, 4 and 6 ms");
    let (pos, _) = field_difference(&cpu_frames, &gpu_frames, |f| &f.position);
    let (vel, v_scale) = field_difference(&cpu_frames, &gpu_frames, |f| &f.velocity);
    let (ang, w_scale) = field_difference(&cpu_frames, &gpu_frames, |f| &f.angular_velocity);
    let diameter = 0.004;
    println!(
        "box: positions {:.3e} diameters, velocities {:.3e}, angular velocities {:.3e} of the largest",
        pos / diameter,
        vel / v_scale,
        ang / w_scale
    );
    // Measured on lavapipe: 3.4e-18 diameters, 1.6e-16 and 1.8e-16 of the largest speeds.
    assert!(pos / diameter < 1e-16, "positions: {pos:.3e} m");
    assert!(vel / v_scale < 1e-15, "velocities: {vel:.3e} m/s");
    assert!(ang / w_scale < 1e-15, "angular velocities: {ang:.3e} rad/s");
    let touching: u32 = gpu_frames.last().unwrap().contacts.iter().sum();
    assert!(touching > 0, "the spheres touch at the end");
    for (c, g) in cpu_frames.iter().zip(&gpu_frames) {
        assert_eq!(c.contacts, g.contacts, "contacts per sphere");
        assert_eq!(c.radius, g.radius);
        assert_eq!(c.id, g.id);
        // Every field is written (the plastic work's values per law in `gpu_books.rs`).
        assert_eq!(c.plastic_work.len(), c.position.len());
        assert_eq!(g.plastic_work.len(), g.position.len());
    }

    // The energy books: the GPU writes the CPU run's columns, equal to its values (the works
    // per law in `gpu_books.rs`).
    let (cpu_header, cpu_rows) = energy_csv(&cpu_out, "box");
    let (gpu_header, gpu_rows) = energy_csv(&gpu_out, "box");
    assert_eq!(gpu_header, GPU_ENERGY_COLUMNS);
    assert_eq!(cpu_rows.len(), gpu_rows.len());
    assert_eq!(gpu_rows.len(), 13, "rows every 0.5 ms over 6 ms");
    let mut worst = 0.0f64;
    for (c, g) in cpu_rows.iter().zip(&gpu_rows) {
        for (k, name) in GPU_ENERGY_COLUMNS.iter().enumerate() {
            let col = cpu_header.iter().position(|h| h == name).unwrap();
            let scale = cpu_rows.iter().map(|r| r[col].abs()).fold(0.0, f64::max);
            let d = (c[col] - g[k]).abs() / scale.max(f64::MIN_POSITIVE);
            worst = worst.max(d);
            // Measured on lavapipe: within 4.6e-16 of the column's largest value (the works
            // and the balance included).
            assert!(d < 1e-15, "{name}: CPU {} GPU {}", c[col], g[k]);
        }
    }
    println!("box: energy columns agree within {worst:.3e} of each column's largest value");
    let pvd = std::fs::read_to_string(gpu_out.join("box.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 4, "{pvd}");
    assert!(gpu_out.join("box_energy.svg").exists());
    assert!(
        gpu_out
            .join("checkpoints")
            .join(checkpoint_name("box", 300))
            .exists(),
        "the GPU run writes its end checkpoint"
    );

    // Negative control: friction 0.5 → 0.51 on the GPU alone moves the spheres beyond the
    // tolerance.
    let control_dir = scratch("box_control");
    let control = box_scene(&control_dir, 0.51);
    gpu_run(&ctx, &control, &control_dir.join("out"));
    let (moved, _) = field_difference(&cpu_frames, &frames(&control_dir.join("out"), "box"), |f| {
        &f.position
    });
    println!(
        "box: friction + 2 % on the GPU moves positions by {:.3e} diameters",
        moved / diameter
    );
    assert!(moved / diameter > 1e-9, "{moved:.3e} m");
    // ... and its tangential springs' elastic energy beyond the energy columns' tolerance.
    let (control_header, control_rows) = energy_csv(&control_dir.join("out"), "box");
    let col = |header: &[String], name: &str| header.iter().position(|h| h == name).unwrap();
    let (c_cpu, c_control) = (
        col(&cpu_header, "elastic_tangential_j"),
        col(&control_header, "elastic_tangential_j"),
    );
    let scale = cpu_rows.iter().map(|r| r[c_cpu].abs()).fold(0.0, f64::max);
    let moved = cpu_rows
        .iter()
        .zip(&control_rows)
        .map(|(c, g)| (c[c_cpu] - g[c_control]).abs() / scale)
        .fold(0.0, f64::max);
    println!("box: friction + 2 % moves elastic_tangential_j by {moved:.3e} of its largest");
    assert!(scale > 0.0 && moved > 1e-9, "{moved:.3e}");
}

#[test]
fn what_the_gpu_run_cannot_write_is_refused_by_its_key() {
    let dir = scratch("refusals");
    let base = box_scene(&dir, 0.5);
    gpu_run_support(&base).unwrap();
    // Checkpoints are written on the GPU too.
    let mut checkpoints = base.clone();
    checkpoints.source.run.checkpoint_interval_s = Some(0.001);
    gpu_run_support(&checkpoints).unwrap();
    let mut network = base.clone();
    network.contact_network = true;
    let err = gpu_run_support(&network).unwrap_err().to_string();
    assert!(err.contains("contact_network"), "{err}");
    // The energy guard runs on the GPU too.
    let mut guard = base.clone();
    guard.source.run.max_energy_drift = Some(0.05);
    gpu_run_support(&guard).unwrap();
    // The scene refusals of `bench scene --device gpu`, by name.
    let mut hopper =
        load_scene(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/hopper.toml"))
            .unwrap_or_else(|p| panic!("{p}"));
    // Its cylinder of flat pieces instead of the exact surface.
    hopper.walls[0].revolution = None;
    let err = gpu_run_support(&hopper).unwrap_err().to_string();
    assert!(err.contains("`kind = \"cylinder\"`"), "{err}");
    assert!(err.contains("exact_surface"), "{err}");
    // A sink runs on the GPU.
    let mut sink = base.clone();
    sink.source.run.delete_below_m = Some(-0.1);
    gpu_run_support(&sink).unwrap();
}

/// The end state of a run from its end checkpoint: the particles and the checkpoint.
fn end_checkpoint(out: &Path, step: u64) -> CheckpointData {
    let path = out.join("checkpoints").join(checkpoint_name("box", step));
    CheckpointData::read(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// A GPU run of the box stopped at `stop` (its checkpoint written there), or resumed from
/// `resume`, into `out`.
fn gpu_run_with(
    ctx: &GpuContext,
    scene: &Scene,
    out: &Path,
    stop: Option<u64>,
    resume: Option<PathBuf>,
) -> mdr_gpu::GpuRunSummary {
    let options = GpuRunOptions {
        out_dir: out.to_path_buf(),
        quiet: true,
        stop_at_step: stop,
        resume,
        no_frames: true,
        ..GpuRunOptions::default()
    };
    run_gpu_scene(ctx, scene, &options).unwrap_or_else(|e| panic!("{e}"))
}

#[path = "common/bodies.rs"]
mod bodies;
use bodies::{body_differences, same_bits};

#[test]
fn a_gpu_run_resumed_from_its_checkpoint_continues_bit_identically() {
    let ctx = context();
    let dir = scratch("resume_gpu");
    let scene = box_scene(&dir, 0.5);
    let n = scene.particles.len();
    // 300 steps straight, and 150 + checkpoint + 150 resumed from it.
    let straight = dir.join("straight");
    gpu_run_with(&ctx, &scene, &straight, None, None);
    let split = dir.join("split");
    let first = gpu_run_with(&ctx, &scene, &split, Some(150), None);
    assert!(first.stopped_early);
    let checkpoint = first.checkpoint.expect("a checkpoint at the stop");
    let data = CheckpointData::read(&checkpoint).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(data.step, 150);
    let lists = data.neighbour_list.as_ref().unwrap();
    // The checkpoint carries live histories, and the second half rebuilds.
    println!(
        "checkpoint at step 150: {} sphere and {} wall contacts",
        lists.pair_histories.len(),
        lists.surface_histories.len()
    );
    assert!(
        !lists.pair_histories.is_empty(),
        "sphere contacts at step 150"
    );
    let second = gpu_run_with(&ctx, &scene, &split, None, Some(checkpoint.clone()));
    assert_eq!((second.start_step, second.step), (150, 300));
    let (a, b) = (end_checkpoint(&straight, 300), end_checkpoint(&split, 300));
    assert!(
        same_bits(&a, &b, n),
        "resumed run differs: {:?}",
        body_differences(&a, &b, n)
    );
    assert!(a.neighbour_list.as_ref().unwrap().rebuilds > lists.rebuilds);
    // The histories at the end too, bit for bit.
    assert_eq!(a.neighbour_list, b.neighbour_list);

    // Negative control: the same checkpoint without its contacts' histories does not continue
    // the run.
    let mut amnesic = data.clone();
    let lists = amnesic.neighbour_list.as_mut().unwrap();
    lists.pair_histories.clear();
    lists.surface_histories.clear();
    let control = dir.join("control");
    let control_checkpoint = control
        .join("checkpoints")
        .join(checkpoint_name("box", 150));
    mdr_sim::checkpoint::write(&control_checkpoint, &amnesic).unwrap();
    gpu_run_with(&ctx, &scene, &control, None, Some(control_checkpoint));
    let c = end_checkpoint(&control, 300);
    let [pos, vel, _] = body_differences(&a, &c, n);
    println!(
        "resume without histories: positions move by {pos:.3e} m, velocities by {vel:.3e} m/s"
    );
    assert!(!same_bits(&a, &c, n));
    assert!(pos > 1e-9, "{pos:.3e} m");
}

#[test]
fn checkpoints_resume_across_devices() {
    let ctx = context();
    let dir = scratch("resume_across");
    let scene = box_scene(&dir, 0.5);
    let n = scene.particles.len();
    let diameter = 0.004;
    let cpu_straight = dir.join("cpu_straight");
    run_scene(
        &scene,
        &RunOptions::new(&cpu_straight).quiet(true).no_frames(true),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let gpu_straight = dir.join("gpu_straight");
    gpu_run_with(&ctx, &scene, &gpu_straight, None, None);
    let cpu_end = end_checkpoint(&cpu_straight, 300);
    let gpu_end = end_checkpoint(&gpu_straight, 300);
    let speeds = |d: &CheckpointData| {
        d.bodies[..n].iter().fold([0.0f64; 2], |m, b| {
            let norm = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
            [m[0].max(norm(b.linvel)), m[1].max(norm(b.angvel))]
        })
    };
    let [v_scale, w_scale] = speeds(&cpu_end);
    let relative = |d: [f64; 3]| [d[0] / diameter, d[1] / v_scale, d[2] / w_scale];
    let straight = relative(body_differences(&cpu_end, &gpu_end, n));
    println!(
        "straight runs, GPU vs CPU (diameters, of the largest speeds): {}",
        e3(straight)
    );

    // A GPU checkpoint at step 150 continued on the CPU.
    let gpu_half = dir.join("gpu_half");
    let stopped = gpu_run_with(&ctx, &scene, &gpu_half, Some(150), None);
    let gpu_checkpoint = stopped.checkpoint.unwrap();
    let on_cpu = dir.join("on_cpu");
    let summary = run_scene(
        &scene,
        &RunOptions::new(&on_cpu)
            .quiet(true)
            .no_frames(true)
            .resume(Some(gpu_checkpoint)),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((summary.start_step, summary.step), (150, 300));
    let gpu_then_cpu = relative(body_differences(&cpu_end, &end_checkpoint(&on_cpu, 300), n));
    println!(
        "GPU to step 150, then the CPU, vs the CPU: {}",
        e3(gpu_then_cpu)
    );

    // A CPU checkpoint at step 150 continued on the GPU.
    let cpu_half = dir.join("cpu_half");
    let stopped = run_scene(
        &scene,
        &RunOptions::new(&cpu_half)
            .quiet(true)
            .no_frames(true)
            .stop_at_step(Some(150)),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let cpu_checkpoint = stopped.checkpoint.unwrap();
    let on_gpu = dir.join("on_gpu");
    let resumed = gpu_run_with(&ctx, &scene, &on_gpu, None, Some(cpu_checkpoint));
    assert_eq!((resumed.start_step, resumed.step), (150, 300));
    let cpu_then_gpu = relative(body_differences(&cpu_end, &end_checkpoint(&on_gpu, 300), n));
    println!(
        "CPU to step 150, then the GPU, vs the CPU: {}",
        e3(cpu_then_gpu)
    );
    // The bounds of the GPU-vs-CPU comparison of the box's frames (1e-16 diameters, 1e-15 of
    // the largest speeds): a resume on the other device adds nothing beyond them.
    for d in [straight, gpu_then_cpu, cpu_then_gpu] {
        assert!(d[0] < 1e-16 && d[1] < 1e-15 && d[2] < 1e-15, "{}", e3(d));
    }

    // Negative control: the GPU checkpoint without its histories, continued on the CPU, is
    // far outside those bounds.
    let mut amnesic = CheckpointData::read(&end_checkpoint_path(&gpu_half, 150)).unwrap();
    let lists = amnesic.neighbour_list.as_mut().unwrap();
    lists.pair_histories.clear();
    lists.surface_histories.clear();
    let control = dir.join("control");
    let path = control
        .join("checkpoints")
        .join(checkpoint_name("box", 150));
    mdr_sim::checkpoint::write(&path, &amnesic).unwrap();
    run_scene(
        &scene,
        &RunOptions::new(&control)
            .quiet(true)
            .no_frames(true)
            .resume(Some(path)),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let control = relative(body_differences(
        &cpu_end,
        &end_checkpoint(&control, 300),
        n,
    ));
    println!("without the histories: {}", e3(control));
    assert!(control[0] > 1e-9, "{}", e3(control));
}

/// Three differences in scientific notation.
fn e3(d: [f64; 3]) -> String {
    format!("{:.3e}, {:.3e}, {:.3e}", d[0], d[1], d[2])
}

fn end_checkpoint_path(out: &Path, step: u64) -> PathBuf {
    out.join("checkpoints").join(checkpoint_name("box", step))
}

/// A sphere thrown at the floor at 100 m/s sinks deeper than the contact can hold (the CPU
/// run's wall-guard scene): the device's guard, checked at every step, stops the run naming
/// the sphere, the wall and the first step it sank too deep at, the step the CPU run stops at;
/// the guard at the samples alone (every 125 steps) would name step 125.
#[test]
fn the_wall_guard_names_the_first_step_a_sphere_goes_through_a_wall() {
    let ctx = context();
    let dir = scratch("crossing");
    std::fs::write(
        dir.join("shot.csv"),
        "x_m,y_m,z_m,radius_m\n0,0,0.0025,0.002\n",
    )
    .unwrap();
    let path = dir.join("shot.toml");
    std::fs::write(
        &path,
        r#"
[run]
name = "shot"
duration_s = 0.001
dt_s = 4.0e-6
max_speed_m_per_s = 100.0
output_interval_s = 0.0005

[[material]]
name = "grain"
youngs_pa = 5.0e7
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 100.0
hardening_ratio = 0.37

[[particles]]
material = "grain"
placement = "csv"
file = "shot.csv"
velocity_m_per_s = [0.0, 0.0, -100.0]

[[walls]]
kind = "plane"
material = "grain"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#,
    )
    .unwrap();
    let scene = load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
    let cpu = run_scene(&scene, &RunOptions::new(dir.join("cpu")).quiet(true)).unwrap_err();
    let mdr_sim::SimError::Stopped { step: cpu_step, .. } = cpu else {
        panic!("{cpu}");
    };
    let options = GpuRunOptions {
        out_dir: dir.join("gpu"),
        quiet: true,
        ..GpuRunOptions::default()
    };
    let e = run_gpu_scene(&ctx, &scene, &options).unwrap_err();
    let mdr_gpu::GpuRunError::Stopped { reason, .. } = &e else {
        panic!("{e}");
    };
    println!("CPU stops at step {cpu_step}; GPU: {reason}");
    assert!(
        reason.contains("sphere 0 ") && reason.contains("wall 0 "),
        "{reason}"
    );
    assert!(cpu_step > 0 && cpu_step < 125, "{cpu_step}");
    assert!(
        reason.contains(&format!("at step {cpu_step} ")),
        "CPU step {cpu_step}: {reason}"
    );
    // The series up to the stop are written.
    assert!(dir.join("gpu/shot_energy.csv").exists());
}
