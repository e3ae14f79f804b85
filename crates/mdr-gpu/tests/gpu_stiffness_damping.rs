//! The stiffness-viscous dashpot (Tsuji's `F_d = η √(m k_n) dδ/dt`, `k_n` the normal law's
//! tangent stiffness at each step) on the GPU against the CPU neighbour-list path: the box
//! scene of 27 spheres with each normal law (Hertz, MDR, Thornton, adhesive MDR: loading,
//! plastic loading, unloading, a neck held in tension and let go) and a tangential dashpot, a
//! few hundred steps on both paths, sphere pairs and walls; negative controls (`η` 1 % larger on
//! the GPU only; no dashpot on the GPU); and the shipped `scenes/drum.toml` as it is, 300 steps
//! on both paths from the CPU run's checkpoint where its block has met the drum, with its
//! damping work. The box's books: `gpu_books.rs`. The device tests need a Vulkan (or
//! Metal/DX12) device with 64-bit floats (on Linux without a GPU, Mesa's lavapipe).

#[path = "common/box_scene.rs"]
mod box_scene;
#[path = "common/box_toml.rs"]
mod box_toml;
mod common;
#[path = "common/scene_end.rs"]
mod scene_end;
use box_scene::{write_box_scene, LAWS, STIFFNESS_DAMPING};
use mdr_gpu::{gpu_scene_support, run_gpu_scene, GpuContext, GpuRunOptions, GpuState};
use mdr_sim::run::CheckpointData;
use mdr_sim::scene::load_scene;
use mdr_sim::{run_scene, RunOptions, Scene};
use scene_end::{CpuEnd, Differences};
use std::path::{Path, PathBuf};

const STEPS: usize = 300;
/// The box scene's sphere diameter (m).
const DIAMETER: f64 = 0.004;

fn context() -> GpuContext {
    GpuContext::new().unwrap_or_else(|e| panic!("{e}"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("gpu_stiffness_damping")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Tolerances of a comparison: positions over the diameter, velocities and angular velocities
/// over the largest.
struct Tolerances {
    position_diameters: f64,
    velocity_relative: f64,
    angular_velocity_relative: f64,
}

fn within(d: &Differences, t: &Tolerances) -> bool {
    d.position_diameters < t.position_diameters
        && d.velocity_relative < t.velocity_relative
        && d.angular_velocity_relative < t.angular_velocity_relative
}

/// The box scenes' tolerances, a few times the largest differences measured on lavapipe after
/// 300 steps over the four laws (Thornton's): positions 4.4e-16 diameters, velocities 1.0e-15
/// and angular velocities 1.9e-15 of the largest (round-off in the order of the sums and in
/// the device's `x^{2/3}`; the others' 3.1e-16 and below). `η` 1 % larger moves positions by
/// 3.9e-4 diameters.
const BOX: Tolerances = Tolerances {
    position_diameters: 2e-15,
    velocity_relative: 5e-15,
    angular_velocity_relative: 5e-15,
};

/// The touching sphere pairs and wall contacts of a GPU state.
fn gpu_contacts(gpu: &GpuState) -> (usize, usize) {
    (
        gpu.pairs.iter().filter(|p| p.active).count(),
        gpu.floor.iter().filter(|w| w.is_some()).count(),
    )
}

/// The end states of `scene` after `steps` steps on the GPU and the CPU path, with their
/// differences (positions over `diameter`) and contacts, printed under `what`.
fn compare(
    ctx: &GpuContext,
    scene: &Scene,
    steps: usize,
    diameter: f64,
    what: &str,
) -> (CpuEnd, GpuState, Differences) {
    gpu_scene_support(scene).unwrap_or_else(|e| panic!("{what}: {e}"));
    let cpu = scene_end::cpu_run(scene, steps);
    let gpu = scene_end::gpu_run(ctx, scene, steps);
    let d = scene_end::differences(&gpu, &cpu, diameter);
    let (touching, walls) = gpu_contacts(&gpu);
    eprintln!(
        "{what}, GPU - CPU after {steps} steps: {d:?}; touching pairs GPU {touching}, CPU {}; \
         wall contacts GPU {walls}, CPU {}",
        cpu.sphere_contacts, cpu.wall_contacts
    );
    (cpu, gpu, d)
}

/// Each normal law with the stiffness-viscous dashpot and its tangential dashpot: the GPU's end
/// state is the CPU path's within [`BOX`], with the same contacts. The dashpot takes the normal
/// law's tangent stiffness of each step in every state the laws pass through here (Thornton's
/// and MDR's plastic loading, unloading, the adhesive neck in tension; `gpu_books.rs` shows the
/// plastic and adhesive works booked). Killed mutants (the device's shader edited, on
/// lavapipe): the secant stiffness `F/δ` in place of `k_n` moves MDR's positions by 1.6e-2
/// diameters.
#[test]
fn each_normal_law_with_the_stiffness_viscous_dashpot_matches_the_cpu_path() {
    let ctx = context();
    for (law, normal) in LAWS {
        let scene = write_box_scene(&scratch(law), normal, STIFFNESS_DAMPING, "");
        let (cpu, gpu, d) = compare(&ctx, &scene, STEPS, DIAMETER, law);
        let (touching, walls) = gpu_contacts(&gpu);
        assert!(cpu.sphere_contacts >= 2, "{law}: {}", cpu.sphere_contacts);
        assert!(cpu.wall_contacts >= 2, "{law}: {}", cpu.wall_contacts);
        assert_eq!(touching, cpu.sphere_contacts, "{law}");
        assert_eq!(walls, cpu.wall_contacts, "{law}");
        assert_eq!(gpu.asymmetric_pairs, 0, "{law}");
        assert!(within(&d, &BOX), "{law}: {d:?}");
    }
}

/// Negative controls: the GPU with `η` 1 % larger, or with no dashpot, misses the CPU path by
/// far more than [`BOX`] (MDR).
#[test]
fn a_wrong_eta_or_no_dashpot_fails_the_comparison() {
    let ctx = context();
    let (law, normal) = LAWS[0];
    let scene = write_box_scene(&scratch("control"), normal, STIFFNESS_DAMPING, "");
    let cpu = scene_end::cpu_run(&scene, STEPS);
    let mut larger = scene.clone();
    larger.contact.sub_models.damping.values[0] *= 1.01;
    let mut none = scene.clone();
    none.contact.sub_models.damping.values[0] = 0.0;
    for (what, wrong) in [("eta 1 % larger", larger), ("eta 0", none)] {
        let d = scene_end::differences(&scene_end::gpu_run(&ctx, &wrong, STEPS), &cpu, DIAMETER);
        eprintln!("{law}, {what} on the GPU: {d:?}");
        assert!(!within(&d, &BOX), "{what}: {d:?}");
    }
}

/// Where the shipped drum's comparison starts (s): its lattice block has fallen onto the drum's
/// side and collapses (from the start it falls freely for about 30 ms, touching nothing).
const DRUM_START_S: f64 = 0.04;
/// Steps of the shipped drum compared from there.
const DRUM_STEPS: u64 = 300;

/// The difference of the damping work the shipped drum's runs book over its steps, as a
/// fraction of that work: measured on lavapipe 8.2e-15.
const BOOK_TOLERANCE: f64 = 5e-14;

/// The shipped drum's tolerances, a few times the differences measured on lavapipe: positions
/// 3.7e-14 diameters, velocities 2.0e-13 and angular velocities 4.6e-13 of the largest (as the
/// small turning drum of `gpu_surfaces.rs`: round-off in the CPU path's turning pose grown
/// through the contacts). `η` 1 % larger on the GPU moves positions by 1.1e-2 diameters.
const DRUM: Tolerances = Tolerances {
    position_diameters: 1e-13,
    velocity_relative: 1e-12,
    angular_velocity_relative: 2e-12,
};

/// The end checkpoint of a run of `scene` (`name`) into `out`, continued from `resume` to
/// `stop` on the CPU or (`ctx`) on the GPU.
fn run_to(
    ctx: Option<&GpuContext>,
    scene: &Scene,
    out: &Path,
    resume: Option<PathBuf>,
    stop: u64,
) -> PathBuf {
    let checkpoint = match ctx {
        Some(ctx) => {
            let options = GpuRunOptions {
                out_dir: out.to_path_buf(),
                quiet: true,
                no_frames: true,
                stop_at_step: Some(stop),
                resume,
                ..GpuRunOptions::default()
            };
            run_gpu_scene(ctx, scene, &options)
                .unwrap_or_else(|e| panic!("{e}"))
                .checkpoint
        }
        None => {
            let options = RunOptions::new(out)
                .quiet(true)
                .no_frames(true)
                .stop_at_step(Some(stop))
                .resume(resume);
            run_scene(scene, &options)
                .unwrap_or_else(|e| panic!("{e}"))
                .checkpoint
        }
    };
    checkpoint.expect("a checkpoint at the stop")
}

/// The largest differences of two checkpoints' positions (over `diameter`), velocities and
/// angular velocities (over the largest of `reference`'s).
fn checkpoint_differences(
    reference: &CheckpointData,
    other: &CheckpointData,
    diameter: f64,
) -> Differences {
    let n = reference.bodies.len().min(other.bodies.len());
    let norm = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
    let diff = |u: [f64; 3], v: [f64; 3]| norm([u[0] - v[0], u[1] - v[1], u[2] - v[2]]);
    let (mut d, mut scale) = ([0.0f64; 3], [0.0f64; 2]);
    for (x, y) in reference.bodies[..n].iter().zip(&other.bodies[..n]) {
        d[0] = d[0].max(diff(x.translation, y.translation));
        d[1] = d[1].max(diff(x.linvel, y.linvel));
        d[2] = d[2].max(diff(x.angvel, y.angvel));
        scale = [scale[0].max(norm(x.linvel)), scale[1].max(norm(x.angvel))];
    }
    Differences {
        position_diameters: d[0] / diameter,
        velocity_relative: d[1] / scale[0],
        angular_velocity_relative: d[2] / scale[1],
    }
}

/// The shipped `scenes/drum.toml`, read from disk as it is (10,404 spheres, MDR, Mindlin,
/// rolling resistance, the stiffness-viscous dashpot, the capped cylinder turning at
/// 1.25 rad/s), runs on the GPU: from the CPU run's checkpoint at [`DRUM_START_S`], where its
/// block has met the drum, [`DRUM_STEPS`] steps on the GPU agree with the CPU run's within
/// [`DRUM`], and so does the damping work booked meanwhile. Negative control: `η` 1 % larger on
/// the GPU only misses the CPU run by far more than [`DRUM`].
#[test]
fn the_shipped_drum_runs_on_the_gpu_as_on_the_cpu() {
    let ctx = context();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/drum.toml");
    let scene = load_scene(&path).unwrap_or_else(|p| panic!("{p}"));
    gpu_scene_support(&scene).unwrap_or_else(|e| panic!("{e}"));
    let diameter = 2.0 * scene.particles[0].radius;
    let dir = scratch("drum");
    let start = (DRUM_START_S / scene.dt).ceil() as u64;
    let end = start + DRUM_STEPS;
    let at_start = run_to(None, &scene, &dir.join("start"), None, start);
    let cpu = run_to(None, &scene, &dir.join("cpu"), Some(at_start.clone()), end);
    let gpu = run_to(
        Some(&ctx),
        &scene,
        &dir.join("gpu"),
        Some(at_start.clone()),
        end,
    );
    let read = |p: &Path| CheckpointData::read(p).unwrap_or_else(|e| panic!("{e}"));
    let (cpu, gpu) = (read(&cpu), read(&gpu));
    let d = checkpoint_differences(&cpu, &gpu, diameter);
    eprintln!(
        "drum.toml, steps {start} to {end} (dt {:e} s), GPU - CPU: {d:?}",
        scene.dt
    );
    assert!(within(&d, &DRUM), "{d:?}");
    // The damping work so far: the books' totals and the live contacts' own books (a CPU
    // checkpoint keeps those apart; a GPU one has them in its totals).
    let damping = |c: &CheckpointData| {
        let lists = c.neighbour_list.as_ref().unwrap();
        c.books.damping
            + lists
                .pair_histories
                .iter()
                .chain(&lists.surface_histories)
                .map(|r| r.contact.books.damping_work)
                .sum::<f64>()
    };
    let (w_start, w_cpu, w_gpu) = (damping(&read(&at_start)), damping(&cpu), damping(&gpu));
    let booked = (w_gpu - w_cpu).abs() / (w_cpu - w_start);
    eprintln!(
        "drum.toml: damping work at the start {w_start:.6e} J, at the end CPU {w_cpu:.9e} J, \
         GPU {w_gpu:.9e} J: they differ by {booked:.2e} of the work of these steps"
    );
    assert!(w_cpu > w_start);
    assert!(booked < BOOK_TOLERANCE, "{booked:e}");
    let mut larger = scene.clone();
    larger.contact.sub_models.damping.values[0] *= 1.01;
    let wrong = run_to(
        Some(&ctx),
        &larger,
        &dir.join("gpu_larger"),
        Some(at_start),
        end,
    );
    let d = checkpoint_differences(&cpu, &read(&wrong), diameter);
    eprintln!("drum.toml, eta 1 % larger on the GPU: {d:?}");
    assert!(!within(&d, &DRUM), "{d:?}");
}
