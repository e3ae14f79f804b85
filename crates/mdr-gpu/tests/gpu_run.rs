//! `sim run` on the GPU against the CPU run of the same scene: a sphere dropped onto a plane
//! (the drop headline's restitution) and a box of spheres thrown about (frame positions,
//! velocities, contacts; the energy columns the GPU writes), each compared with the CPU run's
//! outputs read back from disk; negative controls (a 2 % change of `q_c`, of the friction
//! coefficient, on the GPU alone); the outputs the GPU run leaves out (`plastic_work_j`, the
//! books it does not keep); and the scene keys it refuses by name. The device tests need a
//! Vulkan (or Metal/DX12) device with 64-bit floats (on Linux without a GPU, Mesa's lavapipe).

use mdr_gpu::{gpu_run_support, run_gpu_scene, GpuContext, GpuRunOptions, GPU_ENERGY_COLUMNS};
use mdr_sim::output::vtk::{read_particles, ParticleFrame};
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
const BOX: &str = r#"
[run]
name = "box"
duration_s = 0.006
dt_s = 2.0e-5
max_speed_m_per_s = 1.0
output_interval_s = 0.002
energy_interval_s = 0.0005

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 2.0e6
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = {Q_C}
hardening_ratio = 0.37
tangential = "mindlin"
friction = {FRICTION}
rolling_friction = 0.1
damping = "hertzian_viscous"
damping_gamma_n_per_m_s = 1.0e4
damping_tangential_ratio = 0.5

[[particles]]
material = "grain"
placement = "csv"
file = "particles.csv"

[[walls]]
kind = "box"
material = "grain"
min_m = [-0.01, -0.01, 0.0]
max_m = [0.01, 0.01, 0.02]
thickness_m = 0.004
open_top = false
"#;

fn box_csv() -> String {
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        // SplitMix64: a fixed sequence, the same on every machine.
        seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = seed;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut csv = String::from("x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n");
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..3 {
                let at = |n: usize| -0.006 + 0.006 * n as f64;
                let v = [next(), next(), next()];
                csv.push_str(&format!(
                    "{:.6},{:.6},{:.6},0.002,{:.6},{:.6},{:.6}\n",
                    at(i),
                    at(j),
                    0.004 + 0.006 * k as f64,
                    v[0],
                    v[1],
                    v[2]
                ));
            }
        }
    }
    csv
}

fn box_scene(dir: &Path, friction: f64) -> Scene {
    write_scene(dir, BOX, &box_csv(), 20.0, friction)
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
    // Measured on lavapipe: 1.4e-17 diameters, 1.6e-16 and 2.8e-16 of the largest speeds.
    assert!(pos / diameter < 1e-16, "positions: {pos:.3e} m");
    assert!(vel / v_scale < 1e-15, "velocities: {vel:.3e} m/s");
    assert!(ang / w_scale < 1e-15, "angular velocities: {ang:.3e} rad/s");
    let touching: u32 = gpu_frames.last().unwrap().contacts.iter().sum();
    assert!(touching > 0, "the spheres touch at the end");
    for (c, g) in cpu_frames.iter().zip(&gpu_frames) {
        assert_eq!(c.contacts, g.contacts, "contacts per sphere");
        assert_eq!(c.radius, g.radius);
        assert_eq!(c.id, g.id);
        // The GPU keeps no plastic work: the field is left out, not written as zeros.
        assert_eq!(c.plastic_work.len(), c.position.len());
        assert!(g.plastic_work.is_empty());
    }

    // The energy books: the GPU writes its columns, equal to the CPU run's.
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
            // Measured on lavapipe: within 1.4e-16 of the column's largest value.
            assert!(d < 1e-15, "{name}: CPU {} GPU {}", c[col], g[k]);
        }
    }
    println!("box: energy columns agree within {worst:.3e} of each column's largest value");
    let pvd = std::fs::read_to_string(gpu_out.join("box.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 4, "{pvd}");
    assert!(gpu_out.join("box_energy.svg").exists());
    assert!(
        !gpu_out.join("checkpoints").exists(),
        "the GPU run writes no checkpoints"
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
}

#[test]
fn what_the_gpu_run_cannot_write_is_refused_by_its_key() {
    let dir = scratch("refusals");
    let base = box_scene(&dir, 0.5);
    gpu_run_support(&base, false).unwrap();
    let mut checkpoints = base.clone();
    checkpoints.source.run.checkpoint_interval_s = Some(0.001);
    let err = gpu_run_support(&checkpoints, false)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("checkpoint_interval_s") && err.contains("--no-checkpoints"),
        "{err}"
    );
    gpu_run_support(&checkpoints, true).unwrap();
    let mut network = base.clone();
    network.contact_network = true;
    let err = gpu_run_support(&network, true).unwrap_err().to_string();
    assert!(err.contains("contact_network"), "{err}");
    let mut guard = base.clone();
    guard.source.run.max_energy_drift = Some(0.05);
    let err = gpu_run_support(&guard, true).unwrap_err().to_string();
    assert!(err.contains("max_energy_drift"), "{err}");
    // The scene refusals of `bench scene --device gpu`, by name.
    let hopper =
        load_scene(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/hopper.toml"))
            .unwrap_or_else(|p| panic!("{p}"));
    let err = gpu_run_support(&hopper, true).unwrap_err().to_string();
    assert!(err.contains("`kind = \"cylinder\"`"), "{err}");
    let mut sink = base.clone();
    sink.source.run.delete_below_m = Some(-0.1);
    let err = gpu_run_support(&sink, true).unwrap_err().to_string();
    assert!(err.contains("delete_below_m"), "{err}");
}
