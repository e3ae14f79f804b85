//! Force mode: soft spheres whose contact forces come from the law, integrated by rapier.
//!
//! Per step ([`ForceModeStepper::step`]):
//! 1. candidate pairs from rapier's narrow phase (pairs whose enlarged AABBs overlap), keyed by
//!    [`PairKey`];
//! 2. exact geometry at the current poses, in parallel ([`crate::geometry`]);
//! 3. the history store is merged with the touching pairs (sorted by key: history created at
//!    first touch, dropped at separation);
//! 4. the per-pair kernel ([`crate::kernel::evaluate_pair`]) in parallel;
//! 5. forces and torques reduced per body in key order (deterministic for any thread count) and
//!    written with `reset_forces`/`add_force`;
//! 6. `PhysicsPipeline::step` with one solver iteration: `v_{k+1} = v_k + dt F(x_k, v_k)/m`,
//!    `x_{k+1} = x_k + dt v_{k+1}` (symplectic Euler; see `docs/coupling.md`).

use crate::convert::{to_glam, to_na};
use crate::error::{positive, Result};
use crate::geometry::{sphere_shape, sphere_sphere, SurfaceContact};
use crate::kernel::{evaluate_pair, Arms, ContactKinematics, PairHistory, PairWrench};
use crate::particles::{MaterialHandle, ParticleSet, ParticleShape, SphereBuilder};
use crate::store::{ContactStore, Keyed, PairKey};
use mdr_contact::damping::{DampingModel, NoDamping};
use mdr_contact::model::{ContactLaw, ContactModel, StateOf};
use mdr_contact::normal::NormalModel;
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

/// What happened during one step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Touching pairs handled this step.
    pub contacts: usize,
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

/// The force-mode coupling: owns the contact model, the registered colliders and the history
/// store; call [`ForceModeStepper::step`] instead of `PhysicsWorld::step`.
pub struct ForceModeStepper<
    N: NormalModel,
    T: TangentialModel = Frictionless,
    D: DampingModel = NoDamping,
    R: RollingModel = NoRolling,
> {
    model: ContactModel<N, T, D>,
    rolling: R,
    particles: ParticleSet,
    store: ForceStore<N, T, D, R>,
    candidates: Vec<Candidate>,
    /// Force and torque accumulators by body arena index.
    wrenches: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// Bodies already written this step (by arena index).
    written: Vec<bool>,
    report: StepReport,
}

impl<N: NormalModel, T: TangentialModel, D: DampingModel> ForceModeStepper<N, T, D, NoRolling> {
    /// A stepper for `model` (normal + tangential + damping), no rolling resistance.
    pub fn new(model: ContactModel<N, T, D>) -> Self {
        Self {
            model,
            rolling: NoRolling,
            particles: ParticleSet::new(),
            store: ContactStore::new(),
            candidates: Vec::new(),
            wrenches: Vec::new(),
            written: Vec::new(),
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
            rolling,
            particles: self.particles,
            store: ContactStore::new(),
            candidates: self.candidates,
            wrenches: self.wrenches,
            written: self.written,
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

    /// The registered colliders and materials.
    pub fn particles(&self) -> &ParticleSet {
        &self.particles
    }

    /// The registered colliders and materials, mutably (to add materials or register colliders
    /// built by hand; such colliders need `solver_groups(InteractionGroups::none())`).
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

    /// Insert a sphere (dynamic body + ball collider, rapier's contact impulses off) and
    /// register it.
    pub fn insert_sphere(
        &mut self,
        world: &mut PhysicsWorld,
        sphere: SphereBuilder,
    ) -> Result<(RigidBodyHandle, ColliderHandle)> {
        self.particles.insert_sphere_flagged(world, sphere, |c| {
            c.solver_groups(InteractionGroups::none())
        })
    }

    /// Insert a collider of any shape (a wall, a box, a mesh …), optionally on a body, with
    /// rapier's contact impulses off, and register it as a surface of `material`.
    pub fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle> {
        self.particles
            .insert_surface_flagged(world, collider, parent, material, |c| {
                c.solver_groups(InteractionGroups::none())
            })
    }

    /// One coupled step of `world`: forces from the current poses, then `world.step()`.
    pub fn step(&mut self, world: &mut PhysicsWorld) -> Result<StepReport> {
        let dt = world.integration_parameters.dt;
        self.compute_forces(&world.bodies, &world.colliders, &world.narrow_phase, dt)?;
        self.apply_forces(&mut world.bodies);
        self.report.prediction_distance_ok =
            2.0 * self.report.max_speed * dt <= world.integration_parameters.prediction_distance();
        world.step();
        Ok(self.report)
    }

    /// Steps 1–4: candidates, geometry, history merge and per-pair wrenches, from the poses and
    /// velocities in `bodies`/`colliders`. Does not touch the bodies.
    pub fn compute_forces(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        narrow_phase: &NarrowPhase,
        dt: f64,
    ) -> Result<()> {
        let t0 = Instant::now();
        let particles = &self.particles;
        self.candidates.clear();
        for pair in narrow_phase.contact_pairs() {
            let (Some(a), Some(b)) = (particles.get(pair.collider1), particles.get(pair.collider2))
            else {
                continue;
            };
            if a.body.is_some() && a.body == b.body {
                continue;
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
                (ParticleShape::Surface, ParticleShape::Sphere { .. }) => (b, a),
                (ParticleShape::Surface, ParticleShape::Surface) => continue,
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
            c.contact = candidate_geometry(particles, colliders, c.sphere, c.other);
        });
        self.candidates.par_sort_unstable_by_key(|c| c.key);
        let t2 = Instant::now();

        let (created0, removed0) = (self.store.created(), self.store.removed());
        let model = &self.model;
        let rolling = &self.rolling;
        self.store.merge(
            self.candidates.iter().filter(|c| c.contact.is_some()),
            |c| c.key,
            |c| {
                let p1 = particles.get(c.sphere).expect("registered");
                let p2 = particles.get(c.other).expect("registered");
                let body1 = p1.body.expect("a sphere has a body");
                let m1 = bodies[body1].mass();
                let m2 = p2
                    .body
                    .map(|h| &bodies[h])
                    .filter(|b| b.is_dynamic())
                    .map_or(f64::INFINITY, |b| b.mass());
                let r1 = p1.radius().expect("body 1 is a sphere");
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
                let pair = ContactPair::new(e_star, g_star, radius, mass)?;
                Ok(ForceContact {
                    key: c.key,
                    collider1: c.sphere,
                    collider2: c.other,
                    body1,
                    body2: p2.body,
                    law: model.bind(&pair)?,
                    rolling: rolling.bind(&pair)?,
                    history: PairHistory::default(),
                    contact: c.contact.expect("filtered"),
                    wrench: PairWrench::default(),
                })
            },
            |entry, c| entry.contact = c.contact.expect("filtered"),
        )?;
        self.report = StepReport {
            contacts: self.store.len(),
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

    /// Step 5: replace the user forces of every registered dynamic body by the contact wrenches
    /// of [`ForceModeStepper::compute_forces`].
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
            body.reset_forces(false);
            body.reset_torques(false);
            if let Some(w) = self.wrenches.get_mut(i) {
                body.add_force(to_glam(&w.0), false);
                body.add_torque(to_glam(&w.1), false);
                *w = (Vector3::zeros(), Vector3::zeros());
            }
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

/// Exact contact of a candidate pair at the current poses.
fn candidate_geometry(
    particles: &ParticleSet,
    colliders: &ColliderSet,
    sphere: ColliderHandle,
    other: ColliderHandle,
) -> Option<SurfaceContact> {
    let p1 = particles.get(sphere)?;
    let p2 = particles.get(other)?;
    let co1 = colliders.get(sphere)?;
    let co2 = colliders.get(other)?;
    let c1 = to_na(co1.position().translation);
    let r1 = p1.radius()?;
    match p2.radius() {
        Some(r2) => sphere_sphere(&c1, r1, &to_na(co2.position().translation), r2),
        None => sphere_shape(&c1, r1, co2.shape(), co2.position()),
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
