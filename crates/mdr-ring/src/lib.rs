//! # mdr-ring
//!
//! A planetary-ring shearing box — the local co-rotating patch of a ring of ice particles used by
//! ring dynamicists — with hard-sphere collisions resolved by rapier through a restitution hook,
//! so that the MDR law's `e(v)` can be compared with the Bridges et al. law and a constant on the
//! same ring, and with REBOUND's shearing sheet (`docs/rings.md`).
//!
//! - [`hill`]: Hill's equations and the symplectic epicycle integrator (SEI) for free motion;
//! - [`boundary`]: shear-periodic (Lees–Edwards) boundaries and periodic images;
//! - [`particles`]: state, size distribution, REBOUND's initial conditions;
//! - [`law`]: restitution laws behind one trait: the MDR energy route and a constant from the
//!   plugin ([`mdr_rapier::restitution_law`], re-exported), and the Bridges et al. law of ring
//!   particles;
//! - [`hooks`], [`world`]: rapier collision step with ghost images and the restitution hook;
//! - [`gravity`]: optional self-gravity, Barnes–Hut tree or direct sum over shear-periodic ghost
//!   boxes;
//! - [`wakes`]: surface-density grid, its autocorrelation, wake pitch angle and wavelength, Toomre Q;
//! - [`diagnostics`], [`run`], [`output`]: measurements, the time loop, CSV/JSON/VTK/SVG;
//! - [`app`]: one run from options to files (used by `mdr-dem sim ring`).
//!
//! ```no_run
//! use mdr_ring::prelude::*;
//! let config = RingConfig::default().particles(300).box_size(80.0);
//! let mut ring = RingSimulation::new(config, BridgesLaw::default()).unwrap();
//! let result = ring.run(2.0, |_, _| {}).unwrap();
//! println!("c = {} m/s", result.summary.c_m_per_s);
//! ```
#![warn(missing_docs)]

pub mod app;
pub mod boundary;
pub mod clusters;
pub mod diagnostics;
pub mod error;
pub mod gravity;
pub mod hill;
pub mod hooks;
pub mod law;
pub mod output;
pub mod particles;
pub mod run;
pub mod wakes;
pub mod world;

pub use error::{Result, RingError};

/// The names most programs need.
pub mod prelude {
    pub use crate::boundary::ShearingBox;
    pub use crate::diagnostics::{Sample, Summary};
    pub use crate::error::{Result, RingError};
    pub use crate::gravity::{GravitySolver, SelfGravity};
    pub use crate::hill::{HillFrame, Sei};
    pub use crate::law::{
        BridgesLaw, ConstantRestitution, ImpactPair, MdrRestitution, RestitutionLaw,
    };
    pub use crate::particles::{Particles, Population, SizeDistribution};
    pub use crate::run::{RingConfig, RingSimulation, RunResult, REBOUND_OMEGA};
    pub use crate::world::CollisionSettings;
}
