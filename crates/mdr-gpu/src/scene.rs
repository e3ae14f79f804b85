//! Scenes on the GPU ([`GpuScene`]): force-mode scenes whose walls are all planes and boxes,
//! with the laws the CPU neighbour-list path binds for them, species pair by species pair.
//!
//! A scene the device does not have every part of is refused ([`gpu_scene_support`]) with the
//! part named: a wall of another kind (cylinder, cone, orifice plate, mesh), a rotating or
//! removed wall, a sink, restitution mode, the rapier pipeline path, the stiffness-viscous
//! damping law, Thornton's LIGGGHTS unloading branch or a normal law without a device kernel.

use crate::accessors::system_accessors;
use crate::checkpoint::DeviceHistory;
use crate::device::{GpuContext, GpuError};
use crate::law::{
    adhesive_constants, bound_constants, hertz_constants, mdr_law_constants, thornton_constants,
    LawConstants,
};
use crate::system::{GpuOptions, GpuState, Plane, System, SystemSpec};
use mdr_contact::damping::StiffnessViscous;
use mdr_contact::model::{ContactLaw, ContactModel};
use mdr_contact::normal::{AdhesiveMdr, Hertz, MdrElastoPlastic, NormalLaw, Thornton};
use mdr_contact::params::Declared;
use mdr_contact::rolling::{NoRolling, RollingLaw};
use mdr_contact::tangential::MindlinLaw;
use mdr_rapier::convert::to_glam;
use mdr_rapier::neighbour_list::particles::Species;
use mdr_rapier::neighbour_list::{Boundary, NeighbourListStepper};
use mdr_rapier::particles::SphereBuilder;
use mdr_sim::laws::registry::SceneParts;
use mdr_sim::laws::{AnyDamping, AnyDampingLaw, SceneNormal, SceneRolling};
use mdr_sim::scene::schema::WallKind;
use mdr_sim::scene::{CouplingMode, DampingSpec, ForcePath};
use mdr_sim::walls::WallPiece;
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
    for wall in &scene.walls {
        let j = wall.index;
        let kind = scene.source.walls.get(j).map(|w| w.kind);
        if !matches!(kind, Some(WallKind::Plane | WallKind::Box)) || wall.revolution.is_some() {
            return refuse(format!(
                "wall {j} (`[[walls]]` entry {}, `kind = \"{}\"`{}) has no GPU kernel: the GPU \
                 has `plane` and `box` walls only",
                j + 1,
                kind.map_or("unknown", kind_name),
                if wall.revolution.is_some() {
                    ", an exact surface of revolution"
                } else {
                    ""
                }
            ));
        }
        if wall.angular_velocity.is_some() {
            return refuse(format!(
                "wall {j} (`[[walls]]` entry {}) rotates (`angular_velocity_rad_per_s`): the GPU \
                 has fixed walls only",
                j + 1
            ));
        }
        if wall.removed_at.is_some() {
            return refuse(format!(
                "wall {j} (`[[walls]]` entry {}) is removed during the run (`removed_at_s`): \
                 the GPU has fixed walls only",
                j + 1
            ));
        }
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
    // The kernel binds the damping law from the spec's view (`contact.damping`): its name is
    // the one refused.
    let unsupported_damping = match scene.contact.damping {
        DampingSpec::None | DampingSpec::HertzianViscous(_) => None,
        DampingSpec::StiffnessViscous(_) => Some(StiffnessViscous::DECLARATION.name),
        DampingSpec::Other(name) => Some(name),
    };
    if let Some(name) = unsupported_damping {
        return refuse(format!(
            "`damping = \"{name}\"` has no GPU kernel (the GPU has `none` and `hertzian_viscous`)"
        ));
    }
    if scene.source.run.delete_below_m.is_some() {
        return refuse("the sink `[run] delete_below_m` runs on the CPU only".into());
    }
    Ok(())
}

/// The scene file's name of a wall kind.
fn kind_name(kind: WallKind) -> &'static str {
    match kind {
        WallKind::Plane => "plane",
        WallKind::Box => "box",
        WallKind::Cylinder => "cylinder",
        WallKind::Mesh => "mesh",
        WallKind::OrificePlate => "orifice_plate",
        WallKind::Cone => "cone",
    }
}

/// The planes of `scene`'s walls in the CPU path's surface order, each with its wall index:
/// a plane wall's half-space, and a box's slabs as the planes of their inner faces, each
/// valid over its face.
fn scene_planes(scene: &Scene) -> Result<Vec<(usize, Plane)>, GpuError> {
    let mut planes = Vec::new();
    for wall in &scene.walls {
        for piece in &wall.pieces {
            let plane = match piece {
                WallPiece::HalfSpace { point, normal } => {
                    Plane::infinite(normal.normalize(), wall.origin + point)
                }
                WallPiece::Cuboid {
                    center,
                    rotation,
                    half_extents,
                } if *rotation == nalgebra::UnitQuaternion::identity() => {
                    let center = wall.origin + center;
                    // The slab's thin axis; its inner face looks towards the box's centre.
                    let axis = (0..3)
                        .min_by(|&a, &b| half_extents[a].total_cmp(&half_extents[b]))
                        .unwrap_or(2);
                    let box_center = wall.origin + pieces_center(&wall.pieces);
                    let side = if center[axis] > box_center[axis] {
                        1.0
                    } else {
                        -1.0
                    };
                    let mut normal = Vector3::zeros();
                    normal[axis] = -side;
                    let mut point = center;
                    point[axis] -= side * half_extents[axis];
                    let mut lo = center - half_extents;
                    let mut hi = center + half_extents;
                    lo[axis] = f64::MIN;
                    hi[axis] = f64::MAX;
                    Plane {
                        normal,
                        point,
                        lo,
                        hi,
                    }
                }
                _ => {
                    return Err(GpuError::Unsupported(format!(
                        "wall {} has a piece that is neither a half-space nor an axis-aligned slab",
                        wall.index
                    )))
                }
            };
            planes.push((wall.index, plane));
        }
    }
    Ok(planes)
}

/// The mean of the centres of a box's slabs: inside the box, on the inner side of every slab
/// (an open top leaves the mean above the bottom slab).
fn pieces_center(pieces: &[WallPiece]) -> Vector3<f64> {
    let centers: Vec<_> = pieces
        .iter()
        .filter_map(|p| match p {
            WallPiece::Cuboid { center, .. } => Some(*center),
            _ => None,
        })
        .collect();
    centers.iter().sum::<Vector3<f64>>() / centers.len().max(1) as f64
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
    let parts = SceneParts::of(&scene.contact).map_err(mdr_rapier::error::CouplingError::from)?;
    // The device kernel's tangential law is Mindlin's (μ = 0: frictionless).
    let mindlin = mdr_contact::tangential::Mindlin::new(scene.contact.friction)
        .map_err(mdr_rapier::error::CouplingError::from)?;
    let model = ContactModel::new(normal)
        .with_tangential(mindlin)
        .with_damping(parts.damping);
    let mu_r = scene.contact.rolling_friction;
    match parts.rolling {
        Some(rolling) => bind_with(
            NeighbourListStepper::<N, _, AnyDamping>::new(model, Boundary::Open)
                .with_rolling(rolling),
            scene,
            planes,
            moduli,
            mu_r,
            constants,
        ),
        None => bind_with(
            NeighbourListStepper::<N, _, AnyDamping, NoRolling>::new(model, Boundary::Open),
            scene,
            planes,
            moduli,
            mu_r,
            constants,
        ),
    }
}

fn bind_with<N, R, F>(
    mut stepper: NeighbourListStepper<N, mdr_contact::tangential::Mindlin, AnyDamping, R>,
    scene: &Scene,
    planes: &[(usize, Plane)],
    moduli: Option<&Moduli>,
    mu_r: f64,
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
            sphere.push(bound_constants(
                bound,
                m,
                scene.contact.friction,
                mu_r,
                &constants,
            )?);
        }
    }
    for a in 0..ns {
        for s in 0..nw {
            let bound = stepper.surface_pair_laws(a, s);
            wall_energies.push(energies(bound));
            let m = match moduli {
                Some(m) => m.1[a * nw + s],
                None => (0.0, 0.0),
            };
            walls.push(bound_constants(
                bound,
                m,
                scene.contact.friction,
                mu_r,
                &constants,
            )?);
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
/// (`mdr_sim::run::SceneSteps`) for a scene whose walls are planes and boxes, without the
/// energy books and the headline tracker.
pub struct GpuScene {
    system: System,
    wall_of_plane: Vec<usize>,
    planes: Vec<Plane>,
    /// Each particle's mass and radius (its species').
    mass: Vec<f64>,
    radius: Vec<f64>,
    /// Each particle's species, and the species.
    species: Vec<u32>,
    species_count: usize,
    /// The x/y periodic box's side lengths (zero in open space).
    box_len: [f64; 2],
    /// The elastic energies by species pair `a · species + b`, and by `species · planes +
    /// plane`.
    sphere_energies: Vec<ElasticEnergies>,
    wall_energies: Vec<ElasticEnergies>,
}

impl std::fmt::Debug for GpuScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuScene")
            .field("system", &self.system)
            .field("planes", &self.planes)
            .finish()
    }
}

impl GpuScene {
    /// `scene` at its set-up, uploaded to `ctx`'s device with the list and grid sizes of
    /// `options` (its `laws` are ignored: the scene names its own). Refused with the part
    /// named when the GPU path lacks one ([`gpu_scene_support`]).
    pub fn new(ctx: &GpuContext, scene: &Scene, options: &GpuOptions) -> Result<Self, GpuError> {
        gpu_scene_support(scene)?;
        let planes = scene_planes(scene)?;
        let laws = scene_laws(scene, &planes)?;
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
                walls: planes.iter().map(|p| p.1).collect(),
                periodic,
                gravity: scene.gravity,
                dt: scene.dt,
                skin,
                neck_reach: laws.neck_reach,
                law_code,
                normal_words,
                rolling: scene.contact.rolling_friction > 0.0,
                // Scenes integrate no orientations (no output reads them).
                orientation: false,
                // The energy books of `sim run`.
                books: true,
                options: GpuOptions {
                    laws: None,
                    ..*options
                },
            },
        )?;
        Ok(Self {
            system,
            wall_of_plane: planes.iter().map(|p| p.0).collect(),
            planes: planes.iter().map(|p| p.1).collect(),
            mass,
            radius,
            species,
            species_count,
            box_len,
            sphere_energies: laws.sphere_energies,
            wall_energies: laws.wall_energies,
        })
    }

    /// The elastic energies stored in the contacts of `state` (read back at a sample, where
    /// the force pass set each contact's state), `[normal, tangential, rolling]` (J), and the
    /// plastic work of those live contacts so far: each touching contact's history at its
    /// overlap now, by its pair's laws, the wall contacts first, as the CPU run's energy books
    /// sum them.
    pub(crate) fn contact_energies(&self, state: &GpuState) -> [f64; 4] {
        let mut total = [0.0; 4];
        let mut add = |e: [f64; 4]| {
            for (t, e) in total.iter_mut().zip(e) {
                *t += e;
            }
        };
        let walls = self.planes.len();
        for slot in 0..state.floor.len() {
            if let Some(h) = DeviceHistory::of_wall(state, slot) {
                let (i, k) = (slot / walls, slot % walls);
                let plane = &self.planes[k];
                let overlap = self.radius[i] - plane.normal.dot(&(state.position[i] - plane.point));
                let law = self.species[i] as usize * walls + k;
                add((self.wall_energies[law])(&h, overlap));
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
            add((self.sphere_energies[law])(
                &DeviceHistory::of_pair(pair),
                overlap,
            ));
        }
        total
    }

    system_accessors!();

    /// The scene's wall (`[[walls]]` index) of each wall plane, in the device's order (a box
    /// gives five or six).
    pub fn wall_of_plane(&self) -> &[usize] {
        &self.wall_of_plane
    }

    /// `steps` steps, then the forces of the next one: the state read back holds `x_k`,
    /// `v_k` and the contacts at `x_k`, where the CPU run takes its samples (see
    /// [`crate::GpuBed::step`] for the steps).
    pub fn step_and_evaluate(&mut self, steps: usize) -> Result<(), GpuError> {
        self.system.step_and_evaluate(steps)
    }

    /// Each particle's mass (kg), as the CPU stepper's species table has it.
    pub fn masses(&self) -> &[f64] {
        &self.mass
    }

    /// Each particle's radius (m).
    pub fn radii(&self) -> &[f64] {
        &self.radius
    }

    /// The wall planes, in the device's order.
    pub(crate) fn planes(&self) -> &[Plane] {
        &self.planes
    }

    /// The whole state, read back (wall slot `particle · planes + plane`).
    pub fn state(&self) -> Result<GpuState, GpuError> {
        self.system.state()
    }

    /// Put `state` on the device as the state after `steps` steps, before the force pass of
    /// the next one (a checkpoint's: [`GpuScene::state`] read there gives it back). A particle
    /// with more listed neighbours than the slots is refused ([`GpuError::NeighbourOverflow`]).
    pub fn load(&mut self, state: &GpuState, steps: u64) -> Result<(), GpuError> {
        self.system.load(state, steps)
    }
}
