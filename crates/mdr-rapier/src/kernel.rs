//! The per-pair kernel: contact kinematics → law update on the pair's history → force and
//! torques on both bodies. Every force-mode path (the rapier pipeline path over rapier's narrow phase here,
//! and any faster neighbour-list path) calls this one function, so they agree to round-off.
//!
//! The kernel's structures hold the law crate's vectors (`nalgebra::Vector3<f64>`, the type of
//! [`mdr_contact::model::ContactInput`]), so that the hot loops hand them to the law without a
//! conversion; [`PairWrench`]'s accessors give its results in rapier's vector type.

use crate::convert::to_glam;
use mdr_contact::damping::DampingLaw;
use mdr_contact::model::{ContactInput, ContactLaw, StateOf, WorkBooks};
use mdr_contact::normal::NormalLaw;
use mdr_contact::rolling::{RollingInput, RollingLaw};
use mdr_contact::tangential::TangentialLaw;
use nalgebra::Vector3;
use rapier3d_f64::math::Vector;

/// Where the contact point sits relative to the two centres of mass: it decides the contact
/// point's velocity and the torques of the contact force.
pub trait LeverArms: Copy {
    /// `ω₁ × r₁ − ω₂ × r₂`: the rotational part of body 1's contact-point velocity relative to
    /// body 2's (m/s).
    fn rotational_velocity(
        &self,
        normal: &Vector3<f64>,
        angvel1: &Vector3<f64>,
        angvel2: &Vector3<f64>,
    ) -> Vector3<f64>;
    /// Torques `(r₁ × F, r₂ × (−F))` of the force `F` on body 1 (and `−F` on body 2) (N·m).
    fn torques(&self, normal: &Vector3<f64>, force: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>);
}

/// Lever arms of any contact: the contact point minus each centre of mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arms {
    /// Contact point minus the centre of mass of body 1 (m).
    pub arm1: Vector3<f64>,
    /// Contact point minus the centre of mass of body 2 (m); zero for a body-less collider.
    pub arm2: Vector3<f64>,
}

impl LeverArms for Arms {
    #[inline(always)]
    fn rotational_velocity(
        &self,
        _: &Vector3<f64>,
        angvel1: &Vector3<f64>,
        angvel2: &Vector3<f64>,
    ) -> Vector3<f64> {
        angvel1.cross(&self.arm1) - angvel2.cross(&self.arm2)
    }

    #[inline(always)]
    fn torques(&self, _: &Vector3<f64>, force: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        (self.arm1.cross(force), self.arm2.cross(&(-force)))
    }
}

/// Lever arms of two spheres: the contact point lies on the line of centres, at `lever1` from
/// centre 1 against the normal and `lever2` from centre 2 along it (for an overlap `δ`,
/// `lever = r − δ/2`, the mid-overlap point of [`crate::geometry::sphere_sphere`]). Then
/// `r₁ = −lever1 n`, `r₂ = lever2 n`, so `ω₁ × r₁ − ω₂ × r₂ = −(lever1 ω₁ + lever2 ω₂) × n` and
/// both torques are multiples of `n × F` (`−lever1 n × F` and `−lever2 n × F`): one cross
/// product each instead of two.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereArms {
    /// Distance from centre 1 to the contact point (m).
    pub lever1: f64,
    /// Distance from centre 2 to the contact point (m).
    pub lever2: f64,
}

impl LeverArms for SphereArms {
    #[inline(always)]
    fn rotational_velocity(
        &self,
        normal: &Vector3<f64>,
        angvel1: &Vector3<f64>,
        angvel2: &Vector3<f64>,
    ) -> Vector3<f64> {
        -(angvel1 * self.lever1 + angvel2 * self.lever2).cross(normal)
    }

    #[inline(always)]
    fn torques(&self, normal: &Vector3<f64>, force: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let moment = normal.cross(force);
        (moment * -self.lever1, moment * -self.lever2)
    }
}

/// Kinematics of one touching pair at the start of the step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactKinematics<A: LeverArms = Arms> {
    /// Overlap `δ` (m), > 0.
    pub overlap: f64,
    /// Unit normal from body 2 towards body 1.
    pub normal: Vector3<f64>,
    /// Where the contact point sits relative to the centres of mass.
    pub arms: A,
    /// Velocity of body 1's centre of mass (m/s).
    pub linvel1: Vector3<f64>,
    /// Angular velocity of body 1 (rad/s).
    pub angvel1: Vector3<f64>,
    /// Velocity of body 2's centre of mass (m/s).
    pub linvel2: Vector3<f64>,
    /// Angular velocity of body 2 (rad/s).
    pub angvel2: Vector3<f64>,
}

impl<A: LeverArms> ContactKinematics<A> {
    /// Velocity of body 1 relative to body 2 at the contact point (m/s).
    #[inline(always)]
    pub fn relative_velocity(&self) -> Vector3<f64> {
        (self.linvel1 - self.linvel2)
            + self
                .arms
                .rotational_velocity(&self.normal, &self.angvel1, &self.angvel2)
    }
}

/// Force and torques of one contact, in the law crate's vector type (the law's output as it
/// is); the accessors give them in rapier's.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PairWrench {
    /// Force on body 1 (N); body 2 receives `−force`.
    pub force: Vector3<f64>,
    /// Torque on body 1 about its centre of mass (N·m).
    pub torque1: Vector3<f64>,
    /// Torque on body 2 about its centre of mass (N·m).
    pub torque2: Vector3<f64>,
}

impl PairWrench {
    /// Force on body 1 (N), in rapier's vector type.
    #[inline]
    pub fn force(&self) -> Vector {
        to_glam(&self.force)
    }

    /// Torque on body 1 (N·m), in rapier's vector type.
    #[inline]
    pub fn torque1(&self) -> Vector {
        to_glam(&self.torque1)
    }

    /// Torque on body 2 (N·m), in rapier's vector type.
    #[inline]
    pub fn torque2(&self) -> Vector {
        to_glam(&self.torque2)
    }
}

/// History of one touching pair: the composed law's state and the rolling law's state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PairHistory<S, RS> {
    /// Normal + tangential history and work books ([`mdr_contact::model::ContactState`]).
    pub contact: S,
    /// Rolling-resistance history.
    pub rolling: RS,
}

/// What one contact's history has booked since it began: the work its laws dissipated and the
/// energy its incremental springs gained without work (J). A pair's history ends when the pair
/// separates; a coupling that keeps energy books adds these once, at that moment, instead of
/// taking every contact's increments at every step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactWorks {
    /// Plastic work (`NormalLaw::dissipated_work`).
    pub plastic: f64,
    /// Friction work.
    pub friction: f64,
    /// Damping work.
    pub damping: f64,
    /// Rolling-resistance work.
    pub rolling: f64,
    /// Energy the tangential springs gained without work (negative when lost).
    pub tangential_stiffness: f64,
    /// Energy the rolling spring gained without work (negative when lost).
    pub rolling_stiffness: f64,
}

impl ContactWorks {
    /// The books of `history` under `law` and `rolling` (NaN parts with
    /// [`mdr_contact::model::NoBooks`]).
    #[inline]
    pub fn of<NL, TL, DL, RL, B>(
        law: &ContactLaw<NL, TL, DL>,
        rolling: &RL,
        history: &PairHistory<StateOf<NL, TL, B>, RL::State>,
    ) -> Self
    where
        B: WorkBooks,
        NL: NormalLaw,
        TL: TangentialLaw,
        DL: DampingLaw,
        RL: RollingLaw,
    {
        let books = &history.contact.books;
        Self {
            plastic: law.normal.dissipated_work(&history.contact.normal),
            friction: books.friction_work(),
            damping: books.damping_work(),
            rolling: rolling.dissipated_work(&history.rolling),
            tangential_stiffness: books.tangential_stiffness_energy(),
            rolling_stiffness: books.rolling_stiffness_energy(),
        }
    }

    /// Add `other` part by part.
    #[inline]
    pub fn add(&mut self, other: &ContactWorks) {
        self.plastic += other.plastic;
        self.friction += other.friction;
        self.damping += other.damping;
        self.rolling += other.rolling;
        self.tangential_stiffness += other.tangential_stiffness;
        self.rolling_stiffness += other.rolling_stiffness;
    }
}

/// One contact, one step: the law crate's [`ContactLaw::update`] (normal MDR, tangential Mindlin,
/// damping) and the rolling law, turned into a force and two torques.
#[inline(always)]
pub fn evaluate_pair<NL, TL, DL, RL, A, B>(
    law: &ContactLaw<NL, TL, DL>,
    rolling: &RL,
    history: &mut PairHistory<StateOf<NL, TL, B>, RL::State>,
    kinematics: &ContactKinematics<A>,
    dt: f64,
) -> PairWrench
where
    A: LeverArms,
    B: WorkBooks,
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
    history
        .contact
        .books
        .add_rolling_stiffness_energy(roll.stiffness_energy);
    let force = output.force;
    let (torque1, torque2) = kinematics.arms.torques(&kinematics.normal, &force);
    PairWrench {
        force,
        torque1: torque1 + roll.torque,
        torque2: torque2 - roll.torque,
    }
}
