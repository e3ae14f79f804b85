//! The laws of the GPU path ([`GpuLaws`]) and their constants, taken from the CPU path's own
//! reference system so that both paths run the same numbers: the laws are bound by
//! `reference_system` (on a one-sphere copy of the bed) and read back through the law crate's
//! public accessors; where a law keeps a constant private, the constant is computed here by the
//! law's own formula (same order of operations) from the bound pair's `E*` and `R`, and the
//! result is checked against the bound law (equality of the law objects, or its response).

use crate::device::GpuError;
use mdr_contact::damping::DampingLaw;
use mdr_contact::normal::{
    AdhesiveMdr, Hertz, HertzLaw, MdrElastoPlastic, NormalLaw, NormalModel, NormalResponse,
    Thornton, ThorntonLaw, ThorntonUnloading,
};
use mdr_contact::rolling::{EpsdRolling, RollingInput, RollingLaw};
use mdr_contact::tangential::{TangentialInput, TangentialLaw};
use mdr_contact::ContactPair;
use mdr_rapier::neighbour_list::bed::{
    reference_system, Bed, BenchLaw, BenchSettings, BENCH_THETA_RATIO,
};
use mdr_rapier::neighbour_list::boundary::Boundary;
use mdr_rapier::neighbour_list::particles::Species;
use nalgebra::Vector3;

/// The reference system's Coulomb friction coefficient (`μ = 0.5`, LAMMPS `in.bench`); checked
/// against the bound Mindlin law, which has no accessor for it.
const FRICTION: f64 = 0.5;

/// The normal law of a GPU system: the CPU benchmark's ([`BenchLaw`]), so that both paths
/// name and bind the same laws.
pub type GpuNormalLaw = BenchLaw;

/// What the device needs to know of a normal law beyond its constants.
pub(crate) trait DeviceLaw {
    /// The law's code in `bed.wgsl` (`Params::law`).
    fn code(&self) -> u32;
    /// f64 words of the law's per-contact state on the device: the largest overlap (Hertz,
    /// MDR); with Thornton's unloading coefficient and residual overlap; with the adhesive
    /// law's attached radius.
    fn state_words(&self) -> u32;
}

impl DeviceLaw for BenchLaw {
    fn code(&self) -> u32 {
        match self {
            BenchLaw::Hertz => 0,
            BenchLaw::Mdr { .. } => 1,
            BenchLaw::Thornton { .. } => 2,
            BenchLaw::AdhesiveMdr { .. } => 3,
        }
    }

    fn state_words(&self) -> u32 {
        match self {
            BenchLaw::Hertz | BenchLaw::Mdr { .. } => 1,
            BenchLaw::Thornton { .. } => 3,
            BenchLaw::AdhesiveMdr { .. } => 2,
        }
    }
}

/// The contact model of a GPU system: a normal law with the reference system's Mindlin
/// friction and Hertzian viscous damping, and optionally the elastic–plastic spring rolling
/// resistance (`EpsdRolling`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpuLaws {
    /// The normal law.
    pub normal: GpuNormalLaw,
    /// The rolling resistance coefficient `μ_r` of `EpsdRolling`, or none.
    pub rolling: Option<f64>,
}

impl From<BenchLaw> for GpuLaws {
    fn from(law: BenchLaw) -> Self {
        Self {
            normal: law,
            rolling: None,
        }
    }
}

impl GpuLaws {
    /// The contact model the settings name: their law and rolling resistance.
    pub fn of(settings: &BenchSettings) -> Self {
        Self {
            normal: settings.law,
            rolling: settings.rolling,
        }
    }

    /// `settings` with this contact model in place of theirs.
    pub fn in_settings(&self, settings: &BenchSettings) -> BenchSettings {
        BenchSettings {
            law: self.normal,
            rolling: self.rolling,
            ..*settings
        }
    }

    /// Check every parameter as the law crate does (the error names it).
    pub fn validate(&self) -> Result<(), GpuError> {
        self.normal.validate()?;
        if let Some(mu) = self.rolling {
            EpsdRolling::new(mu)?;
        }
        Ok(())
    }
}

/// The constants of one bound law in the order of `Law` in `bed.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct LawConstants {
    effective_modulus: f64,
    sqrt_radius: f64,
    force_coefficient: f64,
    flat_radius_sqrt: f64,
    flat_force_coefficient: f64,
    /// MDR's `u_c`, Thornton's `δ_y`.
    yield_displacement: f64,
    plastic_fraction: f64,
    shear_modulus: f64,
    friction: f64,
    dashpot: f64,
    tangential_ratio: f64,
    /// `2 E* √R` (MDR's tangent stiffness over `√d`).
    stiffness_coefficient: f64,
    effective_radius: f64,
    hardening_ratio: f64,
    yield_pressure: f64,
    yield_force: f64,
    /// `√(2π Δγ / E*)` of the adhesive law.
    detach_coefficient: f64,
    /// The JKR pull-off force of the adhesive law (zero otherwise).
    pull_off: f64,
    /// `μ_r R` of the rolling law.
    rolling_arm: f64,
    /// `2.25 (μ_r R)²`: the rolling stiffness over the normal stiffness.
    rolling_stiffness_ratio: f64,
    /// `η` of the stiffness-viscous dashpot (zero otherwise).
    stiffness_eta: f64,
    /// The pair's reduced mass `m` of the stiffness-viscous dashpot (zero otherwise).
    reduced_mass: f64,
}

impl LawConstants {
    /// `E*` and `R` of the bound pair.
    pub(crate) fn moduli(&self) -> (f64, f64) {
        (self.effective_modulus, self.effective_radius)
    }
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
    /// The largest separation at which an adhesive contact still holds (the CPU stepper's
    /// `neck_reach`, added to the list's cut-off).
    pub neck_reach: f64,
}

/// The MDR constants of `MdrLaw::from_parts` (its formulas, in its order) from the bound
/// law's `E*`, `R`, `u_c` and `θ`.
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
        stiffness_coefficient: 2.0 * e * r.sqrt(),
        effective_radius: r,
        hardening_ratio: theta,
        ..LawConstants::default()
    }
}

/// The constants of an `MdrLaw`.
pub(crate) fn mdr_law_constants(law: &mdr_contact::normal::MdrLaw) -> LawConstants {
    mdr_constants(
        law.effective_modulus(),
        law.effective_radius(),
        law.yield_overlap(),
        law.hardening_ratio(),
    )
}

/// A pair with `E*` and `R` (the shear modulus and mass, which the normal laws do not read,
/// set to 1) to bind a law again and compare it with the stepper's.
fn pair_of(e: f64, r: f64) -> Result<ContactPair, GpuError> {
    Ok(ContactPair::new(e, 1.0, r, 1.0)?)
}

fn mismatch(what: &str) -> GpuError {
    GpuError::Unsupported(format!(
        "the {what} bound by the CPU path differs from the one the GPU path computes"
    ))
}

/// Hertz's constants (`HertzLaw::new`'s formulas) for `E*`, `R`, checked against `law`.
pub(crate) fn hertz_constants(law: &HertzLaw, e: f64, r: f64) -> Result<LawConstants, GpuError> {
    if HertzLaw::new(&pair_of(e, r)?) != *law {
        return Err(mismatch("Hertz law"));
    }
    let mut c = mdr_constants(e, r, f64::INFINITY, 1.0);
    c.force_coefficient = 4.0 / 3.0 * e * r.sqrt();
    if law.force(1.0) != c.force_coefficient {
        return Err(mismatch("Hertz force coefficient"));
    }
    Ok(c)
}

/// Thornton's constants (`ThorntonLaw::new`'s formulas, in its order) for `E*`, `R`, `p_y`,
/// checked against `law` (the 1997 unloading branch only).
pub(crate) fn thornton_constants(
    law: &ThorntonLaw,
    e: f64,
    r: f64,
    yield_pressure: f64,
) -> Result<LawConstants, GpuError> {
    if law.unloading() != ThorntonUnloading::Thornton1997 {
        return Err(GpuError::Unsupported(
            "Thornton's law with the LIGGGHTS thornton_ning unloading branch".to_owned(),
        ));
    }
    if ThorntonLaw::new(&pair_of(e, r)?, yield_pressure) != *law {
        return Err(mismatch("Thornton law"));
    }
    let force_coefficient = 4.0 / 3.0 * e * r.sqrt();
    let yield_overlap = r * (std::f64::consts::PI * yield_pressure / (2.0 * e)).powi(2);
    let yield_force = force_coefficient * (yield_overlap * yield_overlap.sqrt());
    let mut state = Default::default();
    if law.yield_overlap() != yield_overlap
        || law.update(&mut state, yield_overlap).force != yield_force
    {
        return Err(mismatch("Thornton yield point"));
    }
    Ok(LawConstants {
        effective_modulus: e,
        sqrt_radius: r.sqrt(),
        force_coefficient,
        yield_displacement: yield_overlap,
        effective_radius: r,
        yield_pressure,
        yield_force,
        ..LawConstants::default()
    })
}

/// The adhesive MDR law's constants: its MDR law's, `√(2π Δγ / E*)` and the pull-off force
/// (`AdhesiveMdrLaw::new`'s formulas), checked against the bound law.
pub(crate) fn adhesive_constants(
    law: &mdr_contact::normal::AdhesiveMdrLaw,
) -> Result<LawConstants, GpuError> {
    let mut c = mdr_law_constants(law.mdr());
    let w = law.work_of_adhesion();
    c.detach_coefficient = (2.0 * std::f64::consts::PI * w / c.effective_modulus).sqrt();
    c.pull_off = 1.5 * std::f64::consts::PI * w * c.effective_radius;
    if law.pull_off_force() != c.pull_off || law.critical_elongation(1.0) != c.detach_coefficient {
        return Err(mismatch("adhesive MDR law"));
    }
    Ok(c)
}

/// The tangential and damping constants of a bound law with Coulomb coefficient `friction`,
/// checked against its own responses.
fn add_tangential<T: TangentialLaw, D: DampingLaw>(
    mut c: LawConstants,
    tangential: &T,
    shear_modulus: f64,
    damping: &D,
    friction: f64,
) -> Result<LawConstants, GpuError> {
    c.shear_modulus = shear_modulus;
    c.friction = friction;
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
    if (slip.force.norm() - friction).abs() > 1e-12 {
        return Err(GpuError::Unsupported(format!(
            "the bound law's friction coefficient is {}, the GPU path's {friction}",
            slip.force.norm()
        )));
    }
    Ok(c)
}

/// The rolling constants (`EpsdRolling::bind`'s formulas: `μ_r R`, `2.25 (μ_r R)²`) for the
/// pair radius `r`, checked against the bound law's responses: its stiffness on a unit
/// rotation under a unit normal stiffness, and its cap under a small normal force.
fn add_rolling<R: RollingLaw>(
    mut c: LawConstants,
    coefficient: f64,
    r: f64,
    law: &R,
) -> Result<LawConstants, GpuError> {
    let arm = coefficient * r;
    c.rolling_arm = arm;
    c.rolling_stiffness_ratio = 2.25 * arm * arm;
    let probe = |normal_force: f64| {
        let mut state = R::State::default();
        law.update(
            &mut state,
            &RollingInput {
                normal: Vector3::z(),
                rotation_increment: Vector3::new(1.0, 0.0, 0.0),
                normal_force,
                normal_stiffness: 1.0,
            },
        )
        .torque
        .x
    };
    let sr = c.rolling_stiffness_ratio;
    if probe(f64::MAX) != -sr
        || (sr > 0.0 && probe(1e-3 * sr / arm) != -sr * (arm * (1e-3 * sr / arm) / sr))
    {
        return Err(mismatch("rolling resistance law"));
    }
    Ok(c)
}

/// The stiffness-viscous dashpot's constants, `η` and the pair's reduced mass `m`
/// (`StiffnessViscous::bind`, which keeps them private), checked against the bound law's
/// coefficient `η √(m k_n)` (`StiffnessViscousLaw::normal_coefficient`, the product under one
/// square root, as the device takes it) at normal stiffnesses over twelve decades, bit for bit.
pub(crate) fn add_stiffness_damping<D: DampingLaw>(
    mut c: LawConstants,
    damping: &D,
    eta: f64,
    mass: f64,
) -> Result<LawConstants, GpuError> {
    c.stiffness_eta = eta;
    c.reduced_mass = mass;
    for stiffness in [1e-3, 1.0, 37.5, 2.9e4, 6.1e6, 8.3e9] {
        let response = NormalResponse {
            stiffness,
            ..NormalResponse::default()
        };
        if damping.normal_coefficient(&response, 1.0) != eta * (mass * stiffness).sqrt() {
            return Err(mismatch("stiffness-viscous damping law"));
        }
    }
    Ok(c)
}

/// What a law needs of the bound pair: its `E*` and `R` (read from an MDR law bound for the
/// same pair, which keeps both).
#[derive(Clone, Copy)]
struct PairModuli {
    sphere: (f64, f64),
    floor: (f64, f64),
}

fn pair_moduli(one: &Bed, settings: &BenchSettings) -> Result<PairModuli, GpuError> {
    let (stepper, world) = reference_system(MdrElastoPlastic::elastic(), one)?;
    let mut stepper = stepper.skin(settings.skin)?;
    stepper.compute_forces(&world, false)?;
    let of = |law: &mdr_contact::normal::MdrLaw| (law.effective_modulus(), law.effective_radius());
    Ok(PairModuli {
        sphere: of(&stepper.sphere_pair_laws(0, 0).0.normal),
        floor: of(&stepper.surface_pair_laws(0, 0).0.normal),
    })
}

/// Bind `normal` (with the reference system's Mindlin and damping, and `rolling`) on `one`
/// and read the constants, the normal ones by `constants(law, E*, R)`.
fn bind<N, F>(
    normal: N,
    one: &Bed,
    settings: &BenchSettings,
    rolling: Option<f64>,
    constants: F,
) -> Result<BoundLaws, GpuError>
where
    N: NormalModel,
    N::Law: Clone,
    F: Fn(&N::Law, f64, f64) -> Result<LawConstants, GpuError>,
{
    let moduli = pair_moduli(one, settings)?;
    let (stepper, world) = reference_system(normal, one)?;
    let mu_r = rolling.unwrap_or(0.0);
    let mut stepper = stepper
        .skin(settings.skin)?
        .with_rolling(EpsdRolling::new(mu_r)?);
    stepper.compute_forces(&world, false)?;
    let species = stepper.particles().species_table[0];
    type Bound<L> = (
        mdr_contact::model::ContactLaw<
            L,
            mdr_contact::tangential::MindlinLaw,
            mdr_contact::damping::HertzianViscousLaw,
        >,
        mdr_contact::rolling::EpsdRollingLaw,
    );
    let one_side = |bound: &Bound<N::Law>, moduli: (f64, f64)| {
        bound_constants(bound, moduli, FRICTION, mu_r, &constants)
    };
    let sphere_laws = stepper.sphere_pair_laws(0, 0);
    Ok(BoundLaws {
        boundary: *stepper.boundary(),
        species,
        sphere: one_side(sphere_laws, moduli.sphere)?,
        floor: one_side(stepper.surface_pair_laws(0, 0), moduli.floor)?,
        dt: world.integration_parameters.dt,
        gravity_z: world.gravity.z,
        yield_overlap: sphere_laws.0.normal.yield_overlap(),
        neck_reach: stepper.neck_reach(),
    })
}

/// The constants of one bound pair (`E*`, `R` in `moduli`) with Mindlin friction `friction` and
/// rolling coefficient `mu_r` (0: off), the normal ones by `constants(law, E*, R)`.
pub(crate) fn bound_constants<L, D, R, F>(
    (law, roll): &(
        mdr_contact::model::ContactLaw<L, mdr_contact::tangential::MindlinLaw, D>,
        R,
    ),
    (e, r): (f64, f64),
    friction: f64,
    mu_r: f64,
    constants: &F,
) -> Result<LawConstants, GpuError>
where
    L: NormalLaw,
    D: DampingLaw,
    R: RollingLaw,
    F: Fn(&L, f64, f64) -> Result<LawConstants, GpuError>,
{
    // Mindlin's stiffness `2 G* a` at `a = 1/2` is `G*` exactly.
    let c = add_tangential(
        constants(&law.normal, e, r)?,
        &law.tangential,
        law.tangential.stiffness(0.5),
        &law.damping,
        friction,
    )?;
    let r = c.effective_radius;
    add_rolling(c, mu_r, r, roll)
}

impl BoundLaws {
    /// The laws of `reference_system` with `laws`, bound for `bed`'s species against another
    /// sphere and against the floor.
    pub fn of_reference_system(
        bed: &Bed,
        settings: &BenchSettings,
        laws: &GpuLaws,
    ) -> Result<Self, GpuError> {
        laws.validate()?;
        let one = Bed {
            lo: bed.lo,
            hi: bed.hi,
            diameter: vec![bed.diameter[0]],
            density: vec![bed.density[0]],
            position: vec![bed.position[0]],
        };
        match laws.normal {
            GpuNormalLaw::Hertz => bind(Hertz, &one, settings, laws.rolling, hertz_constants),
            GpuNormalLaw::Mdr { qc } => bind(
                MdrElastoPlastic::new(qc, BENCH_THETA_RATIO)?,
                &one,
                settings,
                laws.rolling,
                |law, _, _| Ok(mdr_law_constants(law)),
            ),
            GpuNormalLaw::Thornton { yield_pressure } => bind(
                Thornton::new(yield_pressure)?,
                &one,
                settings,
                laws.rolling,
                |law, e, r| thornton_constants(law, e, r, yield_pressure),
            ),
            GpuNormalLaw::AdhesiveMdr {
                qc,
                work_of_adhesion,
            } => bind(
                AdhesiveMdr::new(
                    MdrElastoPlastic::new(qc, BENCH_THETA_RATIO)?,
                    work_of_adhesion,
                )?,
                &one,
                settings,
                laws.rolling,
                |law, _, _| adhesive_constants(law),
            ),
        }
    }
}
