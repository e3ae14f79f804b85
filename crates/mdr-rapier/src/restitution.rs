//! Restitution mode: hard spheres whose impacts rapier resolves with impulses, each manifold's
//! restitution set from the MDR law's energy route (docs/theory.md §4) at the approach speed and the
//! pair's plastic history.
//!
//! The history (the largest indentation `d_max` of the pair) lives in an [`ImpactHistory`]: a
//! thread-safe slab of atomic slots. A manifold's `user_data` holds its slot index + 1, so the
//! hook reaches the history with one atomic load; a pair-key index (sharded mutexes, touched only
//! when a manifold is new) lets a re-created manifold of the same pair find its old slot, so a
//! re-impact keeps the plastic state and a second, slower impact on the same spot is elastic.

use crate::error::{positive, Result};
use crate::particles::{MaterialHandle, ParticleSet, SphereBuilder};
use crate::store::PairKey;
use mdr_contact::normal::{MdrElastoPlastic, MdrLaw, MdrState, NormalModel};
use mdr_contact::ContactPair;
use rapier3d_f64::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};

const SHARDS: usize = 64;
/// Segment `s` of the slab holds `FIRST_SEGMENT << s` slots.
const FIRST_SEGMENT_BITS: u32 = 6;
const SEGMENTS: usize = 26;

#[derive(Debug, Default)]
struct ImpactSlot {
    key: AtomicU64,
    /// `d_max` (m) as f64 bits; non-negative floats order like their bits, so `fetch_max` works.
    max_overlap: AtomicU64,
    impacts: AtomicU32,
    /// Last maintenance epoch in which the pair existed.
    seen: u64,
}

/// Thread-safe per-pair impact history (largest indentation), reached through slot indices.
#[derive(Debug)]
pub struct ImpactHistory {
    index: Box<[Mutex<HashMap<u64, u32>>]>,
    segments: Box<[OnceLock<Box<[ImpactSlot]>>]>,
    next: AtomicU32,
    free: Mutex<Vec<u32>>,
    epoch: u64,
}

impl Default for ImpactHistory {
    fn default() -> Self {
        Self {
            index: (0..SHARDS).map(|_| Mutex::new(HashMap::new())).collect(),
            segments: (0..SEGMENTS).map(|_| OnceLock::new()).collect(),
            next: AtomicU32::new(0),
            free: Mutex::new(Vec::new()),
            // Slots start with `seen = 0`: epoch 0 never counts as seen.
            epoch: 1,
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

    /// Keep only the pairs marked with `mark_live` since the previous call, and free the slots
    /// of the others.
    fn retain_marked(&mut self) {
        let epoch = self.epoch;
        let Self {
            index,
            segments,
            free,
            ..
        } = self;
        let free = free.get_mut().expect("history lock");
        for shard in index.iter_mut() {
            shard.get_mut().expect("history lock").retain(|_, slot| {
                let (segment, offset) = locate(*slot);
                let seen = segments[segment].get().map_or(0, |seg| seg[offset].seen);
                if seen == epoch {
                    true
                } else {
                    free.push(*slot);
                    false
                }
            });
        }
        self.epoch += 1;
    }

    fn mark_live(&mut self, key: PairKey) {
        let slot = self.index[shard_of(key.0)]
            .get_mut()
            .expect("history lock")
            .get(&key.0)
            .copied();
        if let Some(slot) = slot {
            let (segment, offset) = locate(slot);
            if let Some(seg) = self.segments[segment].get_mut() {
                seg[offset].seen = self.epoch;
            }
        }
    }
}

/// The restitution-mode coupling: a `PhysicsHooks` value setting each manifold's restitution
/// from the MDR law and its friction from `μ`. Step with [`RestitutionHooks::step`] (or pass it
/// to `PhysicsWorld::step_with_events` and call [`RestitutionHooks::maintain`] afterwards).
#[derive(Debug)]
pub struct RestitutionHooks {
    model: MdrElastoPlastic,
    friction: f64,
    dt: f64,
    particles: ParticleSet,
    history: ImpactHistory,
}

impl RestitutionHooks {
    /// Hooks for the MDR law `model` and Coulomb friction coefficient `friction` (≥ 0).
    pub fn new(model: MdrElastoPlastic, friction: f64) -> Result<Self> {
        if !(friction.is_finite() && friction >= 0.0) {
            return Err(crate::CouplingError::OutOfRange {
                name: "mu",
                value: friction,
                range: "[0, inf)",
            });
        }
        Ok(Self {
            model,
            friction,
            dt: 1.0 / 60.0,
            particles: ParticleSet::new(),
            history: ImpactHistory::new(),
        })
    }

    /// The registered colliders and materials, mutably.
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

    /// The step length the hook assumes when deciding whether a speculative contact closes in
    /// this step (set by [`RestitutionHooks::step`]).
    pub fn set_time_step(&mut self, dt: f64) -> Result<()> {
        self.dt = positive("dt", dt)?;
        Ok(())
    }

    /// Insert a sphere whose contacts go through the hook, and register it.
    pub fn insert_sphere(
        &mut self,
        world: &mut PhysicsWorld,
        sphere: SphereBuilder,
    ) -> Result<(RigidBodyHandle, ColliderHandle)> {
        self.particles.insert_sphere_flagged(world, sphere, |c| {
            c.active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS)
        })
    }

    /// Insert a collider of any shape as a surface of `material`, optionally on a body.
    pub fn insert_surface(
        &mut self,
        world: &mut PhysicsWorld,
        collider: ColliderBuilder,
        parent: Option<RigidBodyHandle>,
        material: MaterialHandle,
    ) -> Result<ColliderHandle> {
        self.particles
            .insert_surface_flagged(world, collider, parent, material, |c| {
                c.active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS)
            })
    }

    /// One step of `world` with these hooks, then [`RestitutionHooks::maintain`].
    pub fn step(&mut self, world: &mut PhysicsWorld) -> Result<()> {
        self.set_time_step(world.integration_parameters.dt)?;
        world.step_with_events(&*self, &());
        self.maintain(&world.narrow_phase);
        Ok(())
    }

    /// Drop the history of pairs that rapier no longer tracks (their bounding boxes separated),
    /// so the store stays proportional to the pairs in proximity.
    pub fn maintain(&mut self, narrow_phase: &NarrowPhase) {
        for pair in narrow_phase.contact_pairs() {
            if self.particles.get(pair.collider1).is_some()
                && self.particles.get(pair.collider2).is_some()
            {
                self.history
                    .mark_live(PairKey::new(pair.collider1, pair.collider2));
            }
        }
        self.history.retain_marked();
    }

    /// The pair quantities and the bound law of two registered colliders.
    fn pair_law(
        &self,
        bodies: &RigidBodySet,
        ctx_bodies: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
        c1: ColliderHandle,
        c2: ColliderHandle,
    ) -> Option<(MdrLaw, f64)> {
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
        Some((self.model.bind(&pair).ok()?, mass))
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
        let bodies = ctx.bodies;
        let (c1, c2) = (ctx.collider1, ctx.collider2);
        let (rb1, rb2) = (ctx.rigid_body1, ctx.rigid_body2);
        let Some((law, mass)) = self.pair_law(bodies, (rb1, rb2), c1, c2) else {
            return;
        };
        let Some(rigid) = ctx.rigid_mut() else {
            return;
        };
        *rigid.friction = self.friction;
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
        if closest > approach * self.dt {
            // The gap does not close in this step: no impact yet.
            defer_speculative_contacts(rigid.solver_contacts, approach, self.dt);
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
        // Energy that fits within the old unloading branch is returned: elastic re-impact
        // (docs/theory.md §4); skip the root solve.
        let restitution = if kinetic <= law.stored_energy(state.max_overlap, state.max_overlap) {
            1.0
        } else {
            let impact = law.impact(&state, mass, approach);
            self.history.commit(slot, impact.state.max_overlap);
            impact.restitution
        };
        *rigid.restitution = restitution;
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
        h.mark_live(PairKey(9));
        h.retain_marked();
        assert_eq!(h.find(PairKey(7)), None);
        assert_eq!(h.find(PairKey(9)), Some(b));
        // The freed slot is reused, with a fresh history.
        let c = h.slot_for(PairKey(11));
        assert_eq!(c, a);
        assert_eq!(h.state(c).max_overlap, 0.0);
    }
}
