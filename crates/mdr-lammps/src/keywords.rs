//! The keywords of `pair_coeff` (and of `fix wall/mdrdem`, which takes the same), each a
//! parameter declaration of `mdr_contact::params`: the law's own wherever a law declares it,
//! under the LAMMPS name the declaration publishes ([`Param::lammps_name`]: `qc`, `theta` of
//! [`MdrElastoPlastic`], `friction` of [`Mindlin`], `damping` and `tangential_damping` of
//! [`HertzianViscous`], `rolling` of [`EpsdRolling`], `adhesion` of [`AdhesiveMdr`]), and the
//! plugin's own for the material and the `E*`/`G*` overrides. Parsing, the range checks, the
//! defaults, the errors and the keyword table of docs/lammps.md (checked by a test) all come
//! from [`KEYWORDS`].

use crate::error::PluginError;
use mdr_contact::damping::HertzianViscous;
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic};
use mdr_contact::params::{Declared, Param, Range};
use mdr_contact::rolling::EpsdRolling;
use mdr_contact::tangential::Mindlin;

/// One keyword: its parameter declaration (the LAMMPS name is [`Param::lammps_name`]), how its
/// range reads in errors and in the docs, and whether it may be left out without a default.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Keyword {
    /// The parameter: name, symbol, unit, allowed range, default (`None`: required unless
    /// `optional`), one line of meaning.
    pub param: Param,
    /// The allowed range as errors print it (units of the LAMMPS `units` style).
    pub range: &'static str,
    /// A keyword without a default that may be left out (the pair's value is derived instead).
    pub optional: bool,
}

impl Keyword {
    const fn new(param: Param, range: &'static str) -> Self {
        Self {
            param,
            range,
            optional: false,
        }
    }

    const fn optional(self) -> Self {
        Self {
            optional: true,
            ..self
        }
    }

    /// The `pair_coeff` keyword.
    pub fn name(&self) -> &'static str {
        self.param.lammps_name()
    }

    /// Whether `value` is allowed (finite and in the declared range).
    pub fn allows(&self, value: f64) -> bool {
        self.param.range.contains(value)
    }
}

/// Poisson's ratio: `(−1, 0.5]`.
const POISSON: Range = Range {
    min: -1.0,
    min_inclusive: false,
    max: 0.5,
    max_inclusive: true,
    notation: "(-1, 0.5]",
};

/// Every keyword, in the order of docs/lammps.md's table.
pub const KEYWORDS: &[Keyword] = &[
    Keyword::new(
        Param::new(
            "youngs",
            "E",
            "pressure",
            Range::POSITIVE,
            "Young's modulus",
        ),
        "> 0 (pressure), required",
    ),
    Keyword::new(
        Param::new("poisson", "ν", "1", POISSON, "Poisson's ratio"),
        "(-1, 0.5], required",
    ),
    Keyword::new(
        MdrElastoPlastic::DECLARATION.params[0],
        ">= 0 (force/length), required",
    ),
    Keyword::new(
        MdrElastoPlastic::DECLARATION.params[1],
        "[0, 1] (ratio Theta/E*), required",
    ),
    // The plugin's pair is frictionless and undamped unless told otherwise: its default 0.
    Keyword::new(
        Mindlin::DECLARATION.params[0].default(0.0),
        ">= 0, default 0",
    ),
    Keyword::new(
        HertzianViscous::DECLARATION.params[0].default(0.0),
        ">= 0 (1/(time length^1/2)), default 0",
    ),
    Keyword::new(
        HertzianViscous::DECLARATION.params[1],
        ">= 0 (ratio), default 0",
    ),
    Keyword::new(
        EpsdRolling::DECLARATION.params[0],
        ">= 0 (EPSD coefficient), default 0",
    ),
    Keyword::new(
        AdhesiveMdr::DECLARATION.params[2].default(0.0),
        ">= 0 (work of adhesion, energy/area), default 0",
    ),
    Keyword::new(
        Param::new(
            "estar",
            "E*",
            "pressure",
            Range::POSITIVE,
            "E* of the pair given directly, instead of eq. (3)",
        ),
        "> 0 (pressure), optional override of E*",
    )
    .optional(),
    Keyword::new(
        Param::new(
            "gstar",
            "G*",
            "pressure",
            Range::POSITIVE,
            "G* of the pair given directly, instead of docs/theory.md §5",
        ),
        "> 0 (pressure), optional override of G*",
    )
    .optional(),
];

/// The keyword named `name`.
pub fn keyword(name: &str) -> Option<&'static Keyword> {
    KEYWORDS.iter().find(|k| k.name() == name)
}

/// Every keyword's name, space-separated (for the error of an unknown one).
pub fn known() -> String {
    KEYWORDS
        .iter()
        .map(Keyword::name)
        .collect::<Vec<_>>()
        .join(" ")
}

/// The keyword-value words of one line, each keyword known, given once and with a number;
/// values in [`KEYWORDS`] order (`None`: not given).
pub fn parse<S: AsRef<str>>(words: &[S]) -> Result<Vec<Option<f64>>, PluginError> {
    if !words.len().is_multiple_of(2) {
        return Err(PluginError::MissingValue(
            words
                .last()
                .map(|w| w.as_ref().to_string())
                .unwrap_or_default(),
        ));
    }
    let mut values = vec![None; KEYWORDS.len()];
    for pair in words.chunks(2) {
        let name = pair[0].as_ref();
        let slot = KEYWORDS
            .iter()
            .position(|k| k.name() == name)
            .ok_or_else(|| PluginError::UnknownKeyword(name.to_string(), known()))?;
        let known = KEYWORDS[slot].name();
        if values[slot].is_some() {
            return Err(PluginError::Duplicate(known.to_string()));
        }
        let text = pair[1].as_ref();
        let value: f64 = text.parse().map_err(|_| PluginError::NotANumber {
            keyword: known.to_string(),
            text: text.to_string(),
        })?;
        if !value.is_finite() {
            return Err(out_of_range(known, value));
        }
        values[slot] = Some(value);
    }
    Ok(values)
}

/// The value of keyword `name` from [`parse`]'s values: given, else its default; an error when
/// a required keyword is missing. `None` for an optional keyword not given.
pub fn value(values: &[Option<f64>], name: &'static str) -> Result<Option<f64>, PluginError> {
    let slot = KEYWORDS
        .iter()
        .position(|k| k.name() == name)
        .expect("a keyword of KEYWORDS");
    let k = &KEYWORDS[slot];
    match (values[slot], k.param.default) {
        (Some(v), _) => Ok(Some(v)),
        (None, Some(d)) => Ok(Some(d)),
        (None, None) if k.optional => Ok(None),
        (None, None) => Err(PluginError::Missing(k.name())),
    }
}

/// `value` of keyword `name` if its declared range allows it, else the error naming the keyword.
pub fn checked(name: &'static str, value: f64) -> Result<f64, PluginError> {
    match keyword(name) {
        Some(k) if k.allows(value) => Ok(value),
        _ => Err(out_of_range(name, value)),
    }
}

/// The error of a value outside keyword `name`'s range.
pub fn out_of_range(name: &str, value: f64) -> PluginError {
    PluginError::OutOfRange {
        keyword: name.to_string(),
        value,
        range: keyword(name).map_or("", |k| k.range),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The declared ranges are the published ones: each range text's bounds hold in the declared
    /// range and the values just outside do not.
    #[test]
    fn declared_ranges_are_the_published_ones() {
        let cases: [(&str, &[f64], &[f64]); 11] = [
            ("youngs", &[1e-300, 2e11], &[0.0, -1.0]),
            ("poisson", &[-0.999, 0.0, 0.5], &[-1.0, 0.5000001]),
            ("qc", &[0.0, 3.8e5], &[-1e-300]),
            ("theta", &[0.0, 0.37, 1.0], &[-1e-9, 1.0000001]),
            ("friction", &[0.0, 0.5], &[-0.1]),
            ("damping", &[0.0, 50.0], &[-0.1]),
            ("tangential_damping", &[0.0, 0.5], &[-0.1]),
            ("rolling", &[0.0, 0.05], &[-0.1]),
            ("adhesion", &[0.0, 0.1], &[-0.1]),
            ("estar", &[1.5e5], &[0.0]),
            ("gstar", &[2e5], &[0.0]),
        ];
        for (name, inside, outside) in cases {
            let k = keyword(name).unwrap_or_else(|| panic!("{name}"));
            for v in inside {
                assert!(k.allows(*v), "{name} {v}");
            }
            for v in outside.iter().chain(&[f64::NAN, f64::INFINITY]) {
                assert!(!k.allows(*v), "{name} {v}");
            }
        }
        assert_eq!(KEYWORDS.len(), 11);
    }

    /// Every parameter the plugin's laws declare is a keyword under the LAMMPS name of its
    /// declaration, with the declared key and range: the table holds no copy of its own.
    #[test]
    fn law_keywords_are_the_declarations() {
        let laws = [
            MdrElastoPlastic::DECLARATION,
            AdhesiveMdr::DECLARATION,
            Mindlin::DECLARATION,
            HertzianViscous::DECLARATION,
            EpsdRolling::DECLARATION,
        ];
        let mut names = Vec::new();
        for p in laws.iter().flat_map(|l| l.params) {
            let k = keyword(p.lammps_name())
                .unwrap_or_else(|| panic!("`{}` is no keyword", p.lammps_name()));
            assert_eq!(
                (k.param.key, k.param.range),
                (p.key, p.range),
                "{}",
                k.name()
            );
            if !names.contains(&p.lammps_name()) {
                names.push(p.lammps_name());
            }
        }
        assert_eq!(
            names,
            [
                "qc",
                "theta",
                "adhesion",
                "friction",
                "damping",
                "tangential_damping",
                "rolling"
            ]
        );
    }

    /// The error texts are a contract: these are the messages LAMMPS prints after
    /// `pair_coeff mdrdem:`.
    #[test]
    fn error_texts() {
        let words = |line: &str| {
            line.split_whitespace()
                .map(str::to_string)
                .collect::<Vec<_>>()
        };
        let good = "youngs 2e11 poisson 0.3 qc 3.8e5 theta 0.37";
        let message = |line: &str| {
            crate::CoeffLine::parse(&words(line))
                .expect_err(line)
                .to_string()
        };
        assert_eq!(
            message(&format!("{good} colour 3")),
            "unknown keyword `colour` (known: youngs poisson qc theta friction damping \
             tangential_damping rolling adhesion estar gstar)"
        );
        assert_eq!(
            message("youngs 2e11 poisson 0.3 qc 3.8e5 theta 1.5"),
            "keyword `theta` = 1.5 is outside the allowed range [0, 1] (ratio Theta/E*), required"
        );
        assert_eq!(
            message(&format!("{good} adhesion -0.1")),
            "keyword `adhesion` = -0.1 is outside the allowed range >= 0 (work of adhesion, \
             energy/area), default 0"
        );
        assert_eq!(
            message("poisson 0.3 qc 3.8e5 theta 0.37"),
            "keyword `youngs` is required"
        );
        assert_eq!(
            message(&format!("{good} theta")),
            "keyword `theta` needs a value"
        );
        assert_eq!(
            message(&format!("{good} qc 1")),
            "keyword `qc` is given twice"
        );
        assert_eq!(
            message(&format!("{good} damping abc")),
            "keyword `damping`: `abc` is not a number"
        );
    }

    /// docs/lammps.md's keyword table lists exactly these keywords in this order, each with its
    /// default (`required` where there is none) and its meaning.
    #[test]
    fn the_docs_table_is_the_keyword_list() {
        let docs = include_str!("../../../docs/lammps.md");
        let start = docs
            .find("| keyword | meaning | range | default |")
            .unwrap();
        let rows: Vec<&str> = docs[start..]
            .lines()
            .skip(2)
            .take_while(|l| l.starts_with('|'))
            .collect();
        let names: Vec<&str> = rows
            .iter()
            .map(|r| r.split('`').nth(1).unwrap_or(""))
            .collect();
        let expected: Vec<&str> = KEYWORDS.iter().map(Keyword::name).collect();
        assert_eq!(names, expected);
        for (row, k) in rows.iter().zip(KEYWORDS) {
            let default = row.trim_end_matches('|').rsplit('|').next().unwrap().trim();
            match k.param.default {
                Some(d) => assert!(default.starts_with(&format!("{d}")), "{row}"),
                None if k.optional => assert!(default.starts_with("from"), "{row}"),
                None => assert_eq!(default, "required", "{row}"),
            }
        }
    }
}
