//! What registration adds to a collider, and the check that it is still there at each step.
//!
//! Registration never replaces the user's flags. Force mode switches rapier's contact impulses
//! off only between the coupling's own colliders, with one solver group that the coupling
//! reserves ([`COUPLING_SOLVER_GROUP`], group 32): a sphere's solver memberships become that
//! group and its solver filter keeps the user's bits less that group; a surface keeps its
//! memberships and loses that group from its filter. rapier's AND test then fails for
//! sphere–sphere and sphere–surface pairs (the law's), and passes as before for every other
//! pair: surface–surface (a dynamic cuboid on a registered floor), surface–anything and
//! sphere–unregistered collider are rapier's rigid contacts. Restitution mode adds
//! `ActiveHooks::MODIFY_SOLVER_CONTACTS` to the user's hooks and touches no group.

use crate::error::{CouplingError, Result};
use crate::particles::{Particle, ParticleShape};
use rapier3d_f64::prelude::*;

/// The solver group the force-mode coupling reserves for its spheres (group 32): a user's
/// collider whose solver filter leaves it out gets no rapier impulses against the spheres.
pub const COUPLING_SOLVER_GROUP: Group = Group::GROUP_32;

/// A force-mode sphere's solver groups from the user's: memberships the coupling's group
/// alone, the user's filter less that group, AND test (which takes priority in rapier).
pub fn force_sphere_solver_groups(user: InteractionGroups) -> InteractionGroups {
    InteractionGroups::new(
        COUPLING_SOLVER_GROUP,
        user.filter.difference(COUPLING_SOLVER_GROUP),
        InteractionTestMode::And,
    )
}

/// A force-mode surface's solver groups from the user's: the same memberships and test mode,
/// the user's filter less the coupling's group.
pub fn force_surface_solver_groups(user: InteractionGroups) -> InteractionGroups {
    InteractionGroups::new(
        user.memberships,
        user.filter.difference(COUPLING_SOLVER_GROUP),
        user.test_mode,
    )
}

/// Whether rapier's solver leaves a force-mode pair of these solver groups to the law.
fn excluded_from_solver(groups: InteractionGroups) -> bool {
    !groups.filter.intersects(COUPLING_SOLVER_GROUP)
}

/// Add what force mode needs to a registered collider (idempotent).
pub(crate) fn add_force_flags(co: &mut Collider, shape: ParticleShape) {
    let groups = co.solver_groups();
    co.set_solver_groups(match shape {
        ParticleShape::Sphere { .. } => force_sphere_solver_groups(groups),
        ParticleShape::Surface => force_surface_solver_groups(groups),
    });
}

/// Add what restitution mode needs to a registered collider (idempotent).
pub(crate) fn add_restitution_flags(co: &mut Collider) {
    co.set_active_hooks(co.active_hooks() | ActiveHooks::MODIFY_SOLVER_CONTACTS);
}

/// The error when a registered collider lost (or never had) the force-mode solver groups.
pub(crate) fn check_force_flags(co: &Collider, particle: &Particle) -> Result<()> {
    let groups = co.solver_groups();
    let ok = match particle.shape {
        ParticleShape::Sphere { .. } => {
            groups.memberships == COUPLING_SOLVER_GROUP && excluded_from_solver(groups)
        }
        ParticleShape::Surface => excluded_from_solver(groups),
    };
    if ok {
        Ok(())
    } else {
        Err(CouplingError::MissingFlag {
            collider: particle.collider,
            problem: "its solver groups let rapier's contact impulses act on its pairs with the \
                      coupling's spheres (the contact would be counted twice)",
            fix: "register it through ForceModeStepper (insert_sphere, insert_surface, \
                  register_sphere, register_surface), which adds the coupling's solver group \
                  to the user's",
        })
    }
}

/// The error when a registered collider lacks the restitution hook flag.
pub(crate) fn check_restitution_flags(co: &Collider, particle: &Particle) -> Result<()> {
    if co
        .active_hooks()
        .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
    {
        Ok(())
    } else {
        Err(CouplingError::MissingFlag {
            collider: particle.collider,
            problem: "it lacks ActiveHooks::MODIFY_SOLVER_CONTACTS, so rapier never calls the \
                      restitution hook for it (every impact would take the colliders' own \
                      restitution)",
            fix: "register it through RestitutionHooks (insert_sphere, insert_surface, \
                  register_sphere, register_surface), which adds the flag to the user's hooks",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn law_pairs_leave_the_solver_and_every_other_pair_keeps_it() {
        let user = InteractionGroups::all();
        let sphere = force_sphere_solver_groups(user);
        let surface = force_surface_solver_groups(user);
        assert!(!sphere.test(sphere), "sphere–sphere is the law's");
        assert!(
            !sphere.test(surface) && !surface.test(sphere),
            "sphere–surface"
        );
        assert!(surface.test(surface), "surface–surface is rapier's");
        assert!(
            surface.test(user) && sphere.test(user),
            "against unregistered colliders"
        );
        // A user's OR-mode groups on a surface change nothing for the law's pairs.
        let or = InteractionGroups::new(Group::GROUP_1, Group::ALL, InteractionTestMode::Or);
        let or_surface = force_surface_solver_groups(or);
        assert!(!sphere.test(or_surface) && !or_surface.test(sphere));
        // A user's filter on the sphere stays in force against unregistered colliders.
        let picky = force_sphere_solver_groups(InteractionGroups::new(
            Group::ALL,
            Group::GROUP_1,
            InteractionTestMode::And,
        ));
        assert!(picky.test(InteractionGroups::new(
            Group::GROUP_1,
            Group::ALL,
            InteractionTestMode::And
        )));
        assert!(!picky.test(InteractionGroups::new(
            Group::GROUP_2,
            Group::ALL,
            InteractionTestMode::And
        )));
    }
}
