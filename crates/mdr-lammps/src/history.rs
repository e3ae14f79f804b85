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

use crate::coeffs::CoeffTable;
use mdr_contact::model::{ContactState, NoBooks};
use mdr_contact::normal::MdrState;
use mdr_contact::rolling::EpsdRollingState;
use mdr_contact::tangential::MindlinState;
use nalgebra::Vector3;

/// The history state of one contact as the law sees it (LAMMPS keeps no work books).
pub type PluginState = ContactState<MdrState, MindlinState, NoBooks>;

/// Values per contact without rolling resistance.
pub const BASE_SIZE: usize = 5;
/// Values per contact with rolling resistance.
pub const ROLLING_SIZE: usize = 10;

/// Sign of each slot when a contact's history passes from atom `i`'s view to atom `j`'s.
pub const PARTNER_SIGNS: [f64; ROLLING_SIZE] =
    [1.0, -1.0, -1.0, -1.0, 1.0, -1.0, -1.0, -1.0, 1.0, 1.0];

/// Which slots a run uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HistoryLayout {
    /// Whether the rolling slots are present.
    pub rolling: bool,
}

impl HistoryLayout {
    /// The layout of a table: rolling slots when any pair has rolling resistance.
    pub fn for_table(table: &CoeffTable) -> Self {
        Self {
            rolling: table.has_rolling(),
        }
    }

    /// Values per contact.
    pub fn size(&self) -> usize {
        if self.rolling {
            ROLLING_SIZE
        } else {
            BASE_SIZE
        }
    }
}

/// Read a contact's state from its values (`ROLLING` selects the 10-value layout).
#[inline(always)]
pub fn load<const ROLLING: bool>(values: &[f64]) -> (PluginState, EpsdRollingState) {
    let state = ContactState {
        normal: MdrState {
            max_overlap: values[0],
        },
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
pub fn store<const ROLLING: bool>(
    values: &mut [f64],
    state: &PluginState,
    rolling: &EpsdRollingState,
) {
    values[0] = state.normal.max_overlap;
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
