//! # mdr-impact
//!
//! The single-impact validator of the MDR elasto-plastic contact law (Lyashenko & Popov 2018):
//! it integrates the equation of motion of one impact (eq. 15) and reports the coefficient of
//! restitution (eq. 14), sweeps impact speeds in parallel, fits the law's parameters to measured
//! restitution data, and simulates oblique impacts with friction and rotation. The contact laws
//! themselves come from `mdr-contact`; nothing here re-implements them.
//!
//! - [`Impact`] → [`ImpactOutcome`]: one impact (time integration or the energy route); with
//!   [`Impact::work_of_adhesion`] an adhesive one that may stick ([`ImpactOutcome::stuck`]).
//! - [`Sweep`]: many speeds or angles in parallel, results in input order.
//! - [`fit`]: least-squares fit of `q_c`, `Θ/E*`, the scale factor and the work of adhesion.
//! - [`plot`]: SVG and PNG figures.
#![warn(missing_docs)]

mod declared;
mod energy;
pub mod error;
pub mod fit;
mod impact;
mod integrate;
pub mod law;
pub mod output;
pub mod plot;
mod sweep;

pub use declared::{DeclaredLaw, DeclaredNormal, MAX_DECLARED_PARAMS};
pub use error::{ImpactError, Result};
pub use impact::{Impact, ImpactOutcome, DEFAULT_STEPS_PER_CONTACT};
pub use integrate::TracePoint;
pub use law::{Method, NormalSpec, Route, TangentialSpec, DEFAULT_SPRINGS};
pub use sweep::{log_spaced, Progress, Sweep};

/// The scale factor the paper applies to the model curve (docs/theory.md §7): the best measured
/// elastic-range restitution of the experiment, 0.95.
pub const PAPER_SCALE: f64 = 0.95;
