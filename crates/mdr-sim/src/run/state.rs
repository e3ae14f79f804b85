//! What a run carries from step to step besides rapier's bodies: the energy books, and the
//! checkpoint payload that holds everything needed to continue bit-identically.

use super::build::{with_fast, Coupling, FastSceneStepper, SceneStepper};
use super::Sim;
use crate::headline::{HeadlineSample, Tracker};
use crate::laws::{AnyDamping, AnyNormalState, SceneNormal, SceneRolling};
use crate::output::energy::EnergyRow;
use crate::output::vtk::CollectionEntry;
use crate::scene::Scene;
use mdr_contact::damping::DampingModel;
use mdr_contact::model::{ContactLaw, ContactState, WorkBooks};
use mdr_contact::normal::{NormalLaw, NormalModel};
use mdr_contact::rolling::{EpsdRollingState, RollingLaw};
use mdr_contact::tangential::{Mindlin, MindlinState, TangentialModel};
use mdr_rapier::convert::{to_glam, to_na};
use mdr_rapier::kernel::ContactWorks;
use mdr_rapier::neighbour_list::particles::NeighbourListParticles;
use mdr_rapier::neighbour_list::{ContactPartner, EndedContact, NeighbourListState};
use nalgebra::Vector3;
use rand_chacha::ChaCha8Rng;
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
/// the live contacts' books are added when the books are read ([`Books::live_fast`]), so a step
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
    /// Rapier path: every touching pair at the last update, sorted by key, with its books then.
    pub last: Vec<PairBooks>,
    /// Plastic work per particle (J; on the neighbour-list path, of the contacts that ended).
    pub particle_plastic: Vec<f64>,
    /// Buffer of the contacts that ended in a step (empty between steps).
    #[serde(skip)]
    ended: Vec<EndedContact>,
}

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
            // The plastic work is a function of the largest overlap
            // (`NormalLaw::dissipated_work`): the same as at the last update unless that grew.
            let max_overlap = e.law.normal.max_overlap(&h.contact.normal);
            let plastic = if max_overlap == prev.max_overlap && prev.key == key {
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
            };
            let dp = now.plastic - prev.plastic;
            self.plastic += dp;
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
    pub(crate) fn take_fast<N: SceneNormal, R: SceneRolling>(
        &mut self,
        stepper: &mut FastSceneStepper<N, R>,
        bodies: &RigidBodySet,
        dt: f64,
    ) {
        stepper.take_ended_contacts(&mut self.ended);
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

    /// The books of the contacts alive on the neighbour-list path, to add to the totals
    /// ([`Books`]); with `particle_plastic`, their plastic work is added to it per particle
    /// (half to each sphere of a pair). Taken in parallel over fixed blocks of particles and
    /// joined in block order, so the sums do not depend on the number of threads.
    pub(crate) fn live_fast<N: SceneNormal, R: SceneRolling>(
        stepper: &FastSceneStepper<N, R>,
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

/// The composed law of a scene's pairs, with normal model `N`.
pub(crate) type SceneLaw<N> = ContactLaw<
    <N as NormalModel>::Law,
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
    pub fn of_particle(p: &NeighbourListParticles, i: usize) -> Self {
        let q = p.rotation[i];
        Self {
            translation: p.position[i].into(),
            rotation: [q.x, q.y, q.z, q.w],
            linvel: p.linvel[i].into(),
            angvel: p.angvel[i].into(),
        }
    }

    /// Put the record into particle `i` of the neighbour-list path.
    pub fn apply_to_particle(&self, p: &mut NeighbourListParticles, i: usize) {
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

/// The neighbour-list stepper's state between two steps ([`mdr_rapier::neighbour_list::NeighbourListState`]),
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

/// The history of one pair on the neighbour-list path of a scene with normal model `N` and
/// rolling model `R`.
pub(crate) type FastPairHistory<N, R> =
    mdr_rapier::neighbour_list::NeighbourListHistory<N, Mindlin, R>;

impl FastRecord {
    pub(crate) fn of<N: SceneNormal, R: SceneRolling>(stepper: &FastSceneStepper<N, R>) -> Self {
        let state = stepper.export_lists();
        let touching = |active: &[bool], history: &[FastPairHistory<N, R>]| -> Vec<ContactRecord> {
            active
                .iter()
                .zip(history)
                .enumerate()
                .filter(|(_, (&a, _))| a)
                .map(|(k, (_, h))| ContactRecord {
                    key: k as u64,
                    contact: ContactState {
                        normal: N::record(&h.contact.normal),
                        tangential: h.contact.tangential,
                        books: h.contact.books,
                    },
                    rolling: R::record(&h.rolling),
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
    pub(crate) fn to_state<N: SceneNormal, R: SceneRolling>(
        &self,
    ) -> Option<NeighbourListState<FastPairHistory<N, R>>> {
        let expand = |n: usize, records: &[ContactRecord]| {
            let mut active = vec![false; n];
            let mut history = vec![FastPairHistory::<N, R>::default(); n];
            for r in records {
                let k = usize::try_from(r.key).ok().filter(|&k| k < n)?;
                active[k] = true;
                history[k] = FastPairHistory::<N, R> {
                    contact: ContactState {
                        normal: N::restore(&r.contact.normal),
                        tangential: r.contact.tangential,
                        books: r.contact.books,
                    },
                    rolling: R::restore(&r.rolling),
                };
            }
            Some((active, history))
        };
        let (pair_active, pair_history) = expand(self.pairs.len(), &self.pair_histories)?;
        let (surface_active, surface_history) =
            expand(self.surface_pairs.len(), &self.surface_histories)?;
        Some(NeighbourListState {
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
    /// Particles (bodies on the rapier pipeline path, the stepper's arrays on the neighbour-list path),
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
    /// The scene's keys a restart may not change, as `fixed_keys` lists them (to name what
    /// changed when a restart is refused).
    pub scene_keys: Vec<(String, String)>,
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
            Coupling::Fast(stepper) => Some(with_fast!(stepper, s => FastRecord::of(s))),
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
            books: sim.books.clone(),
            rng: RngRecord::of(&sim.rng),
            tracker: sim.tracker.clone(),
            collection: sim.collection.clone(),
            energy: sim.energy.clone(),
            samples: sim.samples.clone(),
            scene_keys: fixed_keys(sim.scene),
        })
    }
}

/// The scene file's content as TOML with the keys a restart may change (duration, intervals,
/// the energy guard) blanked.
fn fixed_source(scene: &Scene) -> String {
    let mut source = scene.source.clone();
    source.run.duration_s = 0.0;
    source.run.output_interval_s = 0.0;
    source.run.checkpoint_interval_s = None;
    source.run.energy_interval_s = None;
    source.run.max_energy_drift = None;
    toml::to_string(&source).unwrap_or_default()
}

/// The keys of the scene a restart may not change, each as `(key path, value)`: what a
/// checkpoint keeps to say which of them changed.
pub fn fixed_keys(scene: &Scene) -> Vec<(String, String)> {
    fn walk(prefix: &str, value: &toml::Value, out: &mut Vec<(String, String)>) {
        match value {
            toml::Value::Table(t) => {
                for (k, v) in t {
                    let path = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    walk(&path, v, out);
                }
            }
            toml::Value::Array(a) if a.iter().all(toml::Value::is_table) && !a.is_empty() => {
                for (i, v) in a.iter().enumerate() {
                    walk(&format!("{prefix}[{i}]"), v, out);
                }
            }
            other => out.push((prefix.to_owned(), other.to_string())),
        }
    }
    let mut out = Vec::new();
    if let Ok(table) = toml::from_str::<toml::Table>(&fixed_source(scene)) {
        walk("", &toml::Value::Table(table), &mut out);
    }
    out
}

/// What differs between the keys a checkpoint was written with and a scene's, in words.
pub fn changed_keys(before: &[(String, String)], now: &[(String, String)]) -> Vec<String> {
    let find = |keys: &[(String, String)], k: &str| {
        keys.iter()
            .find(|(key, _)| key == k)
            .map(|(_, v)| v.clone())
    };
    let mut changes = Vec::new();
    for (k, v) in before {
        match find(now, k) {
            Some(w) if &w != v => changes.push(format!("`{k}` {v} → {w}")),
            None => changes.push(format!("`{k}` = {v} removed")),
            _ => {}
        }
    }
    for (k, w) in now {
        if find(before, k).is_none() {
            changes.push(format!("`{k}` = {w} added"));
        }
    }
    changes
}

/// CRC-32 of the scene file's content with the keys a restart may change (duration and
/// intervals) blanked, and of the placed particles.
pub fn fingerprint(scene: &Scene) -> u32 {
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(fixed_source(scene).as_bytes());
    for p in &scene.particles {
        for c in p.position.iter().chain(std::iter::once(&p.radius)) {
            hasher.update(&c.to_le_bytes());
        }
    }
    hasher.finalize()
}

#[cfg(test)]
mod tests {
    use super::FastPairHistory;
    use mdr_contact::normal::{Hertz, MdrElastoPlastic, Thornton};
    use mdr_contact::rolling::{EpsdRolling, NoRolling};
    use std::mem::size_of;

    /// A contact on the neighbour-list path carries its own laws' history and nothing else: the
    /// normal law's (8 bytes for MDR and Hertz, 24 for Thornton), Mindlin's displacement and
    /// radius (32), the work books (32), and the rolling spring (40) only with rolling resistance.
    #[test]
    fn a_contact_carries_only_its_laws_history() {
        assert_eq!(
            size_of::<FastPairHistory<MdrElastoPlastic, NoRolling>>(),
            72
        );
        assert_eq!(size_of::<FastPairHistory<Hertz, NoRolling>>(), 72);
        assert_eq!(size_of::<FastPairHistory<Thornton, NoRolling>>(), 88);
        assert_eq!(
            size_of::<FastPairHistory<MdrElastoPlastic, EpsdRolling>>(),
            112
        );
    }
}
