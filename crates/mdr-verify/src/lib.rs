//! # mdr-verify
//!
//! The verification suite of the contact laws of `mdr-contact`: the eight benchmark tests of
//! Chung & Ooi (2011, Granular Matter 13, 643–656) run on both implementations, the single-impact
//! validator (`mdr-impact`) and the rapier force mode (`mdr-rapier`), with the elastic MDR law
//! (Hertz normal; tangential: the MDR spring bed with partial slip, and Mindlin O(1)) and the
//! elasto-plastic MDR law where the test allows (test 3). References: Hertz (contact time, peak
//! force, overlap) and the impulse theory of oblique impacts in gross sliding. Parameters,
//! sources, tolerances and measured errors: `docs/verification.md`.
//!
//! - [`Collision`] → [`CollisionOutcome`]: one two-body collision on a [`Backend`].
//! - [`chung_ooi`]: the tests, each a [`TestReport`] of [`Check`]s and [`Figure`]s.
//! - [`plot`]: SVG figures.
//!
//! The contact laws are never re-implemented here.
#![warn(missing_docs)]

pub mod chung_ooi;
mod collision;
pub mod error;
pub mod kharaz;
pub mod materials;
pub mod plot;
pub mod reference;
pub mod report;

pub use chung_ooi::Resolution;
pub use collision::{Backend, Collision, CollisionOutcome, Target};
pub use error::{Result, VerifyError};
pub use report::{Check, Figure, Series, Style, TestReport, Tolerance};
