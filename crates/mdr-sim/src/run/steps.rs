//! A scene's steps without output, for timing (`mdr-dem bench scene`).

use super::*;

/// A scene's steps without any output, for timing (`mdr-dem bench scene`): each
/// [`SceneSteps::step`] is a step of [`run_scene`] (scene events such as removed walls and
/// spheres, forces, energy books, the headline tracker where it samples every step,
/// integration) without its energy rows, frames and checkpoints.
pub struct SceneSteps<'a> {
    sim: Sim<'a>,
}

/// Contacts of a [`SceneSteps`] at its last force evaluation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ContactCounts {
    /// Touching sphere–sphere pairs.
    pub sphere: usize,
    /// Touching sphere–wall pairs.
    pub wall: usize,
}

impl<'a> SceneSteps<'a> {
    /// Build `scene`.
    pub fn new(scene: &'a Scene) -> Result<Self, SimError> {
        Ok(Self {
            sim: Sim::new(scene)?,
        })
    }

    /// Continue `scene` from a checkpoint written by [`run_scene`] (e.g. a settled bed, to
    /// time the scene in the state its headline is measured in).
    pub fn resume(scene: &'a Scene, checkpoint: &Path) -> Result<Self, SimError> {
        Ok(Self {
            sim: Sim::resume(scene, checkpoint)?,
        })
    }

    /// One step.
    pub fn step(&mut self) -> Result<(), SimError> {
        let sim = &mut self.sim;
        sim.scene_events();
        sim.compute_forces(false)?;
        if sim.tracker.needs_every_step() {
            sim.track_step();
        }
        sim.advance()
    }

    /// Steps done.
    pub fn steps_done(&self) -> u64 {
        self.sim.step
    }

    /// The largest sphere speed (m/s) now (neighbour-list path; `None` on the rapier pipeline paths).
    pub fn max_speed(&self) -> Option<f64> {
        match &self.sim.built.coupling {
            Coupling::NeighbourList(stepper) => Some(
                stepper
                    .particles()
                    .linvel
                    .iter()
                    .map(|v| v.norm())
                    .fold(0.0, f64::max),
            ),
            _ => None,
        }
    }

    /// The spheres' positions, velocities and species (neighbour-list path; `None` on the
    /// rapier pipeline paths).
    pub fn neighbour_list_particles(
        &self,
    ) -> Option<&mdr_rapier::neighbour_list::particles::NeighbourListParticles> {
        match &self.sim.built.coupling {
            Coupling::NeighbourList(stepper) => Some(stepper.particles()),
            _ => None,
        }
    }

    /// Number of particles.
    pub fn particles(&self) -> usize {
        self.sim.scene.particles.len()
    }

    /// Whether the scene runs on the neighbour-list path.
    pub fn neighbour_list(&self) -> bool {
        matches!(self.sim.built.coupling, Coupling::NeighbourList(_))
    }

    /// Time each part of the neighbour-list path's steps from now on (from zero), or stop
    /// (`false`); nothing on the rapier pipeline paths. The trajectory does not depend on it.
    pub fn time_steps(&mut self, on: bool) {
        if let Coupling::NeighbourList(stepper) = &mut self.sim.built.coupling {
            stepper.time_steps(on);
        }
    }

    /// Time per part of the steps since [`SceneSteps::time_steps`] switched timing on
    /// (neighbour-list path; `None` otherwise or while off). What a step spends outside these
    /// parts (scene events, energy books, the headline tracker) is the rest of its wall time.
    pub fn step_timings(&self) -> Option<StepTimings> {
        match &self.sim.built.coupling {
            Coupling::NeighbourList(stepper) => stepper.step_timings(),
            _ => None,
        }
    }

    /// Neighbour-list builds so far (neighbour-list path only).
    pub fn rebuilds(&self) -> Option<u64> {
        match &self.sim.built.coupling {
            Coupling::NeighbourList(stepper) => Some(stepper.rebuilds()),
            _ => None,
        }
    }

    /// Sphere pairs in the neighbour list (neighbour-list path): the touching ones and those
    /// within the skin, each of which the pair loop tests every step.
    pub fn listed_pairs(&self) -> Option<usize> {
        match &self.sim.built.coupling {
            Coupling::NeighbourList(stepper) => Some(stepper.listed_pairs()),
            _ => None,
        }
    }

    /// Touching pairs at the last force evaluation.
    pub fn contacts(&self) -> ContactCounts {
        match &self.sim.built.coupling {
            Coupling::NeighbourList(stepper) => {
                let report = stepper.last_report();
                ContactCounts {
                    sphere: report.sphere_contacts,
                    wall: report.surface_contacts,
                }
            }
            Coupling::RapierPipeline(stepper) => {
                let mut counts = ContactCounts::default();
                let particle = |c: rapier3d_f64::prelude::ColliderHandle| {
                    self.sim
                        .built
                        .particle_of_collider
                        .get(c.into_raw_parts().0 as usize)
                        .is_some_and(|&i| i != usize::MAX)
                };
                stepper.for_each_contact(&mut |e| {
                    if particle(e.collider1) && particle(e.collider2) {
                        counts.sphere += 1;
                    } else {
                        counts.wall += 1;
                    }
                });
                counts
            }
            Coupling::Restitution(_) => ContactCounts::default(),
        }
    }
}
