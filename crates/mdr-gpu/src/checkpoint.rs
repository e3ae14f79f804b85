//! Checkpoints of GPU runs in the CPU run's format ([`mdr_sim::run::CheckpointData`]), so that
//! either device resumes the other's: the device state read back between two steps
//! ([`GpuState`]: particles, positions at the last build, the half list of sphere pairs and the
//! wall slots with the touching contacts' histories) as the neighbour-list record
//! ([`NeighbourListRecord`]), and a record back as a device state.
//!
//! Each contact's history maps word for word: the normal law's state (Hertz's and MDR's largest
//! overlap; Thornton's largest overlap, unloading coefficient and residual overlap; the adhesive
//! MDR law's largest overlap and attached radius), Mindlin's displacement and contact radius,
//! the rolling spring's torque and stiffness. The device walls are the CPU path's surfaces in
//! its order (`crate::scene`), and a GPU checkpoint lists every (particle, surface) pair as a
//! candidate (the device tests every wall at every step). Orientations are kept as they are:
//! the scenes on the GPU integrate none (a sphere's forces do not depend on it).
//!
//! The energy books: the device books every work per particle as it happens ([`GpuBooks`]),
//! the CPU run per contact (each live history's own books) and in its totals (the contacts
//! that ended). A GPU checkpoint writes the device's totals as the CPU totals with live
//! histories that carry no books; a CPU checkpoint's totals and its live histories' books
//! become the device's totals. Either run then continues the other's books.

use crate::device::GpuError;
use crate::system::{GpuBooks, GpuPair, GpuState};
use mdr_contact::model::{Books as ContactBooks, ContactState};
use mdr_contact::normal::{
    AdhesiveMdr, AdhesiveMdrState, Hertz, MdrElastoPlastic, MdrState, Thornton, ThorntonState,
};
use mdr_contact::params::Declared;
use mdr_contact::rolling::EpsdRollingState;
use mdr_contact::tangential::MindlinState;
use mdr_sim::laws::AnyNormalState;
use mdr_sim::run::{BodyRecord, CheckpointData, ContactRecord, NeighbourListRecord};
use nalgebra::Vector3;

/// One contact's history as the device keeps it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct DeviceHistory {
    pub max_overlap: f64,
    pub normal_state: [f64; 2],
    pub displacement: Vector3<f64>,
    pub contact_radius: f64,
    pub rolling_torque: Vector3<f64>,
    pub rolling_stiffness: f64,
}

impl DeviceHistory {
    pub(crate) fn of_pair(p: &GpuPair) -> Self {
        Self {
            max_overlap: p.max_overlap,
            normal_state: p.normal_state,
            displacement: p.displacement,
            contact_radius: p.contact_radius,
            rolling_torque: p.rolling_torque,
            rolling_stiffness: p.rolling_stiffness,
        }
    }

    /// Wall slot `slot` of `state`, if touching.
    pub(crate) fn of_wall(state: &GpuState, slot: usize) -> Option<Self> {
        let (max_overlap, displacement, contact_radius) = state.floor[slot]?;
        Some(Self {
            max_overlap,
            normal_state: state.floor_normal_state[slot],
            displacement,
            contact_radius,
            rolling_torque: state.floor_rolling_torque[slot],
            rolling_stiffness: state.floor_rolling_stiffness[slot],
        })
    }

    /// The checkpoint's record of this history for normal law `law` (its scene name), under
    /// `key`. The work books are the GPU's: none (zero).
    pub(crate) fn record(&self, law: &str, key: u64) -> ContactRecord {
        let [a, b] = self.normal_state;
        let mut normal = AnyNormalState::default();
        if law == Hertz::DECLARATION.name {
            normal.hertz = self.max_overlap;
        } else if law == MdrElastoPlastic::DECLARATION.name {
            normal.mdr = MdrState {
                max_overlap: self.max_overlap,
            };
        } else if law == Thornton::DECLARATION.name {
            normal.thornton = ThorntonState::from_parts(self.max_overlap, a, b);
        } else if law == AdhesiveMdr::DECLARATION.name {
            normal.adhesive_mdr = AdhesiveMdrState {
                max_overlap: self.max_overlap,
                contact_radius: a,
                adhesive_work: 0.0,
            };
        }
        ContactRecord {
            key,
            contact: ContactState {
                normal,
                tangential: MindlinState {
                    displacement: self.displacement,
                    contact_radius: self.contact_radius,
                },
                books: ContactBooks::default(),
            },
            rolling: EpsdRollingState {
                torque: self.rolling_torque,
                stiffness: self.rolling_stiffness,
                dissipated_work: 0.0,
            },
        }
    }

    /// The device's history of a checkpoint's record for normal law `law`.
    fn of_record(law: &str, r: &ContactRecord) -> Self {
        let n = &r.contact.normal;
        let (max_overlap, normal_state) = if law == Hertz::DECLARATION.name {
            (n.hertz, [0.0; 2])
        } else if law == MdrElastoPlastic::DECLARATION.name {
            (n.mdr.max_overlap, [0.0; 2])
        } else if law == Thornton::DECLARATION.name {
            let [d, c, p] = n.thornton.parts();
            (d, [c, p])
        } else {
            (
                n.adhesive_mdr.max_overlap,
                [n.adhesive_mdr.contact_radius, 0.0],
            )
        };
        let t = &r.contact.tangential;
        Self {
            max_overlap,
            normal_state,
            displacement: t.displacement,
            contact_radius: t.contact_radius,
            rolling_torque: r.rolling.torque,
            rolling_stiffness: r.rolling.stiffness,
        }
    }
}

/// The largest distance of a particle from its position at the last build (m): the CPU
/// stepper's `max_displacement`, whose excess over half the skin makes the next step rebuild.
fn max_displacement(state: &GpuState) -> f64 {
    state
        .position
        .iter()
        .zip(&state.built)
        .map(|(x, b)| (x - b).norm_squared())
        .fold(0.0, f64::max)
        .sqrt()
}

/// The particles of `state` as the checkpoint's body records.
pub(crate) fn particle_records(state: &GpuState) -> Vec<BodyRecord> {
    (0..state.position.len())
        .map(|i| BodyRecord {
            translation: state.position[i].into(),
            rotation: state.rotation[i],
            linvel: state.linvel[i].into(),
            angvel: state.angvel[i].into(),
        })
        .collect()
}

/// The neighbour-list record of a device state read between two steps, for normal law `law`
/// (`surface_poses` left empty: the scene gives them). The displacement recorded is beyond
/// half the skin `skin` exactly when the device's next step rebuilds, so that a run resumed
/// from it (on either device) decides as the device would have.
pub(crate) fn lists_record(law: &str, state: &GpuState, skin: f64) -> NeighbourListRecord {
    let pairs: Vec<(u32, u32, u8)> = state.pairs.iter().map(|p| (p.i, p.j, p.image)).collect();
    let pair_histories = state
        .pairs
        .iter()
        .enumerate()
        .filter(|(_, p)| p.active)
        .map(|(k, p)| DeviceHistory::of_pair(p).record(law, k as u64))
        .collect();
    let n = state.position.len();
    let walls = state.walls;
    let surface_pairs: Vec<(u32, u32)> = (0..n)
        .flat_map(|i| (0..walls).map(move |s| (i as u32, s as u32)))
        .collect();
    let surface_histories = (0..n * walls)
        .filter_map(|slot| DeviceHistory::of_wall(state, slot).map(|h| h.record(law, slot as u64)))
        .collect();
    let displacement = max_displacement(state);
    NeighbourListRecord {
        built_at: state.built.iter().map(|&x| x.into()).collect(),
        max_displacement: if state.rebuild_due {
            displacement.max(skin)
        } else {
            displacement.min(0.5 * skin)
        },
        surface_poses: Vec::new(),
        rebuilds: state.rebuilds,
        pairs,
        pair_histories,
        surface_pairs,
        surface_histories,
    }
}

/// The device state a checkpoint holds for a system of `walls` device walls and normal law
/// `law`, with `skin`: its particles, lists and histories. What does not map is refused with
/// the reason: a checkpoint of another path (rapier's pipeline, restitution), or of surfaces
/// the device lacks.
pub(crate) fn state_of_checkpoint(
    law: &str,
    data: &CheckpointData,
    n: usize,
    walls: usize,
    skin: f64,
) -> Result<GpuState, GpuError> {
    let refuse = |what: String| Err(GpuError::Unsupported(format!("--resume: {what}")));
    let Some(lists) = &data.neighbour_list else {
        return refuse(
            "the checkpoint holds no neighbour-list state (it was written by rapier's \
             pipeline path or in restitution mode, which the GPU does not run)"
                .into(),
        );
    };
    if data.bodies.len() < n || lists.built_at.len() != n {
        return refuse(format!(
            "the checkpoint holds {} particles, the scene {n}",
            lists.built_at.len()
        ));
    }
    let mut pairs: Vec<GpuPair> = lists
        .pairs
        .iter()
        .map(|&(i, j, image)| GpuPair {
            i,
            j,
            image,
            active: false,
            max_overlap: 0.0,
            normal_state: [0.0; 2],
            displacement: Vector3::zeros(),
            contact_radius: 0.0,
            rolling_torque: Vector3::zeros(),
            rolling_stiffness: 0.0,
        })
        .collect();
    for r in &lists.pair_histories {
        let Some(pair) = usize::try_from(r.key).ok().and_then(|k| pairs.get_mut(k)) else {
            return refuse(format!("sphere-pair history {} is out of the list", r.key));
        };
        let h = DeviceHistory::of_record(law, r);
        pair.active = true;
        pair.max_overlap = h.max_overlap;
        pair.normal_state = h.normal_state;
        pair.displacement = h.displacement;
        pair.contact_radius = h.contact_radius;
        pair.rolling_torque = h.rolling_torque;
        pair.rolling_stiffness = h.rolling_stiffness;
    }
    let slots = n * walls;
    let mut floor = vec![None; slots];
    let mut floor_normal_state = vec![[0.0; 2]; slots];
    let mut floor_rolling_torque = vec![Vector3::zeros(); slots];
    let mut floor_rolling_stiffness = vec![0.0; slots];
    for r in &lists.surface_histories {
        let pair = usize::try_from(r.key)
            .ok()
            .and_then(|k| lists.surface_pairs.get(k));
        let Some(&(i, s)) = pair else {
            return refuse(format!("surface history {} is out of the list", r.key));
        };
        if s as usize >= walls || i as usize >= n {
            return refuse(format!(
                "particle {i} touches surface {s}; the device has {walls} walls"
            ));
        }
        let slot = i as usize * walls + s as usize;
        let h = DeviceHistory::of_record(law, r);
        floor[slot] = Some((h.max_overlap, h.displacement, h.contact_radius));
        floor_normal_state[slot] = h.normal_state;
        floor_rolling_torque[slot] = h.rolling_torque;
        floor_rolling_stiffness[slot] = h.rolling_stiffness;
    }
    let books = device_books(law, data, lists, n);
    let body = |i: usize| &data.bodies[i];
    Ok(GpuState {
        position: (0..n).map(|i| Vector3::from(body(i).translation)).collect(),
        linvel: (0..n).map(|i| Vector3::from(body(i).linvel)).collect(),
        angvel: (0..n).map(|i| Vector3::from(body(i).angvel)).collect(),
        rotation: (0..n).map(|i| body(i).rotation).collect(),
        pairs,
        asymmetric_pairs: 0,
        floor,
        floor_rolling_torque,
        floor_normal_state,
        floor_rolling_stiffness,
        built: lists.built_at.iter().map(|&x| Vector3::from(x)).collect(),
        rebuild_due: lists.max_displacement > 0.5 * skin,
        walls,
        rebuilds: lists.rebuilds,
        books,
    })
}

/// The device's books of a checkpoint: its totals (`CheckpointData::books`: the contacts that
/// ended) and its live histories' own books, as the CPU run's energy row adds them; per
/// particle, the checkpoint's plastic work per particle with the live contacts' adhesive work
/// added back, and what the totals hold beyond it (round-off) in the first particle's words.
/// The device keeps the adhesive work apart from the plastic work, and the live histories it
/// loads carry none: their adhesive work so far joins the totals.
fn device_books(
    law: &str,
    data: &CheckpointData,
    lists: &NeighbourListRecord,
    n: usize,
) -> Vec<GpuBooks> {
    let b = &data.books;
    let mut total = GpuBooks {
        plastic: b.plastic - b.adhesive,
        friction: b.friction,
        damping: b.damping,
        rolling: b.rolling,
        tangential_stiffness: -b.stiffness_tangential,
        rolling_stiffness: -b.stiffness_rolling,
        adhesive: b.adhesive,
        wall_work: b.wall_work,
        removed: b.removed,
    };
    for r in lists.pair_histories.iter().chain(&lists.surface_histories) {
        let books = &r.contact.books;
        if law == AdhesiveMdr::DECLARATION.name {
            total.plastic += r.contact.normal.adhesive_mdr.adhesive_work;
        }
        total.friction += books.friction_work;
        total.damping += books.damping_work;
        total.rolling += r.rolling.dissipated_work;
        total.tangential_stiffness += books.tangential_stiffness_energy;
        total.rolling_stiffness += books.rolling_stiffness_energy;
    }
    let mut books = vec![GpuBooks::default(); n];
    if n == 0 {
        return books;
    }
    for (book, &plastic) in books.iter_mut().zip(&b.particle_plastic) {
        book.plastic = plastic;
    }
    if law == AdhesiveMdr::DECLARATION.name {
        // The checkpoint's plastic work per particle has every contact's adhesive work so far
        // taken out, the live contacts' included; the histories loaded carry none, so it goes
        // back to their spheres (half of a pair's to each), where the CPU run's frame adds it.
        let mut add = |i: u32, work: f64| {
            if let Some(book) = books.get_mut(i as usize) {
                book.plastic += work;
            }
        };
        let adhesive_work = |r: &ContactRecord| r.contact.normal.adhesive_mdr.adhesive_work;
        let at = |key: u64| usize::try_from(key).unwrap_or(usize::MAX);
        for r in &lists.pair_histories {
            if let Some(&(i, j, _)) = lists.pairs.get(at(r.key)) {
                add(i, 0.5 * adhesive_work(r));
                add(j, 0.5 * adhesive_work(r));
            }
        }
        for r in &lists.surface_histories {
            if let Some(&(i, _)) = lists.surface_pairs.get(at(r.key)) {
                add(i, adhesive_work(r));
            }
        }
    }
    let per_particle: f64 = books.iter().map(|book| book.plastic).sum();
    books[0] = GpuBooks {
        plastic: books[0].plastic + (total.plastic - per_particle),
        ..total
    };
    books
}
