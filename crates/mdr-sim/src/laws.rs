//! Run-time choice of the sub-models named in a scene file: enums that forward to the law
//! crate's models, so one stepper type serves every scene on rapier's force path; the
//! neighbour-list path is compiled for each normal law and for rolling resistance on or off
//! ([`SceneNormal`], [`SceneRolling`]) and keeps the enum of the damping law. No physics here:
//! each variant calls the law crate's own implementation.

use crate::scene::{ContactSpec, DampingSpec, NormalSpec};
use mdr_contact::damping::{
    DampingLaw, DampingModel, HertzianViscous, NoDamping, StiffnessViscous,
};
use mdr_contact::model::ContactModel;
use mdr_contact::normal::{
    Hertz, HertzLaw, MdrElastoPlastic, MdrLaw, MdrState, NormalLaw, NormalModel, NormalResponse,
    Thornton, ThorntonLaw, ThorntonState,
};
use mdr_contact::rolling::{
    EpsdRolling, EpsdRollingState, NoRolling, RollingInput, RollingLaw, RollingModel,
    RollingResponse,
};
use mdr_contact::tangential::Mindlin;
use mdr_contact::{ContactPair, Result};
use serde::{Deserialize, Serialize};

/// The normal model of a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyNormal {
    /// MDR elasto-plastic.
    Mdr(MdrElastoPlastic),
    /// Hertz.
    Hertz(Hertz),
    /// Thornton.
    Thornton(Thornton),
}

/// [`AnyNormal`] bound to a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyNormalLaw {
    /// MDR elasto-plastic.
    Mdr(MdrLaw),
    /// Hertz.
    Hertz(HertzLaw),
    /// Thornton.
    Thornton(ThorntonLaw),
}

/// History of [`AnyNormalLaw`]: the state of whichever law is in use (the others stay default).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct AnyNormalState {
    /// MDR history.
    pub mdr: MdrState,
    /// Hertz history (largest overlap, m).
    pub hertz: f64,
    /// Thornton history.
    pub thornton: ThorntonState,
}

impl NormalModel for AnyNormal {
    type Law = AnyNormalLaw;
    fn bind(&self, pair: &ContactPair) -> Result<AnyNormalLaw> {
        Ok(match self {
            AnyNormal::Mdr(m) => AnyNormalLaw::Mdr(m.bind(pair)?),
            AnyNormal::Hertz(m) => AnyNormalLaw::Hertz(m.bind(pair)?),
            AnyNormal::Thornton(m) => AnyNormalLaw::Thornton(m.bind(pair)?),
        })
    }
}

macro_rules! forward {
    ($self:ident, $state:ident, |$law:ident, $s:ident| $body:expr) => {
        match $self {
            AnyNormalLaw::Mdr($law) => {
                let $s = &$state.mdr;
                $body
            }
            AnyNormalLaw::Hertz($law) => {
                let $s = &$state.hertz;
                $body
            }
            AnyNormalLaw::Thornton($law) => {
                let $s = &$state.thornton;
                $body
            }
        }
    };
}

impl NormalLaw for AnyNormalLaw {
    type State = AnyNormalState;

    #[inline]
    fn update(&self, state: &mut AnyNormalState, overlap: f64) -> NormalResponse {
        match self {
            AnyNormalLaw::Mdr(l) => l.update(&mut state.mdr, overlap),
            AnyNormalLaw::Hertz(l) => l.update(&mut state.hertz, overlap),
            AnyNormalLaw::Thornton(l) => l.update(&mut state.thornton, overlap),
        }
    }

    fn max_overlap(&self, state: &AnyNormalState) -> f64 {
        forward!(self, state, |l, s| l.max_overlap(s))
    }

    fn residual_overlap(&self, state: &AnyNormalState) -> f64 {
        forward!(self, state, |l, s| l.residual_overlap(s))
    }

    fn dissipated_work(&self, state: &AnyNormalState) -> f64 {
        forward!(self, state, |l, s| l.dissipated_work(s))
    }

    fn elastic_energy(&self, state: &AnyNormalState, overlap: f64) -> f64 {
        forward!(self, state, |l, s| l.elastic_energy(s, overlap))
    }

    fn yield_overlap(&self) -> f64 {
        match self {
            AnyNormalLaw::Mdr(l) => l.yield_overlap(),
            AnyNormalLaw::Hertz(l) => l.yield_overlap(),
            AnyNormalLaw::Thornton(l) => l.yield_overlap(),
        }
    }
}

/// The damping model of a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyDamping {
    /// None.
    None(NoDamping),
    /// `m γ_n (dδ/dt) √(R δ)`.
    HertzianViscous(HertzianViscous),
    /// `η √(m k_n) (dδ/dt)`.
    StiffnessViscous(StiffnessViscous),
}

/// [`AnyDamping`] bound to a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyDampingLaw {
    /// None.
    None(NoDamping),
    /// Hertzian viscous.
    HertzianViscous(<HertzianViscous as DampingModel>::Law),
    /// Stiffness viscous.
    StiffnessViscous(<StiffnessViscous as DampingModel>::Law),
}

impl DampingModel for AnyDamping {
    type Law = AnyDampingLaw;
    fn bind(&self, pair: &ContactPair) -> Result<AnyDampingLaw> {
        Ok(match self {
            AnyDamping::None(d) => AnyDampingLaw::None(d.bind(pair)?),
            AnyDamping::HertzianViscous(d) => AnyDampingLaw::HertzianViscous(d.bind(pair)?),
            AnyDamping::StiffnessViscous(d) => AnyDampingLaw::StiffnessViscous(d.bind(pair)?),
        })
    }
}

impl DampingLaw for AnyDampingLaw {
    #[inline]
    fn normal_coefficient(&self, response: &NormalResponse, overlap: f64) -> f64 {
        match self {
            AnyDampingLaw::None(d) => d.normal_coefficient(response, overlap),
            AnyDampingLaw::HertzianViscous(d) => d.normal_coefficient(response, overlap),
            AnyDampingLaw::StiffnessViscous(d) => d.normal_coefficient(response, overlap),
        }
    }

    #[inline]
    fn tangential_ratio(&self) -> f64 {
        match self {
            AnyDampingLaw::None(d) => d.tangential_ratio(),
            AnyDampingLaw::HertzianViscous(d) => d.tangential_ratio(),
            AnyDampingLaw::StiffnessViscous(d) => d.tangential_ratio(),
        }
    }
}

/// The rolling-resistance model of a scene: off, or the elastic–plastic spring model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnyRolling(pub Option<EpsdRolling>);

/// [`AnyRolling`] bound to a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnyRollingLaw(Option<<EpsdRolling as RollingModel>::Law>);

impl RollingModel for AnyRolling {
    type Law = AnyRollingLaw;
    fn bind(&self, pair: &ContactPair) -> Result<AnyRollingLaw> {
        Ok(AnyRollingLaw(match &self.0 {
            Some(r) => Some(r.bind(pair)?),
            None => None,
        }))
    }
}

impl RollingLaw for AnyRollingLaw {
    type State = EpsdRollingState;
    // Always inlined: called out of line, the law must compute every field of its response,
    // the energies the pair loop does not read among them.
    #[inline(always)]
    fn update(&self, state: &mut EpsdRollingState, input: &RollingInput) -> RollingResponse {
        match &self.0 {
            Some(l) => l.update(state, input),
            None => RollingResponse::default(),
        }
    }
    #[inline]
    fn elastic_energy(&self, state: &EpsdRollingState) -> f64 {
        match &self.0 {
            Some(l) => l.elastic_energy(state),
            None => 0.0,
        }
    }
    #[inline]
    fn dissipated_work(&self, state: &EpsdRollingState) -> f64 {
        match &self.0 {
            Some(l) => l.dissipated_work(state),
            None => 0.0,
        }
    }
}

/// A normal model a scene's neighbour-list stepper can run with, and how its per-contact history
/// is written to and read from a checkpoint (as the field of [`AnyNormalState`] that holds it).
/// The stepper is compiled for each normal law rather than run with [`AnyNormal`], so that a
/// contact carries only its own law's history (8 bytes for MDR and Hertz, not the 40 of
/// [`AnyNormalState`]) and the pair loop takes no branch on the law (docs/performance.md).
pub trait SceneNormal: NormalModel<Law: Clone> + 'static {
    /// The history to write for a contact.
    fn record(state: &<Self::Law as NormalLaw>::State) -> AnyNormalState;
    /// The history a written one restores.
    fn restore(record: &AnyNormalState) -> <Self::Law as NormalLaw>::State;
}

impl SceneNormal for MdrElastoPlastic {
    fn record(state: &MdrState) -> AnyNormalState {
        AnyNormalState {
            mdr: *state,
            ..AnyNormalState::default()
        }
    }
    fn restore(record: &AnyNormalState) -> MdrState {
        record.mdr
    }
}

impl SceneNormal for Hertz {
    fn record(state: &f64) -> AnyNormalState {
        AnyNormalState {
            hertz: *state,
            ..AnyNormalState::default()
        }
    }
    fn restore(record: &AnyNormalState) -> f64 {
        record.hertz
    }
}

impl SceneNormal for Thornton {
    fn record(state: &ThorntonState) -> AnyNormalState {
        AnyNormalState {
            thornton: *state,
            ..AnyNormalState::default()
        }
    }
    fn restore(record: &AnyNormalState) -> ThorntonState {
        record.thornton
    }
}

/// A rolling model a scene's neighbour-list stepper can run with, and how its per-contact
/// history is written to and read from a checkpoint (as the elastic–plastic spring's state, the
/// default one when the scene has no rolling resistance). A scene without rolling resistance
/// runs with [`NoRolling`], whose history is empty and whose update is nothing, rather than with
/// [`AnyRolling`] switched off: every contact then carries no rolling state and takes no rolling
/// branch (docs/performance.md).
pub trait SceneRolling: RollingModel<Law: Clone> + 'static {
    /// The history to write for a contact.
    fn record(state: &<Self::Law as RollingLaw>::State) -> EpsdRollingState;
    /// The history a written one restores.
    fn restore(record: &EpsdRollingState) -> <Self::Law as RollingLaw>::State;
}

impl SceneRolling for NoRolling {
    fn record(_: &()) -> EpsdRollingState {
        EpsdRollingState::default()
    }
    fn restore(_: &EpsdRollingState) {}
}

impl SceneRolling for EpsdRolling {
    fn record(state: &EpsdRollingState) -> EpsdRollingState {
        *state
    }
    fn restore(record: &EpsdRollingState) -> EpsdRollingState {
        *record
    }
}

/// The composed model of a scene (normal + Mindlin with the scene's `μ`, 0 = frictionless +
/// damping) and its rolling model.
pub fn scene_model(
    spec: &ContactSpec,
) -> Result<(ContactModel<AnyNormal, Mindlin, AnyDamping>, AnyRolling)> {
    let normal = match spec.normal {
        NormalSpec::Mdr {
            critical_line_load,
            hardening_ratio,
        } => AnyNormal::Mdr(MdrElastoPlastic::new(critical_line_load, hardening_ratio)?),
        NormalSpec::Hertz => AnyNormal::Hertz(Hertz),
        NormalSpec::Thornton { yield_pressure } => {
            AnyNormal::Thornton(Thornton::new(yield_pressure)?)
        }
    };
    let damping = match spec.damping {
        DampingSpec::None => AnyDamping::None(NoDamping),
        DampingSpec::HertzianViscous(g) => AnyDamping::HertzianViscous(
            HertzianViscous::new(g)?.with_tangential_ratio(spec.tangential_damping_ratio)?,
        ),
        DampingSpec::StiffnessViscous(e) => AnyDamping::StiffnessViscous(
            StiffnessViscous::new(e)?.with_tangential_ratio(spec.tangential_damping_ratio)?,
        ),
    };
    let rolling = if spec.rolling_friction > 0.0 {
        AnyRolling(Some(EpsdRolling::new(spec.rolling_friction)?))
    } else {
        AnyRolling(None)
    };
    let model = ContactModel::new(normal)
        .with_tangential(Mindlin::new(spec.friction)?)
        .with_damping(damping);
    Ok((model, rolling))
}
