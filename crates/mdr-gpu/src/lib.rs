//! The neighbour-list path of mdr-dem on the GPU: wgpu compute shaders in f64 (Vulkan, Metal or
//! DX12 with `SHADER_F64`) running the settled-bed system of `mdr-dem bench bed` ([`GpuBed`])
//! and force-mode scenes whose walls are planes, boxes and exact surfaces of revolution
//! (cylinders, cones, orifice plates), fixed, turning about their own axis or removed at a time
//! ([`GpuScene`]; others are refused by [`gpu_scene_support`]; `sim run --device gpu` is
//! [`run_gpu_scene`], a hopper's orifice sweep [`run_gpu_orifice_sweep`]) with the CPU path's
//! arithmetic: the same law formulas (Hertz, MDR, Thornton or adhesive MDR normal, Mindlin
//! tangential, Hertzian or stiffness-viscous damping, optionally rolling resistance) bound per
//! species pair, the same integrator order, the same list and history semantics ([`GpuLaws`]).
//! The design, its determinism and its cost are described in `docs/gpu.md`.
//!
//! ```no_run
//! use mdr_gpu::{bench_bed_gpu, GpuContext, GpuOptions};
//! use mdr_rapier::neighbour_list::bed::{Bed, BenchSettings};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let ctx = GpuContext::new()?; // names what is missing: an adapter, or f64 in shaders
//! let bed = Bed::read_lammps(std::path::Path::new("benches/lammps/settled.data"))?;
//! let settings = BenchSettings { steps: 100, warmup: 10, ..BenchSettings::default() };
//! let (figures, _state) = bench_bed_gpu(&ctx, &bed, &settings, &GpuOptions::default())?;
//! println!("{} particle-steps/s", figures.figures.particle_steps_per_s);
//! # Ok(())
//! # }
//! ```
#![warn(missing_docs)]

mod accessors;
mod bed;
mod bench;
mod checkpoint;
mod device;
mod law;
mod run;
mod scene;
mod sink;
mod sweep;
mod system;
mod walls;

pub use bed::{GpuBed, GpuBooks, GpuOptions, GpuPair, GpuState};
pub use bench::{
    bench_bed_gpu, cpu_reference_run, cpu_reference_run_with, differences, CpuPair, CpuState,
    Differences, GpuBenchFigures,
};
pub use device::{GpuContext, GpuError};
pub use law::{GpuLaws, GpuNormalLaw};
pub use mdr_rapier::neighbour_list::bed::BENCH_THETA_RATIO;
pub use run::{
    gpu_run_support, run_gpu_scene, GpuEnergyRow, GpuRunError, GpuRunOptions, GpuRunSummary,
    GPU_ENERGY_COLUMNS,
};
pub use scene::{
    gpu_scene_support, DeviceSubModels, GpuScene, DEVICE_DAMPING, DEVICE_ROLLING, DEVICE_TANGENTIAL,
};
pub use sweep::run_gpu_orifice_sweep;
