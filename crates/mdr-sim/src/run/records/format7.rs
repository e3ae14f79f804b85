//! The checkpoint payload of the previous format version
//! ([`crate::checkpoint::PREVIOUS_FORMAT_VERSION`]), read into the present one. Its types are the
//! present ones less what the present format added: the adhesive MDR history in each contact's
//! normal history, the adhesive work in the energy books and in each pair's books, and the
//! adhesive column of the energy rows. A run that wrote this format had no adhesive law, so what
//! it lacks is zero (and the adhesive history its default, a contact that never adhered).

use super::{BodyRecord, CheckpointData, ContactRecord, NeighbourListRecord, RngRecord};
use crate::headline::{HeadlineSample, Tracker};
use crate::laws::AnyNormalState;
use crate::output::energy::EnergyRow;
use crate::output::vtk::CollectionEntry;
use crate::run::books::{Books, PairBooks};
use mdr_contact::model::ContactState;
use mdr_contact::normal::{MdrState, ThorntonState};
use mdr_contact::rolling::EpsdRollingState;
use mdr_contact::tangential::MindlinState;
use serde::Deserialize;

/// [`AnyNormalState`] without the adhesive MDR history.
#[derive(Deserialize)]
struct NormalHistory {
    mdr: MdrState,
    hertz: f64,
    thornton: ThorntonState,
}

/// [`ContactRecord`] with the normal history of this format.
#[derive(Deserialize)]
struct Contact {
    key: u64,
    contact: ContactState<NormalHistory, MindlinState>,
    rolling: EpsdRollingState,
}

impl From<Contact> for ContactRecord {
    fn from(c: Contact) -> Self {
        let NormalHistory {
            mdr,
            hertz,
            thornton,
        } = c.contact.normal;
        Self {
            key: c.key,
            contact: ContactState {
                normal: AnyNormalState {
                    mdr,
                    hertz,
                    thornton,
                    ..AnyNormalState::default()
                },
                tangential: c.contact.tangential,
                books: c.contact.books,
            },
            rolling: c.rolling,
        }
    }
}

/// [`NeighbourListRecord`] with the contact records of this format.
#[derive(Deserialize)]
struct NeighbourList {
    built_at: Vec<[f64; 3]>,
    max_displacement: f64,
    surface_poses: Vec<[f64; 7]>,
    rebuilds: u64,
    pairs: Vec<(u32, u32, u8)>,
    pair_histories: Vec<Contact>,
    surface_pairs: Vec<(u32, u32)>,
    surface_histories: Vec<Contact>,
}

impl From<NeighbourList> for NeighbourListRecord {
    fn from(n: NeighbourList) -> Self {
        Self {
            built_at: n.built_at,
            max_displacement: n.max_displacement,
            surface_poses: n.surface_poses,
            rebuilds: n.rebuilds,
            pairs: n.pairs,
            pair_histories: n.pair_histories.into_iter().map(Into::into).collect(),
            surface_pairs: n.surface_pairs,
            surface_histories: n.surface_histories.into_iter().map(Into::into).collect(),
        }
    }
}

/// [`PairBooks`] without the adhesive work.
#[derive(Deserialize)]
struct Pair {
    key: u64,
    plastic: f64,
    max_overlap: f64,
    friction: f64,
    damping: f64,
    rolling: f64,
    tangential_stiffness: f64,
    rolling_stiffness: f64,
}

impl From<Pair> for PairBooks {
    fn from(p: Pair) -> Self {
        Self {
            key: p.key,
            plastic: p.plastic,
            max_overlap: p.max_overlap,
            friction: p.friction,
            damping: p.damping,
            rolling: p.rolling,
            tangential_stiffness: p.tangential_stiffness,
            rolling_stiffness: p.rolling_stiffness,
            adhesive: 0.0,
        }
    }
}

/// [`Books`] without the adhesive work.
#[derive(Deserialize)]
struct EnergyBooks {
    plastic: f64,
    friction: f64,
    damping: f64,
    rolling: f64,
    wall_work: f64,
    stiffness_tangential: f64,
    stiffness_rolling: f64,
    removed: f64,
    last: Vec<Pair>,
    particle_plastic: Vec<f64>,
}

impl From<EnergyBooks> for Books {
    fn from(b: EnergyBooks) -> Self {
        let mut books = Books::default();
        books.plastic = b.plastic;
        books.friction = b.friction;
        books.damping = b.damping;
        books.rolling = b.rolling;
        books.wall_work = b.wall_work;
        books.stiffness_tangential = b.stiffness_tangential;
        books.stiffness_rolling = b.stiffness_rolling;
        books.removed = b.removed;
        books.last = b.last.into_iter().map(Into::into).collect();
        books.particle_plastic = b.particle_plastic;
        books
    }
}

/// [`EnergyRow`] without the adhesive work.
#[derive(Deserialize)]
struct Row {
    time_s: f64,
    kinetic_translational_j: f64,
    kinetic_rotational_j: f64,
    gravitational_j: f64,
    elastic_normal_j: f64,
    elastic_tangential_j: f64,
    plastic_j: f64,
    friction_j: f64,
    damping_j: f64,
    wall_work_j: f64,
    balance_j: f64,
    contacts: u64,
    elastic_rolling_j: f64,
    rolling_j: f64,
    stiffness_tangential_j: f64,
    stiffness_rolling_j: f64,
    removed_j: f64,
}

impl From<Row> for EnergyRow {
    fn from(r: Row) -> Self {
        Self {
            time_s: r.time_s,
            kinetic_translational_j: r.kinetic_translational_j,
            kinetic_rotational_j: r.kinetic_rotational_j,
            gravitational_j: r.gravitational_j,
            elastic_normal_j: r.elastic_normal_j,
            elastic_tangential_j: r.elastic_tangential_j,
            plastic_j: r.plastic_j,
            friction_j: r.friction_j,
            damping_j: r.damping_j,
            wall_work_j: r.wall_work_j,
            balance_j: r.balance_j,
            contacts: r.contacts,
            elastic_rolling_j: r.elastic_rolling_j,
            rolling_j: r.rolling_j,
            stiffness_tangential_j: r.stiffness_tangential_j,
            stiffness_rolling_j: r.stiffness_rolling_j,
            removed_j: r.removed_j,
            adhesive_j: 0.0,
        }
    }
}

/// [`CheckpointData`] of this format.
#[derive(Deserialize)]
pub(super) struct Payload {
    scene_name: String,
    fingerprint: u32,
    dt_bits: u64,
    step: u64,
    bodies: Vec<BodyRecord>,
    contacts: Vec<Contact>,
    neighbour_list: Option<NeighbourList>,
    impacts: Vec<(u64, f64)>,
    world: Vec<u8>,
    books: EnergyBooks,
    rng: RngRecord,
    tracker: Tracker,
    collection: Vec<CollectionEntry>,
    energy: Vec<Row>,
    samples: Vec<HeadlineSample>,
    scene_keys: Vec<(String, String)>,
}

impl From<Payload> for CheckpointData {
    fn from(p: Payload) -> Self {
        Self {
            scene_name: p.scene_name,
            fingerprint: p.fingerprint,
            dt_bits: p.dt_bits,
            step: p.step,
            bodies: p.bodies,
            contacts: p.contacts.into_iter().map(Into::into).collect(),
            neighbour_list: p.neighbour_list.map(Into::into),
            impacts: p.impacts,
            world: p.world,
            books: p.books.into(),
            rng: p.rng,
            tracker: p.tracker,
            collection: p.collection,
            energy: p.energy.into_iter().map(Into::into).collect(),
            samples: p.samples,
            scene_keys: p.scene_keys,
        }
    }
}
