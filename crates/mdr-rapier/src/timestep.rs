//! Time-step helper for force mode: the step that resolves the shortest contact with a chosen
//! number of steps, and a warning when a step resolves a contact too coarsely.
//!
//! The contact duration is Hertz's, `t_c = 2.868 (m² / (R E*² v))^{1/5}` (eq. 5 integrated over
//! one elastic impact), shortest at the largest speed. The MDR law is softer than Hertz while
//! loading plastically, so Hertz's `t_c` is a lower bound of the MDR contact time on loading.

use crate::error::{positive, Result};
use mdr_contact::ContactPair;

/// Fewer steps per contact than this degrade the restitution by more than about 1 %
/// (symplectic Euler, first order in `dt`); the warning threshold.
pub const MIN_STEPS_PER_CONTACT: f64 = 50.0;

/// A recommended time step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeStepAdvice {
    /// Hertz contact time at the given speed (s).
    pub contact_time: f64,
    /// Recommended step: `contact_time / steps_per_contact` (s).
    pub time_step: f64,
    /// Stability limit of symplectic Euler on the stiffest point of the contact,
    /// `2 √(m / k_max)` with `k_max = 2 E* a_max` (s); the recommended step is far below it.
    pub stability_limit: f64,
}

/// The largest step resolving a Hertz contact of `pair` at normal speed `max_speed` (m/s, > 0)
/// with `steps_per_contact` (≥ 1) steps.
///
/// ```
/// use mdr_rapier::{stable_time_step, LawPair};
/// let advice = stable_time_step(&LawPair::paper_fig2(), 3.0, 50.0).unwrap();
/// assert!(advice.time_step < advice.stability_limit);
/// assert!((advice.contact_time / advice.time_step - 50.0).abs() < 1e-9);
/// ```
pub fn stable_time_step(
    pair: &ContactPair,
    max_speed: f64,
    steps_per_contact: f64,
) -> Result<TimeStepAdvice> {
    positive("max_speed", max_speed)?;
    positive("steps_per_contact", steps_per_contact)?;
    let contact_time = pair.hertz_contact_time(max_speed);
    let a_max = (pair.effective_radius() * pair.hertz_max_overlap(max_speed)).sqrt();
    let k_max = 2.0 * pair.effective_modulus() * a_max;
    Ok(TimeStepAdvice {
        contact_time,
        time_step: contact_time / steps_per_contact,
        stability_limit: 2.0 * (pair.reduced_mass() / k_max).sqrt(),
    })
}

/// A step that resolves a contact with fewer than [`MIN_STEPS_PER_CONTACT`] steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeStepWarning {
    /// The step that was checked (s).
    pub time_step: f64,
    /// Hertz contact time at the checked speed (s).
    pub contact_time: f64,
    /// `contact_time / time_step`.
    pub steps_per_contact: f64,
}

impl std::fmt::Display for TimeStepWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "time step {:.3e} s resolves a {:.3e} s contact with {:.1} steps (fewer than {}): \
             restitution and energy books lose accuracy; reduce dt",
            self.time_step, self.contact_time, self.steps_per_contact, MIN_STEPS_PER_CONTACT
        )
    }
}

/// `Some(warning)` when `dt` resolves the Hertz contact of `pair` at `max_speed` with fewer
/// than [`MIN_STEPS_PER_CONTACT`] steps.
pub fn check_time_step(
    pair: &ContactPair,
    dt: f64,
    max_speed: f64,
) -> Result<Option<TimeStepWarning>> {
    positive("dt", dt)?;
    positive("max_speed", max_speed)?;
    let contact_time = pair.hertz_contact_time(max_speed);
    let steps_per_contact = contact_time / dt;
    Ok(
        (steps_per_contact < MIN_STEPS_PER_CONTACT).then_some(TimeStepWarning {
            time_step: dt,
            contact_time,
            steps_per_contact,
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warns_below_fifty_steps_only() {
        let pair = ContactPair::paper_fig2();
        let advice = stable_time_step(&pair, 1.0, 60.0).unwrap();
        assert!(check_time_step(&pair, advice.time_step, 1.0)
            .unwrap()
            .is_none());
        let coarse = check_time_step(&pair, advice.contact_time / 20.0, 1.0)
            .unwrap()
            .unwrap();
        assert!((coarse.steps_per_contact - 20.0).abs() < 1e-9);
        assert!(stable_time_step(&pair, 0.0, 50.0).is_err());
        assert!(check_time_step(&pair, -1.0, 1.0).is_err());
    }
}
