//! `bench_bed`: throughput of the neighbour-list path of `mdr-rapier` on a settled bed. The run
//! is `mdr_rapier::neighbour_list::bed::bench_bed`, the loop `mdr-dem bench bed` runs; this module loads or
//! generates the bed, converts the arguments and errors, and returns the figures under the keys
//! of `mdr-dem bench bed --json`.

use crate::errors::{contact, invalid};
use mdr_rapier::neighbour_list::bed::reference_data;
use mdr_rapier::neighbour_list::bed::{
    bench_bed as run_bench, settled_bed, Bed, BedError, BedSpec, BenchLaw, BenchSettings,
    BenchValue,
};
use mdr_rapier::neighbour_list::rayon;
use mdr_rapier::CouplingError;
use pyo3::exceptions::{PyOSError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};

/// A bed-bench error as a Python exception: a rejected setting as `ValueError` naming the
/// keyword argument, an unreadable file as `OSError`, a failed run as `RuntimeError`.
fn bed_error(e: BedError) -> PyErr {
    match e {
        BedError::Coupling(CouplingError::Contact(c)) => contact(false)(c),
        BedError::Coupling(CouplingError::OutOfRange { name, .. })
        | BedError::TooManySpheres { name, .. } => invalid(name, &e),
        BedError::Io { .. } => PyOSError::new_err(e.to_string()),
        BedError::Format { .. } | BedError::NotReference { .. } => invalid("data", e),
        other => PyRuntimeError::new_err(other.to_string()),
    }
}

/// Throughput of the neighbour-list path on a settled bed, the run of `mdr-dem bench bed`: the
/// LAMMPS data file `data` (default: the repository's 10,000-sphere reference bed), or, with
/// `count`, a bed of `count` spheres poured and settled with `settle_steps` steps first
/// (untimed). `law`: "hertz", "mdr" (`q_c = qc` in reduced units, Θ = 0.37 E*), "thornton"
/// (limiting contact pressure `yield_stress`) or "adhesive-mdr" (the MDR law with work of
/// adhesion `work_of_adhesion`, reduced units); `rolling`: the rolling resistance coefficient
/// `μ_r` (elastic–plastic spring rolling resistance), or None; `steps` timed
/// steps after `warmup`; `threads` worker threads; `tile`: repeat the bed tile × tile times;
/// `skin`: neighbour skin (reduced length).
///
/// Returns a dict with the keys of `mdr-dem bench bed --json`: particle_steps_per_s and
/// particle_steps_per_cpu_s (particle-steps per wall / CPU second; CPU = all threads, NaN where
/// the process CPU clock is unavailable), ms_per_step (wall ms), wall_seconds and cpu_seconds (s,
/// timed steps), contacts_per_particle, floor_contacts, rebuilds (neighbour-list builds while
/// timed), plastic_contact_fraction, peak_rss_mb (peak resident memory of the whole Python
/// process so far, MB; 0 where unavailable), stepper_bytes_per_particle (bytes), state_checksum,
/// law, particles, steps, threads, orientation, work_books; and cpu_particle_steps_per_s, the
/// same number as particle_steps_per_cpu_s under the name `mdr-dem bench scene` uses. The GIL
/// is released during the run.
#[pyfunction]
#[pyo3(signature = (data = None, *, law = "hertz", steps = 10_000, warmup = 2_000, threads = 1,
    tile = 1, qc = 10.0, yield_stress = 1000.0, work_of_adhesion = 2.0, rolling = None,
    skin = 0.1, no_orientation = false, no_work_books = false, count = None,
    settle_steps = 40_000, seed = 1))]
#[allow(clippy::too_many_arguments)]
pub fn bench_bed<'py>(
    py: Python<'py>,
    data: Option<PathBuf>,
    law: &str,
    steps: usize,
    warmup: usize,
    threads: usize,
    tile: usize,
    qc: f64,
    yield_stress: f64,
    work_of_adhesion: f64,
    rolling: Option<f64>,
    skin: f64,
    no_orientation: bool,
    no_work_books: bool,
    count: Option<usize>,
    settle_steps: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    let law = match law {
        "hertz" => BenchLaw::Hertz,
        "mdr" => BenchLaw::Mdr { qc },
        "thornton" => BenchLaw::Thornton {
            yield_pressure: yield_stress,
        },
        "adhesive-mdr" => BenchLaw::AdhesiveMdr {
            qc,
            work_of_adhesion,
        },
        other => {
            return Err(invalid(
                "law",
                format!("`{other}` (allowed: \"hertz\", \"mdr\", \"thornton\", \"adhesive-mdr\")"),
            ))
        }
    };
    if let Some(mu) = rolling {
        BenchSettings {
            rolling,
            ..BenchSettings::default()
        }
        .validate()
        .map_err(|e| invalid("rolling", format!("{mu}: {e}")))?;
    }
    let settings = BenchSettings {
        law,
        rolling,
        steps,
        warmup,
        threads,
        tile,
        skin,
        orientation: !no_orientation,
        work_books: !no_work_books,
    };
    // Before settling a bed: a bad setting is reported at once.
    settings
        .validate()
        .map_err(|e| bed_error(BedError::Coupling(e)))?;
    let bed = match count {
        Some(count) => {
            let spec = BedSpec {
                count,
                settle_steps,
                seed,
                ..BedSpec::default()
            };
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
            py.detach(|| pool.install(|| settled_bed(&spec)))
                .map_err(bed_error)?
        }
        None => {
            let path = match data {
                Some(p) => p,
                None => reference_data(Path::new(env!("CARGO_MANIFEST_DIR")))
                    .map_err(|e| invalid("data", format!("{e}; pass data=PATH or count=N")))?,
            };
            Bed::read_lammps(&path).map_err(bed_error)?
        }
    };
    let figures = py
        .detach(|| run_bench(&bed, &settings))
        .map_err(bed_error)?;
    let dict = PyDict::new(py);
    for (key, value) in figures.fields() {
        match value {
            BenchValue::Real(x) => dict.set_item(key, x)?,
            BenchValue::Count(n) => dict.set_item(key, n)?,
            BenchValue::Flag(b) => dict.set_item(key, b)?,
            BenchValue::Text(t) => dict.set_item(key, t)?,
        }
    }
    dict.set_item("cpu_particle_steps_per_s", figures.particle_steps_per_cpu_s)?;
    Ok(dict)
}
