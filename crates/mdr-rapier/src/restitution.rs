//! Restitution mode: hard spheres whose impacts rapier resolves with impulses, each manifold's
//! restitution set from the MDR law's energy route (docs/theory.md §4) at the approach speed and the
//! pair's plastic history.
//!
//! The history (the largest indentation `d_max` of the pair) lives in an [`ImpactHistory`]: a
//! thread-safe slab of atomic slots. A manifold's `user_data` holds its slot index + 1, so the
//! hook reaches the history with one atomic load; a pair-key index (sharded mutexes, touched only
//! when a manifold is new) lets a re-created manifold of the same pair find its old slot, so a
//! re-impact keeps the plastic state and a second, slower impact on the same spot is elastic.
//! The history ends by the law's rule, not rapier's: after each step
//! ([`RestitutionHooks::maintain`]) a pair whose surfaces are more than the history reach apart
//! (one effective radius by default, [`RestitutionHooks::history_reach`]) loses its crater,
//! whatever rapier's prediction distance and AABB margins keep in its narrow phase.
//!
//! The law is bound per material pair: every pair runs the hooks' MDR law and work of
//! adhesion, except the pairs of materials given their own with
//! [`RestitutionHooks::set_pair_normal`] (a scene's mixed `Δγ_ij` per material pair,
//! docs/theory.md §9.3), read where an impact's law is bound.

use crate::error::{positive, CouplingError, Result};
use crate::pair_models::PairNormals;
use crate::particles::{MaterialHandle, ParticleSet, SphereBuilder};
use crate::registration::{add_restitution_flags, check_restitution_flags};
use crate::restitution_law::adhesive_impact;
use crate::store::PairKey;
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic, MdrLaw, MdrState, NormalModel};
use mdr_contact::ContactPair;
use rapier3d_f64::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};

const SHARDS: usize = 64;
/// Segment `s` of the slab holds `FIRST_SEGMENT << s` slots.
const FIRST_SEGMENT_BITS: u32 = 6;
const SEGMENTS: usize = 26;
/// The key of a freed slot: no pair has it (collider indices are below `u32::MAX`).
const FREED: u64 = u64::MAX;

#[derive(Debug, Default)]
struct ImpactSlot {
    key: AtomicU64,
    /// `d_max` (m) as f64 bits; non-negative floats order like their bits, so `fetch_max` works.
    max_overlap: AtomicU64,
    impacts: AtomicU32,
}

/// Thread-safe per-pair impact history (largest indentation), reached through slot indices.
#[derive(Debug)]
pub struct ImpactHistory {
    index: Box<[Mutex<HashMap<u64, u32>>]>,
    segments: Box<[OnceLock<Box<[ImpactSlot]>>]>,
    next: AtomicU32,
    free: Mutex<Vec<u32>>,
}

impl Default for ImpactHistory {
    fn default() -> Self {
        Self {
            index: (0..SHARDS).map(|_| Mutex::new(HashMap::new())).collect(),
            segments: (0..SEGMENTS).map(|_| OnceLock::new()).collect(),
            next: AtomicU32::new(0),
            free: Mutex::new(Vec::new()),
        }
    }
}

#[inline]
fn locate(slot: u32) -> (usize, usize) {
    let v = slot as u64 + (1 << FIRST_SEGMENT_BITS);
    let top = 63 - v.leading_zeros();
    let segment = (top - FIRST_SEGMENT_BITS) as usize;
    (segment, (v - (1u64 << top)) as usize)
}

#[inline]
fn shard_of(key: u64) -> usize {
    // Fibonacci hashing spreads neighbouring indices over the shards.
    (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 58) as usize % SHARDS
}

impl ImpactHistory {
    /// An empty history.
    pub fn new() -> Self {
        Self::default()
    }

    fn slot(&self, slot: u32) -> &ImpactSlot {
        let (segment, offset) = locate(slot);
        let seg = self.segments[segment].get_or_init(|| {
            (0..(1usize << (FIRST_SEGMENT_BITS as usize + segment)))
                .map(|_| ImpactSlot::default())
                .collect()
        });
        &seg[offset]
    }

    /// The slot of a pair, created (with an empty history) if the pair has none.
    pub fn slot_for(&self, key: PairKey) -> u32 {
        let mut shard = self.index[shard_of(key.0)].lock().expect("history lock");
        if let Some(&slot) = shard.get(&key.0) {
            return slot;
        }
        let slot = self
            .free
            .lock()
            .expect("history lock")
            .pop()
            .unwrap_or_else(|| self.next.fetch_add(1, Ordering::Relaxed));
        let s = self.slot(slot);
        s.key.store(key.0, Ordering::Relaxed);
        s.max_overlap.store(0f64.to_bits(), Ordering::Relaxed);
        s.impacts.store(0, Ordering::Relaxed);
        shard.insert(key.0, slot);
        slot
    }

    /// The slot of a pair, if it has one.
    pub fn find(&self, key: PairKey) -> Option<u32> {
        self.index[shard_of(key.0)]
            .lock()
            .expect("history lock")
            .get(&key.0)
            .copied()
    }

    /// The pair key a slot belongs to.
    pub fn key(&self, slot: u32) -> PairKey {
        PairKey(self.slot(slot).key.load(Ordering::Relaxed))
    }

    /// The law state of a slot.
    pub fn state(&self, slot: u32) -> MdrState {
        MdrState {
            max_overlap: f64::from_bits(self.slot(slot).max_overlap.load(Ordering::Acquire)),
        }
    }

    /// Number of impacts committed to a slot.
    pub fn impacts(&self, slot: u32) -> u32 {
        self.slot(slot).impacts.load(Ordering::Relaxed)
    }

    /// Record an impact that reached `max_overlap` (m, ≥ 0): `d_max ← max(d_max, max_overlap)`.
    pub fn commit(&self, slot: u32, max_overlap: f64) {
        let s = self.slot(slot);
        s.max_overlap
            .fetch_max(max_overlap.max(0.0).to_bits(), Ordering::AcqRel);
        s.impacts.fetch_add(1, Ordering::Relaxed);
    }

    /// Number of pairs with a history.
    pub fn len(&self) -> usize {
        self.index
            .iter()
            .map(|s| s.lock().expect("history lock").len())
            .sum()
    }

    /// Whether no pair has a history.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Slots allocated so far (bounded by the largest number of simultaneous pairs).
    pub fn allocated(&self) -> u32 {
        self.next.load(Ordering::Relaxed)
    }

    /// Keep the pairs for which `keep` is true, and free the slots of the others.
    fn retain_pairs(&mut self, keep: impl Fn(PairKey) -> bool) {
        let Self {
            index,
            segments,
            free,
            ..
        } = self;
        let free = free.get_mut().expect("history lock");
        for shard in index.iter_mut() {
            shard.get_mut().expect("history lock").retain(|&key, slot| {
                let live = keep(PairKey(key));
                if !live {
                    // A manifold still holding this slot must not take it for its pair's.
                    let (segment, offset) = locate(*slot);
                    if let Some(seg) = segments[segment].get() {
                        seg[offset].key.store(FREED, Ordering::Relaxed);
                    }
                    free.push(*slot);
                }
                live
            });
        }
    }
}

/// Where the friction coefficient of a restitution-mode manifold comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FrictionRule {
    /// The colliders' own: rapier combines the two colliders' `friction` with their
    /// `friction_combine_rule` (default: the average) and the hook leaves it as it is.
    Colliders,
    /// One coefficient `μ` (≥ 0) for every pair of registered colliders.
    Uniform(f64),
}

/// Default reach of a pair's impact history, in effective radii (see
/// [`RestitutionHooks::history_reach`]).
pub const DEFAULT_HISTORY_REACH: f64 = 1.0;

/// What one restitution-mode step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RestitutionReport {
    /// Pairs of registered colliders with contacts, resolved with the law's restitution.
    pub law_pairs: usize,
    /// Impacts whose restitution came from the law this step.
    pub impacts: u64,
    /// Other pairs with contacts that rapier's solver handles as it would without the
    /// coupling (surface on surface, registered on unregistered, pairs without the plugin).
    pub rapier_pairs: usize,
    /// Pairs with a stored impact history (craters within reach).
    pub histories: usize,
}

/// The restitution-mode coupling: a `PhysicsHooks` value setting each manifold's restitution
/// from the MDR law (and, with [`FrictionRule::Uniform`], its friction). Step with
/// [`RestitutionHooks::step`] or [`RestitutionHooks::step_with`] (the user's hooks and event
/// handler); with an own `PhysicsPipeline`, bracket each `step` by
/// [`RestitutionHooks::prepare`] and [`RestitutionHooks::maintain`] and pass
/// [`RestitutionHooks::with_user`] (or the hooks themselves) to it.
///
/// ```
/// use mdr_rapier::prelude::*;
/// use mdr_rapier::rapier::prelude::*;
///
/// /// The user's own hooks (here: rapier's defaults).
/// struct GameHooks;
/// impl PhysicsHooks for GameHooks {}
///
/// let mut world = PhysicsWorld::default();
/// world.integration_parameters.dt = 1e-4;
/// let mut hooks =
///     RestitutionHooks::with_friction_rule(MdrElastoPlastic::paper(), FrictionRule::Colliders)
///         .unwrap();
/// let steel = hooks.particles_mut().insert_material(Material::paper_steel());
/// let floor = ColliderBuilder::new(SharedShape::halfspace(Vector::Y));
/// hooks.insert_surface(&mut world, floor, None, steel).unwrap();
/// let ball = SphereBuilder::new(0.00635, steel)
///     .translation(Vector::new(0.0, 0.007, 0.0))
///     .linvel(Vector::new(0.0, -1.0, 0.0));
/// let (ball, _) = hooks.insert_sphere(&mut world, ball).unwrap();
/// let mut impacts = 0;
/// for _ in 0..100 {
///     impacts += hooks.step_with(&mut world, &GameHooks, &()).unwrap().impacts;
/// }
/// // One impact, with the law's plastic loss.
/// let v = world.bodies[ball].linvel().y;
/// assert!(impacts == 1 && v > 0.5 && v < 1.0);
/// ```
#[derive(Debug)]
pub struct RestitutionHooks {
    model: MdrElastoPlastic,
    work_of_adhesion: f64,
    /// The laws of the material pairs bound with their own (MDR parameters, `Δγ`).
    pair_normals: PairNormals<AdhesiveMdr>,
    friction: FrictionRule,
    /// The step of the last [`RestitutionHooks::prepare`].
    dt: Option<f64>,
    /// The step declared with [`RestitutionHooks::set_time_step`].
    declared_dt: Option<f64>,
    prepared: bool,
    history_reach: f64,
    particles: ParticleSet,
    history: ImpactHistory,
    unprepared: AtomicBool,
    impacts: AtomicU64,
    report: RestitutionReport,
}

impl RestitutionHooks {
    /// Hooks for the MDR law `model` and one Coulomb friction coefficient `friction` (≥ 0) for
    /// every registered pair ([`FrictionRule::Uniform`]).
    pub fn new(model: MdrElastoPlastic, friction: f64) -> Result<Self> {
        Self::with_friction_rule(model, FrictionRule::Uniform(friction))
    }

    /// Hooks for the MDR law `model` with friction by `rule`; [`FrictionRule::Colliders`] takes
    /// each pair's friction from its colliders.
    pub fn with_friction_rule(model: MdrElastoPlastic, rule: FrictionRule) -> Result<Self> {
        if let FrictionRule::Uniform(mu) = rule {
            if !(mu.is_finite() && mu >= 0.0) {
                return Err(crate::CouplingError::OutOfRange {
                    name: "mu",
                    value: mu,
                    range: "[0, inf)",
                });
            }
        }
        Ok(Self {
            model,
            work_of_adhesion: 0.0,
            pair_normals: PairNormals::default(),
            friction: rule,
            dt: None,
            declared_dt: None,
            prepared: false,
            history_reach: DEFAULT_HISTORY_REACH,
            particles: ParticleSet::new(),
            history: ImpactHistory::new(),
            unprepared: AtomicBool::new(false),
            impacts: AtomicU64::new(0),
            report: RestitutionReport::default(),
        })
    }

    /// Adhesive contacts with the work of adhesion `work_of_adhesion` (J/m², finite, ≥ 0; the
    /// adhesive MDR law, docs/theory.md §9): an impact's rebound pays the adhesive hysteresis
    /// of its unloading ([`crate::restitution_law::adhesive_impact`]), and an impact whose
    /// rebound energy that takes whole sticks: zero normal rebound.
    pub fn with_work_of_adhesion(mut self, work_of_adhesion: f64) -> Result<Self> {
        mdr_contact::normal::AdhesiveMdr::new(self.model, work_of_adhesion)?;
        self.work_of_adhesion = work_of_adhesion;
        Ok(self)
    }

    /// The work of adhesion `Δγ` (J/m²) of the pairs without a law of their own
    /// ([`RestitutionHooks::set_pair_normal`]).
    pub fn work_of_adhesion(&self) -> f64 {
        self.work_of_adhesion
    }

    /// Bind the impacts between materials `a` and `b` (sphere–sphere and sphere–surface,
    /// either order) with the adhesive MDR law `normal` (its MDR parameters and work of
    /// adhesion, zero for the plain MDR law) in place of the hooks' own: e.g. a scene's mixed
    /// `Δγ_ij = √(Δγ_i Δγ_j)` per material pair (docs/theory.md §9.3). Each impact binds its
    /// pair's law when it happens, so this may be called between steps; a pair's crater
    /// history stays as it is.
    ///
    /// ```
    /// use mdr_rapier::mdr_contact::normal::AdhesiveMdr;
    /// use mdr_rapier::prelude::*;
    ///
    /// let model = MdrElastoPlastic::paper();
    /// let mut hooks = RestitutionHooks::new(model, 0.0)
    ///     .unwrap()
    ///     .with_work_of_adhesion(0.5)
    ///     .unwrap();
    /// let powder = hooks.particles_mut().insert_material(Material::paper_steel());
    /// let steel = hooks.particles_mut().insert_material(Material::paper_steel());
    /// // Powder on steel adheres with √(0.5 · 0) = 0: the plain MDR law's rebound.
    /// hooks
    ///     .set_pair_normal(powder, steel, AdhesiveMdr::new(model, 0.0).unwrap())
    ///     .unwrap();
    /// assert_eq!(hooks.pair_normal(steel, powder).work_of_adhesion(), 0.0);
    /// assert_eq!(hooks.pair_normal(powder, powder).work_of_adhesion(), 0.5);
    /// ```
    pub fn set_pair_normal(
        &mut self,
        a: MaterialHandle,
        b: MaterialHandle,
        normal: AdhesiveMdr,
    ) -> Result<()> {
        self.particles.material(a)?;
        self.particles.material(b)?;
        self.pair_normals.set(a, b, normal);
        Ok(())
    }

    /// The law of the impacts between materials `a` and `b`: the one set by
    /// [`RestitutionHooks::set_pair_normal`], else the hooks' MDR law with their work of
    /// adhesion.
    pub fn pair_normal(&self, a: MaterialHandle, b: MaterialHandle) -> AdhesiveMdr {
        match self.pair_normals.get(a, b) {
            Some(normal) => *normal,
            None => AdhesiveMdr::new(self.model, self.work_of_adhesion)
                .expect("the hooks' work of adhesion is checked when set"),
        }
    }

    /// Keep a pair's impact history while the gap between its surfaces is below `reach`
    /// effective radii (> 0; default [`DEFAULT_HISTORY_REACH`]): the law's crater rule
    /// (docs/coupling.md, "History").
    pub fn history_reach(mut self, reach: f64) -> Result<Self> {
        self.history_reach = positive("history_reach", reach)?;
        Ok(self)
    }

    /// The friction rule.
    pub fn friction_rule(&self) -> FrictionRule {
        self.friction
    }

    /// The registered colliders and materials, mutably (to add materials; register colliders
    /// with [`RestitutionHooks::register_sphere`] / [`RestitutionHooks::register_surface`],
    /// which add the hook flag).
    pub fn particles_mut(&mut self) -> &mut ParticleSet {
        &mut self.particles
    }

    /// The registered colliders and materials.
    pub fn particles(&self) -> &ParticleSet {
        &self.particles
    }

    /// The impact history.
    pub fn history(&self) -> &ImpactHistory {
        &self.history
    }

    /// The report of the last [`RestitutionHooks::step_with`].
    pub fn last_report(&self) -> RestitutionReport {
        self.report
    }

    /// Declare the step the program steps rapier with (s, > 0). The hooks always take the
    /// step from the integration parameters ([`RestitutionHooks::prepare`], called by the step
    /// methods); once declared, a step whose integration parameters say otherwise is an error
    /// ([`CouplingError::TimeStepMismatch`]) instead of a silent change of step. Declare the
    /// new step when changing it.
    pub fn set_time_step(&mut self, dt: f64) -> Result<()> {
        self.declared_dt = Some(positive("dt", dt)?);
        Ok(())
    }

    /// Insert a sphere whose contacts go through the hook (hook flag added to the user's), and
    /// register it.
    pub fn insert_sphere(
        &mut self,
        world: &mut PhysicsWorld,
        sphere: SphereBuilder,
    ) -> Result<(RigidBodyHandle, ColliderHandle)> {
        self.insert_sphere_into(sphere, &mut world.bodies, &mut world.colliders)
    }

    /// [`RestitutionHooks::insert_sphere`] on rapier's sets.
    pub fn insert_sphere_into(
        &mut self,
        sphere: SphereBuilder,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
    ) -> Result<(RigidBodyHandle, ColliderHandle)> {
        self.particles
            .insert_sphere_into_sets(bodies, colliders, sphere, add_restitution_flags)
    }

    /// Insert a collider of any shape as a surface of `material`, optionally on a body (as
    /// `PhysicsWorld::insert_collider(collider, parent)`).
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

    /// [`RestitutionHooks::insert_surface`] on rapier's sets, in the order of
    /// `ColliderSet::insert_with_parent(collider, parent, bodies)`.
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
            add_restitution_flags,
        )
    }

    /// Register a ball collider already in `colliders` (on a rigid body) as a sphere of
    /// `material`, adding the hook flag to its active hooks.
    pub fn register_sphere(
        &mut self,
        collider: ColliderHandle,
        material: MaterialHandle,
        colliders: &mut ColliderSet,
    ) -> Result<()> {
        self.particles
            .register_sphere(colliders, collider, material)?;
        if let Some(co) = colliders.get_mut(collider) {
            add_restitution_flags(co);
        }
        Ok(())
    }

    /// Register a collider of any shape already in `colliders` as a surface of `material`,
    /// adding the hook flag to its active hooks.
    pub fn register_surface(
        &mut self,
        collider: ColliderHandle,
        material: MaterialHandle,
        colliders: &mut ColliderSet,
    ) -> Result<()> {
        self.particles
            .register_surface(colliders, collider, material)?;
        if let Some(co) = colliders.get_mut(collider) {
            add_restitution_flags(co);
        }
        Ok(())
    }

    /// Before a step: take the time step from `params` (it must be the one declared with
    /// [`RestitutionHooks::set_time_step`], if any) and check that every registered collider
    /// is in `colliders` with the hook flag.
    pub fn prepare(
        &mut self,
        params: &IntegrationParameters,
        colliders: &ColliderSet,
    ) -> Result<()> {
        let dt = positive("dt", params.dt)?;
        if let Some(declared) = self.declared_dt.filter(|&d| d != dt) {
            return Err(CouplingError::TimeStepMismatch {
                coupling: declared,
                world: dt,
                fix: "set the integration parameters' dt to the declared step, or declare the \
                      new one with `RestitutionHooks::set_time_step`",
            });
        }
        self.dt = Some(dt);
        for particle in self.particles.iter() {
            let co = colliders
                .get(particle.collider)
                .ok_or(CouplingError::UnknownCollider(particle.collider))?;
            check_restitution_flags(co, particle)?;
        }
        self.prepared = true;
        Ok(())
    }

    /// These hooks around the user's: `filter_contact_pair` and `filter_intersection_pair` are
    /// the user's; `modify_solver_contacts` runs the user's first where the user's own flags
    /// ask for it, then the law's on the pairs of registered colliders.
    pub fn with_user<'a>(&'a self, user: &'a dyn PhysicsHooks) -> WithUserHooks<'a> {
        WithUserHooks { mdr: self, user }
    }

    /// One step of `world` with these hooks, then [`RestitutionHooks::maintain`].
    pub fn step(&mut self, world: &mut PhysicsWorld) -> Result<()> {
        self.step_with(world, &(), &()).map(|_| ())
    }

    /// One step of `world` with these hooks composed with the user's `hooks`
    /// ([`RestitutionHooks::with_user`]) and the user's event handler: [`RestitutionHooks::prepare`],
    /// `world.step_with_events`, [`RestitutionHooks::maintain`].
    pub fn step_with(
        &mut self,
        world: &mut PhysicsWorld,
        hooks: &dyn PhysicsHooks,
        events: &dyn EventHandler,
    ) -> Result<RestitutionReport> {
        self.prepare(&world.integration_parameters, &world.colliders)?;
        world.step_with_events(&self.with_user(hooks), events);
        self.maintain(&world.colliders)?;
        let (mut law_pairs, mut rapier_pairs) = (0, 0);
        for pair in world.narrow_phase.contact_pairs() {
            if !pair.has_any_active_contact() {
                continue;
            }
            if self.is_law_pair(pair.collider1, pair.collider2) {
                law_pairs += 1;
            } else {
                rapier_pairs += 1;
            }
        }
        self.report = RestitutionReport {
            law_pairs,
            impacts: self.impacts.swap(0, Ordering::Relaxed),
            rapier_pairs,
            histories: self.history.len(),
        };
        Ok(self.report)
    }

    /// After a step: end the histories the law's rule ends (a pair whose surfaces are more
    /// than the history reach apart, see [`RestitutionHooks::history_reach`]; a pair whose
    /// collider left the set), and report hooks that ran without
    /// [`RestitutionHooks::prepare`] ([`CouplingError::TimeStepUnset`]).
    pub fn maintain(&mut self, colliders: &ColliderSet) -> Result<()> {
        let reach = self.history_reach;
        let particles = &self.particles;
        self.history.retain_pairs(|key| {
            pair_gap(particles, colliders, key).is_some_and(|(gap, r)| gap < reach * r)
        });
        self.prepared = false;
        if self.unprepared.swap(false, Ordering::Relaxed) {
            return Err(CouplingError::TimeStepUnset);
        }
        Ok(())
    }

    fn is_law_pair(&self, c1: ColliderHandle, c2: ColliderHandle) -> bool {
        match (self.particles.get(c1), self.particles.get(c2)) {
            (Some(a), Some(b)) => a.radius().is_some() || b.radius().is_some(),
            _ => false,
        }
    }

    /// The bound law of two registered colliders, its work of adhesion (J/m²) and the pair's
    /// reduced mass (kg).
    fn pair_law(
        &self,
        bodies: &RigidBodySet,
        ctx_bodies: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
        c1: ColliderHandle,
        c2: ColliderHandle,
    ) -> Option<(MdrLaw, f64, f64)> {
        let p1 = self.particles.get(c1)?;
        let p2 = self.particles.get(c2)?;
        let radius = match (p1.radius(), p2.radius()) {
            (Some(a), Some(b)) => a * b / (a + b),
            (Some(a), None) | (None, Some(a)) => a,
            (None, None) => return None,
        };
        let mass_of = |h: Option<RigidBodyHandle>| {
            h.and_then(|h| bodies.get(h))
                .filter(|b| b.is_dynamic())
                .map_or(f64::INFINITY, |b| b.mass())
        };
        let (m1, m2) = (mass_of(ctx_bodies.0), mass_of(ctx_bodies.1));
        let mass = match (m1.is_finite(), m2.is_finite()) {
            (true, true) => m1 * m2 / (m1 + m2),
            (true, false) => m1,
            (false, true) => m2,
            (false, false) => return None,
        };
        let (e_star, g_star) = self.particles.pair_moduli(p1.material, p2.material);
        let pair = ContactPair::new(e_star, g_star, radius, mass).ok()?;
        let (model, work_of_adhesion) = match self.pair_normals.get(p1.material, p2.material) {
            Some(normal) => (normal.params(), normal.work_of_adhesion()),
            None => (&self.model, self.work_of_adhesion),
        };
        Some((model.bind(&pair).ok()?, work_of_adhesion, mass))
    }

    /// The law's part of `modify_solver_contacts`.
    fn modify_law_contacts(&self, ctx: &mut ContactModificationContext) {
        let bodies = ctx.bodies;
        let (c1, c2) = (ctx.collider1, ctx.collider2);
        let (rb1, rb2) = (ctx.rigid_body1, ctx.rigid_body2);
        let Some((law, work_of_adhesion, mass)) = self.pair_law(bodies, (rb1, rb2), c1, c2) else {
            return;
        };
        let Some(dt) = self.dt.filter(|_| self.prepared) else {
            // Run without `prepare`: the step length is unknown; `maintain` reports it.
            self.unprepared.store(true, Ordering::Relaxed);
            return;
        };
        let Some(rigid) = ctx.rigid_mut() else {
            return;
        };
        if let FrictionRule::Uniform(mu) = self.friction {
            *rigid.friction = mu;
        }
        // Approach speed at the closest solver contact; the normal points out of collider 1.
        let n = *rigid.normal;
        let mut closest = f64::INFINITY;
        let mut approach = 0.0;
        for contact in rigid.solver_contacts.iter() {
            if contact.dist < closest {
                closest = contact.dist;
                let v1 = rb1
                    .and_then(|h| bodies.get(h))
                    .map_or(Vector::ZERO, |b| b.velocity_at_point(contact.anchor1));
                let v2 = rb2
                    .and_then(|h| bodies.get(h))
                    .map_or(Vector::ZERO, |b| b.velocity_at_point(contact.anchor2));
                approach = (v1 - v2).dot(n);
            }
        }
        if approach.is_nan() || approach <= 0.0 {
            // Separating or resting: rapier applies no bounce.
            return;
        }
        if closest > approach * dt {
            // The gap does not close in this step: no impact yet.
            defer_speculative_contacts(rigid.solver_contacts, approach, dt);
            return;
        }
        let key = PairKey::new(c1, c2);
        let mut slot = rigid.user_data.wrapping_sub(1);
        if *rigid.user_data == 0 || self.history.key(slot) != key {
            slot = self.history.slot_for(key);
            *rigid.user_data = slot + 1;
        }
        let state = self.history.state(slot);
        let kinetic = 0.5 * mass * approach * approach;
        self.impacts.fetch_add(1, Ordering::Relaxed);
        // Energy that fits within the old unloading branch is returned without adhesion:
        // elastic re-impact (docs/theory.md §4); skip the root solve.
        let restitution = if work_of_adhesion == 0.0
            && kinetic <= law.stored_energy(state.max_overlap, state.max_overlap)
        {
            1.0
        } else if let Ok(impact) = adhesive_impact(&law, work_of_adhesion, &state, mass, approach) {
            self.history.commit(slot, impact.state.max_overlap);
            impact.restitution
        } else {
            // An infinite approach speed (a diverged run): no bounce to add.
            1.0
        };
        *rigid.restitution = restitution;
    }
}

/// The gap between the surfaces of a registered pair (m; ≤ 0 when they overlap) and its
/// effective radius (m), from the colliders' current poses; `None` when a collider is gone or
/// the pair is not a law pair.
fn pair_gap(particles: &ParticleSet, colliders: &ColliderSet, key: PairKey) -> Option<(f64, f64)> {
    let (i, j) = ((key.0 >> 32) as u32, key.0 as u32);
    let (co1, h1) = colliders.get_unknown_gen(i)?;
    let (co2, h2) = colliders.get_unknown_gen(j)?;
    let (p1, p2) = (particles.get(h1)?, particles.get(h2)?);
    let centre = |co: &Collider| co.position().translation;
    match (p1.radius(), p2.radius()) {
        (Some(r1), Some(r2)) => Some((
            (centre(co1) - centre(co2)).length() - r1 - r2,
            r1 * r2 / (r1 + r2),
        )),
        (Some(r), None) => Some((
            co2.shape()
                .distance_to_point(co2.position(), centre(co1), true)
                - r,
            r,
        )),
        (None, Some(r)) => Some((
            co1.shape()
                .distance_to_point(co1.position(), centre(co2), true)
                - r,
            r,
        )),
        (None, None) => None,
    }
}

/// [`RestitutionHooks`] around a user's `PhysicsHooks` ([`RestitutionHooks::with_user`]).
pub struct WithUserHooks<'a> {
    mdr: &'a RestitutionHooks,
    user: &'a dyn PhysicsHooks,
}

impl PhysicsHooks for WithUserHooks<'_> {
    fn filter_contact_pair(&self, context: &PairFilterContext) -> Option<SolverFlags> {
        self.user.filter_contact_pair(context)
    }

    fn filter_intersection_pair(&self, context: &PairFilterContext) -> bool {
        self.user.filter_intersection_pair(context)
    }

    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let particles = &self.mdr.particles;
        let user_flags = |c: ColliderHandle| match particles.get(c) {
            Some(p) => p.user_hooks,
            None => context
                .colliders
                .get(c)
                .map_or(ActiveHooks::empty(), |co| co.active_hooks()),
        };
        if (user_flags(context.collider1) | user_flags(context.collider2))
            .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
        {
            self.user.modify_solver_contacts(context);
        }
        self.mdr.modify_law_contacts(context);
    }
}

/// Keep the contacts of a manifold that holds no impact in this step (a pair approaching at
/// `approach > 0` whose gap does not close within the step `dt`, or a separating pair), but put
/// them out of reach for this step, so that rapier solves them with zero impulse.
///
/// Left as they are, rapier's relax pass, which re-measures the gap after moving the bodies by
/// the whole step and caps the approach at (remaining gap)/`dt`, brakes an approaching pair whose
/// gap lies between `approach·dt` and `2·approach·dt` without any impact (a pre-contact loss hard
/// spheres do not have; with a restitution set it bounces the pair a step early instead).
/// Dropping the contacts avoids that but leaves the manifold points' last solved impulse in
/// place, and rapier decides whether the next impact is new, hence bouncy, from that impulse
/// being zero: after an impact, a pair whose contacts are dropped until it comes back (bodies
/// moved by hand, or a re-collision of the same pair while its manifold lives) then hits without
/// a bounce. Each contact's `dist` is therefore lifted to `max(dist, 0) + 2·|approach|·dt`: the
/// remaining gap after the step stays above `|approach|·dt`, an overlapping receding pair gets no
/// position bias, and the zero impulse marks the next impact as new (docs/coupling.md,
/// "Speculative contacts").
pub fn defer_speculative_contacts(contacts: &mut SolverContacts, approach: f64, dt: f64) {
    let margin = 2.0 * approach.abs() * dt;
    for contact in contacts.iter_mut() {
        contact.dist = contact.dist.max(0.0) + margin;
    }
}

impl PhysicsHooks for RestitutionHooks {
    fn modify_solver_contacts(&self, ctx: &mut ContactModificationContext) {
        self.modify_law_contacts(ctx);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slab_locations_are_contiguous() {
        assert_eq!(locate(0), (0, 0));
        assert_eq!(locate(63), (0, 63));
        assert_eq!(locate(64), (1, 0));
        assert_eq!(locate(64 + 127), (1, 127));
        assert_eq!(locate(64 + 128), (2, 0));
    }

    #[test]
    fn history_keeps_the_largest_indentation_and_frees_dead_pairs() {
        let mut h = ImpactHistory::new();
        let a = h.slot_for(PairKey(7));
        assert_eq!(h.slot_for(PairKey(7)), a);
        h.commit(a, 2e-6);
        h.commit(a, 1e-6);
        assert_eq!(h.state(a).max_overlap, 2e-6);
        assert_eq!(h.impacts(a), 2);
        let b = h.slot_for(PairKey(9));
        assert_ne!(a, b);
        h.retain_pairs(|key| key == PairKey(9));
        assert_eq!(h.find(PairKey(7)), None);
        assert_eq!(h.find(PairKey(9)), Some(b));
        // The freed slot is reused, with a fresh history.
        let c = h.slot_for(PairKey(11));
        assert_eq!(c, a);
        assert_eq!(h.state(c).max_overlap, 0.0);
    }
}
