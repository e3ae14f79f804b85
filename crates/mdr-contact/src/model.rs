//! Composition: a contact model is a normal law + a tangential law + a damping law, each with
//! its own parameters and its own history, as LAMMPS `pair granular` composes sub-models.

use crate::damping::{DampingLaw, DampingModel, NoDamping};
use crate::error::Result;
use crate::material::ContactPair;
use crate::normal::{NormalLaw, NormalModel, NormalResponse};
use crate::tangential::{
    Frictionless, TangentialInput, TangentialLaw, TangentialModel, TangentialResponse,
};
use nalgebra::Vector3;

/// Material-level description of a contact: normal, tangential and damping sub-models.
///
/// ```
/// use mdr_contact::prelude::*;
/// let model = ContactModel::new(MdrElastoPlastic::paper())
///     .with_tangential(Mindlin::new(0.3).unwrap());
/// let law = model.bind(&ContactPair::paper_fig2()).unwrap();
/// let mut state = law.new_state();
/// let out = law.update(&mut state, &ContactInput::normal_only(1e-6, -0.1, 1e-7));
/// assert!(out.normal_force > 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactModel<N, T = Frictionless, D = NoDamping> {
    /// Normal sub-model.
    pub normal: N,
    /// Tangential sub-model.
    pub tangential: T,
    /// Damping sub-model.
    pub damping: D,
}

impl<N: NormalModel> ContactModel<N> {
    /// A frictionless, undamped model with the given normal law.
    pub fn new(normal: N) -> Self {
        Self {
            normal,
            tangential: Frictionless,
            damping: NoDamping,
        }
    }
}

impl<N: NormalModel, T: TangentialModel, D: DampingModel> ContactModel<N, T, D> {
    /// Replace the tangential sub-model (the normal one is untouched).
    pub fn with_tangential<T2: TangentialModel>(self, tangential: T2) -> ContactModel<N, T2, D> {
        ContactModel {
            normal: self.normal,
            tangential,
            damping: self.damping,
        }
    }

    /// Replace the damping sub-model.
    pub fn with_damping<D2: DampingModel>(self, damping: D2) -> ContactModel<N, T, D2> {
        ContactModel {
            normal: self.normal,
            tangential: self.tangential,
            damping,
        }
    }

    /// Replace the normal sub-model (the tangential one is untouched).
    pub fn with_normal<N2: NormalModel>(self, normal: N2) -> ContactModel<N2, T, D> {
        ContactModel {
            normal,
            tangential: self.tangential,
            damping: self.damping,
        }
    }

    /// Bind every sub-model to one pair.
    pub fn bind(&self, pair: &ContactPair) -> Result<ContactLaw<N::Law, T::Law, D::Law>> {
        Ok(ContactLaw {
            normal: self.normal.bind(pair)?,
            tangential: self.tangential.bind(pair)?,
            damping: self.damping.bind(pair)?,
        })
    }
}

/// Where a contact books the work its friction and damping dissipate, and the energy its
/// incremental springs gain without work (stiffness changes): a type parameter of
/// [`ContactState`], so that a state without books ([`NoBooks`]) carries no fields and its update
/// forms no work term (the trajectory is the same bit for bit; about 5 % of a settled bed's
/// step per core, docs/performance.md). Plasticity needs no book: its work follows from the normal
/// law's state ([`NormalLaw::dissipated_work`]).
pub trait WorkBooks: Default + Clone + Copy + std::fmt::Debug + PartialEq + Send + Sync {
    /// Add work dissipated by friction (J).
    fn add_friction_work(&mut self, work: f64);
    /// Add work dissipated by damping (J).
    fn add_damping_work(&mut self, work: f64);
    /// Work dissipated by friction so far (J); NaN when not booked.
    fn friction_work(&self) -> f64;
    /// Work dissipated by damping so far (J); NaN when not booked.
    fn damping_work(&self) -> f64;
    /// Add energy the tangential springs gained without work
    /// ([`crate::tangential::TangentialResponse::stiffness_energy`], J).
    fn add_tangential_stiffness_energy(&mut self, energy: f64);
    /// Add energy the rolling spring gained without work
    /// ([`crate::rolling::RollingResponse::stiffness_energy`], J).
    fn add_rolling_stiffness_energy(&mut self, energy: f64);
    /// Energy the tangential springs gained without work so far (J; negative when lost); NaN
    /// when not booked.
    fn tangential_stiffness_energy(&self) -> f64;
    /// Energy the rolling spring gained without work so far (J; negative when lost); NaN when
    /// not booked.
    fn rolling_stiffness_energy(&self) -> f64;
}

/// The work books of one contact (the default of [`ContactState`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Books {
    /// Work dissipated by friction so far (J).
    pub friction_work: f64,
    /// Work dissipated by damping so far (J).
    pub damping_work: f64,
    /// Energy the tangential springs gained without work so far (J; negative when lost).
    #[cfg_attr(feature = "serde", serde(default))]
    pub tangential_stiffness_energy: f64,
    /// Energy the rolling spring gained without work so far (J; negative when lost).
    #[cfg_attr(feature = "serde", serde(default))]
    pub rolling_stiffness_energy: f64,
}

impl WorkBooks for Books {
    #[inline(always)]
    fn add_friction_work(&mut self, work: f64) {
        self.friction_work += work;
    }
    #[inline(always)]
    fn add_damping_work(&mut self, work: f64) {
        self.damping_work += work;
    }
    #[inline(always)]
    fn friction_work(&self) -> f64 {
        self.friction_work
    }
    #[inline(always)]
    fn damping_work(&self) -> f64 {
        self.damping_work
    }
    #[inline(always)]
    fn add_tangential_stiffness_energy(&mut self, energy: f64) {
        self.tangential_stiffness_energy += energy;
    }
    #[inline(always)]
    fn add_rolling_stiffness_energy(&mut self, energy: f64) {
        self.rolling_stiffness_energy += energy;
    }
    #[inline(always)]
    fn tangential_stiffness_energy(&self) -> f64 {
        self.tangential_stiffness_energy
    }
    #[inline(always)]
    fn rolling_stiffness_energy(&self) -> f64 {
        self.rolling_stiffness_energy
    }
}

/// No work books: for throughput runs that never read them (LAMMPS keeps none either). Reports
/// give NaN for the friction and damping work.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NoBooks;

impl WorkBooks for NoBooks {
    #[inline(always)]
    fn add_friction_work(&mut self, _: f64) {}
    #[inline(always)]
    fn add_damping_work(&mut self, _: f64) {}
    #[inline(always)]
    fn friction_work(&self) -> f64 {
        f64::NAN
    }
    #[inline(always)]
    fn damping_work(&self) -> f64 {
        f64::NAN
    }
    #[inline(always)]
    fn add_tangential_stiffness_energy(&mut self, _: f64) {}
    #[inline(always)]
    fn add_rolling_stiffness_energy(&mut self, _: f64) {}
    #[inline(always)]
    fn tangential_stiffness_energy(&self) -> f64 {
        f64::NAN
    }
    #[inline(always)]
    fn rolling_stiffness_energy(&self) -> f64 {
        f64::NAN
    }
}

/// Per-contact history of a composed model, plus the work books of this contact.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactState<NS, TS, B = Books> {
    /// Normal law history.
    pub normal: NS,
    /// Tangential law history.
    pub tangential: TS,
    /// Friction and damping work of this contact ([`Books`], or [`NoBooks`] for none).
    pub books: B,
}

/// Kinematics of one contact at one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactInput {
    /// Overlap `δ` (m), positive when the bodies interpenetrate.
    pub overlap: f64,
    /// Unit normal from body 2 towards body 1.
    pub normal: Vector3<f64>,
    /// Velocity of body 1 relative to body 2 at the contact point (m/s).
    pub relative_velocity: Vector3<f64>,
    /// Time step (m/s × dt gives the tangential displacement increment), s.
    pub dt: f64,
}

impl ContactInput {
    /// A head-on contact along `z`: overlap `δ`, normal relative velocity `v_n` (negative while
    /// approaching), step `dt`.
    pub fn normal_only(overlap: f64, normal_velocity: f64, dt: f64) -> Self {
        Self {
            overlap,
            normal: Vector3::z(),
            relative_velocity: Vector3::new(0.0, 0.0, normal_velocity),
            dt,
        }
    }
}

/// Result of one contact update.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactOutput {
    /// Total force on body 1 (N); body 2 receives the opposite.
    pub force: Vector3<f64>,
    /// Normal force including damping (N; negative only for the tension of a held adhesive
    /// contact, see [`NormalLaw::holds`]).
    pub normal_force: f64,
    /// The normal law's own response (elastic–plastic part).
    pub normal: NormalResponse,
    /// The tangential law's response (its spring force; a tangential dashpot of the damping
    /// sub-model acts on top of it and is included in `force` only).
    pub tangential: TangentialResponse,
}

/// What one contact looks like, for reports and output files.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactReport {
    /// Current overlap (m).
    pub overlap: f64,
    /// Largest overlap so far (m).
    pub max_overlap: f64,
    /// Residual (plastic) indentation (m).
    pub residual_overlap: f64,
    /// Work dissipated by plasticity (J).
    pub plastic_work: f64,
    /// Work dissipated by friction (J).
    pub friction_work: f64,
    /// Work dissipated by damping (J).
    pub damping_work: f64,
    /// Elastic energy stored in the normal direction (J).
    pub normal_elastic_energy: f64,
}

/// A composed contact law bound to one pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw<NL, TL, DL> {
    /// Normal law.
    pub normal: NL,
    /// Tangential law.
    pub tangential: TL,
    /// Damping law.
    pub damping: DL,
}

/// The state type of a composed law, with work books `B` (default [`Books`]).
pub type StateOf<NL, TL, B = Books> =
    ContactState<<NL as NormalLaw>::State, <TL as TangentialLaw>::State, B>;

impl<NL: NormalLaw, TL: TangentialLaw, DL: DampingLaw> ContactLaw<NL, TL, DL> {
    /// A fresh history (no contact yet).
    pub fn new_state(&self) -> StateOf<NL, TL> {
        ContactState::default()
    }

    /// Advance one contact by one step (always inlined: it is the body of every per-contact hot
    /// loop, and inlining lets the caller drop the parts of the output it does not read).
    #[inline(always)]
    pub fn update<B: WorkBooks>(
        &self,
        state: &mut StateOf<NL, TL, B>,
        input: &ContactInput,
    ) -> ContactOutput {
        let normal = self.normal.update(&mut state.normal, input.overlap);
        if normal.force <= 0.0 && normal.contact_radius <= 0.0 {
            // Apart (or touching only the residual crater's rim): no force; the tangential
            // springs forget their displacement.
            let released = self.tangential.update(
                &mut state.tangential,
                &TangentialInput {
                    normal: input.normal,
                    displacement_increment: Vector3::zeros(),
                    normal_response: normal,
                },
            );
            state
                .books
                .add_tangential_stiffness_energy(released.stiffness_energy);
            return ContactOutput::default();
        }
        let normal_speed = input.relative_velocity.dot(&input.normal);
        let approach_rate = -normal_speed;
        // One dashpot coefficient for the normal damping and the tangential dashpot.
        let dashpot = self.damping.normal_coefficient(&normal, input.overlap);
        let damping = dashpot * approach_rate;
        // Damping may not pull the bodies together: it may cancel a repulsive force, and never
        // adds to the adhesive tension of a held contact.
        let normal_force = (normal.force + damping).max(normal.force.min(0.0));
        let applied_damping = normal_force - normal.force;
        // Both dashpots' work of this step, booked once below.
        let mut damping_power = applied_damping * approach_rate;
        let tangential = self.tangential.update(
            &mut state.tangential,
            &TangentialInput {
                normal: input.normal,
                displacement_increment: input.relative_velocity * input.dt,
                // The Coulomb cap uses the total normal force, damping included, plus twice the
                // pull-off force of an adhesive law (Thornton & Yin 1991; zero otherwise).
                normal_response: NormalResponse {
                    force: normal_force + 2.0 * self.normal.pull_off_force(),
                    ..normal
                },
            },
        );
        state
            .books
            .add_tangential_stiffness_energy(tangential.stiffness_energy);
        if tangential.dissipated != 0.0 {
            // Most contacts stick and dissipate nothing here: they skip the book.
            state.books.add_friction_work(tangential.dissipated);
        }
        let mut force = input.normal * normal_force + tangential.force;
        if !tangential.sliding {
            // Tangential dashpot while the spring sticks (see `DampingLaw::tangential_coefficient`):
            // F = −η_t v_t, dissipating η_t |v_t|² dt, booked with the normal damping.
            let eta_t = self.damping.tangential_ratio() * dashpot;
            if eta_t > 0.0 {
                let v_t = input.relative_velocity - input.normal * normal_speed;
                force -= v_t * eta_t;
                damping_power += eta_t * v_t.norm_squared();
            }
        }
        state.books.add_damping_work(damping_power * input.dt);
        ContactOutput {
            force,
            normal_force,
            normal,
            tangential,
        }
    }

    /// The per-contact quantities users look at (NaN friction and damping work with
    /// [`NoBooks`]).
    pub fn report<B: WorkBooks>(&self, state: &StateOf<NL, TL, B>, overlap: f64) -> ContactReport {
        ContactReport {
            overlap,
            max_overlap: self.normal.max_overlap(&state.normal),
            residual_overlap: self.normal.residual_overlap(&state.normal),
            plastic_work: self.normal.dissipated_work(&state.normal),
            friction_work: state.books.friction_work(),
            damping_work: state.books.damping_work(),
            normal_elastic_energy: self.normal.elastic_energy(&state.normal, overlap),
        }
    }
}
