//! The ring particles: state arrays, the power-law size distribution and REBOUND's initial
//! conditions.

use crate::boundary::ShearingBox;
use crate::error::{in_range, positive, Result, RingError};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rapier3d_f64::math::Vector;

/// Particle state, one entry per particle (structure of arrays).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Particles {
    /// Positions in the rotating frame (m).
    pub position: Vec<Vector>,
    /// Velocities in the rotating frame, shear flow included (m/s).
    pub velocity: Vec<Vector>,
    /// Radii (m).
    pub radius: Vec<f64>,
    /// Masses (kg).
    pub mass: Vec<f64>,
}

impl Particles {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.radius.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.radius.is_empty()
    }

    /// Add one particle.
    pub fn push(&mut self, position: Vector, velocity: Vector, radius: f64, mass: f64) {
        self.position.push(position);
        self.velocity.push(velocity);
        self.radius.push(radius);
        self.mass.push(mass);
    }

    /// Total mass (kg).
    pub fn total_mass(&self) -> f64 {
        self.mass.iter().sum()
    }

    /// Mean radius (m).
    pub fn mean_radius(&self) -> f64 {
        self.radius.iter().sum::<f64>() / self.len().max(1) as f64
    }

    /// Largest radius (m).
    pub fn max_radius(&self) -> f64 {
        self.radius.iter().copied().fold(0.0, f64::max)
    }
}

/// Power-law distribution of radii, `dN/dr ∝ r^slope` on `[r_min, r_max]` (slope ≠ −1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SizeDistribution {
    r_min: f64,
    r_max: f64,
    slope: f64,
}

impl SizeDistribution {
    /// Radii in `[r_min, r_max]` (m, 0 < r_min ≤ r_max) with `dN/dr ∝ r^slope` (slope ≠ −1).
    pub fn new(r_min: f64, r_max: f64, slope: f64) -> Result<Self> {
        positive("r_min", r_min)?;
        in_range("r_max", r_max, r_min, f64::MAX, "[r_min, inf)")?;
        if !slope.is_finite() || (slope + 1.0).abs() < 1e-12 {
            return Err(RingError::OutOfRange {
                name: "slope",
                value: slope,
                range: "finite, != -1",
            });
        }
        Ok(Self {
            r_min,
            r_max,
            slope,
        })
    }

    /// REBOUND's shearing-sheet distribution: 1–4 m, slope −3.
    pub fn rebound_default() -> Self {
        Self {
            r_min: 1.0,
            r_max: 4.0,
            slope: -3.0,
        }
    }

    /// Smallest radius (m).
    pub fn r_min(&self) -> f64 {
        self.r_min
    }

    /// Largest radius (m).
    pub fn r_max(&self) -> f64 {
        self.r_max
    }

    /// The radius at cumulative probability `u ∈ [0, 1)` (inverse transform, as REBOUND's
    /// `reb_random_powerlaw`).
    pub fn quantile(&self, u: f64) -> f64 {
        let k = self.slope + 1.0;
        let (lo, hi) = (self.r_min.powf(k), self.r_max.powf(k));
        ((hi - lo) * u + lo).powf(1.0 / k)
    }

    /// Mean of `r^p` over the distribution (for the expected particle number and mass).
    pub fn moment(&self, p: f64) -> f64 {
        let integral = |q: f64| {
            if (q + 1.0).abs() < 1e-12 {
                (self.r_max / self.r_min).ln()
            } else {
                (self.r_max.powf(q + 1.0) - self.r_min.powf(q + 1.0)) / (q + 1.0)
            }
        };
        integral(self.slope + p) / integral(self.slope)
    }
}

/// The most particles a ring may hold (10⁷, a hundred times REBOUND's shearing-sheet examples):
/// `particles` and the number a `surface_density` asks for are checked against it before
/// anything is allocated.
pub const MAX_PARTICLES: usize = 10_000_000;

/// The error for a population beyond [`MAX_PARTICLES`] (or a zero count), naming the parameter.
fn too_many(name: &'static str, value: f64) -> RingError {
    RingError::OutOfRange {
        name,
        value,
        range: if name == "particles" {
            "[1, 10000000] (MAX_PARTICLES)"
        } else {
            "(0, inf) with Σ L_x L_y / mean particle mass ≤ 10000000 particles (MAX_PARTICLES)"
        },
    }
}

/// How many particles to draw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Population {
    /// Draw particles until their total mass reaches `Σ L_x L_y` (REBOUND's rule), Σ in kg/m².
    SurfaceDensity(f64),
    /// Exactly this many particles.
    Count(usize),
}

/// REBOUND's initial conditions, with one change: a particle that would overlap an earlier one is
/// redrawn (REBOUND lets them overlap; in rapier deep initial overlaps would be stuck contacts).
/// Radii from `sizes`, density `density`; x, y uniform in the box; z normal with standard
/// deviation 1 m; velocity the shear flow `ẏ = −(3/2) Ω x`.
pub fn initial_conditions(
    domain: &ShearingBox,
    sizes: &SizeDistribution,
    density: f64,
    population: Population,
    seed: u64,
) -> Result<Particles> {
    positive("density", density)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let target_mass = match population {
        Population::SurfaceDensity(sigma) => {
            let target = positive("surface_density", sigma)? * domain.area();
            // Expected number drawn: Σ L_x L_y over the mean particle mass.
            let mean_mass = density * 4.0 / 3.0 * std::f64::consts::PI * sizes.moment(3.0);
            if target / mean_mass > MAX_PARTICLES as f64 {
                return Err(too_many("surface_density", sigma));
            }
            target
        }
        Population::Count(n) => {
            if n == 0 || n > MAX_PARTICLES {
                return Err(too_many("particles", n as f64));
            }
            f64::INFINITY
        }
    };
    let count = match population {
        Population::Count(n) => n,
        Population::SurfaceDensity(_) => usize::MAX,
    };
    let mut particles = Particles::default();
    let mut grid = OverlapGrid::new(domain, 2.0 * sizes.r_max());
    let mut total = 0.0;
    const ATTEMPTS: usize = 10_000;
    while total < target_mass && particles.len() < count {
        if particles.len() == MAX_PARTICLES {
            return Err(too_many("surface_density", target_mass / domain.area()));
        }
        let radius = sizes.quantile(rng.random::<f64>());
        let mass = density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
        let mut placed = false;
        for _ in 0..ATTEMPTS {
            let position = Vector::new(
                (rng.random::<f64>() - 0.5) * domain.lx(),
                (rng.random::<f64>() - 0.5) * domain.ly(),
                standard_normal(&mut rng),
            );
            if grid.overlaps(&particles, position, radius) {
                continue;
            }
            let velocity = Vector::new(0.0, domain.frame().shear_velocity(position.x), 0.0);
            grid.insert(particles.len(), position);
            particles.push(position, velocity, radius, mass);
            placed = true;
            break;
        }
        if !placed {
            return Err(RingError::Placement {
                index: particles.len(),
                attempts: ATTEMPTS,
            });
        }
        total += mass;
    }
    Ok(particles)
}

/// A standard normal variate (Box–Muller).
fn standard_normal(rng: &mut impl Rng) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>();
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// A periodic 2D cell grid (x, y) for the overlap test of the initial placement.
struct OverlapGrid {
    lx: f64,
    ly: f64,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<usize>>,
}

impl OverlapGrid {
    fn new(domain: &ShearingBox, cell: f64) -> Self {
        // At most 1024 × 1024 cells however large the box: fewer, larger cells stay correct
        // (a cell is never smaller than `cell`), and the grid's size stays bounded.
        const MAX_CELLS_PER_SIDE: f64 = 1024.0;
        let nx = (domain.lx() / cell).floor().clamp(1.0, MAX_CELLS_PER_SIDE) as usize;
        let ny = (domain.ly() / cell).floor().clamp(1.0, MAX_CELLS_PER_SIDE) as usize;
        Self {
            lx: domain.lx(),
            ly: domain.ly(),
            nx,
            ny,
            cells: vec![Vec::new(); nx * ny],
        }
    }

    fn cell_of(&self, p: Vector) -> (usize, usize) {
        let cx = (((p.x / self.lx + 0.5) * self.nx as f64).floor() as isize)
            .clamp(0, self.nx as isize - 1);
        let cy = (((p.y / self.ly + 0.5) * self.ny as f64).floor() as isize)
            .clamp(0, self.ny as isize - 1);
        (cx as usize, cy as usize)
    }

    fn insert(&mut self, index: usize, p: Vector) {
        let (cx, cy) = self.cell_of(p);
        self.cells[cy * self.nx + cx].push(index);
    }

    /// Whether a sphere at `p` of radius `r` overlaps a placed one. Plain periodic images suffice
    /// here: at `t = 0` the shear offset is zero.
    fn overlaps(&self, particles: &Particles, p: Vector, r: f64) -> bool {
        let (cx, cy) = self.cell_of(p);
        for dy in -1isize..=1 {
            for dx in -1isize..=1 {
                let x = (cx as isize + dx).rem_euclid(self.nx as isize) as usize;
                let y = (cy as isize + dy).rem_euclid(self.ny as isize) as usize;
                for &j in &self.cells[y * self.nx + x] {
                    let mut d = particles.position[j] - p;
                    d.x -= self.lx * (d.x / self.lx).round();
                    d.y -= self.ly * (d.y / self.ly).round();
                    let reach = particles.radius[j] + r;
                    if d.length_squared() < reach * reach {
                        return true;
                    }
                }
            }
        }
        false
    }
}
