//! The GPU path against the CPU path on a small bed: the bottom layers of the reference bed
//! (the spheres below `z = 2`, about 1,000, on the floor of the 22 × 22 periodic box) stepped a
//! few hundred steps with both, for each law; the GPU repeating itself bit for bit; negative
//! controls; the typed errors. These tests need a Vulkan (or Metal/DX12) device with 64-bit
//! floats: on a machine without one they fail with the error that says what to install.

use mdr_gpu::{
    cpu_reference_run, differences, Differences, GpuBed, GpuContext, GpuError, GpuOptions,
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

/// Round-off growth over 400 steps. Measured on lavapipe (llvmpipe, Mesa): positions 2.2e-16
/// (Hertz) and 9.2e-16 (MDR) diameters, velocities 6.1e-15 and 1.8e-14, angular velocities
/// 8.8e-15 and 4.9e-14, largest overlaps equal, tangential displacements 4.2e-14 and 9.5e-13 of
/// the largest; the tolerances are a few times those. The same touching pairs.
fn assert_close(d: &Differences, what: &str) {
    eprintln!("{what}: {d:?}");
    assert!(
        d.pairs > 900,
        "{what}: a bed with contacts ({} pairs)",
        d.pairs
    );
    assert_eq!(d.unmatched_pairs, 0, "{what}: the same touching pairs");
    assert!(d.position_diameters < 5e-15, "{what}: {d:?}");
    assert!(d.velocity < 1e-13, "{what}: {d:?}");
    assert!(d.angular_velocity < 3e-13, "{what}: {d:?}");
    assert!(d.max_overlap_relative < 1e-13, "{what}: {d:?}");
    assert!(d.displacement_relative < 5e-12, "{what}: {d:?}");
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

/// Two runs give the same state bit for bit (no atomics on floats, a sorted list).
#[test]
fn the_gpu_repeats_itself_bit_for_bit() {
    let ctx = context();
    let bed = small_bed();
    let s = settings(BenchLaw::Mdr { qc: 10.0 });
    let a = gpu_run(&ctx, &bed, &s);
    let b = gpu_run(&ctx, &bed, &s);
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
        assert_eq!(bits(&[p.displacement]), bits(&[q.displacement]));
    }
    assert_eq!(a.floor, b.floor);
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
