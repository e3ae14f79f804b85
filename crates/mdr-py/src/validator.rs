//! The single-impact validator of `mdr-impact`: `curve` (as `mdr-dem impact curve`), `fit` (as
//! `mdr-dem impact fit`) and `oblique` (as `mdr-dem impact oblique`), with the same argument names
//! and defaults and the same output columns.

use crate::arrays::{array1, Values};
use crate::errors::{self, invalid};
use crate::law::{check_steps, declared_values, parse_method, MdrLaw, Params, Setup, PARAM_NAMES};
use mdr_contact::normal::{AdhesiveMdr, NormalLaw, Thornton};
use mdr_contact::params::{Declared, Param};
use mdr_contact::tangential::Mindlin;
use mdr_impact::fit::{fit as fit_law, predict, FitParameter, FitValues};
use mdr_impact::output::Measurement;
use mdr_impact::{
    log_spaced, Impact, ImpactOutcome, Method, NormalSpec, Progress, Sweep, TangentialSpec,
    DEFAULT_SPRINGS, DEFAULT_STEPS_PER_CONTACT, PAPER_SCALE,
};
use mdr_sim::laws::registry::{normal_law, normal_law_names, NORMAL_LAWS};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::collections::BTreeMap;

/// The parameters of the registered normal laws given as keyword arguments, by Python name
/// (each law declares its parameters' keywords: `qc`, `theta_ratio`, `yield_stress`,
/// `normal_stiffness_n_per_m`, …). Those the material arguments hold (`qc`, `theta_ratio`,
/// `work_of_adhesion`) and `yield_stress` (a named argument) stay where they are.
type LawKeywords = BTreeMap<&'static str, f64>;

/// Take the registered laws' other parameter keywords out of `kwargs`.
fn take_law_keywords(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<LawKeywords> {
    let mut taken = LawKeywords::new();
    let Some(kwargs) = kwargs else {
        return Ok(taken);
    };
    for param in NORMAL_LAWS.iter().flat_map(|e| e.declaration.params) {
        let name = param.python_name();
        if PARAM_NAMES.contains(&name) || name == "yield_stress" {
            continue;
        }
        if let Some(value) = kwargs.get_item(name)? {
            let value = value
                .extract::<f64>()
                .map_err(|_| invalid(name, format!("{value} is not a number")))?;
            taken.insert(name, value);
            kwargs.del_item(name)?;
        }
    }
    Ok(taken)
}

/// The normal law named `law` (any registered law: `mdr_dem.scene_laws()`) for `setup`, as the
/// CLI's `--law`, `--elastic` and the law-parameter flags.
fn normal_spec(
    setup: &Setup,
    law: &str,
    elastic: bool,
    yield_stress: Option<f64>,
    keywords: &LawKeywords,
) -> PyResult<NormalSpec> {
    let entry = normal_law(&law.replace('-', "_")).ok_or_else(|| {
        invalid(
            "law",
            format!(
                "`{law}` (registered: {})",
                normal_law_names()
                    .iter()
                    .map(|n| format!("\"{n}\""))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        )
    })?;
    if let Some(unused) = keywords.keys().find(|k| {
        !entry
            .declaration
            .params
            .iter()
            .any(|p| p.python_name() == **k)
    }) {
        return Err(invalid(
            unused,
            format!(
                "it is not a parameter of law=\"{}\"",
                entry.declaration.name
            ),
        ));
    }
    let given = |p: &Param| keywords.get(p.python_name()).copied();
    // The adhesive MDR law is the MDR law with the material's `work_of_adhesion` (its Δγ, which
    // the impact integrates with Heß's rule), as the CLI's `--law adhesive_mdr`: it needs it.
    let adhesive_law = entry.declaration.name == AdhesiveMdr::DECLARATION.name;
    if adhesive_law && setup.params.work_of_adhesion.is_none() {
        return Err(invalid(
            "work_of_adhesion",
            format!(
                "law=\"{}\" needs it ({})",
                entry.declaration.name,
                AdhesiveMdr::DECLARATION.params[2].help()
            ),
        ));
    }
    Ok(match (entry.declaration.name, elastic) {
        // Adhesion is the MDR law's: its elastic limit is JKR, not Hertz.
        ("mdr", true) if setup.work_of_adhesion() > 0.0 => {
            NormalSpec::Mdr(mdr_contact::normal::MdrElastoPlastic::elastic())
        }
        (_, true) if adhesive_law => {
            NormalSpec::Mdr(mdr_contact::normal::MdrElastoPlastic::elastic())
        }
        (_, true) | ("hertz", false) => NormalSpec::Hertz,
        ("mdr", false) => NormalSpec::Mdr(setup.model),
        (_, false) if adhesive_law => NormalSpec::Mdr(setup.model),
        ("thornton", false) => {
            // The CLI's default p_y: the same yield overlap as the MDR law.
            let matched = mdr_impact::law::thornton_matched_yield_stress(
                &setup.pair,
                setup.law.yield_overlap(),
            );
            let values =
                declared_values(&Thornton::DECLARATION, |_| yield_stress, |_| Some(matched))?;
            NormalSpec::Thornton(Thornton::from_values(&values).map_err(errors::contact(false))?)
        }
        (_, false) => NormalSpec::Declared(
            entry
                .impact
                .with_values(&declared_values(&entry.declaration, given, |_| None)?)
                .map_err(|e| invalid("law", e))?,
        ),
    })
}

fn check_scale(scale: f64) -> PyResult<f64> {
    if scale.is_finite() && scale > 0.0 {
        Ok(scale)
    } else {
        Err(invalid(
            "scale",
            format!("{scale} (must be finite and > 0)"),
        ))
    }
}

/// `mu`, checked as `Mindlin` declares its friction coefficient.
fn check_mu(mu: f64) -> PyResult<f64> {
    let param = &Mindlin::DECLARATION.params[0];
    param.check(mu).map_err(|_| {
        invalid(
            param.python_name(),
            format!(
                "{mu} (must be finite and in {}; {})",
                param.range.notation,
                param.help()
            ),
        )
    })
}

/// 1 for a stuck impact (adhesion, e_n = 0), 0 otherwise: the CSV's `stuck` column.
fn stuck_flag(outcome: &ImpactOutcome) -> f64 {
    if outcome.stuck {
        1.0
    } else {
        0.0
    }
}

/// A column of outcomes.
fn column(
    py: Python<'_>,
    outcomes: &[ImpactOutcome],
    f: impl Fn(&ImpactOutcome) -> f64,
) -> Py<PyAny> {
    array1(py, outcomes.iter().map(f).collect())
}

/// e_n(v0) sweep (as `mdr-dem impact curve`): a dict of arrays with the CSV's columns
/// `v0_m_per_s, e_n, e_n_scaled, d_max_m, d_residual_m, contact_time_s, f_max_n, stuck`, and
/// `yield_speed_m_per_s`. `v0`: speeds (m/s); without it, `points` log-spaced speeds from
/// `v_min` to `v_max`.
#[pyfunction]
#[pyo3(signature = (v0 = None, *, v_min = 0.01, v_max = 30.0, points = 200, law = "mdr",
    method = "closed", springs = None, steps = DEFAULT_STEPS_PER_CONTACT, scale = PAPER_SCALE,
    elastic = false, yield_stress = None, **material))]
#[allow(clippy::too_many_arguments)]
pub fn curve<'py>(
    py: Python<'py>,
    v0: Option<&Bound<'py, PyAny>>,
    v_min: f64,
    v_max: f64,
    points: usize,
    law: &str,
    method: &str,
    springs: Option<usize>,
    steps: usize,
    scale: f64,
    elastic: bool,
    yield_stress: Option<f64>,
    material: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let keywords = take_law_keywords(material)?;
    let setup = Params::from_kwargs(material, &[])?.resolve()?;
    let spec = normal_spec(&setup, law, elastic, yield_stress, &keywords)?;
    let method = parse_method(method, springs)?.unwrap_or(Method::Closed);
    if matches!(method, Method::Springs { .. }) && !matches!(spec, NormalSpec::Mdr(_)) {
        return Err(invalid(
            "method",
            "springs is the discrete MDR law; use it with law=\"mdr\" (and elastic=False)",
        ));
    }
    check_steps(steps)?;
    let scale = check_scale(scale)?;
    let speeds = match v0 {
        Some(v0) => Values::read_positive(py, "v0", v0)?.data,
        None => {
            for (name, v) in [("v_min", v_min), ("v_max", v_max)] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(invalid(
                        name,
                        format!("{v} (must be finite and > 0, in m/s)"),
                    ));
                }
            }
            if v_max <= v_min {
                return Err(invalid(
                    "v_max",
                    format!("{v_max} must exceed v_min {v_min}"),
                ));
            }
            if points < 2 {
                return Err(invalid("points", format!("{points} (at least 2)")));
            }
            log_spaced(v_min, v_max, points)
        }
    };
    let template = Impact::new(setup.pair, spec, 1.0)
        .work_of_adhesion(setup.work_of_adhesion())
        .method(method)
        .steps_per_contact(steps);
    let (outcomes, yield_speed) = py
        .detach(|| -> mdr_impact::Result<_> {
            let outcomes = Sweep::speeds(template, &speeds)
                .progress(Progress::Hidden)
                .run()?;
            Ok((outcomes, template.yield_speed()?))
        })
        .map_err(errors::impact("v0"))?;
    let dict = PyDict::new(py);
    dict.set_item("v0_m_per_s", column(py, &outcomes, |o| o.speed))?;
    dict.set_item("e_n", column(py, &outcomes, |o| o.normal_restitution))?;
    dict.set_item(
        "e_n_scaled",
        column(py, &outcomes, |o| scale * o.normal_restitution),
    )?;
    dict.set_item("d_max_m", column(py, &outcomes, |o| o.max_overlap))?;
    dict.set_item(
        "d_residual_m",
        column(py, &outcomes, |o| o.residual_overlap),
    )?;
    dict.set_item("contact_time_s", column(py, &outcomes, |o| o.contact_time))?;
    dict.set_item("f_max_n", column(py, &outcomes, |o| o.peak_force))?;
    dict.set_item("stuck", column(py, &outcomes, stuck_flag))?;
    dict.set_item("yield_speed_m_per_s", yield_speed)?;
    Ok(dict)
}

/// The result of [`fit`].
#[pyclass(module = "mdr_dem", frozen)]
pub struct FitResult {
    /// Fitted critical line load q_c (N/m).
    #[pyo3(get)]
    qc: f64,
    /// Fitted hardening ratio Θ/E*.
    #[pyo3(get)]
    theta_ratio: f64,
    /// Fitted scale factor.
    #[pyo3(get)]
    scale: f64,
    /// 1σ uncertainty of q_c (N/m); None if q_c was fixed.
    #[pyo3(get)]
    qc_uncertainty: Option<f64>,
    /// 1σ uncertainty of Θ/E*; None if fixed.
    #[pyo3(get)]
    theta_ratio_uncertainty: Option<f64>,
    /// 1σ uncertainty of the scale; None if fixed.
    #[pyo3(get)]
    scale_uncertainty: Option<f64>,
    /// Fitted (or fixed) work of adhesion Δγ (J/m²).
    #[pyo3(get)]
    work_of_adhesion: f64,
    /// 1σ uncertainty of Δγ (J/m²); None if fixed.
    #[pyo3(get)]
    work_of_adhesion_uncertainty: Option<f64>,
    /// measured e − model e at each data point.
    #[pyo3(get)]
    residuals: Py<PyAny>,
    /// Root-mean-square residual.
    #[pyo3(get)]
    rmse: f64,
    /// Number of data points.
    #[pyo3(get)]
    n_points: usize,
    /// Number of points above the fitted yield speed.
    #[pyo3(get)]
    n_plastic: usize,
    /// Fitted yield speed (m/s).
    #[pyo3(get)]
    yield_speed: f64,
    /// The fitted parameters' names, in the order given.
    #[pyo3(get)]
    free: Vec<String>,
    setup: Setup,
    values: FitValues,
}

#[pymethods]
impl FitResult {
    /// The fitted model's scale · e_n at `v0` (m/s; a float or any array-like).
    fn predict(&self, py: Python<'_>, v0: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let values = Values::read_positive(py, "v0", v0)?;
        let (pair, fitted) = (self.setup.pair, self.values);
        let e = py
            .detach(|| predict(&pair, &fitted, &values.data))
            .map_err(errors::impact("v0"))?;
        values.shaped(py, e)
    }

    /// The fitted law (an MdrLaw with the fitted q_c and Θ/E* and the fit's material arguments).
    #[getter]
    fn law(&self) -> PyResult<MdrLaw> {
        let params = Params {
            qc: Some(self.qc),
            theta_ratio: Some(self.theta_ratio),
            work_of_adhesion: Some(self.work_of_adhesion),
            ..self.setup.params
        };
        Ok(MdrLaw {
            setup: params.resolve()?,
        })
    }

    /// The fitted values and uncertainties as a dict, with the keys of
    /// `mdr-dem impact fit --json` (q_c, theta_ratio, scale, work_of_adhesion, rmse, n_points,
    /// uncertainty, yield_speed_m_per_s).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("q_c", self.qc)?;
        dict.set_item("theta_ratio", self.theta_ratio)?;
        dict.set_item("scale", self.scale)?;
        dict.set_item("work_of_adhesion", self.work_of_adhesion)?;
        dict.set_item("rmse", self.rmse)?;
        dict.set_item("n_points", self.n_points)?;
        let uncertainty = PyDict::new(py);
        for (key, value) in [
            ("q_c", self.qc_uncertainty),
            ("theta_ratio", self.theta_ratio_uncertainty),
            ("scale", self.scale_uncertainty),
            ("work_of_adhesion", self.work_of_adhesion_uncertainty),
        ] {
            if let Some(v) = value {
                uncertainty.set_item(key, v)?;
            }
        }
        dict.set_item("uncertainty", uncertainty)?;
        dict.set_item("yield_speed_m_per_s", self.yield_speed)?;
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        let show = |v: f64, s: Option<f64>| match s {
            Some(s) => format!("{v:.6e} ± {s:.2e}"),
            None => format!("{v:.6e} (fixed)"),
        };
        format!(
            "FitResult(qc={}, theta_ratio={}, scale={}, rmse={:.3e}, n_points={})",
            show(self.qc, self.qc_uncertainty),
            show(self.theta_ratio, self.theta_ratio_uncertainty),
            show(self.scale, self.scale_uncertainty),
            self.rmse,
            self.n_points
        )
    }
}

/// Least-squares fit of the MDR law to measured restitution (as `mdr-dem impact fit`):
/// `scale · e_n(v; q_c, Θ/E*, Δγ)` is matched to `(v0, e)`. `free`: the parameters to adjust,
/// a subset of ("qc", "theta_ratio", "scale", "work_of_adhesion") (default: the first three;
/// work_of_adhesion needs data with sticking points, e = 0); `qc`, `theta_ratio`,
/// `work_of_adhesion` (in `material`) and `scale` are the starting values, and the values of the
/// fixed ones.
#[pyfunction]
#[pyo3(signature = (v0, e, *, free = None, scale = PAPER_SCALE, **material))]
pub fn fit<'py>(
    py: Python<'py>,
    v0: &Bound<'py, PyAny>,
    e: &Bound<'py, PyAny>,
    free: Option<Vec<String>>,
    scale: f64,
    material: Option<&Bound<'py, PyDict>>,
) -> PyResult<FitResult> {
    let setup = Params::from_kwargs(material, &[])?.resolve()?;
    let scale = check_scale(scale)?;
    let speeds = Values::read_positive(py, "v0", v0)?.data;
    let measured = Values::read(py, "e", e)?.data;
    if speeds.len() != measured.len() {
        return Err(invalid(
            "e",
            format!(
                "{} values for {} speeds v0 (one e per speed)",
                measured.len(),
                speeds.len()
            ),
        ));
    }
    if let Some(bad) = measured.iter().find(|x| !x.is_finite()) {
        return Err(invalid("e", format!("{bad} (must be finite)")));
    }
    let names = free.unwrap_or_else(|| vec!["qc".into(), "theta_ratio".into(), "scale".into()]);
    let free = names
        .iter()
        .map(|n| FitParameter::parse(n))
        .collect::<Result<Vec<_>, _>>()
        .map_err(errors::impact("v0"))?;
    let data: Vec<Measurement> = speeds
        .iter()
        .zip(&measured)
        .map(|(&speed, &restitution)| Measurement { speed, restitution })
        .collect();
    let initial = FitValues {
        q_c: setup.model.critical_line_load(),
        theta_ratio: setup.law.hardening_ratio(),
        scale,
        work_of_adhesion: setup.work_of_adhesion(),
    };
    let pair = setup.pair;
    let (report, model) = py
        .detach(|| -> mdr_impact::Result<_> {
            let report = fit_law(&pair, initial, &free, &data)?;
            let model = predict(&pair, &report.values, &speeds)?;
            Ok((report, model))
        })
        .map_err(errors::impact("v0"))?;
    let sigma = |p: FitParameter| {
        report
            .uncertainties
            .iter()
            .find(|(q, _)| *q == p)
            .map(|(_, s)| *s)
    };
    let residuals = measured.iter().zip(&model).map(|(m, f)| m - f).collect();
    Ok(FitResult {
        qc: report.values.q_c,
        theta_ratio: report.values.theta_ratio,
        scale: report.values.scale,
        qc_uncertainty: sigma(FitParameter::CriticalLineLoad),
        theta_ratio_uncertainty: sigma(FitParameter::HardeningRatio),
        scale_uncertainty: sigma(FitParameter::Scale),
        work_of_adhesion: report.values.work_of_adhesion,
        work_of_adhesion_uncertainty: sigma(FitParameter::WorkOfAdhesion),
        residuals: array1(py, residuals),
        rmse: report.rmse,
        n_points: report.n_points,
        n_plastic: report.n_plastic,
        yield_speed: report.yield_speed,
        free: names,
        setup,
        values: report.values,
    })
}

/// Oblique impacts on a half-space with friction and rotation (as `mdr-dem impact oblique`): a
/// dict of arrays `angle_deg, e_n, e_t, rebound_angle_deg, omega_rad_per_s`. `speed` (m/s);
/// `angles` from the normal (degrees, in [0, 90)); `tangential`: "springs" (MDR spring bed,
/// needs method="springs", the default then) or "mindlin"; `spin`: initial angular velocity
/// (rad/s); `mu`: friction coefficient.
#[pyfunction]
#[pyo3(signature = (speed, angles = None, *, tangential = None, spin = 0.0, mu = 0.2,
    method = None, springs = None, steps = DEFAULT_STEPS_PER_CONTACT, law = "mdr",
    elastic = false, yield_stress = None, **material))]
#[allow(clippy::too_many_arguments)]
pub fn oblique<'py>(
    py: Python<'py>,
    speed: f64,
    angles: Option<&Bound<'py, PyAny>>,
    tangential: Option<&str>,
    spin: f64,
    mu: f64,
    method: Option<&str>,
    springs: Option<usize>,
    steps: usize,
    law: &str,
    elastic: bool,
    yield_stress: Option<f64>,
    material: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let keywords = take_law_keywords(material)?;
    let setup = Params::from_kwargs(material, &[])?.resolve()?;
    if !setup.half_space() {
        return Err(invalid(
            "target_radius",
            "oblique impacts are computed on a half-space; omit target_radius and target_density",
        ));
    }
    if !(speed.is_finite() && speed > 0.0) {
        return Err(invalid(
            "speed",
            format!("{speed} (must be finite and > 0, in m/s)"),
        ));
    }
    if !spin.is_finite() {
        return Err(invalid(
            "spin",
            format!("{spin} (must be finite, in rad/s)"),
        ));
    }
    let mu = check_mu(mu)?;
    check_steps(steps)?;
    let spec = normal_spec(&setup, law, elastic, yield_stress, &keywords)?;
    let angles = match angles {
        Some(a) => Values::read(py, "angles", a)?.data,
        None => vec![5.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 85.0],
    };
    if let Some(bad) = angles
        .iter()
        .find(|a| !(a.is_finite() && (0.0..90.0).contains(*a)))
    {
        return Err(invalid(
            "angles",
            format!("{bad} (angles from the normal in [0, 90) degrees)"),
        ));
    }
    let method = match method {
        Some(m) => parse_method(m, springs)?,
        None => None,
    };
    // Defaults as the CLI: the spring-bed tangential law for MDR unless method="closed".
    let tangential = match tangential {
        Some("springs") => TangentialSpec::SpringBed,
        Some("mindlin") => TangentialSpec::Mindlin,
        Some(other) => {
            return Err(invalid(
                "tangential",
                format!("`{other}` (allowed: \"springs\", \"mindlin\")"),
            ))
        }
        None if matches!(spec, NormalSpec::Mdr(_)) && method != Some(Method::Closed) => {
            TangentialSpec::SpringBed
        }
        None => TangentialSpec::Mindlin,
    };
    let method = match (method, tangential) {
        (Some(m), _) => m,
        (None, TangentialSpec::SpringBed) => Method::Springs {
            springs: springs.unwrap_or(DEFAULT_SPRINGS),
        },
        (None, TangentialSpec::Mindlin) => Method::Closed,
    };
    if tangential == TangentialSpec::SpringBed && !matches!(method, Method::Springs { .. }) {
        return Err(invalid(
            "tangential",
            "springs needs method=\"springs\" (or use tangential=\"mindlin\")",
        ));
    }
    if matches!(method, Method::Springs { .. }) && !matches!(spec, NormalSpec::Mdr(_)) {
        return Err(invalid(
            "method",
            "springs is the discrete MDR law; use it with law=\"mdr\" (and elastic=False)",
        ));
    }
    let template = Impact::new(setup.pair, spec, speed)
        .work_of_adhesion(setup.work_of_adhesion())
        .method(method)
        .tangential(tangential)
        .spin(spin)
        .friction(mu)
        .steps_per_contact(steps);
    let outcomes = py
        .detach(|| {
            Sweep::angles(template, &angles)
                .progress(Progress::Hidden)
                .run()
        })
        .map_err(errors::impact("speed"))?;
    let dict = PyDict::new(py);
    dict.set_item("angle_deg", column(py, &outcomes, |o| o.angle_degrees))?;
    dict.set_item("e_n", column(py, &outcomes, |o| o.normal_restitution))?;
    dict.set_item(
        "e_t",
        column(py, &outcomes, |o| {
            o.tangential_restitution.unwrap_or(f64::NAN)
        }),
    )?;
    dict.set_item(
        "rebound_angle_deg",
        column(py, &outcomes, |o| o.rebound_angle_degrees),
    )?;
    dict.set_item("omega_rad_per_s", column(py, &outcomes, |o| o.spin))?;
    dict.set_item("stuck", column(py, &outcomes, stuck_flag))?;
    Ok(dict)
}
