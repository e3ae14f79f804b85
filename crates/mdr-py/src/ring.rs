//! `Ring`: the planetary-ring shearing box of `mdr-ring` (`RingSimulation`), with the MDR ice
//! law, the Bridges law, a constant ε or a Python callable `law(v) -> ε` as restitution law (as
//! REBOUND's `coefficient_of_restitution`). Kept small: the configuration dict mirrors the flags
//! of `mdr-dem sim ring`, and the run loop is `RingSimulation::run`'s, so that changes to the
//! ring crate carry over.

use crate::arrays::array1;
use crate::errors::{self, invalid};
use crate::scene::json_to_py;
use mdr_contact::normal::{MdrElastoPlastic, MdrState};
use mdr_contact::Material;
use mdr_ring::diagnostics::{summarize, Sample};
use mdr_ring::law::{BridgesLaw, ConstantRestitution, ImpactPair, MdrRestitution, RestitutionLaw};
use mdr_ring::prelude::{RingConfig, RingSimulation, SelfGravity};
use mdr_ring::RingError;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// A column of the ring samples: its name and how to read it from one sample.
type SampleColumn = (&'static str, fn(&Sample) -> f64);

/// A Python callable `law(v) -> ε` (v: normal approach speed in m/s). The first exception or
/// invalid value is kept and raised by `Ring.run`; later impacts of that step are elastic.
struct PythonLaw {
    callable: Py<PyAny>,
    error: Arc<Mutex<Option<PyErr>>>,
    calls: AtomicU64,
}

impl PythonLaw {
    fn call(&self, speed: f64) -> f64 {
        let Ok(mut error) = self.error.lock() else {
            return 1.0;
        };
        if error.is_some() {
            return 1.0;
        }
        self.calls.fetch_add(1, Ordering::Relaxed);
        let result = Python::attach(|py| -> PyResult<f64> {
            let value = self.callable.call1(py, (speed,))?;
            let eps: f64 = value.extract(py).map_err(|_| {
                PyValueError::new_err(format!(
                    "invalid value for `law`: the restitution callable returned {} for v = {speed} \
                     m/s (must be a number in [0, 1])",
                    value.bind(py)
                ))
            })?;
            if eps.is_finite() && (0.0..=1.0).contains(&eps) {
                Ok(eps)
            } else {
                Err(PyValueError::new_err(format!(
                    "invalid value for `law`: the restitution callable returned {eps} for v = \
                     {speed} m/s (must be in [0, 1])"
                )))
            }
        });
        match result {
            Ok(eps) => eps,
            Err(e) => {
                *error = Some(e);
                1.0
            }
        }
    }
}

/// The restitution law of a ring run.
enum RingLaw {
    Mdr(MdrRestitution),
    Bridges(BridgesLaw),
    Constant(ConstantRestitution),
    Python(PythonLaw),
}

impl RestitutionLaw for RingLaw {
    type History = MdrState;

    fn restitution(&self, pair: &ImpactPair, history: &mut MdrState, speed: f64) -> f64 {
        match self {
            RingLaw::Mdr(law) => law.restitution(pair, history, speed),
            RingLaw::Bridges(law) => law.restitution(pair, &mut (), speed),
            RingLaw::Constant(law) => law.restitution(pair, &mut (), speed),
            RingLaw::Python(law) => law.call(speed),
        }
    }

    fn name(&self) -> &'static str {
        match self {
            RingLaw::Mdr(law) => law.name(),
            RingLaw::Bridges(law) => law.name(),
            RingLaw::Constant(law) => law.name(),
            RingLaw::Python(_) => "python",
        }
    }
}

/// Configuration keys (as the flags of `mdr-dem sim ring`).
const CONFIG_KEYS: [&str; 9] = [
    "particles",
    "surface_density",
    "box",
    "seed",
    "omega",
    "dt_orbits",
    "sample_orbits",
    "density",
    "gravity",
];

fn ring_error(e: RingError) -> PyErr {
    match e {
        RingError::OutOfRange { name, .. } => invalid(name, e),
        RingError::Placement { .. } => invalid("particles", e),
        RingError::Contact(c) => errors::contact(false)(c),
        RingError::Coupling(_) => invalid("law", e),
        other => PyRuntimeError::new_err(other.to_string()),
    }
}

fn config_from(dict: Option<&Bound<'_, PyDict>>) -> PyResult<RingConfig> {
    let mut config = RingConfig::default();
    let Some(dict) = dict else {
        return Ok(config);
    };
    let number = |key: &str, value: &Bound<'_, PyAny>| -> PyResult<f64> {
        value
            .extract::<f64>()
            .map_err(|_| invalid(key, format!("{value} is not a number")))
    };
    let count = |key: &str, value: &Bound<'_, PyAny>| -> PyResult<u64> {
        value
            .extract::<u64>()
            .map_err(|_| invalid(key, format!("{value} is not a non-negative integer")))
    };
    if dict.contains("particles")? && dict.contains("surface_density")? {
        return Err(invalid(
            "surface_density",
            "give either particles or surface_density, not both",
        ));
    }
    for (key, value) in dict.iter() {
        let key: String = key.extract()?;
        match key.as_str() {
            "particles" => config = config.particles(count(&key, &value)? as usize),
            "surface_density" => config = config.surface_density(number(&key, &value)?),
            "box" => config = config.box_size(number(&key, &value)?),
            "seed" => config = config.seed(count(&key, &value)?),
            "omega" => config.omega = number(&key, &value)?,
            "dt_orbits" => config = config.dt_orbits(number(&key, &value)?),
            "sample_orbits" => config.sample_orbits = number(&key, &value)?,
            "density" => config.density = number(&key, &value)?,
            "gravity" => {
                if value
                    .extract::<bool>()
                    .map_err(|_| invalid(&key, "must be True or False"))?
                {
                    config = config.gravity(SelfGravity::default());
                }
            }
            other => {
                return Err(invalid(
                    other,
                    format!("unknown ring setting (allowed: {})", CONFIG_KEYS.join(", ")),
                ))
            }
        }
    }
    Ok(config)
}

fn sample_dict<'py>(py: Python<'py>, sample: &Sample) -> PyResult<Bound<'py, PyAny>> {
    let value = serde_json::to_value(sample).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    json_to_py(py, &value)
}

/// A planetary-ring shearing box (Hill's equations, shear-periodic boundaries, hard-sphere
/// collisions through rapier with a restitution law); docs/rings.md.
#[pyclass(module = "mdr_dem")]
pub struct Ring {
    sim: Mutex<RingSimulation<RingLaw>>,
    error: Arc<Mutex<Option<PyErr>>>,
    samples: Vec<Sample>,
}

impl Ring {
    fn with_sim<T>(&self, f: impl FnOnce(&mut RingSimulation<RingLaw>) -> T) -> PyResult<T> {
        let mut sim = self
            .sim
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the ring is in an inconsistent state"))?;
        Ok(f(&mut sim))
    }

    fn vectors(&self, py: Python<'_>, velocity: bool) -> PyResult<Py<PyAny>> {
        let flat: Vec<f64> = self.with_sim(|sim| {
            let p = sim.particles();
            let source = if velocity { &p.velocity } else { &p.position };
            source.iter().flat_map(|v| [v.x, v.y, v.z]).collect()
        })?;
        let n = flat.len() / 3;
        Ok(PyArray1::from_vec(py, flat)
            .reshape([n, 3])?
            .into_any()
            .unbind())
    }
}

#[pymethods]
impl Ring {
    #[new]
    #[pyo3(signature = (config = None, law = None, *, youngs = 9.0e9, poisson = 0.33, qc = 8.0e3,
        theta_ratio = 0.2))]
    fn new(
        config: Option<&Bound<'_, PyDict>>,
        law: Option<&Bound<'_, PyAny>>,
        youngs: f64,
        poisson: f64,
        qc: f64,
        theta_ratio: f64,
    ) -> PyResult<Self> {
        let config = config_from(config)?;
        let error = Arc::new(Mutex::new(None));
        let law = match law {
            None => RingLaw::Bridges(BridgesLaw::default()),
            Some(law) if law.is_callable() => RingLaw::Python(PythonLaw {
                callable: law.clone().unbind(),
                error: Arc::clone(&error),
                calls: AtomicU64::new(0),
            }),
            Some(law) => {
                if let Ok(name) = law.extract::<String>() {
                    match name.as_str() {
                        "bridges" => RingLaw::Bridges(BridgesLaw::default()),
                        "mdr" => {
                            // Ice spheres of the ring's density (docs/rings.md §6).
                            let ice = Material::new(youngs, poisson, config.density)
                                .map_err(errors::contact(false))?;
                            let model = MdrElastoPlastic::new(qc, theta_ratio)
                                .map_err(errors::contact(false))?;
                            RingLaw::Mdr(
                                MdrRestitution::new(ice, model).map_err(errors::contact(false))?,
                            )
                        }
                        other => {
                            return Err(invalid(
                                "law",
                                format!(
                                    "`{other}` (allowed: \"bridges\", \"mdr\", a constant ε in \
                                     [0, 1], or a callable law(v) -> ε)"
                                ),
                            ))
                        }
                    }
                } else if let Ok(eps) = law.extract::<f64>() {
                    RingLaw::Constant(ConstantRestitution::new(eps).map_err(|e| invalid("law", e))?)
                } else {
                    return Err(invalid(
                        "law",
                        "must be \"bridges\", \"mdr\", a constant ε in [0, 1], or a callable \
                         law(v) -> ε",
                    ));
                }
            }
        };
        let sim = RingSimulation::new(config, law).map_err(ring_error)?;
        Ok(Self {
            sim: Mutex::new(sim),
            error,
            samples: Vec::new(),
        })
    }

    /// Run for `orbits` orbits (> 0), sampling every `sample_orbits`, and return the averages over
    /// the second half of this run as a dict (the keys of `mdr-dem sim ring --json`'s summary:
    /// c_m_per_s, sigma_x_m_per_s, …, optical_depth). `callback(sample)`, if given, is called
    /// with each sample as a dict. The GIL is released while the ring steps; Ctrl-C stops the run
    /// at the next sample with KeyboardInterrupt.
    #[pyo3(signature = (orbits, callback = None))]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        orbits: f64,
        callback: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        if !(orbits.is_finite() && orbits > 0.0) {
            return Err(invalid(
                "orbits",
                format!("{orbits} (must be finite and > 0)"),
            ));
        }
        if let Some(cb) = &callback {
            if !cb.is_callable() {
                return Err(invalid("callback", "must be callable (or None)"));
            }
        }
        let mut sim = self
            .sim
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the ring is in an inconsistent state"))?;
        // The loop of `RingSimulation::run`, with a sample's Python work between steps.
        let (dt_orbits, sample_orbits) = (sim.config().dt_orbits, sim.config().sample_orbits);
        let per_sample = ((sample_orbits / dt_orbits).round() as u64).max(1);
        let total = ((orbits / dt_orbits).round() as u64).max(1);
        let start = Instant::now();
        let mut samples = Vec::new();
        let mut done = 0;
        while done < total {
            let chunk = (per_sample - done % per_sample).min(total - done);
            let sim_ref: &mut RingSimulation<RingLaw> = &mut sim;
            let error = &self.error;
            py.detach(|| {
                sim_ref.step_many(chunk, || error.lock().map_or(true, |e| e.is_some()));
            });
            done += chunk;
            if let Some(e) = self.error.lock().ok().and_then(|mut e| e.take()) {
                return Err(e);
            }
            let sample = Sample {
                wall_s: start.elapsed().as_secs_f64(),
                ..sim.sample()
            };
            samples.push(sample);
            self.samples.push(sample);
            py.check_signals()?;
            if let Some(cb) = &callback {
                cb.call1((sample_dict(py, &sample)?,))?;
            }
        }
        let summary = summarize(&samples, sim.particles(), sim.domain(), orbits);
        let value =
            serde_json::to_value(summary).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        json_to_py(py, &value)
    }

    /// Particle centres (m), an (N, 3) array in the co-rotating frame (x radial, y azimuthal,
    /// z vertical).
    #[getter]
    fn positions(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        self.vectors(py, false)
    }

    /// Particle velocities (m/s), an (N, 3) array (Keplerian shear included).
    #[getter]
    fn velocities(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        self.vectors(py, true)
    }

    /// Particle radii (m).
    #[getter]
    fn radii(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let r = self.with_sim(|sim| sim.particles().radius.clone())?;
        Ok(array1(py, r))
    }

    /// Particle masses (kg).
    #[getter]
    fn masses(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let m = self.with_sim(|sim| sim.particles().mass.clone())?;
        Ok(array1(py, m))
    }

    /// Time since the start (orbits).
    #[getter]
    fn time_orbits(&self) -> PyResult<f64> {
        self.with_sim(|sim| sim.time_orbits())
    }

    /// Impacts resolved so far.
    #[getter]
    fn collisions(&self) -> PyResult<u64> {
        self.with_sim(|sim| sim.collisions())
    }

    /// Name of the restitution law: "bridges", "mdr", "constant" or "python".
    #[getter]
    fn law_name(&self) -> PyResult<&'static str> {
        self.with_sim(|sim| sim.world().hooks().law().name())
    }

    /// Calls of a Python restitution law so far (0 for the built-in laws).
    #[getter]
    fn law_calls(&self) -> PyResult<u64> {
        self.with_sim(|sim| match sim.world().hooks().law() {
            RingLaw::Python(law) => law.calls.load(Ordering::Relaxed),
            _ => 0,
        })
    }

    /// Every sample taken by `run` so far, as a dict of arrays (t_orbits, sigma_x, sigma_y,
    /// sigma_z, c, c_number, z_rms, z_rms_number, filling_factor_z0, collisions, wall_s).
    #[getter]
    fn samples<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        let s = &self.samples;
        let columns: [SampleColumn; 11] = [
            ("t_orbits", |s| s.t_orbits),
            ("sigma_x", |s| s.sigma_x),
            ("sigma_y", |s| s.sigma_y),
            ("sigma_z", |s| s.sigma_z),
            ("c", |s| s.c),
            ("c_number", |s| s.c_number),
            ("z_rms", |s| s.z_rms),
            ("z_rms_number", |s| s.z_rms_number),
            ("filling_factor_z0", |s| s.filling_factor_z0),
            ("collisions", |s| s.collisions as f64),
            ("wall_s", |s| s.wall_s),
        ];
        for (name, f) in columns {
            dict.set_item(name, array1(py, s.iter().map(f).collect()))?;
        }
        Ok(dict)
    }

    fn __len__(&self) -> PyResult<usize> {
        self.with_sim(|sim| sim.particles().len())
    }

    fn __repr__(&self) -> PyResult<String> {
        self.with_sim(|sim| {
            format!(
                "Ring({} particles, law {}, t = {:.3} orbits)",
                sim.particles().len(),
                sim.world().hooks().law().name(),
                sim.time_orbits()
            )
        })
    }
}
