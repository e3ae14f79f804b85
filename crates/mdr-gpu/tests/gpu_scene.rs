//! Scenes on the GPU against the CPU neighbour-list path: a small polydisperse scene (two
//! materials, two radii) thrown about in a closed box, a few hundred steps with both paths;
//! the GPU repeating itself bit for bit; the same scene with a work of adhesion per material,
//! each material pair adhering with its own mixed value; negative controls (a wrong radius of
//! the second species, a wall moved by a fraction of a diameter, one work of adhesion for every
//! pair); and the refusal of scenes with walls or
//! other parts the GPU path lacks (its laws: `gpu_scene_laws.rs`). The device tests need a Vulkan (or Metal/DX12) device with
//! 64-bit floats (on Linux without a GPU, Mesa's lavapipe).

#[path = "common/box_toml.rs"]
mod box_toml;

use box_toml::BoxToml;
use mdr_gpu::{gpu_scene_support, GpuContext, GpuState};
use mdr_sim::scene::load_scene;
use mdr_sim::Scene;
use nalgebra::Vector3;
use std::path::{Path, PathBuf};

const STEPS: usize = 300;

fn context() -> GpuContext {
    GpuContext::new().unwrap_or_else(|e| panic!("{e}"))
}

/// The test scene, written under the test's scratch directory: 216 spheres on a 6 mm lattice
/// (6 × 6 × 6) in the closed box `[-2, 2] cm × [-2, 2] cm × [0, 4] cm`, alternately of radius
/// 2.0 mm (`stiff`, E = 2 MPa) and 2.6 mm (`soft`, E = 0.8 MPa), each with a pseudo-random
/// velocity of up to 0.5 m/s per component: within the 300 steps (6 ms) neighbours collide,
/// spheres hit the walls and the floor, and contacts load plastically (MDR), slide (Mindlin)
/// and roll (rolling resistance), with Hertzian damping.
fn test_scene() -> Scene {
    box_scene("gpu_scene", "", "")
}

/// The test scene under `name`, with `stiff` and `soft` added to those materials' keys.
fn box_scene(name: &str, stiff_keys: &str, soft_keys: &str) -> Scene {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(name)
        // Tests running at once build the same scene: each thread writes and reads its own copy.
        .join(format!("{:?}", std::thread::current().id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        // SplitMix64: a fixed sequence, the same on every machine.
        seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = seed;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let header = "x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n";
    let (mut stiff, mut soft) = (header.to_owned(), header.to_owned());
    for k in 0..6 {
        for j in 0..6 {
            for i in 0..6 {
                let at = |n: usize| -0.015 + 0.006 * n as f64;
                let (x, y, z) = (at(i), at(j), 0.003 + 0.006 * k as f64);
                let v = [next(), next(), next()];
                let (file, r) = if (i + j + k) % 2 == 0 {
                    (&mut stiff, 0.002)
                } else {
                    (&mut soft, 0.0026)
                };
                file.push_str(&format!(
                    "{x:.6},{y:.6},{z:.6},{r},{:.6},{:.6},{:.6}\n",
                    v[0], v[1], v[2]
                ));
            }
        }
    }
    std::fs::write(dir.join("stiff.csv"), stiff).unwrap();
    std::fs::write(dir.join("soft.csv"), soft).unwrap();
    let toml = BoxToml {
        name: "gpu_box",
        duration_s: 0.01,
        dt_s: 2.0e-5,
        max_speed_m_per_s: 1.0,
        output_interval_s: 0.005,
        run: "",
        materials: &[
            ("stiff", 2.0e6, 0.25, 2500.0, stiff_keys),
            ("soft", 8.0e5, 0.3, 1200.0, soft_keys),
        ],
        contact: "normal = \"mdr\"\ncritical_line_load_n_per_m = 20.0\nhardening_ratio = 0.37\n\
                  tangential = \"mindlin\"\nfriction = 0.5\nrolling_friction = 0.1\n\
                  damping = \"hertzian_viscous\"\ndamping_gamma_n_per_m_s = 1.0e4\n\
                  damping_tangential_ratio = 0.5",
        particles: &[("stiff", "stiff.csv"), ("soft", "soft.csv")],
        wall_material: "stiff",
        min_m: [-0.02, -0.02, 0.0],
        max_m: [0.02, 0.02, 0.04],
        thickness_m: 0.004,
        open_top: false,
    }
    .text();
    let path = dir.join("gpu_box.toml");
    std::fs::write(&path, toml).unwrap();
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}

#[path = "common/scene_end.rs"]
mod scene_end;
use scene_end::{CpuEnd, Differences};

fn cpu_run(scene: &Scene) -> CpuEnd {
    scene_end::cpu_run(scene, STEPS)
}

fn gpu_run(ctx: &GpuContext, scene: &Scene) -> GpuState {
    scene_end::gpu_run(ctx, scene, STEPS)
}

fn scene_differences(gpu: &GpuState, cpu: &CpuEnd) -> Differences {
    scene_end::differences(gpu, cpu, 0.004)
}

/// Measured on lavapipe after 300 steps: positions 1.7e-15 diameters, velocities 2.0e-15 and
/// angular velocities 1.6e-15 of the largest (round-off in the order of the sums); the
/// tolerances are a few times these, far below what a wrong radius gives (4e-3 diameters, see
/// the negative controls).
const POSITION_DIAMETERS: f64 = 1e-14;
const VELOCITY_RELATIVE: f64 = 1e-14;
const ANGULAR_VELOCITY_RELATIVE: f64 = 1e-14;

fn within(d: &Differences) -> bool {
    within_tolerances(d, 1.0)
}

/// Within the tolerances times `factor`.
fn within_tolerances(d: &Differences, factor: f64) -> bool {
    d.position_diameters < factor * POSITION_DIAMETERS
        && d.velocity_relative < factor * VELOCITY_RELATIVE
        && d.angular_velocity_relative < factor * ANGULAR_VELOCITY_RELATIVE
}

/// The adhesive scene's tolerances over the others: measured on lavapipe after 300 steps,
/// positions 9.7e-16 diameters, velocities 3.3e-15 and angular velocities 5.0e-15 of the
/// largest (round-off grows faster through the necks' let-go); twice the others' tolerances
/// are a few times these.
const ADHESIVE_FACTOR: f64 = 2.0;

#[test]
fn a_polydisperse_box_scene_matches_the_cpu_path() {
    let ctx = context();
    let scene = test_scene();
    gpu_scene_support(&scene).unwrap();
    let cpu = cpu_run(&scene);
    let gpu = gpu_run(&ctx, &scene);
    let d = scene_differences(&gpu, &cpu);
    eprintln!("GPU - CPU after {STEPS} steps: {d:?}");
    // The scene is a real test: many sphere and wall contacts at the end.
    let touching = gpu.pairs.iter().filter(|p| p.active).count();
    let walls = gpu.floor.iter().filter(|w| w.is_some()).count();
    eprintln!(
        "touching pairs: GPU {touching}, CPU {}; wall contacts: GPU {walls}, CPU {}",
        cpu.sphere_contacts, cpu.wall_contacts
    );
    assert!(cpu.sphere_contacts >= 20, "{}", cpu.sphere_contacts);
    assert!(cpu.wall_contacts >= 3, "{}", cpu.wall_contacts);
    assert_eq!(touching, cpu.sphere_contacts);
    assert_eq!(walls, cpu.wall_contacts);
    assert_eq!(gpu.asymmetric_pairs, 0);
    assert!(within(&d), "{d:?}");
}

#[test]
fn the_gpu_scene_repeats_itself_bit_for_bit() {
    let ctx = context();
    let scene = test_scene();
    let (a, b) = (gpu_run(&ctx, &scene), gpu_run(&ctx, &scene));
    let bits = |v: &[Vector3<f64>]| -> Vec<[u64; 3]> {
        v.iter()
            .map(|x| [x.x.to_bits(), x.y.to_bits(), x.z.to_bits()])
            .collect()
    };
    assert_eq!(bits(&a.position), bits(&b.position));
    assert_eq!(bits(&a.linvel), bits(&b.linvel));
    assert_eq!(bits(&a.angvel), bits(&b.angvel));
    assert_eq!(a.pairs.len(), b.pairs.len());
    for (p, q) in a.pairs.iter().zip(&b.pairs) {
        assert_eq!((p.i, p.j, p.active), (q.i, q.j, q.active));
        assert_eq!(p.max_overlap.to_bits(), q.max_overlap.to_bits());
        assert_eq!(bits(&[p.displacement]), bits(&[q.displacement]));
        assert_eq!(bits(&[p.rolling_torque]), bits(&[q.rolling_torque]));
    }
    assert_eq!(a.floor, b.floor);
}

#[test]
fn a_wrong_second_radius_or_a_moved_wall_fails_the_comparison() {
    let ctx = context();
    let scene = test_scene();
    let cpu = cpu_run(&scene);
    // The soft spheres 0.1 % larger on the GPU only.
    let mut larger = scene.clone();
    for p in &mut larger.particles {
        if p.radius > 0.0025 {
            p.radius *= 1.001;
        }
    }
    let d = scene_differences(&gpu_run(&ctx, &larger), &cpu);
    eprintln!("second species 0.1 % larger: {d:?}");
    assert!(!within(&d), "{d:?}");
    // The box moved by 1 µm along each axis on the GPU only.
    let mut moved = scene.clone();
    moved.walls[0].origin += Vector3::repeat(1e-6);
    let d = scene_differences(&gpu_run(&ctx, &moved), &cpu);
    eprintln!("box moved by 1 um: {d:?}");
    assert!(!within(&d), "{d:?}");
}

fn scene_file(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name);
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}

#[test]
fn scenes_the_gpu_lacks_a_part_of_are_refused_by_name() {
    for file in [
        "column.toml",
        "bed.toml",
        "drop.toml",
        "funnel.toml",
        "funnel_mdr.toml",
    ] {
        gpu_scene_support(&scene_file(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
    }
    let mut sink = test_scene();
    sink.source.run.delete_below_m = Some(-0.1);
    gpu_scene_support(&sink).unwrap();
    let mut removed = test_scene();
    removed.walls[0].removed_at = Some(0.001);
    gpu_scene_support(&removed).unwrap();
    let mut rotating = test_scene();
    rotating.walls[0].angular_velocity = Some(Vector3::z());
    let err = gpu_scene_support(&rotating).unwrap_err().to_string();
    assert!(err.contains("angular_velocity_rad_per_s"), "{err}");
    let mut restitution = test_scene();
    restitution.coupling = mdr_sim::scene::CouplingMode::Restitution;
    let err = gpu_scene_support(&restitution).unwrap_err().to_string();
    assert!(err.contains("restitution"), "{err}");
    assert!(err.contains("--device gpu"), "{err}");
}

/// Works of adhesion (J/m²) of the adhesive box scene's materials: the pairs adhere with
/// `√(Δγ_i Δγ_j)`: stiff–stiff and stiff–box 0.5, stiff–soft and soft–box 1.0, soft–soft 2.0.
const STIFF_ADHESION: f64 = 0.5;
const SOFT_ADHESION: f64 = 2.0;

/// The test scene with a work of adhesion per material (the JKR pull-off force of two soft
/// spheres, `(3/2) π Δγ R` = 12 mN, is 14 times a soft sphere's weight): each material pair
/// runs its own mixed value on the GPU as on the CPU path, within [`ADHESIVE_FACTOR`] times the
/// tolerances of the scene without adhesion, with a contact held apart by its neck at the end.
/// Negative control:
/// the GPU with one work of adhesion for every pair (the largest, as the scene's law carries
/// it) misses the CPU path by far more.
#[test]
fn a_two_material_adhesive_scene_matches_the_cpu_path_pair_by_pair() {
    let ctx = context();
    let key = |w: f64| format!("work_of_adhesion_j_per_m2 = {w:?}\n");
    let scene = box_scene(
        "gpu_scene_adhesive",
        &key(STIFF_ADHESION),
        &key(SOFT_ADHESION),
    );
    assert_eq!(scene.contact.normal.law, "adhesive_mdr");
    let mixed = (STIFF_ADHESION * SOFT_ADHESION).sqrt();
    for (a, b, w) in [(0, 0, STIFF_ADHESION), (0, 1, mixed), (1, 1, SOFT_ADHESION)] {
        assert!((scene.contact.pair_work_of_adhesion(a, b) / w - 1.0).abs() < 1e-12);
    }
    gpu_scene_support(&scene).unwrap();
    let cpu = cpu_run(&scene);
    let gpu = gpu_run(&ctx, &scene);
    let d = scene_differences(&gpu, &cpu);
    eprintln!("adhesive: GPU - CPU after {STEPS} steps: {d:?}");
    let touching = gpu.pairs.iter().filter(|p| p.active).count();
    let walls = gpu.floor.iter().filter(|w| w.is_some()).count();
    let radius = |i: u32| scene.particles[i as usize].radius;
    let held = gpu
        .pairs
        .iter()
        .filter(|p| {
            let gap = (gpu.position[p.i as usize] - gpu.position[p.j as usize]).norm()
                - radius(p.i)
                - radius(p.j);
            p.active && gap > 0.0
        })
        .count();
    eprintln!(
        "adhesive: touching pairs GPU {touching}, CPU {}; wall contacts GPU {walls}, CPU {}; \
         {held} pairs held apart",
        cpu.sphere_contacts, cpu.wall_contacts
    );
    assert!(cpu.sphere_contacts >= 20, "{}", cpu.sphere_contacts);
    assert_eq!(touching, cpu.sphere_contacts);
    assert_eq!(walls, cpu.wall_contacts);
    assert!(held > 0, "some pairs hold at negative overlap");
    assert_eq!(gpu.asymmetric_pairs, 0);
    assert!(within_tolerances(&d, ADHESIVE_FACTOR), "{d:?}");
    // One work of adhesion for every pair, on the GPU only.
    let mut one = scene.clone();
    one.contact.works_of_adhesion.clear();
    assert!((one.contact.pair_work_of_adhesion(0, 0) / SOFT_ADHESION - 1.0).abs() < 1e-12);
    let d = scene_differences(&gpu_run(&ctx, &one), &cpu);
    eprintln!("adhesive, one work of adhesion for every pair: {d:?}");
    assert!(!within_tolerances(&d, 1e3 * ADHESIVE_FACTOR), "{d:?}");
}
