//! The bed benchmark: the reference system stepped on a bed, timed, with the figures
//! `mdr-dem bench bed` and Python's `mdr_dem.bench_bed` report.

use super::clock::{peak_rss_mb, process_cpu_seconds};
use super::generate::reference_system;
use super::{Bed, BedError};
use crate::error::{positive, CouplingError};
use crate::neighbour_list::stepper::NeighbourListStepper;
use crate::neighbour_list::workers::with_workers_awake;
use mdr_contact::damping::HertzianViscous;
use mdr_contact::model::WorkBooks;
use mdr_contact::normal::{AdhesiveMdr, Hertz, MdrElastoPlastic, NormalLaw, NormalModel, Thornton};
use mdr_contact::rolling::{EpsdRolling, EpsdRollingState, RollingLaw, RollingModel};
use mdr_contact::tangential::Mindlin;
use nalgebra::Vector3;
use rapier3d_f64::prelude::PhysicsWorld;
use std::path::{Path, PathBuf};

/// Normal law of [`bench_bed`]; the tangential law, damping and material are those of
/// [`reference_system`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BenchLaw {
    /// Hertz (`E* = 1.5e5` ⇔ `kn = 2e5`).
    Hertz,
    /// The MDR elasto-plastic law with critical line load `q_c = qc` (force/length, reduced
    /// units) and `Θ = 0.37 E*` ([`BENCH_THETA_RATIO`]).
    Mdr {
        /// Critical line load `q_c`.
        qc: f64,
    },
    /// Thornton's elastic–perfectly-plastic law (the 1997 unloading branch) with limiting
    /// contact pressure `p_y` (reduced units).
    Thornton {
        /// Limiting contact pressure `p_y`.
        yield_pressure: f64,
    },
    /// The adhesive MDR law: MDR with `q_c`, `Θ = 0.37 E*`, and Heß's detachment rule with
    /// work of adhesion `Δγ` (energy per area, reduced units); a contact holds at negative
    /// overlap until its neck lets go.
    AdhesiveMdr {
        /// Critical line load `q_c`.
        qc: f64,
        /// Work of adhesion `Δγ`.
        work_of_adhesion: f64,
    },
}

impl BenchLaw {
    /// The law's name in the figures and on the command line: `"hertz"`, `"mdr"`,
    /// `"thornton"` or `"adhesive-mdr"`.
    pub fn name(&self) -> &'static str {
        match self {
            BenchLaw::Hertz => "hertz",
            BenchLaw::Mdr { .. } => "mdr",
            BenchLaw::Thornton { .. } => "thornton",
            BenchLaw::AdhesiveMdr { .. } => "adhesive-mdr",
        }
    }

    /// Check the law's parameters as the law crate does; the error names the parameter
    /// (`q_c`, `yield_stress`, `work_of_adhesion`).
    pub fn validate(&self) -> Result<(), CouplingError> {
        match *self {
            BenchLaw::Hertz => {}
            BenchLaw::Mdr { qc } => {
                MdrElastoPlastic::new(qc, BENCH_THETA_RATIO)?;
            }
            BenchLaw::Thornton { yield_pressure } => {
                Thornton::new(yield_pressure)?;
            }
            BenchLaw::AdhesiveMdr {
                qc,
                work_of_adhesion,
            } => {
                AdhesiveMdr::new(
                    MdrElastoPlastic::new(qc, BENCH_THETA_RATIO)?,
                    work_of_adhesion,
                )?;
            }
        }
        Ok(())
    }
}

/// Settings of [`bench_bed`]; the defaults are those of `mdr-dem bench bed`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchSettings {
    /// Normal law.
    pub law: BenchLaw,
    /// Rolling resistance coefficient `μ_r` of the elastic–plastic spring rolling resistance
    /// (`EpsdRolling`), or none.
    pub rolling: Option<f64>,
    /// Timed steps (at least 1).
    pub steps: usize,
    /// Untimed steps before the timed ones (the first neighbour-list build, allocations; as
    /// `nwarm` of `benches/lammps/in.bench`).
    pub warmup: usize,
    /// Worker threads (at least 1); the run builds its own pool of this size.
    pub threads: usize,
    /// Repeat the bed `tile × tile` times in x and y (at least 1; scaling runs).
    pub tile: usize,
    /// Neighbour skin (length; LAMMPS `neighbor 0.1 bin`).
    pub skin: f64,
    /// Integrate particle orientations (LAMMPS `atom_style sphere` keeps none; sphere
    /// trajectories are the same either way).
    pub orientation: bool,
    /// Keep friction and damping work books in the pair histories (LAMMPS keeps none;
    /// trajectories are the same either way).
    pub work_books: bool,
}

impl Default for BenchSettings {
    fn default() -> Self {
        Self {
            law: BenchLaw::Hertz,
            rolling: None,
            steps: 10_000,
            warmup: 2_000,
            threads: 1,
            tile: 1,
            skin: 0.1,
            orientation: true,
            work_books: true,
        }
    }
}

impl BenchSettings {
    /// Check every setting without running anything: `steps`, `threads` and `tile` at least 1,
    /// `skin` finite and positive, the law's and the rolling resistance's parameters as the law
    /// crate accepts them. The error names the setting (`steps`, `threads`, `tile`, `skin`,
    /// `q_c`, `yield_stress`, `work_of_adhesion`, `mu_r`).
    pub fn validate(&self) -> Result<(), CouplingError> {
        for (name, value) in [
            ("steps", self.steps),
            ("threads", self.threads),
            ("tile", self.tile),
        ] {
            if value == 0 {
                return Err(CouplingError::OutOfRange {
                    name,
                    value: 0.0,
                    range: "[1, inf)",
                });
            }
        }
        positive("skin", self.skin)?;
        self.law.validate()?;
        if let Some(mu) = self.rolling {
            EpsdRolling::new(mu)?;
        }
        Ok(())
    }
}

/// `Θ / E*` of [`BenchLaw::Mdr`] and [`BenchLaw::AdhesiveMdr`].
pub const BENCH_THETA_RATIO: f64 = 0.37;

/// Figures of one [`bench_bed`] run. Rates count particle-steps: particles × timed steps.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchFigures {
    /// The law's name ([`BenchLaw::name`]).
    pub law: &'static str,
    /// Spheres (after tiling).
    pub particles: usize,
    /// Timed steps.
    pub steps: usize,
    /// Worker threads.
    pub threads: usize,
    /// Wall-clock time of the timed steps (s).
    pub wall_seconds: f64,
    /// CPU time (user + system, all threads of the process) during the timed steps (s); NaN
    /// where the process CPU clock is unavailable ([`process_cpu_seconds`]).
    pub cpu_seconds: f64,
    /// Particle-steps per wall-clock second.
    pub particle_steps_per_s: f64,
    /// Particle-steps per CPU second (all threads): per-core throughput that does not depend on
    /// how much of the machine other jobs take; NaN with `cpu_seconds`.
    pub particle_steps_per_cpu_s: f64,
    /// Wall-clock milliseconds per timed step.
    pub ms_per_step: f64,
    /// Sphere–sphere contacts per particle at the last step (`2 × pairs / particles`, as LAMMPS
    /// `contact/atom`).
    pub contacts_per_particle: f64,
    /// Sphere–floor contacts at the last step.
    pub floor_contacts: usize,
    /// Fraction of the touching sphere–sphere pairs that have yielded (`d_max` beyond the law's
    /// yield overlap; 0 for Hertz).
    pub plastic_contact_fraction: f64,
    /// Neighbour-list builds during the timed steps.
    pub rebuilds: u64,
    /// Peak resident set size of the whole process so far (MB, [`peak_rss_mb`]); 0 where
    /// unavailable.
    pub peak_rss_mb: f64,
    /// The stepper's buffers (particles, neighbour lists, histories) per particle (bytes).
    pub stepper_bytes_per_particle: f64,
    /// Whether orientations were integrated.
    pub orientation: bool,
    /// Whether the pair histories booked friction and damping work.
    pub work_books: bool,
    /// FNV-1a hash (16 hex digits) of the bits of every particle's final position, velocity and
    /// angular velocity: two builds (or thread counts) gave the same trajectories iff it is the
    /// same.
    pub state_checksum: String,
}

/// One value of [`BenchFigures::fields`].
#[derive(Debug, Clone, PartialEq)]
pub enum BenchValue<'a> {
    /// A real number.
    Real(f64),
    /// A count.
    Count(u64),
    /// A yes/no.
    Flag(bool),
    /// Text.
    Text(&'a str),
}

impl BenchFigures {
    /// The figures by name, in the order and with the keys of `mdr-dem bench bed --json`.
    pub fn fields(&self) -> [(&'static str, BenchValue<'_>); 18] {
        use BenchValue::{Count, Flag, Real, Text};
        [
            ("particle_steps_per_s", Real(self.particle_steps_per_s)),
            ("ms_per_step", Real(self.ms_per_step)),
            ("contacts_per_particle", Real(self.contacts_per_particle)),
            ("peak_rss_mb", Real(self.peak_rss_mb)),
            ("threads", Count(self.threads as u64)),
            (
                "particle_steps_per_cpu_s",
                Real(self.particle_steps_per_cpu_s),
            ),
            ("cpu_seconds", Real(self.cpu_seconds)),
            ("wall_seconds", Real(self.wall_seconds)),
            ("law", Text(self.law)),
            ("particles", Count(self.particles as u64)),
            ("steps", Count(self.steps as u64)),
            ("rebuilds", Count(self.rebuilds)),
            ("floor_contacts", Count(self.floor_contacts as u64)),
            (
                "plastic_contact_fraction",
                Real(self.plastic_contact_fraction),
            ),
            (
                "stepper_bytes_per_particle",
                Real(self.stepper_bytes_per_particle),
            ),
            ("orientation", Flag(self.orientation)),
            ("work_books", Flag(self.work_books)),
            ("state_checksum", Text(&self.state_checksum)),
        ]
    }
}

/// Throughput of the neighbour-list path on `bed` (the program's `mdr-dem bench bed`): the
/// [`reference_system`] with the settings' law, rolling resistance and skin on the bed tiled
/// `tile × tile` times ([`run_reference_system`]),
/// `warmup` untimed steps, then `steps` timed ones, in a pool of `threads` worker threads.
/// The bed must be the reference one (every sphere of diameter 1 and density 1), as the
/// reference system's material is.
pub fn bench_bed(bed: &Bed, settings: &BenchSettings) -> Result<BenchFigures, BedError> {
    settings.validate()?;
    if let Some(i) = (0..bed.len())
        .find(|&i| (bed.diameter[i] - 1.0).abs() > 1e-12 || (bed.density[i] - 1.0).abs() > 1e-12)
    {
        return Err(BedError::NotReference {
            sphere: i + 1,
            diameter: bed.diameter[i],
            density: bed.density[i],
        });
    }
    run_reference_system(bed, settings, TimedRun(settings))?
}

/// The torque a rolling law's per-contact state stores (zero without rolling resistance).
pub trait RollingTorque {
    /// The stored torque on body 1.
    fn torque(&self) -> Vector3<f64>;
}

impl RollingTorque for () {
    fn torque(&self) -> Vector3<f64> {
        Vector3::zeros()
    }
}

impl RollingTorque for EpsdRollingState {
    fn torque(&self) -> Vector3<f64> {
        self.torque
    }
}

/// What to do with the reference system once [`run_reference_system`] has bound its laws: the
/// models are type parameters, so a run is a trait rather than a closure.
pub trait ReferenceRun: Send {
    /// What the run returns.
    type Output: Send;
    /// Step `stepper` (the reference system with the settings' law, rolling resistance, skin
    /// and orientation tracking) in `world`.
    fn run<N, R>(
        self,
        stepper: NeighbourListStepper<N, Mindlin, HertzianViscous, R>,
        world: PhysicsWorld,
    ) -> Self::Output
    where
        N: NormalModel,
        N::Law: Clone,
        R: RollingModel,
        R::Law: Clone,
        <R::Law as RollingLaw>::State: RollingTorque;
}

/// The [`reference_system`] of `bed` tiled `settings.tile × settings.tile` times, with the
/// settings' normal law, rolling resistance (`EpsdRolling` where set), skin and orientation
/// tracking, handed to `run` inside a pool of `settings.threads` worker threads. The one place
/// where a [`BenchLaw`] becomes a contact model: the CPU benchmark and the GPU path's CPU
/// reference both run through it.
pub fn run_reference_system<V: ReferenceRun>(
    bed: &Bed,
    settings: &BenchSettings,
    run: V,
) -> Result<V::Output, BedError> {
    settings.validate()?;
    let tiled;
    let bed = if settings.tile > 1 {
        tiled = bed.tiled(settings.tile, settings.tile)?;
        &tiled
    } else {
        bed
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(settings.threads)
        .build()
        .map_err(|e| BedError::ThreadPool(e.to_string()))?;
    let theta = BENCH_THETA_RATIO;
    pool.install(|| match settings.law {
        BenchLaw::Hertz => with_rolling(Hertz, bed, settings, run),
        BenchLaw::Mdr { qc } => with_rolling(
            MdrElastoPlastic::new(qc, theta).map_err(CouplingError::from)?,
            bed,
            settings,
            run,
        ),
        BenchLaw::Thornton { yield_pressure } => with_rolling(
            Thornton::new(yield_pressure).map_err(CouplingError::from)?,
            bed,
            settings,
            run,
        ),
        BenchLaw::AdhesiveMdr {
            qc,
            work_of_adhesion,
        } => with_rolling(
            AdhesiveMdr::new(
                MdrElastoPlastic::new(qc, theta).map_err(CouplingError::from)?,
                work_of_adhesion,
            )
            .map_err(CouplingError::from)?,
            bed,
            settings,
            run,
        ),
    })
}

/// The reference system with `normal` and the settings' rolling resistance, handed to `run`.
fn with_rolling<N, V>(
    normal: N,
    bed: &Bed,
    s: &BenchSettings,
    run: V,
) -> Result<V::Output, BedError>
where
    N: NormalModel,
    N::Law: Clone,
    V: ReferenceRun,
{
    let (stepper, world) = reference_system(normal, bed)?;
    let stepper = stepper.skin(s.skin)?;
    Ok(match s.rolling {
        None => run.run(stepper.track_orientation(s.orientation), world),
        Some(mu) => {
            let rolling = EpsdRolling::new(mu).map_err(CouplingError::from)?;
            let stepper = stepper
                .with_rolling(rolling)
                .track_orientation(s.orientation);
            run.run(stepper, world)
        }
    })
}

/// The timed run of [`bench_bed`].
struct TimedRun<'a>(&'a BenchSettings);

impl ReferenceRun for TimedRun<'_> {
    type Output = Result<BenchFigures, BedError>;

    fn run<N, R>(
        self,
        stepper: NeighbourListStepper<N, Mindlin, HertzianViscous, R>,
        world: PhysicsWorld,
    ) -> Self::Output
    where
        N: NormalModel,
        N::Law: Clone,
        R: RollingModel,
        R::Law: Clone,
        <R::Law as RollingLaw>::State: RollingTorque,
    {
        if self.0.work_books {
            bench_steps(stepper, world, self.0)
        } else {
            bench_steps(stepper.without_work_books(), world, self.0)
        }
    }
}

/// Warm-up, then the timed steps, then the figures.
fn bench_steps<N, R, B>(
    mut stepper: NeighbourListStepper<N, Mindlin, HertzianViscous, R, B>,
    mut world: PhysicsWorld,
    s: &BenchSettings,
) -> Result<BenchFigures, BedError>
where
    N: NormalModel,
    N::Law: Clone,
    R: RollingModel,
    R::Law: Clone,
    B: WorkBooks,
{
    // The pool's other threads wait for each pass awake (`workers`), as a scene run's do.
    let (rebuilds0, wall_seconds, cpu_seconds) = with_workers_awake(|| -> Result<_, BedError> {
        for _ in 0..s.warmup {
            stepper.step(&mut world)?;
        }
        let rebuilds0 = stepper.rebuilds();
        let cpu0 = process_cpu_seconds();
        let start = std::time::Instant::now();
        for _ in 0..s.steps {
            stepper.step(&mut world)?;
        }
        let wall_seconds = start.elapsed().as_secs_f64();
        let cpu_seconds = match (cpu0, process_cpu_seconds()) {
            (Some(a), Some(b)) => b - a,
            _ => f64::NAN,
        };
        Ok((rebuilds0, wall_seconds, cpu_seconds))
    })?;
    let report = stepper.last_report();
    let n = stepper.particles().len();
    let pairs = stepper.pairs();
    let (mut touching, mut plastic) = (0usize, 0usize);
    for q in 0..pairs.len() {
        if pairs.active[q] {
            touching += 1;
            let law = stepper.sphere_law(pairs.i[q] as usize, pairs.j[q] as usize);
            let state = &pairs.history[q].contact.normal;
            if law.normal.max_overlap(state) > law.normal.yield_overlap() {
                plastic += 1;
            }
        }
    }
    let particle_steps = (n * s.steps) as f64;
    let p = stepper.particles();
    let vectors = p.position.iter().chain(&p.linvel).chain(&p.angvel);
    Ok(BenchFigures {
        law: s.law.name(),
        particles: n,
        steps: s.steps,
        threads: s.threads,
        wall_seconds,
        cpu_seconds,
        particle_steps_per_s: particle_steps / wall_seconds,
        particle_steps_per_cpu_s: particle_steps / cpu_seconds,
        ms_per_step: 1e3 * wall_seconds / s.steps as f64,
        contacts_per_particle: 2.0 * report.sphere_contacts as f64 / n as f64,
        floor_contacts: report.surface_contacts,
        plastic_contact_fraction: if touching > 0 {
            plastic as f64 / touching as f64
        } else {
            0.0
        },
        rebuilds: stepper.rebuilds() - rebuilds0,
        peak_rss_mb: peak_rss_mb(),
        stepper_bytes_per_particle: stepper.memory_bytes() as f64 / n as f64,
        orientation: s.orientation,
        work_books: s.work_books,
        state_checksum: state_checksum(vectors),
    })
}

/// `state_checksum` of [`BenchFigures`]: FNV-1a (64 bit) over the bit patterns of the vectors'
/// components, in order (the GPU path hashes its state with it too, so the two compare).
pub fn state_checksum<'a>(vectors: impl Iterator<Item = &'a Vector3<f64>>) -> String {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for v in vectors {
        for c in [v.x, v.y, v.z] {
            for byte in c.to_bits().to_le_bytes() {
                hash ^= u64::from(byte);
                hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
    }
    format!("{hash:016x}")
}

/// The reference bed of the benchmark, relative to a checkout of the repository.
pub const REFERENCE_DATA: &str = "benches/lammps/settled.data";

/// The reference bed [`REFERENCE_DATA`], looked for in this order: the working directory and
/// each of its ancestors (the checkout the user works in comes first), then `built_from` (the
/// directory of the crate that was built, `env!("CARGO_MANIFEST_DIR")` of the caller) and each
/// of its ancestors. The first that is a file is returned; otherwise the error lists every path
/// looked at.
pub fn reference_data(built_from: &Path) -> Result<PathBuf, BedError> {
    let relative = Path::new(REFERENCE_DATA);
    let mut tried = Vec::new();
    let roots = std::env::current_dir()
        .into_iter()
        .chain(std::iter::once(built_from.to_path_buf()));
    for root in roots {
        for candidate in root.ancestors().map(|a| a.join(relative)) {
            if candidate.is_file() {
                return Ok(candidate);
            }
            tried.push(candidate);
        }
    }
    Err(BedError::NoReferenceData { tried })
}
