//! # mdr-sim
//!
//! Granular scenes described in TOML files, run on the MDR rapier coupling (`mdr-rapier`):
//!
//! - [`scene`]: the file format (every key carries its unit), validation before the run with the
//!   file, line and key of every problem;
//! - [`placement`], [`walls`]: particles (lattice, random fill, CSV, LAMMPS data) and walls
//!   (planes, boxes, cylinders, orifice plates, STL/OBJ meshes);
//! - [`output`]: VTK frames with a ParaView collection, the energy-book CSV, SVG plots, all written
//!   atomically;
//! - [`checkpoint`]: versioned, checksummed checkpoints for bit-identical restarts;
//! - [`run`]: the run loop, its energy books and the scenes' headline quantities.
#![warn(missing_docs)]

pub mod checkpoint;
pub mod error;
pub mod headline;
pub mod laws;
pub mod mesh;
pub mod output;
pub mod placement;
pub mod run;
pub mod scene;
pub mod walls;

pub use error::SimError;
pub use run::{run_scene, RunOptions, RunSummary};
pub use scene::{load_scene, Scene};
