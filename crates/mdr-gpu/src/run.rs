//! `sim run` on the GPU ([`run_gpu_scene`]): a force-mode scene stepped on the device
//! ([`GpuScene`]) with the outputs of the CPU run that the device's state gives: the VTK frames
//! and their ParaView collection (every field of the CPU run's frames), the energy books with the
//! CPU run's columns ([`GPU_ENERGY_COLUMNS`]) and its energy guard (`max_energy_drift`), the
//! headline with its series, CSV, plots and TOML report, and a progress bar.
//!
//! The samples are taken where the CPU run takes them: at step `k` the device has evaluated
//! the forces at `x_k` (the pass that sets each contact's state) and not yet integrated, so
//! positions, velocities and contacts all describe `x_k` ([`GpuScene::step_and_evaluate`]).
//!
//! The elastic energies stored in the contacts, and the plastic work of the live contacts, are
//! evaluated from the histories read back at each energy sample, by the law crate
//! ([`GpuScene`]'s bound laws). A frame's `plastic_work_j` is each sphere's plastic work as the
//! CPU run's frames give it: the contacts that ended, booked per sphere on the device, and the
//! live contacts' from the histories read back for the frame (half of a pair's to each sphere,
//! a wall contact's to its sphere); the steps between samples compute nothing for it. The
//! dissipated works (friction, damping, rolling, the springs' stiffness energy, the adhesive
//! work, and the plastic work of the contacts that ended) are booked on the device at every
//! step, per particle, in f64 ([`GpuBooks`]), and summed in particle order at a sample; the
//! balance then closes as the CPU run's does, and the energy guard stops a run whose balance
//! drifts beyond `max_energy_drift` at the sample where the CPU run would stop (the same
//! message). The turning walls' work is booked on the device like the other works, and so is
//! the energy the spheres the sink parks take out of the run. A scene that asks for a contact
//! network is refused with the key named ([`gpu_run_support`]).
//!
//! Checkpoints are the CPU run's ([`mdr_sim::run::CheckpointData`], written where the CPU run
//! writes them: every `checkpoint_interval_s`, at an interrupt and at the end), taken before
//! the force pass of their step as the CPU run takes them; a run resumes from a checkpoint of
//! either device (`crate::checkpoint` maps the state).

use crate::checkpoint::{lists_record, particle_records, state_of_checkpoint};
use crate::device::{GpuContext, GpuError};
use crate::scene::{gpu_scene_support, GpuScene};
use crate::system::{GpuBooks, GpuOptions, GpuState};
use indicatif::{ProgressBar, ProgressStyle};
use mdr_sim::checkpoint::{self, CheckpointError};
use mdr_sim::headline::{HeadlineReport, HeadlineSample, ParticleView, Tracker};
use mdr_sim::output::energy::{self, EnergyRow};
use mdr_sim::output::plot;
use mdr_sim::output::vtk::{self, CollectionEntry, ParticleFrame};
use mdr_sim::run::{Books, CheckpointData, NeighbourListRun, CROSSING_OVERLAP};
use mdr_sim::Scene;
use nalgebra::Vector3;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The energy-book columns a GPU run writes (`<name>_energy.csv`), the CPU run's, in its
/// order (and `adhesive_j` after them when a row books adhesive work, as the CPU run writes
/// it): the kinetic and gravitational energies from the state read back, the elastic energies
/// the contacts' histories store, the works booked on the device, the balance, and the
/// contacts alive. `removed_j` is the energy the sink's parked spheres took out of the run.
pub const GPU_ENERGY_COLUMNS: [&str; 17] = [
    "time_s",
    "kinetic_translational_j",
    "kinetic_rotational_j",
    "gravitational_j",
    "elastic_normal_j",
    "elastic_tangential_j",
    "plastic_j",
    "friction_j",
    "damping_j",
    "wall_work_j",
    "balance_j",
    "contacts",
    "elastic_rolling_j",
    "rolling_j",
    "stiffness_tangential_j",
    "stiffness_rolling_j",
    "removed_j",
];

/// Steps between two looks at the interrupt flag and the progress bar.
const STEPS_PER_CHECK: u64 = 1000;

/// How to run a scene on the GPU.
#[derive(Debug, Clone, Default)]
pub struct GpuRunOptions {
    /// Output directory (frames, CSV, plots).
    pub out_dir: PathBuf,
    /// No progress bar.
    pub quiet: bool,
    /// Stop at this step (tests).
    pub stop_at_step: Option<u64>,
    /// Set from outside (Ctrl-C) to stop within 1,000 steps.
    pub interrupt: Option<Arc<AtomicBool>>,
    /// Skip the VTK frames.
    pub no_frames: bool,
    /// Write no checkpoints, whatever the scene's `checkpoint_interval_s`.
    pub without_checkpoints: bool,
    /// Continue from this checkpoint (written by a GPU or a CPU run of the same scene).
    pub resume: Option<PathBuf>,
    /// The device's list and grid sizes.
    pub device: GpuOptions,
}

/// One row of the energy books a GPU run keeps.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GpuEnergyRow {
    /// Simulated time (s).
    pub time_s: f64,
    /// `Σ ½ m v²` (J).
    pub kinetic_translational_j: f64,
    /// `Σ ½ I ω²` with `I = (2/5) m r²` (J).
    pub kinetic_rotational_j: f64,
    /// `−Σ m g·x` (J).
    pub gravitational_j: f64,
    /// Elastic energy stored in the normal direction of the touching contacts (J).
    pub elastic_normal_j: f64,
    /// Elastic energy stored in the tangential springs of the touching contacts (J).
    pub elastic_tangential_j: f64,
    /// Elastic energy stored in the rolling-resistance springs of the touching contacts (J).
    pub elastic_rolling_j: f64,
    /// Contacts alive (touching, or held by an adhesive neck): sphere pairs and wall contacts.
    pub contacts: u64,
    /// Work dissipated by plasticity since the start (J): the contacts that ended, booked on
    /// the device, and the live contacts' from their histories.
    pub plastic_j: f64,
    /// Work dissipated by friction since the start (J).
    pub friction_j: f64,
    /// Work dissipated by damping since the start (J).
    pub damping_j: f64,
    /// Work dissipated by rolling resistance since the start (J).
    pub rolling_j: f64,
    /// Energy the tangential springs lost without work since the start (J).
    pub stiffness_tangential_j: f64,
    /// Energy the rolling springs lost without work since the start (J).
    pub stiffness_rolling_j: f64,
    /// Adhesive work since the start (J).
    pub adhesive_j: f64,
    /// Work the turning walls did on the particles since the start (J).
    pub wall_work_j: f64,
    /// Energy the spheres the sink (`[run] delete_below_m`) parked took out of the run since
    /// the start (J).
    pub removed_j: f64,
    /// The sum of the books (`EnergyRow::with_balance`): constant in an exact integration.
    pub balance_j: f64,
}

impl GpuEnergyRow {
    /// The columns of a CPU run's row that a GPU run keeps (a checkpoint's rows).
    fn of_energy_row(row: &EnergyRow) -> Self {
        Self {
            time_s: row.time_s,
            kinetic_translational_j: row.kinetic_translational_j,
            kinetic_rotational_j: row.kinetic_rotational_j,
            gravitational_j: row.gravitational_j,
            elastic_normal_j: row.elastic_normal_j,
            elastic_tangential_j: row.elastic_tangential_j,
            elastic_rolling_j: row.elastic_rolling_j,
            contacts: row.contacts,
            plastic_j: row.plastic_j,
            friction_j: row.friction_j,
            damping_j: row.damping_j,
            rolling_j: row.rolling_j,
            stiffness_tangential_j: row.stiffness_tangential_j,
            stiffness_rolling_j: row.stiffness_rolling_j,
            adhesive_j: row.adhesive_j,
            wall_work_j: row.wall_work_j,
            removed_j: row.removed_j,
            balance_j: row.balance_j,
        }
    }

    /// The row in the CPU run's type (for its CSV writer and for a checkpoint).
    fn as_energy_row(&self) -> EnergyRow {
        EnergyRow {
            time_s: self.time_s,
            kinetic_translational_j: self.kinetic_translational_j,
            kinetic_rotational_j: self.kinetic_rotational_j,
            gravitational_j: self.gravitational_j,
            elastic_normal_j: self.elastic_normal_j,
            elastic_tangential_j: self.elastic_tangential_j,
            elastic_rolling_j: self.elastic_rolling_j,
            contacts: self.contacts,
            plastic_j: self.plastic_j,
            friction_j: self.friction_j,
            damping_j: self.damping_j,
            rolling_j: self.rolling_j,
            stiffness_tangential_j: self.stiffness_tangential_j,
            stiffness_rolling_j: self.stiffness_rolling_j,
            adhesive_j: self.adhesive_j,
            balance_j: self.balance_j,
            wall_work_j: self.wall_work_j,
            removed_j: self.removed_j,
        }
    }
}

/// What a GPU run did.
#[derive(Debug, Clone)]
pub struct GpuRunSummary {
    /// Last step reached.
    pub step: u64,
    /// Simulated time reached (s).
    pub time: f64,
    /// Step the run started from (0, or the checkpoint's step of a resumed run).
    pub start_step: u64,
    /// Whether the run stopped early (interrupt or `stop_at_step`).
    pub stopped_early: bool,
    /// The last checkpoint written, if any.
    pub checkpoint: Option<PathBuf>,
    /// The energy books the GPU run keeps.
    pub energy: Vec<GpuEnergyRow>,
    /// The headline result.
    pub headline: HeadlineReport,
    /// Wall-clock seconds spent stepping.
    pub wall_seconds: f64,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// The adapter the run used.
    pub adapter: String,
}

/// Errors of a GPU run.
#[derive(Debug, thiserror::Error)]
pub enum GpuRunError {
    /// The scene or the device refused the run before it started.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The run stopped: the frames and series up to `step` are written.
    #[error(
        "--device gpu: the run stopped at t = {time:.6e} s (step {step}): {reason}; the frames \
         and series up to there are in {}",
        out.display()
    )]
    Stopped {
        /// Simulated time (s).
        time: f64,
        /// The step.
        step: u64,
        /// Why.
        reason: String,
        /// The output folder.
        out: PathBuf,
    },
    /// A checkpoint could not be read, does not belong to the scene, or could not be written.
    #[error(transparent)]
    Checkpoint(#[from] CheckpointError),
    /// The scene's CPU set-up, which a checkpoint takes its walls from, failed.
    #[error(transparent)]
    Scene(#[from] mdr_sim::SimError),
    /// An output file could not be written.
    #[error("writing {}: {source}", path.display())]
    Output {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// Whether `sim run --device gpu` runs `scene`: [`gpu_scene_support`], and the output the
/// GPU run cannot write refused by its key: `contact_network`. Needs no device.
pub fn gpu_run_support(scene: &Scene) -> Result<(), GpuError> {
    gpu_scene_support(scene)?;
    if scene.contact_network {
        return Err(GpuError::Unsupported(format!(
            "scene `{}`: `contact_network = true`: the GPU keeps no per-pair forces for the \
             contact-network frames (run on the CPU path, or leave the key out)",
            scene.name
        )));
    }
    Ok(())
}

fn every(interval: f64, dt: f64) -> u64 {
    ((interval / dt).round() as u64).max(1)
}

/// The smallest multiple of `every` above `k`.
fn next_multiple(k: u64, every: u64) -> u64 {
    (k / every + 1) * every
}

/// Run `scene` on `ctx`'s device from its set-up, or from `options.resume`.
pub fn run_gpu_scene(
    ctx: &GpuContext,
    scene: &Scene,
    options: &GpuRunOptions,
) -> Result<GpuRunSummary, GpuRunError> {
    gpu_run_support(scene)?;
    let gpu = GpuScene::new(ctx, scene, &options.device)?;
    let out = options.out_dir.clone();
    std::fs::create_dir_all(&out).map_err(|source| GpuRunError::Output {
        path: out.clone(),
        source,
    })?;
    let mut run = GpuRun {
        scene,
        gpu,
        out,
        tracker: Tracker::new(scene),
        collection: Vec::new(),
        energy: Vec::new(),
        samples: Vec::new(),
        checkpoints: Vec::new(),
        step: 0,
        guard_floor_j: mdr_sim::run::one_diameter_lift_j(scene),
    };
    if let Some(path) = &options.resume {
        run.resume(path)?;
    }
    let mut summary = run.run(options)?;
    summary.adapter = ctx.adapter_name();
    Ok(summary)
}

/// A scene being run on the device.
struct GpuRun<'a> {
    scene: &'a Scene,
    gpu: GpuScene,
    out: PathBuf,
    tracker: Tracker,
    collection: Vec<CollectionEntry>,
    energy: Vec<GpuEnergyRow>,
    samples: Vec<HeadlineSample>,
    /// The checkpoints written, oldest first (the last three are kept).
    checkpoints: Vec<PathBuf>,
    /// The device holds `x_step`, `v_step` and the histories up to `x_{step−1}` at the top of
    /// the loop; the forces at `x_step` are evaluated before the samples.
    step: u64,
    /// The floor of the energy guard's scale (J; `mdr_sim::run::one_diameter_lift_j`).
    guard_floor_j: f64,
}

/// The state at a sample and what the outputs read from it.
struct Sample {
    state: GpuState,
    contacts: Vec<u32>,
}

impl GpuRun<'_> {
    fn time(&self) -> f64 {
        self.step as f64 * self.scene.dt
    }

    /// Continue from the checkpoint at `path` (of either device): the device state, the step,
    /// the headline tracker, the frames' collection, the energy rows and the headline samples;
    /// frames and checkpoints past it are removed, as the CPU run removes them.
    fn resume(&mut self, path: &Path) -> Result<(), GpuRunError> {
        let scene = self.scene;
        let data = CheckpointData::read(path)?;
        data.check_scene(scene, path)?;
        let state = state_of_checkpoint(
            scene.contact.normal.law,
            &data,
            scene.particles.len(),
            self.gpu.walls().len(),
            mdr_sim::run::build::skin(scene),
        )?;
        self.gpu.load(&state, data.step)?;
        self.step = data.step;
        self.tracker = data.tracker;
        self.collection = data.collection;
        self.samples = data.samples;
        self.energy = data
            .energy
            .iter()
            .map(GpuEnergyRow::of_energy_row)
            .collect();
        let frames = self.collection.iter().filter(|e| e.part == 0).count();
        let contact_frames = self.collection.iter().filter(|e| e.part == 1).count();
        mdr_sim::output::run_dir::remove_stale(
            &self.out,
            &scene.name,
            frames,
            contact_frames,
            self.step,
        )
        .map_err(output(&self.out))?;
        let pvd = self.out.join(format!("{}.pvd", scene.name));
        vtk::write_collection(&pvd, &self.collection).map_err(output(&pvd))
    }

    /// Write the checkpoint of the current step (the device between two steps: before the
    /// force pass of `step`), keeping the last three.
    fn write_checkpoint(&mut self) -> Result<(), GpuRunError> {
        let scene = self.scene;
        let path = self
            .out
            .join("checkpoints")
            .join(mdr_sim::output::run_dir::checkpoint_name(
                &scene.name,
                self.step,
            ));
        let state = self.device(|gpu| gpu.state())?;
        let books = cpu_books(&state);
        let run = NeighbourListRun {
            step: self.step,
            particles: particle_records(&state),
            lists: lists_record(
                scene.contact.normal.law,
                &state,
                mdr_sim::run::build::skin(scene),
            ),
            books,
            tracker: self.tracker.clone(),
            collection: self.collection.clone(),
            energy: self
                .energy
                .iter()
                .map(GpuEnergyRow::as_energy_row)
                .collect(),
            samples: self.samples.clone(),
        };
        let data = CheckpointData::of_neighbour_list_run(scene, run, &path)?;
        checkpoint::write(&path, &data)?;
        self.checkpoints.push(path);
        while self.checkpoints.len() > 3 {
            let old = self.checkpoints.remove(0);
            let _ = std::fs::remove_file(old);
        }
        Ok(())
    }

    fn run(&mut self, options: &GpuRunOptions) -> Result<GpuRunSummary, GpuRunError> {
        let scene = self.scene;
        let total = scene.total_steps();
        let frame_every = every(scene.output_interval, scene.dt);
        let energy_every = every(scene.energy_interval, scene.dt);
        let checkpoint_every = scene
            .checkpoint_interval
            .filter(|_| !options.without_checkpoints)
            .map(|c| every(c, scene.dt));
        let start_step = self.step;
        let progress = progress_bar(options.quiet, total);
        progress.set_position(start_step);
        let started = Instant::now();
        let mut last_tick = Instant::now();
        let mut files = Vec::new();
        let mut stopped_early = false;
        let n = scene.particles.len() as f64;
        loop {
            let k = self.step;
            let interrupted = options
                .interrupt
                .as_ref()
                .is_some_and(|f| f.load(Ordering::SeqCst));
            let stop_here = interrupted || (options.stop_at_step == Some(k) && k < total);
            // Where the CPU run writes its checkpoints: when due, at an interrupt, and at the
            // end (here before the last step's force pass, the state every checkpoint holds).
            let due = (checkpoint_every.is_some_and(|c| k.is_multiple_of(c)) || k >= total)
                && k != start_step;
            if !options.without_checkpoints && (due || stop_here) {
                self.write_checkpoint()?;
            }
            if stop_here {
                stopped_early = true;
                break;
            }
            self.device(|gpu| gpu.step_and_evaluate(0))?;
            let last = k >= total;
            let frame_due = k.is_multiple_of(frame_every) || last;
            let energy_due = k.is_multiple_of(energy_every) || last;
            let every_step = self.tracker.needs_every_step();
            if frame_due || energy_due || every_step {
                self.take_samples(frame_due, energy_due, options)?;
            }
            if last {
                break;
            }
            let mut next = next_multiple(k, frame_every)
                .min(next_multiple(k, energy_every))
                .min(total)
                .min(k + STEPS_PER_CHECK);
            if every_step {
                next = k + 1;
            }
            if let Some(stop) = options.stop_at_step.filter(|&s| s > k) {
                next = next.min(stop);
            }
            self.device(|gpu| gpu.step((next - k) as usize))?;
            self.step = next;
            if last_tick.elapsed() > Duration::from_millis(250) {
                last_tick = Instant::now();
                let done = (self.step - start_step) as f64;
                let rate = done * n / started.elapsed().as_secs_f64().max(1e-9);
                progress.set_position(self.step);
                progress.set_message(format!(
                    "t = {:.4e} s of {:.4e} s, {:.3e} particle-steps/s",
                    self.time(),
                    scene.duration,
                    rate
                ));
            }
        }
        progress.finish_and_clear();
        self.write_series(&mut files, true)?;
        let headline = self.tracker.report(scene, &self.samples);
        if !headline.text.is_empty() {
            let path = self.out.join(format!("{}_headline.toml", scene.name));
            let text = toml::to_string(&headline).unwrap_or_default();
            mdr_output::write_atomic(&path, text.as_bytes()).map_err(output(&path))?;
            files.push(path);
        }
        files.push(self.out.join(format!("{}.pvd", scene.name)));
        Ok(GpuRunSummary {
            step: self.step,
            start_step,
            time: self.time(),
            stopped_early,
            checkpoint: self.checkpoints.last().cloned(),
            energy: self.energy.clone(),
            headline,
            wall_seconds: started.elapsed().as_secs_f64(),
            files,
            adapter: String::new(),
        })
    }

    /// A device call; an error stops the run after the series so far are written.
    fn device<T>(
        &mut self,
        call: impl FnOnce(&mut GpuScene) -> Result<T, GpuError>,
    ) -> Result<T, GpuRunError> {
        match call(&mut self.gpu) {
            Ok(value) => Ok(value),
            Err(GpuError::WallCrossing {
                particle,
                wall,
                step,
            }) => {
                let i = particle as usize;
                let radius = self.gpu.radii().get(i).copied().unwrap_or(f64::NAN);
                let wall = self
                    .gpu
                    .wall_of_plane()
                    .get(wall as usize)
                    .copied()
                    .unwrap_or(wall as usize);
                Err(self.stop(format!(
                    "the wall guard: sphere {i} (radius {radius:.3e} m) sank more than \
                     {CROSSING_OVERLAP} of its radius into wall {wall} (`walls[{wall}]`) at \
                     step {step} (t = {:.6e} s): it is going through the wall. Lower dt_s or \
                     declare a larger max_speed_m_per_s if it is that fast",
                    step as f64 * self.scene.dt
                )))
            }
            Err(e) => Err(self.stop(e.to_string())),
        }
    }

    /// Stop the run at the current step: the series so far are written, and the error says
    /// why and where they are.
    fn stop(&mut self, reason: String) -> GpuRunError {
        if let Err(e) = self.write_series(&mut Vec::new(), true) {
            return e;
        }
        GpuRunError::Stopped {
            time: self.time(),
            step: self.step,
            reason,
            out: self.out.clone(),
        }
    }

    /// The samples of the current step (`frame_due`, `energy_due`: also at the run's last
    /// step): the state read back, the headline tracker's step, the energy
    /// row, the frame; the finite-state check. (The wall guard is the device's, at every
    /// step: [`GpuError::WallCrossing`].)
    fn take_samples(
        &mut self,
        frame_due: bool,
        energy_due: bool,
        options: &GpuRunOptions,
    ) -> Result<(), GpuRunError> {
        let scene = self.scene;
        let state = self.device(|gpu| gpu.state())?;
        let sample = Sample {
            contacts: contacts_per_particle(&state),
            state,
        };
        if frame_due {
            if let Some(reason) = non_finite(&sample.state) {
                return Err(self.stop(reason));
            }
        }
        let view = ParticleView {
            position: &sample.state.position,
            velocity: &sample.state.linvel,
            radius: self.gpu.radii(),
            mass: self.gpu.masses(),
            contacts: &sample.contacts,
        };
        self.tracker.on_step(scene, &view);
        if energy_due {
            let row = self.energy_row(&sample);
            self.energy.push(row);
            let rows: Vec<EnergyRow> = self.energy.iter().map(|r| r.as_energy_row()).collect();
            if let Some(reason) = mdr_sim::run::energy_guard(scene, &rows, self.guard_floor_j) {
                return Err(self.stop(reason));
            }
        }
        if frame_due {
            let headline = self.tracker.sample(scene, self.time(), &view);
            self.samples.push(headline);
            if !options.no_frames {
                self.write_frame(&sample)?;
            }
            self.write_series(&mut Vec::new(), false)?;
        }
        Ok(())
    }

    /// The kinetic and gravitational energies, summed in particle order as the CPU run sums
    /// them, the contacts' elastic energies and the live contacts' plastic work
    /// ([`GpuScene::contact_energies`]), the works booked on the device (summed in particle
    /// order), the balance and the contacts.
    fn energy_row(&self, sample: &Sample) -> GpuEnergyRow {
        let g = self.scene.gravity;
        let s = &sample.state;
        let mut row = GpuEnergyRow {
            time_s: self.time(),
            ..GpuEnergyRow::default()
        };
        let (mass, radius) = (self.gpu.masses(), self.gpu.radii());
        for (((x, v), w), (&m, &r)) in s
            .position
            .iter()
            .zip(&s.linvel)
            .zip(&s.angvel)
            .zip(mass.iter().zip(radius))
        {
            row.kinetic_translational_j += 0.5 * m * v.norm_squared();
            // Solid sphere: I = (2/5) m r².
            row.kinetic_rotational_j += 0.5 * 0.4 * m * r * r * w.norm_squared();
            row.gravitational_j -= m * g.dot(x);
        }
        let live_plastic;
        [
            row.elastic_normal_j,
            row.elastic_tangential_j,
            row.elastic_rolling_j,
            live_plastic,
        ] = self.gpu.contact_energies(s);
        row.contacts = (s.pairs.iter().filter(|p| p.active).count()
            + s.floor.iter().filter(|w| w.is_some()).count()) as u64;
        let booked = GpuBooks::total(&s.books);
        row.plastic_j = booked.plastic + live_plastic;
        row.adhesive_j = booked.adhesive;
        row.wall_work_j = booked.wall_work;
        row.removed_j = booked.removed;
        row.friction_j = booked.friction;
        row.damping_j = booked.damping;
        row.rolling_j = booked.rolling;
        // The books hold the energy the springs gained; the columns, what they lost.
        row.stiffness_tangential_j = -booked.tangential_stiffness;
        row.stiffness_rolling_j = -booked.rolling_stiffness;
        row.balance_j = row.as_energy_row().with_balance().balance_j;
        row
    }

    fn write_frame(&mut self, sample: &Sample) -> Result<(), GpuRunError> {
        let scene = self.scene;
        let index = self.collection.iter().filter(|e| e.part == 0).count();
        let name = PathBuf::from("frames").join(format!("{}_{index:06}.vtp", scene.name));
        let s = &sample.state;
        let frame = ParticleFrame {
            position: s.position.iter().map(|&x| x.into()).collect(),
            radius: self.gpu.radii().to_vec(),
            velocity: s.linvel.iter().map(|&v| v.into()).collect(),
            angular_velocity: s.angvel.iter().map(|&w| w.into()).collect(),
            contacts: sample.contacts.clone(),
            plastic_work: self.gpu.particle_plastic_work(s),
            id: (0..s.position.len() as u32).collect(),
        };
        let path = self.out.join(&name);
        vtk::write_particles(&path, &frame).map_err(output(&path))?;
        self.collection.push(CollectionEntry {
            time: self.time(),
            file: name,
            part: 0,
        });
        let pvd = self.out.join(format!("{}.pvd", scene.name));
        vtk::write_collection(&pvd, &self.collection).map_err(output(&pvd))
    }

    /// The energy CSV at every frame; the headline series and the plots at the end, as the
    /// CPU run writes them.
    fn write_series(&self, files: &mut Vec<PathBuf>, plots: bool) -> Result<(), GpuRunError> {
        let name = &self.scene.name;
        let out = &self.out;
        let csv = out.join(format!("{name}_energy.csv"));
        let rows: Vec<EnergyRow> = self.energy.iter().map(|r| r.as_energy_row()).collect();
        energy::write_csv(&csv, &rows).map_err(output(&csv))?;
        if !plots {
            return Ok(());
        }
        files.push(csv);
        let names = self.tracker.series_names();
        if !names.is_empty() {
            let series_csv = out.join(format!("{name}_headline.csv"));
            self.tracker
                .write_csv(&series_csv, &self.samples)
                .map_err(output(&series_csv))?;
            files.push(series_csv);
        }
        let svg = out.join(format!("{name}_energy.svg"));
        plot::write_energy_plot(&svg, &format!("{name}: energy books"), &rows)
            .map_err(output(&svg))?;
        files.push(svg);
        if let Some(path) = self
            .tracker
            .write_chart(self.scene, &self.samples, out)
            .map_err(|(path, e)| output(&path)(e))?
        {
            files.push(path);
        }
        Ok(())
    }
}

/// The CPU run's books of a device state read between two steps (a checkpoint's): the totals
/// of the works booked on the device. The CPU books hold the ended contacts' works and add the
/// live contacts' own books when read; the checkpoint's live histories carry no books (zero),
/// so the device's totals, which hold the live contacts' works so far too, continue there.
/// The CPU's plastic work includes the adhesive work; its stiffness books hold the energy
/// lost. Per particle, the plastic work of the contacts that ended.
fn cpu_books(state: &GpuState) -> Books {
    let total = GpuBooks::total(&state.books);
    let mut books = Books::new(state.position.len());
    books.plastic = total.plastic + total.adhesive;
    books.adhesive = total.adhesive;
    books.friction = total.friction;
    books.damping = total.damping;
    books.rolling = total.rolling;
    books.stiffness_tangential = -total.tangential_stiffness;
    books.stiffness_rolling = -total.rolling_stiffness;
    books.wall_work = total.wall_work;
    books.removed = total.removed;
    for (p, b) in books.particle_plastic.iter_mut().zip(&state.books) {
        *p = b.plastic;
    }
    books
}

/// Each particle's contacts alive: its sphere pairs and its wall contacts.
fn contacts_per_particle(state: &GpuState) -> Vec<u32> {
    let n = state.position.len();
    let mut counts = vec![0u32; n];
    for pair in state.pairs.iter().filter(|p| p.active) {
        counts[pair.i as usize] += 1;
        counts[pair.j as usize] += 1;
    }
    for (slot, contact) in state.floor.iter().enumerate() {
        if let (Some(_), Some(i)) = (contact, slot.checked_div(state.walls)) {
            counts[i] += 1;
        }
    }
    counts
}

/// The first particle with a non-finite position or velocity, as the CPU run words it.
fn non_finite(state: &GpuState) -> Option<String> {
    let finite = |v: &Vector3<f64>| v.iter().all(|c| c.is_finite());
    (0..state.position.len())
        .find(|&i| !(finite(&state.position[i]) && finite(&state.linvel[i])))
        .map(|i| format!("particle {i} has a non-finite position or velocity: reduce dt_s"))
}

fn output(path: &Path) -> impl FnOnce(std::io::Error) -> GpuRunError + '_ {
    move |source| GpuRunError::Output {
        path: path.to_path_buf(),
        source,
    }
}

fn progress_bar(quiet: bool, total: u64) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{bar:30.cyan/blue} {percent:>3}% {msg} ETA {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}
