//! The GPU scene tests' comparison with the CPU neighbour-list path: a scene run the same
//! number of steps on both, and the largest differences of their end states.

use mdr_gpu::{GpuContext, GpuOptions, GpuScene, GpuState};
use mdr_sim::run::SceneSteps;
use mdr_sim::Scene;
use nalgebra::Vector3;

/// The CPU neighbour-list path's state after its steps: positions, velocities, angular
/// velocities, touching sphere pairs and wall contacts.
pub struct CpuEnd {
    pub position: Vec<Vector3<f64>>,
    pub linvel: Vec<Vector3<f64>>,
    pub angvel: Vec<Vector3<f64>>,
    pub sphere_contacts: usize,
    pub wall_contacts: usize,
}

pub fn cpu_run(scene: &Scene, steps: usize) -> CpuEnd {
    let mut run = SceneSteps::new(scene).unwrap();
    for _ in 0..steps {
        run.step().unwrap();
    }
    cpu_state(&run)
}

/// The CPU neighbour-list path's state now.
pub fn cpu_state(run: &SceneSteps) -> CpuEnd {
    let contacts = run.contacts();
    let p = run.neighbour_list_particles().unwrap();
    CpuEnd {
        position: p.position.clone(),
        linvel: p.linvel.clone(),
        angvel: p.angvel.clone(),
        sphere_contacts: contacts.sphere,
        wall_contacts: contacts.wall,
    }
}

pub fn gpu_run(ctx: &GpuContext, scene: &Scene, steps: usize) -> GpuState {
    let mut gpu = GpuScene::new(ctx, scene, &GpuOptions::default()).unwrap();
    gpu.step(steps).unwrap();
    gpu.state().unwrap()
}

/// The largest differences: positions over the diameter, velocities over the largest speed,
/// angular velocities over the largest angular speed.
#[derive(Debug)]
pub struct Differences {
    pub position_diameters: f64,
    pub velocity_relative: f64,
    pub angular_velocity_relative: f64,
}

fn max_norm(v: &[Vector3<f64>]) -> f64 {
    v.iter().map(|x| x.norm()).fold(0.0, f64::max)
}

fn max_difference(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max)
}

/// The differences of the GPU's end state from the CPU's, positions over `diameter` (m).
pub fn differences(gpu: &GpuState, cpu: &CpuEnd, diameter: f64) -> Differences {
    Differences {
        position_diameters: max_difference(&gpu.position, &cpu.position) / diameter,
        velocity_relative: max_difference(&gpu.linvel, &cpu.linvel) / max_norm(&cpu.linvel),
        angular_velocity_relative: max_difference(&gpu.angvel, &cpu.angvel) / max_norm(&cpu.angvel),
    }
}
