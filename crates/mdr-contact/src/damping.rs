//! Viscous damping sub-models (optional; off by default): a normal dashpot and, optionally, a
//! tangential one in proportion to it (LAMMPS `gammat`, GRANULAR `damp_tangential`). Kept
//! separate from the normal and tangential laws so that plastic, frictional and viscous
//! dissipation are booked separately.

#[cfg(feature = "demo-laws")]
mod linear_dashpot;
#[cfg(feature = "demo-laws")]
pub use linear_dashpot::LinearDashpot;

use crate::error::{non_negative, Result};
use crate::material::ContactPair;
use crate::normal::NormalResponse;
use crate::params::{Declared, LawDeclaration, LawKind, Param, Range};

/// A damping law bound to one pair.
pub trait DampingLaw: Send + Sync {
    /// Normal dashpot coefficient `η_n` (N·s/m, ≥ 0) at overlap `overlap` (m): the damping force
    /// along the normal is `η_n dδ/dt`.
    fn normal_coefficient(&self, response: &NormalResponse, overlap: f64) -> f64;

    /// Tangential over normal dashpot coefficient, `η_t/η_n` (≥ 0; LAMMPS `gammat/gamman`).
    /// While the tangential spring sticks the contact adds the force `−η_t v_t` (`v_t` the
    /// tangential relative velocity); on gross slip the force is the Coulomb-capped spring force
    /// alone (the LIGGGHTS `tangential_history` rule; LAMMPS `gran/hertz/history` caps spring
    /// plus dashpot together, which differs only while sliding). No default: a wrapper must
    /// forward it.
    fn tangential_ratio(&self) -> f64;

    /// Damping force along the normal (N, positive = repulsive) at overlap `overlap` (m) and
    /// approach rate `approach_rate = dδ/dt` (m/s, positive while the bodies approach).
    #[inline(always)]
    fn normal_force(&self, response: &NormalResponse, overlap: f64, approach_rate: f64) -> f64 {
        self.normal_coefficient(response, overlap) * approach_rate
    }

    /// Tangential dashpot coefficient `η_t = (η_t/η_n) η_n` (N·s/m) at overlap `overlap`.
    #[inline(always)]
    fn tangential_coefficient(&self, response: &NormalResponse, overlap: f64) -> f64 {
        self.tangential_ratio() * self.normal_coefficient(response, overlap)
    }
}

/// Material-level damping parameters.
pub trait DampingModel: Clone + Send + Sync {
    /// The law for one pair.
    type Law: DampingLaw;
    /// Bind to a pair.
    fn bind(&self, pair: &ContactPair) -> Result<Self::Law>;
}

/// No damping.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NoDamping;

impl DampingModel for NoDamping {
    type Law = NoDamping;
    fn bind(&self, _pair: &ContactPair) -> Result<NoDamping> {
        Ok(NoDamping)
    }
}

impl DampingLaw for NoDamping {
    #[inline]
    fn normal_coefficient(&self, _: &NormalResponse, _: f64) -> f64 {
        0.0
    }

    #[inline]
    fn tangential_ratio(&self) -> f64 {
        0.0
    }
}

/// LAMMPS `gran/hertz/history` damping: `F_d = m γ_n (dδ/dt) √(R δ)`, with `γ_n` in
/// 1/(time·length) (LAMMPS's `gamman`), `m` the reduced mass and `R` the effective radius;
/// optionally a tangential dashpot `−m γ_t √(R δ) v_t` with `γ_t = ratio · γ_n` (LAMMPS
/// `gammat`; its `NULL` default is `γ_n / 2`, ratio 0.5), see
/// [`HertzianViscous::with_tangential_ratio`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HertzianViscous {
    gamma_n: f64,
    #[cfg_attr(feature = "serde", serde(default))]
    tangential_ratio: f64,
}

impl HertzianViscous {
    /// `γ_n` (finite, ≥ 0); no tangential dashpot.
    pub fn new(gamma_n: f64) -> Result<Self> {
        Ok(Self {
            gamma_n: non_negative("gamma_n", gamma_n)?,
            tangential_ratio: 0.0,
        })
    }

    /// Add the tangential dashpot `γ_t = ratio · γ_n` (ratio finite, ≥ 0; LAMMPS
    /// `gran/hertz/history` with `gammat = NULL` is 0.5).
    pub fn with_tangential_ratio(mut self, ratio: f64) -> Result<Self> {
        self.tangential_ratio = non_negative("tangential_damping_ratio", ratio)?;
        Ok(self)
    }
}

/// [`HertzianViscous`] bound to a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzianViscousLaw {
    /// `m γ_n √R`.
    coefficient: f64,
    /// `γ_t / γ_n`.
    tangential_ratio: f64,
}

impl DampingModel for HertzianViscous {
    type Law = HertzianViscousLaw;
    fn bind(&self, pair: &ContactPair) -> Result<HertzianViscousLaw> {
        Ok(HertzianViscousLaw {
            coefficient: pair.reduced_mass() * self.gamma_n * pair.effective_radius().sqrt(),
            tangential_ratio: self.tangential_ratio,
        })
    }
}

impl DampingLaw for HertzianViscousLaw {
    #[inline(always)]
    fn normal_coefficient(&self, _: &NormalResponse, overlap: f64) -> f64 {
        // `√δ` written exactly as the normal laws write it, so that the compiler shares one
        // square root between them once the law chain is inlined.
        if overlap > 0.0 {
            self.coefficient * overlap.sqrt()
        } else {
            0.0
        }
    }

    #[inline(always)]
    fn tangential_ratio(&self) -> f64 {
        self.tangential_ratio
    }
}

/// Tsuji-type viscoelastic damping: `F_d = η √(m k_n) (dδ/dt)`, `k_n` the normal law's tangent
/// stiffness; `η` ≥ 0 is dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StiffnessViscous {
    eta: f64,
    #[cfg_attr(feature = "serde", serde(default))]
    tangential_ratio: f64,
}

impl StiffnessViscous {
    /// `η` (finite, ≥ 0); no tangential dashpot.
    pub fn new(eta: f64) -> Result<Self> {
        Ok(Self {
            eta: non_negative("eta", eta)?,
            tangential_ratio: 0.0,
        })
    }

    /// Add the tangential dashpot `η_t = ratio · η √(m k_n)` (ratio finite, ≥ 0).
    pub fn with_tangential_ratio(mut self, ratio: f64) -> Result<Self> {
        self.tangential_ratio = non_negative("tangential_damping_ratio", ratio)?;
        Ok(self)
    }
}

/// [`StiffnessViscous`] bound to a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessViscousLaw {
    eta: f64,
    mass: f64,
    tangential_ratio: f64,
}

impl DampingModel for StiffnessViscous {
    type Law = StiffnessViscousLaw;
    fn bind(&self, pair: &ContactPair) -> Result<StiffnessViscousLaw> {
        Ok(StiffnessViscousLaw {
            eta: self.eta,
            mass: pair.reduced_mass(),
            tangential_ratio: self.tangential_ratio,
        })
    }
}

impl DampingLaw for StiffnessViscousLaw {
    #[inline]
    fn normal_coefficient(&self, response: &NormalResponse, _overlap: f64) -> f64 {
        self.eta * (self.mass * response.stiffness).sqrt()
    }

    #[inline]
    fn tangential_ratio(&self) -> f64 {
        self.tangential_ratio
    }
}

/// The tangential dashpot's ratio, declared alike by both viscous damping laws.
const TANGENTIAL_RATIO: Param = Param::new(
    "damping_tangential_ratio",
    "η_t/η_n",
    "1",
    Range::NON_NEGATIVE,
    "tangential dashpot over the normal one while the Mindlin spring sticks (LAMMPS gammat/gamman; its NULL is 0.5)",
)
.default(0.0)
.lammps("tangential_damping");

/// No damping: no parameters.
impl Declared for NoDamping {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "none",
        kind: LawKind::Damping,
        summary: "no damping",
        params: &[],
    };
    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Ok(NoDamping)
    }
}

/// `γ_n` and the tangential ratio.
impl Declared for HertzianViscous {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "hertzian_viscous",
        kind: LawKind::Damping,
        summary: "F_d = m γ_n (dδ/dt) √(R δ) (LAMMPS gran/hertz/history)",
        params: &[
            Param::new(
                "damping_gamma_n_per_m_s",
                "γ_n",
                "1/(m·s)",
                Range::NON_NEGATIVE,
                "normal dashpot: F_d = m γ_n (dδ/dt) √(R δ), m the reduced mass, R the effective radius",
            )
            .lammps("damping"),
            TANGENTIAL_RATIO,
        ],
    };
    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Self::new(values[0])?.with_tangential_ratio(values[1])
    }
}

/// `η` and the tangential ratio.
impl Declared for StiffnessViscous {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "stiffness_viscous",
        kind: LawKind::Damping,
        summary: "F_d = η √(m k_n) (dδ/dt), k_n the normal law's tangent stiffness (Tsuji)",
        params: &[
            Param::new(
                "damping_eta",
                "η",
                "1",
                Range::NON_NEGATIVE,
                "normal dashpot: F_d = η √(m k_n) (dδ/dt)",
            ),
            TANGENTIAL_RATIO,
        ],
    };
    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Self::new(values[0])?.with_tangential_ratio(values[1])
    }
}
