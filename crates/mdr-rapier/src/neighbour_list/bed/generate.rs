//! Bed generation: spheres on a jittered lattice, poured and settled with the reference system
//! of `benches/lammps`.

use super::{bounded_spheres, Bed, BedError};
use crate::error::{positive, CouplingError, Result};
use crate::neighbour_list::boundary::Boundary;
use crate::neighbour_list::stepper::NeighbourListStepper;
use crate::particles::SphereBuilder;
use mdr_contact::damping::HertzianViscous;
use mdr_contact::model::ContactModel;
use mdr_contact::normal::{Hertz, NormalModel};
use mdr_contact::tangential::Mindlin;
use mdr_contact::Material;
use nalgebra::Vector3;
use rapier3d_f64::prelude::*;

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
) -> Result<(
    NeighbourListStepper<N, Mindlin, HertzianViscous>,
    PhysicsWorld,
)>
where
    N: NormalModel,
    N::Law: Clone,
{
    let boundary = Boundary::periodic_xy((bed.lo[0], bed.hi[0]), (bed.lo[1], bed.hi[1]))?;
    let model = ContactModel::new(normal)
        .with_tangential(Mindlin::new(0.5)?)
        .with_damping(HertzianViscous::new(50.0)?.with_tangential_ratio(0.5)?);
    let mut stepper = NeighbourListStepper::new(model, boundary).skin(0.1)?;
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
