//! Granular beds for benchmarks: reading and writing LAMMPS data files (`atom_style sphere`),
//! tiling a periodic bed, generating a bed by lattice + settling, and the bed benchmark itself
//! ([`bench_bed`], what `mdr-dem bench bed` and Python's `mdr_dem.bench_bed` run) with the
//! process clocks it reads ([`process_cpu_seconds`], [`peak_rss_mb`]).

use super::boundary::Boundary;
use super::stepper::FastForceStepper;
use crate::error::{positive, CouplingError, Result};
use crate::particles::SphereBuilder;
use mdr_contact::damping::HertzianViscous;
use mdr_contact::model::{ContactModel, WorkBooks};
use mdr_contact::normal::{Hertz, MdrElastoPlastic, NormalLaw, NormalModel};
use mdr_contact::rolling::NoRolling;
use mdr_contact::tangential::Mindlin;
use mdr_contact::Material;
use nalgebra::Vector3;
use rapier3d_f64::prelude::*;
use std::io::Write;
use std::path::Path;

/// Spheres in a box: what a LAMMPS data file with `atom_style sphere` holds.
#[derive(Debug, Clone, PartialEq)]
pub struct Bed {
    /// Box lower corner.
    pub lo: [f64; 3],
    /// Box upper corner.
    pub hi: [f64; 3],
    /// Diameters.
    pub diameter: Vec<f64>,
    /// Densities.
    pub density: Vec<f64>,
    /// Centres.
    pub position: Vec<Vector3<f64>>,
}

/// Errors of bed files.
#[derive(Debug, thiserror::Error)]
pub enum BedError {
    /// The file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The file is not a LAMMPS data file this reader understands.
    #[error("{path}, line {line}: {message}")]
    Format {
        /// The file.
        path: String,
        /// Line number (1-based).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A parameter is out of range, or the stepper failed.
    #[error(transparent)]
    Coupling(#[from] CouplingError),
    /// [`bench_bed`] was given a bed that is not the reference one.
    #[error(
        "sphere {sphere} has diameter {diameter} and density {density}: the bed benchmark \
         expects the reference bed (diameter 1, density 1)"
    )]
    NotReference {
        /// The sphere (1-based, file order).
        sphere: usize,
        /// Its diameter.
        diameter: f64,
        /// Its density.
        density: f64,
    },
    /// The worker-thread pool could not be built.
    #[error("building the thread pool: {0}")]
    ThreadPool(String),
    /// A size parameter asks for more spheres than a bed may hold (checked before anything is
    /// allocated).
    #[error(
        "parameter `{name}` = {value} asks for {spheres} spheres; a bed holds at most \
         {limit} (MAX_BED_SPHERES)"
    )]
    TooManySpheres {
        /// The parameter as the user knows it (`count`, `tile`).
        name: &'static str,
        /// The value that was given.
        value: usize,
        /// The spheres it asks for (saturating).
        spheres: u128,
        /// [`MAX_BED_SPHERES`].
        limit: usize,
    },
}

/// The most spheres a generated or tiled bed may hold, 10⁸: `count` and `tile` are checked
/// against it before anything is allocated.
pub const MAX_BED_SPHERES: usize = 100_000_000;

/// `Err(TooManySpheres)` unless `spheres ≤ MAX_BED_SPHERES`.
fn bounded_spheres(name: &'static str, value: usize, spheres: u128) -> Result<usize, BedError> {
    if spheres <= MAX_BED_SPHERES as u128 {
        Ok(spheres as usize)
    } else {
        Err(BedError::TooManySpheres {
            name,
            value,
            spheres,
            limit: MAX_BED_SPHERES,
        })
    }
}

impl Bed {
    /// Number of spheres.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// Whether the bed is empty.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Read a LAMMPS data file (`atom_style sphere`: `id type diameter density x y z [ix iy iz]`).
    /// Atoms are kept in file order.
    pub fn read_lammps(path: &Path) -> Result<Bed, BedError> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| BedError::Io {
            path: name.clone(),
            source,
        })?;
        let bad = |line: usize, message: String| BedError::Format {
            path: name.clone(),
            line,
            message,
        };
        let mut lo = [0.0; 3];
        let mut hi = [0.0; 3];
        let mut count = None;
        let mut bed = Bed {
            lo,
            hi,
            diameter: Vec::new(),
            density: Vec::new(),
            position: Vec::new(),
        };
        let mut in_atoms = false;
        for (k, raw) in text.lines().enumerate() {
            let line = raw.split('#').next().unwrap_or("").trim();
            if k == 0 || line.is_empty() {
                if raw.trim_start().starts_with("Atoms") {
                    in_atoms = true;
                }
                continue;
            }
            let words: Vec<&str> = line.split_whitespace().collect();
            if raw.trim_start().starts_with("Atoms") {
                in_atoms = true;
                continue;
            }
            if in_atoms {
                if words[0].parse::<f64>().is_err() {
                    in_atoms = false;
                    continue;
                }
                if words.len() < 7 {
                    return Err(bad(
                        k + 1,
                        format!("atom line has {} fields, expected 7", words.len()),
                    ));
                }
                let v: Vec<f64> = words[2..7]
                    .iter()
                    .map(|w| w.parse::<f64>())
                    .collect::<std::result::Result<_, _>>()
                    .map_err(|e| bad(k + 1, format!("{e}")))?;
                bed.diameter.push(v[0]);
                bed.density.push(v[1]);
                bed.position.push(Vector3::new(v[2], v[3], v[4]));
                continue;
            }
            let parse = |w: &str| {
                w.parse::<f64>()
                    .map_err(|e| bad(k + 1, format!("`{w}`: {e}")))
            };
            if words.len() == 2 && words[1] == "atoms" {
                count = Some(parse(words[0])? as usize);
            } else if words.len() == 4 && words[3].ends_with("hi") {
                let axis = match words[2] {
                    "xlo" => 0,
                    "ylo" => 1,
                    "zlo" => 2,
                    _ => continue,
                };
                lo[axis] = parse(words[0])?;
                hi[axis] = parse(words[1])?;
            }
        }
        bed.lo = lo;
        bed.hi = hi;
        match count {
            Some(c) if c == bed.len() => Ok(bed),
            Some(c) => Err(bad(
                0,
                format!("header says {c} atoms, found {}", bed.len()),
            )),
            None => Err(bad(0, "no `N atoms` header line".into())),
        }
    }

    /// Write a LAMMPS data file (atomically: temporary file, then rename).
    pub fn write_lammps(&self, path: &Path) -> Result<(), BedError> {
        let name = path.display().to_string();
        let io = |source| BedError::Io {
            path: name.clone(),
            source,
        };
        let tmp = path.with_extension("tmp");
        {
            let mut f = std::io::BufWriter::new(std::fs::File::create(&tmp).map_err(io)?);
            writeln!(f, "LAMMPS data file written by mdr-rapier (fast::bed)\n").map_err(io)?;
            writeln!(f, "{} atoms\n1 atom types\n", self.len()).map_err(io)?;
            for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                writeln!(f, "{} {} {axis}lo {axis}hi", self.lo[k], self.hi[k]).map_err(io)?;
            }
            writeln!(f, "\nAtoms # sphere\n").map_err(io)?;
            for i in 0..self.len() {
                let p = self.position[i];
                writeln!(
                    f,
                    "{} 1 {} {} {} {} {} 0 0 0",
                    i + 1,
                    self.diameter[i],
                    self.density[i],
                    p.x,
                    p.y,
                    p.z
                )
                .map_err(io)?;
            }
            f.flush().map_err(io)?;
        }
        std::fs::rename(&tmp, path).map_err(io)
    }

    /// The bed repeated `nx × ny` times in x and y (a periodic bed stays a valid periodic bed).
    /// Refuses (naming `tile`) a result of more than [`MAX_BED_SPHERES`] spheres.
    pub fn tiled(&self, nx: usize, ny: usize) -> Result<Bed, BedError> {
        let spheres = (self.len() as u128)
            .saturating_mul(nx as u128)
            .saturating_mul(ny as u128);
        let total = bounded_spheres("tile", nx.max(ny), spheres)?;
        let lx = self.hi[0] - self.lo[0];
        let ly = self.hi[1] - self.lo[1];
        let mut out = Bed {
            lo: self.lo,
            hi: [
                self.lo[0] + lx * nx as f64,
                self.lo[1] + ly * ny as f64,
                self.hi[2],
            ],
            diameter: Vec::with_capacity(total),
            density: Vec::with_capacity(total),
            position: Vec::with_capacity(total),
        };
        // Tile-major in y then x, so that neighbouring particles keep nearby indices.
        for ty in 0..ny {
            for tx in 0..nx {
                let shift = Vector3::new(lx * tx as f64, ly * ty as f64, 0.0);
                for i in 0..self.len() {
                    out.diameter.push(self.diameter[i]);
                    out.density.push(self.density[i]);
                    out.position.push(self.position[i] + shift);
                }
            }
        }
        Ok(out)
    }

    /// Sort the spheres by cell (`cell` side) along z, then y, then x, so that particles close in
    /// space are close in memory (as LAMMPS's atom sorting).
    pub fn sort_spatially(&mut self, cell: f64) {
        let key = |p: &Vector3<f64>| {
            let c = |k: usize| ((p[k] - self.lo[k]) / cell).floor() as i64;
            (c(2), c(1), c(0))
        };
        let mut order: Vec<usize> = (0..self.len()).collect();
        order.sort_by_key(|&i| key(&self.position[i]));
        self.diameter = order.iter().map(|&i| self.diameter[i]).collect();
        self.density = order.iter().map(|&i| self.density[i]).collect();
        self.position = order.iter().map(|&i| self.position[i]).collect();
    }
}

/// Parameters of [`settled_bed`]: monodisperse spheres poured from a jittered lattice onto the
/// floor `z = 0` of an x/y-periodic box and settled with the reference system of
/// `benches/lammps` (`kn = 2e5` Hertz, `γn = 50`, `μ = 0.5`, `g = 1`, `dt = 1e-4`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BedSpec {
    /// Number of spheres.
    pub count: usize,
    /// Spheres per unit floor area (the reference bed has 10,000 / 22² ≈ 20.66).
    pub areal_density: f64,
    /// Settling steps.
    pub settle_steps: usize,
    /// Seed of the jitter.
    pub seed: u64,
}

impl Default for BedSpec {
    fn default() -> Self {
        Self {
            count: 1000,
            areal_density: 10_000.0 / (22.0 * 22.0),
            settle_steps: 40_000,
            seed: 1,
        }
    }
}

/// A small deterministic generator (SplitMix64) so that beds are reproducible without a
/// dependency.
fn split_mix(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// Spheres of diameter 1 on a jittered cubic lattice (spacing 1.1) in a square x/y-periodic box
/// sized for `spec.areal_density`, falling from rest.
pub fn lattice_bed(spec: &BedSpec) -> Result<Bed, BedError> {
    positive("areal_density", spec.areal_density)?;
    if spec.count == 0 {
        return Err(CouplingError::OutOfRange {
            name: "count",
            value: 0.0,
            range: "[1, inf)",
        }
        .into());
    }
    bounded_spheres("count", spec.count, spec.count as u128)?;
    let side = (spec.count as f64 / spec.areal_density).sqrt();
    let spacing = 1.1;
    let per_row = (side / spacing).floor().max(1.0) as usize;
    let per_layer = per_row * per_row;
    let cell = side / per_row as f64;
    let mut rng = spec.seed;
    let mut bed = Bed {
        lo: [0.0; 3],
        hi: [side, side, 0.0],
        diameter: vec![1.0; spec.count],
        density: vec![1.0; spec.count],
        position: Vec::with_capacity(spec.count),
    };
    for k in 0..spec.count {
        let layer = k / per_layer;
        let (row, col) = ((k % per_layer) / per_row, k % per_row);
        let jitter = |rng: &mut u64| 0.04 * (split_mix(rng) - 0.5);
        bed.position.push(Vector3::new(
            (col as f64 + 0.5) * cell + jitter(&mut rng),
            (row as f64 + 0.5) * cell + jitter(&mut rng),
            0.55 + layer as f64 * spacing + jitter(&mut rng),
        ));
    }
    bed.hi[2] = bed.position.iter().map(|p| p.z).fold(0.0, f64::max) + 1.0;
    Ok(bed)
}

/// The reference system of `benches/lammps/in.bench` (`hertzhist`) on `bed`, with
/// normal law `normal`: diameter-1, density-1 spheres, Mindlin `μ = 0.5`, normal damping
/// `γn = 50` and tangential damping `γt = γn/2` (LAMMPS `gammat = NULL`), `kn = 2e5` (`E* = 1.5e5`) and LAMMPS's `kt = 2/7 kn` (`G* = kt/2`), the floor
/// `z = 0` as a rapier half-space, `g = 1` along −z, `dt = 1e-4`, x/y periodic over the bed's box
/// (docs/performance.md). Returns the stepper (skin 0.1) and the rapier world.
#[allow(clippy::type_complexity)]
pub fn reference_system<N>(
    normal: N,
    bed: &Bed,
) -> Result<(FastForceStepper<N, Mindlin, HertzianViscous>, PhysicsWorld)>
where
    N: NormalModel,
    N::Law: Clone,
{
    let boundary = Boundary::periodic_xy((bed.lo[0], bed.hi[0]), (bed.lo[1], bed.hi[1]))?;
    let model = ContactModel::new(normal)
        .with_tangential(Mindlin::new(0.5)?)
        .with_damping(HertzianViscous::new(50.0)?.with_tangential_ratio(0.5)?);
    let mut stepper = FastForceStepper::new(model, boundary).skin(0.1)?;
    let grain = stepper.insert_material(Material::new(1.0, 0.3, 1.0)?);
    // kn = 2e5 ⇔ (4/3) E* = kn; LAMMPS NULL kt = 2/7 kn and k_t = 2 G* a ⇔ G* = kt / 2.
    stepper.set_pair_moduli(grain, grain, 1.5e5, 2.0e5 / 7.0)?;
    let mut world = PhysicsWorld {
        gravity: Vector::new(0.0, 0.0, -1.0),
        ..PhysicsWorld::default()
    };
    stepper.configure(&mut world.integration_parameters, 1e-4)?;
    stepper.insert_surface(
        &mut world,
        ColliderBuilder::new(SharedShape::halfspace(Vector::Z)),
        None,
        grain,
    )?;
    for (i, p) in bed.position.iter().enumerate() {
        stepper.insert_sphere(
            SphereBuilder::new(0.5 * bed.diameter[i], grain)
                .translation(Vector::new(p.x, p.y, p.z)),
        )?;
    }
    Ok((stepper, world))
}

/// Pour a [`lattice_bed`] onto the floor and settle it with the reference Hertz system
/// ([`reference_system`]); returns the settled bed (positions only).
pub fn settled_bed(spec: &BedSpec) -> Result<Bed, BedError> {
    let mut bed = lattice_bed(spec)?;
    let (mut stepper, mut world) = reference_system(Hertz, &bed)?;
    for _ in 0..spec.settle_steps {
        stepper.step(&mut world)?;
    }
    stepper.request_rebuild();
    stepper.step(&mut world)?; // wraps the particles into the box
    bed.position.clone_from(&stepper.particles().position);
    bed.hi[2] = bed.position.iter().map(|p| p.z).fold(0.0, f64::max) + 1.0;
    bed.sort_spatially(1.0);
    Ok(bed)
}

/// Normal law of [`bench_bed`]; the tangential law, damping and material are those of
/// [`reference_system`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BenchLaw {
    /// Hertz (`E* = 1.5e5` ⇔ `kn = 2e5`).
    Hertz,
    /// The MDR elasto-plastic law with critical line load `q_c = qc` (force/length, reduced
    /// units) and `Θ = 0.37 E*`.
    Mdr {
        /// Critical line load `q_c`.
        qc: f64,
    },
}

impl BenchLaw {
    /// The law's name in the figures: `"hertz"` or `"mdr"`.
    pub fn name(&self) -> &'static str {
        match self {
            BenchLaw::Hertz => "hertz",
            BenchLaw::Mdr { .. } => "mdr",
        }
    }
}

/// Settings of [`bench_bed`]; the defaults are those of `mdr-dem bench bed`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchSettings {
    /// Normal law.
    pub law: BenchLaw,
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
    /// `skin` finite and positive, the law's parameters as the law crate accepts them. The
    /// error names the setting (`steps`, `threads`, `tile`, `skin`, `q_c`).
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
        if let BenchLaw::Mdr { qc } = self.law {
            MdrElastoPlastic::new(qc, BENCH_THETA_RATIO)?;
        }
        Ok(())
    }
}

/// `Θ / E*` of [`BenchLaw::Mdr`].
const BENCH_THETA_RATIO: f64 = 0.37;

/// Figures of one [`bench_bed`] run. Rates count particle-steps: particles × timed steps.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchFigures {
    /// `"hertz"` or `"mdr"`.
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
    /// Fraction of the touching sphere–sphere pairs that have yielded (`d_max > u_c`; 0 for
    /// Hertz).
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

/// Throughput of the fast force-mode path on `bed` (the program's `mdr-dem bench bed`): the
/// [`reference_system`] with the settings' law and skin on the bed tiled `tile × tile` times,
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
    pool.install(|| match settings.law {
        BenchLaw::Hertz => bench_law(Hertz, bed, settings),
        BenchLaw::Mdr { qc } => bench_law(
            MdrElastoPlastic::new(qc, BENCH_THETA_RATIO).map_err(CouplingError::from)?,
            bed,
            settings,
        ),
    })
}

fn bench_law<N>(normal: N, bed: &Bed, s: &BenchSettings) -> Result<BenchFigures, BedError>
where
    N: NormalModel,
    N::Law: Clone,
{
    let (stepper, world) = reference_system(normal, bed)?;
    let stepper = stepper.skin(s.skin)?.track_orientation(s.orientation);
    if s.work_books {
        bench_steps(stepper, world, s)
    } else {
        bench_steps(stepper.without_work_books(), world, s)
    }
}

/// Warm-up, then the timed steps, then the figures.
fn bench_steps<N, B>(
    mut stepper: FastForceStepper<N, Mindlin, HertzianViscous, NoRolling, B>,
    mut world: PhysicsWorld,
    s: &BenchSettings,
) -> Result<BenchFigures, BedError>
where
    N: NormalModel,
    N::Law: Clone,
    B: WorkBooks,
{
    // The pool's other threads wait for each pass awake (`workers`), as a scene run's do.
    let (rebuilds0, wall_seconds, cpu_seconds) =
        super::workers::with_workers_awake(|| -> Result<_, BedError> {
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
        state_checksum: format!("{:016x}", fnv1a(vectors.flat_map(|v| [v.x, v.y, v.z]))),
    })
}

/// FNV-1a (64 bit) over the bit patterns of `values`.
fn fnv1a(values: impl Iterator<Item = f64>) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for v in values {
        for byte in v.to_bits().to_le_bytes() {
            hash ^= u64::from(byte);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    hash
}

/// Peak resident set size of this process so far (MB), from `VmHWM` in `/proc/self/status`; 0
/// where unavailable (systems without `/proc`).
pub fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

/// CPU time (user + system, all threads) of this process so far (s), from
/// `clock_gettime(CLOCK_PROCESS_CPUTIME_ID)` (nanosecond resolution, up to date for running
/// threads too); `None` where the clock is unavailable (systems other than Unix).
pub fn process_cpu_seconds() -> Option<f64> {
    #[cfg(unix)]
    {
        let mut time = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: clock_gettime writes one `timespec` through the valid pointer it is given and
        // reads nothing else.
        let status = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut time) };
        (status == 0).then_some(time.tv_sec as f64 + time.tv_nsec as f64 * 1e-9)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_bed_figures_on_a_small_lattice() {
        let spec = BedSpec {
            count: 200,
            ..BedSpec::default()
        };
        let bed = lattice_bed(&spec).unwrap();
        let settings = BenchSettings {
            law: BenchLaw::Mdr { qc: 10.0 },
            steps: 50,
            warmup: 10,
            ..BenchSettings::default()
        };
        let f = bench_bed(&bed, &settings).unwrap();
        assert_eq!(
            (f.law, f.particles, f.steps, f.threads),
            ("mdr", 200, 50, 1)
        );
        assert!(f.wall_seconds > 0.0 && f.particle_steps_per_s > 0.0);
        assert!((f.particle_steps_per_s * f.ms_per_step / 1e3 / 200.0 - 1.0).abs() < 1e-9);
        if cfg!(target_os = "linux") {
            assert!(f.cpu_seconds > 0.0 && f.particle_steps_per_cpu_s.is_finite());
            assert!(f.peak_rss_mb > 0.0);
        }
        assert_eq!(f.state_checksum.len(), 16);
        assert_eq!(f.fields().len(), 18);
        // The same trajectories on two threads, and without work books.
        let two = BenchSettings {
            threads: 2,
            work_books: false,
            ..settings
        };
        assert_eq!(
            bench_bed(&bed, &two).unwrap().state_checksum,
            f.state_checksum
        );
        // Tiling multiplies the spheres.
        let tiled = BenchSettings {
            tile: 2,
            steps: 1,
            warmup: 0,
            ..settings
        };
        assert_eq!(bench_bed(&bed, &tiled).unwrap().particles, 800);
    }

    #[test]
    fn sizes_beyond_the_bed_limit_are_refused_before_allocation() {
        let huge = lattice_bed(&BedSpec {
            count: usize::MAX,
            ..BedSpec::default()
        })
        .unwrap_err();
        assert!(
            matches!(huge, BedError::TooManySpheres { name: "count", .. }),
            "{huge}"
        );
        assert!(huge.to_string().contains("100000000"), "{huge}");
        let bed = lattice_bed(&BedSpec {
            count: 200,
            ..BedSpec::default()
        })
        .unwrap();
        // tile² × 200 overflows usize for tile = 2³²; 708² × 200 > 10⁸ ≥ 707² × 200.
        for tile in [usize::MAX, 1 << 32, 708] {
            let settings = BenchSettings {
                tile,
                ..BenchSettings::default()
            };
            let err = bench_bed(&bed, &settings).unwrap_err();
            assert!(
                matches!(err, BedError::TooManySpheres { name: "tile", .. }),
                "{err}"
            );
            assert!(err.to_string().contains("`tile`"), "{err}");
        }
    }

    #[test]
    fn bench_bed_refuses_bad_settings_by_name() {
        let bed = lattice_bed(&BedSpec {
            count: 200,
            ..BedSpec::default()
        })
        .unwrap();
        let base = BenchSettings::default();
        for (name, settings) in [
            ("steps", BenchSettings { steps: 0, ..base }),
            ("threads", BenchSettings { threads: 0, ..base }),
            ("tile", BenchSettings { tile: 0, ..base }),
            ("skin", BenchSettings { skin: -0.1, ..base }),
            (
                "q_c",
                BenchSettings {
                    law: BenchLaw::Mdr { qc: -1.0 },
                    ..base
                },
            ),
        ] {
            let message = bench_bed(&bed, &settings).unwrap_err().to_string();
            assert!(message.contains(name), "{name}: {message}");
        }
        let mut big = bed.clone();
        big.diameter[3] = 2.0;
        let err = bench_bed(&big, &base).unwrap_err();
        assert!(
            matches!(err, BedError::NotReference { sphere: 4, .. }),
            "{err}"
        );
    }

    #[test]
    fn process_clocks_advance() {
        if cfg!(target_os = "linux") {
            let a = process_cpu_seconds().unwrap();
            let mut x = 0.0f64;
            for i in 0..2_000_000 {
                x += (i as f64).sqrt();
            }
            assert!(x > 0.0);
            assert!(process_cpu_seconds().unwrap() > a);
            assert!(peak_rss_mb() > 0.0);
        }
    }
}
