//! Which normal law an impact uses, and how it is evaluated. The laws themselves live in
//! `mdr-contact`; this module only names them.

use crate::declared::DeclaredNormal;
use mdr_contact::normal::{MdrElastoPlastic, Thornton};
use mdr_contact::ContactPair;

/// The normal contact law of an impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalSpec {
    /// The MDR elasto-plastic law of Lyashenko & Popov (eqs. 7–13).
    Mdr(MdrElastoPlastic),
    /// Thornton's (1997) elastic–perfectly-plastic law, for comparison.
    Thornton(Thornton),
    /// Hertz (eq. 5), purely elastic.
    Hertz,
    /// Any other declared law, by its declaration and parameter values
    /// ([`crate::DeclaredLaw`]): closed form, time integration.
    Declared(DeclaredNormal),
}

impl NormalSpec {
    /// The paper's MDR law (Fig. 2): `q_c = 3.8·10⁵ N/m`, `Θ = 0.37 E*`.
    pub fn paper() -> Self {
        Self::Mdr(MdrElastoPlastic::paper())
    }

    /// Short name used in tables, plots and on the command line: `mdr`, `thornton`, `hertz`,
    /// or a declared law's name.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Mdr(_) => "mdr",
            Self::Thornton(_) => "thornton",
            Self::Hertz => "hertz",
            Self::Declared(law) => law.name(),
        }
    }
}

/// Thornton's yield pressure `p_y` matched to an MDR law on `pair`, the default of Thornton's law
/// wherever it is compared with the MDR law: both yield at the same overlap. Thornton's yield
/// overlap `δ_y = R (π p_y / (2E*))²` equals the MDR law's `u_c = π q_c / (2E*)` (docs/validation.md)
/// for `p_y = (2E*/π) √(u_c / R)`; `yield_overlap` is that `u_c` (`MdrLaw::yield_overlap`).
pub fn thornton_matched_yield_stress(pair: &ContactPair, yield_overlap: f64) -> f64 {
    2.0 * pair.effective_modulus() / std::f64::consts::PI
        * (yield_overlap / pair.effective_radius()).sqrt()
}

/// The validator's value of a law parameter the command line, Python and a `--config` file
/// may omit: the declared default where the law declares one, else the paper's value for the
/// MDR law (Fig. 2: `q_c = 3.8·10⁵ N/m`, `Θ = 0.37 E*`); `None`: the parameter is required.
pub fn validator_default(param: &mdr_contact::params::Param) -> Option<f64> {
    param.default.or(match param.key {
        "critical_line_load_n_per_m" => Some(PAPER_CRITICAL_LINE_LOAD),
        "hardening_ratio" => Some(PAPER_HARDENING_RATIO),
        _ => None,
    })
}

/// The paper's critical line load `q_c` (N/m), Fig. 2.
pub const PAPER_CRITICAL_LINE_LOAD: f64 = 3.8e5;

/// The paper's hardening ratio `Θ/E*`, Fig. 2.
pub const PAPER_HARDENING_RATIO: f64 = 0.37;

/// How the normal law is represented.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// The closed-form law (for `mdr`: the continuum closed form of docs/theory.md §4).
    #[default]
    Closed,
    /// The discrete MDR spring bed (eq. 6 with eqs. 10–13) with this many springs, integrated in
    /// time. Only for the `mdr` law.
    Springs {
        /// Number of springs across the bed.
        springs: usize,
    },
}

/// Default number of springs of the discrete bed ([`Method::Springs`]).
pub const DEFAULT_SPRINGS: usize = 2000;

/// Half-width of the spring bed relative to the largest contact radius of the impact (estimated
/// with the closed form): the margin keeps the contact off the bed's edge.
pub const BED_HALF_WIDTH_MARGIN: f64 = 1.25;

/// How the restitution of a normal impact is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Route {
    /// The energy route where it applies (closed-form MDR, head-on, no spin), time integration
    /// otherwise.
    #[default]
    Auto,
    /// Always integrate the equation of motion (eq. 15) in time.
    TimeIntegration,
    /// The time-free energy route `e_n² = W_unload / W_load` (docs/theory.md §4); closed-form MDR,
    /// head-on impacts only.
    Energy,
}

/// The tangential law of an oblique impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TangentialSpec {
    /// The MDR spring-bed tangential law with per-spring stick/slip (docs/theory.md §5); needs the
    /// spring bed as normal law ([`Method::Springs`]).
    SpringBed,
    /// The O(1) incremental Mindlin law with a Coulomb cap (docs/theory.md §5, `k_t = 2 G* a`); works
    /// with every normal law.
    #[default]
    Mindlin,
}

impl TangentialSpec {
    /// Short name: `springs` or `mindlin`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SpringBed => "springs",
            Self::Mindlin => "mindlin",
        }
    }
}
