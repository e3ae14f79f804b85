//! # mdr-dem
//!
//! Facade of the workspace: re-exports the contact law ([`contact`]), the single-impact validator
//! ([`impact`]), the rapier coupling ([`rapier`]), granular scenes ([`sim`]), planetary-ring runs
//! ([`ring`]) and the verification suite ([`verify`]).
#![warn(missing_docs)]

pub use mdr_contact as contact;
pub use mdr_impact as impact;
pub use mdr_rapier as rapier;
pub use mdr_ring as ring;
pub use mdr_sim as sim;
pub use mdr_verify as verify;
