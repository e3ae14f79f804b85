//! The constants of the bound laws, taken from the CPU path's own reference system so that
//! both paths run the same numbers: the laws are bound by `reference_system` (on a one-sphere
//! copy of the bed) and read back through the law crate's public accessors.

use crate::device::GpuError;
use mdr_contact::damping::DampingLaw;
use mdr_contact::normal::{Hertz, MdrElastoPlastic, NormalLaw, NormalResponse};
use mdr_contact::tangential::{TangentialInput, TangentialLaw};
use mdr_rapier::neighbour_list::bed::{reference_system, Bed, BenchLaw, BenchSettings};
use mdr_rapier::neighbour_list::boundary::Boundary;
use mdr_rapier::neighbour_list::particles::Species;
use nalgebra::Vector3;

/// `Θ / E*` of [`BenchLaw::Mdr`] (as `mdr-dem bench bed` documents it: `Θ = 0.37 E*`).
pub const BENCH_THETA_RATIO: f64 = 0.37;
/// The reference system's Coulomb friction coefficient (`μ = 0.5`, LAMMPS `in.bench`); checked
/// against the bound Mindlin law, which has no accessor for it.
const FRICTION: f64 = 0.5;

/// The constants of one bound law in the order of `Law` in `bed.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct LawConstants {
    effective_modulus: f64,
    sqrt_radius: f64,
    force_coefficient: f64,
    flat_radius_sqrt: f64,
    flat_force_coefficient: f64,
    yield_displacement: f64,
    plastic_fraction: f64,
    shear_modulus: f64,
    friction: f64,
    dashpot: f64,
    tangential_ratio: f64,
    pad: f64,
}

/// What the GPU system takes from the CPU reference system.
pub(crate) struct BoundLaws {
    pub boundary: Boundary,
    pub species: Species,
    pub sphere: LawConstants,
    pub floor: LawConstants,
    pub dt: f64,
    pub gravity_z: f64,
    pub yield_overlap: f64,
}

/// The normal-law constants of `MdrLaw::from_parts` (its formulas, in its order) from the
/// bound law's `E*`, `R`, `u_c` and `θ`.
fn mdr_constants(e: f64, r: f64, yield_displacement: f64, theta: f64) -> LawConstants {
    let flat_factor = if theta > 0.0 {
        1.0 / theta.sqrt()
    } else {
        f64::INFINITY
    };
    LawConstants {
        effective_modulus: e,
        sqrt_radius: r.sqrt(),
        force_coefficient: 4.0 / 3.0 * e * r.sqrt(),
        flat_radius_sqrt: r.sqrt() * flat_factor,
        flat_force_coefficient: 4.0 / 3.0 * e * r.sqrt() * flat_factor,
        yield_displacement,
        plastic_fraction: 1.0 - theta,
        shear_modulus: 0.0,
        friction: 0.0,
        dashpot: 0.0,
        tangential_ratio: 0.0,
        pad: 0.0,
    }
}

/// The tangential and damping constants of a bound law, checked against its own responses.
fn add_tangential<T: TangentialLaw, D: DampingLaw>(
    mut c: LawConstants,
    tangential: &T,
    shear_modulus: f64,
    damping: &D,
) -> Result<LawConstants, GpuError> {
    c.shear_modulus = shear_modulus;
    c.friction = FRICTION;
    // √1 = 1: the coefficient itself.
    c.dashpot = damping.normal_coefficient(&NormalResponse::default(), 1.0);
    c.tangential_ratio = damping.tangential_ratio();
    // A gross slip under a unit normal force gives a force of μ.
    let mut state = T::State::default();
    let slip = tangential.update(
        &mut state,
        &TangentialInput {
            normal: Vector3::z(),
            displacement_increment: Vector3::new(1.0, 0.0, 0.0),
            normal_response: NormalResponse {
                force: 1.0,
                contact_radius: 1.0,
                stiffness: 0.0,
            },
        },
    );
    if (slip.force.norm() - FRICTION).abs() > 1e-12 {
        return Err(GpuError::Unsupported(format!(
            "the reference system's friction coefficient is {}, the GPU path's {FRICTION}",
            slip.force.norm()
        )));
    }
    Ok(c)
}

impl BoundLaws {
    /// The laws of `reference_system` with `settings`' normal law, bound for `bed`'s species
    /// against another sphere and against the floor.
    pub fn of_reference_system(bed: &Bed, settings: &BenchSettings) -> Result<Self, GpuError> {
        let one = Bed {
            lo: bed.lo,
            hi: bed.hi,
            diameter: vec![bed.diameter[0]],
            density: vec![bed.density[0]],
            position: vec![bed.position[0]],
        };
        // Mindlin's stiffness `2 G* a` at `a = 1/2` is `G*` exactly.
        match settings.law {
            BenchLaw::Hertz => {
                let (stepper, world) = reference_system(Hertz, &one)?;
                let mut stepper = stepper.skin(settings.skin)?;
                stepper.compute_forces(&world, false)?;
                let species = stepper.particles().species_table[0];
                let r = species.radius;
                let hertz = |law: &mdr_contact::normal::HertzLaw, radius: f64| {
                    // F(1) = c · 1 · √1: the force coefficient itself.
                    let mut c = mdr_constants(0.0, radius, 0.0, 1.0);
                    c.force_coefficient = law.force(1.0);
                    c
                };
                let (sphere, _) = stepper.sphere_pair_laws(0, 0);
                let (floor, _) = stepper.surface_pair_laws(0, 0);
                Ok(Self {
                    boundary: *stepper.boundary(),
                    species,
                    sphere: add_tangential(
                        hertz(&sphere.normal, r * r / (r + r)),
                        &sphere.tangential,
                        sphere.tangential.stiffness(0.5),
                        &sphere.damping,
                    )?,
                    floor: add_tangential(
                        hertz(&floor.normal, r),
                        &floor.tangential,
                        floor.tangential.stiffness(0.5),
                        &floor.damping,
                    )?,
                    dt: world.integration_parameters.dt,
                    gravity_z: world.gravity.z,
                    yield_overlap: f64::INFINITY,
                })
            }
            BenchLaw::Mdr { qc } => {
                let model = MdrElastoPlastic::new(qc, BENCH_THETA_RATIO)
                    .map_err(mdr_rapier::error::CouplingError::from)?;
                let (stepper, world) = reference_system(model, &one)?;
                let mut stepper = stepper.skin(settings.skin)?;
                stepper.compute_forces(&world, false)?;
                let species = stepper.particles().species_table[0];
                let mdr = |law: &mdr_contact::normal::MdrLaw| {
                    mdr_constants(
                        law.effective_modulus(),
                        law.effective_radius(),
                        law.yield_overlap(),
                        law.hardening_ratio(),
                    )
                };
                let (sphere, _) = stepper.sphere_pair_laws(0, 0);
                let (floor, _) = stepper.surface_pair_laws(0, 0);
                Ok(Self {
                    boundary: *stepper.boundary(),
                    species,
                    sphere: add_tangential(
                        mdr(&sphere.normal),
                        &sphere.tangential,
                        sphere.tangential.stiffness(0.5),
                        &sphere.damping,
                    )?,
                    floor: add_tangential(
                        mdr(&floor.normal),
                        &floor.tangential,
                        floor.tangential.stiffness(0.5),
                        &floor.damping,
                    )?,
                    dt: world.integration_parameters.dt,
                    gravity_z: world.gravity.z,
                    yield_overlap: sphere.normal.yield_overlap(),
                })
            }
        }
    }
}
