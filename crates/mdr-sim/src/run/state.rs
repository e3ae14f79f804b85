//! What a run carries from step to step besides rapier's bodies: the energy books, and the
//! checkpoint payload that holds everything needed to continue bit-identically.

use super::build::{Coupling, FastSceneStepper, SceneStepper};
use super::Sim;
use crate::headline::{HeadlineSample, Tracker};
use crate::laws::{AnyDamping, AnyNormal, AnyNormalState, AnyRollingLaw};
use crate::output::energy::EnergyRow;
use crate::output::vtk::CollectionEntry;
use crate::scene::Scene;
use mdr_contact::damping::DampingModel;
use mdr_contact::model::{ContactLaw, ContactState, WorkBooks};
use mdr_contact::normal::{NormalLaw, NormalModel};
use mdr_contact::rolling::{EpsdRollingState, RollingLaw};
use mdr_contact::tangential::{Mindlin, MindlinState, TangentialModel};
use mdr_rapier::convert::{to_glam, to_na};
use mdr_rapier::fast::particles::FastParticles;
use mdr_rapier::fast::FastListState;
use nalgebra::Vector3;
use rand_chacha::ChaCha8Rng;
use rapier3d_f64::prelude::*;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Running totals of the dissipated work and of the work of moving walls. A pair's history (and
/// its work books) is dropped when the pair separates, so the totals take each contact's
/// increments step by step.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
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
    /// Every touching pair at the last update, sorted by key: its work books and the spring
    /// states the next update starts from. The neighbour-list path keeps them per block of
    /// particles between its updates instead (`blocks`, empty here); a checkpoint holds them
    /// here ([`Books::for_checkpoint`]).
    pub last: Vec<PairBooks>,
    /// Plastic work per particle (J).
    pub particle_plastic: Vec<f64>,
    /// Neighbour-list path: the pair books of each block of particles at the last update.
    #[serde(skip)]
    blocks: Vec<Vec<PairBooks>>,
    /// Buffers for the next update's blocks (reused, so steady updates do not allocate).
    #[serde(skip)]
    spare: Vec<Vec<PairBooks>>,
}

/// Equal totals and equal pair books, however each keeps its pairs between updates.
impl PartialEq for Books {
    fn eq(&self, other: &Self) -> bool {
        let (a, b) = (self.for_checkpoint(), other.for_checkpoint());
        a.plastic == b.plastic
            && a.friction == b.friction
            && a.damping == b.damping
            && a.rolling == b.rolling
            && a.wall_work == b.wall_work
            && a.stiffness_tangential == b.stiffness_tangential
            && a.stiffness_rolling == b.stiffness_rolling
            && a.removed == b.removed
            && a.last == b.last
            && a.particle_plastic == b.particle_plastic
    }
}

/// What the books keep of one touching pair between updates.
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
    /// `|ξ|²` of the Mindlin spring after the update (m²).
    pub displacement_len2: f64,
    /// Contact radius the Mindlin spring was stored at (m; 0 when it holds nothing).
    pub contact_radius: f64,
    /// `|M_r|²` of the rolling spring after the update ((N·m)²).
    pub torque_len2: f64,
    /// Stiffness of the rolling spring after the update (N·m/rad; 0 when it holds nothing).
    pub rolling_stiffness: f64,
}

impl Books {
    pub(crate) fn new(particles: usize) -> Self {
        Self {
            particle_plastic: vec![0.0; particles],
            ..Self::default()
        }
    }

    /// Take the increments of the step whose forces were just computed (rapier path).
    pub(crate) fn take(
        &mut self,
        stepper: &SceneStepper,
        bodies: &RigidBodySet,
        particle_of_collider: &[usize],
        wall_of_collider: &[usize],
        dt: f64,
    ) {
        let entries = stepper.contacts().entries();
        let mut block = BlockBooks {
            next: Vec::with_capacity(entries.len()),
            ..BlockBooks::default()
        };
        let particle = |c: ColliderHandle| {
            particle_of_collider
                .get(c.into_raw_parts().0 as usize)
                .copied()
                .filter(|&i| i != usize::MAX)
        };
        for e in entries {
            let owners = (particle(e.collider1), particle(e.collider2));
            block.book_pair(
                &self.last,
                e.key.0,
                &e.law,
                &e.rolling,
                &e.history.contact,
                &e.history.rolling,
                owners,
            );
            // Work of a moving wall on the sphere: F · v_wall(contact point) dt.
            let on_wall = wall_of_collider
                .get(e.collider2.into_raw_parts().0 as usize)
                .is_some_and(|&w| w != usize::MAX);
            if on_wall {
                if let Some(b2) = e.body2.and_then(|h| bodies.get(h)) {
                    if b2.is_kinematic() {
                        block.totals.wall_work +=
                            wall_power(b2, &e.contact.point, &e.wrench.force) * dt;
                    }
                }
            }
        }
        self.add(&block.totals, &block.plastic_by_particle);
        self.last = block.next;
        self.blocks.clear();
    }

    /// [`Books::take`] on the neighbour-list path. Pairs are visited per particle `i` in the
    /// stepper's order, its surfaces first (key `i · 2³² + s`), then its partners `j > i` (key
    /// `i · 2³² + 2³¹ + j`), so the keys increase as the books' merge needs (scenes are not
    /// periodic: one image per pair).
    ///
    /// The particles are booked in parallel in blocks of a fixed size: each block merges with
    /// its own pair books of the last update, keeps its own totals, and lists its per-particle
    /// plastic increments in visit order. The blocks are then joined in order, so the books do
    /// not depend on the number of threads, and each particle's plastic work takes its
    /// increments in the same order as a one-block pass.
    pub(crate) fn take_fast(&mut self, stepper: &FastSceneStepper, bodies: &RigidBodySet, dt: f64) {
        /// Particles per block.
        const BLOCK: usize = 2048;
        let p = stepper.particles();
        let pairs = stepper.pairs();
        let sp = stepper.surface_pairs();
        let surfaces = stepper.surfaces();
        let n = p.len();
        let nblocks = n.div_ceil(BLOCK);
        // The last update's books of each block: kept per block, or (after a restart or a
        // rapier-path update) found by key in the flat list.
        let last = &self.last;
        let previous: Vec<&[PairBooks]> = if last.is_empty() && self.blocks.len() == nblocks {
            self.blocks.iter().map(Vec::as_slice).collect()
        } else {
            let at = |b: usize| last.partition_point(|l| l.key < ((b * BLOCK) as u64) << 32);
            (0..nblocks).map(|b| &last[at(b)..at(b + 1)]).collect()
        };
        let mut spare = std::mem::take(&mut self.spare);
        spare.resize_with(nblocks, Vec::new);
        let blocks: Vec<BlockBooks> = spare
            .par_drain(..nblocks)
            .zip(previous.into_par_iter())
            .enumerate()
            .map(|(b, (mut next, last))| {
                next.clear();
                let mut block = BlockBooks {
                    next,
                    ..BlockBooks::default()
                };
                for i in b * BLOCK..((b + 1) * BLOCK).min(n) {
                    for q in sp.start[i] as usize..sp.start[i + 1] as usize {
                        if !sp.active[q] {
                            continue;
                        }
                        let s = sp.surface[q] as usize;
                        let (law, rolling) = stepper.surface_pair_laws(i, s);
                        let h = &sp.history[q];
                        let key = ((i as u64) << 32) | s as u64;
                        block.book_pair(
                            last,
                            key,
                            law,
                            rolling,
                            &h.contact,
                            &h.rolling,
                            (Some(i), None),
                        );
                        if let Some(b2) = surfaces[s].body.and_then(|h| bodies.get(h)) {
                            if b2.is_kinematic() {
                                block.totals.wall_work +=
                                    wall_power(b2, &sp.contact[q].point, &sp.wrench[q].force) * dt;
                            }
                        }
                    }
                    for q in pairs.first[i] as usize..pairs.first[i + 1] as usize {
                        if !pairs.active[q] {
                            continue;
                        }
                        let pj = pairs.j[q] as usize;
                        let (law, rolling) = stepper.sphere_pair_laws(i, pj);
                        let h = &pairs.history[q];
                        let key = ((i as u64) << 32) | (1 << 31) | pj as u64;
                        block.book_pair(
                            last,
                            key,
                            law,
                            rolling,
                            &h.contact,
                            &h.rolling,
                            (Some(i), Some(pj)),
                        );
                    }
                }
                block
            })
            .collect();
        // The last update's block buffers become the next update's spares.
        self.spare = std::mem::take(&mut self.blocks);
        self.last.clear();
        for mut block in blocks {
            self.add(&block.totals, &block.plastic_by_particle);
            self.blocks.push(std::mem::take(&mut block.next));
        }
    }

    /// A copy for a checkpoint: every pair's books in the flat list `last`.
    pub(crate) fn for_checkpoint(&self) -> Self {
        let mut books = self.clone();
        if !self.blocks.is_empty() {
            books.last = self.blocks.concat();
            books.blocks.clear();
        }
        books.spare.clear();
        books
    }

    /// Add a block's increments to the running totals.
    fn add(&mut self, t: &Totals, plastic_by_particle: &[(u32, f64)]) {
        self.plastic += t.plastic;
        self.friction += t.friction;
        self.damping += t.damping;
        self.rolling += t.rolling;
        self.wall_work += t.wall_work;
        self.stiffness_tangential += t.stiffness_tangential;
        self.stiffness_rolling += t.stiffness_rolling;
        for &(i, dp) in plastic_by_particle {
            self.particle_plastic[i as usize] += dp;
        }
    }
}

/// Increments of the running totals of [`Books`] over some pairs.
#[derive(Debug, Clone, Copy, Default)]
struct Totals {
    plastic: f64,
    friction: f64,
    damping: f64,
    rolling: f64,
    wall_work: f64,
    stiffness_tangential: f64,
    stiffness_rolling: f64,
}

/// The books of one block of particles, or of one pair on the rapier path.
#[derive(Debug, Default)]
struct BlockBooks {
    /// Position in the previous update's pair books from which the next key is looked for.
    j: usize,
    totals: Totals,
    /// The block's pairs, in key order.
    next: Vec<PairBooks>,
    /// Plastic-work increments per particle, in visit order.
    plastic_by_particle: Vec<(u32, f64)>,
}

impl BlockBooks {
    /// Book one touching pair: its work increments since the last update (found by key in
    /// `last` from position `self.j` on) and the energy its springs lost without work.
    #[allow(clippy::too_many_arguments)]
    fn book_pair(
        &mut self,
        last: &[PairBooks],
        key: u64,
        law: &SceneLaw,
        rolling_law: &AnyRollingLaw,
        contact: &ContactState<AnyNormalState, MindlinState>,
        rolling: &EpsdRollingState,
        owners: (Option<usize>, Option<usize>),
    ) {
        while self.j < last.len() && last[self.j].key < key {
            self.j += 1;
        }
        let prev = match last.get(self.j) {
            Some(l) if l.key == key => *l,
            _ => PairBooks::default(),
        };
        // The plastic work is a function of the largest overlap (`NormalLaw::dissipated_work`):
        // the same as at the last update unless that grew.
        let max_overlap = law.normal.max_overlap(&contact.normal);
        let plastic_work = if max_overlap == prev.max_overlap && prev.key == key {
            prev.plastic
        } else {
            law.normal.dissipated_work(&contact.normal)
        };
        let friction_work = contact.books.friction_work();
        let damping_work = contact.books.damping_work();
        let rolling_work = rolling_law.dissipated_work(rolling);
        let dp = plastic_work - prev.plastic;
        let t = &mut self.totals;
        t.plastic += dp;
        t.friction += friction_work - prev.friction;
        t.damping += damping_work - prev.damping;
        t.rolling += rolling_work - prev.rolling;
        // The springs' energy change without work in this update, from the state the update
        // started from (docs/theory.md, "Energy books of the incremental springs").
        let tangential = &contact.tangential;
        t.stiffness_tangential -= law.tangential.stiffness_energy_change(
            prev.displacement_len2,
            prev.contact_radius,
            tangential.contact_radius,
        );
        t.stiffness_rolling -= EpsdRollingState::stiffness_energy_change(
            prev.torque_len2,
            prev.rolling_stiffness,
            rolling.stiffness,
        );
        if dp != 0.0 {
            let plastic = &mut self.plastic_by_particle;
            match owners {
                (Some(a), Some(b)) => {
                    plastic.push((a as u32, 0.5 * dp));
                    plastic.push((b as u32, 0.5 * dp));
                }
                (Some(a), None) | (None, Some(a)) => plastic.push((a as u32, dp)),
                (None, None) => {}
            }
        }
        self.next.push(PairBooks {
            key,
            plastic: plastic_work,
            max_overlap,
            friction: friction_work,
            damping: damping_work,
            rolling: rolling_work,
            displacement_len2: tangential.displacement.norm_squared(),
            contact_radius: tangential.contact_radius,
            torque_len2: rolling.torque.norm_squared(),
            rolling_stiffness: rolling.stiffness,
        });
    }
}

/// Power of a kinematic wall on a sphere: the force on the sphere times the wall's velocity at
/// the contact point.
fn wall_power(wall: &RigidBody, point: &Vector3<f64>, force: &Vector3<f64>) -> f64 {
    let arm = point - to_na(wall.center_of_mass());
    let v = to_na(wall.linvel()) + to_na(wall.angvel()).cross(&arm);
    force.dot(&v)
}

/// The composed law of a scene's pairs.
pub(crate) type SceneLaw = ContactLaw<
    <AnyNormal as NormalModel>::Law,
    <Mindlin as TangentialModel>::Law,
    <AnyDamping as DampingModel>::Law,
>;

/// Pose and velocities of one rigid body, exactly.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BodyRecord {
    /// Translation (m).
    pub translation: [f64; 3],
    /// Rotation quaternion `(x, y, z, w)`.
    pub rotation: [f64; 4],
    /// Linear velocity (m/s).
    pub linvel: [f64; 3],
    /// Angular velocity (rad/s).
    pub angvel: [f64; 3],
}

impl BodyRecord {
    /// The record of a body.
    pub fn of(body: &RigidBody) -> Self {
        let p = body.position();
        let q = p.rotation;
        Self {
            translation: to_na(p.translation).into(),
            rotation: [q.x, q.y, q.z, q.w],
            linvel: to_na(body.linvel()).into(),
            angvel: to_na(body.angvel()).into(),
        }
    }

    /// The record of particle `i` of the neighbour-list path.
    pub fn of_particle(p: &FastParticles, i: usize) -> Self {
        let q = p.rotation[i];
        Self {
            translation: p.position[i].into(),
            rotation: [q.x, q.y, q.z, q.w],
            linvel: p.linvel[i].into(),
            angvel: p.angvel[i].into(),
        }
    }

    /// Put the record into particle `i` of the neighbour-list path.
    pub fn apply_to_particle(&self, p: &mut FastParticles, i: usize) {
        let [x, y, z, w] = self.rotation;
        p.position[i] = Vector3::from(self.translation);
        p.rotation[i] = rapier3d_f64::math::Rotation::from_xyzw(x, y, z, w);
        p.linvel[i] = Vector3::from(self.linvel);
        p.angvel[i] = Vector3::from(self.angvel);
    }

    /// Put the record into a body.
    pub fn apply(&self, body: &mut RigidBody) {
        let [x, y, z, w] = self.rotation;
        let rotation = rapier3d_f64::math::Rotation::from_xyzw(x, y, z, w);
        body.set_position(
            Pose::from_parts(to_glam(&Vector3::from(self.translation)), rotation),
            true,
        );
        body.set_linvel(to_glam(&Vector3::from(self.linvel)), true);
        body.set_angvel(to_glam(&Vector3::from(self.angvel)), true);
    }
}

/// The history of one touching pair (force mode).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactRecord {
    /// Pair key.
    pub key: u64,
    /// Normal + tangential history and work books.
    pub contact: ContactState<AnyNormalState, MindlinState>,
    /// Rolling history.
    pub rolling: EpsdRollingState,
}

/// The neighbour-list stepper's state between two steps ([`mdr_rapier::fast::FastListState`]),
/// with the histories of touching pairs only (the others are default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FastRecord {
    /// Positions at the last build.
    pub built_at: Vec<[f64; 3]>,
    /// Largest displacement since the last build (m).
    pub max_displacement: f64,
    /// Surface poses at the last build: translation, then rotation `(x, y, z, w)`.
    pub surface_poses: Vec<[f64; 7]>,
    /// Builds so far.
    pub rebuilds: u64,
    /// Sphere pairs of the list `(i, j, image)`.
    pub pairs: Vec<(u32, u32, u8)>,
    /// Touching sphere pairs: `key` = index into `pairs`.
    pub pair_histories: Vec<ContactRecord>,
    /// Particle–surface candidates `(particle, surface)`.
    pub surface_pairs: Vec<(u32, u32)>,
    /// Touching candidates: `key` = index into `surface_pairs`.
    pub surface_histories: Vec<ContactRecord>,
}

pub(crate) type FastPairHistory =
    mdr_rapier::kernel::PairHistory<ContactState<AnyNormalState, MindlinState>, EpsdRollingState>;

impl FastRecord {
    pub(crate) fn of(stepper: &FastSceneStepper) -> Self {
        let state = stepper.export_lists();
        let touching = |active: &[bool], history: &[FastPairHistory]| -> Vec<ContactRecord> {
            active
                .iter()
                .zip(history)
                .enumerate()
                .filter(|(_, (&a, _))| a)
                .map(|(k, (_, h))| ContactRecord {
                    key: k as u64,
                    contact: h.contact.clone(),
                    rolling: h.rolling,
                })
                .collect()
        };
        Self {
            built_at: state.built_at.iter().map(|x| (*x).into()).collect(),
            max_displacement: state.max_displacement,
            surface_poses: state
                .surface_poses
                .iter()
                .map(|p| {
                    let (t, q) = (p.translation, p.rotation);
                    [t.x, t.y, t.z, q.x, q.y, q.z, q.w]
                })
                .collect(),
            rebuilds: state.rebuilds,
            pair_histories: touching(&state.pair_active, &state.pair_history),
            pairs: state.pairs,
            surface_histories: touching(&state.surface_active, &state.surface_history),
            surface_pairs: state.surface_pairs,
        }
    }

    /// The stepper's state; `None` if a history's index is out of range.
    pub(crate) fn to_state(&self) -> Option<FastListState<FastPairHistory>> {
        let expand = |n: usize, records: &[ContactRecord]| {
            let mut active = vec![false; n];
            let mut history = vec![FastPairHistory::default(); n];
            for r in records {
                let k = usize::try_from(r.key).ok().filter(|&k| k < n)?;
                active[k] = true;
                history[k] = FastPairHistory {
                    contact: r.contact.clone(),
                    rolling: r.rolling,
                };
            }
            Some((active, history))
        };
        let (pair_active, pair_history) = expand(self.pairs.len(), &self.pair_histories)?;
        let (surface_active, surface_history) =
            expand(self.surface_pairs.len(), &self.surface_histories)?;
        Some(FastListState {
            built_at: self.built_at.iter().map(|&x| Vector3::from(x)).collect(),
            max_displacement: self.max_displacement,
            surface_poses: self
                .surface_poses
                .iter()
                .map(|p| {
                    Pose::from_parts(
                        rapier3d_f64::math::Vector::new(p[0], p[1], p[2]),
                        rapier3d_f64::math::Rotation::from_xyzw(p[3], p[4], p[5], p[6]),
                    )
                })
                .collect(),
            rebuilds: self.rebuilds,
            pairs: self.pairs.clone(),
            pair_active,
            pair_history,
            surface_pairs: self.surface_pairs.clone(),
            surface_active,
            surface_history,
        })
    }
}

/// State of the run's random generator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RngRecord {
    seed: [u8; 32],
    stream: u64,
    word_pos: u128,
}

impl RngRecord {
    fn of(rng: &ChaCha8Rng) -> Self {
        Self {
            seed: rng.get_seed(),
            stream: rng.get_stream(),
            word_pos: rng.get_word_pos(),
        }
    }

    pub(crate) fn restore(&self) -> ChaCha8Rng {
        use rand::SeedableRng;
        let mut rng = ChaCha8Rng::from_seed(self.seed);
        rng.set_stream(self.stream);
        rng.set_word_pos(self.word_pos);
        rng
    }
}

/// Everything a checkpoint holds.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CheckpointData {
    /// Scene name (messages only).
    pub scene_name: String,
    /// Fingerprint of the scene (see the private `fingerprint` function).
    pub fingerprint: u32,
    /// Bits of the time step.
    pub dt_bits: u64,
    /// Step counter.
    pub step: u64,
    /// Particles (bodies on rapier's path, the stepper's arrays on the neighbour-list path),
    /// then wall bodies, in creation order.
    pub bodies: Vec<BodyRecord>,
    /// Force mode on rapier's pipeline: per-pair histories, sorted by key.
    pub contacts: Vec<ContactRecord>,
    /// Force mode on the neighbour-list path: its lists and histories (the particles are in
    /// `bodies`).
    pub fast: Option<FastRecord>,
    /// Restitution mode: `(pair key, largest overlap)` of the impact history.
    pub impacts: Vec<(u64, f64)>,
    /// Restitution mode and the neighbour-list path (whose world holds the walls only):
    /// rapier's world as `postcard` bytes of `PhysicsWorld` (bodies,
    /// colliders, broad phase, narrow phase with every contact manifold and its warm-start
    /// impulses, islands; rapier leaves out only its pipelines' scratch buffers). Rapier's
    /// solver reads its contacts' previous impulses and its broad phase's tree, so rebuilding
    /// the world from the scene would continue correctly but not bit-identically. Empty on
    /// rapier's force path, where rapier solves no contacts and the bodies alone are the state.
    pub world: Vec<u8>,
    /// Energy books.
    pub books: Books,
    /// Random generator.
    pub rng: RngRecord,
    /// Headline tracker.
    pub tracker: Tracker,
    /// Frames written so far.
    pub collection: Vec<CollectionEntry>,
    /// Energy rows so far.
    pub energy: Vec<EnergyRow>,
    /// Headline samples so far.
    pub samples: Vec<HeadlineSample>,
}

impl CheckpointData {
    /// Everything of `sim`; fails only if rapier's world does not encode (then nothing is
    /// written).
    pub(crate) fn capture(sim: &Sim<'_>) -> Result<Self, String> {
        let bodies = &sim.built.world.bodies;
        let mut records: Vec<BodyRecord> = match &sim.built.coupling {
            Coupling::Fast(stepper) => {
                let p = stepper.particles();
                (0..p.len())
                    .map(|i| BodyRecord::of_particle(p, i))
                    .collect()
            }
            _ => Vec::new(),
        };
        records.extend(
            sim.built
                .particle_bodies
                .iter()
                .chain(&sim.built.wall_bodies)
                .map(|h| BodyRecord::of(&bodies[*h])),
        );
        let fast = match &sim.built.coupling {
            Coupling::Fast(stepper) => Some(FastRecord::of(stepper)),
            _ => None,
        };
        let (contacts, impacts) = match &sim.built.coupling {
            Coupling::Force(stepper) => (
                stepper
                    .contacts()
                    .entries()
                    .iter()
                    .map(|e| ContactRecord {
                        key: e.key.0,
                        contact: e.history.contact.clone(),
                        rolling: e.history.rolling,
                    })
                    .collect(),
                Vec::new(),
            ),
            Coupling::Fast(_) => (Vec::new(), Vec::new()),
            Coupling::Restitution(hooks) => {
                let h = hooks.history();
                let impacts = (0..h.allocated())
                    .filter(|&slot| h.find(h.key(slot)) == Some(slot))
                    .map(|slot| (h.key(slot).0, h.state(slot).max_overlap))
                    .collect();
                (Vec::new(), impacts)
            }
        };
        let world = match &sim.built.coupling {
            Coupling::Force(_) => Vec::new(),
            // The neighbour-list path's world holds the walls only (small): kept whole, so that
            // kinematic walls continue exactly (their derived state, e.g. the world centre of
            // mass, is not in a body record).
            Coupling::Fast(_) | Coupling::Restitution(_) => {
                postcard::to_stdvec(&sim.built.world)
                    .map_err(|e| format!("rapier's world does not encode: {e}"))?
            }
        };
        Ok(Self {
            scene_name: sim.scene.name.clone(),
            fingerprint: fingerprint(sim.scene),
            dt_bits: sim.scene.dt.to_bits(),
            step: sim.step,
            bodies: records,
            contacts,
            fast,
            impacts,
            world,
            books: sim.books.for_checkpoint(),
            rng: RngRecord::of(&sim.rng),
            tracker: sim.tracker.clone(),
            collection: sim.collection.clone(),
            energy: sim.energy.clone(),
            samples: sim.samples.clone(),
        })
    }
}

/// CRC-32 of the scene file's content with the keys a restart may change (duration and
/// intervals) blanked, and of the placed particles.
pub fn fingerprint(scene: &Scene) -> u32 {
    let mut source = scene.source.clone();
    source.run.duration_s = 0.0;
    source.run.output_interval_s = 0.0;
    source.run.checkpoint_interval_s = None;
    source.run.energy_interval_s = None;
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(toml::to_string(&source).unwrap_or_default().as_bytes());
    for p in &scene.particles {
        for c in p.position.iter().chain(std::iter::once(&p.radius)) {
            hasher.update(&c.to_le_bytes());
        }
    }
    hasher.finalize()
}
