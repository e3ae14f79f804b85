//! Library errors → Python exceptions. A rejected value becomes a `ValueError` whose message
//! starts with the keyword argument it came from (`invalid value for `youngs`: …`), as the CLI's
//! messages name the flag.

use mdr_contact::ContactError;
use mdr_impact::ImpactError;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::PyErr;

/// A `ValueError` naming `argument`.
pub fn invalid(argument: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("invalid value for `{argument}`: {message}"))
}

/// The keyword argument a law-crate parameter name came from; `target` for the target material.
pub fn argument_for(name: &str, target: bool) -> &'static str {
    match (name, target) {
        ("youngs_modulus", false) => "youngs",
        ("youngs_modulus", true) => "target_youngs",
        ("poisson_ratio", false) => "poisson",
        ("poisson_ratio", true) => "target_poisson",
        ("density", false) => "density",
        ("density", true) => "target_density",
        ("radius", _) => "radius",
        ("target_radius", _) => "target_radius",
        ("q_c", _) => "qc",
        ("theta_ratio" | "theta", _) => "theta_ratio",
        ("yield_stress" | "yield_pressure", _) => "yield_stress",
        ("mu", _) => "mu",
        ("work_of_adhesion", _) => "work_of_adhesion",
        ("n_springs" | "half_width" | "spacing", _) => "springs",
        _ => "a material or law argument",
    }
}

/// A law-crate error as a `ValueError` naming the keyword argument.
pub fn contact(target: bool) -> impl Fn(ContactError) -> PyErr {
    move |e| {
        let name = match &e {
            ContactError::NotFinite { name, .. }
            | ContactError::OutOfRange { name, .. }
            | ContactError::TooFew { name, .. }
            | ContactError::InvalidTable { name, .. } => *name,
        };
        invalid(argument_for(name, target), e)
    }
}

/// A validator error: parameter errors as `ValueError` naming the argument (`speed_argument` for
/// the impact speed), file errors as `OSError`, the rest as `RuntimeError`.
pub fn impact(speed_argument: &'static str) -> impl Fn(ImpactError) -> PyErr {
    move |e| match &e {
        ImpactError::Parameter { source, .. } => contact(false)(source.clone()),
        ImpactError::Invalid { key, .. } => {
            let argument = match *key {
                "speed" => speed_argument,
                "route" => "method",
                "theta-ratio" => "theta_ratio",
                "target-youngs" => "target_youngs",
                "target-poisson" => "target_poisson",
                "target-radius" => "target_radius",
                "target-density" => "target_density",
                "work-of-adhesion" => "work_of_adhesion",
                other => other,
            };
            invalid(argument, &e)
        }
        ImpactError::Underdetermined(_) => invalid("v0", &e),
        ImpactError::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => PyRuntimeError::new_err(e.to_string()),
    }
}
