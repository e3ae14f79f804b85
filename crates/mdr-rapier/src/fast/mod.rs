//! The fast force-mode path: the same physics as [`crate::force_mode`] (the per-pair kernel
//! [`crate::kernel::evaluate_pair`], symplectic Euler as rapier integrates with one solver
//! iteration), with the particles in the plugin's own structure-of-arrays storage and contacts
//! found by binned neighbour lists with a skin, as LAMMPS does, instead of rapier's broad and
//! narrow phases. rapier remains the geometry and rigid-body backend: any collider registered
//! as a surface (walls, meshes, kinematic containers, user bodies) touches the particles through
//! parry queries and receives the reaction forces. See `docs/coupling.md` and
//! `docs/performance.md`.
//!
//! - [`boundary`]: open space or an x/y-periodic box, through an image-offset abstraction that
//!   a Lees–Edwards box can implement;
//! - [`particles`]: structure-of-arrays particles and species;
//! - [`neighbours`]: binned half neighbour lists with histories carried across rebuilds;
//! - [`surfaces`]: particles against rapier colliders;
//! - [`stepper`]: the step;
//! - [`bed`]: LAMMPS data files, a settled-bed generator and the settled-bed benchmark's timing
//!   loop ([`bed::bench_bed`], shared by `mdr-dem bench bed` and the Python package);
//! - [`workers`]: the pool's other threads kept awake through a run of steps
//!   ([`workers::with_workers_awake`]), and the parallel passes' blocks handed to the same
//!   thread in every pass ([`workers::map_tasks`]).

pub mod bed;
pub mod boundary;
pub mod neighbours;
pub mod particles;
pub mod stepper;
pub mod surfaces;
pub mod workers;

pub use boundary::{Boundary, Image, ImageOffset};
pub use stepper::{
    ContactPartner, EndedContact, FastForceStepper, FastHistory, FastListState, FastStepReport,
    StepTimings,
};
pub use workers::with_workers_awake;

/// The thread-pool crate of the parallel loops, re-exported so that programs size the pool with
/// the same version (`rayon::ThreadPoolBuilder::new().num_threads(t).build()?.install(…)`).
pub use rayon;
