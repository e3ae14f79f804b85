//! Everything a run writes: VTK frames and their ParaView collection ([`vtk`]), the energy-book
//! CSV ([`energy`]), SVG plots ([`plot`]); every file through [`mdr_output::write_atomic`].

pub mod energy;
pub mod plot;
pub mod run_dir;
pub mod vtk;
