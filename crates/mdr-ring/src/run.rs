//! A ring run: configuration (REBOUND's shearing-sheet defaults), the time loop and its samples.
//!
//! One step of length `Δt` (docs/rings.md §4):
//! 1. **collide** — rapier, with the restitution hook, resolves every contact that closes within
//!    `Δt` (speculative contacts) at the current positions and changes velocities only;
//! 2. **drift** — the SEI moves every particle along its exact epicycle for `Δt` (with self-gravity:
//!    half drift, kick, half drift, as REBOUND's SEI);
//! 3. **wrap** — particles that left the box re-enter through the shear-periodic boundaries.

use crate::boundary::ShearingBox;
use crate::diagnostics::{sample, summarize, Sample, Summary};
use crate::error::{in_range, positive, Result, RingError};
use crate::gravity::SelfGravity;
use crate::hill::{HillFrame, Sei};
use crate::law::RestitutionLaw;
use crate::particles::{initial_conditions, Particles, Population, SizeDistribution};
use crate::world::{CollisionSettings, CollisionWorld};
use serde::Serialize;
use std::time::Instant;

/// REBOUND's shearing-sheet orbital frequency (1/s): Saturn's A ring at 130,000 km.
pub const REBOUND_OMEGA: f64 = 1.3143527e-4;

/// Settings of a ring run. [`RingConfig::default`] is REBOUND's shearing-sheet example
/// (`examples/shearing_sheet`, `benches/rebound/ring.py`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RingConfig {
    /// Orbital frequency `Ω` (1/s).
    pub omega: f64,
    /// How many particles.
    pub population: Population,
    /// Particle density (kg/m³).
    pub density: f64,
    /// Radius distribution.
    pub sizes: SizeDistribution,
    /// Side of the square box (m).
    pub box_size: f64,
    /// Time step in orbits.
    pub dt_orbits: f64,
    /// Sampling interval in orbits.
    pub sample_orbits: f64,
    /// Seed of the initial conditions.
    pub seed: u64,
    /// Self-gravity (None: off).
    pub gravity: Option<SelfGravity>,
    /// rapier settings of the collision step.
    pub collisions: CollisionSettings,
}

impl Default for RingConfig {
    fn default() -> Self {
        Self {
            omega: REBOUND_OMEGA,
            population: Population::SurfaceDensity(400.0),
            density: 400.0,
            sizes: SizeDistribution::rebound_default(),
            box_size: 200.0,
            dt_orbits: 1e-3,
            sample_orbits: 0.1,
            seed: 1,
            gravity: None,
            collisions: CollisionSettings::default(),
        }
    }
}

impl RingConfig {
    /// Set the number of particles (instead of the surface density).
    pub fn particles(mut self, count: usize) -> Self {
        self.population = Population::Count(count);
        self
    }

    /// Set the surface density Σ (kg/m²).
    pub fn surface_density(mut self, sigma: f64) -> Self {
        self.population = Population::SurfaceDensity(sigma);
        self
    }

    /// Set the box side (m).
    pub fn box_size(mut self, side: f64) -> Self {
        self.box_size = side;
        self
    }

    /// Set the seed.
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Set the time step in orbits.
    pub fn dt_orbits(mut self, dt: f64) -> Self {
        self.dt_orbits = dt;
        self
    }

    /// Switch self-gravity on with these settings.
    pub fn gravity(mut self, gravity: SelfGravity) -> Self {
        self.gravity = Some(gravity);
        self
    }

    /// Set the collision settings.
    pub fn collisions(mut self, settings: CollisionSettings) -> Self {
        self.collisions = settings;
        self
    }

    /// Set the size distribution.
    pub fn sizes(mut self, sizes: SizeDistribution) -> Self {
        self.sizes = sizes;
        self
    }

    /// Check every parameter.
    pub fn validate(&self) -> Result<()> {
        positive("omega", self.omega)?;
        positive("density", self.density)?;
        positive("box", self.box_size)?;
        in_range("dt_orbits", self.dt_orbits, 1e-6, 0.1, "[1e-6, 0.1]")?;
        in_range(
            "sample_orbits",
            self.sample_orbits,
            self.dt_orbits,
            f64::MAX,
            "[dt, inf)",
        )?;
        positive("prediction_distance", self.collisions.prediction_distance)?;
        // The ghost strip must not wrap onto itself: a particle may meet only one image of
        // another one.
        let reach = 4.0 * self.sizes.r_max() + 2.0 * self.collisions.prediction_distance;
        if self.box_size < 2.0 * reach {
            return Err(RingError::OutOfRange {
                name: "box",
                value: self.box_size,
                range: "[8 r_max + 4 prediction, inf)",
            });
        }
        if let Some(g) = self.gravity {
            g.validate()?;
        }
        Ok(())
    }
}

/// The result of [`RingSimulation::run`].
#[derive(Debug, Clone, Serialize)]
pub struct RunResult {
    /// Second-half averages.
    pub summary: Summary,
    /// Time series.
    pub samples: Vec<Sample>,
}

/// A shearing-box ring with collisions through a [`RestitutionLaw`].
pub struct RingSimulation<L: RestitutionLaw> {
    config: RingConfig,
    domain: ShearingBox,
    sei: Sei,
    half_sei: Sei,
    particles: Particles,
    world: CollisionWorld<L>,
    time: f64,
    steps: u64,
}

impl<L: RestitutionLaw> RingSimulation<L> {
    /// Draw the initial conditions of `config` and build the rapier world.
    pub fn new(config: RingConfig, law: L) -> Result<Self> {
        config.validate()?;
        let frame = HillFrame::new(config.omega)?;
        let domain = ShearingBox::new(frame, config.box_size, config.box_size)?;
        let particles = initial_conditions(
            &domain,
            &config.sizes,
            config.density,
            config.population,
            config.seed,
        )?;
        Self::from_particles(config, particles, law)
    }

    /// A run from given particles (inside the box).
    pub fn from_particles(config: RingConfig, particles: Particles, law: L) -> Result<Self> {
        config.validate()?;
        let frame = HillFrame::new(config.omega)?;
        let domain = ShearingBox::new(frame, config.box_size, config.box_size)?;
        let dt = config.dt_orbits * frame.period();
        let world = CollisionWorld::new(&particles, law, dt, config.collisions);
        Ok(Self {
            config,
            domain,
            sei: Sei::new(frame, dt)?,
            half_sei: Sei::new(frame, 0.5 * dt)?,
            particles,
            world,
            time: 0.0,
            steps: 0,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &RingConfig {
        &self.config
    }

    /// The box.
    pub fn domain(&self) -> &ShearingBox {
        &self.domain
    }

    /// The particles.
    pub fn particles(&self) -> &Particles {
        &self.particles
    }

    /// Time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Time in orbits.
    pub fn time_orbits(&self) -> f64 {
        self.time / self.domain.frame().period()
    }

    /// Impacts resolved so far.
    pub fn collisions(&self) -> u64 {
        self.world.hooks().collisions()
    }

    /// The collision world (ghost count, law).
    pub fn world(&self) -> &CollisionWorld<L> {
        &self.world
    }

    /// The current sample (collision count filled in, wall time zero).
    pub fn sample(&self) -> Sample {
        Sample {
            collisions: self.collisions(),
            ..sample(&self.domain, &self.particles, self.time_orbits())
        }
    }

    /// One step: collide, drift (SEI), wrap.
    pub fn step(&mut self) {
        self.world
            .collide(&mut self.particles, &self.domain, self.time);
        let Particles {
            position, velocity, ..
        } = &mut self.particles;
        match self.config.gravity {
            None => {
                for (p, v) in position.iter_mut().zip(velocity.iter_mut()) {
                    self.sei.advance(p, v);
                }
            }
            Some(gravity) => {
                for (p, v) in position.iter_mut().zip(velocity.iter_mut()) {
                    self.half_sei.advance(p, v);
                }
                let dt = self.sei.dt();
                let mid = self.time + 0.5 * dt;
                let acc = gravity.accelerations(&self.domain, &self.particles, mid);
                let Particles {
                    position, velocity, ..
                } = &mut self.particles;
                for (v, a) in velocity.iter_mut().zip(&acc) {
                    *v += *a * dt;
                }
                for (p, v) in position.iter_mut().zip(velocity.iter_mut()) {
                    self.half_sei.advance(p, v);
                }
            }
        }
        self.steps += 1;
        self.time = self.steps as f64 * self.sei.dt();
        let Particles {
            position, velocity, ..
        } = &mut self.particles;
        for (p, v) in position.iter_mut().zip(velocity.iter_mut()) {
            self.domain.wrap(p, v, self.time);
        }
    }

    /// Take up to `steps` steps, stopping early after a step for which `stop` returns true;
    /// returns the number taken. The steps run on a worker of rayon's pool: rapier's solver and
    /// broad phase and the tree gravity fork there, and a fork from outside the pool would hand
    /// each parallel section to a worker and wait for it (a sleep and a wake-up per section,
    /// 15 % of a one-thread step of the 1,500-particle sheet).
    pub fn step_many(&mut self, steps: u64, stop: impl Fn() -> bool + Sync) -> u64 {
        rayon::scope(|_| {
            let mut taken = 0;
            while taken < steps {
                self.step();
                taken += 1;
                if stop() {
                    break;
                }
            }
            taken
        })
    }

    /// Run for `orbits` orbits, sampling every `sample_orbits`; `observer` sees every sample and
    /// the particles at that time (for progress lines and frames).
    pub fn run(
        &mut self,
        orbits: f64,
        mut observer: impl FnMut(&Sample, &Particles),
    ) -> Result<RunResult> {
        positive("orbits", orbits)?;
        let per_sample =
            ((self.config.sample_orbits / self.config.dt_orbits).round() as u64).max(1);
        let total = (orbits / self.config.dt_orbits).round() as u64;
        let start = Instant::now();
        let mut samples = Vec::with_capacity((total / per_sample.max(1)) as usize + 1);
        let mut done = 0;
        while done < total {
            let chunk = (per_sample - done % per_sample).min(total - done);
            done += self.step_many(chunk, || false);
            let s = Sample {
                wall_s: start.elapsed().as_secs_f64(),
                ..self.sample()
            };
            observer(&s, &self.particles);
            samples.push(s);
        }
        let summary = summarize(&samples, &self.particles, &self.domain, orbits);
        Ok(RunResult { summary, samples })
    }
}
