//! The ring's rapier hook: restitution mode — each manifold's restitution set from a
//! [`RestitutionLaw`] at the pair's approach speed, with the per-contact history in a
//! thread-safe store.

use crate::law::{ImpactPair, RestitutionLaw};
use mdr_rapier::restitution::defer_speculative_contacts;
use rapier3d_f64::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// Bit of a collider's `user_data` marking a ghost image; the low 32 bits hold the index of the
/// particle it images (or is).
pub const GHOST_BIT: u128 = 1 << 32;

/// `user_data` of the collider of particle `index`, real or ghost.
pub fn identity(index: usize, ghost: bool) -> u128 {
    index as u128 | if ghost { GHOST_BIT } else { 0 }
}

/// `(particle index, is ghost)` of a collider's `user_data`.
pub fn decode(user_data: u128) -> (u32, bool) {
    ((user_data & 0xffff_ffff) as u32, user_data & GHOST_BIT != 0)
}

/// Key of the contact history: the two particle indices, smaller first.
type HistoryKey = (u32, u32);

/// The hooks of a ring run (see the module documentation).
///
/// **Ghosts.** A contact across the boundary reaches the hook once, as a particle against the
/// other's ghost: ghosts exist on one side of each boundary only and do not collide with each
/// other ([`crate::world`]).
///
/// **Restitution.** An approaching pair (`u = (v₁ − v₂)·n > 0`) whose gap closes within the step
/// (`gap ≤ u Δt`, rapier's speculative contact) collides in this step: the law is evaluated at `u`
/// with the pair's history, which is then updated, and the manifold's restitution is set. Pairs
/// that will not touch in this step leave the history alone. Friction is zero (smooth spheres, as
/// REBOUND's hard-sphere model).
#[derive(Debug)]
pub struct RingHooks<L: RestitutionLaw> {
    law: L,
    dt: f64,
    histories: Mutex<HashMap<HistoryKey, (L::History, u64)>>,
    step: u64,
    collisions: AtomicU64,
}

impl<L: RestitutionLaw> RingHooks<L> {
    /// Hooks applying `law`, for steps of `dt` (s).
    pub fn new(law: L, dt: f64) -> Self {
        Self {
            law,
            dt,
            histories: Mutex::new(HashMap::new()),
            step: 0,
            collisions: AtomicU64::new(0),
        }
    }

    /// The law.
    pub fn law(&self) -> &L {
        &self.law
    }

    /// Impacts resolved so far.
    pub fn collisions(&self) -> u64 {
        self.collisions.load(Ordering::Relaxed)
    }

    /// Number of contacts whose history is kept.
    pub fn histories(&self) -> usize {
        self.histories.lock().map_or(0, |h| h.len())
    }

    /// Call after each rapier step: drops the histories of pairs that were not in contact (no
    /// manifold reached the hook) during the step, i.e. that separated.
    pub fn end_step(&mut self) {
        let step = self.step;
        if let Ok(histories) = self.histories.get_mut() {
            histories.retain(|_, (_, seen)| *seen == step);
        }
        self.step += 1;
    }
}

fn pair_identities(
    colliders: &ColliderSet,
    a: ColliderHandle,
    b: ColliderHandle,
) -> Option<((u32, bool), (u32, bool))> {
    Some((
        decode(colliders.get(a)?.user_data),
        decode(colliders.get(b)?.user_data),
    ))
}

fn ball_radius(colliders: &ColliderSet, handle: ColliderHandle) -> Option<f64> {
    colliders.get(handle)?.shape().as_ball().map(|b| b.radius)
}

impl<L: RestitutionLaw> PhysicsHooks for RingHooks<L> {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let (Some(rb1), Some(rb2)) = (context.rigid_body1, context.rigid_body2) else {
            return;
        };
        let (Some(body1), Some(body2)) = (context.bodies.get(rb1), context.bodies.get(rb2)) else {
            return;
        };
        let (Some(r1), Some(r2)) = (
            ball_radius(context.colliders, context.collider1),
            ball_radius(context.colliders, context.collider2),
        ) else {
            return;
        };
        let Some(((i1, _), (i2, _))) =
            pair_identities(context.colliders, context.collider1, context.collider2)
        else {
            return;
        };
        let pair = ImpactPair {
            radius1: r1,
            radius2: r2,
            mass1: body1.mass(),
            mass2: body2.mass(),
        };
        let (v1, v2) = (body1.linvel(), body2.linvel());
        let Some(manifold) = context.rigid_mut() else {
            return;
        };
        *manifold.friction = 0.0;
        let normal = *manifold.normal;
        let approach = (v1 - v2).dot(normal);
        let gap = manifold
            .solver_contacts
            .iter()
            .map(|c| c.dist)
            .fold(f64::INFINITY, f64::min);
        let impact = approach > 0.0 && gap.is_finite() && gap <= approach * self.dt;
        if !impact {
            // No impact in this step: defer the contacts (solved with zero impulse). Left alone,
            // rapier's relax pass would brake the approach (an inelastic pre-contact loss hard
            // spheres do not have); dropped, they would keep the impulse of the pair's last impact
            // and rapier would then take its next impact as a resting contact, with no bounce
            // (docs/rings.md §4, docs/coupling.md "Speculative contacts").
            defer_speculative_contacts(manifold.solver_contacts, approach, self.dt);
        }
        // A law without history (Bridges, constant ε) needs no store: no lock, no lookup.
        let stateless = std::mem::size_of::<L::History>() == 0;
        if stateless && !impact {
            return;
        }
        let mut none = L::History::default();
        let mut histories = if stateless {
            None
        } else {
            let Ok(histories) = self.histories.lock() else {
                return;
            };
            Some(histories)
        };
        let history = match histories.as_mut() {
            Some(histories) => {
                let entry = histories.entry((i1.min(i2), i1.max(i2))).or_default();
                entry.1 = self.step;
                &mut entry.0
            }
            None => &mut none,
        };
        if impact {
            *manifold.restitution = self.law.restitution(&pair, history, approach);
            self.collisions.fetch_add(1, Ordering::Relaxed);
        }
    }
}
