//! `run_scene`: a granular scene from a TOML file, run by `mdr-sim` (as `mdr-dem sim run`).

use mdr_sim::scene::Problems;
use mdr_sim::{load_scene, run_scene as run, RunOptions, SimError};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// The laws a scene can name, as the registry declares them: the normal laws (`[contact]
/// normal = "…"`), then the tangential, damping and rolling laws (`tangential = "…"`,
/// `damping = "…"`, `rolling = "…"`); `kind` ("normal", "tangential", "damping", "rolling")
/// keeps one kind. A list of dicts with `name`, `kind`, `summary` and `parameters` (each with
/// its scene `key`, `symbol`, `unit`, `range`, `default`, `doc`, command-line `flag`, `python`
/// keyword and `lammps` keyword).
#[pyfunction]
#[pyo3(signature = (kind = None))]
pub fn scene_laws<'py>(py: Python<'py>, kind: Option<&str>) -> PyResult<Bound<'py, PyAny>> {
    use mdr_sim::laws::registry::{NORMAL_LAWS, SUB_MODEL_KINDS};
    const KINDS: [&str; 4] = ["normal", "tangential", "damping", "rolling"];
    if let Some(k) = kind.filter(|k| !KINDS.contains(k)) {
        return Err(PyValueError::new_err(format!(
            "invalid value for `kind`: `{k}` (allowed: {})",
            KINDS.map(|k| format!("\"{k}\"")).join(", ")
        )));
    }
    let laws: Vec<_> = NORMAL_LAWS
        .iter()
        .map(|e| e.declaration)
        .chain(
            SUB_MODEL_KINDS
                .iter()
                .flat_map(|k| k.laws)
                .map(|e| e.declaration),
        )
        .collect();
    let value = serde_json::to_value(laws).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let value = match (kind, value) {
        (Some(k), serde_json::Value::Array(items)) => {
            serde_json::Value::Array(items.into_iter().filter(|l| l["kind"] == k).collect())
        }
        (_, value) => value,
    };
    json_to_py(py, &value)
}

/// A JSON value as the Python object `json.loads` would give.
pub fn json_to_py<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value;
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => u.into_pyobject(py)?.into_any(),
            (None, Some(i)) => i.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json_to_py(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (k, v) in map {
                dict.set_item(k, json_to_py(py, v)?)?;
            }
            dict.into_any()
        }
    })
}

fn problems_error(path: &std::path::Path, problems: &Problems) -> PyErr {
    let lines: Vec<String> = problems.0.iter().map(|p| p.to_string()).collect();
    PyValueError::new_err(format!(
        "invalid value for `path`: {} refused: {} error(s)\n{}",
        path.display(),
        problems.errors().count(),
        lines.join("\n")
    ))
}

/// Run the scene file `path` (TOML, docs/user-guide.md) writing its outputs (VTK frames, energy
/// books, plots, checkpoints) into `out_dir` (default `out/<scene name>`), and return its
/// headline as a dict: each headline quantity by name (with its unit, e.g. `e_n`, `runout_m`),
/// plus `text` (the summary line), `step`, `time_s`, `wall_seconds`, `stopped_early` and
/// `checkpoint`. `resume`: a checkpoint to continue from; `stop_at_step`: stop there with a
/// checkpoint; `no_frames`: skip the VTK frames. The GIL is released during the run; Ctrl-C
/// stops it with a checkpoint and raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (path, out_dir = None, *, resume = None, stop_at_step = None, no_frames = false,
    quiet = true))]
pub fn run_scene<'py>(
    py: Python<'py>,
    path: PathBuf,
    out_dir: Option<PathBuf>,
    resume: Option<PathBuf>,
    stop_at_step: Option<u64>,
    no_frames: bool,
    quiet: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = load_scene(&path).map_err(|p| problems_error(&path, &p))?;
    let out = out_dir.unwrap_or_else(|| PathBuf::from("out").join(&scene.name));
    let interrupt = Arc::new(AtomicBool::new(false));
    let options = RunOptions::new(&out)
        .quiet(quiet)
        .resume(resume)
        .stop_at_step(stop_at_step)
        .no_frames(no_frames)
        .interrupt(Arc::clone(&interrupt));
    let mut signal: Option<PyErr> = None;
    // The run goes on in a worker thread; this thread, detached from the interpreter, looks for
    // Ctrl-C (Python's signal handlers run only on the main thread while attached).
    let result = py.detach(|| {
        std::thread::scope(|scope| {
            let handle = scope.spawn(|| run(&scene, &options));
            while !handle.is_finished() {
                std::thread::sleep(Duration::from_millis(20));
                if signal.is_none() {
                    if let Err(e) = Python::attach(|py| py.check_signals()) {
                        interrupt.store(true, Ordering::SeqCst);
                        signal = Some(e);
                    }
                }
            }
            handle.join()
        })
    });
    let summary = match result {
        Ok(Ok(summary)) => summary,
        Ok(Err(SimError::Scene(problems))) => return Err(problems_error(&path, &problems)),
        Ok(Err(e)) => return Err(PyRuntimeError::new_err(e.to_string())),
        Err(_) => return Err(PyRuntimeError::new_err("the scene run panicked")),
    };
    if let Some(e) = signal {
        return Err(e);
    }
    let dict = PyDict::new(py);
    for value in &summary.headline.values {
        dict.set_item(&value.name, value.value)?;
    }
    dict.set_item("text", &summary.headline.text)?;
    dict.set_item("step", summary.step)?;
    dict.set_item("time_s", summary.time)?;
    dict.set_item("wall_seconds", summary.wall_seconds)?;
    dict.set_item("stopped_early", summary.stopped_early)?;
    dict.set_item("checkpoint", summary.checkpoint)?;
    Ok(dict)
}
