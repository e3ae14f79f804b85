//! Granular beds for benchmarks: reading and writing LAMMPS data files (`atom_style sphere`),
//! tiling a periodic bed, and generating a bed by lattice + settling.

use super::boundary::Boundary;
use super::stepper::FastForceStepper;
use crate::error::{positive, CouplingError, Result};
use crate::particles::SphereBuilder;
use mdr_contact::damping::HertzianViscous;
use mdr_contact::model::ContactModel;
use mdr_contact::normal::{Hertz, NormalModel};
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
    /// A parameter is out of range.
    #[error(transparent)]
    Coupling(#[from] CouplingError),
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
    pub fn tiled(&self, nx: usize, ny: usize) -> Bed {
        let lx = self.hi[0] - self.lo[0];
        let ly = self.hi[1] - self.lo[1];
        let mut out = Bed {
            lo: self.lo,
            hi: [
                self.lo[0] + lx * nx as f64,
                self.lo[1] + ly * ny as f64,
                self.hi[2],
            ],
            diameter: Vec::with_capacity(self.len() * nx * ny),
            density: Vec::with_capacity(self.len() * nx * ny),
            position: Vec::with_capacity(self.len() * nx * ny),
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
        out
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
