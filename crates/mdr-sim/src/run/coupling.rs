//! The two force-mode paths of a scene behind one interface each, whichever the scene's laws:
//! [`NeighbourListScene`] (the stepper with its own neighbour lists) and [`RapierPipelineScene`]
//! (rapier's broad and narrow phase). Each is implemented once, generically, for the stepper
//! compiled with the scene's normal law `N` (and, on the neighbour-list path, its rolling model
//! `R`: none, or the registered rolling laws' enum), the tangential and damping laws being the
//! registered laws' enums ([`AnyTangential`], [`AnyDamping`]): the run calls a path through its interface once per step or per output, and the pair
//! loop inside runs the monomorphised law, with no call through the interface per contact.
//! The registry ([`crate::laws::registry`]) picks the compiled stepper by the law's name.

use super::books::Books;
use super::records::{ContactRecord, NeighbourListRecord};
use crate::error::SimError;
use crate::laws::{AnyDamping, AnyRolling, AnyTangential, SceneNormal, SceneRolling};
use crate::output::energy::EnergyRow;
use crate::output::vtk::ContactFrame;
use crate::scene::Scene;
use mdr_contact::model::ContactModel;
use mdr_contact::rolling::{NoRolling, RollingLaw};
use mdr_contact::tangential::TangentialLaw;
use mdr_contact::Material;
use mdr_rapier::geometry::{SurfaceContact, SurfaceOfRevolution};
use mdr_rapier::kernel::{ContactWorks, PairWrench};
use mdr_rapier::neighbour_list::particles::NeighbourListParticles;
use mdr_rapier::neighbour_list::{
    Boundary, NeighbourListStepReport, NeighbourListStepper, StepTimings,
};
use mdr_rapier::particles::{MaterialHandle, SphereBuilder};
use mdr_rapier::ForceModeStepper;
use rapier3d_f64::prelude::*;
use std::path::Path;

/// The neighbour-list stepper of a scene with normal model `N` and rolling model `R`.
pub type NeighbourListSceneStepper<N, R> = NeighbourListStepper<N, AnyTangential, AnyDamping, R>;

/// The rapier pipeline stepper of a scene with normal model `N`.
pub type RapierPipelineSceneStepper<N> = ForceModeStepper<N, AnyTangential, AnyDamping, AnyRolling>;

/// A scene's neighbour-list stepper, whichever its laws: what the run does with it.
pub trait NeighbourListScene: Send + Sync {
    /// The spheres.
    fn particles(&self) -> &NeighbourListParticles;
    /// The spheres, to move them (sinks, checkpoints).
    fn particles_mut(&mut self) -> &mut NeighbourListParticles;
    /// Neighbour-list builds so far.
    fn rebuilds(&self) -> u64;
    /// Sphere pairs in the neighbour list.
    fn listed_pairs(&self) -> usize;
    /// What the last step did.
    fn last_report(&self) -> NeighbourListStepReport;
    /// Build the neighbour lists at the next step (after particles jumped).
    fn request_rebuild(&mut self);
    /// Time each part of the steps from now on, or stop ([`NeighbourListStepper::time_steps`]).
    fn time_steps(&mut self, on: bool);
    /// Time per part of the steps while timed.
    fn step_timings(&self) -> Option<StepTimings>;

    /// Add a material.
    fn insert_material(&mut self, material: Material) -> MaterialHandle;
    /// Insert a wall collider as a surface of `material`.
    fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle, SimError>;
    /// Insert a wall collider touching as the exact surface of revolution `surface`.
    fn insert_surface_of_revolution(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
        surface: SurfaceOfRevolution,
    ) -> Result<ColliderHandle, SimError>;
    /// Bind the contacts between materials `a` and `b` with the scene's normal law at
    /// parameter `values` (declared order) in place of the scene's values.
    fn set_pair_normal(
        &mut self,
        a: MaterialHandle,
        b: MaterialHandle,
        values: &[f64],
    ) -> Result<(), SimError>;
    /// Add a sphere.
    fn insert_sphere(&mut self, sphere: SphereBuilder) -> Result<(), SimError>;
    /// Set rapier's integration parameters for step `dt`.
    fn configure(&self, params: &mut IntegrationParameters, dt: f64) -> Result<(), SimError>;
    /// The same stepper with the settings of scenes: the skin, energy books that take each
    /// contact's works once, when its history ends, and no orientations (no output reads a
    /// sphere's orientation and no sphere contact depends on it, as LAMMPS's
    /// `atom_style sphere`; spins are integrated).
    fn with_scene_settings(
        self: Box<Self>,
        scene: &Scene,
    ) -> Result<Box<dyn NeighbourListScene>, SimError>;

    /// Forces at the current positions (rebuilding the lists if due), every pair's wrench kept
    /// when `keep_wrenches`; then the step's books: the contacts that ended and the work of
    /// kinematic walls.
    fn compute_forces(
        &mut self,
        world: &PhysicsWorld,
        keep_wrenches: bool,
        books: &mut Books,
        dt: f64,
    ) -> Result<(), SimError>;
    /// Integrate the spheres and step rapier's wall bodies.
    fn advance(&mut self, world: &mut PhysicsWorld) -> Result<(), SimError>;

    /// Add each sphere's touching contacts to `counts` (indexed by particle).
    fn count_contacts(&self, counts: &mut [u32]);
    /// Each touching sphere–surface pair: `(particle, surface, overlap)`.
    fn for_each_surface_contact(&self, f: &mut dyn FnMut(usize, usize, f64));
    /// The books of the live contacts, added to the totals when the books are read; with
    /// `particle_plastic`, their plastic work per particle.
    fn live_works(&self, particle_plastic: Option<&mut [f64]>) -> ContactWorks;
    /// Add the live contacts' elastic energies to `row`, and count them.
    fn add_elastic_energies(&self, row: &mut EnergyRow);
    /// Add the live contacts to a contact-network frame.
    fn add_contact_network(&self, net: &mut ContactFrame);
    /// The lists and histories, for a checkpoint.
    fn record(&self) -> NeighbourListRecord;
    /// Put a checkpoint's lists and histories back (`path` names the checkpoint in errors).
    fn restore(
        &mut self,
        world: &PhysicsWorld,
        record: Option<&NeighbourListRecord>,
        path: &Path,
    ) -> Result<(), SimError>;
}

impl<N: SceneNormal, R: SceneRolling> NeighbourListScene for NeighbourListSceneStepper<N, R> {
    fn particles(&self) -> &NeighbourListParticles {
        NeighbourListStepper::particles(self)
    }
    fn particles_mut(&mut self) -> &mut NeighbourListParticles {
        NeighbourListStepper::particles_mut(self)
    }
    fn rebuilds(&self) -> u64 {
        NeighbourListStepper::rebuilds(self)
    }
    fn listed_pairs(&self) -> usize {
        self.pairs().len()
    }
    fn last_report(&self) -> NeighbourListStepReport {
        NeighbourListStepper::last_report(self)
    }
    fn request_rebuild(&mut self) {
        NeighbourListStepper::request_rebuild(self)
    }
    fn time_steps(&mut self, on: bool) {
        NeighbourListStepper::time_steps(self, on)
    }
    fn step_timings(&self) -> Option<StepTimings> {
        NeighbourListStepper::step_timings(self).copied()
    }

    fn insert_material(&mut self, material: Material) -> MaterialHandle {
        NeighbourListStepper::insert_material(self, material)
    }
    fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle, SimError> {
        Ok(NeighbourListStepper::insert_surface(
            self, world, collider, parent, material,
        )?)
    }
    fn insert_surface_of_revolution(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
        surface: SurfaceOfRevolution,
    ) -> Result<ColliderHandle, SimError> {
        Ok(NeighbourListStepper::insert_surface_of_revolution(
            self, world, collider, parent, material, surface,
        )?)
    }
    fn set_pair_normal(
        &mut self,
        a: MaterialHandle,
        b: MaterialHandle,
        values: &[f64],
    ) -> Result<(), SimError> {
        Ok(NeighbourListStepper::set_pair_normal(
            self,
            a,
            b,
            N::from_values(values)?,
        )?)
    }
    fn insert_sphere(&mut self, sphere: SphereBuilder) -> Result<(), SimError> {
        NeighbourListStepper::insert_sphere(self, sphere)?;
        Ok(())
    }
    fn configure(&self, params: &mut IntegrationParameters, dt: f64) -> Result<(), SimError> {
        Ok(NeighbourListStepper::configure(self, params, dt)?)
    }
    fn with_scene_settings(
        self: Box<Self>,
        scene: &Scene,
    ) -> Result<Box<dyn NeighbourListScene>, SimError> {
        Ok(Box::new(
            self.skin(super::build::skin(scene))?
                .record_ended_contacts(true)
                .track_orientation(false),
        ))
    }

    fn compute_forces(
        &mut self,
        world: &PhysicsWorld,
        keep_wrenches: bool,
        books: &mut Books,
        dt: f64,
    ) -> Result<(), SimError> {
        NeighbourListStepper::compute_forces(self, world, keep_wrenches)?;
        books.take_neighbour_list(self, &world.bodies, dt);
        Ok(())
    }
    fn advance(&mut self, world: &mut PhysicsWorld) -> Result<(), SimError> {
        NeighbourListStepper::advance(self, world)?;
        Ok(())
    }

    fn count_contacts(&self, counts: &mut [u32]) {
        let pairs = self.pairs();
        for q in (0..pairs.len()).filter(|&q| pairs.active[q]) {
            counts[pairs.i[q] as usize] += 1;
            counts[pairs.j[q] as usize] += 1;
        }
        let sp = self.surface_pairs();
        for q in (0..sp.len()).filter(|&q| sp.active[q]) {
            counts[sp.particle[q] as usize] += 1;
        }
    }
    fn for_each_surface_contact(&self, f: &mut dyn FnMut(usize, usize, f64)) {
        let sp = self.surface_pairs();
        for q in (0..sp.len()).filter(|&q| sp.active[q]) {
            f(
                sp.particle[q] as usize,
                sp.surface[q] as usize,
                sp.contact[q].overlap,
            );
        }
    }
    fn live_works(&self, particle_plastic: Option<&mut [f64]>) -> ContactWorks {
        Books::live_neighbour_list(self, particle_plastic)
    }
    fn add_elastic_energies(&self, row: &mut EnergyRow) {
        super::outputs::live_elastic_energies(self, row)
    }
    fn add_contact_network(&self, net: &mut ContactFrame) {
        super::outputs::live_contact_network(self, net)
    }
    fn record(&self) -> NeighbourListRecord {
        NeighbourListRecord::of(self)
    }
    fn restore(
        &mut self,
        world: &PhysicsWorld,
        record: Option<&NeighbourListRecord>,
        path: &Path,
    ) -> Result<(), SimError> {
        let state = record.and_then(|r| r.to_state::<N, R>()).ok_or_else(|| {
            crate::checkpoint::CheckpointError::Incompatible {
                path: path.to_path_buf(),
                reason: "it holds no valid neighbour-list state".to_owned(),
            }
        })?;
        self.import_lists(world, state)?;
        Ok(())
    }
}

/// The neighbour-list stepper of a scene whose normal model is `model.normal` (type `N`), with
/// the scene's rolling model: compiled for rolling resistance on or off, so that a scene
/// without it (`None`) runs with [`NoRolling`] (no rolling history, no rolling branch in the
/// pair loop; docs/performance.md).
pub fn neighbour_list_stepper<N: SceneNormal>(
    model: ContactModel<N, AnyTangential, AnyDamping>,
    rolling: Option<AnyRolling>,
    boundary: Boundary,
) -> Box<dyn NeighbourListScene> {
    let stepper = NeighbourListStepper::new(model, boundary);
    match rolling {
        Some(rolling) => {
            let s: NeighbourListSceneStepper<N, AnyRolling> = stepper.with_rolling(rolling);
            Box::new(s)
        }
        None => {
            let s: NeighbourListSceneStepper<N, NoRolling> = stepper;
            Box::new(s)
        }
    }
}

/// One touching pair of the rapier pipeline path, as the run reads it (geometry and wrench of
/// the current step; no law).
pub struct ContactView<'a> {
    /// Pair key.
    pub key: u64,
    /// The sphere.
    pub collider1: ColliderHandle,
    /// The other collider.
    pub collider2: ColliderHandle,
    /// Body of collider 1.
    pub body1: RigidBodyHandle,
    /// Body of collider 2, if any.
    pub body2: Option<RigidBodyHandle>,
    /// Geometry at the start of the step.
    pub contact: &'a SurfaceContact,
    /// Wrench of the step.
    pub wrench: &'a PairWrench,
}

/// A scene's rapier pipeline stepper, whichever its normal law: what the run does with it.
pub trait RapierPipelineScene: Send + Sync {
    /// Add a material.
    fn insert_material(&mut self, material: Material) -> MaterialHandle;
    /// Insert a wall collider as a surface of `material`.
    fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle, SimError>;
    /// Bind the contacts between materials `a` and `b` with the scene's normal law at
    /// parameter `values` (declared order) in place of the scene's values.
    fn set_pair_normal(
        &mut self,
        a: MaterialHandle,
        b: MaterialHandle,
        values: &[f64],
    ) -> Result<(), SimError>;
    /// Insert a sphere body and collider.
    fn insert_sphere(
        &mut self,
        world: &mut PhysicsWorld,
        sphere: SphereBuilder,
    ) -> Result<(RigidBodyHandle, ColliderHandle), SimError>;
    /// Set rapier's integration parameters for step `dt`.
    fn configure(
        &self,
        params: &mut IntegrationParameters,
        dt: f64,
        prediction_distance: f64,
    ) -> Result<(), SimError>;
    /// The coupling's checks ([`ForceModeStepper::check_step`]).
    fn check_step(
        &self,
        params: &IntegrationParameters,
        colliders: &ColliderSet,
        dt: f64,
    ) -> Result<(), SimError>;
    /// Forces at the current poses.
    fn compute_forces(&mut self, world: &PhysicsWorld, dt: f64) -> Result<(), SimError>;
    /// Take the step's increments into the energy books.
    fn take_books(
        &self,
        books: &mut Books,
        bodies: &RigidBodySet,
        particle_of_collider: &[usize],
        wall_of_collider: &[usize],
        dt: f64,
    );
    /// Apply the forces, step rapier's world, and give the user's forces back.
    fn advance(&mut self, world: &mut PhysicsWorld);
    /// Discard the forces of the last force pass (the bodies keep none of them).
    fn discard_forces(&mut self, bodies: &mut RigidBodySet);
    /// Touching pairs.
    fn contact_count(&self) -> usize;
    /// Each touching pair, in key order.
    fn for_each_contact(&self, f: &mut dyn FnMut(ContactView<'_>));
    /// The residual (plastic) overlap of each touching pair, in key order.
    fn residual_overlaps(&self) -> Vec<f64>;
    /// Add the touching pairs' elastic energies to `row`, and count them.
    fn add_elastic_energies(&self, row: &mut EnergyRow);
    /// The touching pairs' histories, for a checkpoint, in key order.
    fn records(&self) -> Vec<ContactRecord>;
    /// Give every touching pair the history of `records` (sorted by key), or a fresh one.
    fn restore(&mut self, records: &[ContactRecord]);
}

impl<N: SceneNormal> RapierPipelineScene for RapierPipelineSceneStepper<N> {
    fn insert_material(&mut self, material: Material) -> MaterialHandle {
        self.particles_mut().insert_material(material)
    }
    fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle, SimError> {
        Ok(ForceModeStepper::insert_surface(
            self, world, collider, parent, material,
        )?)
    }
    fn set_pair_normal(
        &mut self,
        a: MaterialHandle,
        b: MaterialHandle,
        values: &[f64],
    ) -> Result<(), SimError> {
        Ok(ForceModeStepper::set_pair_normal(
            self,
            a,
            b,
            N::from_values(values)?,
        )?)
    }
    fn insert_sphere(
        &mut self,
        world: &mut PhysicsWorld,
        sphere: SphereBuilder,
    ) -> Result<(RigidBodyHandle, ColliderHandle), SimError> {
        Ok(ForceModeStepper::insert_sphere(self, world, sphere)?)
    }
    fn configure(
        &self,
        params: &mut IntegrationParameters,
        dt: f64,
        prediction_distance: f64,
    ) -> Result<(), SimError> {
        Ok(ForceModeStepper::configure(
            self,
            params,
            dt,
            prediction_distance,
        )?)
    }
    fn check_step(
        &self,
        params: &IntegrationParameters,
        colliders: &ColliderSet,
        dt: f64,
    ) -> Result<(), SimError> {
        Ok(ForceModeStepper::check_step(self, params, colliders, dt)?)
    }
    fn compute_forces(&mut self, world: &PhysicsWorld, dt: f64) -> Result<(), SimError> {
        ForceModeStepper::compute_forces(
            self,
            &world.bodies,
            &world.colliders,
            &world.narrow_phase,
            dt,
        )?;
        Ok(())
    }
    fn take_books(
        &self,
        books: &mut Books,
        bodies: &RigidBodySet,
        particle_of_collider: &[usize],
        wall_of_collider: &[usize],
        dt: f64,
    ) {
        books.take(self, bodies, particle_of_collider, wall_of_collider, dt)
    }
    fn advance(&mut self, world: &mut PhysicsWorld) {
        self.apply_forces(&mut world.bodies);
        world.step();
        self.give_back_user_forces(&mut world.bodies);
    }
    fn discard_forces(&mut self, bodies: &mut RigidBodySet) {
        self.apply_forces(bodies);
        self.give_back_user_forces(bodies);
    }
    fn contact_count(&self) -> usize {
        self.contacts().len()
    }
    fn for_each_contact(&self, f: &mut dyn FnMut(ContactView<'_>)) {
        for e in self.contacts().entries() {
            f(ContactView {
                key: e.key.0,
                collider1: e.collider1,
                collider2: e.collider2,
                body1: e.body1,
                body2: e.body2,
                contact: &e.contact,
                wrench: &e.wrench,
            });
        }
    }
    fn residual_overlaps(&self) -> Vec<f64> {
        use mdr_contact::normal::NormalLaw;
        self.contacts()
            .entries()
            .iter()
            .map(|e| e.law.normal.residual_overlap(&e.history.contact.normal))
            .collect()
    }
    fn add_elastic_energies(&self, row: &mut EnergyRow) {
        for e in self.contacts().entries() {
            let report = e.law.report(&e.history.contact, e.contact.overlap);
            row.elastic_normal_j += report.normal_elastic_energy;
            row.elastic_tangential_j += e
                .law
                .tangential
                .elastic_energy(&e.history.contact.tangential);
            row.elastic_rolling_j += e.rolling.elastic_energy(&e.history.rolling);
        }
        row.contacts = self.contacts().len() as u64;
    }
    fn records(&self) -> Vec<ContactRecord> {
        self.contacts()
            .entries()
            .iter()
            .map(|e| ContactRecord::of::<N>(e.key.0, &e.history.contact, e.history.rolling))
            .collect()
    }
    fn restore(&mut self, records: &[ContactRecord]) {
        for entry in self.contacts_mut().entries_mut() {
            match records.binary_search_by_key(&entry.key.0, |r| r.key) {
                Ok(i) => {
                    entry.history.contact = records[i].contact_state::<N>();
                    entry.history.rolling = records[i].rolling;
                }
                Err(_) => entry.history = Default::default(),
            }
        }
    }
}

/// The rapier pipeline stepper of a scene whose normal model is `model.normal` (type `N`); a
/// scene without rolling resistance (`None`) runs [`NoRolling`] in its place (every contact of
/// this path carries the rolling history).
pub fn rapier_pipeline_stepper<N: SceneNormal>(
    model: ContactModel<N, AnyTangential, AnyDamping>,
    rolling: Option<AnyRolling>,
) -> Box<dyn RapierPipelineScene> {
    let rolling = rolling.unwrap_or(AnyRolling::NoRolling(NoRolling));
    let stepper: RapierPipelineSceneStepper<N> = ForceModeStepper::new(model).with_rolling(rolling);
    Box::new(stepper)
}
