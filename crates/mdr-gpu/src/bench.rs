//! `mdr-dem bench bed --device gpu`: the bed benchmark on the device, with the figures of the
//! CPU benchmark ([`BenchFigures`]) and the GPU's own, and the comparison with the CPU path.

use crate::bed::{GpuBed, GpuOptions, GpuState};
use crate::device::{GpuContext, GpuError};
use crate::law::GpuLaws;
use mdr_contact::damping::HertzianViscous;
use mdr_contact::normal::{NormalLaw, NormalModel};
use mdr_contact::rolling::{RollingLaw, RollingModel};
use mdr_contact::tangential::Mindlin;
use mdr_rapier::neighbour_list::bed::{
    peak_rss_mb, run_reference_system, Bed, BenchFigures, BenchSettings, BenchValue, ReferenceRun,
    RollingTorque,
};
use mdr_rapier::neighbour_list::{Boundary, NeighbourListStepper};
use mdr_rapier::rapier::prelude::PhysicsWorld;
use nalgebra::Vector3;

/// Figures of one GPU bed run: the CPU benchmark's ([`BenchFigures`]; `threads` is 0,
/// `cpu_seconds` the host's, `stepper_bytes_per_particle` the device buffers', `work_books`
/// false: the bed's device keeps no work books) and the device's own.
#[derive(Debug, Clone, PartialEq)]
pub struct GpuBenchFigures {
    /// The figures in the CPU benchmark's form.
    pub figures: BenchFigures,
    /// The adapter that ran it.
    pub adapter: String,
    /// Whether the adapter is a CPU device (lavapipe): its rates say nothing of a GPU's.
    pub cpu_device: bool,
    /// Bytes of device buffers per sphere.
    pub device_bytes_per_particle: f64,
    /// Neighbour slots per particle.
    pub max_neighbours: u32,
}

impl GpuBenchFigures {
    /// The GPU's own figures by name, as `mdr-dem bench bed --json` adds them.
    pub fn fields(&self) -> [(&'static str, BenchValue<'_>); 4] {
        use BenchValue::{Count, Flag, Real, Text};
        [
            ("gpu_adapter", Text(&self.adapter)),
            ("gpu_is_cpu_device", Flag(self.cpu_device)),
            (
                "device_bytes_per_particle",
                Real(self.device_bytes_per_particle),
            ),
            ("max_neighbours", Count(u64::from(self.max_neighbours))),
        ]
    }
}

/// The bed benchmark on the device: `settings.warmup` untimed steps, then `settings.steps`
/// timed ones (the device waited for at both ends), then the figures. Also returns the final
/// state.
pub fn bench_bed_gpu(
    ctx: &GpuContext,
    bed: &Bed,
    settings: &BenchSettings,
    options: &GpuOptions,
) -> Result<(GpuBenchFigures, GpuState), GpuError> {
    let mut system = GpuBed::new(ctx, bed, settings, options)?;
    system.step(settings.warmup)?;
    let rebuilds0 = system.rebuilds()?;
    let cpu0 = mdr_rapier::neighbour_list::bed::process_cpu_seconds();
    let start = std::time::Instant::now();
    system.step(settings.steps)?;
    let wall_seconds = start.elapsed().as_secs_f64();
    let cpu_seconds = match (cpu0, mdr_rapier::neighbour_list::bed::process_cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    };
    let state = system.state()?;
    let n = system.len();
    let touching = state.pairs.iter().filter(|p| p.active).count();
    let plastic = state
        .pairs
        .iter()
        .filter(|p| p.active && p.max_overlap > system.yield_overlap())
        .count();
    let particle_steps = (n * settings.steps) as f64;
    let vectors = state
        .position
        .iter()
        .chain(&state.linvel)
        .chain(&state.angvel);
    let figures = BenchFigures {
        law: system.laws().normal.name(),
        particles: n,
        steps: settings.steps,
        threads: 0,
        wall_seconds,
        cpu_seconds,
        particle_steps_per_s: particle_steps / wall_seconds,
        particle_steps_per_cpu_s: particle_steps / cpu_seconds,
        ms_per_step: 1e3 * wall_seconds / settings.steps as f64,
        contacts_per_particle: 2.0 * touching as f64 / n as f64,
        floor_contacts: state.floor.iter().filter(|f| f.is_some()).count(),
        plastic_contact_fraction: if touching > 0 {
            plastic as f64 / touching as f64
        } else {
            0.0
        },
        rebuilds: state.rebuilds - rebuilds0,
        peak_rss_mb: peak_rss_mb(),
        stepper_bytes_per_particle: system.device_bytes() as f64 / n as f64,
        orientation: settings.orientation,
        work_books: false,
        state_checksum: mdr_rapier::neighbour_list::bed::state_checksum(vectors),
    };
    Ok((
        GpuBenchFigures {
            figures,
            adapter: ctx.adapter_name(),
            cpu_device: ctx.is_cpu_device(),
            device_bytes_per_particle: system.device_bytes() as f64 / n as f64,
            max_neighbours: options.max_neighbours,
        },
        state,
    ))
}

/// A pair of the CPU path's list with its history, in the form of [`crate::GpuPair`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CpuPair {
    /// The lower index.
    pub i: u32,
    /// The higher index.
    pub j: u32,
    /// Image code of `j` as seen from `i`.
    pub image: u8,
    /// The largest overlap so far.
    pub max_overlap: f64,
    /// Mindlin's `ξ`.
    pub displacement: Vector3<f64>,
    /// Mindlin's contact radius.
    pub contact_radius: f64,
    /// The normal law's residual overlap (`NormalLaw::residual_overlap`).
    pub residual_overlap: f64,
    /// The rolling resistance spring's torque (zero without rolling resistance).
    pub rolling_torque: Vector3<f64>,
}

/// The CPU path's state after a run: particles and the touching pairs' histories.
#[derive(Debug, Clone, PartialEq)]
pub struct CpuState {
    /// Positions.
    pub position: Vec<Vector3<f64>>,
    /// Velocities.
    pub linvel: Vec<Vector3<f64>>,
    /// Angular velocities.
    pub angvel: Vec<Vector3<f64>>,
    /// Touching pairs, sorted by `(i, j, image)`.
    pub pairs: Vec<CpuPair>,
    /// Per particle: the floor contact's `(max overlap, ξ, contact radius)` (as
    /// [`crate::GpuState::floor`]), `None` when apart.
    pub floor: Vec<Option<(f64, Vector3<f64>, f64)>>,
    /// Per particle: the floor contact's rolling torque (zero when apart).
    pub floor_rolling_torque: Vec<Vector3<f64>>,
    /// Neighbour-list builds.
    pub rebuilds: u64,
    /// The box.
    pub boundary: Boundary,
}

/// The CPU path (`NeighbourListStepper` of the reference system) on the same bed and settings,
/// `steps` steps in a pool of `settings.threads` threads (the result does not depend on it).
pub fn cpu_reference_run(
    bed: &Bed,
    settings: &BenchSettings,
    steps: usize,
) -> Result<CpuState, GpuError> {
    cpu_reference_run_with(bed, settings, &GpuLaws::of(settings), steps)
}

/// [`cpu_reference_run`] with the contact model `laws` (as [`crate::GpuOptions::laws`] gives
/// the GPU path): the reference system with that normal law, Mindlin, damping and, where
/// `laws.rolling` is set, `EpsdRolling`, bound by the CPU benchmark's own
/// [`run_reference_system`].
pub fn cpu_reference_run_with(
    bed: &Bed,
    settings: &BenchSettings,
    laws: &GpuLaws,
    steps: usize,
) -> Result<CpuState, GpuError> {
    laws.validate()?;
    run_reference_system(bed, &laws.in_settings(settings), CpuRun { steps })?
}

/// [`cpu_reference_run_with`]'s steps and read-back.
struct CpuRun {
    steps: usize,
}

impl ReferenceRun for CpuRun {
    type Output = Result<CpuState, GpuError>;

    fn run<N, R>(
        self,
        mut stepper: NeighbourListStepper<N, Mindlin, HertzianViscous, R>,
        mut world: PhysicsWorld,
    ) -> Self::Output
    where
        N: NormalModel,
        N::Law: Clone,
        R: RollingModel,
        R::Law: Clone,
        <R::Law as RollingLaw>::State: RollingTorque,
    {
        cpu_run(&mut stepper, &mut world, self.steps)
    }
}

fn cpu_run<N, R>(
    stepper: &mut NeighbourListStepper<N, Mindlin, HertzianViscous, R>,
    world: &mut PhysicsWorld,
    steps: usize,
) -> Result<CpuState, GpuError>
where
    N: NormalModel,
    N::Law: Clone,
    R: RollingModel,
    R::Law: Clone,
    <R::Law as RollingLaw>::State: RollingTorque,
{
    mdr_rapier::neighbour_list::with_workers_awake(|| -> Result<(), GpuError> {
        for _ in 0..steps {
            stepper.step(world)?;
        }
        Ok(())
    })?;
    let list = stepper.pairs();
    let mut pairs = Vec::new();
    for q in 0..list.len() {
        if list.active[q] {
            let (i, j) = (list.i[q] as usize, list.j[q] as usize);
            let law = stepper.sphere_law(i, j);
            let h = &list.history[q].contact;
            pairs.push(CpuPair {
                i: list.i[q],
                j: list.j[q],
                image: list.image[q],
                max_overlap: law.normal.max_overlap(&h.normal),
                displacement: h.tangential.displacement,
                contact_radius: h.tangential.contact_radius,
                residual_overlap: law.normal.residual_overlap(&h.normal),
                rolling_torque: list.history[q].rolling.torque(),
            });
        }
    }
    let n = stepper.particles().len();
    let mut floor = vec![None; n];
    let mut floor_rolling_torque = vec![Vector3::zeros(); n];
    let surface = stepper.surface_pairs();
    for q in 0..surface.len() {
        if surface.active[q] {
            let i = surface.particle[q] as usize;
            let (law, _) = stepper.surface_pair_laws(i, surface.surface[q] as usize);
            let h = &surface.history[q];
            floor[i] = Some((
                law.normal.max_overlap(&h.contact.normal),
                h.contact.tangential.displacement,
                h.contact.tangential.contact_radius,
            ));
            floor_rolling_torque[i] = h.rolling.torque();
        }
    }
    let p = stepper.particles();
    Ok(CpuState {
        floor,
        floor_rolling_torque,
        position: p.position.clone(),
        linvel: p.linvel.clone(),
        angvel: p.angvel.clone(),
        pairs,
        rebuilds: stepper.rebuilds(),
        boundary: *stepper.boundary(),
    })
}

/// How far two runs of the same bed ended apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Differences {
    /// The largest position difference (nearest periodic image in x and y), in sphere
    /// diameters.
    pub position_diameters: f64,
    /// The largest velocity difference (|Δv|).
    pub velocity: f64,
    /// The largest angular velocity difference (|Δω|).
    pub angular_velocity: f64,
    /// The largest difference of a touching pair's largest overlap, relative to it.
    pub max_overlap_relative: f64,
    /// The largest difference of a touching pair's tangential displacement, relative to the
    /// largest displacement of any pair.
    pub displacement_relative: f64,
    /// The largest difference of a touching pair's contact radius, relative to the largest
    /// contact radius of any pair.
    pub contact_radius_relative: f64,
    /// The largest difference of a touching pair's rolling torque, relative to the largest
    /// rolling torque of any pair (zero without rolling resistance).
    pub rolling_torque_relative: f64,
    /// Touching pairs found in one run and not the other.
    pub unmatched_pairs: usize,
    /// The largest difference of a floor contact's history (largest overlap, tangential
    /// displacement, contact radius, rolling torque), each relative to its largest value over
    /// the floor contacts.
    pub floor_history_relative: f64,
    /// Particles touching the floor in one run and not the other.
    pub unmatched_floor_contacts: usize,
    /// Touching pairs compared.
    pub pairs: usize,
}

/// The differences of a GPU state from the CPU state of the same bed (diameter 1).
pub fn differences(gpu: &GpuState, cpu: &CpuState) -> Differences {
    let lengths = cpu.boundary.lengths();
    let position_diameters = gpu
        .position
        .iter()
        .zip(&cpu.position)
        .map(|(a, b)| {
            let mut d = a - b;
            for (k, &length) in lengths.iter().enumerate() {
                if length.is_finite() {
                    d[k] -= (d[k] / length).round() * length;
                }
            }
            d.norm()
        })
        .fold(0.0, f64::max);
    let largest = |a: &[Vector3<f64>], b: &[Vector3<f64>]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).norm())
            .fold(0.0, f64::max)
    };
    let active: Vec<_> = gpu.pairs.iter().filter(|p| p.active).collect();
    let mut unmatched = 0;
    let (mut overlap_rel, mut disp_abs) = (0.0f64, 0.0f64);
    let disp_scale = cpu
        .pairs
        .iter()
        .map(|p| p.displacement.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let scale = |f: &dyn Fn(&CpuPair) -> f64| {
        cpu.pairs
            .iter()
            .map(f)
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE)
    };
    let radius_scale = scale(&|p| p.contact_radius);
    let torque_scale = scale(&|p| p.rolling_torque.norm());
    let (mut radius_abs, mut torque_abs) = (0.0f64, 0.0f64);
    let mut g = 0;
    for c in &cpu.pairs {
        while g < active.len() && (active[g].i, active[g].j, active[g].image) < (c.i, c.j, c.image)
        {
            unmatched += 1;
            g += 1;
        }
        if g < active.len() && (active[g].i, active[g].j, active[g].image) == (c.i, c.j, c.image) {
            let a = active[g];
            overlap_rel = overlap_rel.max((a.max_overlap - c.max_overlap).abs() / c.max_overlap);
            disp_abs = disp_abs.max((a.displacement - c.displacement).norm());
            radius_abs = radius_abs.max((a.contact_radius - c.contact_radius).abs());
            torque_abs = torque_abs.max((a.rolling_torque - c.rolling_torque).norm());
            g += 1;
        } else {
            unmatched += 1;
        }
    }
    unmatched += active.len() - g;
    let (floor_history_relative, unmatched_floor_contacts) = floor_differences(gpu, cpu);
    Differences {
        position_diameters,
        velocity: largest(&gpu.linvel, &cpu.linvel),
        angular_velocity: largest(&gpu.angvel, &cpu.angvel),
        max_overlap_relative: overlap_rel,
        displacement_relative: disp_abs / disp_scale,
        contact_radius_relative: radius_abs / radius_scale,
        rolling_torque_relative: torque_abs / torque_scale,
        unmatched_pairs: unmatched,
        floor_history_relative,
        unmatched_floor_contacts,
        pairs: cpu.pairs.len(),
    }
}

/// A floor contact's `(max overlap, ξ, contact radius)`.
type FloorHistory = (f64, Vector3<f64>, f64);

/// The largest relative difference of the floor contacts' histories, and the particles touching
/// the floor in one run only.
fn floor_differences(gpu: &GpuState, cpu: &CpuState) -> (f64, usize) {
    let both: Vec<_> = gpu
        .floor
        .iter()
        .zip(&cpu.floor)
        .zip(
            gpu.floor_rolling_torque
                .iter()
                .zip(&cpu.floor_rolling_torque),
        )
        .filter_map(|((g, c), t)| Some(((*g)?, (*c)?, t)))
        .collect();
    let unmatched = gpu
        .floor
        .iter()
        .zip(&cpu.floor)
        .filter(|(g, c)| g.is_some() != c.is_some())
        .count();
    let largest = |f: &dyn Fn(&FloorHistory, &Vector3<f64>) -> f64| {
        both.iter()
            .map(|(_, c, (_, t))| f(c, t))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE)
    };
    let scales = [
        largest(&|c, _| c.0),
        largest(&|c, _| c.1.norm()),
        largest(&|c, _| c.2),
        largest(&|_, t| t.norm()),
    ];
    let worst = both
        .iter()
        .map(|(g, c, (tg, tc))| {
            [
                (g.0 - c.0).abs() / scales[0],
                (g.1 - c.1).norm() / scales[1],
                (g.2 - c.2).abs() / scales[2],
                (*tg - *tc).norm() / scales[3],
            ]
            .into_iter()
            .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    (worst, unmatched)
}
