//! Errors of the plugin; the C ABI turns them into the message of a LAMMPS `error->all`.

use mdr_contact::ContactError;

/// Why a `pair_coeff` line, a type pair or a force computation was refused.
#[derive(Debug, thiserror::Error)]
pub enum PluginError {
    /// A keyword `pair_style mdrdem` does not know, and the known ones (space-separated).
    #[error("unknown keyword `{0}` (known: {1})")]
    UnknownKeyword(String, String),
    /// A keyword without its value.
    #[error("keyword `{0}` needs a value")]
    MissingValue(String),
    /// A required keyword was not given.
    #[error("keyword `{0}` is required")]
    Missing(&'static str),
    /// A keyword given twice on one line.
    #[error("keyword `{0}` is given twice")]
    Duplicate(String),
    /// A value that is not a number.
    #[error("keyword `{keyword}`: `{text}` is not a number")]
    NotANumber {
        /// The keyword.
        keyword: String,
        /// What was given.
        text: String,
    },
    /// A value outside its allowed range.
    #[error("keyword `{keyword}` = {value} is outside the allowed range {range}")]
    OutOfRange {
        /// The keyword.
        keyword: String,
        /// What was given.
        value: f64,
        /// The allowed range.
        range: &'static str,
    },
    /// mdr-contact refused a value (reported with the keyword that carried it).
    #[error("keyword `{keyword}`: {source}")]
    Law {
        /// The keyword.
        keyword: &'static str,
        /// The law's own error.
        source: ContactError,
    },
    /// Types I and J have different law parameters and no explicit `pair_coeff I J`.
    #[error("pair_coeff {i} {j} must be given explicitly: types {i} and {j} differ in keyword `{keyword}` (only materials are mixed)")]
    CannotMix {
        /// First type.
        i: usize,
        /// Second type.
        j: usize,
        /// The first differing keyword.
        keyword: String,
    },
    /// A type pair without coefficients.
    #[error(
        "no pair_coeff for types {i} {j} (give pair_coeff {i} {j}, or both {i} {i} and {j} {j})"
    )]
    NotSet {
        /// First type.
        i: usize,
        /// Second type.
        j: usize,
    },
    /// A type outside 1..=ntypes.
    #[error("atom types {i} {j} are outside 1..ntypes")]
    TypeRange {
        /// First type.
        i: usize,
        /// Second type.
        j: usize,
    },
    /// A contact whose pair quantities mdr-contact refuses (e.g. zero radius or mass).
    #[error("contact between atoms {i} and {j}: {source}")]
    Contact {
        /// Local index of the first atom.
        i: usize,
        /// Local index of the second atom.
        j: usize,
        /// The law's error.
        source: ContactError,
    },
    /// A sphere touching a wall whose type has no material (`pair_coeff T T`).
    #[error("atom type {0} touches the wall but has no pair_coeff {0} {0} line of pair_style mdrdem (the wall mixes its material with that type's)")]
    WallTypeNotSet(usize),
    /// A sphere touching a wall whose surface curves more tightly than the sphere.
    #[error("a sphere of radius {radius} touches a concave wall of radius {wall_radius}: the wall must be wider than the sphere")]
    WallTooCurved {
        /// The sphere's radius.
        radius: f64,
        /// The wall's radius of curvature (negative: concave).
        wall_radius: f64,
    },
    /// A null pointer or inconsistent size passed through the C ABI.
    #[error("invalid argument through the C ABI: {0}")]
    Abi(&'static str),
}

impl PluginError {
    /// Wrap an mdr-contact error with the keyword that carried the value.
    pub fn law(keyword: &'static str, source: ContactError) -> Self {
        Self::Law { keyword, source }
    }
}
