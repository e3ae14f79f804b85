//! # mdr-lammps
//!
//! The contact model of `mdr-contact` (the MDR elasto-plastic normal law of Lyashenko & Popov
//! 2018, Mindlin tangential law, Hertzian viscous damping, EPSD rolling resistance) behind a C
//! ABI, for the LAMMPS pair style `mdrdem` and the wall fix `wall/mdrdem` (a plugin: `shim/`
//! holds the C++ `Pair`, the history `Fix` and the wall `Fix`, built against LAMMPS by
//! `build-plugin.sh`). The calls are batched: one
//! [`ffi::mdrdem_compute`] per neighbour list. No law is written here: every force comes from
//! [`mdr_contact::model::ContactLaw::update`] and the rolling law. See `docs/lammps.md`.
#![warn(missing_docs)]

pub mod coeffs;
pub mod compute;
mod contact;
pub mod error;
pub mod ffi;
pub mod history;
pub mod keywords;
pub mod wall;

pub use coeffs::{CoeffLine, CoeffTable, PairModel};
pub use error::PluginError;
pub use wall::WallTable;
