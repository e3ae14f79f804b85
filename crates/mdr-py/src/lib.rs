//! # mdr-py
//!
//! The Python module `mdr_dem`: a thin binding of the mdr-dem crates. Nothing here computes
//! physics: the law is `mdr-contact`'s, impacts, sweeps and fits are `mdr-impact`'s, rings are
//! `mdr-ring`'s and scenes are `mdr-sim`'s. This crate converts arguments and results between
//! Python/numpy and Rust, names the keyword argument of every rejected value in a `ValueError`,
//! and releases the GIL during long computations.
//!
//! Built by maturin (`python3 -m pip install ./crates/mdr-py`); see `docs/python.md`.
#![warn(missing_docs)]

mod arrays;
mod bench;
mod errors;
mod law;
mod ring;
mod scene;
mod validator;

use pyo3::prelude::*;

/// Python module `mdr_dem._native`; `mdr_dem/__init__.py` re-exports it.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<law::MdrLaw>()?;
    m.add_class::<law::MdrState>()?;
    m.add_class::<law::ImpactTrace>()?;
    m.add_class::<validator::FitResult>()?;
    m.add_class::<ring::Ring>()?;
    m.add_function(wrap_pyfunction!(validator::curve, m)?)?;
    m.add_function(wrap_pyfunction!(validator::fit, m)?)?;
    m.add_function(wrap_pyfunction!(validator::oblique, m)?)?;
    m.add_function(wrap_pyfunction!(scene::run_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::scene_laws, m)?)?;
    m.add_function(wrap_pyfunction!(bench::bench_bed, m)?)?;
    m.add("PAPER_SCALE", mdr_impact::PAPER_SCALE)?;
    Ok(())
}
