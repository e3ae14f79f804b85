//! The per-pair kernel: contact kinematics → law update on the pair's history → force and
//! torques on both bodies. Every force-mode path (the plain path over rapier's narrow phase here,
//! and any faster neighbour-list path) calls this one function, so they agree to round-off.

use mdr_contact::damping::DampingLaw;
use mdr_contact::model::{ContactInput, ContactLaw, StateOf};
use mdr_contact::normal::NormalLaw;
use mdr_contact::rolling::{RollingInput, RollingLaw};
use mdr_contact::tangential::TangentialLaw;
use nalgebra::Vector3;

/// Kinematics of one touching pair at the start of the step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactKinematics {
    /// Overlap `δ` (m), > 0.
    pub overlap: f64,
    /// Unit normal from body 2 towards body 1.
    pub normal: Vector3<f64>,
    /// Contact point minus the centre of mass of body 1 (m).
    pub arm1: Vector3<f64>,
    /// Contact point minus the centre of mass of body 2 (m); zero for a body-less collider.
    pub arm2: Vector3<f64>,
    /// Velocity of body 1's centre of mass (m/s).
    pub linvel1: Vector3<f64>,
    /// Angular velocity of body 1 (rad/s).
    pub angvel1: Vector3<f64>,
    /// Velocity of body 2's centre of mass (m/s).
    pub linvel2: Vector3<f64>,
    /// Angular velocity of body 2 (rad/s).
    pub angvel2: Vector3<f64>,
}

impl ContactKinematics {
    /// Velocity of body 1 relative to body 2 at the contact point (m/s).
    #[inline]
    pub fn relative_velocity(&self) -> Vector3<f64> {
        (self.linvel1 + self.angvel1.cross(&self.arm1))
            - (self.linvel2 + self.angvel2.cross(&self.arm2))
    }
}

/// Force and torques of one contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PairWrench {
    /// Force on body 1 (N); body 2 receives `−force`.
    pub force: Vector3<f64>,
    /// Torque on body 1 about its centre of mass (N·m).
    pub torque1: Vector3<f64>,
    /// Torque on body 2 about its centre of mass (N·m).
    pub torque2: Vector3<f64>,
}

/// History of one touching pair: the composed law's state and the rolling law's state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PairHistory<S, RS> {
    /// Normal + tangential history and work books ([`mdr_contact::model::ContactState`]).
    pub contact: S,
    /// Rolling-resistance history.
    pub rolling: RS,
}

/// One contact, one step: the law crate's [`ContactLaw::update`] (normal MDR, tangential Mindlin,
/// damping) and the rolling law, turned into a force and two torques.
#[inline(always)]
pub fn evaluate_pair<NL, TL, DL, RL>(
    law: &ContactLaw<NL, TL, DL>,
    rolling: &RL,
    history: &mut PairHistory<StateOf<NL, TL>, RL::State>,
    kinematics: &ContactKinematics,
    dt: f64,
) -> PairWrench
where
    NL: NormalLaw,
    TL: TangentialLaw,
    DL: DampingLaw,
    RL: RollingLaw,
{
    let output = law.update(
        &mut history.contact,
        &ContactInput {
            overlap: kinematics.overlap,
            normal: kinematics.normal,
            relative_velocity: kinematics.relative_velocity(),
            dt,
        },
    );
    let roll = rolling.update(
        &mut history.rolling,
        &RollingInput {
            normal: kinematics.normal,
            rotation_increment: (kinematics.angvel1 - kinematics.angvel2) * dt,
            normal_force: output.normal_force,
            normal_stiffness: output.normal.stiffness,
        },
    );
    let force = output.force;
    PairWrench {
        force,
        torque1: kinematics.arm1.cross(&force) + roll.torque,
        torque2: kinematics.arm2.cross(&(-force)) - roll.torque,
    }
}
