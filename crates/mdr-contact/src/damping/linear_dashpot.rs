//! A linear dashpot, `F_d = c dδ/dt` with a constant coefficient `c` (LAMMPS `hooke`'s damping
//! with a fixed `damp`): the smallest damping law with one declared parameter, built only with
//! the `demo-laws` feature. It shows, in the tests of every layer, that a damping law added as
//! one file plus one registry line runs in scenes, from the command line and from Python.
//!
//! With the demo linear spring (`k_n`) it is the linear spring–dashpot, whose restitution is
//! analytic. With `ω₀ = √(k_n/m*)`, `β = c/(2m*)`, `ζ = β/ω₀ = c/(2√(m* k_n))` and
//! `ω_d = ω₀√(1−ζ²)`, the overlap of an impact at speed `v` is `δ(t) = (v/ω_d) e^{−βt} sin ω_d t`.
//! A contact that may pull ends at `δ = 0`, `t = π/ω_d`, with `e_n = exp(−πζ/√(1−ζ²))`. A contact
//! that only pushes (the total normal force `k_n δ + c dδ/dt` kept ≥ 0, as the contact model
//! does) lets go earlier, when that force reaches 0: `tan ω_d t = −2βω_d/(ω_d²−β²)`, i.e.
//! `ω_d t_e = π − 2 arctan(β/ω_d)`, where the velocity is `−v e^{−β t_e}`, so
//! `e_n = exp(−β t_e)` (for `ζ < 1/√2`; Schwager & Pöschel, Granular Matter 9 (2007) 465–469).

use super::{DampingLaw, DampingModel};
use crate::error::Result;
use crate::material::ContactPair;
use crate::normal::NormalResponse;
use crate::params::{Declared, LawDeclaration, LawKind, Param, Range};

/// The linear dashpot: its coefficient `c` (N·s/m), the same for every pair; no tangential
/// dashpot.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LinearDashpot {
    coefficient: f64,
}

impl LinearDashpot {
    /// `c` (N·s/m, finite, ≥ 0).
    pub fn new(coefficient: f64) -> Result<Self> {
        Ok(Self {
            coefficient: Self::DECLARATION.params[0].check(coefficient)?,
        })
    }

    /// `c` (N·s/m).
    pub fn coefficient(&self) -> f64 {
        self.coefficient
    }
}

/// The linear dashpot's parameter: `c`.
impl Declared for LinearDashpot {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "linear_dashpot",
        kind: LawKind::Damping,
        summary: "linear dashpot F_d = c dδ/dt (LAMMPS hooke's damping); built with the demo-laws feature",
        params: &[Param::new(
            "damping_coefficient_n_s_per_m",
            "c",
            "N·s/m",
            Range::NON_NEGATIVE,
            "normal dashpot: F_d = c dδ/dt; with a linear spring the damping ratio is c / (2 √(m* k_n))",
        )],
    };

    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Self::new(values[0])
    }
}

impl DampingModel for LinearDashpot {
    type Law = LinearDashpot;
    fn bind(&self, _pair: &ContactPair) -> Result<LinearDashpot> {
        Ok(*self)
    }
}

impl DampingLaw for LinearDashpot {
    #[inline]
    fn normal_coefficient(&self, _: &NormalResponse, overlap: f64) -> f64 {
        if overlap > 0.0 {
            self.coefficient
        } else {
            0.0
        }
    }

    #[inline]
    fn tangential_ratio(&self) -> f64 {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_is_the_coefficient_times_the_approach_rate_in_contact_only() {
        let law = LinearDashpot::new(3.0)
            .unwrap()
            .bind(&ContactPair::paper_fig2())
            .unwrap();
        let r = NormalResponse::default();
        assert_eq!(law.normal_force(&r, 1e-4, 2.0), 6.0);
        assert_eq!(law.normal_force(&r, 1e-4, -2.0), -6.0);
        assert_eq!(law.normal_force(&r, 0.0, 2.0), 0.0);
        assert_eq!(law.tangential_coefficient(&r, 1e-4), 0.0);
    }

    #[test]
    fn coefficient_outside_its_declared_range_is_refused_by_key() {
        for c in [-1.0, f64::NAN, f64::INFINITY] {
            let e = LinearDashpot::new(c).unwrap_err().to_string();
            assert!(e.contains("damping_coefficient_n_s_per_m"), "{e}");
        }
    }
}
