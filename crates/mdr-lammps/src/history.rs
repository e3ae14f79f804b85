//! Layout of one contact's history in the flat `double` arrays LAMMPS carries per contact (the
//! plugin's history fix stores, migrates and restarts them without knowing what they mean).
//!
//! | slot | value | seen from the partner |
//! |------|-------|-----------------------|
//! | 0 | MDR `d_max` (largest overlap, length) | same |
//! | 1–3 | Mindlin tangential displacement `ξ` (length) | negated |
//! | 4 | Mindlin contact radius of the last step (length) | same |
//! | 5–7 | rolling spring torque (force·length), with `rolling` only | negated |
//! | 8 | rolling stiffness, with `rolling` only | same |
//! | 9 | rolling work dissipated, with `rolling` only | same |
//! | last (5 or 10) | attached radius `a` of Heß's rule (length), with `adhesion` only | same |
//!
//! The layouts without adhesion are those of runs without it, so their restart files stay
//! readable. The adhesive law's booked adhesive work is not kept (LAMMPS keeps no work books).

use crate::coeffs::CoeffTable;
use crate::error::PluginError;
use crate::PairModel;
use mdr_contact::damping::HertzianViscousLaw;
use mdr_contact::material::ContactPair;
use mdr_contact::model::{ContactInput, ContactLaw, ContactState, NoBooks};
use mdr_contact::normal::{AdhesiveMdrLaw, AdhesiveMdrState, MdrLaw, MdrState, NormalLaw};
use mdr_contact::rolling::{EpsdRollingLaw, EpsdRollingState, RollingInput, RollingLaw};
use mdr_contact::tangential::{MindlinLaw, MindlinState};
use nalgebra::Vector3;

/// The history state of one contact as the law sees it (LAMMPS keeps no work books).
pub type PluginState<S = MdrState> = ContactState<S, MindlinState, NoBooks>;

/// Values per contact without rolling resistance or adhesion.
pub const BASE_SIZE: usize = 5;
/// Values per contact with rolling resistance.
pub const ROLLING_SIZE: usize = 10;
/// The most values per contact (rolling resistance and adhesion).
pub const MAX_SIZE: usize = ROLLING_SIZE + 1;

/// Sign of each slot when a contact's history passes from atom `i`'s view to atom `j`'s, for
/// the layout with rolling resistance (the attached radius, slot 10 there and slot 5 without
/// rolling, keeps its sign: [`HistoryLayout::partner_signs`]).
pub const PARTNER_SIGNS: [f64; MAX_SIZE] =
    [1.0, -1.0, -1.0, -1.0, 1.0, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0];

/// Which slots a run uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HistoryLayout {
    /// Whether the rolling slots are present.
    pub rolling: bool,
    /// Whether the attached-radius slot of the adhesive law is present.
    pub adhesion: bool,
}

impl HistoryLayout {
    /// The layout of a table: rolling slots when any pair has rolling resistance, the adhesive
    /// slot when any pair is adhesive.
    pub fn for_table(table: &CoeffTable) -> Self {
        Self {
            rolling: table.has_rolling(),
            adhesion: table.has_adhesion(),
        }
    }

    /// The layout of `size` values per contact (each layout has its own size).
    pub fn of_size(size: usize) -> Result<Self, PluginError> {
        match size {
            5 => Ok(Self {
                rolling: false,
                adhesion: false,
            }),
            6 => Ok(Self {
                rolling: false,
                adhesion: true,
            }),
            10 => Ok(Self {
                rolling: true,
                adhesion: false,
            }),
            11 => Ok(Self {
                rolling: true,
                adhesion: true,
            }),
            _ => Err(PluginError::Abi("history size is not 5, 6, 10 or 11")),
        }
    }

    /// Values per contact.
    pub const fn size(&self) -> usize {
        let base = if self.rolling {
            ROLLING_SIZE
        } else {
            BASE_SIZE
        };
        base + self.adhesion as usize
    }

    /// The sign of each slot seen from the partner atom (`size()` values).
    pub fn partner_signs(&self) -> Vec<f64> {
        let base = if self.rolling {
            ROLLING_SIZE
        } else {
            BASE_SIZE
        };
        let mut signs = PARTNER_SIGNS[..base].to_vec();
        if self.adhesion {
            signs.push(1.0);
        }
        signs
    }
}

/// The composed law of a pair, as the plugin binds it.
pub type PairLaw<N> = ContactLaw<N, MindlinLaw, HertzianViscousLaw>;

/// A normal law the plugin runs: how it is bound from a pair's model and where its state sits in
/// a contact's history values. The loops are monomorphised per law (no call through a pointer
/// per contact).
pub trait PluginNormalLaw: NormalLaw + Copy {
    /// Whether the law keeps the attached-radius slot ([`HistoryLayout::adhesion`]).
    const ADHESIVE: bool;
    /// Bind the pair's model (with its work of adhesion) to one pair of bodies.
    fn bind(
        model: &PairModel,
        pair: &ContactPair,
    ) -> Result<PairLaw<Self>, mdr_contact::ContactError>;
    /// Read the normal state (`ROLLING` selects the layout).
    fn load<const ROLLING: bool>(values: &[f64]) -> Self::State;
    /// Write the normal state back.
    fn store<const ROLLING: bool>(values: &mut [f64], state: &Self::State);
}

impl PluginNormalLaw for MdrLaw {
    const ADHESIVE: bool = false;
    #[inline(always)]
    fn bind(
        model: &PairModel,
        pair: &ContactPair,
    ) -> Result<PairLaw<Self>, mdr_contact::ContactError> {
        model.model.bind(pair)
    }
    #[inline(always)]
    fn load<const ROLLING: bool>(values: &[f64]) -> MdrState {
        MdrState {
            max_overlap: values[0],
        }
    }
    #[inline(always)]
    fn store<const ROLLING: bool>(values: &mut [f64], state: &MdrState) {
        values[0] = state.max_overlap;
    }
}

impl PluginNormalLaw for AdhesiveMdrLaw {
    const ADHESIVE: bool = true;
    #[inline(always)]
    fn bind(
        model: &PairModel,
        pair: &ContactPair,
    ) -> Result<PairLaw<Self>, mdr_contact::ContactError> {
        let law = model.model.bind(pair)?;
        Ok(ContactLaw {
            normal: AdhesiveMdrLaw::new(law.normal, model.adhesion),
            tangential: law.tangential,
            damping: law.damping,
        })
    }
    #[inline(always)]
    fn load<const ROLLING: bool>(values: &[f64]) -> AdhesiveMdrState {
        let slot = if ROLLING { ROLLING_SIZE } else { BASE_SIZE };
        AdhesiveMdrState {
            max_overlap: values[0],
            contact_radius: values[slot],
            adhesive_work: 0.0,
        }
    }
    #[inline(always)]
    fn store<const ROLLING: bool>(values: &mut [f64], state: &AdhesiveMdrState) {
        let slot = if ROLLING { ROLLING_SIZE } else { BASE_SIZE };
        values[0] = state.max_overlap;
        values[slot] = state.contact_radius;
    }
}

/// Read a contact's state from its values (`ROLLING` selects the layout with rolling slots).
#[inline(always)]
pub fn load<N: PluginNormalLaw, const ROLLING: bool>(
    values: &[f64],
) -> (PluginState<N::State>, EpsdRollingState) {
    let state = ContactState {
        normal: N::load::<ROLLING>(values),
        tangential: MindlinState {
            displacement: Vector3::new(values[1], values[2], values[3]),
            contact_radius: values[4],
        },
        books: NoBooks,
    };
    let rolling = if ROLLING {
        EpsdRollingState {
            torque: Vector3::new(values[5], values[6], values[7]),
            stiffness: values[8],
            dissipated_work: values[9],
        }
    } else {
        EpsdRollingState::default()
    };
    (state, rolling)
}

/// Write a contact's state back.
#[inline(always)]
pub fn store<N: PluginNormalLaw, const ROLLING: bool>(
    values: &mut [f64],
    state: &PluginState<N::State>,
    rolling: &EpsdRollingState,
) {
    N::store::<ROLLING>(values, &state.normal);
    values[1] = state.tangential.displacement.x;
    values[2] = state.tangential.displacement.y;
    values[3] = state.tangential.displacement.z;
    values[4] = state.tangential.contact_radius;
    if ROLLING {
        values[5] = rolling.torque.x;
        values[6] = rolling.torque.y;
        values[7] = rolling.torque.z;
        values[8] = rolling.stiffness;
        values[9] = rolling.dissipated_work;
    }
}

/// A contact whose spheres (or sphere and wall) separated, and whose neck, for an adhesive law,
/// let go: the law sees the separation (MDR keeps `d_max` for a re-touch, the Mindlin and
/// rolling springs are released) and the state is written to `values`; no force.
#[inline(always)]
pub fn release<N: PluginNormalLaw, const ROLLING: bool>(
    law: &PairLaw<N>,
    rolling: &EpsdRollingLaw,
    (mut state, mut roll_state): (PluginState<N::State>, EpsdRollingState),
    values: &mut [f64],
    overlap: f64,
    dt: f64,
) {
    law.update(
        &mut state,
        &ContactInput {
            overlap,
            normal: Vector3::z(),
            relative_velocity: Vector3::zeros(),
            dt,
        },
    );
    if ROLLING {
        rolling.update(
            &mut roll_state,
            &RollingInput {
                normal: Vector3::z(),
                rotation_increment: Vector3::zeros(),
                normal_force: 0.0,
                normal_stiffness: 0.0,
            },
        );
    }
    store::<N, ROLLING>(values, &state, &roll_state);
}
