//! The neighbour-list path: the same physics as [`crate::force_mode`] (the per-pair kernel
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
    ContactPartner, EndedContact, NeighbourListHistory, NeighbourListState,
    NeighbourListStepReport, NeighbourListStepper, StepTimings,
};
pub use workers::{run_awake, with_workers_awake};

/// Former names of the neighbour-list path's types, which named a speed rather than the method.
#[allow(deprecated)]
pub use deprecated_names::*;

mod deprecated_names {
    use mdr_contact::damping::NoDamping;
    use mdr_contact::model::Books;
    use mdr_contact::rolling::NoRolling;
    use mdr_contact::tangential::Frictionless;

    /// Former name of [`super::NeighbourListStepper`].
    #[deprecated(note = "renamed `NeighbourListStepper`")]
    pub type FastForceStepper<N, T = Frictionless, D = NoDamping, R = NoRolling, B = Books> =
        super::NeighbourListStepper<N, T, D, R, B>;

    /// Former name of [`super::NeighbourListHistory`].
    #[deprecated(note = "renamed `NeighbourListHistory`")]
    pub type FastHistory<N, T, R, B = Books> = super::NeighbourListHistory<N, T, R, B>;

    /// Former name of [`super::NeighbourListStepReport`].
    #[deprecated(note = "renamed `NeighbourListStepReport`")]
    pub type FastStepReport = super::NeighbourListStepReport;

    /// Former name of [`super::NeighbourListState`].
    #[deprecated(note = "renamed `NeighbourListState`")]
    pub type FastListState<H> = super::NeighbourListState<H>;

    /// Former name of [`super::surfaces::NeighbourListSurface`].
    #[deprecated(note = "renamed `surfaces::NeighbourListSurface`")]
    pub type FastSurface = super::surfaces::NeighbourListSurface;

    /// Former name of [`super::particles::NeighbourListParticles`].
    #[deprecated(note = "renamed `particles::NeighbourListParticles`")]
    pub type FastParticles = super::particles::NeighbourListParticles;
}

/// The thread-pool crate of the parallel loops, re-exported so that programs size the pool with
/// the same version (`rayon::ThreadPoolBuilder::new().num_threads(t).build()?.install(…)`).
pub use rayon;
