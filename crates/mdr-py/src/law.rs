//! `MdrLaw`, `MdrState`, `ImpactTrace`: the MDR law of `mdr-contact` bound to one pair, with the
//! keyword arguments of the CLI's material and law flags (`src/cli/impact.rs`) and their defaults
//! (the paper's Fig. 2: steel ball R = 0.635 cm on a steel half-space, `q_c = 3.8·10⁵ N/m`,
//! `Θ/E* = 0.37`).

use crate::arrays::{array1, Values};
use crate::errors::{self, invalid};
use mdr_contact::normal::{AdhesiveMdr, AdhesiveMdrLaw, AdhesiveMdrState as State};
use mdr_contact::normal::{MdrElastoPlastic, MdrLaw as BoundLaw, MdrState as PlainState};
use mdr_contact::normal::{NormalLaw, NormalModel};
use mdr_contact::params::{Declared, LawDeclaration, Param, ParamProblem};
use mdr_contact::{ContactPair, Material};
use mdr_impact::{Impact, Method, NormalSpec, DEFAULT_SPRINGS, DEFAULT_STEPS_PER_CONTACT};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The material and law keyword arguments (SI units); `None` takes the default.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Params {
    pub radius: Option<f64>,
    pub density: Option<f64>,
    pub youngs: Option<f64>,
    pub poisson: Option<f64>,
    pub target_radius: Option<f64>,
    pub target_density: Option<f64>,
    pub target_youngs: Option<f64>,
    pub target_poisson: Option<f64>,
    pub qc: Option<f64>,
    pub theta_ratio: Option<f64>,
    pub work_of_adhesion: Option<f64>,
}

/// The names of [`Params`], as keyword arguments.
pub const PARAM_NAMES: [&str; 11] = [
    "radius",
    "density",
    "youngs",
    "poisson",
    "target_radius",
    "target_density",
    "target_youngs",
    "target_poisson",
    "qc",
    "theta_ratio",
    "work_of_adhesion",
];

impl Params {
    /// Take the material and law keys out of `kwargs`; any other key left is a `TypeError`
    /// unless it is in `others` (the caller's own keys, left in place).
    pub fn from_kwargs(kwargs: Option<&Bound<'_, PyDict>>, others: &[&str]) -> PyResult<Params> {
        let mut params = Params::default();
        let Some(kwargs) = kwargs else {
            return Ok(params);
        };
        for (key, value) in kwargs.iter() {
            let key: String = key.extract()?;
            let slot = match key.as_str() {
                "radius" => &mut params.radius,
                "density" => &mut params.density,
                "youngs" => &mut params.youngs,
                "poisson" => &mut params.poisson,
                "target_radius" => &mut params.target_radius,
                "target_density" => &mut params.target_density,
                "target_youngs" => &mut params.target_youngs,
                "target_poisson" => &mut params.target_poisson,
                "qc" => &mut params.qc,
                "theta_ratio" => &mut params.theta_ratio,
                "work_of_adhesion" => &mut params.work_of_adhesion,
                other if others.contains(&other) => continue,
                other => {
                    return Err(PyTypeError::new_err(format!(
                        "unexpected keyword argument `{other}` (the material and law arguments \
                         are {}; see help())",
                        PARAM_NAMES.join(", ")
                    )))
                }
            };
            *slot = if value.is_none() {
                None
            } else {
                Some(
                    value
                        .extract::<f64>()
                        .map_err(|_| invalid(&key, format!("{value} is not a number")))?,
                )
            };
        }
        Ok(params)
    }

    /// The pair and the MDR parameters, as the CLI resolves its flags: target material defaults
    /// to the particle's, no target radius/density is a half-space.
    pub fn resolve(&self) -> PyResult<Setup> {
        let particle = Material::new(
            self.youngs.unwrap_or(2.0e11),
            self.poisson.unwrap_or(0.286),
            self.density.unwrap_or(7800.0),
        )
        .map_err(errors::contact(false))?;
        let target = Material::new(
            self.target_youngs.unwrap_or(particle.youngs_modulus()),
            self.target_poisson.unwrap_or(particle.poisson_ratio()),
            self.target_density.unwrap_or(particle.density()),
        )
        .map_err(errors::contact(true))?;
        let radius = self.radius.unwrap_or(0.635e-2);
        let pair = match (self.target_radius, self.target_density) {
            (None, None) => ContactPair::sphere_on_half_space(radius, &particle, &target),
            (Some(target_radius), Some(_)) => {
                ContactPair::sphere_on_sphere(radius, &particle, target_radius, &target)
            }
            (Some(_), None) => {
                return Err(invalid(
                    "target_radius",
                    "a target sphere needs target_density too (omit both for a half-space)",
                ))
            }
            (None, Some(_)) => {
                return Err(invalid(
                    "target_density",
                    "a target sphere needs target_radius too (omit both for a half-space)",
                ))
            }
        }
        .map_err(errors::contact(false))?;
        let given = |p: &Param| match p.python_name() {
            "qc" => self.qc,
            "theta_ratio" => self.theta_ratio,
            _ => None,
        };
        let model = MdrElastoPlastic::from_values(&declared_values(
            &MdrElastoPlastic::DECLARATION,
            given,
            |_| None,
        )?)
        .map_err(errors::contact(false))?;
        let law = model.bind(&pair).map_err(errors::contact(false))?;
        let work_of_adhesion = self.work_of_adhesion.unwrap_or(0.0);
        let adhesive = AdhesiveMdr::new(model, work_of_adhesion)
            .map_err(errors::contact(false))?
            .bind(&pair)
            .map_err(errors::contact(false))?;
        Ok(Setup {
            params: *self,
            pair,
            model,
            law,
            adhesive,
        })
    }
}

/// The values of `law`'s declared parameters: the keyword's (`given`), else the validator's
/// default (`mdr_impact::law::validator_default`), else `fallback`'s; each checked against its
/// declared range, the error naming the keyword, the range and the equation.
pub fn declared_values(
    law: &LawDeclaration,
    given: impl Fn(&Param) -> Option<f64>,
    fallback: impl Fn(&Param) -> Option<f64>,
) -> PyResult<Vec<f64>> {
    law.values(|p| {
        given(p)
            .or_else(|| mdr_impact::law::validator_default(p))
            .or_else(|| fallback(p))
    })
    .map_err(|problems| {
        let problem = &problems[0];
        let (ParamProblem::Missing(p) | ParamProblem::Invalid(p, _)) = problem;
        invalid(p.python_name(), format!("{problem} (law=\"{}\")", law.name))
    })
}

/// Resolved [`Params`].
#[derive(Debug, Clone, Copy)]
pub struct Setup {
    pub params: Params,
    pub pair: ContactPair,
    pub model: MdrElastoPlastic,
    pub law: BoundLaw,
    /// The law with the work of adhesion (the plain law when it is 0).
    pub adhesive: AdhesiveMdrLaw,
}

impl Setup {
    /// Whether the target is a half-space.
    pub fn half_space(&self) -> bool {
        self.params.target_radius.is_none()
    }

    /// `Δγ` (J/m²).
    pub fn work_of_adhesion(&self) -> f64 {
        self.adhesive.work_of_adhesion()
    }

    /// An impact of this pair with the MDR law (and its adhesion) at `speed`.
    pub fn impact(&self, speed: f64) -> Impact {
        Impact::new(self.pair, NormalSpec::Mdr(self.model), speed)
            .work_of_adhesion(self.work_of_adhesion())
    }
}

/// History of one MDR contact: the largest overlap reached so far and, with adhesion, the
/// radius of the attached springs and the adhesive work booked so far.
#[pyclass(module = "mdr_dem", from_py_object)]
#[derive(Debug, Clone, Copy, Default)]
pub struct MdrState {
    /// Largest overlap so far, d_max (m).
    #[pyo3(get, set)]
    pub max_overlap: f64,
    /// Radius of the attached springs (m); with adhesion it stays positive while the contact
    /// holds, also at negative overlaps.
    #[pyo3(get, set)]
    pub contact_radius: f64,
    /// Energy the springs held when they let go, summed (J).
    #[pyo3(get, set)]
    pub adhesive_work: f64,
}

impl MdrState {
    fn history(&self) -> State {
        State {
            max_overlap: self.max_overlap,
            contact_radius: self.contact_radius,
            adhesive_work: self.adhesive_work,
        }
    }

    fn store(&mut self, history: &State) {
        self.max_overlap = history.max_overlap;
        self.contact_radius = history.contact_radius;
        self.adhesive_work = history.adhesive_work;
    }
}

#[pymethods]
impl MdrState {
    #[new]
    #[pyo3(signature = (max_overlap = 0.0, contact_radius = 0.0, adhesive_work = 0.0))]
    fn new(max_overlap: f64, contact_radius: f64, adhesive_work: f64) -> PyResult<Self> {
        for (name, value) in [
            ("max_overlap", max_overlap),
            ("contact_radius", contact_radius),
            ("adhesive_work", adhesive_work),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(name, format!("{value} (must be finite and ≥ 0)")));
            }
        }
        Ok(Self {
            max_overlap,
            contact_radius,
            adhesive_work,
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "MdrState(max_overlap={:e}, contact_radius={:e}, adhesive_work={:e})",
            self.max_overlap, self.contact_radius, self.adhesive_work
        )
    }
}

/// The time history of one head-on impact, integrated in time (eq. 15), one point per step.
#[pyclass(module = "mdr_dem", frozen)]
pub struct ImpactTrace {
    /// Time since first contact (s).
    #[pyo3(get)]
    t: Py<PyAny>,
    /// Overlap d (m).
    #[pyo3(get)]
    overlap: Py<PyAny>,
    /// Approach velocity (m/s), positive towards the target.
    #[pyo3(get)]
    velocity: Py<PyAny>,
    /// Normal force (N).
    #[pyo3(get)]
    force: Py<PyAny>,
    /// Contact radius (m).
    #[pyo3(get)]
    contact_radius: Py<PyAny>,
    /// Plastic work dissipated so far (J).
    #[pyo3(get)]
    plastic_work: Py<PyAny>,
    /// Coefficient of restitution e_n of the time integration (eq. 14).
    #[pyo3(get)]
    restitution: f64,
    /// Largest overlap (m).
    #[pyo3(get)]
    max_overlap: f64,
    /// Residual (plastic) overlap after separation (m).
    #[pyo3(get)]
    residual_overlap: f64,
    /// Contact time (s).
    #[pyo3(get)]
    contact_time: f64,
    /// Peak force (N).
    #[pyo3(get)]
    peak_force: f64,
    /// Whether the sphere stuck (adhesion; restitution 0).
    #[pyo3(get)]
    stuck: bool,
    /// Largest tensile force (N, ≥ 0; 0 without adhesion).
    #[pyo3(get)]
    pull_off_force: f64,
    /// Overlap at which the contact let go (m); NaN when stuck.
    #[pyo3(get)]
    release_overlap: f64,
}

#[pymethods]
impl ImpactTrace {
    fn __repr__(&self) -> String {
        format!(
            "ImpactTrace(restitution={:.6}, max_overlap={:e}, residual_overlap={:e}, \
             contact_time={:e}, peak_force={:.4}, stuck={})",
            self.restitution,
            self.max_overlap,
            self.residual_overlap,
            self.contact_time,
            self.peak_force,
            if self.stuck { "True" } else { "False" }
        )
    }
}

/// The MDR elasto-plastic law (Lyashenko & Popov 2018) bound to one pair.
#[pyclass(module = "mdr_dem", frozen, from_py_object)]
#[derive(Debug, Clone, Copy)]
pub struct MdrLaw {
    pub setup: Setup,
}

impl MdrLaw {
    fn advance(&self, state: Option<&Bound<'_, MdrState>>, overlap: f64) -> PyResult<f64> {
        if !overlap.is_finite() {
            return Err(invalid(
                "overlap",
                format!("{overlap} (must be finite, in m)"),
            ));
        }
        Ok(match state {
            Some(state) => {
                let mut history = state.borrow().history();
                let force = self.setup.adhesive.update(&mut history, overlap).force;
                state.borrow_mut().store(&history);
                force
            }
            None => {
                self.setup
                    .adhesive
                    .evaluate(&State::default(), overlap)
                    .force
            }
        })
    }
}

#[pymethods]
impl MdrLaw {
    #[new]
    #[pyo3(signature = (*, radius = 0.00635, density = 7800.0, youngs = 2.0e11, poisson = 0.286,
        target_radius = None, target_density = None, target_youngs = None, target_poisson = None,
        qc = 3.8e5, theta_ratio = 0.37, work_of_adhesion = 0.0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        radius: f64,
        density: f64,
        youngs: f64,
        poisson: f64,
        target_radius: Option<f64>,
        target_density: Option<f64>,
        target_youngs: Option<f64>,
        target_poisson: Option<f64>,
        qc: f64,
        theta_ratio: f64,
        work_of_adhesion: f64,
    ) -> PyResult<Self> {
        let params = Params {
            radius: Some(radius),
            density: Some(density),
            youngs: Some(youngs),
            poisson: Some(poisson),
            target_radius,
            target_density,
            target_youngs,
            target_poisson,
            qc: Some(qc),
            theta_ratio: Some(theta_ratio),
            work_of_adhesion: Some(work_of_adhesion),
        };
        Ok(Self {
            setup: params.resolve()?,
        })
    }

    /// The keyword arguments this law was built with (defaults filled in; None for an omitted
    /// target argument).
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let p = &self.setup.params;
        let dict = PyDict::new(py);
        let values = [
            p.radius,
            p.density,
            p.youngs,
            p.poisson,
            p.target_radius,
            p.target_density,
            p.target_youngs,
            p.target_poisson,
            p.qc,
            p.theta_ratio,
            p.work_of_adhesion,
        ];
        for (name, value) in PARAM_NAMES.iter().zip(values) {
            dict.set_item(name, value)?;
        }
        Ok(dict)
    }

    /// Critical line load q_c (N/m), eq. (7).
    #[getter]
    fn qc(&self) -> f64 {
        self.setup.model.critical_line_load()
    }

    /// Hardening ratio Θ/E*, eq. (12).
    #[getter]
    fn theta_ratio(&self) -> f64 {
        self.setup.law.hardening_ratio()
    }

    /// Work of adhesion Δγ (J/m²).
    #[getter]
    fn work_of_adhesion(&self) -> f64 {
        self.setup.work_of_adhesion()
    }

    /// Elastic (JKR) pull-off force (3/2) π Δγ R (N); 0 without adhesion.
    #[getter]
    fn pull_off_force(&self) -> f64 {
        self.setup.adhesive.pull_off_force()
    }

    /// Overlap (m) below which a contact with history `state` has let go: with adhesion, the
    /// smallest (typically negative) overlap it holds to while unloading; otherwise the
    /// residual overlap.
    fn detachment_overlap(&self, state: &Bound<'_, MdrState>) -> f64 {
        self.setup
            .adhesive
            .detachment_overlap(&state.borrow().history())
    }

    /// Effective modulus E* (Pa), eq. (3).
    #[getter]
    fn effective_modulus(&self) -> f64 {
        self.setup.pair.effective_modulus()
    }

    /// Effective radius R (m).
    #[getter]
    fn effective_radius(&self) -> f64 {
        self.setup.pair.effective_radius()
    }

    /// Reduced mass m (kg).
    #[getter]
    fn reduced_mass(&self) -> f64 {
        self.setup.pair.reduced_mass()
    }

    /// Overlap at which the first loading leaves the Hertz branch, u_c = π q_c / (2 E*) (m),
    /// eq. (11).
    #[getter]
    fn yield_overlap(&self) -> f64 {
        self.setup.law.yield_overlap()
    }

    /// Impact speed below which a first impact is elastic (m/s).
    #[getter]
    fn yield_speed(&self) -> f64 {
        self.setup.law.yield_speed(self.setup.pair.reduced_mass())
    }

    /// Whether the target is a half-space (no target_radius/target_density).
    #[getter]
    fn half_space(&self) -> bool {
        self.setup.half_space()
    }

    /// Normal force (N) at `overlap` (m). With `state` (an MdrState), the contact's history is
    /// advanced in place; without, the force of a fresh contact is returned.
    #[pyo3(signature = (overlap, state = None))]
    fn force(&self, overlap: f64, state: Option<&Bound<'_, MdrState>>) -> PyResult<f64> {
        self.advance(state, overlap)
    }

    /// Forces (N) along a loading path: `overlaps` (m, any array-like) are visited in order by
    /// one contact history (starting from `state`, or a fresh one, which is then advanced).
    /// Returns an array of the same shape.
    #[pyo3(signature = (overlaps, state = None))]
    fn force_curve(
        &self,
        py: Python<'_>,
        overlaps: &Bound<'_, PyAny>,
        state: Option<&Bound<'_, MdrState>>,
    ) -> PyResult<Py<PyAny>> {
        let values = Values::read(py, "overlaps", overlaps)?;
        if let Some(bad) = values.data.iter().find(|v| !v.is_finite()) {
            return Err(invalid("overlaps", format!("{bad} (must be finite, in m)")));
        }
        let mut history = state.map_or(State::default(), |s| s.borrow().history());
        let law = self.setup.adhesive;
        let forces = values
            .data
            .iter()
            .map(|&d| law.update(&mut history, d).force)
            .collect();
        if let Some(state) = state {
            state.borrow_mut().store(&history);
        }
        values.shaped(py, forces)
    }

    /// Residual (plastic) overlap of a contact with history `state` (m): where the force vanishes
    /// on unloading.
    fn residual_overlap(&self, state: &Bound<'_, MdrState>) -> f64 {
        self.setup
            .adhesive
            .residual_overlap(&state.borrow().history())
    }

    /// Coefficient of restitution e_n of a first impact at `v0` (m/s, > 0; a float or any
    /// array-like), unscaled: as `mdr-dem impact curve` column `e_n`. Without adhesion the
    /// closed form (the energy route e_n² = W_unload / W_load, eq. 14 with docs/theory.md);
    /// with it, time integration of the closed-form law, 0 where the sphere sticks.
    fn restitution(&self, py: Python<'_>, v0: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let values = Values::read_positive(py, "v0", v0)?;
        let setup = self.setup;
        if setup.work_of_adhesion() > 0.0 {
            let e = py
                .detach(|| {
                    values
                        .data
                        .iter()
                        .map(|&v| setup.impact(v).run().map(|o| o.normal_restitution))
                        .collect::<mdr_impact::Result<Vec<f64>>>()
                })
                .map_err(errors::impact("v0"))?;
            return values.shaped(py, e);
        }
        let law = setup.law;
        let mass = setup.pair.reduced_mass();
        let e = py
            .detach(|| {
                values
                    .data
                    .iter()
                    .map(|&v| {
                        law.impact(&PlainState::default(), mass, v)
                            .map(|o| o.restitution)
                    })
                    .collect::<mdr_contact::Result<Vec<f64>>>()
            })
            .map_err(|e| invalid("v0", e))?;
        values.shaped(py, e)
    }

    /// Integrate one head-on impact at `v0` (m/s) in time (eq. 15) and return its history.
    /// `method`: "closed" (the closed-form law) or "springs" (the discrete spring bed with
    /// `springs` springs); `steps`: time steps per Hertz contact time.
    #[pyo3(signature = (v0, *, method = "closed", springs = None, steps = DEFAULT_STEPS_PER_CONTACT))]
    fn impact(
        &self,
        py: Python<'_>,
        v0: f64,
        method: &str,
        springs: Option<usize>,
        steps: usize,
    ) -> PyResult<ImpactTrace> {
        if !(v0.is_finite() && v0 > 0.0) {
            return Err(invalid(
                "v0",
                format!("{v0} (must be finite and > 0, in m/s)"),
            ));
        }
        let method = parse_method(method, springs)?.unwrap_or(Method::Closed);
        check_steps(steps)?;
        let impact = self
            .setup
            .impact(v0)
            .method(method)
            .steps_per_contact(steps);
        let (outcome, points) = py.detach(|| impact.trace()).map_err(errors::impact("v0"))?;
        let column =
            |f: fn(&mdr_impact::TracePoint) -> f64| array1(py, points.iter().map(f).collect());
        Ok(ImpactTrace {
            t: column(|p| p.time),
            overlap: column(|p| p.overlap),
            velocity: column(|p| p.velocity),
            force: column(|p| p.force),
            contact_radius: column(|p| p.contact_radius),
            plastic_work: column(|p| p.plastic_work),
            restitution: outcome.normal_restitution,
            max_overlap: outcome.max_overlap,
            residual_overlap: outcome.residual_overlap,
            contact_time: outcome.contact_time,
            peak_force: outcome.peak_force,
            stuck: outcome.stuck,
            pull_off_force: outcome.pull_off_force,
            release_overlap: outcome.release_overlap,
        })
    }

    fn __repr__(&self) -> String {
        let p = &self.setup.params;
        let mut text = format!(
            "MdrLaw(radius={}, density={}, youngs={:e}, poisson={}",
            p.radius.unwrap_or_default(),
            p.density.unwrap_or_default(),
            p.youngs.unwrap_or_default(),
            p.poisson.unwrap_or_default()
        );
        for (name, value) in [
            ("target_radius", p.target_radius),
            ("target_density", p.target_density),
            ("target_youngs", p.target_youngs),
            ("target_poisson", p.target_poisson),
        ] {
            if let Some(v) = value {
                text.push_str(&format!(", {name}={v}"));
            }
        }
        text.push_str(&format!(
            ", qc={:e}, theta_ratio={}",
            self.qc(),
            self.theta_ratio()
        ));
        if self.setup.work_of_adhesion() > 0.0 {
            text.push_str(&format!(
                ", work_of_adhesion={}",
                self.setup.work_of_adhesion()
            ));
        }
        text.push(')');
        text
    }
}

/// `method` ("closed" or "springs") and `springs` as the CLI's `--method`/`--springs`.
pub fn parse_method(method: &str, springs: Option<usize>) -> PyResult<Option<Method>> {
    if let Some(n) = springs {
        if !(2..=mdr_contact::normal::SpringBed::MAX_SPRINGS).contains(&n) {
            return Err(invalid("springs", format!("{n} (2 to 1e8 springs)")));
        }
    }
    match method {
        "closed" if springs.is_some() => {
            Err(invalid("springs", "it applies to method=\"springs\" only"))
        }
        "closed" => Ok(Some(Method::Closed)),
        "springs" => Ok(Some(Method::Springs {
            springs: springs.unwrap_or(DEFAULT_SPRINGS),
        })),
        other => Err(invalid(
            "method",
            format!("`{other}` (allowed: \"closed\", \"springs\")"),
        )),
    }
}

/// At least 10 time steps per contact, as the CLI's `--steps`.
pub fn check_steps(steps: usize) -> PyResult<()> {
    if steps < 10 {
        return Err(invalid(
            "steps",
            format!("{steps} (at least 10 steps per contact)"),
        ));
    }
    Ok(())
}
