//! Shared helpers of the integration tests.

use mdr_contact::normal::NormalLaw;

/// Result of one time-stepped normal impact.
#[derive(Debug, Clone, Copy)]
#[allow(dead_code)] // each test binary reads only some fields
pub struct SteppedImpact {
    /// `e_n = −v_exit / v_0`, eq. (14).
    pub restitution: f64,
    /// Number of steps with contact.
    pub steps: usize,
    /// Largest overlap (m).
    pub max_overlap: f64,
}

/// Integrate `m δ'' = −F(δ)` (eq. 15) with velocity Verlet from `δ = 0`, `δ' = speed`, with a
/// step of `contact_time_estimate / steps_per_contact`, until the force vanishes while the bodies
/// separate. The exit velocity is corrected for the part of the last step after the force
/// reached zero (at the law's residual overlap).
pub fn impact<L: NormalLaw>(
    law: &L,
    state: &mut L::State,
    mass: f64,
    speed: f64,
    contact_time_estimate: f64,
    steps_per_contact: usize,
) -> SteppedImpact {
    let dt = contact_time_estimate / steps_per_contact as f64;
    let (mut d, mut v, mut f) = (0.0_f64, speed, 0.0_f64);
    let mut steps = 0;
    let mut max_overlap: f64 = 0.0;
    loop {
        let d_new = d + v * dt - 0.5 * f / mass * dt * dt;
        let f_new = law.update(state, d_new).force;
        let v_new = v - 0.5 * (f + f_new) / mass * dt;
        steps += 1;
        max_overlap = max_overlap.max(d_new);
        if v_new < 0.0 && f_new <= 0.0 && steps > 1 {
            // The force reached zero at the residual overlap inside this step: only the part
            // τ dt before it carried (linearly decaying) force.
            let zero = law.residual_overlap(state);
            let tau = ((d - zero) / (d - d_new)).clamp(0.0, 1.0);
            let v_exit = v - 0.5 * f / mass * tau * dt;
            return SteppedImpact {
                restitution: -v_exit / speed,
                steps,
                max_overlap,
            };
        }
        assert!(steps < 100 * steps_per_contact, "impact did not end");
        (d, v, f) = (d_new, v_new, f_new);
    }
}
