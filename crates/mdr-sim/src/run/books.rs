//! The energy books of a run: running totals of the dissipated work and of the work of moving
//! walls.

use super::coupling::{NeighbourListSceneStepper, RapierPipelineSceneStepper};
use crate::laws::{SceneNormal, SceneRolling};
use mdr_contact::model::WorkBooks;
use mdr_contact::normal::NormalLaw;
use mdr_contact::rolling::RollingLaw;
use mdr_rapier::convert::to_na;
use mdr_rapier::kernel::ContactWorks;
use mdr_rapier::neighbour_list::{ContactPartner, EndedContact};
use nalgebra::Vector3;
use rapier3d_f64::prelude::*;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Running totals of the dissipated work and of the work of moving walls.
///
/// On the rapier path a pair's history (and its work books) is dropped when the pair
/// separates, so the totals take each contact's increments step by step. On the neighbour-list
/// path every contact's history books its own works as it goes (friction, damping and the
/// springs' stiffness energy in its work books; plastic and rolling work in the laws' states),
/// and the stepper hands over each contact whose history ends with what it booked
/// ([`mdr_rapier::neighbour_list::EndedContact`]): the totals here then hold the contacts that ended, and
/// the live contacts' books are added when the books are read (`Books::live_neighbour_list`), so a step
/// costs nothing per contact.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Books {
    /// Plastic work since the start (J).
    pub plastic: f64,
    /// Friction work since the start (J).
    pub friction: f64,
    /// Damping work since the start (J).
    pub damping: f64,
    /// Rolling-resistance work since the start (J).
    pub rolling: f64,
    /// Work of kinematic walls on the particles since the start (J).
    pub wall_work: f64,
    /// Energy the tangential springs lost without work since the start (J; negative when
    /// gained): stiffness changes at fixed displacement, the rescale of a shrinking contact,
    /// and what a spring held when its contact opened.
    pub stiffness_tangential: f64,
    /// Energy the rolling springs lost without work since the start (J; negative when gained):
    /// stiffness changes at fixed torque.
    pub stiffness_rolling: f64,
    /// Kinetic and gravitational energy removed spheres took out of the run (J).
    pub removed: f64,
    /// Adhesive work since the start (J): the energy the adhesive springs held when they let go
    /// (`AdhesiveMdrState::adhesive_work`). The contacts' dissipated work, which `plastic`
    /// totals, includes it: the plastic work alone is `plastic − adhesive`.
    pub adhesive: f64,
    /// Neighbour-list path, adhesive law: the adhesive work of each live contact that had
    /// booked some at the last step, by contact, sorted.
    pub adhesive_last: Vec<(AdhesiveKey, f64)>,
    /// Rapier path: every touching pair at the last update, sorted by key, with its books then.
    pub last: Vec<PairBooks>,
    /// Plastic work per particle (J), the adhesive work left out. On the neighbour-list path,
    /// the dissipated work of the contacts that ended less the adhesive work booked so far of
    /// every contact (a frame adds the live contacts' dissipated work).
    pub particle_plastic: Vec<f64>,
    /// Buffer of the contacts that ended in a step (empty between steps).
    #[serde(skip)]
    ended: Vec<EndedContact>,
}

/// A contact of the neighbour-list path: particle, 0 for a surface and 1 for a sphere, and the
/// surface's or the other sphere's index.
pub type AdhesiveKey = (u32, u8, u32);

/// What the rapier path's books keep of one touching pair between updates: the pair's books
/// at the last update.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PairBooks {
    /// Pair key.
    pub key: u64,
    /// Plastic work of the pair so far (J).
    pub plastic: f64,
    /// Largest overlap of the pair so far (m), which the plastic work is a function of.
    pub max_overlap: f64,
    /// Friction work (J).
    pub friction: f64,
    /// Damping work (J).
    pub damping: f64,
    /// Rolling work (J).
    pub rolling: f64,
    /// Energy the tangential springs gained without work (J).
    pub tangential_stiffness: f64,
    /// Energy the rolling spring gained without work (J).
    pub rolling_stiffness: f64,
    /// Adhesive work of the pair so far (J; part of `plastic`).
    pub adhesive: f64,
}

impl Books {
    /// Empty books of a run of `particles` spheres.
    pub fn new(particles: usize) -> Self {
        Self {
            particle_plastic: vec![0.0; particles],
            ..Self::default()
        }
    }

    /// Take the increments of the step whose forces were just computed (rapier path).
    pub(crate) fn take<N: SceneNormal>(
        &mut self,
        stepper: &RapierPipelineSceneStepper<N>,
        bodies: &RigidBodySet,
        particle_of_collider: &[usize],
        wall_of_collider: &[usize],
        dt: f64,
    ) {
        let entries = stepper.contacts().entries();
        let mut next = Vec::with_capacity(entries.len());
        let mut j = 0;
        let particle = |c: ColliderHandle| {
            particle_of_collider
                .get(c.into_raw_parts().0 as usize)
                .copied()
                .filter(|&i| i != usize::MAX)
        };
        for e in entries {
            let key = e.key.0;
            while j < self.last.len() && self.last[j].key < key {
                j += 1;
            }
            let prev = match self.last.get(j) {
                Some(l) if l.key == key => *l,
                _ => PairBooks::default(),
            };
            let h = &e.history;
            // Without adhesion the dissipated work is a function of the largest overlap
            // (`NormalLaw::dissipated_work`): the same as at the last update unless that grew.
            let max_overlap = e.law.normal.max_overlap(&h.contact.normal);
            let plastic = if !N::ADHESIVE && max_overlap == prev.max_overlap && prev.key == key {
                prev.plastic
            } else {
                e.law.normal.dissipated_work(&h.contact.normal)
            };
            let books = &h.contact.books;
            let now = PairBooks {
                key,
                plastic,
                max_overlap,
                friction: books.friction_work(),
                damping: books.damping_work(),
                rolling: e.rolling.dissipated_work(&h.rolling),
                tangential_stiffness: books.tangential_stiffness_energy(),
                rolling_stiffness: books.rolling_stiffness_energy(),
                adhesive: N::adhesive_work(&h.contact.normal),
            };
            let da = now.adhesive - prev.adhesive;
            self.adhesive += da;
            self.plastic += now.plastic - prev.plastic;
            // The particles' plastic work leaves the adhesive work out.
            let dp = now.plastic - prev.plastic - da;
            self.friction += now.friction - prev.friction;
            self.damping += now.damping - prev.damping;
            self.rolling += now.rolling - prev.rolling;
            self.stiffness_tangential -= now.tangential_stiffness - prev.tangential_stiffness;
            self.stiffness_rolling -= now.rolling_stiffness - prev.rolling_stiffness;
            if dp != 0.0 {
                match (particle(e.collider1), particle(e.collider2)) {
                    (Some(a), Some(b)) => {
                        self.particle_plastic[a] += 0.5 * dp;
                        self.particle_plastic[b] += 0.5 * dp;
                    }
                    (Some(a), None) | (None, Some(a)) => self.particle_plastic[a] += dp,
                    (None, None) => {}
                }
            }
            next.push(now);
            // Work of a moving wall on the sphere: F · v_wall(contact point) dt.
            let on_wall = wall_of_collider
                .get(e.collider2.into_raw_parts().0 as usize)
                .is_some_and(|&w| w != usize::MAX);
            if on_wall {
                if let Some(b2) = e.body2.and_then(|h| bodies.get(h)) {
                    if b2.is_kinematic() {
                        self.wall_work += wall_power(b2, &e.contact.point, &e.wrench.force) * dt;
                    }
                }
            }
        }
        self.last = next;
    }

    /// The step whose forces were just computed, on the neighbour-list path: the contacts that
    /// ended (their whole books, once), and the work of kinematic walls (`F · v_wall dt` per
    /// touching sphere, in the stepper's surface-pair order).
    pub(crate) fn take_neighbour_list<N: SceneNormal, R: SceneRolling>(
        &mut self,
        stepper: &mut NeighbourListSceneStepper<N, R>,
        bodies: &RigidBodySet,
        dt: f64,
    ) {
        stepper.take_ended_contacts(&mut self.ended);
        if N::ADHESIVE {
            self.take_adhesive(stepper);
        }
        for e in self.ended.drain(..) {
            let w = &e.works;
            self.plastic += w.plastic;
            self.friction += w.friction;
            self.damping += w.damping;
            self.rolling += w.rolling;
            self.stiffness_tangential -= w.tangential_stiffness;
            self.stiffness_rolling -= w.rolling_stiffness;
            let i = e.particle as usize;
            match e.partner {
                ContactPartner::Sphere(j) => {
                    self.particle_plastic[i] += 0.5 * w.plastic;
                    self.particle_plastic[j as usize] += 0.5 * w.plastic;
                }
                ContactPartner::Surface(_) => self.particle_plastic[i] += w.plastic,
            }
        }
        let surfaces = stepper.surfaces();
        let kinematic: Vec<Option<&RigidBody>> = surfaces
            .iter()
            .map(|s| {
                s.body
                    .and_then(|h| bodies.get(h))
                    .filter(|b| b.is_kinematic())
            })
            .collect();
        if kinematic.iter().all(Option::is_none) {
            return;
        }
        let sp = stepper.surface_pairs();
        for q in (0..sp.len()).filter(|&q| sp.active[q]) {
            if let Some(b2) = kinematic[sp.surface[q] as usize] {
                self.wall_work += wall_power(b2, &sp.contact[q].point, &sp.wrench[q].force) * dt;
            }
        }
    }

    /// Neighbour-list path: book the adhesive work the live contacts added since the last step
    /// (a contact's adhesive work only grows while it lives; once it ends it books no more, and
    /// a contact found with less than its key had at the last step is a new one).
    fn take_adhesive<N: SceneNormal, R: SceneRolling>(
        &mut self,
        stepper: &NeighbourListSceneStepper<N, R>,
    ) {
        let mut now: Vec<(AdhesiveKey, f64)> = Vec::new();
        let p = stepper.particles();
        let pairs = stepper.pairs();
        let sp = stepper.surface_pairs();
        for i in 0..p.len() {
            for q in sp.start[i] as usize..sp.start[i + 1] as usize {
                let w = N::adhesive_work(&sp.history[q].contact.normal);
                if sp.active[q] && w > 0.0 {
                    now.push(((i as u32, 0, sp.surface[q]), w));
                }
            }
            for q in pairs.first[i] as usize..pairs.first[i + 1] as usize {
                let w = N::adhesive_work(&pairs.history[q].contact.normal);
                if pairs.active[q] && w > 0.0 {
                    now.push(((i as u32, 1, pairs.j[q]), w));
                }
            }
        }
        now.sort_unstable_by_key(|&(k, _)| k);
        for &((i, kind, other), w) in &now {
            let before = match self
                .adhesive_last
                .binary_search_by_key(&(i, kind, other), |&(k, _)| k)
            {
                Ok(k) if self.adhesive_last[k].1 <= w => self.adhesive_last[k].1,
                _ => 0.0,
            };
            let added = w - before;
            self.adhesive += added;
            // The particles' plastic work leaves the adhesive work out: the contact's
            // dissipated work, added when it ends or a frame is written, includes it.
            if kind == 0 {
                self.particle_plastic[i as usize] -= added;
            } else {
                self.particle_plastic[i as usize] -= 0.5 * added;
                self.particle_plastic[other as usize] -= 0.5 * added;
            }
        }
        self.adhesive_last = now;
    }

    /// The books of the contacts alive on the neighbour-list path, to add to the totals
    /// ([`Books`]); with `particle_plastic`, their plastic work is added to it per particle
    /// (half to each sphere of a pair). Taken in parallel over fixed blocks of particles and
    /// joined in block order, so the sums do not depend on the number of threads.
    pub(crate) fn live_neighbour_list<N: SceneNormal, R: SceneRolling>(
        stepper: &NeighbourListSceneStepper<N, R>,
        particle_plastic: Option<&mut [f64]>,
    ) -> ContactWorks {
        /// Particles per block.
        const BLOCK: usize = 2048;
        let per_particle = particle_plastic.is_some();
        let p = stepper.particles();
        let pairs = stepper.pairs();
        let sp = stepper.surface_pairs();
        let n = p.len();
        let blocks: Vec<(ContactWorks, Vec<(u32, f64)>)> = (0..n.div_ceil(BLOCK))
            .into_par_iter()
            .map(|b| {
                let mut total = ContactWorks::default();
                let mut plastic = Vec::new();
                for i in b * BLOCK..((b + 1) * BLOCK).min(n) {
                    for q in sp.start[i] as usize..sp.start[i + 1] as usize {
                        if sp.active[q] {
                            let (law, rolling) =
                                stepper.surface_pair_laws(i, sp.surface[q] as usize);
                            let w = ContactWorks::of(law, rolling, &sp.history[q]);
                            total.add(&w);
                            if per_particle {
                                plastic.push((i as u32, w.plastic));
                            }
                        }
                    }
                    for q in pairs.first[i] as usize..pairs.first[i + 1] as usize {
                        if pairs.active[q] {
                            let j = pairs.j[q] as usize;
                            let (law, rolling) = stepper.sphere_pair_laws(i, j);
                            let w = ContactWorks::of(law, rolling, &pairs.history[q]);
                            total.add(&w);
                            if per_particle {
                                plastic.push((i as u32, 0.5 * w.plastic));
                                plastic.push((j as u32, 0.5 * w.plastic));
                            }
                        }
                    }
                }
                (total, plastic)
            })
            .collect();
        let mut total = ContactWorks::default();
        let mut particle_plastic = particle_plastic;
        for (block, plastic) in &blocks {
            total.add(block);
            if let Some(pp) = particle_plastic.as_deref_mut() {
                for &(i, w) in plastic {
                    pp[i as usize] += w;
                }
            }
        }
        total
    }
}

/// Power of a kinematic wall on a sphere: the force on the sphere times the wall's velocity at
/// the contact point.
fn wall_power(wall: &RigidBody, point: &Vector3<f64>, force: &Vector3<f64>) -> f64 {
    let arm = point - to_na(wall.center_of_mass());
    let v = to_na(wall.linvel()) + to_na(wall.angvel()).cross(&arm);
    force.dot(&v)
}
