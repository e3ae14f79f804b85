//! `sim run` on the GPU ([`run_gpu_scene`]): a force-mode scene stepped on the device
//! ([`GpuScene`]) with the outputs of the CPU run that the device's state gives: the VTK frames
//! and their ParaView collection (every field but `plastic_work_j`), the energy books the
//! state holds ([`GPU_ENERGY_COLUMNS`]), the headline with its series, CSV, plots and TOML
//! report, and a progress bar.
//!
//! The samples are taken where the CPU run takes them: at step `k` the device has evaluated
//! the forces at `x_k` (the pass that sets each contact's state) and not yet integrated, so
//! positions, velocities and contacts all describe `x_k` ([`GpuScene::step_and_evaluate`]).
//!
//! What the device does not keep is never written as a number: the dissipated works (plastic,
//! friction, damping, rolling, adhesive), the elastic energies stored in the contacts, the
//! wall work and so the balance, and the per-particle plastic work. The run writes no
//! checkpoint and reads none; a scene that asks for checkpoints (`checkpoint_interval_s`), a
//! contact network or an explicit energy guard (`max_energy_drift`) is refused with the key
//! named ([`gpu_run_support`]) unless the caller accepts a run without checkpoints.

use crate::device::{GpuContext, GpuError};
use crate::scene::{gpu_scene_support, GpuScene};
use crate::system::{GpuOptions, GpuState};
use indicatif::{ProgressBar, ProgressStyle};
use mdr_sim::headline::{HeadlineReport, HeadlineSample, ParticleView, Tracker};
use mdr_sim::output::energy::{self, EnergyRow};
use mdr_sim::output::plot;
use mdr_sim::output::vtk::{self, CollectionEntry, ParticleFrame};
use mdr_sim::run::CROSSING_OVERLAP;
use mdr_sim::Scene;
use nalgebra::Vector3;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The energy-book columns a GPU run writes (`<name>_energy.csv`), in the CPU run's order:
/// the kinetic and gravitational energies from the state read back, and the contacts alive.
pub const GPU_ENERGY_COLUMNS: [&str; 5] = [
    "time_s",
    "kinetic_translational_j",
    "kinetic_rotational_j",
    "gravitational_j",
    "contacts",
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
    /// Run a scene that asks for checkpoints (`checkpoint_interval_s`) without them.
    pub without_checkpoints: bool,
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
    /// Contacts alive (touching, or held by an adhesive neck): sphere pairs and wall contacts.
    pub contacts: u64,
}

impl GpuEnergyRow {
    /// The row in the CPU run's type (for its CSV writer: only [`GPU_ENERGY_COLUMNS`] are
    /// written).
    fn as_energy_row(&self) -> EnergyRow {
        EnergyRow {
            time_s: self.time_s,
            kinetic_translational_j: self.kinetic_translational_j,
            kinetic_rotational_j: self.kinetic_rotational_j,
            gravitational_j: self.gravitational_j,
            contacts: self.contacts,
            ..EnergyRow::default()
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
    /// Whether the run stopped early (interrupt or `stop_at_step`).
    pub stopped_early: bool,
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
    /// An output file could not be written.
    #[error("writing {}: {source}", path.display())]
    Output {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// Whether `sim run --device gpu` runs `scene`: [`gpu_scene_support`], and the outputs the
/// GPU run cannot write refused by their key: `checkpoint_interval_s` (unless
/// `without_checkpoints`), `contact_network`, an explicit `max_energy_drift`, `orifice_sweep_m`.
/// Needs no device.
pub fn gpu_run_support(scene: &Scene, without_checkpoints: bool) -> Result<(), GpuError> {
    gpu_scene_support(scene)?;
    let refuse = |what: &str| {
        Err(GpuError::Unsupported(format!(
            "scene `{}`: {what}",
            scene.name
        )))
    };
    let run = &scene.source.run;
    if run.checkpoint_interval_s.is_some() && !without_checkpoints {
        return refuse(
            "`[run] checkpoint_interval_s`: the GPU run writes no checkpoints (run on the CPU \
             path for checkpoints, or pass --no-checkpoints to run without them)",
        );
    }
    if scene.contact_network {
        return refuse(
            "`contact_network = true`: the GPU keeps no per-pair forces for the contact-network \
             frames (run on the CPU path, or leave the key out)",
        );
    }
    if run.max_energy_drift.is_some() {
        return refuse(
            "`[run] max_energy_drift`: the energy guard needs the balance, and the GPU keeps no \
             dissipated works (leave the key out to run without the guard)",
        );
    }
    if run.orifice_sweep_m.is_some() {
        return refuse("`[run] orifice_sweep_m`: a sweep runs on the CPU only");
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

/// Run `scene` on `ctx`'s device from its set-up.
pub fn run_gpu_scene(
    ctx: &GpuContext,
    scene: &Scene,
    options: &GpuRunOptions,
) -> Result<GpuRunSummary, GpuRunError> {
    gpu_run_support(scene, options.without_checkpoints)?;
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
        step: 0,
    };
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
    /// The device holds `x_step` with the forces at `x_step` evaluated.
    step: u64,
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

    fn run(&mut self, options: &GpuRunOptions) -> Result<GpuRunSummary, GpuRunError> {
        let scene = self.scene;
        let total = scene.total_steps();
        let frame_every = every(scene.output_interval, scene.dt);
        let energy_every = every(scene.energy_interval, scene.dt);
        let progress = progress_bar(options.quiet, total);
        let started = Instant::now();
        let mut last_tick = Instant::now();
        let mut files = Vec::new();
        let mut stopped_early = false;
        let n = scene.particles.len() as f64;
        self.device(|gpu| gpu.step_and_evaluate(0))?;
        loop {
            let k = self.step;
            let interrupted = options
                .interrupt
                .as_ref()
                .is_some_and(|f| f.load(Ordering::SeqCst));
            if interrupted || (options.stop_at_step == Some(k) && k < total) {
                stopped_early = true;
                break;
            }
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
            self.device(|gpu| gpu.step_and_evaluate((next - k) as usize))?;
            self.step = next;
            if last_tick.elapsed() > Duration::from_millis(250) {
                last_tick = Instant::now();
                let rate = self.step as f64 * n / started.elapsed().as_secs_f64().max(1e-9);
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
            time: self.time(),
            stopped_early,
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
    /// row, the frame; the wall guard and the finite-state check.
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
        if let Some(reason) = self.wall_guard(&sample.state) {
            return Err(self.stop(reason));
        }
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

    /// The kinetic and gravitational energies and the contacts, summed in particle order as
    /// the CPU run sums them.
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
        row.contacts = (s.pairs.iter().filter(|p| p.active).count()
            + s.floor.iter().filter(|w| w.is_some()).count()) as u64;
        row
    }

    /// The wall guard of the CPU run, at each sample: a sphere sinking into a wall plane by
    /// more than [`CROSSING_OVERLAP`] of its radius is going through it.
    fn wall_guard(&self, state: &GpuState) -> Option<String> {
        let radius = self.gpu.radii();
        let planes = self.gpu.planes();
        for (i, x) in state.position.iter().enumerate() {
            for (k, plane) in planes.iter().enumerate() {
                let over_face = (0..3).all(|a| x[a] >= plane.lo[a] && x[a] <= plane.hi[a]);
                let overlap = radius[i] - plane.normal.dot(&(x - plane.point));
                if over_face && overlap > CROSSING_OVERLAP * radius[i] {
                    let wall = self.gpu.wall_of_plane()[k];
                    return Some(format!(
                        "sphere {i} (radius {:.3e} m) sinks {overlap:.3e} m into wall {wall} \
                         (`walls[{wall}]`): it is going through the wall. Lower dt_s or declare \
                         a larger max_speed_m_per_s if it is that fast",
                        radius[i]
                    ));
                }
            }
        }
        None
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
            // The device keeps no plastic work: the frame leaves the field out.
            plastic_work: Vec::new(),
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
        energy::write_csv_columns(&csv, &rows, &GPU_ENERGY_COLUMNS).map_err(output(&csv))?;
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
        let col = |f: fn(&GpuEnergyRow) -> f64| {
            self.energy
                .iter()
                .map(|r| (r.time_s, f(r)))
                .collect::<Vec<_>>()
        };
        plot::write_lines(
            &svg,
            &format!("{name}: energy books (GPU: kinetic and gravitational)"),
            "time (s)",
            "energy (J)",
            &[
                ("kinetic (transl.)", col(|r| r.kinetic_translational_j)),
                ("kinetic (rot.)", col(|r| r.kinetic_rotational_j)),
                ("gravitational", col(|r| r.gravitational_j)),
            ],
        )
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
