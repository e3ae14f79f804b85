//! Time integration of one impact: the equation of motion `m dv/dt = −F` (eq. 15) with velocity
//! Verlet, the step set from the Hertz contact time. The exit velocity is taken at the instant the
//! normal force vanishes (linear interpolation of the overlap to the law's residual depth inside
//! the last step), so `e_n` (eq. 14) does not carry a half-step error.
//!
//! An adhesive contact holds past that point ([`NormalLaw::holds`]): the integration goes on
//! through negative overlaps, with the tensile force, until the contact lets go. The impact is
//! **stuck** (`e_n = 0`) when the sphere, moving away while the contact holds, turns back
//! towards the target: from then on the neck's tension has taken all the kinetic energy the
//! sphere had left, and without other losses it oscillates in the adhesive well, each let-go of
//! springs only dissipating more; it never reaches the let-go overlap again.

use crate::error::{ImpactError, Result};
use mdr_contact::normal::{NormalLaw, NormalResponse, SpringBed};
use mdr_contact::tangential::{
    MindlinLaw, SpringBedTangential, SpringBedTangentialState, TangentialInput, TangentialLaw,
};
use nalgebra::Vector3;

/// One sample of an impact's time history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TracePoint {
    /// Time since first touch (s).
    pub time: f64,
    /// Overlap `δ` (m).
    pub overlap: f64,
    /// Normal velocity of the sphere relative to the target (m/s), positive away from it:
    /// `−dδ/dt`.
    pub velocity: f64,
    /// Normal force (N).
    pub force: f64,
    /// Contact radius (m).
    pub contact_radius: f64,
    /// Work dissipated by plasticity so far (J), as the law books it.
    pub plastic_work: f64,
}

/// What the normal time integration yields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NormalRun {
    /// `e_n = −v_out / v_in`, eq. (14).
    pub restitution: f64,
    /// Largest overlap (m).
    pub max_overlap: f64,
    /// Residual depth after separation (m).
    pub residual_overlap: f64,
    /// Time from first touch to separation (s).
    pub contact_time: f64,
    /// Largest normal force (N).
    pub peak_force: f64,
    /// Largest tensile force (N, ≥ 0; zero without adhesion).
    pub pull_off_force: f64,
    /// Overlap at which the contact let go (m): the residual depth without adhesion, typically
    /// negative with it; NaN when stuck.
    pub release_overlap: f64,
    /// Whether the sphere stuck (`e_n = 0`).
    pub stuck: bool,
}

impl NormalRun {
    fn stuck(state_max: f64, residual: f64, contact_time: f64, peak: f64, pull: f64) -> Self {
        Self {
            restitution: 0.0,
            max_overlap: state_max,
            residual_overlap: residual,
            contact_time,
            peak_force: peak,
            pull_off_force: pull,
            release_overlap: f64::NAN,
            stuck: true,
        }
    }
}

/// Linear fraction of the last step at which the overlap crosses `residual`.
fn exit_fraction(previous: f64, current: f64, residual: f64) -> f64 {
    let drop = previous - current;
    if drop > 0.0 {
        ((previous - residual) / drop).clamp(0.0, 1.0)
    } else {
        1.0
    }
}

/// Integrate a head-on impact of reduced mass `mass` (kg) arriving at normal speed `speed`
/// (m/s, > 0) on a fresh contact, with step `dt` (s). Records every step in `trace` if given.
pub(crate) fn integrate_normal<L: NormalLaw>(
    law: &L,
    mass: f64,
    speed: f64,
    dt: f64,
    max_steps: usize,
    mut trace: Option<&mut Vec<TracePoint>>,
) -> Result<NormalRun> {
    let mut state = L::State::default();
    let inverse_mass = 1.0 / mass;
    // rate = dδ/dt (positive while approaching).
    let (mut overlap, mut rate, mut force) = (0.0_f64, speed, 0.0_f64);
    let mut peak_force = 0.0_f64;
    let mut tension = 0.0_f64;
    // Whether the contact held at the previous step, and down to which overlap it could.
    let (mut held, mut reach) = (false, 0.0_f64);
    if let Some(t) = trace.as_deref_mut() {
        t.push(TracePoint {
            time: 0.0,
            overlap: 0.0,
            velocity: -speed,
            force: 0.0,
            contact_radius: 0.0,
            plastic_work: 0.0,
        });
    }
    for step in 1..=max_steps {
        let half_rate = rate - 0.5 * dt * force * inverse_mass;
        let previous_overlap = overlap;
        overlap += dt * half_rate;
        let response = law.update(&mut state, overlap);
        let new_force = response.force;
        let holds = law.holds(&state);
        if new_force <= 0.0 && half_rate < 0.0 && !holds {
            // Separation inside this step. Without adhesion the force vanished where the
            // overlap crossed the residual depth: integrate only that part of the step, force
            // linear in time. A held contact let go at its reach, with the force still tensile:
            // the whole step's half kick applies.
            let residual = law.residual_overlap(&state);
            let (tau, release) = if held {
                (1.0, reach.clamp(overlap, previous_overlap))
            } else {
                let tau = exit_fraction(previous_overlap, overlap, residual);
                (tau, previous_overlap + tau * (overlap - previous_overlap))
            };
            let exit_rate = rate - 0.5 * tau * dt * force * inverse_mass;
            let contact_time = (step as f64 - 1.0 + tau) * dt;
            if let Some(t) = trace.as_deref_mut() {
                t.push(TracePoint {
                    time: contact_time,
                    overlap: release,
                    velocity: -exit_rate,
                    force: 0.0,
                    contact_radius: 0.0,
                    plastic_work: law.dissipated_work(&state),
                });
            }
            return Ok(NormalRun {
                restitution: -exit_rate / speed,
                max_overlap: law.max_overlap(&state),
                residual_overlap: residual,
                contact_time,
                peak_force,
                pull_off_force: tension,
                release_overlap: release,
                stuck: false,
            });
        }
        force = new_force;
        peak_force = peak_force.max(force);
        tension = tension.max(-force);
        let previous_rate = rate;
        rate = half_rate - 0.5 * dt * force * inverse_mass;
        if let Some(t) = trace.as_deref_mut() {
            t.push(TracePoint {
                time: step as f64 * dt,
                overlap,
                velocity: -rate,
                force,
                contact_radius: response.contact_radius,
                plastic_work: law.dissipated_work(&state),
            });
        }
        held = holds;
        if holds {
            reach = law.detachment_overlap(&state);
            if previous_rate < 0.0 && rate >= 0.0 {
                // Turned back while held: stuck.
                return Ok(NormalRun::stuck(
                    law.max_overlap(&state),
                    law.residual_overlap(&state),
                    f64::NAN,
                    peak_force,
                    tension,
                ));
            }
        }
    }
    Err(ImpactError::NoSeparation {
        steps: max_steps,
        speed,
    })
}

/// One step of a tangential law in the oblique integrator: the slip increment of the contact
/// point along `x` in, the tangential force on the sphere along `x` out.
pub(crate) trait TangentialStep<N: NormalLaw> {
    /// Tangential history.
    type State: Default;
    /// Advance by `slip` (m); `normal_state` is already updated to this step.
    fn step(
        &self,
        normal_law: &N,
        normal_state: &N::State,
        normal: &NormalResponse,
        state: &mut Self::State,
        slip: f64,
    ) -> f64;
}

/// The O(1) Mindlin law works with any normal law (it reads the force and contact radius).
impl<N: NormalLaw> TangentialStep<N> for MindlinLaw {
    type State = <MindlinLaw as TangentialLaw>::State;
    fn step(
        &self,
        normal_law: &N,
        _normal_state: &N::State,
        normal: &NormalResponse,
        state: &mut Self::State,
        slip: f64,
    ) -> f64 {
        self.update(
            state,
            &TangentialInput {
                normal: Vector3::z(),
                displacement_increment: Vector3::new(slip, 0.0, 0.0),
                // Coulomb limit on F_n + 2 F_c (Thornton & Yin; zero offset without adhesion).
                normal_response: NormalResponse {
                    force: normal.force + 2.0 * normal_law.pull_off_force(),
                    ..*normal
                },
            },
        )
        .force
        .x
    }
}

/// The MDR spring-bed tangential law reads every spring's normal force from the bed.
impl TangentialStep<SpringBed> for SpringBedTangential {
    type State = SpringBedTangentialState;
    fn step(
        &self,
        normal_law: &SpringBed,
        normal_state: &<SpringBed as NormalLaw>::State,
        _normal: &NormalResponse,
        state: &mut SpringBedTangentialState,
        slip: f64,
    ) -> f64 {
        // The law returns the springs' force, along their displacement; the sphere feels the
        // opposite.
        -self.update(normal_law, normal_state, state, slip)
    }
}

/// What the oblique time integration yields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ObliqueRun {
    /// The normal part.
    pub normal: NormalRun,
    /// Tangential velocity of the centre after the impact (m/s), signed along the incoming one.
    pub tangential_velocity: f64,
    /// Angular velocity after the impact (rad/s), positive in the sense of rolling forward.
    pub spin: f64,
}

/// Sphere of mass `mass` and radius `radius` on a fixed half-space, arriving with normal speed
/// `normal_speed` (> 0), tangential speed `tangential_speed` along `x` and spin `spin` (rad/s)
/// about `y` (positive = rolling towards `+x`). The half-space normal is `+z`. Rotation uses
/// `I = (2/5) m R²`. Normal and tangential laws are updated once per step, the tangential one with
/// the slip increment `(v_x − R ω) dt` at mid-step velocities (leapfrog).
#[allow(clippy::too_many_arguments)]
pub(crate) fn integrate_oblique<N: NormalLaw, T: TangentialStep<N>>(
    normal_law: &N,
    tangential_law: &T,
    mass: f64,
    radius: f64,
    normal_speed: f64,
    tangential_speed: f64,
    spin: f64,
    dt: f64,
    max_steps: usize,
) -> Result<ObliqueRun> {
    let mut normal_state = N::State::default();
    let mut tangential_state = T::State::default();
    let inverse_mass = 1.0 / mass;
    let inverse_inertia = 1.0 / (0.4 * mass * radius * radius);
    let (mut overlap, mut rate, mut force) = (0.0_f64, normal_speed, 0.0_f64);
    // Tangential force on the sphere along x, and the state of x and ω.
    let (mut vx, mut omega, mut fx) = (tangential_speed, spin, 0.0_f64);
    let mut peak_force = 0.0_f64;
    let mut tension = 0.0_f64;
    let (mut held, mut reach) = (false, 0.0_f64);
    for step in 1..=max_steps {
        let half_rate = rate - 0.5 * dt * force * inverse_mass;
        let half_vx = vx + 0.5 * dt * fx * inverse_mass;
        // Torque about y from a force F_x at the contact point −R ẑ: τ_y = −R F_x.
        let half_omega = omega - 0.5 * dt * radius * fx * inverse_inertia;
        let previous_overlap = overlap;
        overlap += dt * half_rate;
        let normal = normal_law.update(&mut normal_state, overlap);
        let slip = (half_vx - radius * half_omega) * dt;
        let tangential_force = tangential_law.step(
            normal_law,
            &normal_state,
            &normal,
            &mut tangential_state,
            slip,
        );
        let holds = normal_law.holds(&normal_state);
        if normal.force <= 0.0 && half_rate < 0.0 && !holds {
            let residual = normal_law.residual_overlap(&normal_state);
            let (tau, release) = if held {
                (1.0, reach.clamp(overlap, previous_overlap))
            } else {
                let tau = exit_fraction(previous_overlap, overlap, residual);
                (tau, previous_overlap + tau * (overlap - previous_overlap))
            };
            let part = 0.5 * tau * dt;
            return Ok(ObliqueRun {
                normal: NormalRun {
                    restitution: -(rate - part * force * inverse_mass) / normal_speed,
                    max_overlap: normal_law.max_overlap(&normal_state),
                    residual_overlap: residual,
                    contact_time: (step as f64 - 1.0 + tau) * dt,
                    peak_force,
                    pull_off_force: tension,
                    release_overlap: release,
                    stuck: false,
                },
                tangential_velocity: vx + part * fx * inverse_mass,
                spin: omega - part * radius * fx * inverse_inertia,
            });
        }
        force = normal.force;
        fx = tangential_force;
        peak_force = peak_force.max(force);
        tension = tension.max(-force);
        let previous_rate = rate;
        rate = half_rate - 0.5 * dt * force * inverse_mass;
        vx = half_vx + 0.5 * dt * fx * inverse_mass;
        omega = half_omega - 0.5 * dt * radius * fx * inverse_inertia;
        held = holds;
        if holds {
            reach = normal_law.detachment_overlap(&normal_state);
            if previous_rate < 0.0 && rate >= 0.0 {
                // Turned back while held: stuck; the tangential motion is what it is now.
                return Ok(ObliqueRun {
                    normal: NormalRun::stuck(
                        normal_law.max_overlap(&normal_state),
                        normal_law.residual_overlap(&normal_state),
                        f64::NAN,
                        peak_force,
                        tension,
                    ),
                    tangential_velocity: vx,
                    spin: omega,
                });
            }
        }
    }
    Err(ImpactError::NoSeparation {
        steps: max_steps,
        speed: normal_speed,
    })
}
