//! The GPU path against the CPU path on a small bed: the bottom layers of the reference bed
//! (the spheres below `z = 2`, about 1,000, on the floor of the 22 × 22 periodic box) stepped a
//! few hundred steps with both, for each law; the GPU repeating itself bit for bit; negative
//! controls; the typed errors. These tests need a Vulkan (or Metal/DX12) device with 64-bit
//! floats: on a machine without one they fail with the error that says what to install.

use mdr_gpu::{
    cpu_reference_run, cpu_reference_run_with, differences, CpuState, Differences, GpuBed,
    GpuContext, GpuError, GpuLaws, GpuNormalLaw, GpuOptions, GpuState,
};
use mdr_rapier::neighbour_list::bed::{reference_data, Bed, BenchLaw, BenchSettings};
use std::path::Path;

fn context() -> GpuContext {
    GpuContext::new().unwrap_or_else(|e| panic!("{e}"))
}

/// The reference bed's spheres below `z = 2`: two layers, resting on the floor and
/// on each other, with the upper ones free to settle.
fn small_bed() -> Bed {
    let path = reference_data(Path::new(env!("CARGO_MANIFEST_DIR"))).unwrap();
    let bed = Bed::read_lammps(&path).unwrap();
    let keep: Vec<usize> = (0..bed.len())
        .filter(|&i| bed.position[i].z < 2.0)
        .collect();
    Bed {
        lo: bed.lo,
        hi: bed.hi,
        diameter: keep.iter().map(|&i| bed.diameter[i]).collect(),
        density: keep.iter().map(|&i| bed.density[i]).collect(),
        position: keep.iter().map(|&i| bed.position[i]).collect(),
    }
}

const STEPS: usize = 400;

fn settings(law: BenchLaw) -> BenchSettings {
    BenchSettings {
        law,
        steps: STEPS,
        warmup: 0,
        threads: 1,
        ..BenchSettings::default()
    }
}

fn gpu_run(ctx: &GpuContext, bed: &Bed, s: &BenchSettings) -> mdr_gpu::GpuState {
    let mut system = GpuBed::new(ctx, bed, s, &GpuOptions::default()).unwrap();
    system.step(STEPS).unwrap();
    system.state().unwrap()
}

/// Both paths on the same bed with the same law, and how far apart they ended.
fn compare(ctx: &GpuContext, bed: &Bed, gpu: &BenchSettings, cpu: &BenchSettings) -> Differences {
    let g = gpu_run(ctx, bed, gpu);
    let c = cpu_reference_run(bed, cpu, STEPS).unwrap();
    assert_eq!(
        g.asymmetric_pairs, 0,
        "both sides of every pair agree bit for bit"
    );
    differences(&g, &c)
}

/// How far the two paths may end apart: a few times the round-off growth measured over 400
/// steps on lavapipe (llvmpipe, Mesa).
struct Tolerances {
    position_diameters: f64,
    velocity: f64,
    angular_velocity: f64,
    max_overlap_relative: f64,
    displacement_relative: f64,
    contact_radius_relative: f64,
    rolling_torque_relative: f64,
    floor_history_relative: f64,
}

/// Hertz and MDR. Measured: positions 2.2e-16 (Hertz) and 9.2e-16 (MDR) diameters, velocities
/// 6.1e-15 and 1.8e-14, angular velocities 8.8e-15 and 4.9e-14, largest overlaps 1.3e-13 of the
/// largest (MDR), tangential displacements 4.2e-14 and 9.5e-13 of the largest, contact radii
/// 6.5e-14 and 1.2e-12, floor histories 6.5e-16 and 1.4e-13 (the adhesive law: 8.3e-16).
const ELASTIC_PLASTIC: Tolerances = Tolerances {
    position_diameters: 5e-15,
    velocity: 1e-13,
    angular_velocity: 3e-13,
    max_overlap_relative: 5e-13,
    displacement_relative: 5e-12,
    contact_radius_relative: 5e-12,
    rolling_torque_relative: 0.0,
    floor_history_relative: 5e-13,
};

/// Thornton's law and rolling resistance, whose contacts change more per step. Measured:
/// positions 3.6e-15 (Thornton) and 2.1e-15 (rolling) diameters, velocities 1.5e-13 and
/// 2.2e-13, angular velocities 3.9e-13 and 4.0e-13, largest overlaps 4.2e-12 and 6.0e-13,
/// tangential displacements 1.2e-11 and 3.5e-12, contact radii 8.4e-12 and 2.3e-12, rolling
/// torques 2.2e-12 of the largest, floor histories 3.8e-12 and 4.8e-15.
const SUB_MODELS: Tolerances = Tolerances {
    position_diameters: 2e-14,
    velocity: 1e-12,
    angular_velocity: 2e-12,
    max_overlap_relative: 2e-11,
    displacement_relative: 5e-11,
    contact_radius_relative: 4e-11,
    rolling_torque_relative: 1e-11,
    floor_history_relative: 2e-11,
};

/// The same touching pairs, and every difference within `t`.
fn assert_within(d: &Differences, t: &Tolerances, what: &str) {
    eprintln!("{what}: {d:?}");
    assert!(
        d.pairs > 900,
        "{what}: a bed with contacts ({} pairs)",
        d.pairs
    );
    assert_eq!(d.unmatched_pairs, 0, "{what}: the same touching pairs");
    assert_eq!(
        d.unmatched_floor_contacts, 0,
        "{what}: the same floor contacts"
    );
    assert!(
        d.floor_history_relative < t.floor_history_relative,
        "{what}: {d:?}"
    );
    assert!(d.position_diameters < t.position_diameters, "{what}: {d:?}");
    assert!(d.velocity < t.velocity, "{what}: {d:?}");
    assert!(d.angular_velocity < t.angular_velocity, "{what}: {d:?}");
    assert!(
        d.max_overlap_relative < t.max_overlap_relative,
        "{what}: {d:?}"
    );
    assert!(
        d.displacement_relative < t.displacement_relative,
        "{what}: {d:?}"
    );
    assert!(
        d.contact_radius_relative < t.contact_radius_relative,
        "{what}: {d:?}"
    );
    assert!(
        d.rolling_torque_relative <= t.rolling_torque_relative,
        "{what}: {d:?}"
    );
}

fn assert_close(d: &Differences, what: &str) {
    assert_within(d, &ELASTIC_PLASTIC, what);
}

/// Hertz + Mindlin + damping with the floor and the periodic box: the GPU equals the CPU path
/// within round-off growth (positions, velocities, histories).
#[test]
fn hertz_bed_matches_the_cpu_path() {
    let ctx = context();
    let s = settings(BenchLaw::Hertz);
    assert_close(&compare(&ctx, &small_bed(), &s, &s), "hertz");
}

/// The MDR law (plastic contacts, `q_c = 10`) with Mindlin and damping: the same.
#[test]
fn mdr_bed_matches_the_cpu_path() {
    let ctx = context();
    let s = settings(BenchLaw::Mdr { qc: 10.0 });
    assert_close(&compare(&ctx, &small_bed(), &s, &s), "mdr");
}

/// Negative control: the GPU with `q_c = 10.5` against the CPU with `q_c = 10` lies far outside
/// the tolerances of the comparison, which therefore sees a 5 % change of a law parameter.
#[test]
fn a_perturbed_law_parameter_fails_the_comparison() {
    let ctx = context();
    let d = compare(
        &ctx,
        &small_bed(),
        &settings(BenchLaw::Mdr { qc: 10.5 }),
        &settings(BenchLaw::Mdr { qc: 10.0 }),
    );
    eprintln!("perturbed: {d:?}");
    // Measured: positions 2.8e-5 diameters apart, largest overlaps 9 % apart.
    assert!(d.max_overlap_relative > 1e-3, "{d:?}");
    assert!(d.position_diameters > 1e-6, "{d:?}");
}

/// Two runs give the same state bit for bit (no atomics on floats, a sorted list), with the
/// MDR law and with the adhesive law and rolling resistance.
#[test]
fn the_gpu_repeats_itself_bit_for_bit() {
    let ctx = context();
    let bed = small_bed();
    let s = settings(BenchLaw::Mdr { qc: 10.0 });
    for laws in [
        None,
        Some(GpuLaws {
            rolling: Some(0.2),
            ..ADHESIVE
        }),
    ] {
        let run = || {
            let options = GpuOptions {
                laws,
                ..GpuOptions::default()
            };
            let mut system = GpuBed::new(&ctx, &bed, &s, &options).unwrap();
            system.step(STEPS).unwrap();
            system.state().unwrap()
        };
        assert_repeats(&run(), &run());
    }
}

fn assert_repeats(a: &GpuState, b: &GpuState) {
    assert!(a.rebuilds >= 1);
    let bits = |v: &[nalgebra::Vector3<f64>]| -> Vec<[u64; 3]> {
        v.iter()
            .map(|x| [x.x.to_bits(), x.y.to_bits(), x.z.to_bits()])
            .collect()
    };
    assert_eq!(bits(&a.position), bits(&b.position));
    assert_eq!(bits(&a.linvel), bits(&b.linvel));
    assert_eq!(bits(&a.angvel), bits(&b.angvel));
    assert_eq!(a.pairs.len(), b.pairs.len());
    for (p, q) in a.pairs.iter().zip(&b.pairs) {
        assert_eq!((p.i, p.j, p.image, p.active), (q.i, q.j, q.image, q.active));
        assert_eq!(p.max_overlap.to_bits(), q.max_overlap.to_bits());
        assert_eq!(
            p.normal_state.map(f64::to_bits),
            q.normal_state.map(f64::to_bits)
        );
        assert_eq!(bits(&[p.displacement]), bits(&[q.displacement]));
        assert_eq!(bits(&[p.rolling_torque]), bits(&[q.rolling_torque]));
    }
    assert_eq!(a.floor, b.floor);
    assert_eq!(bits(&a.floor_rolling_torque), bits(&b.floor_rolling_torque));
}

/// Too few neighbour slots stop the run with the typed error naming the setting.
#[test]
fn too_few_neighbour_slots_are_a_typed_error() {
    let ctx = context();
    let options = GpuOptions {
        max_neighbours: 2,
        ..GpuOptions::default()
    };
    let mut system = GpuBed::new(&ctx, &small_bed(), &settings(BenchLaw::Hertz), &options).unwrap();
    let err = system.step(1).unwrap_err();
    assert!(
        matches!(
            err,
            GpuError::NeighbourOverflow {
                max_neighbours: 2,
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("max_neighbours"), "{err}");
    let bad = GpuOptions {
        max_neighbours: 0,
        ..GpuOptions::default()
    };
    let err = GpuBed::new(&ctx, &small_bed(), &settings(BenchLaw::Hertz), &bad).unwrap_err();
    assert!(err.to_string().contains("max_neighbours"), "{err}");
}

/// The error of a machine without a device tells a Linux user how to get one.
#[test]
fn the_missing_device_errors_name_what_is_missing() {
    let none = GpuError::NoAdapter.to_string();
    assert!(none.contains("no Vulkan, Metal or DX12 adapter"), "{none}");
    assert!(none.contains("mesa-vulkan-drivers"), "{none}");
    let no_f64 = GpuError::NoF64 {
        adapters: "card (Vulkan)".to_owned(),
    }
    .to_string();
    assert!(
        no_f64.contains("64-bit floats") && no_f64.contains("card (Vulkan)"),
        "{no_f64}"
    );
    assert!(no_f64.contains("mesa-vulkan-drivers"), "{no_f64}");
}

/// Both paths with the contact models `gpu` and `cpu` on the same bed (MDR settings otherwise).
fn compare_laws(ctx: &GpuContext, gpu: GpuLaws, cpu: GpuLaws) -> (GpuState, CpuState, Differences) {
    let bed = small_bed();
    let s = settings(BenchLaw::Hertz);
    let options = GpuOptions {
        laws: Some(gpu),
        ..GpuOptions::default()
    };
    let mut system = GpuBed::new(ctx, &bed, &s, &options).unwrap();
    system.step(STEPS).unwrap();
    let g = system.state().unwrap();
    let c = cpu_reference_run_with(&bed, &s, &cpu, STEPS).unwrap();
    assert_eq!(
        g.asymmetric_pairs, 0,
        "both sides of every pair agree bit for bit"
    );
    let d = differences(&g, &c);
    (g, c, d)
}

const THORNTON: GpuLaws = GpuLaws {
    normal: GpuNormalLaw::Thornton {
        yield_pressure: 1000.0,
    },
    rolling: None,
};

/// Thornton's law (1997 unloading, `p_y = 1000`: most contacts of the bed yield) with Mindlin
/// and damping: the GPU equals the CPU path within round-off growth, the residual overlaps of
/// the yielded contacts included.
#[test]
fn thornton_bed_matches_the_cpu_path() {
    let ctx = context();
    let (g, c, d) = compare_laws(&ctx, THORNTON, THORNTON);
    assert_within(&d, &SUB_MODELS, "thornton");
    // The yielded contacts carry a residual overlap (Thornton's δ_p) on both paths.
    let yielded: Vec<_> = c
        .pairs
        .iter()
        .filter(|p| p.residual_overlap > 0.0)
        .collect();
    eprintln!(
        "thornton: {} of {} contacts yielded",
        yielded.len(),
        c.pairs.len()
    );
    assert!(
        yielded.len() > c.pairs.len() / 2,
        "{} yielded",
        yielded.len()
    );
    let active: Vec<_> = g.pairs.iter().filter(|p| p.active).collect();
    let mut worst = 0.0f64;
    for (a, b) in active.iter().zip(&c.pairs) {
        assert_eq!((a.i, a.j, a.image), (b.i, b.j, b.image));
        if b.residual_overlap > 0.0 {
            worst = worst.max((a.normal_state[1] - b.residual_overlap).abs() / b.residual_overlap);
        }
    }
    eprintln!("thornton: residual overlaps within {worst:e}");
    // Measured: 5.6e-13.
    assert!(worst < 3e-12, "{worst:e}");
}

const ROLLING_MDR: GpuLaws = GpuLaws {
    normal: GpuNormalLaw::Mdr { qc: 10.0 },
    rolling: Some(0.2),
};

/// Rolling resistance (`EpsdRolling`, `μ_r = 0.2`) with every normal law (its stiffness is
/// the normal law's tangent stiffness): the GPU equals the CPU path within round-off growth,
/// the rolling springs' torques included.
#[test]
fn rolling_resistance_matches_the_cpu_path() {
    let ctx = context();
    for normal in [
        GpuNormalLaw::Mdr { qc: 10.0 },
        GpuNormalLaw::Hertz,
        THORNTON.normal,
        ADHESIVE.normal,
    ] {
        let laws = GpuLaws {
            normal,
            ..ROLLING_MDR
        };
        let (_, c, d) = compare_laws(&ctx, laws, laws);
        let what = format!("rolling with {}", normal.name());
        assert_within(&d, &SUB_MODELS, &what);
        let loaded = c
            .pairs
            .iter()
            .filter(|p| p.rolling_torque.norm() > 0.0)
            .count();
        eprintln!("{what}: {loaded} of {} springs loaded", c.pairs.len());
        assert!(
            loaded > c.pairs.len() / 2,
            "{what}: {loaded} loaded springs"
        );
    }
}

const ADHESIVE: GpuLaws = GpuLaws {
    normal: GpuNormalLaw::AdhesiveMdr {
        qc: 10.0,
        work_of_adhesion: 2.0,
    },
    rolling: None,
};

/// The adhesive MDR law (`q_c = 10`, `Δγ = 2`): contacts hold at negative overlap until their
/// necks let go; the GPU equals the CPU path within round-off growth, held pairs included.
#[test]
fn adhesive_mdr_bed_matches_the_cpu_path() {
    let ctx = context();
    let (g, c, d) = compare_laws(&ctx, ADHESIVE, ADHESIVE);
    assert_close(&d, "adhesive mdr");
    let held = |position: &[nalgebra::Vector3<f64>], i: u32, j: u32, image: u8| {
        let mut x = position[i as usize] - position[j as usize];
        let len = [c.boundary.lengths()[0], c.boundary.lengths()[1]];
        x.x -= f64::from(i32::from(image / 3) - 1) * len[0];
        x.y -= f64::from(i32::from(image % 3) - 1) * len[1];
        x.norm() > 1.0
    };
    let cpu_held = c
        .pairs
        .iter()
        .filter(|p| held(&c.position, p.i, p.j, p.image))
        .count();
    let gpu_held = g
        .pairs
        .iter()
        .filter(|p| p.active && held(&g.position, p.i, p.j, p.image))
        .count();
    eprintln!("adhesive mdr: {cpu_held} pairs held apart (GPU {gpu_held})");
    assert!(cpu_held > 0, "some pairs hold at negative overlap");
    assert_eq!(cpu_held, gpu_held);
}

/// Negative controls: a 5 % change of Thornton's `p_y`, of `μ_r`, or of `Δγ` on the GPU side
/// lies far outside the tolerances, so the comparisons above see each parameter.
#[test]
fn perturbed_sub_model_parameters_fail_the_comparison() {
    let ctx = context();
    let cases = [
        (
            GpuLaws {
                normal: GpuNormalLaw::Thornton {
                    yield_pressure: 1050.0,
                },
                rolling: None,
            },
            THORNTON,
        ),
        (
            GpuLaws {
                rolling: Some(0.21),
                ..ROLLING_MDR
            },
            ROLLING_MDR,
        ),
        (
            GpuLaws {
                normal: GpuNormalLaw::AdhesiveMdr {
                    qc: 10.0,
                    work_of_adhesion: 2.1,
                },
                rolling: None,
            },
            ADHESIVE,
        ),
    ];
    for (gpu, cpu) in cases {
        let (_, _, d) = compare_laws(&ctx, gpu, cpu);
        eprintln!("perturbed {gpu:?}: {d:?}");
        assert!(
            d.position_diameters > 1e-9 && d.velocity > 1e-7,
            "{gpu:?}: {d:?}"
        );
    }
}
