//! The sub-models of a scene, each picked by name from the registry ([`registry`]): the normal
//! law, compiled into the steppers ([`SceneNormal`]); the tangential, damping and rolling laws,
//! each kind an enum generated from its registry list ([`AnyTangential`], [`AnyDamping`],
//! [`AnyRolling`]) and dispatched per contact by a `match`; rolling resistance that cannot act
//! compiled out ([`SceneRolling`]). No physics here: each calls the law crate's own
//! implementation.

pub mod registry;
mod sub_models;

pub use registry::{
    AnyDamping, AnyDampingLaw, AnyRolling, AnyRollingLaw, AnyTangential, AnyTangentialLaw,
};
pub use sub_models::HistoryIn;

use mdr_contact::normal::{AdhesiveMdrState, MdrState, NormalLaw, NormalModel, ThorntonState};
use mdr_contact::params::Declared;
use mdr_contact::rolling::{EpsdRollingState, NoRolling, RollingLaw, RollingModel};
use serde::{Deserialize, Serialize};

/// The per-contact normal history of a checkpoint: one field per kind of history a registered
/// normal law keeps (the others stay default).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct AnyNormalState {
    /// The MDR history.
    pub mdr: MdrState,
    /// The history of a law that keeps its largest overlap alone (m): Hertz's.
    pub hertz: f64,
    /// Thornton's history.
    pub thornton: ThorntonState,
    /// The adhesive MDR history.
    pub adhesive_mdr: AdhesiveMdrState,
}

/// A normal law's per-contact history as a checkpoint writes it: its field of
/// [`AnyNormalState`]. A registered law whose history is one of these types needs nothing
/// more; a new kind of history adds a field (and a checkpoint format version).
pub trait NormalHistoryRecord: Sized {
    /// Whether the history books adhesive work ([`NormalHistoryRecord::adhesive_work`]): the
    /// energy books then take it apart from the plastic work.
    const ADHESIVE: bool = false;
    /// The record of this history.
    fn record(&self) -> AnyNormalState;
    /// The history a record restores.
    fn restore(record: &AnyNormalState) -> Self;
    /// The adhesive work of the history so far (J): the part of
    /// [`NormalLaw::dissipated_work`] that the springs held when they let go; zero for a
    /// non-adhesive law.
    fn adhesive_work(&self) -> f64 {
        0.0
    }
}

impl NormalHistoryRecord for MdrState {
    fn record(&self) -> AnyNormalState {
        AnyNormalState {
            mdr: *self,
            ..AnyNormalState::default()
        }
    }
    fn restore(record: &AnyNormalState) -> Self {
        record.mdr
    }
}

/// The largest overlap alone (Hertz's history).
impl NormalHistoryRecord for f64 {
    fn record(&self) -> AnyNormalState {
        AnyNormalState {
            hertz: *self,
            ..AnyNormalState::default()
        }
    }
    fn restore(record: &AnyNormalState) -> Self {
        record.hertz
    }
}

impl NormalHistoryRecord for AdhesiveMdrState {
    const ADHESIVE: bool = true;
    fn record(&self) -> AnyNormalState {
        AnyNormalState {
            adhesive_mdr: *self,
            ..AnyNormalState::default()
        }
    }
    fn restore(record: &AnyNormalState) -> Self {
        record.adhesive_mdr
    }
    fn adhesive_work(&self) -> f64 {
        self.adhesive_work
    }
}

impl NormalHistoryRecord for ThorntonState {
    fn record(&self) -> AnyNormalState {
        AnyNormalState {
            thornton: *self,
            ..AnyNormalState::default()
        }
    }
    fn restore(record: &AnyNormalState) -> Self {
        record.thornton
    }
}

/// A normal model a scene's steppers can run with: both force paths are compiled for each
/// normal law, so that a contact carries only its own law's history (8 bytes for MDR and Hertz)
/// and the pair loop takes no branch on the law (docs/performance.md). Every normal model whose
/// history has a checkpoint record ([`NormalHistoryRecord`]) is one.
pub trait SceneNormal: NormalModel<Law: Clone> + Declared + 'static {
    /// Whether a contact's history books adhesive work.
    const ADHESIVE: bool;
    /// The history to write for a contact.
    fn record(state: &<Self::Law as NormalLaw>::State) -> AnyNormalState;
    /// The history a written one restores.
    fn restore(record: &AnyNormalState) -> <Self::Law as NormalLaw>::State;
    /// The adhesive work a contact's history booked so far (J; part of its dissipated work).
    fn adhesive_work(state: &<Self::Law as NormalLaw>::State) -> f64;
}

impl<N> SceneNormal for N
where
    N: NormalModel<Law: Clone> + Declared + 'static,
    <N::Law as NormalLaw>::State: NormalHistoryRecord,
{
    const ADHESIVE: bool = <<N::Law as NormalLaw>::State as NormalHistoryRecord>::ADHESIVE;
    fn record(state: &<N::Law as NormalLaw>::State) -> AnyNormalState {
        state.record()
    }
    fn restore(record: &AnyNormalState) -> <N::Law as NormalLaw>::State {
        NormalHistoryRecord::restore(record)
    }
    fn adhesive_work(state: &<N::Law as NormalLaw>::State) -> f64 {
        state.adhesive_work()
    }
}

/// A rolling model a scene's neighbour-list stepper can run with, and how its per-contact
/// history is written to and read from a checkpoint (as the elastic–plastic spring's state, the
/// default one when the scene has no rolling resistance). A scene whose rolling law cannot give
/// a torque ([`AnyRolling::resists`]) runs with [`NoRolling`], whose history is empty and whose
/// update is nothing, rather than with [`AnyRolling`]: every contact then carries no rolling
/// state and takes no rolling branch (docs/performance.md).
pub trait SceneRolling: RollingModel<Law: Clone> + 'static {
    /// The history to write for a contact.
    fn record(state: &<Self::Law as RollingLaw>::State) -> EpsdRollingState;
    /// The history a written one restores.
    fn restore(record: &EpsdRollingState) -> <Self::Law as RollingLaw>::State;
}

impl SceneRolling for NoRolling {
    fn record(_: &()) -> EpsdRollingState {
        EpsdRollingState::default()
    }
    fn restore(_: &EpsdRollingState) {}
}

impl SceneRolling for AnyRolling {
    fn record(state: &EpsdRollingState) -> EpsdRollingState {
        *state
    }
    fn restore(record: &EpsdRollingState) -> EpsdRollingState {
        *record
    }
}
