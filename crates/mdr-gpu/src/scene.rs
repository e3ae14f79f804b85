//! Scenes on the GPU ([`GpuScene`]): force-mode scenes whose walls the device has (planes,
//! boxes, and cylinders, cones and orifice plates as exact surfaces of revolution; fixed,
//! turning about their own axis, or removed at a time: `crate::walls`), with the laws the CPU
//! neighbour-list path binds for them, species pair by species pair, and with or without a
//! sink (`[run] delete_below_m`: the CPU run's parking, `crate::sink`).
//!
//! The kernel's laws are chosen by the scene's declared laws' registered names
//! ([`DeviceSubModels`]): the normal law by [`DEVICE_LAWS`], the tangential, damping and rolling
//! laws by [`DEVICE_TANGENTIAL`], [`DEVICE_DAMPING`] and [`DEVICE_ROLLING`], each with its
//! values read by its declared keys.
//!
//! A scene the device does not have every part of is refused ([`gpu_scene_support`]) with the
//! part named: a mesh wall, a cylinder, cone or orifice plate of flat pieces, a turning box or a
//! surface turning about another axis than its own, restitution mode, the rapier
//! pipeline path, Thornton's LIGGGHTS unloading branch, or a normal, tangential, damping or
//! rolling law without a device kernel (by its registered name, with the names the device has).

use crate::accessors::system_accessors;
use crate::checkpoint::DeviceHistory;
use crate::device::{GpuContext, GpuError};
use crate::law::{
    add_stiffness_damping, adhesive_constants, bound_constants, hertz_constants, mdr_law_constants,
    thornton_constants, LawConstants,
};
use crate::sink::park_state;
use crate::system::{GpuOptions, GpuState, System, SystemSpec};
use crate::walls::{removal_stage, removal_steps, scene_walls, wall_support, DeviceWall, Plane};
use mdr_contact::damping::{HertzianViscous, NoDamping, StiffnessViscous};
use mdr_contact::model::{ContactLaw, ContactModel};
use mdr_contact::normal::{AdhesiveMdr, Hertz, MdrElastoPlastic, NormalLaw, Thornton};
use mdr_contact::params::{Declared, LawKind};
use mdr_contact::rolling::{EpsdRolling, NoRolling, RollingLaw};
use mdr_contact::tangential::{Frictionless, Mindlin, MindlinLaw};
use mdr_rapier::convert::to_glam;
use mdr_rapier::neighbour_list::particles::Species;
use mdr_rapier::neighbour_list::{Boundary, NeighbourListStepper};
use mdr_rapier::particles::SphereBuilder;
use mdr_sim::laws::registry::{sub_model_kind, SceneParts};
use mdr_sim::laws::{AnyDamping, AnyDampingLaw, SceneNormal, SceneRolling};
use mdr_sim::scene::{ContactSpec, CouplingMode, DampingSpec, ForcePath, SubModelSpec};
use mdr_sim::walls::Sink;
use mdr_sim::Scene;
use nalgebra::Vector3;
use rapier3d_f64::prelude::{ColliderBuilder, PhysicsWorld, SharedShape};
use std::sync::Arc;

/// The elastic energies a contact's history stores at an overlap, `[normal, tangential,
/// rolling]` (J), and its plastic work so far, by the law crate's laws bound for its pair as
/// the CPU run's energy books take them: `NormalLaw::elastic_energy`, `½ k_t |ξ|²` with
/// Mindlin's `k_t = 2 G* a`, `RollingLaw::elastic_energy`, `NormalLaw::dissipated_work` (the
/// device books the adhesive work apart, as it happens: the history carries none).
type ElasticEnergies = Arc<dyn Fn(&DeviceHistory, f64) -> [f64; 4] + Send + Sync>;

/// The normal laws with a device kernel: scene name, `Params::law` code of `bed.wgsl`, f64
/// words of per-contact state.
const DEVICE_LAWS: [(&str, u32, u32); 4] = [
    (Hertz::DECLARATION.name, 0, 1),
    (MdrElastoPlastic::DECLARATION.name, 1, 1),
    (Thornton::DECLARATION.name, 2, 3),
    (AdhesiveMdr::DECLARATION.name, 3, 2),
];

/// The tangential laws with a device kernel, by registered name: Mindlin's spring with its
/// Coulomb cap, and the frictionless law as Mindlin's at `μ = 0` (no force, no displacement
/// kept).
pub const DEVICE_TANGENTIAL: [&str; 2] =
    [Frictionless::DECLARATION.name, Mindlin::DECLARATION.name];

/// The damping laws with a device kernel, by registered name: none, the Hertzian viscous
/// dashpot (its coefficient bound per pair) and the stiffness-viscous one (Tsuji's `η √(m k_n)`:
/// `η` and the reduced mass bound per pair, `k_n` the device normal law's tangent stiffness at
/// each step), each with its tangential dashpot.
pub const DEVICE_DAMPING: [&str; 3] = [
    NoDamping::DECLARATION.name,
    HertzianViscous::DECLARATION.name,
    StiffnessViscous::DECLARATION.name,
];

/// The rolling-resistance laws with a device kernel, by registered name: none, and the
/// elastic–plastic spring (off at `μ_r = 0`).
pub const DEVICE_ROLLING: [&str; 2] = [NoRolling::DECLARATION.name, EpsdRolling::DECLARATION.name];

/// What the device kernel runs for a scene's tangential, damping and rolling laws, chosen by
/// their registered names ([`DEVICE_TANGENTIAL`], [`DEVICE_DAMPING`], [`DEVICE_ROLLING`]; the
/// damping coefficients are bound from the scene's law itself), each value read by its
/// declared key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeviceSubModels {
    /// Mindlin's Coulomb coefficient `μ` (0 for the frictionless law).
    pub friction: f64,
    /// The elastic–plastic rolling spring's `μ_r`; 0: the kernel runs without rolling state.
    pub rolling_friction: f64,
    /// The stiffness-viscous dashpot's `η`; `None`: the kernel runs the Hertzian dashpot (at a
    /// zero coefficient without damping).
    pub stiffness_eta: Option<f64>,
}

impl DeviceSubModels {
    /// The kernel's laws for `contact`, or the refusal naming the first of its tangential,
    /// damping and rolling laws (by its registered name, under its `[contact]` key) that has no
    /// device kernel, with the names the device has. Needs no device.
    pub fn of(contact: &ContactSpec) -> Result<Self, String> {
        let laws = &contact.sub_models;
        let tangential = device_law(LawKind::Tangential, &laws.tangential, &DEVICE_TANGENTIAL)?;
        let damping = device_law(LawKind::Damping, &laws.damping, &DEVICE_DAMPING)?;
        let rolling = device_law(LawKind::Rolling, &laws.rolling, &DEVICE_ROLLING)?;
        Ok(Self {
            friction: if tangential == Mindlin::DECLARATION.name {
                contact.friction()
            } else {
                0.0
            },
            rolling_friction: if rolling == EpsdRolling::DECLARATION.name {
                contact.rolling_friction()
            } else {
                0.0
            },
            stiffness_eta: match contact.damping() {
                DampingSpec::StiffnessViscous(eta)
                    if damping == StiffnessViscous::DECLARATION.name =>
                {
                    Some(eta)
                }
                _ => None,
            },
        })
    }

    /// Whether the kernel runs the rolling spring (with its per-contact state).
    pub fn rolling(&self) -> bool {
        self.rolling_friction > 0.0
    }
}

/// The name of `law` if it is one of `device` (the laws of its kind the kernel has), else the
/// refusal naming it under its `[contact]` key.
fn device_law(
    kind: LawKind,
    law: &SubModelSpec,
    device: &[&'static str],
) -> Result<&'static str, String> {
    let name = law.declaration.name;
    if law.declaration.kind == kind && device.contains(&name) {
        return Ok(name);
    }
    let key = sub_model_kind(kind).map_or("law", |k| k.key);
    let names: Vec<String> = device.iter().map(|n| format!("`{n}`")).collect();
    let has = match names.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => "none".into(),
    };
    Err(format!(
        "`{key} = \"{name}\"` has no GPU kernel (the GPU has {has})"
    ))
}

/// Whether the GPU path runs `scene`: `Ok`, or the error naming the first part it lacks (a
/// wall by its `[[walls]]` entry and kind, a key by its name). Needs no device.
pub fn gpu_scene_support(scene: &Scene) -> Result<(), GpuError> {
    let refuse = |what: String| {
        Err(GpuError::Unsupported(format!(
            "scene `{}`: {what}",
            scene.name
        )))
    };
    if scene.coupling != CouplingMode::Force {
        return refuse(
            "restitution mode (`coupling = \"restitution\"`) runs on the CPU only".into(),
        );
    }
    if scene.force_path == ForcePath::Rapier {
        return refuse("`force_path = \"rapier\"` is the CPU's rapier pipeline path".into());
    }
    if let Err(why) = wall_support(scene) {
        return refuse(why);
    }
    if !DEVICE_LAWS.iter().any(|l| l.0 == scene.contact.normal.law) {
        return refuse(format!(
            "the normal law `normal = \"{}\"` has no GPU kernel (the GPU has {})",
            scene.contact.normal.law,
            DEVICE_LAWS.map(|l| l.0).join(", ")
        ));
    }
    if scene.contact.normal.law == Thornton::DECLARATION.name {
        let thornton = Thornton::from_values(&scene.contact.normal.values)?;
        if thornton.unloading() != mdr_contact::normal::ThorntonUnloading::Thornton1997 {
            return refuse(
                "Thornton's LIGGGHTS `thornton_ning` unloading branch has no GPU kernel".into(),
            );
        }
    }
    if let Err(refusal) = DeviceSubModels::of(&scene.contact) {
        return refuse(refusal);
    }
    Ok(())
}

/// The species of `scene`'s particles as the CPU stepper numbers them (in order of first
/// appearance), and the first particle of each.
fn scene_species(scene: &Scene) -> (Vec<u32>, Vec<usize>) {
    let mut keys: Vec<(usize, u64)> = Vec::new();
    let mut first = Vec::new();
    let species = scene
        .particles
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let key = (p.material, p.radius.to_bits());
            match keys.iter().position(|k| *k == key) {
                Some(s) => s as u32,
                None => {
                    keys.push(key);
                    first.push(i);
                    (keys.len() - 1) as u32
                }
            }
        })
        .collect();
    (species, first)
}

/// What a scene's CPU stepper binds: the species table, the laws per species pair and per
/// (species, wall), the adhesive necks' reach.
struct SceneLaws {
    species_table: Vec<Species>,
    sphere: Vec<LawConstants>,
    walls: Vec<LawConstants>,
    sphere_energies: Vec<ElasticEnergies>,
    wall_energies: Vec<ElasticEnergies>,
    neck_reach: f64,
}

/// `E*` and `R` of every species pair and (species, wall), from an MDR law bound for each.
type Moduli = (Vec<(f64, f64)>, Vec<(f64, f64)>);

/// Bind the scene's laws with normal model `normal` on a stepper holding the first particle of
/// each species and the walls' planes (a law depends on the materials and the species, not
/// on the shape), as the CPU path's stepper binds them (with each material pair's own normal
/// values where the scene gives them: the mixed work of adhesion); the normal constants by
/// `constants(law, E*, R)` with the pair's `E*` and `R` from `moduli` (`None`: the law keeps
/// them itself).
fn bind_scene<N, F>(
    normal: N,
    scene: &Scene,
    planes: &[(usize, Plane)],
    moduli: Option<&Moduli>,
    constants: F,
) -> Result<SceneLaws, GpuError>
where
    N: SceneNormal,
    N::Law: Send + Sync,
    F: Fn(&N::Law, f64, f64) -> Result<LawConstants, GpuError>,
{
    let device = DeviceSubModels::of(&scene.contact).map_err(GpuError::Unsupported)?;
    let parts = SceneParts::of(&scene.contact).map_err(mdr_rapier::error::CouplingError::from)?;
    // The kernel's tangential law is Mindlin's, at the μ its registered name gives.
    let mindlin = Mindlin::new(device.friction).map_err(mdr_rapier::error::CouplingError::from)?;
    let model = ContactModel::new(normal)
        .with_tangential(mindlin)
        .with_damping(parts.damping);
    match parts.rolling {
        Some(rolling) => bind_with(
            NeighbourListStepper::<N, _, AnyDamping>::new(model, Boundary::Open)
                .with_rolling(rolling),
            scene,
            planes,
            moduli,
            device,
            constants,
        ),
        None => bind_with(
            NeighbourListStepper::<N, _, AnyDamping, NoRolling>::new(model, Boundary::Open),
            scene,
            planes,
            moduli,
            device,
            constants,
        ),
    }
}

fn bind_with<N, R, F>(
    mut stepper: NeighbourListStepper<N, Mindlin, AnyDamping, R>,
    scene: &Scene,
    planes: &[(usize, Plane)],
    moduli: Option<&Moduli>,
    device: DeviceSubModels,
    constants: F,
) -> Result<SceneLaws, GpuError>
where
    N: SceneNormal,
    N::Law: Send + Sync,
    R: SceneRolling,
    R::Law: Send + Sync,
    F: Fn(&N::Law, f64, f64) -> Result<LawConstants, GpuError>,
{
    let energies = |bound: &(ContactLaw<N::Law, MindlinLaw, AnyDampingLaw>, R::Law)| {
        let (law, rolling) = bound.clone();
        let energies: ElasticEnergies = Arc::new(move |h: &DeviceHistory, overlap: f64| {
            let r = h.record(N::DECLARATION.name, 0);
            let t = &r.contact.tangential;
            let normal = N::restore(&r.contact.normal);
            [
                law.normal.elastic_energy(&normal, overlap),
                0.5 * law.tangential.stiffness(t.contact_radius) * t.displacement.norm_squared(),
                rolling.elastic_energy(&R::restore(&r.rolling)),
                law.normal.dissipated_work(&normal),
            ]
        });
        energies
    };
    let mut world = PhysicsWorld::default();
    let materials: Vec<_> = scene
        .materials
        .iter()
        .map(|(_, m)| stepper.insert_material(*m))
        .collect();
    // The scene's material pairs with their own values of its law (as the CPU path's build).
    if N::DECLARATION.name == scene.contact.normal.law {
        for a in 0..materials.len() {
            for b in a..materials.len() {
                if let Some(values) = scene.contact.pair_normal_values(a, b) {
                    stepper.set_pair_normal(
                        materials[a],
                        materials[b],
                        N::from_values(&values)?,
                    )?;
                }
            }
        }
    }
    for (j, plane) in planes {
        let material = materials[scene.walls[*j].material];
        stepper.insert_surface(
            &mut world,
            ColliderBuilder::new(SharedShape::halfspace(to_glam(&plane.normal)))
                .translation(to_glam(&plane.point)),
            None,
            material,
        )?;
    }
    let (_, first) = scene_species(scene);
    for &i in &first {
        let p = &scene.particles[i];
        stepper.insert_sphere(
            SphereBuilder::new(p.radius, materials[p.material]).translation(to_glam(&p.position)),
        )?;
    }
    let mut stepper = stepper.skin(mdr_sim::run::build::skin(scene))?;
    stepper.configure(&mut world.integration_parameters, scene.dt)?;
    stepper.compute_forces(&world, false)?;
    let ns = first.len();
    let nw = planes.len();
    let table = &stepper.particles().species_table;
    // The stiffness-viscous dashpot's `η` and the pair's reduced mass, as the stepper binds
    // it: `m₁m₂/(m₁ + m₂)` for two spheres, the sphere's mass against a fixed or turning wall.
    let device_law = |bound, moduli, mass: f64| {
        let c = bound_constants(
            bound,
            moduli,
            device.friction,
            device.rolling_friction,
            &constants,
        )?;
        match device.stiffness_eta {
            Some(eta) => add_stiffness_damping(c, &bound.0.damping, eta, mass),
            None => Ok(c),
        }
    };
    let mut sphere = Vec::with_capacity(ns * ns);
    let mut walls = Vec::with_capacity(ns * nw);
    let mut sphere_energies = Vec::with_capacity(ns * ns);
    let mut wall_energies = Vec::with_capacity(ns * nw);
    for a in 0..ns {
        for b in 0..ns {
            let bound = stepper.sphere_pair_laws(a, b);
            sphere_energies.push(energies(bound));
            let m = match moduli {
                Some(m) => m.0[a * ns + b],
                None => (0.0, 0.0),
            };
            let (ma, mb) = (table[a].mass, table[b].mass);
            sphere.push(device_law(bound, m, ma * mb / (ma + mb))?);
        }
    }
    for (a, species) in table.iter().enumerate() {
        for s in 0..nw {
            let bound = stepper.surface_pair_laws(a, s);
            wall_energies.push(energies(bound));
            let m = match moduli {
                Some(m) => m.1[a * nw + s],
                None => (0.0, 0.0),
            };
            walls.push(device_law(bound, m, species.mass)?);
        }
    }
    Ok(SceneLaws {
        species_table: stepper.particles().species_table.clone(),
        sphere,
        walls,
        sphere_energies,
        wall_energies,
        neck_reach: stepper.neck_reach(),
    })
}

/// `E*` and `R` of every species pair and (species, wall) of `scene`, read from MDR laws bound
/// for them by the CPU path's binding.
fn scene_moduli(scene: &Scene, planes: &[(usize, Plane)]) -> Result<Moduli, GpuError> {
    let laws = bind_scene(
        MdrElastoPlastic::elastic(),
        scene,
        planes,
        None,
        |law, _, _| Ok(mdr_law_constants(law)),
    )?;
    Ok((
        laws.sphere.iter().map(LawConstants::moduli).collect(),
        laws.walls.iter().map(LawConstants::moduli).collect(),
    ))
}

/// The laws of `scene` as its CPU stepper binds them.
fn scene_laws(scene: &Scene, planes: &[(usize, Plane)]) -> Result<SceneLaws, GpuError> {
    let values = &scene.contact.normal.values;
    let law = scene.contact.normal.law;
    let laws = if law == MdrElastoPlastic::DECLARATION.name {
        bind_scene(
            MdrElastoPlastic::from_values(values)?,
            scene,
            planes,
            None,
            |law, _, _| Ok(mdr_law_constants(law)),
        )?
    } else if law == AdhesiveMdr::DECLARATION.name {
        bind_scene(
            AdhesiveMdr::from_values(values)?,
            scene,
            planes,
            None,
            |law, _, _| adhesive_constants(law),
        )?
    } else if law == Hertz::DECLARATION.name {
        let moduli = scene_moduli(scene, planes)?;
        bind_scene(
            Hertz::from_values(values)?,
            scene,
            planes,
            Some(&moduli),
            hertz_constants,
        )?
    } else if law == Thornton::DECLARATION.name {
        let moduli = scene_moduli(scene, planes)?;
        let thornton = Thornton::from_values(values)?;
        let p_y = thornton.yield_pressure();
        bind_scene(thornton, scene, planes, Some(&moduli), |law, e, r| {
            thornton_constants(law, e, r, p_y)
        })?
    } else {
        return Err(GpuError::Unsupported(format!(
            "the normal law `{law}` has no GPU kernel"
        )));
    };
    Ok(laws)
}

/// A force-mode scene stepped on the device: the steps of the CPU neighbour-list path
/// (`mdr_sim::run::SceneSteps`) for a scene whose walls the device has ([`gpu_scene_support`]:
/// planes, boxes, exact cylinders, cones and orifice plates, fixed or turning about their own
/// axis, removed at a time or not; a sink), with the energy books on the device
/// (`crate::run`) and without the headline tracker.
pub struct GpuScene {
    system: System,
    wall_of_plane: Vec<usize>,
    walls: Vec<DeviceWall>,
    /// The steps at whose force pass walls are removed, ascending (removal stages).
    removal_steps: Vec<u64>,
    /// Each particle's mass and radius (its species').
    mass: Vec<f64>,
    radius: Vec<f64>,
    /// Each particle's species, and the species.
    species: Vec<u32>,
    species_count: usize,
    /// The x/y periodic box's side lengths (zero in open space).
    box_len: [f64; 2],
    /// The elastic energies by species pair `a · species + b`, and by `species · walls +
    /// wall`.
    sphere_energies: Vec<ElasticEnergies>,
    wall_energies: Vec<ElasticEnergies>,
    /// The scene's sink (`[run] delete_below_m`): the CPU run's, spots and all.
    sink: Option<Sink>,
}

impl std::fmt::Debug for GpuScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuScene")
            .field("system", &self.system)
            .field("walls", &self.walls)
            .finish()
    }
}

impl GpuScene {
    /// `scene` at its set-up, uploaded to `ctx`'s device with the list and grid sizes of
    /// `options` (its `laws` are ignored: the scene names its own). Refused with the part
    /// named when the GPU path lacks one ([`gpu_scene_support`]).
    pub fn new(ctx: &GpuContext, scene: &Scene, options: &GpuOptions) -> Result<Self, GpuError> {
        gpu_scene_support(scene)?;
        let walls = scene_walls(scene)?;
        // The laws depend on the materials, not on the walls' shapes: each wall is bound as a
        // half-space (its own plane, or one no sphere reaches).
        let planes: Vec<(usize, Plane)> =
            walls.iter().map(|w| (w.wall, w.law_stand_in())).collect();
        let laws = scene_laws(scene, &planes)?;
        let sub_models = DeviceSubModels::of(&scene.contact).map_err(GpuError::Unsupported)?;
        let &(_, law_code, normal_words) = DEVICE_LAWS
            .iter()
            .find(|l| l.0 == scene.contact.normal.law)
            .ok_or_else(|| GpuError::Unsupported("no GPU kernel for the normal law".into()))?;
        let skin = mdr_sim::run::build::skin(scene);
        let periodic = match scene.periodic {
            Some([x, y]) => {
                let boundary = Boundary::periodic_xy(x, y)?;
                let r_max = scene.particles.iter().map(|p| p.radius).fold(0.0, f64::max);
                boundary.check_cutoff(2.0 * r_max + skin + laws.neck_reach)?;
                Some(([x.0, y.0], [x.1, y.1]))
            }
            None => None,
        };
        let (species, _) = scene_species(scene);
        let species_count = laws.species_table.len();
        let box_len = scene
            .periodic
            .map_or([0.0; 2], |[x, y]| [x.1 - x.0, y.1 - y.0]);
        let mass = species
            .iter()
            .map(|&s| laws.species_table[s as usize].mass)
            .collect();
        let radius = species
            .iter()
            .map(|&s| laws.species_table[s as usize].radius)
            .collect();
        let position: Vec<_> = scene.particles.iter().map(|p| p.position).collect();
        let linvel: Vec<_> = scene.particles.iter().map(|p| p.velocity).collect();
        let angvel = vec![Vector3::zeros(); position.len()];
        let sink = mdr_sim::run::scene_sink(scene);
        let system = System::new(
            ctx,
            &SystemSpec {
                position: &position,
                linvel: &linvel,
                angvel: &angvel,
                species: species.clone(),
                species_table: laws.species_table,
                sphere_laws: laws.sphere,
                wall_laws: laws.walls,
                walls: walls.clone(),
                periodic,
                gravity: scene.gravity,
                dt: scene.dt,
                skin,
                neck_reach: laws.neck_reach,
                law_code,
                normal_words,
                rolling: sub_models.rolling(),
                stiffness_damping: sub_models.stiffness_eta.is_some(),
                // Scenes integrate no orientations (no output reads them).
                orientation: false,
                // The energy books of `sim run`.
                books: true,
                sink: sink.as_ref(),
                options: GpuOptions {
                    laws: None,
                    ..*options
                },
            },
        )?;
        let mut gpu = Self {
            system,
            wall_of_plane: walls.iter().map(|w| w.wall).collect(),
            removal_steps: removal_steps(&walls),
            walls,
            mass,
            radius,
            species,
            species_count,
            box_len,
            sphere_energies: laws.sphere_energies,
            wall_energies: laws.wall_energies,
            sink,
        };
        // The CPU run's first step parks the spheres that start below the sink before its
        // force pass (the device parks at the end of each step): the set-up loads them parked.
        if let Some(sink) = &gpu.sink {
            if position.iter().any(|x| sink.is_removed(x)) {
                let state = gpu.system.state()?;
                gpu.load(&state, 0)?;
            }
        }
        Ok(gpu)
    }

    /// The elastic energies stored in the contacts of `state` (read back at a sample, where
    /// the force pass set each contact's state), `[normal, tangential, rolling]` (J), and the
    /// plastic work of those live contacts so far, summed as the CPU run's energy books sum
    /// them ([`GpuScene::visit_live_contacts`]).
    pub(crate) fn contact_energies(&self, state: &GpuState) -> [f64; 4] {
        let mut total = [0.0; 4];
        self.visit_live_contacts(state, |_, _, e| {
            for (t, e) in total.iter_mut().zip(e) {
                *t += e;
            }
        });
        total
    }

    /// Each particle's plastic work so far (J), as the CPU run's frames give it
    /// (`plastic_work_j`, `Books::particle_plastic` with the live contacts added): the contacts
    /// that ended, booked on the device (half of a pair's to each sphere), and each live
    /// contact's from its history now, half of a pair's to each sphere and a wall contact's to
    /// its sphere. The adhesive work is left out, as the CPU run leaves it out.
    pub(crate) fn particle_plastic_work(&self, state: &GpuState) -> Vec<f64> {
        let mut plastic = vec![0.0; state.position.len()];
        for (p, b) in plastic.iter_mut().zip(&state.books) {
            *p = b.plastic;
        }
        self.visit_live_contacts(state, |i, other, [.., work]| match other {
            Some(j) => {
                plastic[i] += 0.5 * work;
                plastic[j] += 0.5 * work;
            }
            None => plastic[i] += work,
        });
        plastic
    }

    /// `visit(particle, other sphere (None: a wall), energies)` for each live contact of
    /// `state` with its energies by its pair's laws ([`ElasticEnergies`]: its history at its
    /// overlap now), the wall contacts first, then the pairs in the state's order.
    fn visit_live_contacts(
        &self,
        state: &GpuState,
        mut visit: impl FnMut(usize, Option<usize>, [f64; 4]),
    ) {
        let walls = self.walls.len();
        for slot in 0..state.floor.len() {
            if let Some(h) = DeviceHistory::of_wall(state, slot) {
                let (i, k) = (slot / walls, slot % walls);
                // A touching contact has a normal (the device ends one without).
                let Some(overlap) =
                    self.walls[k].signed_overlap(&state.position[i], self.radius[i])
                else {
                    continue;
                };
                let law = self.species[i] as usize * walls + k;
                visit(i, None, (self.wall_energies[law])(&h, overlap));
            }
        }
        for pair in state.pairs.iter().filter(|p| p.active) {
            let (i, j) = (pair.i as usize, pair.j as usize);
            // Body 2's image as body 1 sees it.
            let shift = Vector3::new(
                f64::from(i32::from(pair.image / 3) - 1) * self.box_len[0],
                f64::from(i32::from(pair.image % 3) - 1) * self.box_len[1],
                0.0,
            );
            let d = state.position[i] - (state.position[j] + shift);
            let overlap = self.radius[i] + self.radius[j] - d.norm();
            let law = self.species[i] as usize * self.species_count + self.species[j] as usize;
            visit(
                i,
                Some(j),
                (self.sphere_energies[law])(&DeviceHistory::of_pair(pair), overlap),
            );
        }
    }

    system_accessors!();

    /// The scene's wall (`[[walls]]` index) of each device wall, in the device's order (a box
    /// gives five or six planes; a cylinder, cone or orifice plate one surface of revolution).
    pub fn wall_of_plane(&self) -> &[usize] {
        &self.wall_of_plane
    }

    /// `steps` steps: per step, the rebuild decision, the list build when due (indirect
    /// dispatches of zero size otherwise, so the host never waits inside a batch), the forces
    /// and the integration; a wall removed at a time acts no more from the force pass of the
    /// first step whose time `k · dt` reaches it, as on the CPU run. Waits for the device at
    /// the end and checks the overflow flags.
    pub fn step(&mut self, steps: usize) -> Result<(), GpuError> {
        self.advance(steps, false)
    }

    /// `steps` steps, then the forces of the next one: the state read back holds `x_k`,
    /// `v_k` and the contacts at `x_k`, where the CPU run takes its samples (see
    /// [`GpuScene::step`] for the steps).
    pub fn step_and_evaluate(&mut self, steps: usize) -> Result<(), GpuError> {
        self.advance(steps, true)
    }

    /// The steps of [`GpuScene::step`] (`evaluate`: of [`GpuScene::step_and_evaluate`]), cut
    /// at each wall removal so that its stage is on the device before the force pass of its
    /// step; the stage of the first force pass is put there first (after a [`GpuScene::load`],
    /// that of the step loaded).
    fn advance(&mut self, steps: usize, evaluate: bool) -> Result<(), GpuError> {
        let end = self.system.steps() + steps as u64;
        // The last force pass of these steps.
        let last_pass = if evaluate {
            Some(end)
        } else {
            end.checked_sub(1)
        };
        loop {
            self.sync_removed_walls()?;
            let next = self.system.next_force_step();
            let removal = self
                .removal_steps
                .iter()
                .find(|&&r| r > next && last_pass.is_some_and(|last| r <= last));
            match removal {
                // Up to the removal's step, its force pass still to come.
                Some(&r) => self.system.step((r - self.system.steps()) as usize)?,
                None => break,
            }
        }
        let rest = (end - self.system.steps()) as usize;
        if evaluate {
            self.system.step_and_evaluate(rest)
        } else {
            self.system.step(rest)
        }
    }

    /// Put on the device the removal stage of the next force pass.
    fn sync_removed_walls(&mut self) -> Result<(), GpuError> {
        let stage = removal_stage(&self.removal_steps, self.system.next_force_step());
        self.system.set_walls_removed(stage)
    }

    /// Each particle's mass (kg), as the CPU stepper's species table has it.
    pub fn masses(&self) -> &[f64] {
        &self.mass
    }

    /// Each particle's radius (m).
    pub fn radii(&self) -> &[f64] {
        &self.radius
    }

    /// The device walls, in the device's order.
    pub(crate) fn walls(&self) -> &[DeviceWall] {
        &self.walls
    }

    /// The whole state, read back (wall slot `particle · walls + wall`).
    pub fn state(&self) -> Result<GpuState, GpuError> {
        self.system.state()
    }

    /// Put `state` on the device as the state after `steps` steps, before the force pass of
    /// the next one (a checkpoint's: [`GpuScene::state`] read there gives it back). Spheres
    /// below the sink are parked first, as the CPU run parks them at the start of the step
    /// (a CPU checkpoint is written before that; the device's states are parked already). A
    /// particle with more listed neighbours than the slots is refused
    /// ([`GpuError::NeighbourOverflow`]).
    pub fn load(&mut self, state: &GpuState, steps: u64) -> Result<(), GpuError> {
        match &self.sink {
            Some(sink) => {
                let mut state = state.clone();
                park_state(sink, &mut state, &self.mass, &self.radius);
                self.system.load(&state, steps)
            }
            None => self.system.load(state, steps),
        }
    }

    /// The scene's sink (`[run] delete_below_m`), if it has one.
    pub fn sink(&self) -> Option<&Sink> {
        self.sink.as_ref()
    }
}
