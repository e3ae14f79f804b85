//! The energy books of `sim run` on the GPU against the CPU run of the same scene: a box of 27
//! spheres thrown about for 300 steps with each normal law on the device (MDR, Hertz,
//! Thornton, adhesive MDR) and Mindlin friction, Hertzian or stiffness-viscous damping and
//! rolling resistance; each
//! dissipated work the device books (friction, damping, rolling, the springs' stiffness
//! energy, plastic, adhesive), the balance and its drift, compared with the CPU run's columns
//! read back from disk; a negative control (the balance without one work); the energy guard
//! (`max_energy_drift`) stopping both runs at the same sample; the books continued across a
//! checkpoint in both directions (and a checkpoint without its books as a negative control);
//! and the device's books repeating themselves bit for bit. The device tests need a Vulkan (or
//! Metal/DX12) device with 64-bit floats (on Linux without a GPU, Mesa's lavapipe).

#[path = "common/box_scene.rs"]
mod box_scene;
mod common;
use box_scene::{write_box_scene, LAWS, STIFFNESS_DAMPING};
use mdr_gpu::{run_gpu_scene, GpuContext, GpuRunError, GpuRunOptions, GPU_ENERGY_COLUMNS};
use mdr_sim::output::run_dir::checkpoint_name;
use mdr_sim::run::{Books, CheckpointData};
use mdr_sim::{run_scene, RunOptions, Scene};
use std::path::{Path, PathBuf};

/// The dissipated works and stiffness books the device books, by their CSV column.
const WORKS: [&str; 7] = [
    "plastic_j",
    "friction_j",
    "damping_j",
    "rolling_j",
    "stiffness_tangential_j",
    "stiffness_rolling_j",
    "adhesive_j",
];

/// Largest difference of a work column between the GPU and the CPU run, over every row, as a
/// fraction of the energy scale (the initial kinetic energy): measured on lavapipe over the
/// 300 steps of the four laws, at most 3.0e-16 (Thornton's plastic work; the others' 4.8e-17
/// and below), and 7.7e-16 for the balance, a sum of a dozen columns of up to twice that
/// scale; with the stiffness-viscous dashpot at most 9.7e-17 (Hertz's damping work), the
/// balance 3.9e-16.
const WORK_TOLERANCE: f64 = 2e-15;

fn context() -> GpuContext {
    GpuContext::new().unwrap_or_else(|e| panic!("{e}"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("gpu_books")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The Hertzian dashpot of the box scene of these tests, with its tangential dashpot.
const HERTZIAN_DAMPING: &str =
    "damping = \"hertzian_viscous\"\ndamping_gamma_n_per_m_s = 1.0e4\ndamping_tangential_ratio = 0.5";

/// The box scene (`common/box_scene.rs`) with the normal law's keys `normal`, the Hertzian
/// dashpot and extra `[run]` keys `run`, written into `dir`.
fn box_scene(dir: &Path, normal: &str, run: &str) -> Scene {
    write_box_scene(dir, normal, HERTZIAN_DAMPING, run)
}

fn gpu_options(out: &Path) -> GpuRunOptions {
    GpuRunOptions {
        out_dir: out.to_path_buf(),
        quiet: true,
        no_frames: true,
        ..GpuRunOptions::default()
    }
}

fn gpu_run(ctx: &GpuContext, scene: &Scene, out: &Path) -> mdr_gpu::GpuRunSummary {
    run_gpu_scene(ctx, scene, &gpu_options(out)).unwrap_or_else(|e| panic!("{e}"))
}

fn cpu_options(out: &Path) -> RunOptions {
    RunOptions::new(out).quiet(true).no_frames(true)
}

/// The energy CSV of a run: its header and rows.
struct Energy {
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Energy {
    fn read(out: &Path) -> Self {
        let text = std::fs::read_to_string(out.join("box_energy.csv")).unwrap();
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

    /// Column `name` (zeros where the CSV leaves it out: `adhesive_j` without adhesive work).
    fn column(&self, name: &str) -> Vec<f64> {
        match self.header.iter().position(|h| h == name) {
            Some(k) => self.rows.iter().map(|r| r[k]).collect(),
            None => vec![0.0; self.rows.len()],
        }
    }

    /// The initial kinetic energy: the scale the differences are measured against.
    fn scale(&self) -> f64 {
        self.column("kinetic_translational_j")[0] + self.column("kinetic_rotational_j")[0]
    }

    /// The balance's drift from the first row to the last (J).
    fn drift(&self) -> f64 {
        let b = self.column("balance_j");
        b[b.len() - 1] - b[0]
    }
}

/// The largest difference of column `name` between two runs over every row, as a fraction of
/// `scale`.
fn column_difference(a: &Energy, b: &Energy, name: &str, scale: f64) -> f64 {
    let (x, y) = (a.column(name), b.column(name));
    assert_eq!(x.len(), y.len(), "{name}: rows");
    x.iter()
        .zip(&y)
        .map(|(u, v)| (u - v).abs() / scale)
        .fold(0.0, f64::max)
}

#[test]
fn each_work_the_gpu_books_is_the_cpu_runs_for_every_normal_law() {
    books_match_the_cpu_runs(&context(), "", HERTZIAN_DAMPING);
}

/// The stiffness-viscous dashpot, whose coefficient follows each normal law's tangent
/// stiffness step by step (loading, plastic loading, unloading, a held neck in tension): its
/// damping work and every other book are the CPU run's, within the same tolerance.
#[test]
fn each_work_the_gpu_books_is_the_cpu_runs_with_the_stiffness_viscous_dashpot() {
    books_match_the_cpu_runs(&context(), "_stiffness_viscous", STIFFNESS_DAMPING);
}

/// Each normal law's box scene with the damping law's keys `damping` on both devices (in
/// scratch directories named after the law and `suffix`): every work and the balance within
/// [`WORK_TOLERANCE`], each work the law has booked; negative control: the balance without its
/// friction work.
fn books_match_the_cpu_runs(ctx: &GpuContext, suffix: &str, damping: &str) {
    for (law, normal) in LAWS {
        let dir = scratch(&format!("{law}{suffix}"));
        let scene = write_box_scene(&dir, normal, damping, "");
        let law = format!("{law}{suffix}");
        let law = law.as_str();
        let (cpu_out, gpu_out) = (dir.join("cpu"), dir.join("gpu"));
        run_scene(&scene, &cpu_options(&cpu_out)).unwrap_or_else(|e| panic!("{law}: {e}"));
        let summary = gpu_run(ctx, &scene, &gpu_out);
        // The default energy guard (5 %) holds on both devices: the runs finish.
        assert!(!summary.stopped_early);
        assert_eq!(summary.step, 300);
        let (cpu, gpu) = (Energy::read(&cpu_out), Energy::read(&gpu_out));
        assert_eq!(gpu.header, cpu.header, "{law}: the CPU run's columns");
        assert_eq!(&gpu.header[..GPU_ENERGY_COLUMNS.len()], GPU_ENERGY_COLUMNS);
        assert_eq!(gpu.rows.len(), 13, "{law}: rows every 0.5 ms over 6 ms");
        let scale = cpu.scale();
        let mut worst = 0.0f64;
        for name in WORKS {
            let d = column_difference(&cpu, &gpu, name, scale);
            let last = |e: &Energy| *e.column(name).last().unwrap();
            println!(
                "{law}: {name} CPU {:.6e} GPU {:.6e} J, largest difference {d:.3e} of the \
                 initial kinetic energy {scale:.3e} J",
                last(&cpu),
                last(&gpu)
            );
            worst = worst.max(d);
            assert!(d < WORK_TOLERANCE, "{law}: {name} differs by {d:.3e}");
        }
        // Every work the law has is booked (the comparison is not of zeros).
        let booked = |name: &str| gpu.column(name).last().unwrap().abs() > 1e-6 * scale;
        for name in [
            "friction_j",
            "damping_j",
            "rolling_j",
            "stiffness_tangential_j",
        ] {
            assert!(booked(name), "{law}: {name} is booked");
        }
        assert_eq!(
            booked("plastic_j"),
            !law.starts_with("hertz"),
            "{law}: plastic_j"
        );
        assert_eq!(
            booked("adhesive_j"),
            law.starts_with("adhesive_mdr"),
            "{law}: adhesive_j"
        );
        // The balance closes on the GPU as on the CPU.
        let d = column_difference(&cpu, &gpu, "balance_j", scale);
        let (drift_cpu, drift_gpu) = (cpu.drift() / scale, gpu.drift() / scale);
        println!(
            "{law}: balance differs by {d:.3e}; drift CPU {drift_cpu:+.3e}, GPU {drift_gpu:+.3e} \
             of the initial kinetic energy; works within {worst:.3e}"
        );
        assert!(d < WORK_TOLERANCE, "{law}: balance_j differs by {d:.3e}");
        assert!(
            (drift_gpu - drift_cpu).abs() < WORK_TOLERANCE,
            "{law}: drift CPU {drift_cpu:.3e} GPU {drift_gpu:.3e}"
        );

        // Negative control: the GPU's balance without its friction work misses the CPU's
        // balance by far more than the tolerance.
        let friction = gpu.column("friction_j");
        let without: Vec<f64> = gpu
            .column("balance_j")
            .iter()
            .zip(&friction)
            .map(|(b, f)| b - f)
            .collect();
        let missed = cpu
            .column("balance_j")
            .iter()
            .zip(&without)
            .map(|(c, g)| (c - g).abs() / scale)
            .fold(0.0, f64::max);
        println!("{law}: without the friction work the balance misses by {missed:.3e}");
        assert!(missed > 1e3 * WORK_TOLERANCE, "{law}: {missed:.3e}");
    }
}

#[test]
fn the_gpu_books_repeat_themselves_bit_for_bit() {
    let ctx = context();
    let dir = scratch("repeat");
    let scene = box_scene(&dir, LAWS[3].1, "");
    let (a, b) = (dir.join("a"), dir.join("b"));
    gpu_run(&ctx, &scene, &a);
    gpu_run(&ctx, &scene, &b);
    let text = |out: &Path| std::fs::read_to_string(out.join("box_energy.csv")).unwrap();
    assert_eq!(text(&a), text(&b));
}

/// A guard of `max_energy_drift = 1e-15` stops both runs at the first energy sample after the
/// start (step 25), with the CPU run's message; the default guard lets both run to the end
/// (each law's run above).
#[test]
fn the_energy_guard_stops_the_gpu_run_where_it_stops_the_cpu_run() {
    let ctx = context();
    let dir = scratch("guard");
    let scene = box_scene(&dir, LAWS[0].1, "max_energy_drift = 1e-15");
    assert_eq!(scene.max_energy_drift, Some(1e-15));
    let cpu = run_scene(&scene, &cpu_options(&dir.join("cpu")))
        .expect_err("the CPU run stops")
        .to_string();
    let gpu =
        run_gpu_scene(&ctx, &scene, &gpu_options(&dir.join("gpu"))).expect_err("the GPU run stops");
    let GpuRunError::Stopped { step, reason, .. } = &gpu else {
        panic!("{gpu}");
    };
    println!("CPU: {cpu}\nGPU: {gpu}");
    assert_eq!(*step, 25, "the first energy sample after the start");
    assert!(
        reason.starts_with("the energy balance drifted by"),
        "{reason}"
    );
    // The CPU run's message, figures included, at the same time.
    assert!(cpu.contains(reason.as_str()), "{cpu}");
    assert!(cpu.contains("t = 5.000000e-4 s (step 25)"), "{cpu}");
    // The series up to the stop are written.
    let gpu_rows = Energy::read(&dir.join("gpu"));
    assert_eq!(gpu_rows.rows.len(), 2);
}

fn checkpoint_path(out: &Path, step: u64) -> PathBuf {
    out.join("checkpoints").join(checkpoint_name("box", step))
}

/// The largest difference of the work columns and the balance between two runs' last rows, as
/// a fraction of the initial kinetic energy.
fn last_row_difference(a: &Energy, b: &Energy) -> f64 {
    let scale = a.scale();
    WORKS
        .iter()
        .chain(&["balance_j"])
        .map(|name| {
            let (x, y) = (a.column(name), b.column(name));
            (x.last().unwrap() - y.last().unwrap()).abs() / scale
        })
        .fold(0.0, f64::max)
}

/// The books continue across a checkpoint at step 200 in both directions: the adhesive scene
/// to step 200 (where every work has begun) on one device and on to 300 on the other ends with the CPU run's books, within
/// the tolerance of the straight runs; a GPU checkpoint whose books are cleared does not.
#[test]
fn the_books_continue_across_devices() {
    let ctx = context();
    let dir = scratch("across");
    let scene = box_scene(&dir, LAWS[3].1, "");
    let cpu_straight = dir.join("cpu_straight");
    run_scene(&scene, &cpu_options(&cpu_straight)).unwrap_or_else(|e| panic!("{e}"));
    let cpu = Energy::read(&cpu_straight);

    // GPU to step 200, then the CPU.
    let gpu_half = dir.join("gpu_half");
    let stopped = run_gpu_scene(
        &ctx,
        &scene,
        &GpuRunOptions {
            stop_at_step: Some(200),
            ..gpu_options(&gpu_half)
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let gpu_checkpoint = stopped.checkpoint.unwrap();
    let data = CheckpointData::read(&gpu_checkpoint).unwrap();
    let b = &data.books;
    assert!(
        b.friction > 0.0 && b.plastic > b.adhesive && b.adhesive > 0.0,
        "{b:?}"
    );
    assert!(data.energy.iter().all(|r| r.balance_j.is_finite()));
    let on_cpu = dir.join("on_cpu");
    run_scene(
        &scene,
        &cpu_options(&on_cpu).resume(Some(gpu_checkpoint.clone())),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let gpu_then_cpu = last_row_difference(&cpu, &Energy::read(&on_cpu));

    // CPU to step 200, then the GPU.
    let cpu_half = dir.join("cpu_half");
    let stopped = run_scene(&scene, &cpu_options(&cpu_half).stop_at_step(Some(200)))
        .unwrap_or_else(|e| panic!("{e}"));
    let on_gpu = dir.join("on_gpu");
    run_gpu_scene(
        &ctx,
        &scene,
        &GpuRunOptions {
            resume: stopped.checkpoint,
            ..gpu_options(&on_gpu)
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let cpu_then_gpu = last_row_difference(&cpu, &Energy::read(&on_gpu));
    println!(
        "books after 300 steps vs the CPU run: GPU then CPU {gpu_then_cpu:.3e}, CPU then GPU \
         {cpu_then_gpu:.3e} of the initial kinetic energy"
    );
    assert!(gpu_then_cpu < WORK_TOLERANCE, "{gpu_then_cpu:.3e}");
    assert!(cpu_then_gpu < WORK_TOLERANCE, "{cpu_then_gpu:.3e}");
    assert!(checkpoint_path(&on_gpu, 300).exists());

    // Negative control: the GPU checkpoint with its books cleared breaks the balance by more
    // than the default guard's 5 %, so the CPU run continued from it stops at its first
    // sample, and so does a GPU run continued from the CPU's checkpoint with its books
    // cleared: the guard stops a GPU run whose balance breaks.
    let cleared = |path: &Path, dir: &Path| -> PathBuf {
        let mut data = CheckpointData::read(path).unwrap();
        data.books = Books::new(scene.particles.len());
        let lists = data.neighbour_list.as_mut().unwrap();
        for r in lists
            .pair_histories
            .iter_mut()
            .chain(lists.surface_histories.iter_mut())
        {
            r.contact.books = Default::default();
            r.rolling.dissipated_work = 0.0;
            r.contact.normal.adhesive_mdr.adhesive_work = 0.0;
        }
        let out = checkpoint_path(dir, 200);
        mdr_sim::checkpoint::write(&out, &data).unwrap();
        out
    };
    let control = dir.join("cpu_control");
    let path = cleared(&gpu_checkpoint, &control);
    let err = run_scene(&scene, &cpu_options(&control).resume(Some(path)))
        .expect_err("the CPU guard stops the run")
        .to_string();
    println!("a GPU checkpoint without its books, on the CPU: {err}");
    assert!(err.contains("the energy balance drifted by"), "{err}");
    let control = dir.join("gpu_control");
    let path = cleared(&checkpoint_path(&cpu_half, 200), &control);
    let err = run_gpu_scene(
        &ctx,
        &scene,
        &GpuRunOptions {
            resume: Some(path),
            ..gpu_options(&control)
        },
    )
    .expect_err("the GPU guard stops the run");
    println!("a CPU checkpoint without its books, on the GPU: {err}");
    let GpuRunError::Stopped { step, reason, .. } = &err else {
        panic!("{err}");
    };
    assert_eq!(*step, 200);
    assert!(
        reason.starts_with("the energy balance drifted by"),
        "{reason}"
    );
}
