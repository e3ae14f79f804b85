//! A linear spring, `F = k_n δ` (LAMMPS `hooke` without its dashpot): the smallest law with one
//! declared parameter, built only with the `demo-laws` feature. It shows, in the tests of every
//! layer, that a law added as one file plus one registry line runs in scenes, from the command
//! line and from Python. Its contact lasts half a period of the spring, `t_c = π √(m*/k_n)`, and
//! returns all the energy it took (`e_n = 1`): an analytic check for the layers that run it.

use super::{NormalLaw, NormalModel, NormalResponse};
use crate::error::Result;
use crate::material::ContactPair;
use crate::params::{Declared, LawDeclaration, LawKind, Param, Range};

/// The linear spring as a model: its stiffness `k_n` (N/m), the same for every pair.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LinearSpring {
    stiffness: f64,
}

impl LinearSpring {
    /// `k_n` (N/m, finite, > 0).
    pub fn new(stiffness: f64) -> Result<Self> {
        Ok(Self {
            stiffness: Self::DECLARATION.params[0].check(stiffness)?,
        })
    }

    /// `k_n` (N/m).
    pub fn stiffness(&self) -> f64 {
        self.stiffness
    }
}

/// The linear spring's parameter: `k_n`.
impl Declared for LinearSpring {
    const DECLARATION: LawDeclaration = LawDeclaration {
        name: "linear_spring",
        kind: LawKind::Normal,
        summary: "linear spring F = k_n δ (LAMMPS hooke without dashpot); built with the demo-laws feature",
        params: &[Param::new(
            "normal_stiffness_n_per_m",
            "k_n",
            "N/m",
            Range::POSITIVE,
            "spring constant: F = k_n δ, contact time π √(m*/k_n)",
        )
        .lammps("kn")],
    };

    fn from_values(values: &[f64]) -> Result<Self> {
        crate::params::check_values::<Self>(values)?;
        Self::new(values[0])
    }
}

impl NormalModel for LinearSpring {
    type Law = LinearSpringLaw;
    fn bind(&self, pair: &ContactPair) -> Result<LinearSpringLaw> {
        Ok(LinearSpringLaw {
            stiffness: self.stiffness,
            effective_radius: pair.effective_radius(),
        })
    }
}

/// The linear spring of one pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearSpringLaw {
    stiffness: f64,
    effective_radius: f64,
}

impl NormalLaw for LinearSpringLaw {
    /// Largest overlap so far (m).
    type State = f64;

    #[inline]
    fn update(&self, state: &mut f64, overlap: f64) -> NormalResponse {
        if overlap <= 0.0 {
            return NormalResponse::default();
        }
        if overlap > *state {
            *state = overlap;
        }
        NormalResponse {
            force: self.stiffness * overlap,
            // The geometric contact radius of two spheres, for the tangential law.
            contact_radius: (self.effective_radius * overlap).sqrt(),
            stiffness: self.stiffness,
        }
    }

    fn max_overlap(&self, state: &f64) -> f64 {
        *state
    }

    fn residual_overlap(&self, _state: &f64) -> f64 {
        0.0
    }

    fn dissipated_work(&self, _state: &f64) -> f64 {
        0.0
    }

    fn elastic_energy(&self, _state: &f64, overlap: f64) -> f64 {
        if overlap > 0.0 {
            0.5 * self.stiffness * overlap * overlap
        } else {
            0.0
        }
    }

    fn yield_overlap(&self) -> f64 {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_is_linear_and_its_work_is_the_stored_energy() {
        let law = LinearSpring::new(2.0e5)
            .unwrap()
            .bind(&ContactPair::paper_fig2())
            .unwrap();
        let mut state = 0.0;
        let r = law.update(&mut state, 1e-3);
        assert_eq!(r.force, 200.0);
        assert_eq!(r.stiffness, 2.0e5);
        // ∫₀^δ k x dx = k δ² / 2, by the trapezoid rule (exact for a linear integrand).
        let n = 1000;
        let h = 1e-3 / n as f64;
        let work: f64 = (0..n)
            .map(|i| {
                0.5 * h
                    * (law.evaluate(&state, i as f64 * h).force
                        + law.evaluate(&state, (i + 1) as f64 * h).force)
            })
            .sum();
        assert!((law.elastic_energy(&state, 1e-3) / work - 1.0).abs() < 1e-12);
        assert_eq!(law.update(&mut state, -1e-6), NormalResponse::default());
        assert_eq!(law.max_overlap(&state), 1e-3);
    }

    #[test]
    fn stiffness_outside_its_declared_range_is_refused_by_key() {
        for k in [0.0, -1.0, f64::NAN] {
            let e = LinearSpring::new(k).unwrap_err().to_string();
            assert!(e.contains("normal_stiffness_n_per_m"), "{e}");
        }
    }
}
