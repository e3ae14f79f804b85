//! # mdr-dem
//!
//! Facade of the workspace: re-exports the contact law ([`contact`]), the single-impact validator
//! ([`impact`]) and the rapier coupling ([`rapier`]).
#![warn(missing_docs)]

pub use mdr_contact as contact;
pub use mdr_impact as impact;
pub use mdr_rapier as rapier;
