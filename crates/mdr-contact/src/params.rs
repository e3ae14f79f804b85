//! What a law declares about itself, once: its name, a one-line summary, and each parameter's
//! name, symbol, unit, allowed range, default and equation. The layers above derive their
//! inputs from a declaration instead of restating it: the scene file's keys (`[contact]`),
//! command-line flags, Python keywords and LAMMPS `pair_coeff` keywords, their help texts and
//! the range errors a wrong value gets.
//!
//! A law becomes usable by name by implementing [`Declared`] next to its model (its
//! [`LawDeclaration`] and how the model is made from the declared values) and by one line in
//! the registry of the layer that runs it (`mdr_sim::laws::registry`).
//!
//! ```
//! use mdr_contact::params::Declared;
//! use mdr_contact::normal::MdrElastoPlastic;
//! let d = MdrElastoPlastic::DECLARATION;
//! assert_eq!(d.name, "mdr");
//! assert_eq!(d.params[0].key, "critical_line_load_n_per_m");
//! assert_eq!(d.params[0].flag_name(), "qc");
//! // A value outside the declared range is refused with the parameter's key and its range.
//! let err = MdrElastoPlastic::from_values(&[380e3, 1.5]).unwrap_err();
//! assert!(err.to_string().contains("`hardening_ratio` = 1.5"));
//! ```

use crate::error::{ContactError, Result};

/// The allowed values of a parameter: an interval of the real line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower bound (`-inf` for none).
    pub min: f64,
    /// Whether the lower bound is allowed.
    pub min_inclusive: bool,
    /// Upper bound (`inf` for none).
    pub max: f64,
    /// Whether the upper bound is allowed.
    pub max_inclusive: bool,
    /// The interval in mathematical notation, as errors and help texts print it.
    pub notation: &'static str,
}

impl Range {
    /// `(0, inf)`: finite and strictly positive.
    pub const POSITIVE: Range = Range {
        min: 0.0,
        min_inclusive: false,
        max: f64::INFINITY,
        max_inclusive: false,
        notation: "(0, inf)",
    };
    /// `[0, inf)`: finite and not negative.
    pub const NON_NEGATIVE: Range = Range {
        min: 0.0,
        min_inclusive: true,
        max: f64::INFINITY,
        max_inclusive: false,
        notation: "[0, inf)",
    };
    /// `[0, 1]`.
    pub const UNIT_INTERVAL: Range = Range {
        min: 0.0,
        min_inclusive: true,
        max: 1.0,
        max_inclusive: true,
        notation: "[0, 1]",
    };

    /// Whether `value` is finite and in the interval.
    pub fn contains(&self, value: f64) -> bool {
        let above = if self.min_inclusive {
            value >= self.min
        } else {
            value > self.min
        };
        let below = if self.max_inclusive {
            value <= self.max
        } else {
            value < self.max
        };
        value.is_finite() && above && below
    }
}

/// One parameter of a law, declared once.
///
/// `key` is the parameter's name in a scene file's `[contact]` table and, unless given
/// otherwise, in Python (`key`), on the command line (`--key-with-hyphens`) and in LAMMPS
/// `pair_coeff` (`key`). `flag`, `python` and `lammps` override those derived names where a
/// published name differs (e.g. `--qc`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Param {
    /// Scene-file key, with its unit in its name (`critical_line_load_n_per_m`).
    pub key: &'static str,
    /// The symbol of the equations (`q_c`).
    pub symbol: &'static str,
    /// Unit (`N/m`; `1` for a dimensionless one).
    pub unit: &'static str,
    /// Allowed values.
    pub range: Range,
    /// The value when not given; `None`: required.
    pub default: Option<f64>,
    /// One line for help texts: what it is and the equation it enters.
    pub doc: &'static str,
    /// Command-line flag without the leading `--`, when not `key` with hyphens.
    pub flag_override: Option<&'static str>,
    /// Python keyword, when not `key`.
    pub python_override: Option<&'static str>,
    /// LAMMPS `pair_coeff` keyword, when not `key`.
    pub lammps_override: Option<&'static str>,
}

impl Param {
    /// A required parameter whose every name derives from `key`.
    pub const fn new(
        key: &'static str,
        symbol: &'static str,
        unit: &'static str,
        range: Range,
        doc: &'static str,
    ) -> Self {
        Self {
            key,
            symbol,
            unit,
            range,
            default: None,
            doc,
            flag_override: None,
            python_override: None,
            lammps_override: None,
        }
    }

    /// The same parameter with a default value (no longer required).
    pub const fn default(self, value: f64) -> Self {
        Self {
            default: Some(value),
            ..self
        }
    }

    /// The same parameter with its published command-line flag (without `--`).
    pub const fn flag(self, flag: &'static str) -> Self {
        Self {
            flag_override: Some(flag),
            ..self
        }
    }

    /// The same parameter with its published Python keyword.
    pub const fn python(self, keyword: &'static str) -> Self {
        Self {
            python_override: Some(keyword),
            ..self
        }
    }

    /// The same parameter with its LAMMPS `pair_coeff` keyword.
    pub const fn lammps(self, keyword: &'static str) -> Self {
        Self {
            lammps_override: Some(keyword),
            ..self
        }
    }

    /// The command-line flag, without the leading `--`.
    pub fn flag_name(&self) -> String {
        self.flag_override
            .map_or_else(|| self.key.replace('_', "-"), str::to_owned)
    }

    /// The Python keyword.
    pub fn python_name(&self) -> &'static str {
        self.python_override.unwrap_or(self.key)
    }

    /// The LAMMPS `pair_coeff` keyword.
    pub fn lammps_name(&self) -> &'static str {
        self.lammps_override.unwrap_or(self.key)
    }

    /// `value` if it lies in the declared range, else the error naming the key and the range.
    pub fn check(&self, value: f64) -> Result<f64> {
        if !value.is_finite() {
            return Err(ContactError::NotFinite {
                name: self.key,
                value,
            });
        }
        if self.range.contains(value) {
            Ok(value)
        } else {
            Err(ContactError::OutOfRange {
                name: self.key,
                value,
                range: self.range.notation,
            })
        }
    }

    /// One help line: `symbol (unit, range[, default d]): doc`.
    pub fn help(&self) -> String {
        let default = self
            .default
            .map_or(String::new(), |d| format!(", default {d}"));
        format!(
            "{} ({}, in {}{default}): {}",
            self.symbol, self.unit, self.range.notation, self.doc
        )
    }
}

/// Written as its derived names too (`flag`, `python`, `lammps`), and its range as its notation:
/// what a command-line listing or a Python caller shows of it.
#[cfg(feature = "serde")]
impl serde::Serialize for Param {
    fn serialize<S: serde::Serializer>(
        &self,
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut s = serializer.serialize_struct("Param", 9)?;
        s.serialize_field("key", self.key)?;
        s.serialize_field("symbol", self.symbol)?;
        s.serialize_field("unit", self.unit)?;
        s.serialize_field("range", self.range.notation)?;
        s.serialize_field("default", &self.default)?;
        s.serialize_field("doc", self.doc)?;
        s.serialize_field("flag", &format!("--{}", self.flag_name()))?;
        s.serialize_field("python", self.python_name())?;
        s.serialize_field("lammps", self.lammps_name())?;
        s.end()
    }
}

/// What kind of sub-model a law is: where it slots into a contact model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum LawKind {
    /// A normal law ([`crate::normal::NormalModel`]).
    Normal,
    /// A tangential law ([`crate::tangential::TangentialModel`]).
    Tangential,
    /// A damping law ([`crate::damping::DampingModel`]).
    Damping,
    /// A rolling-resistance law ([`crate::rolling::RollingModel`]).
    Rolling,
}

/// A law's declaration: its name (the value of `normal = "…"` in a scene, of `--law`, of
/// Python's `law=`), a summary, and its parameters in the order [`Declared::from_values`] takes
/// them.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct LawDeclaration {
    /// Name, lower case with underscores.
    pub name: &'static str,
    /// Kind.
    pub kind: LawKind,
    /// One line: what the law is and where it comes from.
    pub summary: &'static str,
    /// Parameters.
    #[cfg_attr(feature = "serde", serde(rename = "parameters"))]
    pub params: &'static [Param],
}

impl LawDeclaration {
    /// The parameter with scene key `key`.
    pub fn param(&self, key: &str) -> Option<&'static Param> {
        self.params.iter().find(|p| p.key == key)
    }

    /// The values of the parameters, in declared order, from a lookup by key: a missing one
    /// takes its default; each is checked against its range. Every missing or out-of-range
    /// parameter is reported, in declared order.
    pub fn values(
        &self,
        mut get: impl FnMut(&Param) -> Option<f64>,
    ) -> std::result::Result<Vec<f64>, Vec<ParamProblem>> {
        let mut values = Vec::with_capacity(self.params.len());
        let mut problems = Vec::new();
        for p in self.params {
            match get(p).or(p.default).map(|v| p.check(v)) {
                Some(Ok(v)) => values.push(v),
                Some(Err(e)) => problems.push(ParamProblem::Invalid(p, e)),
                None => problems.push(ParamProblem::Missing(p)),
            }
        }
        if problems.is_empty() {
            Ok(values)
        } else {
            Err(problems)
        }
    }
}

/// Why a declared parameter has no usable value.
#[derive(Debug, Clone, PartialEq)]
pub enum ParamProblem {
    /// Required (no default) and not given.
    Missing(&'static Param),
    /// Given, and refused by its range check.
    Invalid(&'static Param, ContactError),
}

impl std::fmt::Display for ParamProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ParamProblem::Missing(p) => write!(f, "`{}` is required: {}", p.key, p.help()),
            ParamProblem::Invalid(p, e) => write!(f, "{e} ({})", p.help()),
        }
    }
}

/// A law that declares its parameters ([`LawDeclaration`]) and is made from their values.
pub trait Declared: Sized {
    /// The declaration.
    const DECLARATION: LawDeclaration;

    /// The model from the declared parameters' values, in declared order. Each value is
    /// checked against its declared range first; the model's constructor may check more.
    fn from_values(values: &[f64]) -> Result<Self>;
}

/// Check `values` against the declaration of `L` (count and ranges).
pub fn check_values<L: Declared>(values: &[f64]) -> Result<()> {
    let params = L::DECLARATION.params;
    if values.len() != params.len() {
        return Err(ContactError::InvalidTable {
            name: L::DECLARATION.name,
            reason: format!(
                "{} parameter values given, the law declares {}",
                values.len(),
                params.len()
            ),
        });
    }
    for (p, &v) in params.iter().zip(values) {
        p.check(v)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_hold_their_bounds_as_declared() {
        assert!(!Range::POSITIVE.contains(0.0));
        assert!(Range::POSITIVE.contains(1e-300));
        assert!(Range::NON_NEGATIVE.contains(0.0));
        assert!(!Range::NON_NEGATIVE.contains(-1e-300));
        assert!(Range::UNIT_INTERVAL.contains(1.0));
        assert!(!Range::UNIT_INTERVAL.contains(1.0 + 1e-15));
        assert!(!Range::NON_NEGATIVE.contains(f64::INFINITY));
        assert!(!Range::UNIT_INTERVAL.contains(f64::NAN));
    }

    #[test]
    fn names_derive_from_the_key_unless_published_otherwise() {
        let p = Param::new(
            "work_of_adhesion_j_per_m2",
            "Δγ",
            "J/m²",
            Range::NON_NEGATIVE,
            "",
        );
        assert_eq!(p.flag_name(), "work-of-adhesion-j-per-m2");
        assert_eq!(p.python_name(), "work_of_adhesion_j_per_m2");
        assert_eq!(p.lammps_name(), "work_of_adhesion_j_per_m2");
        let q = p.flag("work-of-adhesion").python("gamma").lammps("dgamma");
        assert_eq!(q.flag_name(), "work-of-adhesion");
        assert_eq!(q.python_name(), "gamma");
        assert_eq!(q.lammps_name(), "dgamma");
    }

    #[test]
    fn values_take_defaults_and_name_the_missing_or_wrong_key() {
        static PARAMS: &[Param] = &[
            Param::new("a_m", "a", "m", Range::POSITIVE, ""),
            Param::new("b", "b", "1", Range::UNIT_INTERVAL, "").default(0.5),
        ];
        let d = LawDeclaration {
            name: "test",
            kind: LawKind::Normal,
            summary: "",
            params: PARAMS,
        };
        assert_eq!(
            d.values(|p| (p.key == "a_m").then_some(2.0)).unwrap(),
            [2.0, 0.5]
        );
        let missing = d.values(|_| None).unwrap_err();
        assert_eq!(missing, [ParamProblem::Missing(&PARAMS[0])]);
        let wrong = d.values(|p| Some(if p.key == "b" { 2.0 } else { -1.0 }));
        let expected = |p: &'static Param, value, range| {
            ParamProblem::Invalid(
                p,
                ContactError::OutOfRange {
                    name: p.key,
                    value,
                    range,
                },
            )
        };
        assert_eq!(
            wrong.unwrap_err(),
            [
                expected(&PARAMS[0], -1.0, "(0, inf)"),
                expected(&PARAMS[1], 2.0, "[0, 1]")
            ]
        );
    }
}
