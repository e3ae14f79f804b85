//! A box's slabs on the GPU against the CPU neighbour-list path, where spheres leave the box:
//! an open-top box (each slab a cuboid, touched on its inner face, its rim's top face, its
//! outer face, its edges and corners) with spheres thrown out over the rim, spheres falling
//! onto the rim and off it outside, spheres hitting the outer faces and the floor slab from
//! below, and spheres pushed into the box's inner corners (three slabs at once). Both paths
//! step the scene; at every sample they agree to round-off, with the same touching pairs and
//! wall contacts. Negative controls: one slab thinner on the GPU alone, and the floor slab as
//! the half-space of its inner face (the plane a box's side used to stand for). The device
//! tests need a Vulkan (or Metal/DX12) device with 64-bit floats (on Linux without a GPU,
//! Mesa's lavapipe).

#[path = "common/box_toml.rs"]
mod box_toml;
#[path = "common/scene_end.rs"]
mod scene_end;

use box_toml::BoxToml;
use mdr_gpu::{GpuContext, GpuOptions, GpuScene, GpuState};
use mdr_sim::run::SceneSteps;
use mdr_sim::scene::load_scene;
use mdr_sim::walls::WallPiece;
use mdr_sim::Scene;
use nalgebra::Vector3;
use scene_end::Differences;
use std::path::PathBuf;

/// Steps of the scene (12 ms), compared every [`SAMPLE`] steps.
const STEPS: usize = 600;
const SAMPLE: usize = 50;
/// The spheres' radius (m).
const RADIUS: f64 = 0.002;

/// The largest GPU − CPU differences over every sample: positions over the diameter,
/// velocities and angular velocities over the largest. Measured on lavapipe over the 600 steps:
/// 6.8e-18 diameters, 1.3e-16 and 2.2e-16 (round-off, grown through the collisions); the
/// tolerances are a few times these. The y− side 0.1 mm thinner on the GPU alone misses by
/// 0.040 diameters, 0.090 and 0.12; the floor slab as the half-space of its inner face stops
/// the GPU run at its first step (the centre of the sphere under the floor is 6.5 mm behind
/// that plane, past the wall guard).
const TOLERANCE: [f64; 3] = [5e-17, 1e-15, 1e-15];

fn context() -> GpuContext {
    GpuContext::new().unwrap_or_else(|e| panic!("{e}"))
}

/// An open-top box whose inside is `[-8, 8] mm² × [0, 8] mm`, its slabs 4 mm thick (the sides
/// reach 4 mm above the inside, to the rim's top face at `z = 12` mm; the floor slab's bottom
/// face is at `z = −4` mm), MDR, Mindlin, Hertzian damping and rolling resistance.
const SCENE: BoxToml = BoxToml {
    name: "open_box",
    duration_s: 0.012,
    dt_s: 2.0e-5,
    max_speed_m_per_s: 2.0,
    output_interval_s: 0.006,
    run: "energy_interval_s = 0.001",
    materials: &[("grain", 2.0e6, 0.25, 2500.0, "")],
    contact: "normal = \"mdr\"\ncritical_line_load_n_per_m = 20.0\nhardening_ratio = 0.37\n\
              tangential = \"mindlin\"\nfriction = 0.5\nrolling_friction = 0.1\n\
              damping = \"hertzian_viscous\"\ndamping_gamma_n_per_m_s = 1.0e4\n\
              damping_tangential_ratio = 0.5",
    particles: &[("grain", "particles.csv")],
    wall_material: "grain",
    min_m: [-0.008, -0.008, 0.0],
    max_m: [0.008, 0.008, 0.008],
    thickness_m: 0.004,
    open_top: true,
};

/// The spheres (centre and velocity, m and m/s), 20 of radius 2 mm, none touching at the start:
/// nine inside on a 5 mm lattice 6.5 mm up with the GPU tests' pseudo-random velocities of up
/// to 0.5 m/s per component plus 0.8 m/s upwards (some leave over the rim); four in the inner
/// corners, moving into them; four above the rims, falling (onto the top face of the x+ side,
/// the outer top edge of the x− side, the inner top edge of the y+ side, and the corner where
/// the x+ and y+ sides' rims overlap: two slabs at one spot); and three outside, moving onto the
/// x+ side's outer face, down the y− side's outer face past its bottom edge, and up onto the
/// floor slab's bottom face.
fn spheres() -> Vec<([f64; 3], [f64; 3])> {
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        // SplitMix64: a fixed sequence, the same on every machine.
        seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = seed;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut out = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            let at = |n: usize| -0.005 + 0.005 * n as f64;
            let v = [next(), next(), next() + 0.8];
            out.push(([at(i), at(j), 0.0065], v));
        }
    }
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        out.push((
            [sx * 0.0058, sy * 0.0058, 0.0021],
            [sx * 0.3, sy * 0.3, -0.3],
        ));
    }
    out.extend([
        ([0.010, 0.0, 0.0145], [0.3, 0.0, -0.5]),
        ([-0.0131, 0.003, 0.0138], [0.1, 0.0, -0.5]),
        ([0.0, 0.0105, 0.0146], [0.0, -0.3, -0.5]),
        ([0.0105, 0.0105, 0.0145], [0.0, 0.0, -0.5]),
        ([0.0145, -0.004, 0.006], [-0.3, 0.0, 0.0]),
        ([-0.004, -0.0145, 0.0], [0.0, 0.2, -0.3]),
        ([0.0, 0.005, -0.0065], [0.0, 0.0, 0.3]),
    ]);
    out
}

/// The scene, written under the test's scratch directory.
fn open_box() -> Scene {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu_box");
    std::fs::create_dir_all(&dir).unwrap();
    let mut csv = String::from("x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n");
    for (x, v) in spheres() {
        csv.push_str(&format!(
            "{:?},{:?},{:?},{RADIUS:?},{:?},{:?},{:?}\n",
            x[0], x[1], x[2], v[0], v[1], v[2]
        ));
    }
    std::fs::write(dir.join("particles.csv"), csv).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, SCENE.text()).unwrap();
    load_scene(&path).unwrap_or_else(|p| panic!("{p}"))
}

/// Where a touching sphere's centre lies against the slab it touches: over the slab's inner
/// face (the only place the plane of that face stood for the slab), over another face (the
/// rim's top, the outer face, the floor slab's bottom), beside an edge, or beside a corner.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
struct Features {
    inner_face: usize,
    other_face: usize,
    edge: usize,
    corner: usize,
    /// Spheres touching two or more slabs at once.
    several_slabs: usize,
}

/// The features of the wall contacts of `state` (slabs `slabs`: centre and half extents) and
/// where the box's centre `middle` lies.
fn features(state: &GpuState, slabs: &[(Vector3<f64>, Vector3<f64>)]) -> Features {
    let middle = slabs.iter().map(|s| s.0).sum::<Vector3<f64>>() / slabs.len() as f64;
    let mut f = Features::default();
    for (i, x) in state.position.iter().enumerate() {
        let mut touching = 0;
        for (k, (center, half)) in slabs.iter().enumerate() {
            if state.floor[i * slabs.len() + k].is_none() {
                continue;
            }
            touching += 1;
            let local = x - center;
            let beyond: Vec<usize> = (0..3).filter(|&a| local[a].abs() > half[a]).collect();
            match beyond.len() {
                1 => {
                    let a = beyond[0];
                    let thin = (0..3).min_by(|&p, &q| half[p].total_cmp(&half[q])).unwrap();
                    let inward = (middle[a] - center[a]) * local[a] > 0.0;
                    if a == thin && inward {
                        f.inner_face += 1;
                    } else {
                        f.other_face += 1;
                    }
                }
                2 => f.edge += 1,
                3 => f.corner += 1,
                _ => {}
            }
        }
        if touching > 1 {
            f.several_slabs += 1;
        }
    }
    f
}

/// The box's slabs as the CPU path holds them: centre (world) and half extents.
fn slabs(scene: &Scene) -> Vec<(Vector3<f64>, Vector3<f64>)> {
    scene.walls[0]
        .pieces
        .iter()
        .map(|p| match p {
            WallPiece::Cuboid {
                center,
                half_extents,
                ..
            } => (scene.walls[0].origin + center, *half_extents),
            other => panic!("a box piece that is not a slab: {other:?}"),
        })
        .collect()
}

/// Both paths stepped [`STEPS`] steps, `gpu_scene` on the device and `scene` on the CPU: the
/// largest differences over the samples (or the device's error), the features the device's
/// wall contacts met over the samples, and whether the contact counts agreed at every sample.
fn compare(
    ctx: &GpuContext,
    scene: &Scene,
    gpu_scene: &Scene,
) -> (Result<[f64; 3], String>, Features, bool) {
    let mut cpu = SceneSteps::new(scene).unwrap();
    let mut gpu = GpuScene::new(ctx, gpu_scene, &GpuOptions::default()).unwrap();
    let slabs = slabs(scene);
    let mut worst = [0.0f64; 3];
    let mut seen = Features::default();
    let mut same_contacts = true;
    for _ in 0..STEPS / SAMPLE {
        for _ in 0..SAMPLE {
            cpu.step().unwrap();
        }
        if let Err(e) = gpu.step(SAMPLE) {
            return (Err(e.to_string()), seen, false);
        }
        let state = gpu.state().unwrap();
        let end = scene_end::cpu_state(&cpu);
        let d: Differences = scene_end::differences(&state, &end, 2.0 * RADIUS);
        for (w, v) in worst.iter_mut().zip([
            d.position_diameters,
            d.velocity_relative,
            d.angular_velocity_relative,
        ]) {
            *w = w.max(v);
        }
        let f = features(&state, &slabs);
        seen.inner_face += f.inner_face;
        seen.other_face += f.other_face;
        seen.edge += f.edge;
        seen.corner += f.corner;
        seen.several_slabs += f.several_slabs;
        let pairs = state.pairs.iter().filter(|p| p.active).count();
        let walls = state.floor.iter().filter(|w| w.is_some()).count();
        same_contacts &= (pairs, walls) == (end.sphere_contacts, end.wall_contacts);
        assert_eq!(state.asymmetric_pairs, 0);
    }
    (Ok(worst), seen, same_contacts)
}

fn within(d: &[f64; 3]) -> bool {
    d.iter().zip(&TOLERANCE).all(|(d, t)| d <= t)
}

#[test]
fn spheres_leaving_an_open_box_follow_the_cpu_path() {
    let ctx = context();
    let scene = open_box();
    let (worst, seen, same_contacts) = compare(&ctx, &scene, &scene);
    eprintln!("GPU - CPU over {STEPS} steps: {worst:?}; wall contacts at the samples: {seen:?}");
    let worst = worst.unwrap_or_else(|e| panic!("{e}"));
    // The scene reaches what the planes of the inner faces lacked: the rim's top and the outer
    // faces, the slabs' edges, and a sphere against two or three slabs at once.
    assert!(seen.inner_face > 0, "{seen:?}");
    assert!(seen.other_face > 0, "{seen:?}");
    assert!(seen.edge > 0, "{seen:?}");
    assert!(seen.several_slabs > 0, "{seen:?}");
    // Some spheres end outside the box (beside or under it), the same on both paths.
    let outside = |position: &[Vector3<f64>]| {
        position
            .iter()
            .filter(|x| x.x.abs() > 0.012 || x.y.abs() > 0.012 || x.z < -0.004)
            .count()
    };
    let cpu = scene_end::cpu_run(&scene, STEPS);
    let gpu = scene_end::gpu_run(&ctx, &scene, STEPS);
    eprintln!(
        "{} spheres outside the box at the end",
        outside(&cpu.position)
    );
    assert!(outside(&cpu.position) > 0);
    assert_eq!(outside(&gpu.position), outside(&cpu.position));
    assert!(
        same_contacts,
        "touching pairs or wall contacts differ at a sample"
    );
    assert!(within(&worst), "{worst:?}");
}

#[test]
fn a_thinner_slab_or_the_plane_of_an_inner_face_misses_the_cpu_path() {
    let ctx = context();
    let scene = open_box();
    // The y− side (piece 2: x−, x+, y−, y+, floor) 0.1 mm thinner on the GPU alone, its outer
    // face moved in.
    let mut thinner = scene.clone();
    if let WallPiece::Cuboid {
        center,
        half_extents,
        ..
    } = &mut thinner.walls[0].pieces[2]
    {
        half_extents.y -= 0.5e-4;
        center.y += 0.5e-4;
    }
    let (d, _, _) = compare(&ctx, &scene, &thinner);
    eprintln!("y- side 0.1 mm thinner on the GPU: {d:?}");
    assert!(!d.as_ref().is_ok_and(within), "{d:?}");
    // The floor slab as the half-space of its inner face on the GPU alone.
    let mut plane = scene.clone();
    plane.walls[0].pieces[4] = WallPiece::HalfSpace {
        point: Vector3::zeros(),
        normal: Vector3::z(),
    };
    let (d, _, _) = compare(&ctx, &scene, &plane);
    eprintln!("floor slab as its inner face's plane on the GPU: {d:?}");
    assert!(
        d.as_ref().is_err_and(|e| e.contains("sank more than")),
        "{d:?}"
    );
}
