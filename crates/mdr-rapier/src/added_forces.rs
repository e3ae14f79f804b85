//! The coupling's contact wrenches added to the forces a user put on rapier bodies, and taken
//! back after the step.
//!
//! rapier keeps a body's user force (`add_force`) from step to step until `reset_forces`. The
//! coupling writes each body's force as the user's own plus the law's wrench of the step, and
//! after rapier's step gives the body back the user's own, so that between steps a program sees
//! exactly the forces it added, and a constant force it added once acts at every step as in a
//! world without the coupling. A program that runs its own pipeline and skips the give-back
//! loses nothing: the next write recognises the coupling's own total (bit for bit) and starts
//! again from the user's part.

use rapier3d_f64::math::{AngVector, Vector};
use rapier3d_f64::prelude::{RigidBody, RigidBodyHandle, RigidBodySet};

/// What the coupling wrote on one body.
#[derive(Debug, Clone, Copy)]
struct Written {
    handle: RigidBodyHandle,
    /// The user's force and torque before the write.
    user: (Vector, AngVector),
    /// The coupling's wrench in the write.
    coupling: (Vector, AngVector),
    /// The body's force and torque right after the write.
    total: (Vector, AngVector),
}

/// The bodies whose forces hold a coupling wrench, until [`AddedForces::give_back`].
#[derive(Debug, Clone, Default)]
pub(crate) struct AddedForces {
    written: Vec<Written>,
    /// Where each body (by arena index) is in `written`, plus one (0: not written).
    slot: Vec<u32>,
}

impl AddedForces {
    /// Set `body`'s force to the user's own plus `force`, its torque to the user's plus
    /// `torque`. The user's own is the body's force as it stands, unless it still holds this
    /// coupling's last write (no give-back since), whose wrench is then left out.
    pub(crate) fn add(
        &mut self,
        handle: RigidBodyHandle,
        body: &mut RigidBody,
        force: Vector,
        torque: AngVector,
    ) {
        let now = (body.user_force(), body.user_torque());
        let index = handle.into_raw_parts().0 as usize;
        let previous = self
            .slot
            .get(index)
            .filter(|&&s| s > 0)
            .map(|&s| self.written[s as usize - 1])
            .filter(|w| w.handle == handle);
        let user = match previous {
            Some(w) if same_bits(now, w.total) => w.user,
            // The user changed the forces after the coupling's write: their change on top of it.
            Some(w) => (now.0 - w.coupling.0, now.1 - w.coupling.1),
            None => now,
        };
        body.reset_forces(false);
        body.reset_torques(false);
        body.add_force(user.0 + force, false);
        body.add_torque(user.1 + torque, false);
        let written = Written {
            handle,
            user,
            coupling: (force, torque),
            total: (body.user_force(), body.user_torque()),
        };
        match previous {
            Some(_) => self.written[self.slot[index] as usize - 1] = written,
            None => {
                if self.slot.len() <= index {
                    self.slot.resize(index + 1, 0);
                }
                self.written.push(written);
                self.slot[index] = self.written.len() as u32;
            }
        }
    }

    /// Give every written body back the user's own force and torque (after rapier's step).
    pub(crate) fn give_back(&mut self, bodies: &mut RigidBodySet) {
        for w in self.written.drain(..) {
            if let Some(body) = bodies.get_mut(w.handle) {
                body.reset_forces(false);
                body.reset_torques(false);
                body.add_force(w.user.0, false);
                body.add_torque(w.user.1, false);
            }
            if let Some(s) = self.slot.get_mut(w.handle.into_raw_parts().0 as usize) {
                *s = 0;
            }
        }
    }
}

fn same_bits(a: (Vector, AngVector), b: (Vector, AngVector)) -> bool {
    let bits = |v: Vector| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
    bits(a.0) == bits(b.0) && bits(a.1) == bits(b.1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapier3d_f64::prelude::RigidBodyBuilder;

    #[test]
    fn the_users_force_survives_writes_with_or_without_give_back() {
        let mut bodies = RigidBodySet::new();
        let h = bodies.insert(RigidBodyBuilder::dynamic());
        let user = Vector::new(1.0, -2.0, 0.5);
        bodies[h].add_force(user, false);
        let mut added = AddedForces::default();
        let wrench = Vector::new(0.25, 0.0, 3.0);
        added.add(h, &mut bodies[h], wrench, Vector::X);
        assert_eq!(bodies[h].user_force(), user + wrench);
        // A second write without give-back replaces the coupling's part only.
        added.add(h, &mut bodies[h], -wrench, Vector::ZERO);
        assert_eq!(bodies[h].user_force(), user - wrench);
        assert_eq!(bodies[h].user_torque(), Vector::ZERO);
        // The user adds more between the write and the step: kept on top.
        bodies[h].add_force(Vector::Y, false);
        added.add(h, &mut bodies[h], wrench, Vector::ZERO);
        let expected = user + Vector::Y + wrench;
        assert!((bodies[h].user_force() - expected).length() < 1e-15);
        added.give_back(&mut bodies);
        assert!((bodies[h].user_force() - (user + Vector::Y)).length() < 1e-15);
        // After a give-back the body's force is the user's again, however it was changed.
        bodies[h].reset_forces(false);
        added.add(h, &mut bodies[h], wrench, Vector::ZERO);
        assert_eq!(bodies[h].user_force(), wrench);
        added.give_back(&mut bodies);
        assert_eq!(bodies[h].user_force(), Vector::ZERO);
    }
}
