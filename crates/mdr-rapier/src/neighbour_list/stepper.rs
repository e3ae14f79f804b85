//! The neighbour-list stepper: the particles live in the plugin's own arrays, contacts come
//! from binned neighbour lists with a skin, and rapier keeps every other collider and body.
//!
//! Per step ([`NeighbourListStepper::step`]):
//! 1. rebuild the neighbour lists if a particle moved more than half the skin, or a surface
//!    collider moved more than half the skin, since the last build (the first step always
//!    builds); a build wraps the particles into the periodic box;
//! 2. every particle–surface candidate: [`crate::geometry::sphere_shape`] against the rapier
//!    collider (for a convex polyhedron the exact face projection
//!    [`crate::geometry::sphere_convex`]), then the per-pair kernel
//!    [`crate::kernel::evaluate_pair`] (parallel);
//! 3. every sphere–sphere candidate, in two passes per chunk of the list: the exact overlap test
//!    alone (branch-free, collecting the touching pairs), then, per block of touching pairs, their
//!    geometry ([`crate::geometry::sphere_sphere`]) and the same kernel on the history
//!    stored next to each touching pair; each wrench is added to both particles' force and
//!    torque sums right away (after their surface wrenches), per block of particles: blocks of
//!    alternate colours in parallel, each owning its own and the next block's sums, and the rare
//!    share for a particle further on added after them (parallel);
//! 4. per particle, integrate as rapier does with one solver iteration: `v += (F + m g)/m · dt`,
//!    `ω += τ/I · dt`, `x += v dt`, the orientation by rapier's linearised update unless switched
//!    off with [`NeighbourListStepper::track_orientation`] (parallel);
//! 5. reaction forces on dynamic rapier bodies, in key order, added to the forces the user put
//!    on them (`add_force`/`add_torque`); then `PhysicsWorld::step` moves the rapier bodies, and
//!    each body gets the user's own forces back.
//!
//! Every sum has an order fixed by the particle count and the lists, so results do not depend on
//! the number of threads.
//!
//! The stepper's parts: its type, builders, accessors and the two halves of a step here; the
//! neighbour-list builds in `rebuild`, the force passes in `forces`, the integration and the
//! reactions in `integrate`, the restart state in `restart`.

use super::boundary::Boundary;
use super::neighbours::{NeighbourBuilder, PairList};
use super::particles::{NeighbourListParticles, Species};
use super::surfaces::{surface_displacement, NeighbourListSurface, SurfacePairs};
use super::workers::map_tasks;
use crate::added_forces::AddedForces;
use crate::adhesion::neck_reach;
use crate::convert::{to_glam, to_na};
use crate::error::{positive, CouplingError, Result};
use crate::geometry::{
    sphere_sphere, sphere_sphere_signed, ConvexFaces, SurfaceContact, SurfaceOfRevolution,
};
use crate::kernel::{
    evaluate_pair, Arms, ContactKinematics, ContactWorks, PairHistory, PairWrench, SphereArms,
};
use crate::pair_models::PairNormals;
use crate::particles::{MaterialHandle, ParticleShape, SphereBuilder};
use crate::registration::add_force_flags;
use crate::timestep::stable_time_step;
use mdr_contact::damping::{DampingModel, NoDamping};
use mdr_contact::material::{effective_modulus, effective_shear_modulus};
use mdr_contact::model::{
    Books, ContactLaw, ContactModel, ContactState, NoBooks, StateOf, WorkBooks,
};
use mdr_contact::normal::{NormalLaw, NormalModel};
use mdr_contact::rolling::{NoRolling, RollingLaw, RollingModel};
use mdr_contact::tangential::{Frictionless, TangentialModel};
use mdr_contact::{ContactPair, Material};
use nalgebra::Vector3;
use rapier3d_f64::parry::mass_properties::MassProperties;
use rapier3d_f64::prelude::*;
use std::sync::Arc;

mod forces;
mod integrate;
mod rebuild;
mod restart;

/// Pairs per chunk of a block's sphere pair loop: pass 1 (the overlap test) runs over a chunk,
/// then pass 2 (geometry and law) over its touching pairs. Small enough that the positions and
/// radii pass 1 reads are still in the core's first-level cache when pass 2 reads them again.
const CHUNK: usize = 256;
/// Particle–surface pairs per chunk of the parallel surface pass.
const SURFACE_CHUNK: usize = 256;
/// Touching pairs per block of the two-stage pair loop (geometry, then law).
const BLOCK: usize = 128;

type Law<N, T, D> =
    ContactLaw<<N as NormalModel>::Law, <T as TangentialModel>::Law, <D as DampingModel>::Law>;
/// The pair history of a stepper's laws, with work books `B`.
pub type NeighbourListHistory<N, T, R, B = Books> = PairHistory<
    StateOf<<N as NormalModel>::Law, <T as TangentialModel>::Law, B>,
    <<R as RollingModel>::Law as RollingLaw>::State,
>;

/// What one neighbour-list step did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NeighbourListStepReport {
    /// Touching sphere–sphere pairs.
    pub sphere_contacts: usize,
    /// Touching particle–surface pairs.
    pub surface_contacts: usize,
    /// Sphere–sphere pairs in the neighbour list.
    pub neighbour_pairs: usize,
    /// Whether the neighbour lists were rebuilt at the start of this step.
    pub rebuilt: bool,
    /// Largest particle displacement since the last build, after this step.
    pub max_displacement: f64,
}

/// Wall-clock time a [`NeighbourListStepper`] spent in each part of its steps while timing was on
/// ([`NeighbourListStepper::time_steps`]): LAMMPS's timing breakdown (`Pair`, `Neigh`, `Modify`) for
/// this path. Reading the clock costs a few tens of nanoseconds per part and step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepTimings {
    /// Steps timed.
    pub steps: u64,
    /// Neighbour-list builds (step 1 of [`NeighbourListStepper::step`]; LAMMPS `Neigh`).
    pub builds: std::time::Duration,
    /// Particle–surface pairs (step 2).
    pub surfaces: std::time::Duration,
    /// Sphere–sphere pairs with the per-particle sums (step 3; LAMMPS `Pair`).
    pub pairs: std::time::Duration,
    /// Integration of the particles (step 4).
    pub integration: std::time::Duration,
    /// Reactions on rapier bodies and rapier's own step (step 5).
    pub rapier: std::time::Duration,
}

impl StepTimings {
    /// The sum of the parts.
    pub fn total(&self) -> std::time::Duration {
        self.builds + self.surfaces + self.pairs + self.integration + self.rapier
    }
}

/// The other side of a contact whose history ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactPartner {
    /// Particle `j` (> the first particle, or its periodic image).
    Sphere(u32),
    /// Surface `s`: the index in [`NeighbourListStepper::surfaces`].
    Surface(u32),
}

/// A contact whose history ended (the pair separated, or the lists dropped it), with what its
/// history had booked (see [`NeighbourListStepper::record_ended_contacts`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndedContact {
    /// The particle.
    pub particle: u32,
    /// What it touched.
    pub partner: ContactPartner,
    /// The contact's works over its whole life.
    pub works: ContactWorks,
}

impl EndedContact {
    /// `particle`'s contact with `partner`, whose `history` ends, under its bound laws.
    #[inline]
    fn of<NL, TL, DL, RL, B>(
        particle: u32,
        partner: ContactPartner,
        (law, rolling): &(ContactLaw<NL, TL, DL>, RL),
        history: &PairHistory<StateOf<NL, TL, B>, RL::State>,
    ) -> Self
    where
        NL: mdr_contact::normal::NormalLaw,
        TL: mdr_contact::tangential::TangentialLaw,
        DL: mdr_contact::damping::DampingLaw,
        RL: RollingLaw,
        B: WorkBooks,
    {
        Self {
            particle,
            partner,
            works: ContactWorks::of(law, rolling, history),
        }
    }
}

/// The neighbour-list coupling. Owns the particles (structure of arrays), the neighbour lists
/// with their histories, and the registered rapier surfaces; call
/// [`NeighbourListStepper::step`] instead of `PhysicsWorld::step`.
pub struct NeighbourListStepper<
    N: NormalModel,
    T: TangentialModel = Frictionless,
    D: DampingModel = NoDamping,
    R: RollingModel = NoRolling,
    B: WorkBooks = Books,
> {
    model: ContactModel<N, T, D>,
    /// Normal models set per material pair, in place of `model.normal`.
    pair_normals: PairNormals<N>,
    rolling: R,
    boundary: Boundary,
    skin: f64,
    materials: Vec<Material>,
    /// `(E*, G*)` of material pair `(a, b)` at `a * n + b`.
    moduli: Vec<(f64, f64)>,
    particles: NeighbourListParticles,
    /// Positions at the last build.
    built_at: Vec<Vector3<f64>>,
    /// Sphere–sphere laws by species pair `(a, b)` at `a * n + b`.
    sphere_laws: Vec<(Law<N, T, D>, R::Law)>,
    /// Particle–surface laws by `(species, surface)` at `species * surfaces + surface`.
    surface_laws: Vec<(Law<N, T, D>, R::Law)>,
    /// Mass of each surface's dynamic body (infinite otherwise) when `surface_laws` were bound.
    surface_masses: Vec<f64>,
    laws_species: usize,
    /// Largest separation at which a sphere–sphere contact of the bound laws still holds
    /// ([`crate::adhesion::neck_reach`]; zero without adhesion): added to the list's cut-off.
    sphere_neck: f64,
    /// The same for particle–surface contacts: added to the candidates' reach.
    surface_neck: f64,
    /// Whether a bound sphere–sphere law is adhesive (a contact may hold apart).
    adhesive: bool,
    /// Whether a bound particle–surface law is adhesive.
    surface_adhesive: bool,
    /// Whether the cut-off covers the necks (always, but for a negative control in tests).
    neck_rule: bool,
    surfaces: Vec<NeighbourListSurface>,
    pairs: PairList<NeighbourListHistory<N, T, R, B>>,
    old_pairs: PairList<NeighbourListHistory<N, T, R, B>>,
    builder: NeighbourBuilder,
    surface_pairs: SurfacePairs<NeighbourListHistory<N, T, R, B>>,
    old_surface_pairs: SurfacePairs<NeighbourListHistory<N, T, R, B>>,
    surface_candidates: Vec<(u32, u32)>,
    /// Reaction wrench per surface body, reduced in key order.
    reactions: Vec<(RigidBodyHandle, Vector3<f64>, Vector3<f64>)>,
    /// The reactions written on top of the user's forces, until given back.
    added: AddedForces,
    /// Per-particle force and torque sums of the step (see [`NeighbourListStepper::step`]).
    sums: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// Per particle block of the pair loop: the shares deferred for particles beyond the next
    /// block.
    deferred: Vec<Vec<forces::DeferredShare>>,
    /// Whether orientations are integrated (see [`NeighbourListStepper::track_orientation`]).
    orientation: bool,
    needs_build: bool,
    max_displacement: f64,
    report: NeighbourListStepReport,
    rebuilds: u64,
    /// Set by [`NeighbourListStepper::compute_forces`], taken by [`NeighbourListStepper::advance`].
    pending: Option<Pending>,
    /// Contacts that ended since the last [`NeighbourListStepper::take_ended_contacts`], when
    /// recorded.
    ended: Option<Vec<EndedContact>>,
    /// Time per part of the steps, while timed ([`NeighbourListStepper::time_steps`]).
    timings: Option<StepTimings>,
}

/// What [`NeighbourListStepper::compute_forces`] leaves for [`NeighbourListStepper::advance`].
#[derive(Debug, Clone, Copy)]
struct Pending {
    rebuilt: bool,
    sphere_contacts: usize,
    surface_contacts: usize,
}

/// The neighbour-list state of a [`NeighbourListStepper`] between two steps: what, with the
/// particles' positions and velocities, makes a restored stepper continue bit for bit (the
/// lists are not rebuilt at the restore, so the next build happens at the same step as in the
/// uninterrupted run, and the histories sit in the same pair order).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NeighbourListState<H> {
    /// Particle positions at the last build.
    pub built_at: Vec<Vector3<f64>>,
    /// Largest displacement since the last build.
    pub max_displacement: f64,
    /// Pose of every surface (in collider-index order) at the last build.
    pub surface_poses: Vec<Pose>,
    /// Neighbour builds so far.
    pub rebuilds: u64,
    /// Sphere pairs of the list, sorted: `(i, j, image code)`.
    pub pairs: Vec<(u32, u32, u8)>,
    /// Per pair: whether it touched at the last force evaluation.
    pub pair_active: Vec<bool>,
    /// Per pair: its history (default where not active).
    pub pair_history: Vec<H>,
    /// Particle–surface candidates, sorted: `(particle, surface index)`.
    pub surface_pairs: Vec<(u32, u32)>,
    /// Per candidate: whether it touched at the last force evaluation.
    pub surface_active: Vec<bool>,
    /// Per candidate: its history.
    pub surface_history: Vec<H>,
}

impl<N: NormalModel, T: TangentialModel, D: DampingModel> NeighbourListStepper<N, T, D, NoRolling> {
    /// A stepper for `model` in `boundary`, no rolling resistance, skin 0.1 × (set it with
    /// [`NeighbourListStepper::skin`]).
    pub fn new(model: ContactModel<N, T, D>, boundary: Boundary) -> Self {
        Self {
            model,
            pair_normals: PairNormals::default(),
            rolling: NoRolling,
            boundary,
            skin: 0.0,
            materials: Vec::new(),
            moduli: Vec::new(),
            particles: NeighbourListParticles::default(),
            built_at: Vec::new(),
            sphere_laws: Vec::new(),
            surface_laws: Vec::new(),
            surface_masses: Vec::new(),
            laws_species: 0,
            sphere_neck: 0.0,
            surface_neck: 0.0,
            adhesive: false,
            surface_adhesive: false,
            neck_rule: true,
            surfaces: Vec::new(),
            pairs: PairList::default(),
            old_pairs: PairList::default(),
            builder: NeighbourBuilder::default(),
            surface_pairs: SurfacePairs::default(),
            old_surface_pairs: SurfacePairs::default(),
            surface_candidates: Vec::new(),
            reactions: Vec::new(),
            added: AddedForces::default(),
            sums: Vec::new(),
            deferred: Vec::new(),
            orientation: true,
            needs_build: true,
            max_displacement: 0.0,
            report: NeighbourListStepReport::default(),
            rebuilds: 0,
            pending: None,
            ended: None,
            timings: None,
        }
    }
}

impl<N, T, D, R, B> NeighbourListStepper<N, T, D, R, B>
where
    N: NormalModel,
    T: TangentialModel,
    D: DampingModel,
    R: RollingModel,
    B: WorkBooks,
    N::Law: Clone,
    T::Law: Clone,
    D::Law: Clone,
    R::Law: Clone,
{
    /// Add a rolling-resistance sub-model (call before inserting particles).
    pub fn with_rolling<R2: RollingModel>(
        self,
        rolling: R2,
    ) -> NeighbourListStepper<N, T, D, R2, B> {
        // The bound laws and the histories depend on the rolling law: both start afresh.
        self.retyped(rolling, Vec::new(), Vec::new(), |_| {
            (PairList::default(), SurfacePairs::default())
        })
    }

    /// Keep no friction and damping work books in the pair histories ([`NoBooks`]): the same
    /// trajectory bit for bit, with less work per contact (docs/performance.md); the histories'
    /// reports then give NaN for those works. Histories
    /// are carried over, so this may be called at any point of a run.
    pub fn without_work_books(mut self) -> NeighbourListStepper<N, T, D, R, NoBooks> {
        fn unbooked<NS, TS, B, RS>(
            h: PairHistory<ContactState<NS, TS, B>, RS>,
        ) -> PairHistory<ContactState<NS, TS, NoBooks>, RS> {
            PairHistory {
                contact: ContactState {
                    normal: h.contact.normal,
                    tangential: h.contact.tangential,
                    books: NoBooks,
                },
                rolling: h.rolling,
            }
        }
        let rolling = self.rolling.clone();
        let sphere_laws = std::mem::take(&mut self.sphere_laws);
        let surface_laws = std::mem::take(&mut self.surface_laws);
        self.retyped(rolling, sphere_laws, surface_laws, |s| {
            (
                std::mem::take(&mut s.pairs).map_history(unbooked),
                std::mem::take(&mut s.surface_pairs).map_history(unbooked),
            )
        })
    }

    /// The same stepper with rolling model `rolling`, bound laws `sphere_laws`/`surface_laws`
    /// (empty sphere laws: bound again, and the pairs found again, by a build at the next step)
    /// and the pair lists `lists(&mut self)` returns; every other field moves over.
    #[allow(clippy::type_complexity)]
    fn retyped<R2: RollingModel, B2: WorkBooks>(
        mut self,
        rolling: R2,
        sphere_laws: Vec<(Law<N, T, D>, R2::Law)>,
        surface_laws: Vec<(Law<N, T, D>, R2::Law)>,
        lists: impl FnOnce(
            &mut Self,
        ) -> (
            PairList<NeighbourListHistory<N, T, R2, B2>>,
            SurfacePairs<NeighbourListHistory<N, T, R2, B2>>,
        ),
    ) -> NeighbourListStepper<N, T, D, R2, B2> {
        let (pairs, surface_pairs) = lists(&mut self);
        // No bound laws: the next step must build (which binds them and finds the pairs).
        let fresh = sphere_laws.is_empty();
        NeighbourListStepper {
            model: self.model,
            pair_normals: self.pair_normals,
            rolling,
            boundary: self.boundary,
            skin: self.skin,
            materials: self.materials,
            moduli: self.moduli,
            particles: self.particles,
            built_at: self.built_at,
            laws_species: if fresh { 0 } else { self.laws_species },
            sphere_laws,
            surface_laws,
            sphere_neck: self.sphere_neck,
            surface_neck: self.surface_neck,
            adhesive: self.adhesive,
            surface_adhesive: self.surface_adhesive,
            neck_rule: self.neck_rule,
            surface_masses: if fresh {
                Vec::new()
            } else {
                self.surface_masses
            },
            surfaces: self.surfaces,
            pairs,
            old_pairs: PairList::default(),
            builder: self.builder,
            surface_pairs,
            old_surface_pairs: SurfacePairs::default(),
            surface_candidates: self.surface_candidates,
            reactions: self.reactions,
            added: self.added,
            sums: self.sums,
            deferred: self.deferred,
            orientation: self.orientation,
            needs_build: self.needs_build || fresh,
            max_displacement: self.max_displacement,
            report: self.report,
            rebuilds: self.rebuilds,
            pending: None,
            ended: self.ended,
            timings: self.timings,
        }
    }

    /// Record every contact whose history ends (its pair separated, or a rebuild dropped it)
    /// with what the history had booked ([`ContactWorks`]), in an order that does not depend on
    /// the number of threads: per step the rebuild's drops, the surface contacts, then the
    /// sphere pairs, each in list order. Energy books then need the live contacts' books only when
    /// they are read, plus these, instead of every contact's increments at every step. Drain
    /// them with [`NeighbourListStepper::take_ended_contacts`]. Off by default.
    pub fn record_ended_contacts(mut self, yes: bool) -> Self {
        self.ended = yes.then(Vec::new);
        self
    }

    /// Move the contacts that ended since the last call (see
    /// [`NeighbourListStepper::record_ended_contacts`]) to the end of `into`.
    pub fn take_ended_contacts(&mut self, into: &mut Vec<EndedContact>) {
        if let Some(ended) = &mut self.ended {
            into.append(ended);
        }
    }

    /// Neighbour skin (length, > 0): pairs closer than `r_i + r_j + skin` are listed, and the
    /// lists are rebuilt once something moved more than half of it. Without this call the skin
    /// is 10 % of the first particle's diameter.
    pub fn skin(mut self, skin: f64) -> Result<Self> {
        self.skin = positive("skin", skin)?;
        self.needs_build = true;
        Ok(self)
    }

    /// The largest separation (m) at which a contact of the bound laws can still hold
    /// adhesively ([`crate::adhesion::neck_reach`], over the sphere–sphere and particle–surface
    /// laws; zero without adhesion, and before the first build binds the laws). The sphere
    /// list's cut-off is `r_i + r_j + skin + neck` and a particle's surface candidates lie within
    /// `r + skin + neck`: a held pair is never dropped by a rebuild (docs/coupling.md).
    pub fn neck_reach(&self) -> f64 {
        self.sphere_neck.max(self.surface_neck)
    }

    /// Whether the cut-off covers the adhesive necks ([`NeighbourListStepper::neck_reach`]);
    /// always on, switched off only by tests to show that a held contact is lost without it.
    #[doc(hidden)]
    pub fn cover_necks(mut self, yes: bool) -> Self {
        self.neck_rule = yes;
        self.laws_species = 0;
        self.needs_build = true;
        self
    }

    /// Whether to integrate the particles' orientations (default: yes, as rapier does). Contact
    /// forces and torques of spheres do not depend on orientation, so switching it off changes
    /// no trajectory; it saves a quaternion product and normalisation (a square root and a
    /// division) per particle and step, and leaves [`NeighbourListParticles::rotation`] at its last value.
    /// LAMMPS `atom_style sphere` keeps no orientation either.
    pub fn track_orientation(mut self, yes: bool) -> Self {
        self.orientation = yes;
        self
    }

    /// Add a material; pair moduli follow from eq. (3) and docs/theory.md §5 unless overridden by
    /// [`NeighbourListStepper::set_pair_moduli`].
    pub fn insert_material(&mut self, material: Material) -> MaterialHandle {
        let old_n = self.materials.len();
        self.materials.push(material);
        let n = old_n + 1;
        let mut moduli = Vec::with_capacity(n * n);
        for a in 0..n {
            for b in 0..n {
                moduli.push(if a < old_n && b < old_n {
                    self.moduli[a * old_n + b]
                } else {
                    (
                        effective_modulus(&self.materials[a], &self.materials[b]),
                        effective_shear_modulus(&self.materials[a], &self.materials[b]),
                    )
                });
            }
        }
        self.moduli = moduli;
        self.laws_species = 0;
        MaterialHandle(old_n as u32)
    }

    /// Set `E*` and `G*` of a material pair directly (both > 0), e.g. to match a code that
    /// specifies normal and tangential stiffnesses instead of materials.
    pub fn set_pair_moduli(
        &mut self,
        a: MaterialHandle,
        b: MaterialHandle,
        effective_modulus: f64,
        effective_shear_modulus: f64,
    ) -> Result<()> {
        self.material(a)?;
        self.material(b)?;
        positive("effective_modulus", effective_modulus)?;
        positive("effective_shear_modulus", effective_shear_modulus)?;
        let n = self.materials.len();
        let value = (effective_modulus, effective_shear_modulus);
        self.moduli[a.0 as usize * n + b.0 as usize] = value;
        self.moduli[b.0 as usize * n + a.0 as usize] = value;
        self.laws_species = 0;
        Ok(())
    }

    /// Bind the contacts between materials `a` and `b` (sphere–sphere and sphere–surface,
    /// either order) with the normal model `normal` in place of the contact model's (the
    /// tangential and damping models stay the model's): e.g. the adhesive MDR law with the
    /// pair's own work of adhesion. The laws are bound again at the next step; the pair loop
    /// runs the same law type for every pair.
    pub fn set_pair_normal(
        &mut self,
        a: MaterialHandle,
        b: MaterialHandle,
        normal: N,
    ) -> Result<()> {
        self.material(a)?;
        self.material(b)?;
        self.pair_normals.set(a, b, normal);
        self.laws_species = 0;
        self.needs_build = true;
        Ok(())
    }

    /// The normal model that binds the contacts between materials `a` and `b`: the one set by
    /// [`NeighbourListStepper::set_pair_normal`], else the contact model's.
    pub fn pair_normal(&self, a: MaterialHandle, b: MaterialHandle) -> &N {
        self.pair_normals.get(a, b).unwrap_or(&self.model.normal)
    }

    fn material(&self, handle: MaterialHandle) -> Result<&Material> {
        self.materials
            .get(handle.0 as usize)
            .ok_or(CouplingError::UnknownMaterial(
                handle.0,
                self.materials.len(),
            ))
    }

    /// Add a sphere; returns its particle index. Mass and inertia are rapier's for a ball of the
    /// material's density.
    pub fn insert_sphere(&mut self, sphere: SphereBuilder) -> Result<usize> {
        positive("radius", sphere.radius)?;
        let density = self.material(sphere.material)?.density();
        let props = MassProperties::from_ball(density, sphere.radius);
        let species = self.particles.species_of(Species {
            material: sphere.material,
            radius: sphere.radius,
            mass: props.mass(),
            inv_mass: props.inv_mass,
            inv_inertia: props.inv_principal_inertia.x,
        })?;
        if self.skin == 0.0 {
            self.skin = 0.2 * sphere.radius;
        }
        self.needs_build = true;
        Ok(self.particles.push(
            species,
            to_na(sphere.translation),
            to_na(sphere.linvel),
            to_na(sphere.angvel),
        ))
    }

    /// Insert a collider of any shape (wall, box, mesh, container …), optionally on a body (as
    /// `PhysicsWorld::insert_collider(collider, parent)`), and register it as a surface of
    /// `material`. Its solver groups follow force mode's rule ([`crate::registration`]): the
    /// coupling's solver group leaves its filter, so its contacts with every rapier collider
    /// (another surface, a user's unregistered body) stay rapier's, as without the plugin; the
    /// particles, which are not rapier colliders, touch it through the law.
    pub fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: impl Into<Collider>,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle> {
        self.material(material)?;
        let c = world.insert_collider(surface_collider(collider), parent);
        self.register_surface(&world.colliders, c, material)?;
        Ok(c)
    }

    /// Register an existing collider as a surface of `material`.
    pub fn register_surface(
        &mut self,
        colliders: &ColliderSet,
        collider: ColliderHandle,
        material: MaterialHandle,
    ) -> Result<()> {
        self.register_surface_as(colliders, collider, material, None)
    }

    /// Insert a collider (on `parent`, solver groups as [`NeighbourListStepper::insert_surface`]'s)
    /// whose contacts with the particles follow the exact surface of revolution `surface` (given
    /// in the collider's local frame) instead of its shape: a cylinder, cone or orifice-plate
    /// wall that rapier sees as flat pieces (for its bounding box and its other uses) touches
    /// the spheres as the smooth surface it stands for.
    pub fn insert_surface_of_revolution(
        &mut self,
        world: &mut PhysicsWorld,
        collider: impl Into<Collider>,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
        surface: SurfaceOfRevolution,
    ) -> Result<ColliderHandle> {
        self.material(material)?;
        let c = world.insert_collider(surface_collider(collider), parent);
        self.register_surface_as(&world.colliders, c, material, Some(Arc::new(surface)))?;
        Ok(c)
    }

    fn register_surface_as(
        &mut self,
        colliders: &ColliderSet,
        collider: ColliderHandle,
        material: MaterialHandle,
        revolution: Option<Arc<SurfaceOfRevolution>>,
    ) -> Result<()> {
        self.material(material)?;
        let co = colliders
            .get(collider)
            .ok_or(CouplingError::UnknownCollider(collider))?;
        let surface = NeighbourListSurface {
            collider,
            body: co.parent(),
            material,
            pose_at_build: *co.position(),
            bounding_radius: co.shape().compute_local_bounding_sphere().radius(),
            convex: co
                .shape()
                .as_convex_polyhedron()
                .map(|poly| Arc::new(ConvexFaces::of(poly))),
            revolution,
            plane: co
                .shape()
                .as_halfspace()
                .map(|half_space| to_na(half_space.normal).normalize()),
        };
        // Keep surfaces in collider-index order (the rapier pipeline path's summation order).
        let at = self
            .surfaces
            .partition_point(|s| s.collider.into_raw_parts().0 < collider.into_raw_parts().0);
        self.surfaces.insert(at, surface);
        self.needs_build = true;
        self.old_surface_pairs = SurfacePairs::default();
        self.surface_pairs = SurfacePairs::default();
        Ok(())
    }

    /// Set what the neighbour-list path needs on rapier's integration parameters (for the rapier bodies):
    /// time step `dt`, one solver iteration, no CCD, no speed cap.
    pub fn configure(&self, params: &mut IntegrationParameters, dt: f64) -> Result<()> {
        positive("dt", dt)?;
        params.dt = dt;
        params.num_solver_iterations = 1;
        params.max_ccd_substeps = 0;
        params.normalized_max_linear_velocity = f64::MAX;
        Ok(())
    }

    /// The particles (structure of arrays).
    pub fn particles(&self) -> &NeighbourListParticles {
        &self.particles
    }

    /// The particles, mutably (positions, velocities). Moving particles by hand triggers no
    /// rebuild by itself: call [`NeighbourListStepper::request_rebuild`] afterwards.
    pub fn particles_mut(&mut self) -> &mut NeighbourListParticles {
        &mut self.particles
    }

    /// Force a neighbour-list rebuild at the next step.
    pub fn request_rebuild(&mut self) {
        self.needs_build = true;
    }

    /// The boundary.
    pub fn boundary(&self) -> &Boundary {
        &self.boundary
    }

    /// The sphere–sphere neighbour list (pairs, images, histories).
    pub fn pairs(&self) -> &PairList<NeighbourListHistory<N, T, R, B>> {
        &self.pairs
    }

    /// The particle–surface candidates (histories included).
    pub fn surface_pairs(&self) -> &SurfacePairs<NeighbourListHistory<N, T, R, B>> {
        &self.surface_pairs
    }

    /// The sphere–sphere law bound to the species of particles `i` and `j`.
    pub fn sphere_law(&self, i: usize, j: usize) -> &Law<N, T, D> {
        let ns = self.laws_species;
        let (si, sj) = (
            self.particles.species[i] as usize,
            self.particles.species[j] as usize,
        );
        &self.sphere_laws[si * ns + sj].0
    }

    /// The report of the last step.
    pub fn last_report(&self) -> NeighbourListStepReport {
        self.report
    }

    /// Neighbour-list builds so far.
    pub fn rebuilds(&self) -> u64 {
        self.rebuilds
    }

    /// Time each part of the steps from now on (`true`, starting from zero) or stop timing
    /// (`false`). The trajectory does not depend on it.
    pub fn time_steps(&mut self, on: bool) {
        self.timings = on.then(StepTimings::default);
    }

    /// Time spent per part of the steps since [`NeighbourListStepper::time_steps`] switched timing
    /// on; `None` while off.
    pub fn step_timings(&self) -> Option<&StepTimings> {
        self.timings.as_ref()
    }

    /// The time since `*mark` added to a part of the timings, and `*mark` moved to now; nothing
    /// while timing is off.
    fn lap(
        &mut self,
        mark: &mut Option<std::time::Instant>,
        part: fn(&mut StepTimings) -> &mut std::time::Duration,
    ) {
        if let (Some(timings), Some(start)) = (&mut self.timings, mark.as_mut()) {
            let now = std::time::Instant::now();
            *part(timings) += now - *start;
            *start = now;
        }
    }

    /// The registered surfaces, in collider-index order (the `surface` index of
    /// [`SurfacePairs`]).
    pub fn surfaces(&self) -> &[NeighbourListSurface] {
        &self.surfaces
    }

    /// The composed and rolling laws bound to the species of particles `i` and `j` (bound at
    /// the first build, i.e. after the first [`NeighbourListStepper::compute_forces`]).
    pub fn sphere_pair_laws(&self, i: usize, j: usize) -> &(Law<N, T, D>, R::Law) {
        let ns = self.laws_species;
        let (si, sj) = (
            self.particles.species[i] as usize,
            self.particles.species[j] as usize,
        );
        &self.sphere_laws[si * ns + sj]
    }

    /// The composed and rolling laws of particle `i` against surface `s` (an index into
    /// [`NeighbourListStepper::surfaces`]), bound at each build.
    pub fn surface_pair_laws(&self, i: usize, s: usize) -> &(Law<N, T, D>, R::Law) {
        &self.surface_laws[self.particles.species[i] as usize * self.surfaces.len() + s]
    }

    /// Bytes held by the stepper's buffers (capacities), particles and lists included.
    pub fn memory_bytes(&self) -> usize {
        self.particles.bytes()
            + self.built_at.capacity() * 24
            + self.pairs.bytes()
            + self.old_pairs.bytes()
            + self.builder.bytes()
            + self.surface_pairs.bytes()
            + self.old_surface_pairs.bytes()
            + self.surface_candidates.capacity() * 8
            + self.sums.capacity() * 48
            + (self.sphere_laws.capacity() + self.surface_laws.capacity())
                * std::mem::size_of::<(Law<N, T, D>, R::Law)>()
    }

    /// One coupled step: particle forces and integration, reactions on rapier bodies, then
    /// `world.step()`. The same as [`NeighbourListStepper::compute_forces`] followed by
    /// [`NeighbourListStepper::advance`].
    pub fn step(&mut self, world: &mut PhysicsWorld) -> Result<NeighbourListStepReport> {
        self.step_with(world, &(), &())
    }

    /// [`NeighbourListStepper::step`] with the user's hooks and event handler for rapier's own
    /// pairs (`world.step_with_events(hooks, events)`); the particles are not rapier colliders,
    /// so the hooks and events see the rapier bodies' pairs only.
    pub fn step_with(
        &mut self,
        world: &mut PhysicsWorld,
        hooks: &dyn PhysicsHooks,
        events: &dyn EventHandler,
    ) -> Result<NeighbourListStepReport> {
        self.compute_forces(world, false)?;
        self.advance_with(world, hooks, events)
    }

    /// First half of a step at the current state `x_k, v_k`: rebuild the lists if due, then every
    /// touching pair's law (which updates its history and work books) and its wrench. Between
    /// this call and [`NeighbourListStepper::advance`], positions, velocities, histories and the
    /// surface contacts all describe step `k`: the place to read energies and contacts.
    /// `keep_wrenches` also stores every sphere pair's wrench in [`PairList::wrench`] (a
    /// contact-network frame needs them); the particles' force sums, hence the trajectory, are
    /// the same bits either way.
    pub fn compute_forces(&mut self, world: &PhysicsWorld, keep_wrenches: bool) -> Result<()> {
        let dt = world.integration_parameters.dt;
        positive("dt", dt)?;
        if self.pending.is_some() {
            // Forces of this state are already computed (a second call would update the
            // histories twice).
            return Ok(());
        }
        let mut mark = self.timings.is_some().then(std::time::Instant::now);
        let half_skin = 0.5 * self.skin;
        let rebuilt = self.needs_build
            || self.max_displacement > half_skin
            || self.surfaces_moved(&world.colliders) > half_skin;
        if rebuilt {
            self.rebuild(&world.bodies, &world.colliders)?;
            self.check_stability(&world.bodies, dt)?;
        }
        self.lap(&mut mark, |t| &mut t.builds);
        let surface_contacts = self.surface_wrenches(&world.bodies, &world.colliders, dt);
        self.lap(&mut mark, |t| &mut t.surfaces);
        let sphere_contacts = self.sphere_wrenches(dt, keep_wrenches);
        self.lap(&mut mark, |t| &mut t.pairs);
        self.pending = Some(Pending {
            rebuilt,
            sphere_contacts,
            surface_contacts,
        });
        Ok(())
    }

    /// Second half of a step: integrate the particles with the forces of
    /// [`NeighbourListStepper::compute_forces`] (called first if it was not), put the reactions on
    /// dynamic rapier bodies, then `world.step()`.
    pub fn advance(&mut self, world: &mut PhysicsWorld) -> Result<NeighbourListStepReport> {
        self.advance_with(world, &(), &())
    }

    /// [`NeighbourListStepper::advance`] with the user's hooks and event handler for rapier's step
    /// (`world.step_with_events(hooks, events)`).
    pub fn advance_with(
        &mut self,
        world: &mut PhysicsWorld,
        hooks: &dyn PhysicsHooks,
        events: &dyn EventHandler,
    ) -> Result<NeighbourListStepReport> {
        if self.pending.is_none() {
            self.compute_forces(world, false)?;
        }
        let Some(pending) = self.pending.take() else {
            return Err(CouplingError::StateMismatch(
                "no forces were computed for this step".to_owned(),
            ));
        };
        let dt = world.integration_parameters.dt;
        let gravity = to_na(world.gravity);
        let mut mark = self.timings.is_some().then(std::time::Instant::now);
        self.max_displacement = self.integrate(&gravity, dt).sqrt();
        self.lap(&mut mark, |t| &mut t.integration);
        self.apply_reactions(&mut world.bodies);
        world.step_with_events(hooks, events);
        self.added.give_back(&mut world.bodies);
        self.lap(&mut mark, |t| &mut t.rapier);
        if let Some(timings) = &mut self.timings {
            timings.steps += 1;
        }
        self.report = NeighbourListStepReport {
            sphere_contacts: pending.sphere_contacts,
            surface_contacts: pending.surface_contacts,
            neighbour_pairs: self.pairs.len(),
            rebuilt: pending.rebuilt,
            max_displacement: self.max_displacement,
        };
        Ok(self.report)
    }
}

impl<N, T, D, R, B> NeighbourListStepper<N, T, D, R, B>
where
    N: NormalModel,
    T: TangentialModel,
    D: DampingModel,
    R: RollingModel,
    B: WorkBooks,
{
    /// At each neighbour-list build: `dt` must stay below the stability limit `2 √(m/k_max)`
    /// ([`stable_time_step`]) of the Hertz contact that any two species could make at twice the
    /// largest particle speed, and that any species could make with any surface at the largest
    /// particle speed plus the surface body's speed, else [`CouplingError::NeighbourListTimeStepTooLarge`].
    fn check_stability(&self, bodies: &RigidBodySet, dt: f64) -> Result<()> {
        let p = &self.particles;
        let v_max = p
            .linvel
            .iter()
            .map(|v| v.norm_squared())
            .fold(0.0, f64::max)
            .sqrt();
        let table = &p.species_table;
        let nm = self.materials.len();
        let check = |pair: ContactPair, speed: f64, kind: &'static str| -> Result<()> {
            if !(speed > 0.0 && speed.is_finite()) {
                return Ok(());
            }
            let advice = stable_time_step(&pair, speed, 1.0)?;
            if dt > advice.stability_limit {
                return Err(CouplingError::NeighbourListTimeStepTooLarge {
                    dt,
                    limit: advice.stability_limit,
                    contact_time: advice.contact_time,
                    speed,
                    kind,
                });
            }
            Ok(())
        };
        // Two particles at least for a sphere–sphere contact.
        let pairs = if p.len() > 1 { table.len() } else { 0 };
        for (k, a) in table.iter().enumerate() {
            for b in &table[k..pairs.max(k)] {
                let (e, g) = self.moduli[a.material.0 as usize * nm + b.material.0 as usize];
                let pair = ContactPair::new(
                    e,
                    g,
                    a.radius * b.radius / (a.radius + b.radius),
                    a.mass * b.mass / (a.mass + b.mass),
                )?;
                check(pair, 2.0 * v_max, "sphere–sphere")?;
            }
            for s in &self.surfaces {
                let (e, g) = self.moduli[a.material.0 as usize * nm + s.material.0 as usize];
                let body = s.body.and_then(|h| bodies.get(h));
                let body_speed = body.map_or(0.0, |b| {
                    let spin = b.angvel().length();
                    b.linvel().length()
                        + if spin > 0.0 && s.bounding_radius.is_finite() {
                            spin * s.bounding_radius
                        } else {
                            0.0
                        }
                });
                let mass = match body.filter(|b| b.is_dynamic()) {
                    Some(b) => a.mass * b.mass() / (a.mass + b.mass()),
                    None => a.mass,
                };
                let pair = ContactPair::new(e, g, a.radius, mass)?;
                check(pair, v_max + body_speed, "sphere–surface")?;
            }
        }
        Ok(())
    }
}

/// A surface collider with force mode's solver-group rule applied to the user's groups.
fn surface_collider(collider: impl Into<Collider>) -> Collider {
    let mut co = collider.into();
    add_force_flags(&mut co, ParticleShape::Surface);
    co
}
