//! Force mode: soft spheres whose contact forces come from the law, integrated by rapier.
//!
//! Per step ([`ForceModeStepper::step`]):
//! 1. candidate pairs from rapier's narrow phase (pairs whose enlarged AABBs overlap), keyed by
//!    [`PairKey`];
//! 2. exact geometry at the current poses, in parallel ([`crate::geometry`]);
//! 3. the history store is merged with the touching pairs (sorted by key: history created at
//!    first touch, dropped at separation); a contact whose adhesive law still holds
//!    ([`mdr_contact::normal::NormalLaw::holds`]) stays, with its geometry at its negative
//!    overlap, until the law lets it go, whether or not the narrow phase still lists it;
//! 4. the per-pair kernel ([`crate::kernel::evaluate_pair`]) in parallel;
//! 5. forces and torques reduced per body in key order (deterministic for any thread count) and
//!    added to the forces the user put on the bodies (rapier's `add_force`, kept from step to
//!    step);
//! 6. `PhysicsPipeline::step` with one solver iteration: `v_{k+1} = v_k + dt F(x_k, v_k)/m`,
//!    `x_{k+1} = x_k + dt v_{k+1}` (symplectic Euler; see `docs/coupling.md`);
//! 7. every body gets the user's own forces back.

use crate::added_forces::AddedForces;
use crate::convert::{to_glam, to_na};
use crate::error::{positive, CouplingError, Result};
use crate::geometry::{
    sphere_shape, sphere_shape_signed, sphere_sphere, sphere_sphere_signed, SurfaceContact,
};
use crate::kernel::{evaluate_pair, Arms, ContactKinematics, PairHistory, PairWrench};
use crate::pair_models::PairNormals;
use crate::particles::{MaterialHandle, Particle, ParticleSet, ParticleShape, SphereBuilder};
use crate::registration::{add_force_flags, check_force_flags};
use crate::store::{ContactStore, Keyed, PairKey};
use crate::timestep::stable_time_step;
use mdr_contact::damping::{DampingModel, NoDamping};
use mdr_contact::model::{ContactLaw, ContactModel, StateOf};
use mdr_contact::normal::{NormalLaw, NormalModel};
use mdr_contact::rolling::{NoRolling, RollingLaw, RollingModel};
use mdr_contact::tangential::{Frictionless, TangentialModel};
use mdr_contact::ContactPair;
use nalgebra::Vector3;
use rapier3d_f64::prelude::*;
use rayon::prelude::*;
use std::time::Instant;

/// One touching pair in force mode: who, the law bound to the pair, its history, the geometry
/// and the wrench of the current step.
#[derive(Debug, Clone)]
pub struct ForceContact<NL, TL, DL, RL>
where
    NL: mdr_contact::normal::NormalLaw,
    TL: mdr_contact::tangential::TangentialLaw,
    RL: RollingLaw,
{
    /// Pair key (sort order).
    pub key: PairKey,
    /// The sphere ("body 1": the force and the normal refer to it).
    pub collider1: ColliderHandle,
    /// The other collider (a sphere or a surface).
    pub collider2: ColliderHandle,
    /// Body of collider 1.
    pub body1: RigidBodyHandle,
    /// Body of collider 2, if any.
    pub body2: Option<RigidBodyHandle>,
    /// The composed law bound to this pair (`E*`, `G*`, `R`, `m` precomputed).
    pub law: ContactLaw<NL, TL, DL>,
    /// The rolling law bound to this pair.
    pub rolling: RL,
    /// The pair's history.
    pub history: PairHistory<StateOf<NL, TL>, RL::State>,
    /// Geometry at the start of the current step.
    pub contact: SurfaceContact,
    /// Wrench of the current step.
    pub wrench: PairWrench,
}

impl<NL, TL, DL, RL> ForceContact<NL, TL, DL, RL>
where
    NL: mdr_contact::normal::NormalLaw,
    TL: mdr_contact::tangential::TangentialLaw,
    RL: RollingLaw,
{
    /// Unit normal from collider 2 towards the sphere (collider 1), in rapier's vector type.
    pub fn normal(&self) -> Vector {
        to_glam(&self.contact.normal)
    }

    /// Contact point (m), in rapier's vector type.
    pub fn point(&self) -> Vector {
        to_glam(&self.contact.point)
    }

    /// Overlap (m).
    pub fn overlap(&self) -> f64 {
        self.contact.overlap
    }

    /// Force on the sphere (N) of the current step, in rapier's vector type (collider 2 gets
    /// the opposite).
    pub fn force(&self) -> Vector {
        to_glam(&self.wrench.force)
    }
}

impl<NL, TL, DL, RL> Keyed for ForceContact<NL, TL, DL, RL>
where
    NL: mdr_contact::normal::NormalLaw,
    TL: mdr_contact::tangential::TangentialLaw,
    RL: RollingLaw,
{
    fn key(&self) -> PairKey {
        self.key
    }
}

/// The history store of a force-mode stepper with these sub-models.
pub type ForceStore<N, T, D, R> = ContactStore<
    ForceContact<
        <N as NormalModel>::Law,
        <T as TangentialModel>::Law,
        <D as DampingModel>::Law,
        <R as RollingModel>::Law,
    >,
>;

/// What happened during one step, with every pair of the world that has contacts counted by
/// who handles it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Touching pairs handled by the law this step (`sphere_sphere + sphere_surface`).
    pub contacts: usize,
    /// Of those, pairs of two registered spheres.
    pub sphere_sphere: usize,
    /// Of those, pairs of a registered sphere and a registered surface.
    pub sphere_surface: usize,
    /// Pairs with contacts that rapier's solver handles (any pair but the law's: surface on
    /// surface, a registered collider against an unregistered one, pairs without the plugin),
    /// as rapier's narrow phase saw them at the start of the step.
    pub rapier_pairs: usize,
    /// Candidate pairs of the law that the user's `filter_contact_pair` rejected (no force).
    pub filtered: usize,
    /// Pairs with contacts involving a registered sphere that neither the law nor rapier's
    /// solver handles (listed by [`ForceModeStepper::unhandled_pairs`]).
    pub unhandled: usize,
    /// Candidate pairs examined (narrow-phase pairs involving the plugin's colliders).
    pub candidates: usize,
    /// History entries created this step.
    pub created: u64,
    /// History entries removed this step (pairs that separated).
    pub removed: u64,
    /// Largest sphere speed at the start of the step (m/s).
    pub max_speed: f64,
    /// `false` when two spheres at the largest speed could close more than rapier's prediction
    /// distance in one step, i.e. a new contact could be seen one step late: reduce `dt` or raise
    /// the prediction distance.
    pub prediction_distance_ok: bool,
    /// Wall-clock time of each phase of the plugin's force pass.
    pub timings: PhaseTimings,
}

/// Wall-clock seconds spent in each phase of one force pass (for profiling; not used by the
/// physics).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PhaseTimings {
    /// Collecting candidate pairs from the narrow phase.
    pub candidates: f64,
    /// Exact geometry of the candidates (parallel) and sorting them by key.
    pub geometry: f64,
    /// Merging the touching pairs into the history store.
    pub merge: f64,
    /// The per-pair kernel (parallel): law updates and wrenches.
    pub kernel: f64,
    /// Per-body reduction in key order.
    pub reduction: f64,
    /// Writing forces and torques to rapier's bodies.
    pub apply: f64,
}

#[derive(Debug, Clone, Copy)]
struct Candidate {
    key: PairKey,
    sphere: ColliderHandle,
    other: ColliderHandle,
    contact: Option<SurfaceContact>,
}

/// A pair with contacts that gets no response at all: neither the law nor rapier's solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnhandledPair {
    /// The registered sphere.
    pub sphere: ColliderHandle,
    /// The other collider (not registered with the coupling).
    pub other: ColliderHandle,
}

impl std::fmt::Display for UnhandledPair {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "sphere {:?} touches collider {:?}, which is not registered and whose solver groups \
             leave out the coupling's group: no force acts; register it as a surface \
             (ForceModeStepper::register_surface) or let its solver filter include \
             COUPLING_SOLVER_GROUP",
            self.sphere, self.other
        )
    }
}

/// The force-mode coupling: owns the contact model, the registered colliders and the history
/// store; call [`ForceModeStepper::step`] instead of `PhysicsWorld::step`.
pub struct ForceModeStepper<
    N: NormalModel,
    T: TangentialModel = Frictionless,
    D: DampingModel = NoDamping,
    R: RollingModel = NoRolling,
> {
    model: ContactModel<N, T, D>,
    /// Normal models set per material pair, in place of `model.normal`.
    pair_normals: PairNormals<N>,
    rolling: R,
    particles: ParticleSet,
    store: ForceStore<N, T, D, R>,
    candidates: Vec<Candidate>,
    /// Force and torque accumulators by body arena index.
    wrenches: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// Bodies already written this step (by arena index).
    written: Vec<bool>,
    /// The wrenches written on top of the user's forces, until given back.
    added: AddedForces,
    unhandled: Vec<UnhandledPair>,
    report: StepReport,
}

impl<N: NormalModel, T: TangentialModel, D: DampingModel> ForceModeStepper<N, T, D, NoRolling> {
    /// A stepper for `model` (normal + tangential + damping), no rolling resistance.
    pub fn new(model: ContactModel<N, T, D>) -> Self {
        Self {
            model,
            pair_normals: PairNormals::default(),
            rolling: NoRolling,
            particles: ParticleSet::new(),
            store: ContactStore::new(),
            candidates: Vec::new(),
            wrenches: Vec::new(),
            written: Vec::new(),
            added: AddedForces::default(),
            unhandled: Vec::new(),
            report: StepReport::default(),
        }
    }
}

impl<N, T, D, R> ForceModeStepper<N, T, D, R>
where
    N: NormalModel,
    T: TangentialModel,
    D: DampingModel,
    R: RollingModel,
{
    /// Add a rolling-resistance sub-model (e.g. [`mdr_contact::rolling::EpsdRolling`]).
    pub fn with_rolling<R2: RollingModel>(self, rolling: R2) -> ForceModeStepper<N, T, D, R2> {
        ForceModeStepper {
            model: self.model,
            pair_normals: self.pair_normals,
            rolling,
            particles: self.particles,
            store: ContactStore::new(),
            candidates: self.candidates,
            wrenches: self.wrenches,
            written: self.written,
            added: self.added,
            unhandled: self.unhandled,
            report: self.report,
        }
    }

    /// Use an existing particle set (materials and registered colliders).
    pub fn with_particles(mut self, particles: ParticleSet) -> Self {
        self.particles = particles;
        self
    }

    /// The contact model.
    pub fn model(&self) -> &ContactModel<N, T, D> {
        &self.model
    }

    /// Bind the contacts between materials `a` and `b` (sphere–sphere and sphere–surface,
    /// either order) with the normal model `normal` in place of the contact model's (the
    /// tangential and damping models stay the model's): e.g. the adhesive MDR law with the
    /// pair's own work of adhesion. A contact's law is bound when it begins: call this before
    /// the pair's first contact.
    pub fn set_pair_normal(
        &mut self,
        a: MaterialHandle,
        b: MaterialHandle,
        normal: N,
    ) -> Result<()> {
        self.particles.material(a)?;
        self.particles.material(b)?;
        self.pair_normals.set(a, b, normal);
        Ok(())
    }

    /// The normal model that binds the contacts between materials `a` and `b`: the one set by
    /// [`ForceModeStepper::set_pair_normal`], else the contact model's.
    pub fn pair_normal(&self, a: MaterialHandle, b: MaterialHandle) -> &N {
        self.pair_normals.get(a, b).unwrap_or(&self.model.normal)
    }

    /// The registered colliders and materials.
    pub fn particles(&self) -> &ParticleSet {
        &self.particles
    }

    /// The registered colliders and materials, mutably (to add materials). Register colliders
    /// built by hand with [`ForceModeStepper::register_sphere`] and
    /// [`ForceModeStepper::register_surface`], which add the coupling's solver group; a collider
    /// registered through the particle set alone is refused by the next step.
    pub fn particles_mut(&mut self) -> &mut ParticleSet {
        &mut self.particles
    }

    /// The history store (one entry per touching pair).
    pub fn contacts(&self) -> &ForceStore<N, T, D, R> {
        &self.store
    }

    /// The history store, mutably: restoring per-contact histories from a checkpoint
    /// (used by `mdr-sim`; the entries' keys must stay sorted).
    pub fn contacts_mut(&mut self) -> &mut ForceStore<N, T, D, R> {
        &mut self.store
    }

    /// The report of the last step.
    pub fn last_report(&self) -> StepReport {
        self.report
    }

    /// The pairs of the last step that got no response (see [`StepReport::unhandled`]).
    pub fn unhandled_pairs(&self) -> &[UnhandledPair] {
        &self.unhandled
    }

    /// Set what force mode needs on rapier's integration parameters: time step `dt` (s), one
    /// solver iteration (exact symplectic Euler), no CCD, no speed cap, and a prediction distance
    /// (m) that must exceed the largest relative displacement of two bodies in one step.
    pub fn configure(
        &self,
        params: &mut IntegrationParameters,
        dt: f64,
        prediction_distance: f64,
    ) -> Result<()> {
        positive("dt", dt)?;
        positive("prediction_distance", prediction_distance)?;
        params.dt = dt;
        params.num_solver_iterations = 1;
        params.max_ccd_substeps = 0;
        params.normalized_max_linear_velocity = f64::MAX;
        params.normalized_prediction_distance = prediction_distance / params.length_unit;
        Ok(())
    }

    /// Insert a sphere (dynamic body + ball collider) into `world` and register it; its pairs
    /// with the coupling's spheres and surfaces leave rapier's solver (solver group added to the
    /// user's, see [`crate::registration`]).
    pub fn insert_sphere(
        &mut self,
        world: &mut PhysicsWorld,
        sphere: SphereBuilder,
    ) -> Result<(RigidBodyHandle, ColliderHandle)> {
        self.insert_sphere_into(sphere, &mut world.bodies, &mut world.colliders)
    }

    /// [`ForceModeStepper::insert_sphere`] on rapier's sets, for programs that run their own
    /// `PhysicsPipeline`.
    pub fn insert_sphere_into(
        &mut self,
        sphere: SphereBuilder,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
    ) -> Result<(RigidBodyHandle, ColliderHandle)> {
        self.particles
            .insert_sphere_into_sets(bodies, colliders, sphere, |co| {
                add_force_flags(co, ParticleShape::Sphere { radius: 0.0 })
            })
    }

    /// Insert a collider of any shape (a wall, a box, a mesh …) into `world`, optionally on a
    /// body (as `PhysicsWorld::insert_collider(collider, parent)`), and register it as a
    /// surface of `material`: its contacts with the coupling's spheres come from the law, its
    /// contacts with everything else stay rapier's.
    pub fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: impl Into<Collider>,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle> {
        self.insert_surface_with_parent(
            collider,
            parent,
            material,
            &mut world.colliders,
            &mut world.bodies,
        )
    }

    /// [`ForceModeStepper::insert_surface`] on rapier's sets, in the order of
    /// `ColliderSet::insert_with_parent(collider, parent, bodies)` (the collider set first,
    /// as the receiver of rapier's call).
    pub fn insert_surface_with_parent(
        &mut self,
        collider: impl Into<Collider>,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
        colliders: &mut ColliderSet,
        bodies: &mut RigidBodySet,
    ) -> Result<ColliderHandle> {
        self.particles.insert_surface_into_sets(
            collider,
            parent,
            material,
            bodies,
            colliders,
            |co| add_force_flags(co, ParticleShape::Surface),
        )
    }

    /// Register a ball collider already in `colliders` (on a dynamic body) as a sphere of
    /// `material`, adding the coupling's solver group to its own.
    pub fn register_sphere(
        &mut self,
        collider: ColliderHandle,
        material: MaterialHandle,
        colliders: &mut ColliderSet,
    ) -> Result<()> {
        self.particles
            .register_sphere(colliders, collider, material)?;
        if let Some(co) = colliders.get_mut(collider) {
            add_force_flags(co, ParticleShape::Sphere { radius: 0.0 });
        }
        Ok(())
    }

    /// Register a collider of any shape already in `colliders` as a surface of `material`,
    /// removing the coupling's solver group from its solver filter.
    pub fn register_surface(
        &mut self,
        collider: ColliderHandle,
        material: MaterialHandle,
        colliders: &mut ColliderSet,
    ) -> Result<()> {
        self.particles
            .register_surface(colliders, collider, material)?;
        if let Some(co) = colliders.get_mut(collider) {
            add_force_flags(co, ParticleShape::Surface);
        }
        Ok(())
    }

    /// One coupled step of `world`: forces from the current poses, then `world.step()`.
    /// Equivalent to [`ForceModeStepper::step_with`] with no hooks and no event handler.
    pub fn step(&mut self, world: &mut PhysicsWorld) -> Result<StepReport> {
        self.step_with(world, &(), &())
    }

    /// One coupled step of `world` with the user's hooks and event handler: checks that the
    /// world is configured ([`ForceModeStepper::configure`]) and that every registered collider
    /// still has the coupling's solver group, computes the law's forces from the current poses
    /// (pairs that `hooks.filter_contact_pair` rejects get none), then
    /// `world.step_with_events(hooks, events)`.
    pub fn step_with(
        &mut self,
        world: &mut PhysicsWorld,
        hooks: &dyn PhysicsHooks,
        events: &dyn EventHandler,
    ) -> Result<StepReport> {
        self.check(&world.integration_parameters, &world.colliders)?;
        let dt = world.integration_parameters.dt;
        self.compute_forces_with(
            &world.bodies,
            &world.colliders,
            &world.narrow_phase,
            dt,
            hooks,
        )?;
        self.apply_forces(&mut world.bodies);
        self.report.prediction_distance_ok =
            2.0 * self.report.max_speed * dt <= world.integration_parameters.prediction_distance();
        world.step_with_events(hooks, events);
        self.give_back_user_forces(&mut world.bodies);
        Ok(self.report)
    }

    /// The checks of [`ForceModeStepper::step_with`], for programs that run their own
    /// `PhysicsPipeline`: `params` must be as [`ForceModeStepper::configure`] left them (one
    /// solver iteration, no CCD substeps, no speed cap), and every registered collider must
    /// be in rapier's set with the coupling's solver group.
    pub fn check(&self, params: &IntegrationParameters, colliders: &ColliderSet) -> Result<()> {
        check_configured(params)?;
        for particle in self.particles.iter() {
            let co = colliders
                .get(particle.collider)
                .ok_or(CouplingError::UnknownCollider(particle.collider))?;
            check_force_flags(co, particle)?;
        }
        Ok(())
    }

    /// [`ForceModeStepper::check`] for a program that passes its step to
    /// [`ForceModeStepper::compute_forces`]: also `dt` must be the step rapier integrates with
    /// (`params.dt`), else [`CouplingError::TimeStepMismatch`] (the law would advance the
    /// histories by one step while rapier moves the bodies by another).
    pub fn check_step(
        &self,
        params: &IntegrationParameters,
        colliders: &ColliderSet,
        dt: f64,
    ) -> Result<()> {
        self.check(params, colliders)?;
        if dt != params.dt {
            return Err(CouplingError::TimeStepMismatch {
                coupling: dt,
                world: params.dt,
                fix: "pass the integration parameters' dt to compute_forces (set by \
                      `ForceModeStepper::configure`)",
            });
        }
        Ok(())
    }

    /// Steps 1–4: candidates, geometry, history merge and per-pair wrenches, from the poses and
    /// velocities in `bodies`/`colliders`. Does not touch the bodies. No user hooks: see
    /// [`ForceModeStepper::compute_forces_with`]. No checks: a program that runs its own
    /// pipeline calls [`ForceModeStepper::check_step`] first.
    pub fn compute_forces(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        narrow_phase: &NarrowPhase,
        dt: f64,
    ) -> Result<()> {
        self.compute_forces_with(bodies, colliders, narrow_phase, dt, &())
    }

    /// [`ForceModeStepper::compute_forces`] honouring the user's `hooks`: a candidate pair in
    /// which either collider has `ActiveHooks::FILTER_CONTACT_PAIRS` gets the law's force only
    /// when `hooks.filter_contact_pair` returns solver flags with `COMPUTE_RIGID_IMPULSES` (as
    /// rapier would solve it); pairs whose collision groups do not interact get none either.
    /// A contact that begins with a step above the stability limit of symplectic Euler at its
    /// approach speed is an error ([`CouplingError::TimeStepTooLarge`]).
    pub fn compute_forces_with(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        narrow_phase: &NarrowPhase,
        dt: f64,
        hooks: &dyn PhysicsHooks,
    ) -> Result<()> {
        let t0 = Instant::now();
        let particles = &self.particles;
        self.candidates.clear();
        self.unhandled.clear();
        let (mut rapier_pairs, mut filtered) = (0, 0);
        for pair in narrow_phase.contact_pairs() {
            let (a, b) = (particles.get(pair.collider1), particles.get(pair.collider2));
            let law_pair = match (a, b) {
                (Some(a), Some(b)) => {
                    !(a.body.is_some() && a.body == b.body)
                        && (a.radius().is_some() || b.radius().is_some())
                }
                _ => false,
            };
            if !law_pair {
                match rapier_response(pair) {
                    Some(true) => rapier_pairs += 1,
                    Some(false) => {
                        if let Some(unhandled) = unhandled_pair(a, b, pair) {
                            self.unhandled.push(unhandled);
                        }
                    }
                    None => {}
                }
                continue;
            }
            let (a, b) = (a.expect("law pair"), b.expect("law pair"));
            match filter_verdict(bodies, colliders, a, b, hooks) {
                Verdict::Law => {}
                Verdict::Filtered => {
                    filtered += 1;
                    continue;
                }
                Verdict::NoInteraction => continue,
            }
            // Body 1 is a sphere; between two spheres, the one with the smaller index.
            let (sphere, other) = match (a.shape, b.shape) {
                (ParticleShape::Sphere { .. }, ParticleShape::Sphere { .. }) => {
                    if a.collider.into_raw_parts().0 <= b.collider.into_raw_parts().0 {
                        (a, b)
                    } else {
                        (b, a)
                    }
                }
                (ParticleShape::Sphere { .. }, ParticleShape::Surface) => (a, b),
                (ParticleShape::Surface, _) => (b, a),
            };
            self.candidates.push(Candidate {
                key: PairKey::new(sphere.collider, other.collider),
                sphere: sphere.collider,
                other: other.collider,
                contact: None,
            });
        }
        let t1 = Instant::now();
        self.candidates.par_iter_mut().for_each(|c| {
            c.contact = pair_geometry(particles, colliders, (c.sphere, c.other), Reach::Touching);
        });
        self.candidates.par_sort_unstable_by_key(|c| c.key);
        keep_held_contacts(&self.store, particles, colliders, &mut self.candidates);
        let t2 = Instant::now();

        for c in &self.candidates {
            if let Some(contact) = &c.contact {
                if self.store.get(c.key).is_none() {
                    check_stability(particles, bodies, c, contact, dt)?;
                }
            }
        }
        let (created0, removed0) = (self.store.created(), self.store.removed());
        let (model, pair_normals) = (&self.model, &self.pair_normals);
        let rolling = &self.rolling;
        self.store.merge(
            self.candidates.iter().filter(|c| c.contact.is_some()),
            |c| c.key,
            |c| {
                let p1 = particles.get(c.sphere).expect("registered");
                let p2 = particles.get(c.other).expect("registered");
                let body1 = p1.body.expect("a sphere has a body");
                let pair = bind_pair(particles, bodies, p1, p2)?;
                Ok(ForceContact {
                    key: c.key,
                    collider1: c.sphere,
                    collider2: c.other,
                    body1,
                    body2: p2.body,
                    law: pair_normals.bind(model, p1.material, p2.material, &pair)?,
                    rolling: rolling.bind(&pair)?,
                    history: PairHistory::default(),
                    contact: c.contact.expect("filtered"),
                    wrench: PairWrench::default(),
                })
            },
            |entry, c| entry.contact = c.contact.expect("filtered"),
        )?;
        let sphere_sphere = self
            .store
            .entries()
            .iter()
            .filter(|e| {
                particles
                    .get(e.collider2)
                    .is_some_and(|p| p.radius().is_some())
            })
            .count();
        self.report = StepReport {
            contacts: self.store.len(),
            sphere_sphere,
            sphere_surface: self.store.len() - sphere_sphere,
            rapier_pairs,
            filtered,
            unhandled: self.unhandled.len(),
            candidates: self.candidates.len(),
            created: self.store.created() - created0,
            removed: self.store.removed() - removed0,
            max_speed: 0.0,
            prediction_distance_ok: true,
            timings: PhaseTimings::default(),
        };
        let t3 = Instant::now();

        self.store.entries_mut().par_iter_mut().for_each(|entry| {
            let kinematics = kinematics(bodies, entry.body1, entry.body2, &entry.contact);
            entry.wrench = evaluate_pair(
                &entry.law,
                &entry.rolling,
                &mut entry.history,
                &kinematics,
                dt,
            );
        });

        let t4 = Instant::now();
        // Deterministic reduction: entries are sorted by key, each body sums in that order.
        for entry in self.store.entries() {
            let w = &entry.wrench;
            let i = entry.body1.into_raw_parts().0 as usize;
            accumulate(&mut self.wrenches, i, w.force, w.torque1);
            if let Some(b2) = entry.body2 {
                if bodies[b2].is_dynamic() {
                    let j = b2.into_raw_parts().0 as usize;
                    accumulate(&mut self.wrenches, j, -w.force, w.torque2);
                }
            }
        }
        let t5 = Instant::now();
        self.report.timings = PhaseTimings {
            candidates: (t1 - t0).as_secs_f64(),
            geometry: (t2 - t1).as_secs_f64(),
            merge: (t3 - t2).as_secs_f64(),
            kernel: (t4 - t3).as_secs_f64(),
            reduction: (t5 - t4).as_secs_f64(),
            apply: 0.0,
        };
        Ok(())
    }

    /// Step 5: add the contact wrenches of [`ForceModeStepper::compute_forces`] to the forces
    /// the user put on every registered dynamic body (`add_force` / `add_torque`, which rapier
    /// keeps from step to step). After `PhysicsPipeline::step`,
    /// [`ForceModeStepper::give_back_user_forces`] leaves each body with the user's own forces
    /// again; without it the next call still adds to the user's own (it recognises its own
    /// write), but between the steps the bodies hold the user's forces plus the wrenches.
    pub fn apply_forces(&mut self, bodies: &mut RigidBodySet) {
        let started = Instant::now();
        let mut max_speed2: f64 = 0.0;
        for particle in self.particles.iter() {
            let Some(handle) = particle.body else {
                continue;
            };
            let i = handle.into_raw_parts().0 as usize;
            if self.written.len() <= i {
                self.written.resize(i + 1, false);
            }
            if self.written[i] {
                continue;
            }
            let Some(body) = bodies.get_mut(handle) else {
                continue;
            };
            if !body.is_dynamic() {
                continue;
            }
            self.written[i] = true;
            max_speed2 = max_speed2.max(body.linvel().length_squared());
            let (force, torque) = match self.wrenches.get_mut(i) {
                Some(w) => {
                    let wrench = (to_glam(&w.0), to_glam(&w.1));
                    *w = (Vector3::zeros(), Vector3::zeros());
                    wrench
                }
                None => (Vector::ZERO, Vector::ZERO),
            };
            self.added.add(handle, body, force, torque);
        }
        for particle in self.particles.iter() {
            if let Some(handle) = particle.body {
                if let Some(flag) = self.written.get_mut(handle.into_raw_parts().0 as usize) {
                    *flag = false;
                }
            }
        }
        self.report.max_speed = max_speed2.sqrt();
        self.report.timings.apply = started.elapsed().as_secs_f64();
    }

    /// Step 7, after `PhysicsPipeline::step`: give every body that
    /// [`ForceModeStepper::apply_forces`] wrote the user's own force and torque back, as if
    /// the coupling had never added to them ([`ForceModeStepper::step_with`] does it).
    pub fn give_back_user_forces(&mut self, bodies: &mut RigidBodySet) {
        self.added.give_back(bodies);
    }
}

/// The parameters [`ForceModeStepper::configure`] sets, checked before a step.
fn check_configured(params: &IntegrationParameters) -> Result<()> {
    let problem = if params.num_solver_iterations != 1 {
        format!(
            "{} solver iterations instead of 1 (the force would be applied more than once)",
            params.num_solver_iterations
        )
    } else if params.max_ccd_substeps != 0 {
        format!(
            "{} CCD substeps instead of 0 (CCD would move soft spheres apart)",
            params.max_ccd_substeps
        )
    } else if params.normalized_max_linear_velocity != f64::MAX {
        "rapier's speed cap is on (it would clip impact speeds)".to_owned()
    } else if !(params.dt.is_finite() && params.dt > 0.0) {
        format!("dt = {} is not a positive step", params.dt)
    } else {
        return Ok(());
    };
    Err(CouplingError::NotConfigured(problem))
}

/// Whether rapier's solver acts on a pair with contacts: `None` without contacts.
fn rapier_response(pair: &rapier3d_f64::geometry::ContactPair) -> Option<bool> {
    let mut touching = false;
    for m in pair.solver_manifolds() {
        if !m.data.solver_contacts.is_empty() {
            if m.data
                .solver_flags
                .contains(SolverFlags::COMPUTE_RIGID_IMPULSES)
            {
                return Some(true);
            }
            touching = true;
        }
    }
    touching.then_some(false)
}

/// A pair with contacts but no solver response in which a registered sphere meets an
/// unregistered collider (any other such pair is the user's choice: their filter or groups).
fn unhandled_pair(
    a: Option<&Particle>,
    b: Option<&Particle>,
    pair: &rapier3d_f64::geometry::ContactPair,
) -> Option<UnhandledPair> {
    match (a, b) {
        (Some(p), None) if p.radius().is_some() => Some(UnhandledPair {
            sphere: p.collider,
            other: pair.collider2,
        }),
        (None, Some(p)) if p.radius().is_some() => Some(UnhandledPair {
            sphere: p.collider,
            other: pair.collider1,
        }),
        _ => None,
    }
}

/// Who answers for a law candidate pair.
enum Verdict {
    /// The law.
    Law,
    /// Nobody: the user's filter rejected it.
    Filtered,
    /// Nobody: the collision groups do not interact (rapier computes no contact either).
    NoInteraction,
}

/// The user's say on a law candidate, as rapier's narrow phase would ask it.
fn filter_verdict(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    a: &Particle,
    b: &Particle,
    hooks: &dyn PhysicsHooks,
) -> Verdict {
    let (Some(co1), Some(co2)) = (colliders.get(a.collider), colliders.get(b.collider)) else {
        return Verdict::NoInteraction;
    };
    if !co1.collision_groups().test(co2.collision_groups()) {
        return Verdict::NoInteraction;
    }
    if !(co1.active_hooks() | co2.active_hooks()).contains(ActiveHooks::FILTER_CONTACT_PAIRS) {
        return Verdict::Law;
    }
    let context = PairFilterContext {
        bodies,
        colliders,
        collider1: a.collider,
        collider2: b.collider,
        rigid_body1: a.body,
        rigid_body2: b.body,
    };
    match hooks.filter_contact_pair(&context) {
        Some(flags) if flags.contains(SolverFlags::COMPUTE_RIGID_IMPULSES) => Verdict::Law,
        _ => Verdict::Filtered,
    }
}

/// A contact that begins must be resolvable: `dt` below the stability limit `2 √(m / k_max)`
/// of the Hertz contact at its approach speed ([`stable_time_step`]).
fn check_stability(
    particles: &ParticleSet,
    bodies: &RigidBodySet,
    candidate: &Candidate,
    contact: &SurfaceContact,
    dt: f64,
) -> Result<()> {
    let (Some(p1), Some(p2)) = (
        particles.get(candidate.sphere),
        particles.get(candidate.other),
    ) else {
        return Ok(());
    };
    let velocity = |h: Option<RigidBodyHandle>| {
        h.and_then(|h| bodies.get(h))
            .map_or(Vector3::zeros(), |b| to_na(b.linvel()))
    };
    let approach = -(velocity(p1.body) - velocity(p2.body)).dot(&contact.normal);
    if approach.is_nan() || approach <= 0.0 {
        return Ok(());
    }
    let Ok(pair) = bind_pair(particles, bodies, p1, p2) else {
        return Ok(());
    };
    let advice = stable_time_step(&pair, approach, 1.0)?;
    if dt > advice.stability_limit {
        return Err(CouplingError::TimeStepTooLarge {
            dt,
            limit: advice.stability_limit,
            contact_time: advice.contact_time,
            collider1: candidate.sphere,
            collider2: candidate.other,
        });
    }
    Ok(())
}

/// The pair quantities of sphere `p1` against `p2` (sphere or surface): `E*`, `G*`, effective
/// radius (the sphere's against a surface) and reduced mass (the sphere's against a fixed body).
fn bind_pair(
    particles: &ParticleSet,
    bodies: &RigidBodySet,
    p1: &Particle,
    p2: &Particle,
) -> Result<ContactPair> {
    let body1 = p1.body.ok_or(CouplingError::NoParentBody(p1.collider))?;
    let m1 = bodies
        .get(body1)
        .ok_or(CouplingError::UnknownBody(body1))?
        .mass();
    let m2 = p2
        .body
        .and_then(|h| bodies.get(h))
        .filter(|b| b.is_dynamic())
        .map_or(f64::INFINITY, |b| b.mass());
    let r1 = p1.radius().ok_or(CouplingError::NotABall(p1.collider))?;
    let radius = match p2.radius() {
        Some(r2) => r1 * r2 / (r1 + r2),
        None => r1,
    };
    let mass = if m2.is_finite() {
        m1 * m2 / (m1 + m2)
    } else {
        m1
    };
    let (e_star, g_star) = particles.pair_moduli(p1.material, p2.material);
    Ok(ContactPair::new(e_star, g_star, radius, mass)?)
}

fn accumulate(
    wrenches: &mut Vec<(Vector3<f64>, Vector3<f64>)>,
    index: usize,
    force: Vector3<f64>,
    torque: Vector3<f64>,
) {
    if wrenches.len() <= index {
        wrenches.resize(index + 1, (Vector3::zeros(), Vector3::zeros()));
    }
    wrenches[index].0 += force;
    wrenches[index].1 += torque;
}

/// How far apart a pair's geometry is computed.
#[derive(Clone, Copy)]
enum Reach {
    /// Only while the bodies overlap (a candidate pair).
    Touching,
    /// At any distance, with a negative overlap while apart (a pair whose contact still holds).
    AnyDistance,
}

/// Exact contact of a pair at the current poses.
fn pair_geometry(
    particles: &ParticleSet,
    colliders: &ColliderSet,
    (sphere, other): (ColliderHandle, ColliderHandle),
    reach: Reach,
) -> Option<SurfaceContact> {
    let p1 = particles.get(sphere)?;
    let p2 = particles.get(other)?;
    let co1 = colliders.get(sphere)?;
    let co2 = colliders.get(other)?;
    let c1 = to_na(co1.position().translation);
    let r1 = p1.radius()?;
    let c2 = to_na(co2.position().translation);
    match (p2.radius(), reach) {
        (Some(r2), Reach::Touching) => sphere_sphere(&c1, r1, &c2, r2),
        (Some(r2), Reach::AnyDistance) => sphere_sphere_signed(&c1, r1, &c2, r2),
        (None, Reach::Touching) => sphere_shape(&c1, r1, co2.shape(), co2.position()),
        (None, Reach::AnyDistance) => sphere_shape_signed(&c1, r1, co2.shape(), co2.position()),
    }
}

/// Keep every stored contact whose law still holds adhesively
/// ([`mdr_contact::normal::NormalLaw::holds`]) among the `candidates` (sorted by key), with its
/// geometry at any distance ([`sphere_sphere_signed`], [`sphere_shape_signed`]): its neck
/// outlives geometric contact, and may outlive the narrow phase's pair (whose AABBs are
/// enlarged by the prediction distance only), so the store, not the narrow phase, says which
/// pairs are held; the law is evaluated on them at their (negative) overlap until it lets go.
fn keep_held_contacts<NL, TL, DL, RL>(
    store: &ContactStore<ForceContact<NL, TL, DL, RL>>,
    particles: &ParticleSet,
    colliders: &ColliderSet,
    candidates: &mut Vec<Candidate>,
) where
    NL: NormalLaw,
    TL: mdr_contact::tangential::TangentialLaw,
    RL: RollingLaw,
{
    let mut added = false;
    for entry in store.entries() {
        if !entry.law.normal.holds(&entry.history.contact.normal) {
            continue;
        }
        let geometry = pair_geometry(
            particles,
            colliders,
            (entry.collider1, entry.collider2),
            Reach::AnyDistance,
        );
        match candidates.binary_search_by_key(&entry.key, |c| c.key) {
            Ok(k) => {
                if candidates[k].contact.is_none() {
                    candidates[k].contact = geometry;
                }
            }
            Err(_) => {
                candidates.push(Candidate {
                    key: entry.key,
                    sphere: entry.collider1,
                    other: entry.collider2,
                    contact: geometry,
                });
                added = true;
            }
        }
    }
    if added {
        candidates.sort_unstable_by_key(|c| c.key);
    }
}

/// Velocities and lever arms of a touching pair.
fn kinematics(
    bodies: &RigidBodySet,
    body1: RigidBodyHandle,
    body2: Option<RigidBodyHandle>,
    contact: &SurfaceContact,
) -> ContactKinematics {
    let b1 = &bodies[body1];
    let (linvel2, angvel2, arm2) = match body2.and_then(|h| bodies.get(h)) {
        Some(b2) => (
            to_na(b2.linvel()),
            to_na(b2.angvel()),
            contact.point - to_na(b2.center_of_mass()),
        ),
        None => (Vector3::zeros(), Vector3::zeros(), Vector3::zeros()),
    };
    ContactKinematics {
        overlap: contact.overlap,
        normal: contact.normal,
        arms: Arms {
            arm1: contact.point - to_na(b1.center_of_mass()),
            arm2,
        },
        linvel1: to_na(b1.linvel()),
        angvel1: to_na(b1.angvel()),
        linvel2,
        angvel2,
    }
}
