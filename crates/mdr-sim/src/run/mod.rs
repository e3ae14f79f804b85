//! The run loop: build the world, step it with the coupling, keep the energy books, write
//! frames, energy CSV, plots and checkpoints, and resume from a checkpoint bit-identically.
//!
//! One step `k` (force mode, on either path):
//! 1. a checkpoint, if one is due (the state holds `x_k, v_k` and the histories up to `x_{k−1}`);
//! 2. the coupling's `compute_forces` at `x_k, v_k` (the law updates every touching pair's
//!    history; the neighbour-list path first rebuilds its lists if due); the rapier pipeline
//!    path's checks (`check_step`) run once, when the run is built;
//! 3. the books take the work increments of every contact, and the samples (energy row, frame,
//!    headline) are taken here, where positions, velocities and contact states all describe `x_k`;
//! 4. the integration to `v_{k+1}`, `x_{k+1}` (symplectic Euler) and `PhysicsWorld::step`:
//!    `apply_forces` + `step` + `give_back_user_forces` on the rapier pipeline path, `advance` on
//!    the neighbour-list path (which integrates its particles itself and then steps rapier's wall
//!    bodies).
//!
//! The loop and the scene events are here; what a run writes is in `outputs`, the same steps
//! without output for timing (`SceneSteps`) in `steps`.

mod books;
pub mod build;
pub mod coupling;
mod outputs;
mod records;
mod steps;
mod sweep;

pub use books::Books;
pub use mdr_rapier::neighbour_list::StepTimings;
pub use records::{
    BodyRecord, CheckpointData, ContactRecord, NeighbourListRecord, NeighbourListRun, RngRecord,
};
pub use steps::{ContactCounts, SceneSteps};
pub use sweep::{orifice_sweep, run_orifice_sweep, SweepRun, SweepSummary};

use crate::checkpoint::{self, CheckpointError};
use crate::error::{output, SimError};
use crate::headline::{HeadlineReport, HeadlineSample, ParticleView, Tracker};
use crate::output::energy::{self, BalanceDrift, EnergyRow};
use crate::output::plot;
use crate::output::vtk::{self, CollectionEntry, ContactFrame, ParticleFrame};
use crate::scene::Scene;
use build::{build, Built, Coupling};
use indicatif::{ProgressBar, ProgressStyle};
use mdr_contact::normal::NormalLaw;
use mdr_contact::rolling::RollingLaw;
use mdr_rapier::convert::to_na;
use mdr_rapier::geometry::sphere_sphere;
use mdr_rapier::kernel::ContactWorks;
use nalgebra::Vector3;
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How to run a scene.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Output directory (frames, CSV, plots, checkpoints).
    pub out_dir: PathBuf,
    /// No progress bar, no summary on stderr.
    pub quiet: bool,
    /// Continue from this checkpoint.
    pub resume: Option<PathBuf>,
    /// Stop at this step with a checkpoint (batch jobs, tests).
    pub stop_at_step: Option<u64>,
    /// Set from outside (Ctrl-C) to stop at the next step with a checkpoint.
    pub interrupt: Option<Arc<AtomicBool>>,
    /// Skip VTK frames (tests that look at the books only).
    pub no_frames: bool,
    /// Print an estimate of the run's wall time to stderr once its first steps are measured.
    pub estimate: bool,
}

impl RunOptions {
    /// Options writing into `out_dir`.
    pub fn new(out_dir: impl Into<PathBuf>) -> Self {
        Self {
            out_dir: out_dir.into(),
            ..Self::default()
        }
    }

    /// Quiet or not.
    pub fn quiet(mut self, quiet: bool) -> Self {
        self.quiet = quiet;
        self
    }

    /// Resume from a checkpoint.
    pub fn resume(mut self, checkpoint: Option<PathBuf>) -> Self {
        self.resume = checkpoint;
        self
    }

    /// Stop at a step with a checkpoint.
    pub fn stop_at_step(mut self, step: Option<u64>) -> Self {
        self.stop_at_step = step;
        self
    }

    /// Flag that interrupts the run.
    pub fn interrupt(mut self, flag: Arc<AtomicBool>) -> Self {
        self.interrupt = Some(flag);
        self
    }

    /// Skip the VTK frames.
    pub fn no_frames(mut self, yes: bool) -> Self {
        self.no_frames = yes;
        self
    }

    /// Print a wall-time estimate once the first steps are measured.
    pub fn estimate(mut self, yes: bool) -> Self {
        self.estimate = yes;
        self
    }
}

/// A sphere–wall overlap beyond this fraction of the sphere's radius stops the run: the sphere
/// is going through the wall (a two-sided sheet's overlap reaches the radius as the centre
/// passes it).
pub const CROSSING_OVERLAP: f64 = 0.95;

/// Seconds of stepping after which a run prints its wall-time estimate.
const ESTIMATE_AFTER_S: f64 = 2.0;

/// The wall time of `remaining` steps at `steps_per_s`, as a sentence.
fn estimate_text(done: u64, seconds: f64, remaining: u64) -> String {
    let rate = done as f64 / seconds.max(1e-9);
    let left = remaining as f64 / rate.max(1e-300);
    format!(
        "estimate: {rate:.3e} steps/s over the first {done} steps, so the {remaining} steps to go take about {} \
         (more once the spheres pack and flow: contacts cost more than free flight)",
        human_duration(left)
    )
}

/// `seconds` as `1 h 23 min`, `4 min 5 s` or `6.7 s`.
fn human_duration(seconds: f64) -> String {
    if !seconds.is_finite() {
        return "forever".to_owned();
    }
    let s = seconds.round() as u64;
    match s {
        _ if seconds < 60.0 => format!("{seconds:.1} s"),
        0..3600 => format!("{} min {} s", s / 60, s % 60),
        3600..172_800 => format!("{} h {} min", s / 3600, (s % 3600) / 60),
        _ => format!("{:.1} days", seconds / 86_400.0),
    }
}

/// Build `scene` and time its first steps for about `budget` (at least two steps, the first
/// of which builds the neighbour lists and is not timed): an estimate of the whole run's wall
/// time on the current rayon pool, as a sentence (`sim run --check`).
pub fn estimate_run_time(scene: &Scene, budget: Duration) -> Result<String, SimError> {
    mdr_rapier::neighbour_list::run_awake(|| {
        let total = scene.total_steps();
        let mut steps = SceneSteps::new(scene)?;
        steps.step()?;
        let started = Instant::now();
        let mut done = 0;
        while done < total.saturating_sub(1) && (done < 1 || started.elapsed() < budget) {
            steps.step()?;
            done += 1;
        }
        Ok(estimate_text(
            done.max(1),
            started.elapsed().as_secs_f64(),
            total,
        ))
    })
}

/// What a run did.
#[derive(Debug, Clone)]
pub struct RunSummary {
    /// Last step reached.
    pub step: u64,
    /// Step the run started from (0, or the checkpoint's step of a resumed run): it ran
    /// `step - start_step` steps.
    pub start_step: u64,
    /// Simulated time reached (s).
    pub time: f64,
    /// Whether the run stopped early (interrupt or `stop_at_step`).
    pub stopped_early: bool,
    /// The last checkpoint written.
    pub checkpoint: Option<PathBuf>,
    /// The energy books.
    pub energy: Vec<EnergyRow>,
    /// The headline result.
    pub headline: HeadlineReport,
    /// Final state of every particle.
    pub particles: Vec<BodyRecord>,
    /// Wall-clock seconds spent stepping.
    pub wall_seconds: f64,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// A scene being run.
pub(crate) struct Sim<'a> {
    scene: &'a Scene,
    built: Built,
    step: u64,
    books: Books,
    rng: ChaCha8Rng,
    tracker: Tracker,
    collection: Vec<CollectionEntry>,
    energy: Vec<EnergyRow>,
    samples: Vec<HeadlineSample>,
    checkpoints: Vec<PathBuf>,
    /// Scratch: per-particle state for the trackers.
    view: ViewBuffers,
    /// Spheres below `delete_below_m` leave the run (crate::walls::Sink).
    sink: Option<crate::walls::Sink>,
    /// The floor of the energy guard's scale (J): see [`one_diameter_lift_j`].
    guard_floor_j: f64,
}

#[derive(Default)]
struct ViewBuffers {
    position: Vec<Vector3<f64>>,
    velocity: Vec<Vector3<f64>>,
    radius: Vec<f64>,
    mass: Vec<f64>,
    contacts: Vec<u32>,
}

impl ViewBuffers {
    /// The buffers as the headline tracker reads them.
    fn view(&self) -> ParticleView<'_> {
        ParticleView {
            position: &self.position,
            velocity: &self.velocity,
            radius: &self.radius,
            mass: &self.mass,
            contacts: &self.contacts,
        }
    }
}

/// Whether a decoded world holds the bodies and colliders the scene builds, with the same
/// handles and shapes' kinds (the colliders registered with the coupling refer to them).
fn handles_match(sim: &Sim<'_>, world: &rapier3d_f64::prelude::PhysicsWorld) -> bool {
    let built = &sim.built.world;
    built.bodies.len() == world.bodies.len()
        && built.colliders.len() == world.colliders.len()
        && built.bodies.iter().all(|(h, b)| {
            world
                .bodies
                .get(h)
                .is_some_and(|w| w.body_type() == b.body_type())
        })
        && built.colliders.iter().all(|(h, c)| {
            world.colliders.get(h).is_some_and(|w| {
                w.shape().shape_type() == c.shape().shape_type() && w.parent() == c.parent()
            })
        })
}

fn every(interval: f64, dt: f64) -> u64 {
    ((interval / dt).round() as u64).max(1)
}

/// Run `scene` (from the start, or from `options.resume`), on the threads of the current rayon
/// pool (the global pool unless called inside [`rayon::ThreadPool::install`]).
pub fn run_scene(scene: &Scene, options: &RunOptions) -> Result<RunSummary, SimError> {
    // The whole run goes onto one of the pool's threads: a step makes several parallel passes,
    // and each one started from a thread outside the pool hands its work over and sleeps until
    // it is done (two context switches a pass, a fifth of a 2,000-sphere step on one thread).
    // From a pool thread a pass starts in place. The pool's other threads wait for each pass
    // awake (waking a sleeping one costs a pass tens of microseconds), and a run from outside
    // the pool waits outside it for its turn (`run_awake`).
    mdr_rapier::neighbour_list::run_awake(|| {
        let mut sim = match &options.resume {
            Some(path) => Sim::resume(scene, path)?,
            None => Sim::new(scene)?,
        };
        sim.run(options)
    })
}

impl<'a> Sim<'a> {
    fn new(scene: &'a Scene) -> Result<Self, SimError> {
        let mut built = build(scene)?;
        // Force mode: candidate pairs for the first step (a restart does the same, so both see
        // the same touching pairs). Restitution mode leaves detection to rapier's step: a
        // detection pass before the first step would consume the bodies' change flags before
        // the island manager activates them.
        if let Coupling::RapierPipeline(stepper) = &built.coupling {
            // The coupling's checks (configured world, registration groups, the scene's step
            // equal to rapier's) once: a scene changes none of them while it runs.
            let world = &built.world;
            stepper.check_step(&world.integration_parameters, &world.colliders, scene.dt)?;
            built.world.detect_collisions(&(), &());
        }
        // The placement used its own generator; the run's generator continues the seed's
        // stream after it (kept in the checkpoint for any later random input).
        let rng = records::RngRecord::at_start(scene).restore();
        Ok(Self {
            scene,
            books: Books::new(scene.particles.len()),
            built,
            step: 0,
            rng,
            tracker: Tracker::new(scene),
            collection: Vec::new(),
            energy: Vec::new(),
            samples: Vec::new(),
            checkpoints: Vec::new(),
            view: ViewBuffers::default(),
            sink: scene_sink(scene),
            guard_floor_j: one_diameter_lift_j(scene),
        })
    }

    fn resume(scene: &'a Scene, path: &Path) -> Result<Self, SimError> {
        let data = CheckpointData::read(path)?;
        data.check_scene(scene, path)?;
        let incompatible = |reason: String| CheckpointError::Incompatible {
            path: path.to_path_buf(),
            reason,
        };
        let mut sim = Self::new(scene)?;
        let n_particles = match &sim.built.coupling {
            Coupling::NeighbourList(stepper) => stepper.particles().len(),
            _ => sim.built.particle_bodies.len(),
        };
        let n_bodies = n_particles + sim.built.wall_bodies.len();
        if data.bodies.len() != n_bodies
            || data.books.particle_plastic.len() != scene.particles.len()
        {
            return Err(incompatible(format!(
                "it holds {} bodies, the scene builds {n_bodies}",
                data.bodies.len()
            ))
            .into());
        }
        // Restitution mode: rapier's whole world (decoded and checked before anything is used).
        let world = match sim.built.coupling {
            Coupling::RapierPipeline(_) => None,
            Coupling::NeighbourList(_) | Coupling::Restitution(_) => {
                let world: rapier3d_f64::prelude::PhysicsWorld = postcard::from_bytes(&data.world)
                    .map_err(|e| CheckpointError::Decode {
                        path: path.to_path_buf(),
                        reason: format!("rapier's world: {e}"),
                    })?;
                let same_bodies = handles_match(&sim, &world);
                if !same_bodies {
                    return Err(incompatible(
                        "rapier's world in it does not hold the scene's bodies and colliders"
                            .into(),
                    )
                    .into());
                }
                Some(world)
            }
        };
        // Everything is checked: now apply it.
        let handles: Vec<_> = sim
            .built
            .particle_bodies
            .iter()
            .chain(&sim.built.wall_bodies)
            .copied()
            .collect();
        if let Coupling::NeighbourList(stepper) = &mut sim.built.coupling {
            let p = stepper.particles_mut();
            for (i, record) in data.bodies.iter().take(n_particles).enumerate() {
                record.apply_to_particle(p, i);
            }
        }
        match world {
            // Restitution and the neighbour-list path: rapier's world continues exactly where it
            // stopped (the bodies are in it).
            Some(world) => sim.built.world = world,
            None => {
                for (h, record) in handles.iter().zip(&data.bodies) {
                    record.apply(&mut sim.built.world.bodies[*h]);
                }
                sim.built.world.detect_collisions(&(), &());
            }
        }
        sim.restore_contacts(&data, path)?;
        sim.step = data.step;
        sim.books = data.books;
        sim.rng = data.rng.restore();
        sim.tracker = data.tracker;
        sim.collection = data.collection;
        sim.energy = data.energy;
        sim.samples = data.samples;
        Ok(sim)
    }

    /// Put the checkpoint's per-contact histories back. Force mode: the plugin binds the laws of
    /// the pairs touching now (one force pass, whose forces are discarded), then every entry gets
    /// the checkpoint's history, or a fresh one for a pair that was not touching at the checkpoint.
    fn restore_contacts(&mut self, data: &CheckpointData, path: &Path) -> Result<(), SimError> {
        let dt = self.scene.dt;
        let world = &mut self.built.world;
        match &mut self.built.coupling {
            Coupling::RapierPipeline(stepper) => {
                stepper.compute_forces(world, dt)?;
                // Clears the plugin's force accumulators; the bodies keep no force of it.
                stepper.discard_forces(&mut world.bodies);
                stepper.restore(&data.contacts);
            }
            Coupling::NeighbourList(stepper) => {
                stepper.restore(world, data.neighbour_list.as_ref(), path)?;
            }
            Coupling::Restitution(hooks) => {
                let history = hooks.history();
                for (key, max_overlap) in &data.impacts {
                    let slot = history.slot_for(mdr_rapier::PairKey(*key));
                    history.commit(slot, *max_overlap);
                }
            }
        }
        Ok(())
    }

    fn time(&self) -> f64 {
        self.step as f64 * self.scene.dt
    }

    fn run(&mut self, options: &RunOptions) -> Result<RunSummary, SimError> {
        let scene = self.scene;
        let out = &options.out_dir;
        std::fs::create_dir_all(out).map_err(output(out))?;
        let total = scene.total_steps();
        let frame_every = every(scene.output_interval, scene.dt);
        let energy_every = every(scene.energy_interval, scene.dt);
        let checkpoint_every = scene.checkpoint_interval.map(|c| every(c, scene.dt));
        let start_step = self.step;
        if options.resume.is_some() {
            self.remove_stale_outputs(out)?;
        }
        let progress = progress_bar(options.quiet, total, start_step);
        let started = Instant::now();
        let mut last_tick = Instant::now();
        let mut files = Vec::new();
        let mut stopped_early = false;
        let n = scene.particles.len() as f64;
        let mut estimated = !options.estimate;
        loop {
            let k = self.step;
            let interrupted = options
                .interrupt
                .as_ref()
                .is_some_and(|f| f.load(Ordering::SeqCst));
            let stop_here = options.stop_at_step == Some(k) && k < total;
            let due = checkpoint_every.is_some_and(|c| k.is_multiple_of(c)) && k != start_step;
            if (due && k < total) || interrupted || stop_here {
                self.write_checkpoint(out)?;
            }
            if interrupted || stop_here {
                stopped_early = true;
                break;
            }
            self.scene_events();
            let last = k >= total;
            let frame_due = k.is_multiple_of(frame_every) || last;
            self.compute_forces(frame_due && scene.contact_network && !options.no_frames)?;
            if let Some(reason) = self.wall_guard() {
                return Err(self.stop(out, last, reason));
            }
            let sampling = k.is_multiple_of(energy_every) || k.is_multiple_of(frame_every) || last;
            if sampling || self.tracker.needs_every_step() {
                self.track_step();
            }
            if k.is_multiple_of(energy_every) || last {
                let row = self.energy_row();
                self.energy.push(row);
                if let Some(reason) = self.energy_guard() {
                    return Err(self.stop(out, last, reason));
                }
            }
            if k.is_multiple_of(frame_every) || last {
                if let Err(e) = self.check_state() {
                    // The energy rows since the last frame were booked before the state went
                    // bad: they are written with the rest (no checkpoint of a broken state).
                    self.write_series(out, &mut files, false)?;
                    return Err(e);
                }
                let sample = self.tracker.sample(scene, self.time(), &self.view_ref());
                self.samples.push(sample);
                if !options.no_frames {
                    self.write_frame(out)?;
                }
                self.write_series(out, &mut files, false)?;
            }
            if last {
                break;
            }
            self.advance()?;
            if last_tick.elapsed() > Duration::from_millis(250) {
                last_tick = Instant::now();
                let seconds = started.elapsed().as_secs_f64();
                if !estimated && seconds > ESTIMATE_AFTER_S {
                    estimated = true;
                    let text = estimate_text(self.step - start_step, seconds, total - self.step);
                    progress.suspend(|| eprintln!("{text}"));
                }
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
        if !stopped_early {
            self.write_checkpoint(out)?;
        }
        self.write_series(out, &mut files, true)?;
        let headline = self.tracker.report(scene, &self.samples);
        if !headline.text.is_empty() {
            let path = out.join(format!("{}_headline.toml", scene.name));
            let text = toml::to_string(&headline).unwrap_or_default();
            mdr_output::write_atomic(&path, text.as_bytes()).map_err(output(&path))?;
            files.push(path);
        }
        files.push(out.join(format!("{}.pvd", scene.name)));
        Ok(RunSummary {
            step: self.step,
            start_step,
            time: self.time(),
            stopped_early,
            checkpoint: self.checkpoints.last().cloned(),
            energy: self.energy.clone(),
            headline,
            particles: match &self.built.coupling {
                Coupling::NeighbourList(stepper) => {
                    let p = stepper.particles();
                    (0..p.len())
                        .map(|i| BodyRecord::of_particle(p, i))
                        .collect()
                }
                _ => self
                    .built
                    .particle_bodies
                    .iter()
                    .map(|h| BodyRecord::of(&self.built.world.bodies[*h]))
                    .collect(),
            },
            wall_seconds: started.elapsed().as_secs_f64(),
            files,
        })
    }

    /// Walls due to be removed and spheres below the sink (idempotent: a resumed run redoes
    /// them at its first step).
    fn scene_events(&mut self) {
        let world = &mut self.built.world;
        let up = -self
            .scene
            .gravity
            .try_normalize(0.0)
            .unwrap_or(-Vector3::z());
        let removed = crate::walls::remove_due_walls(
            &self.scene.walls,
            self.step as f64 * self.scene.dt,
            &up,
            world,
            &self.built.wall_bodies,
        );
        match &mut self.built.coupling {
            Coupling::NeighbourList(stepper) => {
                let mut jumped = false;
                if let Some(sink) = &self.sink {
                    let p = stepper.particles_mut();
                    let (species, table, radius) = (&p.species, &p.species_table, &p.radius);
                    // Solid spheres, I = (2/5) m r², as the energy rows count them.
                    let inertia = |i: usize| {
                        let m = table[species[i] as usize].mass;
                        (m, 0.4 * m * radius[i] * radius[i])
                    };
                    let parking =
                        sink.apply(&mut p.position, &mut p.linvel, &mut p.angvel, inertia);
                    jumped = parking.jumped;
                    self.books.removed += parking.energy;
                }
                if removed || jumped {
                    stepper.request_rebuild();
                }
            }
            _ => {
                if let Some(sink) = &self.sink {
                    let particles = &self.scene.particles;
                    let parking =
                        sink.apply_to_bodies(&mut world.bodies, &self.built.particle_bodies, |i| {
                            particles[i].radius
                        });
                    self.books.removed += parking.energy;
                }
            }
        }
    }

    /// Forces at `x_k` and the books of this step; `keep_wrenches`: the neighbour-list path
    /// stores every pair's wrench (a contact-network frame follows).
    fn compute_forces(&mut self, keep_wrenches: bool) -> Result<(), SimError> {
        let dt = self.scene.dt;
        let world = &self.built.world;
        match &mut self.built.coupling {
            Coupling::RapierPipeline(stepper) => {
                stepper.compute_forces(world, dt)?;
                stepper.take_books(
                    &mut self.books,
                    &world.bodies,
                    &self.built.particle_of_collider,
                    &self.built.wall_of_collider,
                    dt,
                );
            }
            Coupling::NeighbourList(stepper) => {
                stepper.compute_forces(world, keep_wrenches, &mut self.books, dt)?;
            }
            Coupling::Restitution(_) => {}
        }
        Ok(())
    }

    fn advance(&mut self) -> Result<(), SimError> {
        let world = &mut self.built.world;
        match &mut self.built.coupling {
            Coupling::RapierPipeline(stepper) => stepper.advance(world),
            Coupling::NeighbourList(stepper) => stepper.advance(world)?,
            Coupling::Restitution(hooks) => hooks.step(world)?,
        }
        self.step += 1;
        Ok(())
    }

    fn gather_view(&mut self) {
        let v = &mut self.view;
        let bodies = &self.built.world.bodies;
        let n = self.scene.particles.len();
        v.position.clear();
        v.velocity.clear();
        v.mass.clear();
        v.radius.clear();
        if let Coupling::NeighbourList(stepper) = &self.built.coupling {
            let p = stepper.particles();
            v.position.extend_from_slice(&p.position);
            v.velocity.extend_from_slice(&p.linvel);
            v.radius.extend_from_slice(&p.radius);
            v.mass
                .extend(p.species.iter().map(|&s| p.species_table[s as usize].mass));
            v.contacts.clear();
            v.contacts.resize(n, 0);
            stepper.count_contacts(&mut v.contacts);
            return;
        }
        for (h, p) in self.built.particle_bodies.iter().zip(&self.scene.particles) {
            let b = &bodies[*h];
            v.position.push(to_na(b.translation()));
            v.velocity.push(to_na(b.linvel()));
            v.mass.push(b.mass());
            v.radius.push(p.radius);
        }
        v.contacts.clear();
        v.contacts.resize(n, 0);
        if let Coupling::RapierPipeline(stepper) = &self.built.coupling {
            stepper.for_each_contact(&mut |e| {
                let count = |c: rapier3d_f64::prelude::ColliderHandle, v: &mut Vec<u32>| {
                    if let Some(&i) = self
                        .built
                        .particle_of_collider
                        .get(c.into_raw_parts().0 as usize)
                    {
                        if i != usize::MAX {
                            v[i] += 1;
                        }
                    }
                };
                count(e.collider1, &mut v.contacts);
                count(e.collider2, &mut v.contacts);
            });
        }
    }

    fn view_ref(&self) -> ParticleView<'_> {
        self.view.view()
    }

    /// Gather the particles' view and give it to the headline tracker for this step.
    fn track_step(&mut self) {
        self.gather_view();
        self.tracker.on_step(self.scene, &self.view.view());
    }

    /// The wall guard: a sphere whose overlap with a wall exceeds [`CROSSING_OVERLAP`] of its
    /// radius is going through the wall (no contact law resolves such an overlap: the step is
    /// far too coarse for its speed, or a wall pushes it the wrong way). Checked at every step
    /// from the overlaps the force pass just computed.
    fn wall_guard(&self) -> Option<String> {
        let (i, wall, overlap, radius) = self.deepest_wall_overlap()?;
        (overlap > CROSSING_OVERLAP * radius).then(|| {
            let w = &self.scene.source.walls[wall];
            format!(
                "sphere {i} (radius {radius:.3e} m) sinks {overlap:.3e} m into wall {wall} \
                 (`walls[{wall}]`, kind {:?}{}): it is going through the wall. Lower dt_s or \
                 declare a larger max_speed_m_per_s if it is that fast; for a mesh, check its \
                 winding (docs/user-guide.md, mesh walls)",
                w.kind,
                w.file
                    .as_deref()
                    .map_or(String::new(), |f| format!(", file {f}"))
            )
        })
    }

    /// The touching sphere–wall pair with the largest overlap relative to the sphere's radius:
    /// (sphere, wall, overlap, radius).
    fn deepest_wall_overlap(&self) -> Option<(usize, usize, f64, f64)> {
        let mut deepest: Option<(usize, usize, f64, f64)> = None;
        let mut consider = |i: usize, wall: usize, overlap: f64, radius: f64| {
            if deepest.is_none_or(|(_, _, o, r)| overlap * r > o * radius) {
                deepest = Some((i, wall, overlap, radius));
            }
        };
        match &self.built.coupling {
            Coupling::NeighbourList(stepper) => {
                let radius = &stepper.particles().radius;
                stepper.for_each_surface_contact(&mut |i, surface, overlap| {
                    if let Some(&wall) = self.built.wall_of_surface.get(surface) {
                        consider(i, wall, overlap, radius[i]);
                    }
                });
            }
            Coupling::RapierPipeline(stepper) => {
                let index = |map: &[usize], c: rapier3d_f64::prelude::ColliderHandle| {
                    map.get(c.into_raw_parts().0 as usize)
                        .copied()
                        .filter(|&i| i != usize::MAX)
                };
                stepper.for_each_contact(&mut |e| {
                    let particle = index(&self.built.particle_of_collider, e.collider1);
                    let wall = index(&self.built.wall_of_collider, e.collider2);
                    if let (Some(i), Some(wall)) = (particle, wall) {
                        consider(i, wall, e.contact.overlap, self.scene.particles[i].radius);
                    }
                });
            }
            Coupling::Restitution(_) => {}
        }
        deepest
    }

    /// The energy guard: why the books' drift from their first row is beyond the scene's
    /// `max_energy_drift`, if it is.
    fn energy_guard(&self) -> Option<String> {
        energy_guard(self.scene, &self.energy, self.guard_floor_j)
    }

    /// Stop the run on a guard at step `k` (after its forces and samples): the step is finished
    /// (unless it is the last), a checkpoint and the series so far are written, and the error
    /// says why and where the state is.
    fn stop(&mut self, out: &Path, last: bool, reason: String) -> SimError {
        let (time, step) = (self.time(), self.step);
        let written = (|| {
            if !last {
                self.advance()?;
            }
            self.write_checkpoint(out)?;
            self.write_series(out, &mut Vec::new(), true)
        })();
        match (written, self.checkpoints.last()) {
            (Ok(()), Some(checkpoint)) => SimError::Stopped {
                time,
                step,
                reason,
                checkpoint: checkpoint.clone(),
            },
            (Err(e), _) => e,
            (Ok(()), None) => SimError::Diverged { time, step, reason },
        }
    }

    /// A resumed run continues the frame numbering and the collection from its checkpoint:
    /// frames numbered past the checkpoint's collection and checkpoints past its step belong to a
    /// future this run replaces, and are removed; the collection is written back as the
    /// checkpoint has it.
    fn remove_stale_outputs(&self, out: &Path) -> Result<(), SimError> {
        let frames = self.collection.iter().filter(|e| e.part == 0).count();
        let contact_frames = self.collection.iter().filter(|e| e.part == 1).count();
        crate::output::run_dir::remove_stale(
            out,
            &self.scene.name,
            frames,
            contact_frames,
            self.step,
        )
        .map_err(output(out))?;
        let pvd = out.join(format!("{}.pvd", self.scene.name));
        vtk::write_collection(&pvd, &self.collection).map_err(output(&pvd))
    }

    /// A NaN stops the run with a clear message.
    fn check_state(&self) -> Result<(), SimError> {
        for (i, p) in self.view.position.iter().enumerate() {
            let v = self.view.velocity[i];
            if !(p.iter().all(|c| c.is_finite()) && v.iter().all(|c| c.is_finite())) {
                return Err(SimError::Diverged {
                    time: self.time(),
                    step: self.step,
                    reason: format!(
                        "particle {i} has a non-finite position or velocity: reduce dt_s"
                    ),
                });
            }
        }
        Ok(())
    }
}

fn progress_bar(quiet: bool, total: u64, start: u64) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{bar:30.cyan/blue} {percent:>3}% {msg} ETA {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_position(start);
    bar
}

/// The energy guard of a run of `scene` whose energy rows are `rows`: why the balance's drift
/// from its first row with a balance is beyond the scene's `max_energy_drift` (measured against
/// at least `floor_j`, [`one_diameter_lift_j`]), if it is. Both devices' runs check it at each
/// energy sample.
pub fn energy_guard(scene: &Scene, rows: &[EnergyRow], floor_j: f64) -> Option<String> {
    let max = scene.max_energy_drift?;
    let drift = BalanceDrift::of(rows)?.at_least(floor_j);
    (drift.fraction.abs() > max).then(|| {
        format!(
            "the energy balance drifted by {:+.3e} J, {:+.2} % of the energy scale {:.3e} J, beyond \
             `run.max_energy_drift` = {max} ({} %): the time step is too coarse for the contacts \
             (lower dt_s or raise steps_per_contact), or a wall pushes spheres the wrong way (a \
             mesh's winding); raise max_energy_drift to go on",
            drift.joules,
            100.0 * drift.fraction,
            drift.scale_j,
            100.0 * max
        )
    })
}

/// The work of lifting every particle of the scene by its own diameter against gravity (J):
/// the floor of the energy guard's scale.
pub fn one_diameter_lift_j(scene: &Scene) -> f64 {
    let g = scene.gravity.norm();
    scene
        .particles
        .iter()
        .map(|p| {
            let density = scene.materials[p.material].1.density();
            let mass = 4.0 / 3.0 * std::f64::consts::PI * p.radius.powi(3) * density;
            mass * g * 2.0 * p.radius
        })
        .sum()
}

/// The scene's sink (`[run] delete_below_m`), if it has one (the GPU path parks its spheres
/// on the same spots).
pub fn scene_sink(scene: &Scene) -> Option<crate::walls::Sink> {
    let height = scene.source.run.delete_below_m?;
    let g = scene.gravity.norm();
    let up = if g > 0.0 {
        -scene.gravity / g
    } else {
        Vector3::z()
    };
    let centres: Vec<_> = scene.particles.iter().map(|p| p.position).collect();
    let radii: Vec<_> = scene.particles.iter().map(|p| p.radius).collect();
    Some(crate::walls::Sink::new(height, up, g, &centres, &radii))
}
