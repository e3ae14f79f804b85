//! The checkpoint payload: everything needed to continue a run bit-identically (bodies,
//! contacts, neighbour-list histories, random-number state, the energy books, the headline
//! tracker), and the scene keys a checkpoint must agree with. A checkpoint of the previous
//! format version is read into the present payload ([`CheckpointData::read`]).

mod format7;

use super::books::Books;
use super::build::Coupling;
use super::coupling::NeighbourListSceneStepper;
use super::Sim;
use crate::checkpoint::{self, CheckpointError};
use crate::headline::{HeadlineSample, Tracker};
use crate::laws::{AnyDamping, AnyNormalState, AnyTangential, SceneNormal, SceneRolling};
use crate::output::energy::EnergyRow;
use crate::output::vtk::CollectionEntry;
use crate::scene::Scene;
use mdr_contact::damping::DampingModel;
use mdr_contact::model::Books as WorkBooksOfContact;
use mdr_contact::model::{ContactLaw, ContactState};
use mdr_contact::normal::NormalLaw;
use mdr_contact::normal::NormalModel;
use mdr_contact::rolling::EpsdRollingState;
use mdr_contact::tangential::{MindlinState, TangentialModel};
use mdr_rapier::convert::{to_glam, to_na};
use mdr_rapier::neighbour_list::particles::NeighbourListParticles;
use mdr_rapier::neighbour_list::NeighbourListState;
use nalgebra::Vector3;
use rand_chacha::ChaCha8Rng;
use rapier3d_f64::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The composed law of a scene's pairs, with normal model `N`.
pub(crate) type SceneLaw<N> = ContactLaw<
    <N as NormalModel>::Law,
    <AnyTangential as TangentialModel>::Law,
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

impl ContactRecord {
    /// The record of a contact of normal model `N`.
    pub(crate) fn of<N: SceneNormal>(
        key: u64,
        contact: &ContactState<<N::Law as NormalLaw>::State, MindlinState, WorkBooksOfContact>,
        rolling: EpsdRollingState,
    ) -> Self {
        Self {
            key,
            contact: ContactState {
                normal: N::record(&contact.normal),
                tangential: contact.tangential,
                books: contact.books,
            },
            rolling,
        }
    }

    /// The normal, tangential and books history of a contact of normal model `N`.
    pub(crate) fn contact_state<N: SceneNormal>(
        &self,
    ) -> ContactState<<N::Law as NormalLaw>::State, MindlinState, WorkBooksOfContact> {
        ContactState {
            normal: N::restore(&self.contact.normal),
            tangential: self.contact.tangential,
            books: self.contact.books,
        }
    }
}

/// The neighbour-list stepper's state between two steps ([`mdr_rapier::neighbour_list::NeighbourListState`]),
/// with the histories of touching pairs only (the others are default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NeighbourListRecord {
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
pub(crate) type NeighbourListPairHistory<N, R> =
    mdr_rapier::neighbour_list::NeighbourListHistory<N, AnyTangential, R>;

impl NeighbourListRecord {
    pub(crate) fn of<N: SceneNormal, R: SceneRolling>(
        stepper: &NeighbourListSceneStepper<N, R>,
    ) -> Self {
        let state = stepper.export_lists();
        let touching =
            |active: &[bool], history: &[NeighbourListPairHistory<N, R>]| -> Vec<ContactRecord> {
                active
                    .iter()
                    .zip(history)
                    .enumerate()
                    .filter(|(_, (&a, _))| a)
                    .map(|(k, (_, h))| {
                        ContactRecord::of::<N>(k as u64, &h.contact, R::record(&h.rolling))
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
    ) -> Option<NeighbourListState<NeighbourListPairHistory<N, R>>> {
        let expand = |n: usize, records: &[ContactRecord]| {
            let mut active = vec![false; n];
            let mut history = vec![NeighbourListPairHistory::<N, R>::default(); n];
            for r in records {
                let k = usize::try_from(r.key).ok().filter(|&k| k < n)?;
                active[k] = true;
                history[k] = NeighbourListPairHistory::<N, R> {
                    contact: r.contact_state::<N>(),
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
    /// The run's generator at the start of `scene`: the placement used its own generator, and
    /// the run's continues the seed's stream after it.
    pub fn at_start(scene: &Scene) -> Self {
        use rand::SeedableRng;
        Self::of(&ChaCha8Rng::seed_from_u64(scene.seed.wrapping_add(1)))
    }

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

/// A neighbour-list run stepped outside this crate (the GPU path), at a step where a checkpoint
/// is due: what its checkpoint holds besides what the scene itself gives (rapier's world of
/// walls, the wall bodies, the surfaces' poses, the random generator, the scene's keys).
#[derive(Debug, Clone)]
pub struct NeighbourListRun {
    /// Step counter.
    pub step: u64,
    /// The particles, in the scene's order.
    pub particles: Vec<BodyRecord>,
    /// The lists and the touching pairs' histories (`surface_poses` is taken from the scene).
    pub lists: NeighbourListRecord,
    /// Energy books.
    pub books: Books,
    /// Headline tracker.
    pub tracker: Tracker,
    /// Frames written so far.
    pub collection: Vec<CollectionEntry>,
    /// Energy rows so far.
    pub energy: Vec<EnergyRow>,
    /// Headline samples so far.
    pub samples: Vec<HeadlineSample>,
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
    #[serde(rename = "fast")]
    pub neighbour_list: Option<NeighbourListRecord>,
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
    /// Read and check a checkpoint file of the present format version or of the previous one
    /// ([`checkpoint::PREVIOUS_FORMAT_VERSION`], decoded into the present payload with no
    /// adhesive history and no adhesive work); other versions are refused
    /// ([`CheckpointError::Version`]).
    pub fn read(path: &Path) -> Result<Self, CheckpointError> {
        let bytes = checkpoint::read_bytes(path)?;
        match checkpoint::check(path, &bytes)? {
            (checkpoint::PREVIOUS_FORMAT_VERSION, body) => {
                checkpoint::decode_payload::<format7::Payload>(path, body).map(Into::into)
            }
            (_, body) => checkpoint::decode_payload(path, body),
        }
    }

    /// The checkpoint of a neighbour-list run of `scene` stepped outside this crate's stepper,
    /// in the format the CPU run writes and reads: the walls (fixed, as the runs that use this
    /// have them) are the scene's at its set-up. `path` names the file in errors.
    pub fn of_neighbour_list_run(
        scene: &Scene,
        run: NeighbourListRun,
        path: &Path,
    ) -> Result<Self, crate::SimError> {
        let encode = |reason: String| CheckpointError::Encode {
            path: path.to_path_buf(),
            reason,
        };
        let built = super::build::build(scene)?;
        let Coupling::NeighbourList(stepper) = &built.coupling else {
            return Err(encode(format!(
                "scene `{}` does not run on the neighbour-list path",
                scene.name
            ))
            .into());
        };
        let mut lists = run.lists;
        lists.surface_poses = stepper.record().surface_poses;
        let mut bodies = run.particles;
        bodies.extend(
            built
                .wall_bodies
                .iter()
                .map(|h| BodyRecord::of(&built.world.bodies[*h])),
        );
        let world = postcard::to_stdvec(&built.world)
            .map_err(|e| encode(format!("rapier's world does not encode: {e}")))?;
        Ok(Self {
            scene_name: scene.name.clone(),
            fingerprint: fingerprint(scene),
            dt_bits: scene.dt.to_bits(),
            step: run.step,
            bodies,
            contacts: Vec::new(),
            neighbour_list: Some(lists),
            impacts: Vec::new(),
            world,
            books: run.books,
            rng: RngRecord::at_start(scene),
            tracker: run.tracker,
            collection: run.collection,
            energy: run.energy,
            samples: run.samples,
            scene_keys: fixed_keys(scene),
        })
    }

    /// Whether this checkpoint (read from `path`) belongs to `scene`: the same fingerprint
    /// (else the keys that changed are named) and time step.
    pub fn check_scene(&self, scene: &Scene, path: &Path) -> Result<(), CheckpointError> {
        let incompatible = |reason: String| CheckpointError::Incompatible {
            path: path.to_path_buf(),
            reason,
        };
        let fingerprint = fingerprint(scene);
        if self.fingerprint != fingerprint {
            let changes = changed_keys(&self.scene_keys, &fixed_keys(scene));
            let what = if changes.is_empty() {
                "the placed particles differ (a placement file changed?)".to_owned()
            } else {
                format!("changed: {}", changes.join(", "))
            };
            return Err(incompatible(format!(
                "it was written for scene `{}` with fingerprint {:08x}; this scene (`{}`) has {:08x}: \
                 {what} (only duration_s, the output/checkpoint/energy intervals and \
                 max_energy_drift may change on a restart)",
                self.scene_name, self.fingerprint, scene.name, fingerprint
            )));
        }
        if self.dt_bits != scene.dt.to_bits() {
            return Err(incompatible(format!(
                "time step {} s differs from the scene's {} s",
                f64::from_bits(self.dt_bits),
                scene.dt
            )));
        }
        Ok(())
    }

    /// Everything of `sim`; fails only if rapier's world does not encode (then nothing is
    /// written).
    pub(crate) fn capture(sim: &Sim<'_>) -> Result<Self, String> {
        let bodies = &sim.built.world.bodies;
        let mut records: Vec<BodyRecord> = match &sim.built.coupling {
            Coupling::NeighbourList(stepper) => {
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
        let neighbour_list = match &sim.built.coupling {
            Coupling::NeighbourList(stepper) => Some(stepper.record()),
            _ => None,
        };
        let (contacts, impacts) = match &sim.built.coupling {
            Coupling::RapierPipeline(stepper) => (stepper.records(), Vec::new()),
            Coupling::NeighbourList(_) => (Vec::new(), Vec::new()),
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
            Coupling::RapierPipeline(_) => Vec::new(),
            // The neighbour-list path's world holds the walls only (small): kept whole, so that
            // kinematic walls continue exactly (their derived state, e.g. the world centre of
            // mass, is not in a body record).
            Coupling::NeighbourList(_) | Coupling::Restitution(_) => {
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
            neighbour_list,
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
    use super::NeighbourListPairHistory;
    use crate::laws::AnyRolling;
    use mdr_contact::normal::{Hertz, MdrElastoPlastic, Thornton};
    use mdr_contact::rolling::NoRolling;
    use std::mem::size_of;

    /// A contact on the neighbour-list path carries its own laws' history and nothing else: the
    /// normal law's (8 bytes for MDR and Hertz, 24 for Thornton), Mindlin's displacement and
    /// radius (32), the work books (32), and the rolling spring (40) only with rolling resistance.
    #[test]
    fn a_contact_carries_only_its_laws_history() {
        assert_eq!(
            size_of::<NeighbourListPairHistory<MdrElastoPlastic, NoRolling>>(),
            72
        );
        assert_eq!(size_of::<NeighbourListPairHistory<Hertz, NoRolling>>(), 72);
        assert_eq!(
            size_of::<NeighbourListPairHistory<Thornton, NoRolling>>(),
            88
        );
        assert_eq!(
            size_of::<NeighbourListPairHistory<MdrElastoPlastic, AnyRolling>>(),
            112
        );
    }
}
