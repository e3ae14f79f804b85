//! Granular beds for benchmarks, one job per module: the LAMMPS data-file format
//! ([`lammps_data`], `atom_style sphere`), bed generation by lattice + settling ([`generate`]),
//! the bed benchmark itself ([`harness`]: [`bench_bed`], what `mdr-dem bench bed` and Python's
//! `mdr_dem.bench_bed` run) and the process clocks it reads ([`clock`]). Tiling a periodic bed
//! and its spatial order are here.

pub mod clock;
pub mod generate;
pub mod harness;
pub mod lammps_data;

pub use clock::{peak_rss_mb, process_cpu_seconds};
pub use generate::{lattice_bed, reference_system, settled_bed, BedSpec};
pub use harness::{
    bench_bed, reference_data, run_reference_system, state_checksum, BenchFigures, BenchLaw,
    BenchSettings, BenchValue, ReferenceRun, RollingTorque, BENCH_THETA_RATIO, REFERENCE_DATA,
};

use crate::error::CouplingError;
use nalgebra::Vector3;

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
    /// The reference bed was not found ([`reference_data`]).
    #[error(
        "the reference bed `{}` was not found (looked at {})",
        harness::REFERENCE_DATA,
        tried.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
    )]
    NoReferenceData {
        /// Every path looked at, in the order of the search.
        tried: Vec<std::path::PathBuf>,
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

    /// The reference system with every sphere thrown at `speed` in a direction of its own,
    /// stepped `steps` times: the state checksum of [`BenchFigures::state_checksum`].
    struct Thrown {
        speed: f64,
        steps: usize,
    }

    impl ReferenceRun for Thrown {
        type Output = Result<String, BedError>;

        fn run<N, R>(
            self,
            mut stepper: crate::neighbour_list::NeighbourListStepper<
                N,
                mdr_contact::tangential::Mindlin,
                mdr_contact::damping::HertzianViscous,
                R,
            >,
            mut world: rapier3d_f64::prelude::PhysicsWorld,
        ) -> Self::Output
        where
            N: mdr_contact::normal::NormalModel,
            N::Law: Clone,
            R: mdr_contact::rolling::RollingModel,
            R::Law: Clone,
            <R::Law as mdr_contact::rolling::RollingLaw>::State: RollingTorque,
        {
            for (i, v) in stepper.particles_mut().linvel.iter_mut().enumerate() {
                let a = i as f64;
                *v = self.speed * Vector3::new((1.3 * a).sin(), (2.1 * a).cos(), (0.7 * a).sin());
            }
            for _ in 0..self.steps {
                stepper.step(&mut world)?;
            }
            let p = stepper.particles();
            Ok(state_checksum(
                p.position.iter().chain(&p.linvel).chain(&p.angvel),
            ))
        }
    }

    /// On a bed whose spheres collide and part (thrown at one unit of speed across the lattice's
    /// gaps of a tenth of a diameter, 1500 steps: every sphere meets its neighbours and
    /// rebounds), the adhesive law's contacts unload past touching into tension, so the work
    /// of adhesion reaches the trajectories: `Δγ = 0.5` and `2` give different checksums, and
    /// so does `Δγ = 0.5` against the MDR law; `Δγ = 0` gives the MDR law's checksum exactly.
    #[test]
    fn work_of_adhesion_reaches_the_trajectories_of_a_thrown_bed() {
        let bed = lattice_bed(&BedSpec {
            count: 200,
            ..BedSpec::default()
        })
        .unwrap();
        let checksum = |law| {
            let settings = BenchSettings {
                law,
                ..BenchSettings::default()
            };
            run_reference_system(
                &bed,
                &settings,
                Thrown {
                    speed: 1.0,
                    steps: 1500,
                },
            )
            .unwrap()
            .unwrap()
        };
        let adhesive = |work_of_adhesion| {
            checksum(BenchLaw::AdhesiveMdr {
                qc: 10.0,
                work_of_adhesion,
            })
        };
        let mdr = checksum(BenchLaw::Mdr { qc: 10.0 });
        let (weak, strong) = (adhesive(0.5), adhesive(2.0));
        assert_ne!(weak, strong, "Δγ = 0.5 and 2 ran the same trajectories");
        assert_ne!(weak, mdr, "Δγ = 0.5 ran the MDR law's trajectories");
        assert_eq!(adhesive(0.0), mdr, "Δγ = 0 is the MDR law");
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
            (
                "yield_stress",
                BenchSettings {
                    law: BenchLaw::Thornton {
                        yield_pressure: f64::NAN,
                    },
                    ..base
                },
            ),
            (
                "work_of_adhesion",
                BenchSettings {
                    law: BenchLaw::AdhesiveMdr {
                        qc: 10.0,
                        work_of_adhesion: -1.0,
                    },
                    ..base
                },
            ),
            (
                "mu_r",
                BenchSettings {
                    rolling: Some(-1.0),
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
